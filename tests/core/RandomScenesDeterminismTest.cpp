// Random scenes rendered frame after frame by one Renderer (the camera turning, so the plan
// and the set-up's chunks by work change between frames): the same bytes on 1, 2 and 8
// threads, on every SIMD target, and whether the every-face frames take one pass or two (the
// plan's choice, from estimateCoveredPixels before a first frame, changes only the work).

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "../support/SameRender.h"
#include "../support/Sanitizers.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "Raster.h"
#include "SetupBatch.h"
#include "facet/Renderer.h"

namespace facet::testing {
namespace {

struct RandomScene {
  std::vector<Mesh> meshes;
  Scene scene;
  std::vector<Camera> cameras;  // one a frame
  int width = 0, height = 0;
};

// A closed sphere (its back faces skipped), a soup of small triangles in a cube, facing
// either way (every face drawn), and a few huge ones, some through the eye's plane; the
// camera orbiting, perspective or parallel, the image narrower than a tile at times.
RandomScene makeRandomScene(int seed) {
  std::mt19937 random(static_cast<unsigned>(seed));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  RandomScene s;
  s.meshes.push_back(
      makeUvSphere(8 + static_cast<int>(random() % 80), 6 + static_cast<int>(random() % 60), 0.8));
  Mesh soup;
  const int triangles = 1000 + static_cast<int>(random() % 30000);
  for (int t = 0; t < triangles; ++t) {
    const glm::dvec3 center(unit(random), unit(random), unit(random));
    const double size = 0.02 + 0.2 * std::abs(unit(random));
    const std::int64_t a = soup.addPoint(center);
    const std::int64_t b =
        soup.addPoint(center + size * glm::dvec3(unit(random), unit(random), unit(random)));
    const std::int64_t c =
        soup.addPoint(center + size * glm::dvec3(unit(random), unit(random), unit(random)));
    soup.addPolygon({a, b, c});
  }
  for (int t = 0; t < 4; ++t) {  // huge: across the view, some through the near plane
    const std::int64_t a = soup.addPoint(50.0 * glm::dvec3(unit(random), unit(random), 0.1));
    const std::int64_t b = soup.addPoint(50.0 * glm::dvec3(unit(random), unit(random), 0.1));
    const std::int64_t c = soup.addPoint(glm::dvec3(unit(random), unit(random), unit(random)));
    soup.addPolygon({a, b, c});
  }
  s.meshes.push_back(std::move(soup));
  for (std::size_t m = 0; m < s.meshes.size(); ++m) {
    Material material;
    material.color = Color(0.3f + 0.2f * m, 0.5f, 0.9f - 0.3f * m);
    material.specular = m == 0 ? 0.4 : 0.0;
    material.specularPower = 12.0;
    s.scene.meshes.push_back({s.meshes[m].view(), material});
  }
  s.scene.lights.lights.push_back(DirectionalLight{{-1, -0.5, -1}, Color(1.0f, 0.9f, 0.8f), 1.0});
  s.width = 20 + static_cast<int>(random() % 200);
  s.height = 20 + static_cast<int>(random() % 160);
  const bool parallel = random() % 3 == 0;
  const double distance = 1.2 + 3.0 * std::abs(unit(random));  // at times inside the soup
  for (int frame = 0; frame < 4; ++frame) {
    const double angle = 0.5 * frame + unit(random);
    Camera camera;
    camera.position = distance * glm::dvec3(std::sin(angle), 0.3 * unit(random), std::cos(angle));
    camera.focalPoint = {0.0, 0.0, 0.0};
    camera.parallelProjection = parallel;
    camera.parallelScale = 1.5;
    camera.nearClip = 0.05;
    camera.farClip = 20.0;
    s.cameras.push_back(camera);
  }
  return s;
}

// Every frame of `s` by one Renderer on `threads` threads.
std::vector<Rendered> renderFrames(const RandomScene& s, int threads) {
  Renderer renderer;
  renderer.setThreadCount(threads);
  std::vector<Rendered> frames;
  for (const Camera& camera : s.cameras) {
    Rendered rendered{Framebuffer(s.width, s.height), {}};
    rendered.stats = renderer.render(s.scene, camera, rendered.framebuffer);
    frames.push_back(std::move(rendered));
  }
  return frames;
}

// The same frames with the soup edited before each (its points turned and shrunk, under a new
// version: its blocks' boxes measured again), the sphere versioned and kept.
std::vector<Rendered> renderEditedFrames(const RandomScene& s, int threads) {
  Renderer renderer;
  renderer.setThreadCount(threads);
  Mesh soup = s.meshes[1];
  std::vector<Rendered> frames;
  for (std::size_t f = 0; f < s.cameras.size(); ++f) {
    for (glm::dvec3& p : soup.points)
      p = 0.95 * glm::dvec3(p.y, p.z, p.x);
    Scene scene = s.scene;
    scene.meshes[0].mesh.version = 1;
    scene.meshes[1].mesh = soup.view();
    scene.meshes[1].mesh.version = f + 1;
    Rendered rendered{Framebuffer(s.width, s.height), {}};
    rendered.stats = renderer.render(scene, s.cameras[f], rendered.framebuffer);
    frames.push_back(std::move(rendered));
  }
  return frames;
}

void expectSameFrames(const std::vector<Rendered>& expected, const std::vector<Rendered>& got) {
  ASSERT_EQ(expected.size(), got.size());
  for (std::size_t f = 0; f < expected.size(); ++f) {
    SCOPED_TRACE(::testing::Message() << "frame " << f);
    expectSameRender(expected[f], got[f]);
  }
}

class RandomScenes : public EveryTargetTest {
 protected:
  void TearDown() override {
    detail::planTwoPassFrames();
    EveryTargetTest::TearDown();
  }
};

TEST_F(RandomScenes, SameBytesOnOneTwoAndEightThreadsFrameAfterFrame) {
  for (int seed = 1; seed <= trialsToRun(8); ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const RandomScene s = makeRandomScene(seed);
    const std::vector<Rendered> one = renderFrames(s, 1);
    std::size_t covered = 0;
    for (const Rendered& frame : one)
      covered += frame.stats.pixelsCovered;
    EXPECT_GT(covered, 0u);
    for (int threads : threadCountsToRun({2, 8})) {
      SCOPED_TRACE(::testing::Message() << threads << " threads");
      expectSameFrames(one, renderFrames(s, threads));
    }
  }
}

TEST_F(RandomScenes, EditedVersionsRenderTheSameBytesOnOneTwoAndEightThreads) {
  for (int seed = 31; seed < 31 + trialsToRun(5); ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const RandomScene s = makeRandomScene(seed);
    const std::vector<Rendered> one = renderEditedFrames(s, 1);
    for (int threads : threadCountsToRun({2, 8})) {
      SCOPED_TRACE(::testing::Message() << threads << " threads");
      expectSameFrames(one, renderEditedFrames(s, threads));
    }
  }
}

TEST_F(RandomScenes, SameBytesInOnePassOrTwo) {
  std::size_t plannedOnePass = 0, plannedTwoPasses = 0;
  for (int seed = 11; seed <= 18; ++seed) {  // whole under a sanitizer: both sides of the rule
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const RandomScene s = makeRandomScene(seed);
    const std::vector<Rendered> planned = renderFrames(s, 2);
    for (const Rendered& frame : planned)
      ++(frame.stats.plan.twoPassFrame ? plannedTwoPasses : plannedOnePass);
    for (bool twoPasses : {false, true}) {
      SCOPED_TRACE(twoPasses ? "two passes" : "one pass");
      detail::enableTwoPassFrames(twoPasses);
      const std::vector<Rendered> forced = renderFrames(s, 2);
      ASSERT_EQ(forced.size(), planned.size());
      for (std::size_t f = 0; f < forced.size(); ++f) {
        EXPECT_EQ(differingPixels(planned[f].framebuffer, forced[f].framebuffer), 0u)
            << "frame " << f;
      }
    }
    detail::planTwoPassFrames();
  }
  // The scenes reach both sides of the plan's rule (and the coarse depth's one pass).
  EXPECT_GT(plannedOnePass, 0u);
  EXPECT_GT(plannedTwoPasses, 0u);
}

TEST_F(RandomScenes, SameBytesOnEverySimdTarget) {
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  ASSERT_FALSE(targets.empty());
  for (int seed = 21; seed < 21 + trialsToRun(5); ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const RandomScene s = makeRandomScene(seed);
    detail::useSimdTarget(targets.front().bits);
    const std::vector<Rendered> first = renderFrames(s, 2);
    for (std::size_t t = 1; t < targets.size(); ++t) {
      SCOPED_TRACE(targets[t].name);
      detail::useSimdTarget(targets[t].bits);
      expectSameFrames(first, renderFrames(s, 2));
    }
  }
}

}  // namespace
}  // namespace facet::testing
