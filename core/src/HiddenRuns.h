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

// A kept block's reads asked for ahead of its runs (the back pass takes them a kept block or
// two before shownOfRuns, section 62 of bench/core-frame-issue11.md): its polygons' offsets
// and connectivity (written long before, and after hidden blocks the hardware prefetcher's
// stream skipped), then, once those are in, its triangles' corners. Hints only: nothing read
// changes. `ids`: the block's deferred ids (at least one), ascending.
template <class Index>
inline void prefetchRunConnectivity(const RunSource<Index>& source, const std::uint32_t* ids,
                                    std::size_t count) {
  constexpr std::size_t kLine = 64;
  const std::size_t first = ids[0] - source.firstId, last = ids[count - 1] - source.firstId;
  const char* from;
  std::size_t bytes;
  if (source.offsetsThrice) {  // every polygon a triangle: the references from 3·first on
    from = reinterpret_cast<const char*>(source.polygons.connectivity + 3 * first);
    bytes = 3 * (last - first + 1) * sizeof(Index);
  } else {  // offsets[first] to offsets[last + 1]
    from = reinterpret_cast<const char*>(source.polygons.offsets + first);
    bytes = (last - first + 2) * sizeof(Index);
  }
  for (std::size_t at = 0; at < bytes; at += kLine)
    __builtin_prefetch(from + at);
}
template <class Index>
inline void prefetchRunCorners(const RunSource<Index>& source, const std::uint32_t* ids,
                               std::size_t count) {
  if (source.offsetsThrice) {  // each corner's vertex (its connectivity asked for before)
    for (std::size_t i = 0; i < count; ++i) {
      const Index* c = source.polygons.connectivity + 3 * std::size_t(ids[i] - source.firstId);
      __builtin_prefetch(source.vertices + c[0]);
      __builtin_prefetch(source.vertices + c[1]);
      __builtin_prefetch(source.vertices + c[2]);
    }
    return;
  }
  if (!source.allTriangles) return;
  // A triangle block's references: the 3 (last − first + 1) from offsets[first] on.
  constexpr std::size_t kLine = 64;
  const std::size_t first = ids[0] - source.firstId, last = ids[count - 1] - source.firstId;
  const auto* from = reinterpret_cast<const char*>(
      source.polygons.connectivity + static_cast<std::size_t>(source.polygons.offsets[first]));
  for (std::size_t at = 0; at < 3 * (last - first + 1) * sizeof(Index); at += kLine)
    __builtin_prefetch(from + at);
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
