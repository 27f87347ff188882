#pragma once

// Phase 5: resolve. Every pixel takes its polygon's color (or the background's), in bands of
// whole rows. Its window depth (Conventions.h, "Depth") is not the resolve's: the raster turns
// each tile's depth keys into window depths once it is painted, while the tile is in cache
// (resolveDepths), which saved the resolve a read and a write of the depth plane.

#include <cstddef>
#include <cstdint>

#include "FrameTransform.h"
#include "PhaseRunner.h"
#include "TileGrid.h"
#include "facet/Color.h"
#include "facet/Framebuffer.h"
#include "facet/IdPlane.h"
#include "facet/Renderer.h"

namespace facet::detail {

struct EstimateHook;  // EstimateHook.h
struct PaintCounts;   // RasterTriangle.h

struct ResolveContext {
  const Rgba8* colors;  // per polygon id (Shade.h)
  Rgba8 background;
  Rgba8* color;  // the framebuffer's planes (FramebufferView)
  const std::int32_t* polygonId;
  int width;
  // The error estimate, taken by each band after it is resolved (EstimateHook.h); null: none.
  const EstimateHook* estimate = nullptr;
  // Renderer::ResolvedRowsCallback, called with `target` (the caller's planes) and each band
  // once it is resolved and estimated; null: none.
  const Renderer::ResolvedRowsCallback* resolvedRows = nullptr;
  const FramebufferView* target = nullptr;
  // The raster's counts of the frame's tiles (TileGrid order), or null. A tile with no pixel
  // covered (PaintCounts::covered, counted from its final ids) shows only the background: its
  // colors are written without its ids read (416 of the 510 tiles of the 500k closed sphere),
  // with the estimate too (each row's covered span, which it reads, is found within the
  // covered tiles' columns as they are colored).
  const PaintCounts* tiles = nullptr;
};

// The window depth of a pixel that shows the background (the far plane's).
inline constexpr float kBackgroundWindowDepth = 1.0f;

// The depth keys of a box of pixels (final: a tile the raster has painted) turned into window
// depths, 1 where the id is the background's.
void resolveDepths(const std::int32_t* polygonId, float* depth, int width,
                   const PixelBounds& pixels, const FrameTransform& transform);

// FrameTransform::windowDepth of a key as resolveDepths' scalar path computes it, compiled
// without fused multiply-adds (core/CMakeLists.txt): the bytes every SIMD target gives.
float resolvedDepth(const FrameTransform& transform, float key);

// A color plane of this many bytes or more is streamed to memory (unless the estimate reads
// it back), as a large id plane by widenPolygonIds (facet/IdPlane.h says why). A smaller one
// (a thumbnail, a test's image) is stored plainly, to be read from the caches.
inline constexpr std::size_t kStreamedColorBytes = kStreamedPlaneBytes;

// Colors every pixel of the grid's viewport, a band of whole rows per task (Resolve.cpp says
// why not tile by tile).
bool resolveTiles(PhaseRunner& runner, const TileGrid& grid, const ResolveContext& context);

}  // namespace facet::detail
