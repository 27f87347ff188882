// EstimateRows.h, compiled once per instruction set by Highway's foreach_target (this file
// includes itself) and dispatched at run time. Integers throughout (the bounds come in fixed
// point, EstimateRows.h): every target gives the scalar loops' bytes.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "EstimateRows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "EstimateHook.h"
#include "EstimateRows.h"

#ifndef FACET_ESTIMATE_ROWS_SCALAR
#define FACET_ESTIMATE_ROWS_SCALAR
namespace facet::detail {
namespace {

static_assert(kEstimateUnit == 1u << 7, "the SIMD lanes scale a channel by a shift of 7");

inline std::uint32_t wordOf(Rgba8 color) {
  std::uint32_t word;
  std::memcpy(&word, &color, sizeof word);
  return word;
}

// Channel j of a color word (red in the low byte), scaled.
inline std::uint32_t scaledChannel(std::uint32_t word, int j) {
  return ((word >> (8 * j)) & 0xFFu) * kEstimateUnit;
}

// r = g = b (the alpha byte aside).
inline bool greyWord(std::uint32_t word) {
  return ((word ^ (word >> 8)) & 0xFFFFu) == 0;
}

// The scalar definitions; the SIMD loops below end with them. fieldsOf returns whether the
// sample is grey or the background.
inline bool fieldsOf(Rgba8 color, std::int32_t id, const EstimateBound* fixedBounds, int shift,
                     int x, EstimateField* fields, std::size_t stride, int planes) {
  const std::uint32_t word = wordOf(color);
  const std::uint32_t q = id < 0 ? 0 : fixedBounds[id >> shift];
  for (int j = 0; j < planes / 2; ++j) {
    const std::uint32_t c = scaledChannel(word, j);
    fields[2 * j * stride + x] = static_cast<EstimateField>(id < 0 ? 0 : c + q);
    fields[(2 * j + 1) * stride + x] =
        static_cast<EstimateField>(id < 0 ? 0 : kEstimateCap - c + q);
  }
  return id < 0 || greyWord(word);
}

inline void rowMaximumOf(const EstimateField* in, int x, EstimateField* out, std::size_t stride,
                         int planes) {
  for (int k = 0; k < planes; ++k) {
    const EstimateField* plane = in + k * stride;
    out[k * stride + x] = std::max({plane[x - 1], plane[x], plane[x + 1]});
  }
}

inline std::uint32_t sampleEstimateOf(const EstimateField* above, const EstimateField* row,
                                      const EstimateField* below, std::size_t stride,
                                      const Rgba8* colors, const std::int32_t* ids, int x,
                                      int planes) {
  if (ids[x] < 0) return 0;
  const std::uint32_t word = wordOf(colors[x]);
  std::uint32_t largest = 0;
  for (int k = 0; k < planes; ++k) {
    const std::size_t i = k * stride + x;
    const std::uint32_t c = scaledChannel(word, k / 2);
    const std::uint32_t m = std::max({above[i], row[i], below[i]});  // promoted
    // No wrap: the sample's own field is part of the maximum.
    largest = std::max(largest, m - (k % 2 == 0 ? c : kEstimateCap - c));
  }
  // largest = max(D·unit + ⌈b·unit⌉) + 1: less the 1, plus the 0.5 of rounding.
  return std::min(largest - 1 + kEstimateUnit / 2, kEstimateCap);
}

}  // namespace
}  // namespace facet::detail
#endif  // FACET_ESTIMATE_ROWS_SCALAR

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DU = hn::ScalableTag<std::uint32_t>;
using DI = hn::RebindToSigned<DU>;
using DH = hn::Rebind<EstimateField, DU>;  // the fields of as many samples

// Channel j of color words, scaled by kEstimateUnit (a shift of 7).
template <int j>
HWY_INLINE hn::Vec<DU> scaledChannels(hn::Vec<DU> words) {
  const DU du;
  const auto mask = hn::Set(du, 0xFFu << 7);
  if constexpr (j == 0) {
    return hn::And(hn::ShiftLeft<7>(words), mask);
  } else {
    return hn::And(hn::ShiftRight<8 * j - 7>(words), mask);
  }
}

