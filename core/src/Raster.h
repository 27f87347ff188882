#pragma once

// Phase 3: raster. Each tile, on one thread: cleared, then its bins' triangles painted in
// draw order (depth key and polygon id per pixel, RasterTriangle.h) — with the depth test,
// the front faces' first, then the back faces' (so that an exact tie keeps the front face, and
// back faces mostly fail against the front faces already there) — then the polygons its
// final image shows marked, and its depth keys turned into window depths.

#include <cstdint>
#include <span>
#include <vector>

#include "Frame.h"
#include "FrameTransform.h"
#include "PhaseRunner.h"
#include "TileGrid.h"
#include "facet/RenderPlan.h"

namespace facet::detail {

struct RasterContext {
  std::span<const Chunk> chunks;
  const WindowVertex* vertices;  // the frame's projected points (Transform.h)
  float* depth;  // the framebuffer's planes (FramebufferView): keys, or window depths
  std::int32_t* polygonId;
  int width;
  std::span<std::uint8_t> shown;  // out, per polygon id: a pixel of the image shows it
  // Not null: each tile's depth keys become window depths once it is painted, while in cache
  // (resolveDepths, Resolve.h), and the resolve colors only.
  const FrameTransform* windowDepths = nullptr;
};

// One tile's painting, specialized once per render (llvmpipe's lp_rast_tri_tab).
using TileRoutine = PaintCounts (*)(const RasterContext& context, std::size_t tile,
                                    const PixelBounds& bounds);
struct TileRoutineChoice {
  TileRoutine paint;
  const char* name;
};
// The painter's overwrite, the depth test, or the depth test behind the tiles' coarse depth.
TileRoutineChoice chooseTileRoutine(bool depthTest, bool coarseDepth);

bool paintTiles(PhaseRunner& runner, const TileGrid& grid, const RasterContext& context,
                TileRoutine routine, std::vector<PaintCounts>& counts);

// Adds what the tiles counted (fragments, pixels covered, triangles hidden) to `stats`.
void addPaintCounts(std::span<const PaintCounts> tiles, RenderStats& stats);

}  // namespace facet::detail
