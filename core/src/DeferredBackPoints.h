#pragma once

// A two-pass frame's (Raster.h) back-face blocks that BackFaceTest proves all back faces are
// deferred whole by the front pass (SetupContext::deferCertainBackBlocks), and the back
// pass's block reject (HiddenBlocks.h) drops nearly all of them from their boxes alone, before
// any of their points is read. So the transform phase leaves out the points only those blocks
// use (ViewCulling.h: FrameMesh::deferredBackBlocks), and once the front faces are painted
// the blocks are tested here, each block's verdict kept for the back pass
// (FrameMesh::backBlockVerdicts: setUpBackRun takes it in place of its own test, the same
// one), and the points the kept blocks use that were left out are projected then
// (FrameMesh::latePoints, transformLatePoints). Every point a set-up or paint reads is thus
// projected, by the same per-point code, before it is read: the same bytes. At 2M polygons
// in vtkSphereSource's order this spares the transform of about a third of the points
// (bench/core-frame-issue11.md, section 33).

#include <cstdint>
#include <span>
#include <vector>

#include "Frame.h"
#include "MeshCache.h"
#include "PhaseRunner.h"
#include "TileGrid.h"
#include "ViewCulling.h"

namespace facet::detail {

// Tests every deferred block against the front faces' blocks (`front` null, or the reject
// off: every block kept), points the meshes at their verdicts and late points, and projects
// those points into `vertices`; then no mesh has deferred blocks (a second call does nothing).
// `blockRanges`, `pointRanges`: scratch.
void transformKeptBackBlocks(PhaseRunner& runner, std::span<FrameMesh> meshes,
                             const MeshCache& cache, const FrameTransform& transform,
                             const TileGrid& grid, const FrontDepthBlocks* front,
                             ViewCulling& culling, std::vector<MeshRange>& blockRanges,
                             std::vector<MeshRange>& pointRanges,
                             HugePageVector<WindowVertex>& vertices);

}  // namespace facet::detail
