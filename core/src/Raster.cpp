#include "Raster.h"

#include <algorithm>

#include "facet/Framebuffer.h"

namespace facet::detail {
namespace {

void clearTile(const RasterContext& context, const PixelBounds& tile) {
  for (int y = tile.y0; y <= tile.y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * context.width;
    std::fill(context.depth + row + tile.x0, context.depth + row + tile.x1 + 1,
              kBackgroundDepthKey);
    std::fill(context.polygonId + row + tile.x0, context.polygonId + row + tile.x1 + 1,
              Framebuffer::kBackgroundId);
  }
}

template <DepthMode kMode>
PaintCounts paintTile(const RasterContext& context, std::size_t t, const PixelBounds& tile) {
  clearTile(context, tile);
  const Planes planes{context.color, context.depth, context.polygonId, context.width,
                      context.shown.data()};
  PaintCounts counts;
  for (const Chunk& chunk : context.chunks) {
    for (const std::uint32_t index : chunk.bins[t]) {
      const BinnedTriangle& tri = chunk.triangles[index];
      paintTriangle<kMode>(vertexOf(context.vertices, chunk, tri.vertex[0]),
                           vertexOf(context.vertices, chunk, tri.vertex[1]),
                           vertexOf(context.vertices, chunk, tri.vertex[2]),
                           chunk.boundaryEdges[index], tri.polygon, tile, planes, counts);
    }
  }
  return counts;
}

}  // namespace

TileRoutineChoice chooseTileRoutine(bool depthTest) {
  if (depthTest) return {paintTile<DepthMode::Test>, "depth test"};
  return {paintTile<DepthMode::Overwrite>, "painter's overwrite"};
}

bool paintTiles(PhaseRunner& runner, const TileGrid& grid, const RasterContext& context,
                TileRoutine routine, std::vector<PaintCounts>& counts) {
  std::fill(context.shown.begin(), context.shown.end(), std::uint8_t{0});
  counts.assign(grid.count(), {});
  return runner.run(Phase::Raster, grid.count(),
                    [&](std::size_t t) { counts[t] = routine(context, t, grid.bounds(t)); });
}

}  // namespace facet::detail
