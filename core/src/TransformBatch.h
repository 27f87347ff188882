#pragma once

// Phase 1's projection of points to window coordinates in SIMD lanes (Google Highway, the
// instruction set chosen at run time, as SetupBatch.h): FrameTransform::project for a run of
// points, the same bytes on every instruction set.

#include <cstddef>
#include <cstdint>

#include "FrameTransform.h"

namespace facet::detail {

// vertices[i] = transform.project(point i of xyz) for i < count; returns the OR of their
// outcodes.
std::uint32_t projectPoints(const FrameTransform& transform, const float* xyz, std::size_t count,
                            WindowVertex* vertices);
std::uint32_t projectPoints(const FrameTransform& transform, const double* xyz, std::size_t count,
                            WindowVertex* vertices);

// transform.project(world), compiled as the lanes are: without contraction into fused
// multiply-adds (core/CMakeLists.txt). The reference a test checks the lanes against: project()
// is inline, and a test's own file, compiled for a CPU with FMA, could fuse its products.
WindowVertex projectPoint(const FrameTransform& transform, const glm::dvec3& world);

}  // namespace facet::detail
