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

// Marks the needed-point flags (Transform.h) that a span of point ids falls in.
void markPointsOf(const PointSpan& span, std::uint8_t* flags) {
  if (span.first > span.last) return;  // no point
  std::fill(flags + (span.first >> kNeededPointBits), flags + (span.last >> kNeededPointBits) + 1,
            std::uint8_t{1});
}

// Whether decideBackFaces will skip the mesh's back faces, known before its points are
// transformed: a closed mesh's when no point can be beyond the near plane nor non-finite.
bool willSkipBackFaces(const FrameMesh& mesh, const MeshFacts& facts,
                       const FrameTransform& transform, bool closedSurfaces) {
  if (mesh.source->material.backfaceCulling) return true;
  return closedSurfaces && mesh.mesh().closedSurface && facts.bounded && facts.allFinite &&
         transform.boxInFrontOfNear(facts.bounds);
}

// Whether decideBackFaces will surely draw the mesh's back faces, whatever its points.
bool surelyDrawsBackFaces(const FrameMesh& mesh, bool closedSurfaces) {
  return !mesh.source->material.backfaceCulling && !(closedSurfaces && mesh.mesh().closedSurface);
}

// Back-face blocks per task of the parallel test: about 100k instructions at most.
constexpr std::size_t kBackBlocksPerTask = 64;

bool backBlockInView(const std::uint8_t* visible, std::size_t b) {
  return !visible || visible[b >> (kBlockBits - kBackBlockBits)];
}

void fillFlags(std::uint32_t first, std::uint32_t end, std::uint8_t* flags) {
  std::fill(flags + first, flags + end, std::uint8_t{1});
}