// The fixed bounds of polygons `index` (≥ 0): 16-bit values read as the 32-bit pairs that
// hold them (there is no 16-bit gather), the odd one in the high half.
HWY_INLINE hn::Vec<DU> gatherFixedBounds(const EstimateBound* fixedBounds, hn::Vec<DI> index) {
  const DU du;
  const DI di;
  const auto* pairs = reinterpret_cast<const std::uint32_t*>(fixedBounds);
  const auto pair = hn::GatherIndex(du, pairs, hn::ShiftRight<1>(index));
  const auto shift = hn::BitCast(du, hn::ShiftLeft<4>(hn::And(index, hn::Set(di, 1))));
  return hn::And(hn::Shr(pair, shift), hn::Set(du, 0xFFFFu));
}

// kById: each sample's color gathered from its polygon's (polygonColors[id]), as the resolve
// gathers it; else read from the row of colors.
template <bool kById, int kPlanes>
HWY_INLINE bool FieldsOf(const Rgba8* colors, const std::int32_t* ids,
                         const EstimateBound* fixedBounds, int shift, int begin, int end,
                         EstimateField* fields, std::size_t stride) {
  const DU du;
  const DH dh;
  const DI di;
  const int lanes = static_cast<int>(hn::Lanes(du));
  const auto* words = reinterpret_cast<const std::uint32_t*>(colors);
  auto colored = hn::Zero(du);  // r ≠ g or g ≠ b in some covered lane
  int x = begin;
  for (; x + lanes <= end; x += lanes) {
    const auto id = hn::LoadU(di, ids + x);
    const auto backgroundI = id < hn::Zero(di);
    const auto background = hn::RebindMask(du, backgroundI);
    const auto index = hn::IfThenZeroElse(backgroundI, id);
    const auto q = gatherFixedBounds(fixedBounds, hn::ShiftRightSame(index, shift));
    const auto color = kById ? hn::GatherIndex(du, words, index) : hn::LoadU(du, words + x);
    const auto word = hn::IfThenZeroElse(background, color);
    const auto plus = hn::IfThenZeroElse(background, q);
    const auto minus = hn::IfThenZeroElse(background, q + hn::Set(du, kEstimateCap));
    colored = hn::Or(colored, hn::Xor(word, hn::ShiftRight<8>(word)));
    const hn::Vec<DU> channels[3] = {scaledChannels<0>(word), scaledChannels<1>(word),
                                     scaledChannels<2>(word)};
    // Below 2^16 (EstimateRows.h): narrowed exactly.
    const auto narrow = [&](hn::Vec<DU> v) { return hn::DemoteTo(dh, hn::BitCast(di, v)); };
    for (int j = 0; j < kPlanes / 2; ++j) {
      hn::StoreU(narrow(channels[j] + plus), dh, fields + 2 * j * stride + x);
      hn::StoreU(narrow(minus - channels[j]), dh, fields + (2 * j + 1) * stride + x);
    }
  }
  bool grey = hn::AllTrue(du, hn::And(colored, hn::Set(du, 0xFFFFu)) == hn::Zero(du));
  for (; x < end; ++x) {
    const std::int32_t id = ids[x];
    const Rgba8 color = !kById ? colors[x] : id < 0 ? Rgba8{} : colors[id];
    grey = fieldsOf(color, id, fixedBounds, shift, x, fields, stride, kPlanes) && grey;
  }
  return grey;
}

template <bool kById>
HWY_INLINE bool FieldsOfPlanes(const Rgba8* colors, const std::int32_t* ids,
                               const EstimateBound* fixedBounds, int shift, int begin, int end,
                               EstimateField* fields, std::size_t stride, int planes) {
  return planes == kGreyFields ? FieldsOf<kById, kGreyFields>(colors, ids, fixedBounds, shift,
                                                              begin, end, fields, stride)
                               : FieldsOf<kById, kEstimateFields>(colors, ids, fixedBounds, shift,
                                                                  begin, end, fields, stride);
}

