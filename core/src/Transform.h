#pragma once

// Phase 1: every point of every mesh to window coordinates (FrameTransform.h), then which
// meshes' back faces cannot be seen this frame, and, for the painter's algorithm, the order
// in which polygons are drawn.

#include <cstdint>
#include <span>
#include <vector>

#include "Frame.h"
#include "PhaseRunner.h"

namespace facet::detail {

// Points per transform task.
inline constexpr std::size_t kPointsPerTransformTask = 1 << 14;
// Points per flag of FrameMesh::neededPoints: a task transforms only its runs of needed
// points. Fine enough that the part of each ring of a 2M-polygon UV sphere (1,000 points)
// that only back-facing blocks use frees a flag or two, and that a sphere listed meridian by
// meridian (vtkSphereSource's; 500 points a meridian at 500k) frees its meridians' far ends
// though its caps' blocks use a point near each meridian's other end (32 points: at 128 the
// cap's flags held the previous meridian's far end too; bench/core-frame-issue11.md, 27).
inline constexpr int kNeededPointBits = 5;
inline constexpr std::size_t kPointsPerNeededFlag = std::size_t{1} << kNeededPointBits;
static_assert(kPointsPerTransformTask % kPointsPerNeededFlag == 0);

// The transform's tasks and, per task, the OR of its points' outcodes.
struct PointRanges {
  std::vector<MeshRange> ranges;
  std::vector<std::uint32_t> outcodes;
};

bool transformPoints(PhaseRunner& runner, std::span<const FrameMesh> meshes,
                     const FrameTransform& transform, PointRanges& ranges,
                     HugePageVector<WindowVertex>& vertices);

// A two-pass frame's points that only the back pass's kept blocks need (FrameMesh::
// latePoints, DeferredBackPoints.h), projected by the same per-point code, on the runner's
// threads as part of the set-up (no progress of its own). `ranges`: scratch.
void transformLatePoints(PhaseRunner& runner, std::span<const FrameMesh> meshes,
                         const FrameTransform& transform, std::vector<MeshRange>& ranges,
                         HugePageVector<WindowVertex>& vertices);

// Sets FrameMesh::skipBackFaces from the material and, for closed surfaces (when
// Rule::ClosedSurfaces may fire), from the points' outcodes. Returns how many closed meshes
// skip their back faces only for being closed.
std::size_t decideBackFaces(std::span<FrameMesh> meshes, const PointRanges& ranges,
                            bool closedSurfaces);

// Painter's order: far to near by the view distance of each polygon's centroid, ties by id.
bool sortForPainter(PhaseRunner& runner, std::span<const FrameMesh> meshes,
                    const FrameTransform& transform, std::vector<MeshRange>& ranges,
                    DrawOrder& order);

}  // namespace facet::detail
