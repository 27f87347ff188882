#pragma once

// The back pass's runs (HiddenBlocks.h, steps R1–R3) of one back-face block's deferred ids,
// their bounds taken in SIMD lanes (HiddenRuns.cpp: Highway, the instruction set chosen at run
// time): each vertex's four 32-bit words (x, y, key, outcode word: WindowVertex) in one
// 128-bit vector, a run's bounds its lanes' minimum, maximum and bitwise or. Min, max and or
// are exact, so every instruction set drops the same runs (the bounds of RunBounds::add, a
// NaN key aside, which only a vertex with kNonFinite in its outcode has: never dropped).

#include <cstddef>
#include <cstdint>
#include <span>

#include "FrameTransform.h"
#include "HiddenBlocks.h"
#include "MeshAccess.h"

namespace facet::detail {

// What a block's runs are taken from: the mesh's window vertices and polygons, its first
// polygon id (the deferred ids are global), whether every polygon of the block is a
// triangle (MeshFacts::backSkippable: the sizes are not read), and whether every polygon of
// the mesh is one, stored in order (FrameMesh::allTriangles: offsets[p] = 3p, the offsets are
// not read either).
template <class Index>
struct RunSource {
  const WindowVertex* vertices;
  Polygons<Index> polygons;
  std::uint32_t firstId;
  bool allTriangles;
  bool offsetsThrice;
};

// Asks for every cache line of [from, from + bytes).
[[gnu::always_inline]] inline void prefetchBytes(const void* from, std::size_t bytes) {
  constexpr std::uintptr_t kLine = 64;
  const auto end = reinterpret_cast<std::uintptr_t>(from) + bytes;
  for (auto at = reinterpret_cast<std::uintptr_t>(from) & ~(kLine - 1); at < end; at += kLine)
    __builtin_prefetch(reinterpret_cast<const void*>(at));
}

// A kept block's polygon references asked for ahead of its runs (section 64 of
// bench/core-frame-issue11.md; written long before, and read after hidden blocks the hardware
// prefetcher's stream skipped). The back pass asks for the first part as it queues the block,
// a few kept blocks before its runs: a mesh of triangles in order (offsetsThrice) has its
// connectivity at 3p, read from no offset; another mesh, its offsets. Then, right before the
// runs, the second: such a mesh's triangle block's connectivity, from the offsets asked for
// then (section 49). Hints only: nothing read changes. `firstId`, `lastId`: the block's
// first and last deferred ids (global). Always inlined: GCC takes a function that only prefetches
// for one without effects and drops the call (measured: none was left in setUpBackRun).
template <class Index>
[[gnu::always_inline]] inline void prefetchRunsAhead(const RunSource<Index>& source,
                                                     std::uint32_t firstId, std::uint32_t lastId) {
  const std::size_t first = firstId - source.firstId, last = lastId - source.firstId;
  if (source.offsetsThrice)
    prefetchBytes(source.polygons.connectivity + 3 * first, 3 * (last - first + 1) * sizeof(Index));
  else
    prefetchBytes(source.polygons.offsets + first, (last - first + 2) * sizeof(Index));
}
template <class Index>
[[gnu::always_inline]] inline void prefetchRunsNow(const RunSource<Index>& source,
                                                   std::uint32_t firstId, std::uint32_t lastId) {
  if (source.offsetsThrice || !source.allTriangles) return;
  const std::size_t first = firstId - source.firstId, last = lastId - source.firstId;
  prefetchBytes(
      source.polygons.connectivity + static_cast<std::size_t>(source.polygons.offsets[first]),
      3 * (last - first + 1) * sizeof(Index));
}

// The runs a block's ids made and dropped, and their polygons (FACET_HIDDEN_BLOCKS_DEBUG).
struct RunTally {
  std::size_t runs = 0, hiddenRuns = 0, polygons = 0, hiddenPolygons = 0;
};

// Splits `ids` (one back-face block's deferred ids, ascending) into runs, the ids of one
// aligned window of kHiddenRunIds polygon ids, and writes the positions in `ids` of the ids of
// the runs `test` does not drop to `shown`, in order; returns how many. `corners` (room for
// 3 · ids.size()) receives every polygon's corners as they were read for the runs, polygon
// ids[i]'s corner j at 3i + j when it is a triangle (the window vertices' bytes; any bytes for
// one that is not), so that the back pass's set-up loads a shown triangle from there instead
// of reading its connectivity and vertices again. `tally` adds up the runs.
std::size_t shownOfRuns(const HiddenRunTest& test, const RunSource<std::int32_t>& source,
                        std::span<const std::uint32_t> ids, std::uint32_t* shown,
                        WindowVertex* corners, RunTally& tally);
std::size_t shownOfRuns(const HiddenRunTest& test, const RunSource<std::int64_t>& source,
                        std::span<const std::uint32_t> ids, std::uint32_t* shown,
                        WindowVertex* corners, RunTally& tally);

}  // namespace facet::detail
