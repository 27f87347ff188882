// The same bytes for any thread count, on a real mesh.

#include <cstddef>

#include <gtest/gtest.h>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "Resolve.h"

namespace facet::testing {
namespace {

class Determinism : public ::testing::TestWithParam<Visibility> {};

// The bunny lit by a point and a directional light, specular, cut by the near plane (so the
// clipper runs too), rendered at width × height on 1, 2 and 8 threads: the same bytes (and
// more than `leastCovered` pixels covered).
void expectTheSameBytesOnOneTwoAndEightThreads(Visibility visibility, int width, int height,
                                               std::size_t leastCovered) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  ASSERT_EQ(bunny.polygonCount(), 69451u);
  LightSet lights;
  lights.lights.push_back(
      PointLight{{0.3, 0.4, 0.5}, Color(1.0f, 0.6f, 0.3f), 1.5, QuadraticAttenuation{1, 0, 1}});
  lights.lights.push_back(DirectionalLight{{-1, -1, -1}, Color(0.3f, 0.4f, 1.0f), 0.8});
  Material material;
  material.specular = 0.4;
  material.specularPower = 20.0;
  const Scene scene = oneMeshScene(bunny.view(), material, lights);
  Camera camera = fitCamera(bunny, {0.2, -0.3, -1.0});
  camera.nearClip *= 1.3;

  RenderOptions options;
  options.visibility = visibility;
  options.threads = 1;
  const Rendered one = renderScene(scene, camera, width, height, options);
  EXPECT_GT(one.stats.pixelsCovered, leastCovered);
  for (int threads : {2, 8}) {
    options.threads = threads;
    const Rendered many = renderScene(scene, camera, width, height, options);
    EXPECT_EQ(differingPixels(one.framebuffer, many.framebuffer), 0u) << threads << " threads";
    EXPECT_EQ(one.stats.trianglesBinned, many.stats.trianglesBinned);
    EXPECT_EQ(one.stats.fragmentsWritten, many.stats.fragmentsWritten);
  }
}

TEST_P(Determinism, BunnyRendersTheSameBytesOnOneTwoAndEightThreads) {
  expectTheSameBytesOnOneTwoAndEightThreads(GetParam(), 640, 480, 20000);
}

// Colors of 4 MiB or more are streamed to memory (Resolve.h, kStreamedColorBytes), in rows
// whose length is no multiple of a vector's pixels here.
TEST_P(Determinism, StreamedColorPlanesAreTheSameBytesOnOneTwoAndEightThreads) {
  static_assert(std::size_t{1031} * 1030 * 4 >= detail::kStreamedColorBytes);
  expectTheSameBytesOnOneTwoAndEightThreads(GetParam(), 1031, 1030, 70000);
}

INSTANTIATE_TEST_SUITE_P(BothVisibilityModes, Determinism,
                         ::testing::Values(Visibility::ZBuffer, Visibility::PainterSort));

}  // namespace
}  // namespace facet::testing
