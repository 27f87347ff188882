// HiddenRuns.h's runs, compiled once per instruction set by Highway's foreach_target (this file
// includes itself) and dispatched at run time, once per block.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "HiddenRuns.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <limits>

#include "HiddenRuns.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// One lane: the bounds vertex by vertex (RunBounds::add).
struct RunLanes {
  RunBounds bounds;
  HWY_INLINE void add(const WindowVertex& v) { bounds.add(v); }
  HWY_INLINE RunBounds finish() const { return bounds; }
};
#else
// A vertex's words x, y, key and outcode word in the lanes of one 128-bit vector: the least
// and the largest x and y, the largest key (as floats) and the outcodes' bits, over the run.
struct RunLanes {
  using DI = hn::Full128<std::int32_t>;
  using DF = hn::Full128<float>;
  hn::Vec<DI> least, most, bits;
  hn::Vec<DF> nearest;

  // (Not default member initializers: the implicit constructor has not the target's options.)
  HWY_INLINE RunLanes()
      : least(hn::Set(DI(), std::numeric_limits<std::int32_t>::max())),
        most(hn::Set(DI(), std::numeric_limits<std::int32_t>::min())),
        bits(hn::Zero(DI())),
        nearest(hn::Set(DF(), -std::numeric_limits<float>::infinity())) {}

  HWY_INLINE void add(const WindowVertex& v) {
    const auto words = hn::LoadU(DI(), reinterpret_cast<const std::int32_t*>(&v));
    least = hn::Min(least, words);
    most = hn::Max(most, words);
    bits = hn::Or(bits, words);
    nearest = hn::Max(nearest, hn::BitCast(DF(), words));
  }
  HWY_INLINE RunBounds finish() const {
    RunBounds run;
    run.x0 = hn::GetLane(least), run.y0 = hn::ExtractLane(least, 1);
    run.x1 = hn::GetLane(most), run.y1 = hn::ExtractLane(most, 1);
    run.nearest = hn::ExtractLane(nearest, 2);
    run.outcodes = static_cast<std::uint32_t>(hn::ExtractLane(bits, 3)) & 0xFFFFu;  // outcode
    return run;
  }
};
static_assert(sizeof(WindowVertex) == 16);
#endif

// What a polygon that is not a triangle gets for corners: an outcode never kInside, so its
// run is not dropped (step R1, as RunBounds::kNotTriangle).
constexpr WindowVertex kNotTriangleCorner{0, 0, 0.0f, kNonFinite, 0, 0};

// Copies the corners of the ids' polygons to `corners` (3 a polygon), every polygon's loads
// independent of the others' so that their misses overlap: the runs then take their bounds
// from there, in order.
template <class Index>
HWY_INLINE void gatherCorners(const RunSource<Index>& source, const std::uint32_t* ids,
                              std::size_t count, WindowVertex* HWY_RESTRICT corners) {
  const WindowVertex* const vertices = source.vertices;
  const Index* const offsets = source.polygons.offsets;
  const Index* const connectivity = source.polygons.connectivity;
  // Polygon i's corners, from its three point references `c`.
  const auto copy = [&](std::size_t i, const Index* c) {
    corners[3 * i] = vertices[c[0]];
    corners[3 * i + 1] = vertices[c[1]];
    corners[3 * i + 2] = vertices[c[2]];
  };
  if (source.offsetsThrice) {
    for (std::size_t i = 0; i < count; ++i)
      copy(i, connectivity + 3 * static_cast<std::size_t>(ids[i] - source.firstId));
    return;
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t polygon = ids[i] - source.firstId;
    if (!source.allTriangles && offsets[polygon + 1] - offsets[polygon] != 3) {
      corners[3 * i] = corners[3 * i + 1] = corners[3 * i + 2] = kNotTriangleCorner;
      continue;
    }
    copy(i, connectivity + static_cast<std::size_t>(offsets[polygon]));
  }
}

template <class Index>
std::size_t shownOfRunsOf(const HiddenRunTest& test, const RunSource<Index>& source,
                          const std::uint32_t* ids, std::size_t count, std::uint32_t* shown,
                          WindowVertex* corners, RunTally& tally) {
  if (count == 0) return 0;
  gatherCorners(source, ids, count, corners);
  std::size_t out = 0;
  for (std::size_t k = 0; k < count;) {
    const std::uint32_t windowEnd =
        ((ids[k] - source.firstId) | (kHiddenRunIds - 1)) + 1 + source.firstId;
    RunLanes lanes;
    std::size_t i = k;
    do {
      lanes.add(corners[3 * i]);
      lanes.add(corners[3 * i + 1]);
      lanes.add(corners[3 * i + 2]);
    } while (++i < count && ids[i] < windowEnd);
    const bool hidden = test.hidden(lanes.finish());
    ++tally.runs;
    tally.polygons += i - k;
    if (hidden) {
      ++tally.hiddenRuns;
      tally.hiddenPolygons += i - k;
      k = i;
      continue;
    }
    for (; k < i; ++k)
      shown[out++] = static_cast<std::uint32_t>(k);
  }
  return out;
}

std::size_t ShownOfRuns32(const HiddenRunTest& test, const RunSource<std::int32_t>& source,
                          const std::uint32_t* ids, std::size_t count, std::uint32_t* shown,
                          WindowVertex* corners, RunTally& tally) {
  return shownOfRunsOf(test, source, ids, count, shown, corners, tally);
}

std::size_t ShownOfRuns64(const HiddenRunTest& test, const RunSource<std::int64_t>& source,
                          const std::uint32_t* ids, std::size_t count, std::uint32_t* shown,
                          WindowVertex* corners, RunTally& tally) {
  return shownOfRunsOf(test, source, ids, count, shown, corners, tally);
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {

HWY_EXPORT(ShownOfRuns32);
HWY_EXPORT(ShownOfRuns64);

std::size_t shownOfRuns(const HiddenRunTest& test, const RunSource<std::int32_t>& source,
                        std::span<const std::uint32_t> ids, std::uint32_t* shown,
                        WindowVertex* corners, RunTally& tally) {
  return HWY_DYNAMIC_DISPATCH(ShownOfRuns32)(test, source, ids.data(), ids.size(), shown, corners,
                                             tally);
}

std::size_t shownOfRuns(const HiddenRunTest& test, const RunSource<std::int64_t>& source,
                        std::span<const std::uint32_t> ids, std::uint32_t* shown,
                        WindowVertex* corners, RunTally& tally) {
  return HWY_DYNAMIC_DISPATCH(ShownOfRuns64)(test, source, ids.data(), ids.size(), shown, corners,
                                             tally);
}

}  // namespace facet::detail
#endif  // HWY_ONCE
