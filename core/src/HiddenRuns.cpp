// HiddenRuns.h's runs, compiled once per instruction set by Highway's foreach_target (this file
// includes itself) and dispatched at run time, once per block.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "HiddenRuns.cpp"
#include <hwy/cache_control.h>
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

// A kept block's polygons' offsets and (a triangle block's) connectivity, written long before
// and read after hidden blocks the hardware prefetcher's stream skipped, asked for at once, all
// their cache lines, before the runs load them one polygon after another (bench section 49).
template <class Index>
HWY_INLINE void prefetchBlock(const RunSource<Index>& source, const std::uint32_t* ids,
                              std::size_t count) {
  constexpr std::size_t kLine = 64;
  const std::size_t first = ids[0] - source.firstId, last = ids[count - 1] - source.firstId;
  const auto* offsets = reinterpret_cast<const char*>(source.polygons.offsets);
  for (std::size_t at = first * sizeof(Index); at < (last + 2) * sizeof(Index); at += kLine)
    hwy::Prefetch(offsets + at);
  if (!source.allTriangles) return;
  // Every polygon from first to last is a triangle: their references are the 3 (last - first
  // + 1) from offsets[first] on.
  const auto* connectivity = reinterpret_cast<const char*>(
      source.polygons.connectivity + static_cast<std::size_t>(source.polygons.offsets[first]));
  const std::size_t bytes = 3 * (last - first + 1) * sizeof(Index);
  for (std::size_t at = 0; at < bytes; at += kLine)
    hwy::Prefetch(connectivity + at);
}

template <class Index>
std::size_t shownOfRunsOf(const HiddenRunTest& test, const RunSource<Index>& source,
                          const std::uint32_t* ids, std::size_t count, std::uint32_t* shown,
                          RunTally& tally) {
  const WindowVertex* const vertices = source.vertices;
  const Index* const offsets = source.polygons.offsets;
  const Index* const connectivity = source.polygons.connectivity;
  if (count != 0) prefetchBlock(source, ids, count);
  std::size_t out = 0;
  for (std::size_t k = 0; k < count;) {
    const std::uint32_t windowEnd =
        ((ids[k] - source.firstId) | (kHiddenRunIds - 1)) + 1 + source.firstId;
    RunLanes lanes;
    bool notTriangle = false;
    std::size_t i = k;
    do {
      const std::size_t polygon = ids[i] - source.firstId;
      const auto begin = static_cast<std::size_t>(offsets[polygon]);
      if (!source.allTriangles && offsets[polygon + 1] - offsets[polygon] != 3) {
        notTriangle = true;
        continue;
      }
      lanes.add(vertices[connectivity[begin]]);
      lanes.add(vertices[connectivity[begin + 1]]);
      lanes.add(vertices[connectivity[begin + 2]]);
    } while (++i < count && ids[i] < windowEnd);
    RunBounds bounds = lanes.finish();
    if (notTriangle) bounds.outcodes |= RunBounds::kNotTriangle;
    const bool hidden = test.hidden(bounds);
    ++tally.runs;
    tally.polygons += i - k;
    if (hidden) {
      ++tally.hiddenRuns;
      tally.hiddenPolygons += i - k;
      k = i;
      continue;
    }
    for (; k < i; ++k)
      shown[out++] = ids[k];
  }
  return out;
}

std::size_t ShownOfRuns32(const HiddenRunTest& test, const RunSource<std::int32_t>& source,
                          const std::uint32_t* ids, std::size_t count, std::uint32_t* shown,
                          RunTally& tally) {
  return shownOfRunsOf(test, source, ids, count, shown, tally);
}

std::size_t ShownOfRuns64(const HiddenRunTest& test, const RunSource<std::int64_t>& source,
                          const std::uint32_t* ids, std::size_t count, std::uint32_t* shown,
                          RunTally& tally) {
  return shownOfRunsOf(test, source, ids, count, shown, tally);
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {

HWY_EXPORT(ShownOfRuns32);
HWY_EXPORT(ShownOfRuns64);

std::size_t shownOfRuns(const HiddenRunTest& test, const RunSource<std::int32_t>& source,
                        std::span<const std::uint32_t> ids, std::uint32_t* shown, RunTally& tally) {
  return HWY_DYNAMIC_DISPATCH(ShownOfRuns32)(test, source, ids.data(), ids.size(), shown, tally);
}

std::size_t shownOfRuns(const HiddenRunTest& test, const RunSource<std::int64_t>& source,
                        std::span<const std::uint32_t> ids, std::uint32_t* shown, RunTally& tally) {
  return HWY_DYNAMIC_DISPATCH(ShownOfRuns64)(test, source, ids.data(), ids.size(), shown, tally);
}

}  // namespace facet::detail
#endif  // HWY_ONCE