bool NeighbourFields(const Rgba8* colors, const std::int32_t* ids, const EstimateBound* fixedBounds,
                     int begin, int end, EstimateField* fields, std::size_t stride, int planes,
                     int shift) {
  return FieldsOfPlanes<false>(colors, ids, fixedBounds, shift, begin, end, fields, stride, planes);
}

bool NeighbourFieldsById(const Rgba8* polygonColors, const std::int32_t* ids,
                         const EstimateBound* fixedBounds, int begin, int end,
                         EstimateField* fields, std::size_t stride, int planes, int shift) {
  return FieldsOfPlanes<true>(polygonColors, ids, fixedBounds, shift, begin, end, fields, stride,
                              planes);
}

void RowMaxima(const EstimateField* in, int begin, int end, EstimateField* out, std::size_t stride,
               int planes) {
  const hn::ScalableTag<EstimateField> d16;  // whole vectors of fields
  const int lanes = static_cast<int>(hn::Lanes(d16));
  int x = begin;
  for (; x + lanes <= end; x += lanes) {
    for (int k = 0; k < planes; ++k) {
      const EstimateField* plane = in + k * stride + x;
      const auto m = hn::Max(hn::Max(hn::LoadU(d16, plane - 1), hn::LoadU(d16, plane)),
                             hn::LoadU(d16, plane + 1));
      hn::StoreU(m, d16, out + k * stride + x);
    }
  }
  for (; x < end; ++x)
    rowMaximumOf(in, x, out, stride, planes);
}

template <int kPlanes>
HWY_INLINE void SampleEstimatesOf(const EstimateField* above, const EstimateField* row,
                                  const EstimateField* below, std::size_t stride,
                                  const Rgba8* colors, const std::int32_t* ids, int begin, int end,
                                  std::uint32_t* out) {
  const DU du;
  const DH dh;
  const DI di;
  const int lanes = static_cast<int>(hn::Lanes(du));
  const auto* words = reinterpret_cast<const std::uint32_t*>(colors);
  const auto cap = hn::Set(du, kEstimateCap);
  int x = begin;
  for (; x + lanes <= end; x += lanes) {
    const auto word = hn::LoadU(du, words + x);
    const hn::Vec<DU> channels[3] = {scaledChannels<0>(word), scaledChannels<1>(word),
                                     scaledChannels<2>(word)};
    auto largest = hn::Zero(du);
    for (int k = 0; k < kPlanes; ++k) {
      const std::size_t i = k * stride + x;
      const auto m =
          hn::PromoteTo(du, hn::Max(hn::Max(hn::LoadU(dh, above + i), hn::LoadU(dh, row + i)),
                                    hn::LoadU(dh, below + i)));
      const auto own = k % 2 == 0 ? channels[k / 2] : cap - channels[k / 2];
      largest = hn::Max(largest, m - own);
    }
    const auto estimate = hn::Min(largest + hn::Set(du, kEstimateUnit / 2 - 1), cap);
    const auto background = hn::RebindMask(du, hn::LoadU(di, ids + x) < hn::Zero(di));
    hn::StoreU(hn::IfThenZeroElse(background, estimate), du, out + x);
  }
  for (; x < end; ++x)
    out[x] = sampleEstimateOf(above, row, below, stride, colors, ids, x, kPlanes);
}

void SampleEstimates(const EstimateField* above, const EstimateField* row,
                     const EstimateField* below, std::size_t stride, const Rgba8* colors,
                     const std::int32_t* ids, int begin, int end, std::uint32_t* out, int planes) {
  if (planes == kGreyFields) {
    SampleEstimatesOf<kGreyFields>(above, row, below, stride, colors, ids, begin, end, out);
  } else {
    SampleEstimatesOf<kEstimateFields>(above, row, below, stride, colors, ids, begin, end, out);
  }
}

