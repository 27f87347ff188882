#include "DeferredBackPoints.h"

#include <algorithm>
#include <optional>

#include "BackFacingBlocks.h"
#include "HiddenBlocks.h"
#include "Transform.h"

namespace facet::detail {
namespace {

// Deferred blocks per task of the parallel reject: about 100k instructions at most.
constexpr std::size_t kBlocksPerRejectTask = 64;

// The flags of `culling`'s arrays that belong to mesh m (ViewCulling::MeshFlags' offsets).
std::uint8_t* verdictsOf(ViewCulling& culling, std::size_t m) {
  return culling.verdicts.data() + (culling.meshes[m].back - culling.backBlocks.data());
}
std::uint8_t* latePointsOf(ViewCulling& culling, std::size_t m) {
  return culling.latePoints.data() + (culling.meshes[m].needed - culling.neededPoints.data());
}

// The late points of mesh m: those its kept blocks use that the transform phase left out.
void markLatePoints(const FrameMesh& mesh, const MeshFacts& facts, const std::uint8_t* verdicts,
                    std::uint8_t* late, std::size_t flagCount) {
  std::fill(late, late + flagCount, std::uint8_t{0});
  for (std::size_t b = 0; b < facts.backBlockCount(); ++b) {
    if (verdicts[b] == kBlockKept) markPointsOfBlock(facts, b, late);
  }
  for (std::size_t f = 0; f < flagCount; ++f)
    late[f] &= static_cast<std::uint8_t>(!mesh.neededPoints[f]);
}

}  // namespace

void transformKeptBackBlocks(PhaseRunner& runner, std::span<FrameMesh> meshes,
                             const MeshCache& cache, const FrameTransform& transform,
                             const TileGrid& grid, const FrontDepthBlocks* front,
                             ViewCulling& culling, std::vector<MeshRange>& blockRanges,
                             std::vector<MeshRange>& pointRanges,
                             HugePageVector<WindowVertex>& vertices) {
  culling.verdicts.resize(culling.backBlocks.size());
  culling.latePoints.resize(culling.neededPoints.size());
  blockRanges.clear();
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (!meshes[m].deferredBackBlocks) continue;
    const std::size_t count = cache[m].backBlockCount();
    for (std::size_t b = 0; b < count; b += kBlocksPerRejectTask)
      blockRanges.push_back({m, b, std::min(count, b + kBlocksPerRejectTask)});
  }
  if (blockRanges.empty()) return;
  // The back pass's reject (setUpBackRun): on with the front blocks unless turned off.
  const bool reject = front != nullptr && hiddenBlocksEnabled();
  std::optional<HiddenBlockTest> hidden;
  if (reject) hidden.emplace(transform, grid, *front);
  runner.runUnreported(blockRanges.size(), [&](std::size_t i) {
    const MeshRange& r = blockRanges[i];
    const std::uint8_t* deferred = meshes[r.mesh].deferredBackBlocks;
    const MeshFacts& facts = cache[r.mesh];
    std::uint8_t* verdicts = verdictsOf(culling, r.mesh);
    for (std::size_t b = r.begin; b < r.end; ++b) {
      if (!deferred[b]) {
        verdicts[b] = 0;
        continue;
      }
      const bool dropped = reject && facts.backSkippable(b) &&
                           hidden->hidden(boxOf(facts.backTests[b], facts.backFrameOf(b)));
      verdicts[b] = dropped ? kBlockHidden : kBlockKept;
    }
  });
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    FrameMesh& mesh = meshes[m];
    if (!mesh.deferredBackBlocks) continue;
    const std::uint8_t* verdicts = verdictsOf(culling, m);
    // Without the reject the back pass tests nothing: no verdict for it to take.
    if (reject) mesh.backBlockVerdicts = verdicts;
    if (countingHiddenBlocks()) {
      const std::size_t n = cache[m].backBlockCount();
      waitingBlocksDebug(n - std::size_t(std::count(verdicts, verdicts + n, std::uint8_t{0})),
                         std::size_t(std::count(verdicts, verdicts + n, kBlockKept)));
    }
    std::uint8_t* late = latePointsOf(culling, m);
    const std::size_t flagCount =
        (mesh.mesh().points.count + kPointsPerNeededFlag - 1) >> kNeededPointBits;
    markLatePoints(mesh, cache[m], verdicts, late, flagCount);
    mesh.latePoints = late;
    mesh.deferredBackBlocks = nullptr;  // no point waits any more
  }
  transformLatePoints(runner, meshes, transform, pointRanges, vertices);
}

}  // namespace facet::detail
