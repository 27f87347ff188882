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
//
// In a frame expected to take two passes (Raster.h) whose front pass defers cone-certain
// blocks whole (SetupContext::deferCertainBackBlocks), the same test finds, for each mesh
// that surely draws its back faces, the blocks the front pass will defer whole: their points
// are left out of the needed ones too, and wait for the back pass's block reject
// (DeferredBackPoints.h), which transforms those of the blocks it keeps.

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
    std::size_t outside = 0;        // blocks outside the view
    bool testsBackBlocks = false;   // the set-up will skip its back faces
    bool defersBackBlocks = false;  // it draws them, its cone-certain blocks' points wait
  };
  std::vector<std::uint8_t> visibleBlocks;  // per block of every culled mesh, in turn
  std::vector<std::uint8_t> neededPoints;   // per kPointsPerNeededFlag points of every mesh
  std::vector<std::uint8_t> backBlocks;     // per back-face block of every mesh, in turn
  std::vector<std::uint8_t> latePoints;     // as neededPoints (DeferredBackPoints.h)
  std::vector<std::uint8_t> verdicts;       // as backBlocks (DeferredBackPoints.h)
  std::size_t blocksTested = 0, blocksOutside = 0, polygonsOutside = 0;
  std::size_t backBlocksSkipped = 0, backPolygonsSkipped = 0;
  std::vector<MeshFlags> meshes;      // scratch, per mesh
  std::vector<MeshRange> backRanges;  // scratch: the back-face blocks' test tasks
};

// Marks the needed-point flags (Transform.h) of the points a back-face block of the mesh uses:
// its two spans' flag ranges or, when those are scattered, its list of flags
// (MeshFacts::backPointFlags).
void markPointsOfBlock(const MeshFacts& facts, std::size_t block, std::uint8_t* flags);

// Tests the blocks of every measured mesh against the view and points the meshes with
// blocks outside it at their flags (FrameMesh::visibleBlocks, FrameMesh::neededPoints), and
// those with back-face blocks to skip at theirs (FrameMesh::backBlocks). `closedSurfaces`:
// Rule::ClosedSurfaces may fire (decideBackFaces). The back-face blocks are tested on the
// runner's threads, as part of the transform phase (no progress of their own).
// `deferBackBlockPoints`: the frame is expected to take two passes with the front pass's
// whole-block deferral; the meshes that surely draw their back faces get
// FrameMesh::deferredBackBlocks.
void cullBlocksOutsideView(PhaseRunner& runner, std::span<FrameMesh> meshes, const MeshCache& cache,
                           const FrameTransform& transform, bool closedSurfaces,
                           bool deferBackBlockPoints, ViewCulling& culling);

}  // namespace facet::detail
