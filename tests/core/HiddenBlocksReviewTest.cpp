// review25's checks of the whole-block reject (HiddenBlocks.h) and the two-pass frames it runs
// in: what a frame reports and paints must not depend on whether the plan chose two passes.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "../support/TwoPassScenes.h"
#include "HiddenBlocks.h"
#include "MeshCache.h"
#include "Raster.h"
#include "SetupBatch.h"

namespace facet::testing {
namespace {

class HiddenBlocksReview : public TwoPassTest {};

// 256 back-facing triangles (one back-face block) of side `side`, scattered on a 16 × 16 grid
// over [-spread, spread]² at z = `z`: wound clockwise seen from +Z.
void addBackSpecks(Mesh& mesh, double spread, double side, double z) {
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      const double x = -spread + 2.0 * spread * (i + 0.37) / 16.0;
      const double y = -spread + 2.0 * spread * (j + 0.61) / 16.0;
      const std::int64_t a = mesh.addPoint({x, y, z});
      const std::int64_t b = mesh.addPoint({x + side, y, z});
      const std::int64_t c = mesh.addPoint({x, y + side, z});
      mesh.addPolygon({a, c, b});
    }
  }
}

// The field data the filters report (PolygonsDrawn, PolygonsOutside, PolygonsHidden, ...) must
// not depend on whether the plan chose two passes (it does so from the last frame's covered
// pixels) but through PolygonsHidden: a back face too small to cover a pixel center is
// "outside" in one pass, and a two-pass frame that drops its block whole behind the front
// faces cannot tell, so it counts the block's polygons hidden, neither drawn nor outside
// (review25 found them counted drawn and binned: one pass 512 drawn, 256 outside, 512 binned;
// two passes 768, 0, 768).
TEST_F(HiddenBlocksReview, DroppedBlocksCountTheirPolygonsHidden) {
  Mesh mesh;
  addBackSpecks(mesh, 0.5, 0.001, -3.5);  // polygons 0–255: sub-pixel specks far behind
  addBackFan(mesh, -3.4, -3.4);           // 256–511: a fan behind, covering pixels
  addFrontSquare(mesh, 16, 0.6, -3.0, 0.0);
  MeshView view = mesh.view();
  view.version = 1;  // measured: its blocks' boxes
  Camera camera;
  camera.position = {0.0, 0.0, 0.0};
  camera.focalPoint = {0.0, 0.0, -1.0};
  const RenderOptions options = optionsWith(1);
  detail::enableTwoPassFrames(false);
  const Rendered before = renderScene(oneMeshScene(view), camera, 320, 240, options);
  ASSERT_GT(before.stats.polygonsOutside, 100u);  // most specks cover no pixel center
  EXPECT_EQ(before.stats.polygonsHidden, 0u);
  detail::enableTwoPassFrames(true);
  const Rendered after = renderScene(oneMeshScene(view), camera, 320, 240, options);
  ASSERT_EQ(after.stats.plan.polygonsHiddenBehindFront, 512u);  // both blocks dropped
  EXPECT_EQ(after.stats.polygonsHidden, 512u);
  EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u);
  const RenderStats &s = before.stats, &t = after.stats;
  EXPECT_EQ(t.polygonsDrawn + t.polygonsOutside + t.polygonsDegenerate + t.polygonsHidden,
            s.polygonsDrawn + s.polygonsOutside + s.polygonsDegenerate);
  EXPECT_EQ(t.polygonsDrawn, 512u);  // the square alone
  EXPECT_EQ(t.polygonsOutside, 0u);
  EXPECT_EQ(t.trianglesBinned, 512u);
  EXPECT_GT(s.trianglesBinned, t.trianglesBinned);  // the fan's, in one pass
  EXPECT_EQ(s.polygonsCulled, t.polygonsCulled);
  EXPECT_EQ(s.fragmentsWritten, t.fragmentsWritten);
}

// Back faces coplanar with the front faces (a surface and its own back, or two sheets glued
// together): their keys tie with the front keys up to the interpolation's rounding, so the
// clamp of a written key to the triangle's nearest vertex key (nearestWrittenKey) decides
// pixels here. One pass and two passes must paint the same bytes on every SIMD target: a
// clamp applied in one kind of frame and not the other would show as z-fighting that depends
// on the last frame's coverage.
TEST_F(HiddenBlocksReview, CoplanarBackFacesRenderAsOnePassOnEveryTarget) {
  for (const double slope : {0.0, 0.7, -2.5}) {
    SCOPED_TRACE("slope " + std::to_string(slope));
    Mesh mesh;
    addFrontSquare(mesh, 24, 0.6, -3.0, slope);
    // The same plane as back faces, tessellated otherwise: 37 × 37 cells, wound clockwise.
    const std::int64_t corner = static_cast<std::int64_t>(mesh.points.size());
    constexpr int kCells = 37;
    for (int y = 0; y <= kCells; ++y) {
      for (int x = 0; x <= kCells; ++x) {
        const double px = -0.55 + 1.1 * x / kCells, py = -0.55 + 1.1 * y / kCells;
        mesh.addPoint({px, py, -3.0 + slope * px});
      }
    }
    for (int y = 0; y < kCells; ++y) {
      for (int x = 0; x < kCells; ++x) {
        const std::int64_t p = corner + y * (kCells + 1) + x;
        mesh.addPolygon({p, p + kCells + 2, p + 1});
        mesh.addPolygon({p, p + kCells + 1, p + kCells + 2});
      }
    }
    MeshView view = mesh.view();
    view.version = 1;
    Camera camera;
    camera.position = {0.05, -0.03, 0.0};
    camera.focalPoint = {0.0, 0.0, -3.0};
    for (int threads : {1, 2}) {
      SCOPED_TRACE(std::to_string(threads) + " threads");
      const RenderOptions options = optionsWith(threads);
      detail::enableTwoPassFrames(false);
      const Rendered before = renderScene(oneMeshScene(view), camera, 400, 300, options);
      ASSERT_GT(before.stats.pixelsCovered, 40000u);
      detail::enableTwoPassFrames(true);
      for (const detail::SimdTarget& target : detail::simdTargets()) {
        SCOPED_TRACE(target.name);
        detail::useSimdTarget(target.bits);
        const Rendered after = renderScene(oneMeshScene(view), camera, 400, 300, options);
        EXPECT_TRUE(after.stats.plan.twoPassFrame);
        EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u);
        EXPECT_EQ(before.stats.fragmentsWritten, after.stats.fragmentsWritten);
      }
    }
  }
}

