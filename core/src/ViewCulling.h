#pragma once

// Rule::GeometryOutsideView: the blocks of polygons (MeshCache.h) whose bounding box lies
// outside the view are dropped before any per-vertex work. Their points are not transformed
// (unless a visible block uses them too) and their polygons not set up, counted as outside.
//
// A closed mesh's back faces are skipped only while none of its points is beyond the near
// plane (Transform.h, decideBackFaces), which untransformed points could not tell: such a
// mesh is culled only when its whole box is in front of the near plane, which decides the
// same way. Blocks with a non-finite point are kept, so that their polygons are counted as
// non-finite as before.
//
// The same pass finds, for each mesh whose back faces the set-up will skip (decided here as
// decideBackFaces will: its material culls them, or it is closed, finite and wholly in front
// of the near plane), the back-face blocks whose every triangle it would cull
// (BackFacingBlocks.h): those are counted as culled without being set up, and their points
// are transformed only when a block that is set up uses them too. Which points are needed is
// marked per kPointsPerNeededFlag points from each back-face block's two point spans
// (MeshCache.h), so that the points between a strip's two rings that only skipped blocks use
// are freed even where every transform task holds some drawn block's points, or, for a block
// whose spans are scattered (a cap of a sphere listed meridian by meridian), from its list of
// flags, so that its spans do not mark the whole mesh needed.

#include <cstdint>
#include <span>
#include <vector>

#include "Frame.h"
#include "MeshCache.h"
#include "PhaseRunner.h"

namespace facet::detail {

struct ViewCulling {
  // One mesh's part of the flags below, and what its tests found.
  struct MeshFlags {
    std::uint8_t* visible = nullptr;
    std::uint8_t* back = nullptr;
    std::uint8_t* needed = nullptr;
    std::size_t outside = 0;       // blocks outside the view
    bool testsBackBlocks = false;  // the set-up will skip its back faces
  };
  std::vector<std::uint8_t> visibleBlocks;  // per block of every culled mesh, in turn
  std::vector<std::uint8_t> neededPoints;   // per kPointsPerNeededFlag points of every mesh
  std::vector<std::uint8_t> backBlocks;     // per back-face block of every mesh, in turn
  std::size_t blocksTested = 0, blocksOutside = 0, polygonsOutside = 0;
  std::size_t backBlocksSkipped = 0, backPolygonsSkipped = 0;
  std::vector<MeshFlags> meshes;      // scratch, per mesh
  std::vector<MeshRange> backRanges;  // scratch: the back-face blocks' test tasks
};

// Tests the blocks of every measured mesh against the view and points the meshes with
// blocks outside it at their flags (FrameMesh::visibleBlocks, FrameMesh::neededPoints), and
// those with back-face blocks to skip at theirs (FrameMesh::backBlocks). `closedSurfaces`:
// Rule::ClosedSurfaces may fire (decideBackFaces). The back-face blocks are tested on the
// runner's threads, as part of the transform phase (no progress of their own).
void cullBlocksOutsideView(PhaseRunner& runner, std::span<FrameMesh> meshes, const MeshCache& cache,
                           const FrameTransform& transform, bool closedSurfaces,
                           ViewCulling& culling);

}  // namespace facet::detail
