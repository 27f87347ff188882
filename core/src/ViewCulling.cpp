#include "ViewCulling.h"

#include <algorithm>

#include "BackFacingBlocks.h"
#include "Transform.h"

namespace facet::detail {
namespace {

// Whether the mesh's blocks may be culled at all this frame.
bool cullable(const FrameMesh& mesh, const MeshFacts& facts, const FrameTransform& transform) {
  if (!facts.measured || facts.blocks.empty()) return false;
  return !mesh.mesh().closedSurface ||
         (facts.allFinite && transform.boxInFrontOfNear(facts.bounds));
}

// Tests the mesh's blocks into `visible`; returns how many are outside.
std::size_t testBlocks(const MeshFacts& facts, const FrameTransform& transform,
                       std::uint8_t* visible) {
  std::size_t outside = 0;
  for (std::size_t b = 0; b < facts.blocks.size(); ++b) {
    visible[b] = !(facts.blockFinite[b] && transform.boxOutsideView(facts.blocks[b]));
    outside += !visible[b];
  }
  return outside;
}

// The transform tasks (Transform.h) that the visible blocks' points fall in.
void markNeededTasks(const MeshFacts& facts, const std::uint8_t* visible, std::uint8_t* tasks) {
  for (std::size_t b = 0; b < facts.blocks.size(); ++b) {
    const PointSpan span = facts.blockPoints[b];
    if (!visible[b] || span.first > span.last) continue;
    std::fill(tasks + span.first / kPointsPerTransformTask,
              tasks + span.last / kPointsPerTransformTask + 1, std::uint8_t{1});
  }
}

// Whether decideBackFaces will skip the mesh's back faces, known before its points are
// transformed: a closed mesh's when no point can be beyond the near plane nor non-finite.
bool willSkipBackFaces(const FrameMesh& mesh, const MeshFacts& facts,
                       const FrameTransform& transform, bool closedSurfaces) {
  if (mesh.source->material.backfaceCulling) return true;
  return closedSurfaces && mesh.mesh().closedSurface && facts.bounded && facts.allFinite &&
         transform.boxInFrontOfNear(facts.bounds);
}

// Tests the back-face blocks in view into `back`; returns how many are skipped.
std::size_t testBackBlocks(const MeshFacts& facts, const BackFaceTest& test,
                           const std::uint8_t* visible, std::uint8_t* back) {
  std::size_t skipped = 0;
  for (std::size_t b = 0; b < facts.backBlocks.size(); ++b) {
    const bool inView = !visible || visible[b >> (kBlockBits - kBackBlockBits)];
    back[b] = inView && test.certainlyCulled(facts.backBlocks[b]);
    skipped += back[b];
  }
  return skipped;
}

// The transform tasks that the back-face blocks in view and not skipped use.
void markTasksOfBackBlocks(const MeshFacts& facts, const std::uint8_t* visible,
                           const std::uint8_t* back, std::uint8_t* tasks) {
  for (std::size_t b = 0; b < facts.backBlocks.size(); ++b) {
    const PointSpan span = facts.backBlocks[b].points;
    const bool inView = !visible || visible[b >> (kBlockBits - kBackBlockBits)];
    if (!inView || back[b] || span.first > span.last) continue;
    std::fill(tasks + span.first / kPointsPerTransformTask,
              tasks + span.last / kPointsPerTransformTask + 1, std::uint8_t{1});
  }
}

std::size_t polygonsOutside(const MeshFacts& facts, const MeshView& mesh,
                            const std::uint8_t* visible) {
  std::size_t count = 0;
  for (std::size_t b = 0; b < facts.blocks.size(); ++b) {
    if (!visible[b]) {
      count += std::min(kPolygonsPerBlock, mesh.polygons.count - b * kPolygonsPerBlock);
    }
  }
  return count;
}

std::size_t taskCount(const MeshView& mesh) {
  return (mesh.points.count + kPointsPerTransformTask - 1) / kPointsPerTransformTask;
}

}  // namespace

void cullBlocksOutsideView(std::span<FrameMesh> meshes, const MeshCache& cache,
                           const FrameTransform& transform, bool closedSurfaces,
                           ViewCulling& culling) {
  culling.blocksTested = culling.blocksOutside = culling.polygonsOutside = 0;
  culling.backBlocksSkipped = 0;
  std::size_t blocks = 0, tasks = 0, backBlocks = 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    blocks += cache[m].blocks.size();
    backBlocks += cache[m].backBlocks.size();
    tasks += taskCount(meshes[m].mesh());
  }
  culling.visibleBlocks.resize(blocks);  // pointers into these stay valid below
  culling.backBlocks.resize(backBlocks);
  culling.neededTasks.assign(tasks, 0);
  const BackFaceTest backFaceTest(transform);
  std::size_t firstBlock = 0, firstBackBlock = 0, firstTask = 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    FrameMesh& mesh = meshes[m];
    const MeshFacts& facts = cache[m];
    std::uint8_t* visible = culling.visibleBlocks.data() + firstBlock;
    std::uint8_t* back = culling.backBlocks.data() + firstBackBlock;
    std::uint8_t* needed = culling.neededTasks.data() + firstTask;
    firstBlock += facts.blocks.size();
    firstBackBlock += facts.backBlocks.size();
    firstTask += taskCount(mesh.mesh());
    if (!cullable(mesh, facts, transform)) continue;
    culling.blocksTested += facts.blocks.size();
    const std::size_t outside = testBlocks(facts, transform, visible);
    const std::uint8_t* visibleOrAll = outside > 0 ? visible : nullptr;
    const std::size_t skipped =
        backBlockSkippingEnabled() && willSkipBackFaces(mesh, facts, transform, closedSurfaces)
            ? testBackBlocks(facts, backFaceTest, visibleOrAll, back)
            : 0;
    if (outside > 0) {
      culling.blocksOutside += outside;
      culling.polygonsOutside += polygonsOutside(facts, mesh.mesh(), visible);
      mesh.visibleBlocks = visible;
    }
    if (skipped > 0) {
      culling.backBlocksSkipped += skipped;
      markTasksOfBackBlocks(facts, visibleOrAll, back, needed);
      mesh.backBlocks = back;
      mesh.neededTasks = needed;
    } else if (outside > 0) {
      markNeededTasks(facts, visible, needed);
      mesh.neededTasks = needed;
    }
  }
}

}  // namespace facet::detail
