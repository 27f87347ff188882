#pragma once

// Phase 5: resolve. Every pixel takes its polygon's color (or the background's), and its
// depth key becomes window depth (Conventions.h, "Depth"), in bands of whole rows.

#include <cstdint>
#include <functional>

#include "FrameTransform.h"
#include "PhaseRunner.h"
#include "TileGrid.h"
#include "facet/Color.h"
#include "facet/Framebuffer.h"

namespace facet::detail {

struct EstimateHook;  // EstimateHook.h

struct ResolveContext {
  const Rgba8* colors;  // per polygon id (Shade.h)
  Rgba8 background;
  Rgba8* color;  // the framebuffer's planes (FramebufferView)
  float* depth;
  const std::int32_t* polygonId;
  int width;
  // The error estimate, taken by each band after it is resolved (EstimateHook.h); null: none.
  const EstimateHook* estimate = nullptr;
  // Renderer::ResolvedRowsCallback, called with `target` (the caller's planes) and each band
  // once it is resolved and estimated; null: none.
  const std::function<void(const FramebufferView&, int, int)>* resolvedRows = nullptr;
  const FramebufferView* target = nullptr;
};

// The resolve of a box of pixels, chosen once per render: colors and window depths, or colors
// only (no depth output, or depths already resolved by the frame an incremental render
// reuses).
using ResolveRoutine = void (*)(const ResolveContext& context, const PixelBounds& pixels,
                                const FrameTransform& transform);
struct ResolveRoutineChoice {
  ResolveRoutine resolve;
  const char* name;
};
ResolveRoutineChoice chooseResolveRoutine(bool depth);

// The depth keys of a box of pixels (final: a tile the raster has painted, while it is in
// cache) turned into window depths, the bytes chooseResolveRoutine(true) gives them; the
// resolve then colors only.
void resolveDepths(const std::int32_t* polygonId, float* depth, int width, const PixelBounds& pixels,
                   const FrameTransform& transform);

// FrameTransform::windowDepth of a key as this phase's scalar path computes it, compiled
// without fused multiply-adds (core/CMakeLists.txt): the bytes every SIMD target gives.
float resolvedDepth(const FrameTransform& transform, float key);

// Resolves every pixel of the grid's viewport with the routine, a band of whole rows per task
// (Resolve.cpp says why not tile by tile), turning depth keys into window depths by
// `transform`.
bool resolveTiles(PhaseRunner& runner, const TileGrid& grid, const ResolveContext& context,
                  ResolveRoutine routine, const FrameTransform& transform);

}  // namespace facet::detail
