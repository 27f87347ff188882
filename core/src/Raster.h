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
  // A two-pass frame: the front pass leaves each tile's blocks here (paintFrontTiles).
  FrontDepthBlocks* frontBlocks = nullptr;
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

// A two-pass frame (every face drawn, with the depth test and without the coarse depth), its
// raster in two passes around the back faces' set-up (SetupPass, Setup.h). The front pass
// paints every chunk's front bins and leaves each tile's depth keys and ids in the image's
// planes (no extra memory: they are the planes the tile would write at its end) and its
// FarthestBlocks in context.frontBlocks; the back pass reads a tile's planes back (one more
// read and write of 8 bytes a pixel, 16 MB at 1080p), paints every chunk's back bins, then
// finishes the tile as one pass would. The same pixels as the depth test in one pass: the
// back faces the set-up dropped would have written none.
bool paintFrontTiles(PhaseRunner& runner, const TileGrid& grid, const RasterContext& context,
                     std::vector<PaintCounts>& counts);
bool paintBackTiles(PhaseRunner& runner, const TileGrid& grid, const RasterContext& context,
                    std::vector<PaintCounts>& counts);

// Whether frames that may (every face drawn, the depth test, no forced coarse depth) run in two
// passes: by the plan's rule by default (chooseTwoPassFrame, Plan.h); forced on or off by
// FACET_TWO_PASS_FRAMES=1 / 0 in the environment or enableTwoPassFrames (tests, measurements),
// back to the plan by planTwoPassFrames.
enum class TwoPassFrames { ByPlan, Off, On };
void enableTwoPassFrames(bool on);
void planTwoPassFrames();
TwoPassFrames twoPassFrames();

// Adds what the tiles counted (fragments, pixels covered, triangles hidden) to `stats`.
void addPaintCounts(std::span<const PaintCounts> tiles, RenderStats& stats);

}  // namespace facet::detail
