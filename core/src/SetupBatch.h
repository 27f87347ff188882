#pragma once

// Set-up's first pass over triangles, in batches: most triangles of a dense mesh are dropped
// (back-facing, zero area, or covering no pixel center) and need none of the per-triangle
// path's work. A batch decides those drops for kBatchSize triangles at once, in SIMD lanes
// (Google Highway, the instruction set chosen at run time); the triangles it cannot drop go
// through the per-triangle path (Setup.cpp), which decides again, exactly as without batches.
// A drop is only ever decided on the same exact integer facts as that path's, so the image
// is the same bytes with batches or without, on any instruction set.

#include <cstdint>
#include <vector>

#include "TileGrid.h"

namespace facet::detail {

// 16: the int32 lanes of one AVX-512 vector, two of AVX2, four of SSE4, sixteen rounds of
// the portable target's one lane.
inline constexpr int kBatchSize = 16;
static_assert(kBatchSize <= 32, "verdicts hold a bit per lane");

// Triangles in lanes: vertex j's snapped window coordinates (FrameTransform.h) in x[j], y[j].
// A lane is tested only when its triangle is a plain triangle with every vertex inside
// (`tested` = 1); others (polygons, triangles to clip, unused lanes) are left to the
// per-triangle path.
struct TriangleBatch {
  alignas(64) std::int32_t x[3][kBatchSize];
  alignas(64) std::int32_t y[3][kBatchSize];
  alignas(64) std::int32_t tested[kBatchSize];
};

// What a batch decided: per kind of drop, one bit per lane (bit l for lane l). Each drop is
// counted as the per-triangle path would count it; every other lane goes on to that path.
// The counts are the bits set in each (counted with the instruction set's POPCNT, which the
// baseline build has not: std::popcount there is a call into libgcc).
struct BatchVerdicts {
  std::uint32_t culled = 0;          // back-facing, and the mesh skips back faces
  std::uint32_t zeroArea = 0;        // degenerate
  std::uint32_t coversNoSample = 0;  // no pixel center inside (or in the viewport): outside
  // Not a drop: lanes kept whose box of at most 2 × 2 pixel centers holds one they cover, so
  // binning need not test their coverage again (coversAnySample, RasterTriangle.h).
  std::uint32_t coversSample = 0;
  int culledCount = 0, zeroAreaCount = 0, coversNoSampleCount = 0;
  std::uint32_t dropped() const { return culled | zeroArea | coversNoSample; }
};

// The verdicts for a viewport and the mesh's back-face handling.
BatchVerdicts classifyBatch(const TriangleBatch& batch, const PixelBounds& viewport,
                            bool skipBackFaces);

// Tests and benchmarks: which instruction sets the batch runs on. Not for use while a render
// runs.
struct SimdTarget {
  std::int64_t bits;  // Highway's HWY_* target bit
  const char* name;   // "EMU128" (portable C++), "SSE4", "AVX2", "AVX3", ...
};
// The targets compiled in and supported by this CPU, best first; the last is the portable
// fallback.
std::vector<SimdTarget> simdTargets();
// Restricts the batch to `target`'s instruction set (0: the best this CPU has again).
void useSimdTarget(std::int64_t target);
// The instruction set the batch runs on now.
const char* simdTargetInUse();
// Off: every polygon through the per-triangle path alone (the set-up before batches).
void enableSetupBatches(bool on);
bool setupBatchesEnabled();

}  // namespace facet::detail
