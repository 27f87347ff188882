#pragma once

// Phase 2, second half: binning. A triangle in window space joins the bins of the tiles its
// pixel centers may fall in; the raster phase paints each tile from its bins.

#include <cstddef>
#include <cstdint>
#include <span>

#include "Frame.h"
#include "TileGrid.h"

namespace facet::detail {

enum class BinOutcome { Binned, ZeroArea, CoversNoSample };

// One triangle of `polygon`, given as vertex references (Frame.h) with their window
// vertices, in either winding, `area` its doubleSignedArea and `boundary` its polygon-edge
// mask (RasterTriangle.h). Kept counter-clockwise (corners 1 and 2 swapped if need be)
// unless it has zero area or covers no pixel center; in the chunk's backBins when `last`
// (Chunk::binsFor).
BinOutcome binTriangle(Chunk& chunk, const TileGrid& grid, std::uint32_t r0, std::uint32_t r1,
                       std::uint32_t r2, const WindowVertex& a, const WindowVertex& b,
                       const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                       std::int32_t polygon, bool last);

// The tile of pixel (x, y) in the viewport.
inline std::size_t tileOf(const TileGrid& grid, int x, int y) {
  return static_cast<std::size_t>(y / TileGrid::kTileSize) *
             static_cast<std::size_t>(grid.tilesX()) +
         static_cast<std::size_t>(x / TileGrid::kTileSize);
}

// The three appends below leave PolygonCounts::boxSamples to their callers: the set-up's
// batches count a batch's kept boxes at once, in lanes (BatchVerdicts::keptSamples).

// Bins a triangle whose box holds one pixel center, (x, y) in `tile`, as its fragment there: it
// covers it with depth key `key` (keyOfOnlySample, RasterTriangle.h). Inlined, as
// binCovering: the set-up's batches bin most triangles, and out of line their eight
// arguments and the call cost as much as the appends.
[[gnu::always_inline]] inline void binFragment(Chunk& chunk, std::size_t tile, int x, int y,
                                               float key, std::int32_t polygon, bool last) {
  chunk.binsFor(last)[tile].push_back(static_cast<std::uint32_t>(chunk.fragments.size()) |
                                      kFragmentBit);
  chunk.fragments.push_back(
      {static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), key, polygon});
}

// Bins a counter-clockwise triangle (vertex references r0, r1, r2) that covers a pixel center
// of `samples`, those of its box (samplesInBoundingBox), in the tiles they overlap: `onlyTile`
// alone when it is one (not negative).
[[gnu::always_inline]] inline void binCovering(Chunk& chunk, const TileGrid& grid, std::uint32_t r0,
                                               std::uint32_t r1, std::uint32_t r2,
                                               const PixelBounds& samples, EdgeMask boundary,
                                               std::int32_t polygon, bool last,
                                               std::int64_t onlyTile = -1) {
  const auto index = static_cast<std::uint32_t>(chunk.triangles.size());
  auto& bins = chunk.binsFor(last);
  if (onlyTile >= 0) {
    bins[static_cast<std::size_t>(onlyTile)].push_back(index);
  } else {
    grid.forEachTile(samples, [&](std::size_t t) { bins[t].push_back(index); });
  }
  chunk.triangles.push_back({{r0, r1, r2}, polygon});
  chunk.boundaryEdges.push_back(boundary);
}

// Bins a SmallTriangle (RasterTriangle.h) the set-up's lanes made, in its one tile; in the
// chunk's backBins when `last` (Chunk::binsFor).
[[gnu::always_inline]] inline void binSmall(Chunk& chunk, std::size_t tile,
                                            const SmallTriangle& triangle, bool last) {
  chunk.binsFor(last)[tile].push_back(static_cast<std::uint32_t>(chunk.smallTriangles.size()) |
                                      kSmallTriangleBit);
  chunk.smallTriangles.push_back(triangle);
}

// A bin entry is 32 bits with the top two telling a fragment (kFragmentBit), a small
// triangle (kSmallTriangleBit) and a triangle apart, and a vertex reference has its top bit
// for a clipped vertex (kClippedVertexBit): a chunk can index fewer than 2^30 of each. Its
// 2^20 polygons stay far below that unless they are huge polygons, each a fan of triangles.
inline constexpr std::size_t kMaxBinnedPerChunk = kBinIndexMask + std::size_t{1};

// Throws facet::Error naming the count when a chunk holds kMaxBinnedPerChunk or more of any
// of the four (its indices have wrapped: the raster must not read them).
void requireIndexable(std::size_t triangles, std::size_t fragments, std::size_t smallTriangles,
                      std::size_t clippedVertices);

// Empties a chunk's triangles and bins for a new frame, with one bin per tile.
void clearBins(Chunk& chunk, const TileGrid& grid);

// Once a frame's records are painted: every chunk's records, bins and lists emptied, their
// storage sized for the next frame from what they held (AppendBuffer::settle).
void settleRecords(std::span<Chunk> chunks);

}  // namespace facet::detail
