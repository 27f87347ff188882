// review25's checks of the whole-block reject (HiddenBlocks.h) and the two-pass frames it runs
// in: what a frame reports and paints must not depend on whether the plan chose two passes.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "HiddenBlocks.h"
#include "Raster.h"

namespace facet::testing {
namespace {

class HiddenBlocksReview : public EveryTargetTest {
 protected:
  void TearDown() override {
    detail::planTwoPassFrames();
    detail::enableHiddenBlocks(true);
    detail::countHiddenBlocks(false);
    EveryTargetTest::TearDown();
  }
  static RenderOptions optionsWith(int threads) {
    RenderOptions options;
    options.visibility = Visibility::ZBuffer;
    options.threads = threads;
    return options;
  }
};

// A square of 2·cells² front-facing triangles in the plane z = z0 + slope·x, seen from +Z.
void addFrontSquare(Mesh& mesh, int cells, double half, double z0, double slope) {
  const std::int64_t corner = static_cast<std::int64_t>(mesh.points.size());
  for (int y = 0; y <= cells; ++y) {
    for (int x = 0; x <= cells; ++x) {
      const double px = -half + 2.0 * half * x / cells, py = -half + 2.0 * half * y / cells;
      mesh.addPoint({px, py, z0 + slope * px});
    }
  }
  for (int y = 0; y < cells; ++y) {
    for (int x = 0; x < cells; ++x) {
      const std::int64_t p = corner + y * (cells + 1) + x;
      mesh.addPolygon({p, p + 1, p + cells + 2});
      mesh.addPolygon({p, p + cells + 2, p + cells + 1});
    }
  }
}

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

// The field data the filters report (PolygonsDrawn, PolygonsOutside, TrianglesBinned, ...)
// must not depend on whether the plan chose two passes (it does so from the last frame's
// covered pixels): a back face too small to cover a pixel center is "outside" in one pass, so
// it must be in a two-pass frame even when its block is dropped whole behind the front faces.
// DISABLED: fails on every24's main (one pass: 512 drawn, 256 outside, 512 binned; two passes:
// 768, 0, 768): Setup.cpp's forEachShown counts a dropped block's polygons drawn and binned.
// Enable it with the fix review25's report describes.
TEST_F(HiddenBlocksReview, DISABLED_DroppedBlocksCountTheirPolygonsAsOnePassCountsThem) {
  Mesh mesh;
  addBackSpecks(mesh, 0.5, 0.001, -3.5);  // polygons 0–255: sub-pixel specks far behind
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
  detail::enableTwoPassFrames(true);
  const Rendered after = renderScene(oneMeshScene(view), camera, 320, 240, options);
  ASSERT_EQ(after.stats.plan.polygonsHiddenBehindFront, 256u);  // the specks' block dropped
  EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u);
  EXPECT_EQ(before.stats.polygonsDrawn, after.stats.polygonsDrawn);
  EXPECT_EQ(before.stats.polygonsOutside, after.stats.polygonsOutside);
  EXPECT_EQ(before.stats.polygonsCulled, after.stats.polygonsCulled);
  EXPECT_EQ(before.stats.polygonsDegenerate, after.stats.polygonsDegenerate);
  EXPECT_EQ(before.stats.trianglesBinned, after.stats.trianglesBinned);
  EXPECT_EQ(before.stats.fragmentsWritten, after.stats.fragmentsWritten);
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
      for (const SimdTarget& target : detail::simdTargets()) {
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

// A fan of 256 back-facing triangles around (0, 0, apexZ) with its rim at rimZ, radius 0.3.
void addReviewBackFan(Mesh& mesh, double apexZ, double rimZ) {
  const std::int64_t apex = mesh.addPoint({0.0, 0.0, apexZ});
  const std::int64_t first = static_cast<std::int64_t>(mesh.points.size());
  constexpr int kSides = 256;
  for (int i = 0; i < kSides; ++i) {
    const double angle = 2.0 * 3.14159265358979323846 * i / kSides;
    mesh.addPoint({0.3 * std::cos(angle), 0.3 * std::sin(angle), rimZ});
  }
  for (int i = 0; i < kSides; ++i)
    mesh.addPolygon({apex, first + (i + 1) % kSides, first + i});
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
    addReviewBackFan(mesh, -3.5, -3.5);  // polygons 0–255: far behind the square
    addReviewBackFan(mesh, -3.0 + v.poke, -3.0 - v.rimDrop);  // 256–511: the apex through it
    addFrontSquare(mesh, 16, 0.6, -3.0, 0.0);                 // 512–1023
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
    for (const SimdTarget& target : detail::simdTargets()) {
      SCOPED_TRACE(target.name);
      detail::useSimdTarget(target.bits);
      detail::countHiddenBlocks(true);
      const Rendered after = renderScene(oneMeshScene(view), camera, 320, 240, options);
      const detail::HiddenBlockCounts counts = detail::hiddenBlockCounts();
      EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u);
      EXPECT_EQ(before.stats.fragmentsWritten, after.stats.fragmentsWritten);
      EXPECT_EQ(counts.hidden, 1u) << "of " << counts.blocks;  // the far fan alone
    }
  }
}

}  // namespace
}  // namespace facet::testing