// The points that the back-face blocks in view and not skipped (`back` null: none is) use,
// from their compact flag ranges (MeshFacts::backPointFlags): the whole record only for a
// block with scattered flags.
void markNeededPoints(const MeshFacts& facts, const std::uint8_t* visible, const std::uint8_t* back,
                      std::uint8_t* flags) {
  for (std::size_t b = 0; b < facts.backPointFlags.size(); ++b) {
    if (!backBlockInView(visible, b) || (back && back[b])) continue;
    const BackPointFlags& ranges = facts.backPointFlags[b];
    if (ranges.lowFirst == kReadWholeBackBlock) {
      markPointsOfBlock(facts, b, flags);
      continue;
    }
    fillFlags(ranges.lowFirst, ranges.lowEnd, flags);
    fillFlags(ranges.highFirst, ranges.highEnd, flags);
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

std::size_t flagCount(const MeshView& mesh) {
  return (mesh.points.count + kPointsPerNeededFlag - 1) >> kNeededPointBits;
}

// Points the mesh at its flags and counts what its tests found.
void applyCulling(FrameMesh& mesh, const MeshFacts& facts, ViewCulling& culling, std::size_t m) {
  const ViewCulling::MeshFlags& flags = culling.meshes[m];
  // The blocks it skips (testsBackBlocks) or the front pass will defer (defersBackBlocks).
  const std::size_t flagged =
      flags.testsBackBlocks || flags.defersBackBlocks
          ? std::size_t(std::count(flags.back, flags.back + facts.backBlockCount(), 1))
          : 0;
  const std::size_t skipped = flags.testsBackBlocks ? flagged : 0;
  const std::uint8_t* visibleOrAll = flags.outside > 0 ? flags.visible : nullptr;
  if (flags.outside > 0) {
    culling.blocksOutside += flags.outside;
    culling.polygonsOutside += polygonsOutside(facts, mesh.mesh(), flags.visible);
    mesh.visibleBlocks = flags.visible;
  }
  if (skipped > 0) {
    // Only the last back-face block may be short (skipped > 0: there is one).
    const std::size_t lastBlock = facts.backBlockCount() - 1;
    const std::size_t lastBlockPolygons =
        mesh.mesh().polygons.count - (lastBlock << kBackBlockBits);
    culling.backBlocksSkipped += skipped;
    culling.backPolygonsSkipped += (skipped - flags.back[lastBlock]) * kPolygonsPerBackBlock +
                                   flags.back[lastBlock] * lastBlockPolygons;
    mesh.backBlocks = flags.back;
  }
  if (flags.defersBackBlocks && flagged > 0) mesh.deferredBackBlocks = flags.back;
  if (flagged > 0 || flags.outside > 0) {
    markNeededPoints(facts, visibleOrAll, flagged > 0 ? flags.back : nullptr, flags.needed);
    mesh.neededPoints = flags.needed;
  }
}

}  // namespace

void markPointsOfBlock(const MeshFacts& facts, std::size_t block, std::uint8_t* flags) {
  const BackPointFlags& ranges = facts.backPointFlags[block];
  if (ranges.lowFirst != kReadWholeBackBlock) {
    fillFlags(ranges.lowFirst, ranges.lowEnd, flags);
    fillFlags(ranges.highFirst, ranges.highEnd, flags);
  } else if (!facts.wideBackSpans.empty()) {
    markPointsOf(facts.wideBackSpans[2 * block], flags);
    markPointsOf(facts.wideBackSpans[2 * block + 1], flags);
  } else {
    for (std::uint32_t i = ranges.highFirst; i < ranges.highEnd; ++i)
      flags[facts.scatteredPointFlags[i]] = 1;
  }
}

void cullBlocksOutsideView(PhaseRunner& runner, std::span<FrameMesh> meshes, const MeshCache& cache,
                           const FrameTransform& transform, bool closedSurfaces,
                           bool deferBackBlockPoints, ViewCulling& culling) {
  culling.blocksTested = culling.blocksOutside = culling.polygonsOutside = 0;
  culling.backBlocksSkipped = culling.backPolygonsSkipped = 0;
  std::size_t blocks = 0, pointFlags = 0, backBlocks = 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    blocks += cache[m].blocks.size();
    backBlocks += cache[m].backBlockCount();
    pointFlags += flagCount(meshes[m].mesh());
  }
  culling.visibleBlocks.resize(blocks);  // pointers into these stay valid below
  culling.backBlocks.resize(backBlocks);
  culling.neededPoints.assign(pointFlags, 0);
  culling.meshes.assign(meshes.size(), ViewCulling::MeshFlags{});
  culling.backRanges.clear();
  std::size_t firstBlock = 0, firstBackBlock = 0, firstFlag = 0;
  const bool skipping = ScopedBackBlockSettings::current().skipping;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const FrameMesh& mesh = meshes[m];
    const MeshFacts& facts = cache[m];
    ViewCulling::MeshFlags& flags = culling.meshes[m];
    flags.visible = culling.visibleBlocks.data() + firstBlock;
    flags.back = culling.backBlocks.data() + firstBackBlock;
    flags.needed = culling.neededPoints.data() + firstFlag;
    firstBlock += facts.blocks.size();
    firstBackBlock += facts.backBlockCount();
    firstFlag += flagCount(mesh.mesh());
    if (!cullable(mesh, facts, transform)) continue;
    culling.blocksTested += facts.blocks.size();
    flags.outside = testBlocks(facts, transform, flags.visible);
    if (!skipping) continue;
    flags.testsBackBlocks = willSkipBackFaces(mesh, facts, transform, closedSurfaces);
    flags.defersBackBlocks = !flags.testsBackBlocks && deferBackBlockPoints &&
                             surelyDrawsBackFaces(mesh, closedSurfaces);
    if (!flags.testsBackBlocks && !flags.defersBackBlocks) continue;
    for (std::size_t b = 0; b < facts.backBlockCount(); b += kBackBlocksPerTask)
      culling.backRanges.push_back(
          {m, b, std::min(facts.backBlockCount(), b + kBackBlocksPerTask)});
  }
  // The back-face blocks, independent of each other, on every thread: at 2M polygons about
  // 31,000 of them, most of the culling's work. The pre-test reads the compact cones
  // and the rest of the test (MeshFacts::backTests), not the whole records.
  const BackFaceTest backFaceTest(transform);
  runner.runUnreported(culling.backRanges.size(), [&](std::size_t i) {
    const MeshRange& r = culling.backRanges[i];
    const ViewCulling::MeshFlags& flags = culling.meshes[r.mesh];
    const std::uint8_t* visible = flags.outside > 0 ? flags.visible : nullptr;
    const MeshFacts& facts = cache[r.mesh];
    // A view-culling block's back-face blocks at a time (the tasks start at one): the
    // pre-tests first, their verdicts kept without a branch, so that the blocks' chains of
    // decoding, dot products and square root overlap instead of restarting after each
    // mispredicted verdict (half of them); then the rest of the test for those that passed.
    constexpr std::size_t kBackBlocksPerBlock = std::size_t{1} << (kBlockBits - kBackBlockBits);
    static_assert(kBackBlocksPerTask % kBackBlocksPerBlock == 0);
    for (std::size_t first = r.begin; first < r.end; first += kBackBlocksPerBlock) {
      const std::size_t end = std::min(r.end, first + kBackBlocksPerBlock);
      std::fill(flags.back + first, flags.back + end, std::uint8_t{0});
      if (!backBlockInView(visible, first)) continue;
      const BackBlockFrame& frame = facts.backFrameOf(first);
      bool mayFaceAway[kBackBlocksPerBlock];
      for (std::size_t b = first; b < end; ++b)
        mayFaceAway[b - first] = backFaceTest.mayFaceAway(facts.backTests[b], frame);
      ParentClipBounds parent;
      parent.box = &facts.blocks[first >> (kBlockBits - kBackBlockBits)];
      for (std::size_t b = first; b < end; ++b) {
        if (mayFaceAway[b - first])
          flags.back[b] = backFaceTest.culledPastPreTest(facts.backTests[b], frame, parent);
      }
    }
  });
  for (std::size_t m = 0; m < meshes.size(); ++m)
    applyCulling(meshes[m], cache[m], culling, m);
}

}  // namespace facet::detail
