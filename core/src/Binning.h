#pragma once

// Phase 2, second half: binning. A triangle in window space joins the bins of the tiles its
// pixel centers may fall in; the raster phase paints each tile from its bins.

#include <cstddef>
#include <cstdint>

#include "Frame.h"
#include "TileGrid.h"

namespace facet::detail {

enum class BinOutcome { Binned, ZeroArea, CoversNoSample };

// One triangle of `polygon`, given as vertex references (Frame.h) with their window
// vertices, in either winding, `area` its doubleSignedArea and `boundary` its polygon-edge
// mask (RasterTriangle.h). Kept counter-clockwise (corners 1 and 2 swapped if need be)
// unless it has zero area or covers no pixel center.
BinOutcome binTriangle(Chunk& chunk, const TileGrid& grid, std::uint32_t r0, std::uint32_t r1,
                       std::uint32_t r2, const WindowVertex& a, const WindowVertex& b,
                       const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                       std::int32_t polygon);

// Bins a triangle whose box holds one pixel center, (x, y), as its fragment there: it covers
// it with depth key `key` (keyOfOnlySample, RasterTriangle.h).
inline void binFragment(Chunk& chunk, const TileGrid& grid, int x, int y, float key,
                        std::int32_t polygon) {
  ++chunk.counts.boxSamples;
  const auto index = static_cast<std::uint32_t>(chunk.fragments.size()) | kFragmentBit;
  grid.forEachTile({x, y, x, y}, [&](std::size_t t) { chunk.bins[t].push_back(index); });
  chunk.fragments.push_back(
      {static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), key, polygon});
}

// Bins a counter-clockwise triangle (vertex references r0, r1, r2) that covers a pixel center
// of `samples`, those of its box (samplesInBoundingBox), in the tiles they overlap.
inline void binCovering(Chunk& chunk, const TileGrid& grid, std::uint32_t r0, std::uint32_t r1,
                        std::uint32_t r2, const PixelBounds& samples, EdgeMask boundary,
                        std::int32_t polygon) {
  chunk.counts.boxSamples += samples.area();
  const auto index = static_cast<std::uint32_t>(chunk.triangles.size());
  grid.forEachTile(samples, [&](std::size_t t) { chunk.bins[t].push_back(index); });
  chunk.triangles.push_back({{r0, r1, r2}, polygon});
  chunk.boundaryEdges.push_back(boundary);
}

// A bin entry is 32 bits with the top one telling a fragment from a triangle (kFragmentBit),
// and a vertex reference has its top bit for a clipped vertex (kClippedVertexBit): a chunk
// can index fewer than 2^31 triangles, fragments and clipped vertices each. Its 2^20
// polygons stay far below that unless they are huge polygons, each a fan of triangles.
inline constexpr std::size_t kMaxBinnedPerChunk = std::size_t{1} << 31;

// Throws facet::Error naming the count when a chunk holds kMaxBinnedPerChunk or more of any
// of the three (its indices have wrapped: the raster must not read them).
void requireIndexable(std::size_t triangles, std::size_t fragments, std::size_t clippedVertices);

// Empties a chunk's triangles and bins for a new frame, with one bin per tile.
void clearBins(Chunk& chunk, const TileGrid& grid);

}  // namespace facet::detail
