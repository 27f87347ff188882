#pragma once

// Sutherland–Hodgman clipping of one triangle in homogeneous clip space.

#include <cstdint>

#include "FrameTransform.h"

namespace facet::detail {

// A clip-space vertex, remembering which input vertex it is (or kNewVertex for a vertex the
// clipper made), so that unclipped corners keep their already-snapped window coordinates,
// and which edges of the input triangle it lies on (bit i: the edge opposite corner i), so
// that the sides of the clipped polygon know which input edge they are part of.
struct ClipVertex {
  static constexpr std::uint32_t kNewVertex = 0xffffffffu;
  ClipPoint clip;
  std::uint32_t source = kNewVertex;
  std::uint8_t onEdges = 0;
};

// One extra vertex per plane at most.
inline constexpr int kMaxClippedVertices = 3 + kClipPlaneCount;

// Clips the triangle against every plane whose Outcode bit is set in `planes`. Writes the
// convex result to `out` and returns its vertex count: 0 (nothing left) or 3..9.
//
// The intersection on an edge is always computed from its inside end toward its outside end,
// so two triangles sharing an edge get bit-identical new vertices on it: clipping keeps the
// mesh watertight. It is robust for every finite input (FrameTransform::toClip bounds the
// magnitudes): the parameter along the edge is a ratio of a non-negative and a positive
// distance, in [0, 1], never NaN; the point is interpolated from the nearer end, so it stays
// between the ends (d and h stay positive where both ends' are); and it is then put exactly
// on the plane (FrameTransform::placeOnPlane).
int clipTriangle(const FrameTransform& transform, const ClipVertex (&triangle)[3],
                 std::uint32_t planes, ClipVertex (&out)[kMaxClippedVertices]);

}  // namespace facet::detail