// coveredSpan: whole groups of background skipped four vectors at a time, then one (a row of
// 1080p is often half background; one branch per id was most of the time of finding the
// span, and one test per vector most of what was left: the ids are all below 0 where the
// AND of four vectors is, by its sign bits).
std::array<int, 2> CoveredSpan(const std::int32_t* ids, int width) {
  const DI di;
  const int lanes = static_cast<int>(hn::Lanes(di));
  const auto background = [&](int x) {
    return hn::AllTrue(di, hn::LoadU(di, ids + x) < hn::Zero(di));
  };
  const auto background4 = [&](int x) {
    const auto both =
        hn::And(hn::And(hn::LoadU(di, ids + x), hn::LoadU(di, ids + x + lanes)),
                hn::And(hn::LoadU(di, ids + x + 2 * lanes), hn::LoadU(di, ids + x + 3 * lanes)));
    return hn::AllTrue(di, both < hn::Zero(di));
  };
  int first = 0, last = width;
  while (first + 4 * lanes <= width && background4(first))
    first += 4 * lanes;
  while (first + lanes <= width && background(first))
    first += lanes;
  while (first < width && ids[first] < 0)
    ++first;
  while (last - 4 * lanes >= first && background4(last - 4 * lanes))
    last -= 4 * lanes;
  while (last - lanes >= first && background(last - lanes))
    last -= lanes;
  while (last > first && ids[last - 1] < 0)
    --last;
  return {first, last};
}

