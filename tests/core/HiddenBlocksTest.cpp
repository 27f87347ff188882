// The whole-block reject of HiddenBlocks.h (a two-pass frame's back faces dropped block by
// block): the same bytes as one pass, blocks hidden, and never a block whose nearest point
// pokes through the front faces by a few float steps of its key.

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

class HiddenBlocks : public EveryTargetTest {
 protected:
  void TearDown() override {
    detail::planTwoPassFrames();
    detail::enableHiddenBlocks(true);
    detail::countHiddenBlocks(false);
    EveryTargetTest::TearDown();
  }
  static std::vector<SimdTarget> targets() { return detail::simdTargets(); }
  static void use(const SimdTarget& target) { detail::useSimdTarget(target.bits); }
  static RenderOptions optionsWith(int threads) {
    RenderOptions options;
    options.visibility = Visibility::ZBuffer;
    options.threads = threads;
    return options;
  }
};

// A sphere with a cap cut out where the camera sees it at an angle (x above `cut`): back faces show
// through the hole, the others hide behind the front faces.
Mesh sphereWithHole(int theta, double cut) {
  const Mesh sphere = makeUvSphere(theta, theta + 2);
  Mesh holed;
  holed.points = sphere.points;
  for (std::size_t p = 0; p + 1 < sphere.offsets.size(); ++p) {
    const auto begin = static_cast<std::ptrdiff_t>(sphere.offsets[p]);
    const auto end = static_cast<std::ptrdiff_t>(sphere.offsets[p + 1]);
    if (sphere.points[static_cast<std::size_t>(sphere.connectivity[begin])].x > cut) continue;
    holed.connectivity.insert(holed.connectivity.end(), sphere.connectivity.begin() + begin,
                              sphere.connectivity.begin() + end);
    holed.offsets.push_back(static_cast<std::int64_t>(holed.connectivity.size()));
  }
  return holed;
}

TEST_F(HiddenBlocks, VersionedSpheresRenderAsOnePassOnEveryTargetAndThreadCount) {
  const Mesh sphere = sphereWithHole(400, 0.8);
  MeshView view = sphere.view();
  view.version = 1;  // measured: its blocks' boxes
  for (const glm::dvec3 direction : {glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(-0.6, -0.2, -1.0)}) {
    const Camera camera = fitCamera(sphere, direction);
    for (int threads : {1, 2, 8}) {
      SCOPED_TRACE(std::to_string(threads) + " threads");
      const RenderOptions options = optionsWith(threads);
      detail::enableTwoPassFrames(false);
      detail::enableHiddenBlocks(false);
      const Rendered before = renderScene(oneMeshScene(view), camera, 640, 480, options);
      ASSERT_GT(before.stats.pixelsCovered, 10000u);
      detail::enableTwoPassFrames(true);
      detail::enableHiddenBlocks(true);
      for (const SimdTarget& target : targets()) {
        SCOPED_TRACE(target.name);
        use(target);
        detail::countHiddenBlocks(true);
        const Rendered after = renderScene(oneMeshScene(view), camera, 640, 480, options);
        const detail::HiddenBlockCounts counts = detail::hiddenBlockCounts();
        EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u);
        EXPECT_EQ(before.stats.fragmentsWritten, after.stats.fragmentsWritten);
        EXPECT_EQ(before.stats.pixelsCovered, after.stats.pixelsCovered);
        EXPECT_GT(counts.hidden, counts.blocks / 20) << counts.hidden << " of " << counts.blocks;
        EXPECT_LT(counts.hidden, counts.blocks);
        // Most hidden blocks are ones the normal cones prove back-facing: the blocks a proven
        // reject (HiddenBlocks.h, step 4) would be limited to.
        EXPECT_GT(counts.coneCertainHidden, counts.hidden / 2)
            << counts.coneCertainHidden << " of " << counts.hidden;
      }
    }
  }
}

// A fan of 256 triangles around (0, 0, z), radius 0.3, as one back-face block: wound clockwise
// seen from +Z (the eye's side), so back faces; `rim` is the ring's z.
void addBackFan(Mesh& mesh, double apexZ, double rimZ) {
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

// THE MARGIN TEST (HiddenBlocks.h, steps 3–5): behind a front square at distance 3, one fan far
// behind it (hidden: dropped) and one flat tent whose apex pokes 1.5e-6 (5e-7 of the distance,
// about 8 float steps of its key) through the square: its back faces show around the apex, so
// its block must never be dropped. Checked to fail when the reject's comparison is loosened by
// 1e-6 of the bound.
TEST_F(HiddenBlocks, ApexThroughTheFrontFaceIsNeverDropped) {
  Mesh mesh;
  addBackFan(mesh, -3.5, -3.5);               // polygons 0–255: far behind the square
  addBackFan(mesh, -3.0 + 1.5e-6, -3.00002);  // 256–511: the apex through it
  constexpr int kCells = 16;                  // 512–1023: the square, front faces
  const std::int64_t corner = static_cast<std::int64_t>(mesh.points.size());
  for (int y = 0; y <= kCells; ++y) {
    for (int x = 0; x <= kCells; ++x)
      mesh.addPoint({-0.6 + 1.2 * x / kCells, -0.6 + 1.2 * y / kCells, -3.0});
  }
  for (int y = 0; y < kCells; ++y) {
    for (int x = 0; x < kCells; ++x) {
      const std::int64_t p = corner + y * (kCells + 1) + x;
      mesh.addPolygon({p, p + 1, p + kCells + 2});
      mesh.addPolygon({p, p + kCells + 2, p + kCells + 1});
    }
  }
  MeshView view = mesh.view();
  view.version = 1;  // measured: its blocks' boxes
  Camera camera;
  camera.position = {0.0, 0.0, 0.0};
  camera.focalPoint = {0.0, 0.0, -1.0};
  for (int threads : {1, 2}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    const RenderOptions options = optionsWith(threads);
    detail::enableTwoPassFrames(false);
    const Rendered before = renderScene(oneMeshScene(view), camera, 320, 240, options);
    std::size_t apexPixels = 0;
    for (std::int32_t id : before.framebuffer.polygonId())
      apexPixels += id >= 256 && id < 512;
    ASSERT_GT(apexPixels, 4u);  // the tent wins pixels around its apex
    detail::enableTwoPassFrames(true);
    detail::countHiddenBlocks(true);
    const Rendered after = renderScene(oneMeshScene(view), camera, 320, 240, options);
    const detail::HiddenBlockCounts counts = detail::hiddenBlockCounts();
    EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u);
    EXPECT_EQ(before.stats.fragmentsWritten, after.stats.fragmentsWritten);
    EXPECT_EQ(counts.blocks, 2u);  // the two fans
    EXPECT_EQ(counts.hidden, 1u);  // the far one
    EXPECT_EQ(counts.hiddenPolygons, 256u);
    EXPECT_TRUE(after.stats.plan.twoPassFrame);
    EXPECT_EQ(after.stats.plan.polygonsHiddenBehindFront, 256u);
  }
}

}  // namespace
}  // namespace facet::testing