// One view of HiddenBlocks.ApexThroughTheFrontFaceIsNeverDropped's scene, its points scaled by
// `scale` about the eye and moved with it by `offset`.
struct ApexView {
  const char* name;
  glm::dvec3 offset;
  double scale;
  bool parallel;
  double nearClip;  // in units of `scale`
  double poke;      // how far the apex pokes through the square at z = −3, in units of `scale`
  double rimDrop = 2e-5;  // how far behind the square its rim lies, in units of `scale`
};

// Steps 3–5 of the proof (HiddenBlocks.h) where their roundings are largest: data far from
// the origin (the eye beside it), tiny and huge scales, parallel projection with a near plane
// just in front of the geometry (keys near 0) or behind the eye (negative near: keys and
// distances of both signs). In each, the apex pokes through the front square by a few float
// steps of its key and wins pixels in one pass: its block must not be dropped, the far fan's
// must, and the bytes are one pass's.
TEST_F(HiddenBlocksReview, ApexThroughTheFrontFaceIsNeverDroppedAnywhere) {
  const ApexView views[] = {
      {"offset 1e7", {1e7, -3e7, 2e7}, 1.0, false, 0.01, 1.5e-6},
      {"offset 1e12, scale 1e3", {1e12, 1e12, -1e12}, 1e3, false, 0.01, 1.5e-6},
      {"scale 1e-9", {0.0, 0.0, 0.0}, 1e-9, false, 0.01, 1.5e-6},
      {"near 2.99", {0.0, 0.0, 0.0}, 1.0, false, 2.99, 1.5e-6},
      {"parallel", {0.0, 0.0, 0.0}, 1.0, true, 0.01, 1.5e-6},
      {"parallel, near 2.9", {0.0, 0.0, 0.0}, 1.0, true, 2.9, 6e-8, 8e-7},
      {"parallel, near -5", {0.0, 0.0, 0.0}, 1.0, true, -5.0, 4e-6},
      {"parallel, offset 1e6", {1e6, 1e6, 1e6}, 1.0, true, 0.01, 1.5e-6},
  };
  for (const ApexView& v : views) {
    SCOPED_TRACE(v.name);
    Mesh mesh;
    addBackFan(mesh, -3.5, -3.5);                       // polygons 0–255: far behind the square
    addBackFan(mesh, -3.0 + v.poke, -3.0 - v.rimDrop);  // 256–511: the apex through it
    addFrontSquare(mesh, 16, 0.6, -3.0, 0.0);           // 512–1023
    for (glm::dvec3& point : mesh.points)
      point = v.offset + v.scale * point;
    MeshView view = mesh.view();
    view.version = 1;
    Camera camera;
    camera.position = v.offset;
    camera.focalPoint = v.offset + glm::dvec3(0.0, 0.0, -v.scale);
    camera.parallelProjection = v.parallel;
    camera.parallelScale = 0.8 * v.scale;
    camera.nearClip = v.nearClip * v.scale;
    camera.farClip = 10.0 * v.scale;
    const RenderOptions options = optionsWith(1);
    detail::enableTwoPassFrames(false);
    const Rendered before = renderScene(oneMeshScene(view), camera, 320, 240, options);
    std::size_t apexPixels = 0;
    for (std::int32_t id : before.framebuffer.polygonId())
      apexPixels += id >= 256 && id < 512;
    ASSERT_GT(apexPixels, 4u);  // the apex wins pixels around it
    detail::enableTwoPassFrames(true);
    for (const detail::SimdTarget& target : detail::simdTargets()) {
      SCOPED_TRACE(target.name);
      detail::useSimdTarget(target.bits);
      detail::countHiddenBlocks(true);
      const Rendered after = renderScene(oneMeshScene(view), camera, 320, 240, options);
      const detail::HiddenBlockCounts counts = detail::hiddenBlockCounts();
      EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u);
      EXPECT_EQ(before.stats.fragmentsWritten, after.stats.fragmentsWritten);
      // The far fan's back-face blocks alone.
      EXPECT_EQ(counts.hidden, 256 / detail::kPolygonsPerBackBlock) << "of " << counts.blocks;
    }
  }
}

}  // namespace
}  // namespace facet::testing