EstimateSums SumEstimates(const std::uint32_t* estimates, int begin, int end) {
  EstimateSums sums;
  int x = begin;
#if HWY_TARGET != HWY_SCALAR
  const DU du;
  const hn::Repartition<std::uint64_t, DU> d64;
  const int lanes = static_cast<int>(hn::Lanes(du));
  auto squares = hn::Zero(d64);
  auto largest = hn::Zero(du), covered = hn::Zero(du);
  for (; x + lanes <= end; x += lanes) {
    const auto e = hn::LoadU(du, estimates + x);
    largest = hn::Max(largest, e);
    covered = covered + hn::IfThenElseZero(e != hn::Zero(du), hn::Set(du, 1u));
    // Each estimate is below 2^15, its square below 2^30: the even lanes' squares, then the
    // odd lanes' moved down, in 64-bit lanes.
    const auto odd = hn::BitCast(du, hn::ShiftRight<32>(hn::BitCast(d64, e)));
    squares = squares + hn::MulEven(e, e) + hn::MulEven(odd, odd);
  }
  constexpr std::size_t kMax = HWY_MAX_BYTES / sizeof(std::uint32_t);
  HWY_ALIGN std::uint64_t wide[kMax];
  HWY_ALIGN std::uint32_t narrow[2][kMax];
  hn::Store(squares, d64, wide);
  hn::Store(largest, du, narrow[0]);
  hn::Store(covered, du, narrow[1]);
  for (std::size_t i = 0; i < hn::Lanes(d64); ++i)
    sums.squares += wide[i];
  for (std::size_t i = 0; i < hn::Lanes(du); ++i) {
    sums.largest = std::max(sums.largest, narrow[0][i]);
    sums.covered += narrow[1][i];
  }
#endif
  for (; x < end; ++x) {
    const std::uint32_t e = estimates[x];
    sums.squares += static_cast<std::uint64_t>(e) * e;
    sums.largest = std::max(sums.largest, e);
    sums.covered += e != 0;
  }
  return sums;
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {

HWY_EXPORT(NeighbourFields);
HWY_EXPORT(NeighbourFieldsById);
HWY_EXPORT(RowMaxima);
HWY_EXPORT(SampleEstimates);
HWY_EXPORT(SumEstimates);
HWY_EXPORT(CoveredSpan);

EstimateSums estimateSums(const std::uint32_t* estimates, int begin, int end) {
  return HWY_DYNAMIC_DISPATCH(SumEstimates)(estimates, begin, end);
}

bool neighbourFields(const Rgba8* colors, const std::int32_t* ids, const EstimateBound* fixedBounds,
                     int begin, int end, EstimateField* fields, std::size_t stride, int planes,
                     int shift) {
  return HWY_DYNAMIC_DISPATCH(NeighbourFields)(colors, ids, fixedBounds, begin, end, fields, stride,
                                               planes, shift);
}

bool neighbourFieldsById(const Rgba8* polygonColors, const std::int32_t* ids,
                         const EstimateBound* fixedBounds, int begin, int end,
                         EstimateField* fields, std::size_t stride, int planes, int shift) {
  return HWY_DYNAMIC_DISPATCH(NeighbourFieldsById)(polygonColors, ids, fixedBounds, begin, end,
                                                   fields, stride, planes, shift);
}

void rowMaxima(const EstimateField* in, int begin, int end, EstimateField* out, std::size_t stride,
               int planes) {
  HWY_DYNAMIC_DISPATCH(RowMaxima)(in, begin, end, out, stride, planes);
}

void sampleEstimates(const EstimateField* above, const EstimateField* row,
                     const EstimateField* below, std::size_t stride, const Rgba8* colors,
                     const std::int32_t* ids, int begin, int end, std::uint32_t* out, int planes) {
  HWY_DYNAMIC_DISPATCH(SampleEstimates)
  (above, row, below, stride, colors, ids, begin, end, out, planes);
}

std::array<int, 2> coveredSpan(const std::int32_t* ids, int width) {
  return HWY_DYNAMIC_DISPATCH(CoveredSpan)(ids, width);
}

void EstimateSpace::resize(int sampleWidth, int gridSide) {
  if (sampleWidth == width && gridSide == side) return;
  width = sampleWidth;
  side = gridSide;
  stride = static_cast<std::size_t>(width) + 2;
  const std::size_t planes = kEstimateFields * stride;
  fields.assign(planes, 0);
  for (std::vector<EstimateField>& row : maxima)
    row.assign(planes, 0);
  written = {};
  this->planes = {};
  lastGrey = true;
  zeros.assign(planes, 0);
  samples.assign(static_cast<std::size_t>(side) * width, 0);
  pixels.assign(static_cast<std::size_t>(width / side), 0);
}

void EstimateSpace::findMaxima(const EstimateGrid& grid, int r) {
  const std::size_t row = static_cast<std::size_t>(r) * width;
  const std::int32_t* ids = grid.ids + row;
  const auto [first, last] = coveredSpan(ids, width);
  EstimateField* out = at(maxima[r % 3]);
  const auto [wasFirst, wasLast] = written[r % 3];
  for (int k = 0; k < planes[r % 3]; ++k)
    std::fill(out + k * stride + wasFirst, out + k * stride + wasLast, 0u);
  spans[r % 3] = {first, last};
  written[r % 3] = {0, 0};
  planes[r % 3] = kGreyFields;  // no polygon: grey (its maxima are 0)
  if (first >= last) return;
  const int fieldsBegin = std::max(0, first - 2), fieldsEnd = std::min(width, last + 2);
  const auto fieldsOf = [&](int count) {
    if (grid.polygonColors && (r < grid.ownFirst || r > grid.ownLast)) {
      return neighbourFieldsById(grid.polygonColors, ids, grid.fixedBounds, fieldsBegin, fieldsEnd,
                                 at(fields), stride, count, grid.boundShift);
    }
    return neighbourFields(grid.colors + row, ids, grid.fixedBounds, fieldsBegin, fieldsEnd,
                           at(fields), stride, count, grid.boundShift);
  };
  // Tried grey after a grey row (taken again with all planes if it is not), else all planes.
  bool grey = lastGrey && fieldsOf(kGreyFields);
  if (!grey) grey = fieldsOf(kEstimateFields);
  lastGrey = grey;
  planes[r % 3] = grey ? kGreyFields : kEstimateFields;
  const int begin = std::max(0, first - 1), end = std::min(width, last + 1);
  rowMaxima(at(fields), begin, end, out, stride, planes[r % 3]);
  written[r % 3] = {begin, end};
}

void EstimateSpace::expand(int r) {
  if (planes[r % 3] == kEstimateFields) return;
  EstimateField* out = at(maxima[r % 3]);
  const auto [begin, end] = written[r % 3];
  for (int k = kGreyFields; k < kEstimateFields; ++k)
    std::copy(out + (k % 2) * stride + begin, out + (k % 2) * stride + end,
              out + k * stride + begin);
  planes[r % 3] = kEstimateFields;
}

void EstimateSpace::estimateSamples(const EstimateGrid& grid, int r, bool whole) {
  const std::size_t row = static_cast<std::size_t>(r) * width;
  std::uint32_t* out = samples.data() + static_cast<std::size_t>(r % side) * width;
  const auto [first, last] = spans[r % 3];
  if (whole) {
    std::fill(out, out + first, 0u);
    std::fill(out + last, out + width, 0u);
  }
  // Grey only if the three rows are (the rows outside the grid are zeros, any planes).
  int count = kGreyFields;
  for (int n = r - 1; n <= r + 1; ++n)
    if (n >= 0 && n < grid.height && planes[n % 3] != kGreyFields) count = kEstimateFields;
  if (count == kEstimateFields) {
    for (int n = r - 1; n <= r + 1; ++n)
      if (n >= 0 && n < grid.height) expand(n);
  }
  sampleEstimates(maximaOf(r - 1, grid.height), maximaOf(r, grid.height),
                  maximaOf(r + 1, grid.height), stride, grid.colors + row, grid.ids + row, first,
                  last, out, count);
}

const std::uint32_t* EstimateSpace::pixelEstimates() {
  if (side == 1) return samples.data();
  const std::uint32_t area = static_cast<std::uint32_t>(side * side);
  for (std::size_t x = 0; x < pixels.size(); ++x) {
    std::uint32_t sum = 0;
    for (int j = 0; j < side; ++j) {
      const std::uint32_t* s = samples.data() + static_cast<std::size_t>(j) * width + x * side;
      for (int i = 0; i < side; ++i)
        sum += s[i];
    }
    pixels[x] = sum == 0 ? 0 : std::min((sum + area - 1) / area + kEstimateUnit / 2, kEstimateCap);
  }
  return pixels.data();
}

void estimateResolvedRows(const EstimateHook& hook, const Rgba8* polygonColors, const Rgba8* colors,
                          const std::int32_t* ids, int width, int y0, int y1) {
  // One space per thread, kept: the resolve's tasks are bands, not threads.
  thread_local EstimateSpace space;
  space.resize(width, 1);
  const EstimateGrid grid{ids, colors, hook.fixedBounds, polygonColors, width, hook.height,
                          y0,  y1,     hook.boundShift};
  const bool image = hook.image != nullptr;
  for (int r = y0 - 1; r <= y1 + 1; ++r) {
    if (r >= 0 && r < hook.height) space.findMaxima(grid, r);
    const int y = r - 1;
    if (y < y0) continue;
    space.estimateSamples(grid, y, image);  // else only the span is read
    const std::uint32_t* pixels = space.pixelEstimates();
    const auto [first, last] = space.spans[y % 3];
    hook.rows[y] = estimateSums(pixels, first, last);
    if (!image) continue;
    float* out = hook.image + static_cast<std::size_t>(y) * width;
    for (int x = 0; x < width; ++x)  // exact: a power-of-two scale
      out[x] = static_cast<float>(pixels[x]) / static_cast<float>(kEstimateUnit);
  }
}

}  // namespace facet::detail
#endif  // HWY_ONCE
