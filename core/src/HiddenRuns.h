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
// polygon id (the deferred ids are global), and whether every polygon of the block is a
// triangle (MeshFacts::backSkippable: the sizes are not read).
template <class Index>
struct RunSource {
  const WindowVertex* vertices;
  Polygons<Index> polygons;
  std::uint32_t firstId;
  bool allTriangles;
};

// The runs a block's ids made and dropped, and their polygons (FACET_HIDDEN_BLOCKS_DEBUG).
struct RunTally {
  std::size_t runs = 0, hiddenRuns = 0, polygons = 0, hiddenPolygons = 0;
};

// Splits `ids` (one back-face block's deferred ids, ascending) into runs, the ids of one
// aligned window of kHiddenRunIds polygon ids, and writes the ids of the runs `test` does not
// drop to `shown`, in order; returns how many. `tally` adds up the runs.
std::size_t shownOfRuns(const HiddenRunTest& test, const RunSource<std::int32_t>& source,
                        std::span<const std::uint32_t> ids, std::uint32_t* shown, RunTally& tally);
std::size_t shownOfRuns(const HiddenRunTest& test, const RunSource<std::int64_t>& source,
                        std::span<const std::uint32_t> ids, std::uint32_t* shown, RunTally& tally);

}  // namespace facet::detail
