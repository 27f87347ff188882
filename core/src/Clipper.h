#pragma once

// Sutherland–Hodgman clipping of one triangle in homogeneous clip space.

#include <cstdint>

#include <glm/vec4.hpp>

#include "FrameTransform.h"

namespace facet::detail {

// A clip-space vertex, remembering which input vertex it is (or kNewVertex for a vertex the
// clipper made), so that unclipped corners keep their already-snapped window coordinates.
struct ClipVertex {
  static constexpr std::uint32_t kNewVertex = 0xffffffffu;
  glm::dvec4 clip;
  std::uint32_t source = kNewVertex;
};

// One extra vertex per plane at most.
inline constexpr int kMaxClippedVertices = 3 + kClipPlaneCount;

// Clips the triangle against every plane whose Outcode bit is set in `planes`. Writes the
// convex result to `out` and returns its vertex count: 0 (nothing left) or 3..9.
//
// The intersection on an edge is always computed from its inside end toward its outside end,
// so two triangles sharing an edge get bit-identical new vertices on it: clipping keeps the
// mesh watertight.
int clipTriangle(const FrameTransform& transform, const ClipVertex (&triangle)[3],
                 std::uint32_t planes, ClipVertex (&out)[kMaxClippedVertices]);

}  // namespace facet::detail
