// The summary-only estimate (QualityRenderer.cpp, estimateSummary: flat, one sample per pixel,
// no ErrorEstimate image): its bound per block of polygons (FlatErrorBoundOfMesh.h) is at least
// every polygon's bound and reaches it where a polygon meets the worst case; its predicted RMSE and
// maximum are at least the per-pixel estimate's; and it is the same numbers for any thread
// count and on every instruction set.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../support/EveryTargetTest.h"
#include "../support/ReferenceScenes.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "EstimateRows.h"
#include "FlatErrorBoundBatch.h"
#include "FlatErrorBoundOfMesh.h"
#include "SetupBatch.h"
#include "facet/FlatErrorBound.h"
#include "facet/QualityRenderer.h"

namespace facet::testing {
namespace {

struct LightCase {
  std::string name;
  LightSet lights;
  Material material;
};

std::vector<LightCase> lightCases() {
  std::vector<LightCase> cases;
  Material matte;
  matte.diffuse = 0.9;
  Material lerp = matte;
  lerp.diffuseModel = DiffuseModel::Lerp;
  LightSet directional, point, attenuated, both;
  directional.lights.push_back(DirectionalLight{{-1, -1, -2}, Color(0.8f)});
  point.lights.push_back(PointLight{{0.5, 0.2, 6}, Color(1.0f), 1.0, NoAttenuation{}});
  attenuated.lights.push_back(
      PointLight{{2, 1, 3}, Color(0.9f), 1.0, QuadraticAttenuation{1.0, 0.2, 0.05}});
  both = twoLights();
  cases.push_back({"directional", directional, matte});
  cases.push_back({"point", point, matte});
  cases.push_back({"attenuated", attenuated, matte});
  LightSet constant;  // vtkLight's default: a quadratic attenuation of constant term only
  constant.lights.push_back(
      PointLight{{0.5, 0.2, 6}, Color(1.0f), 1.0, QuadraticAttenuation{2.0, 0.0, 0.0}});
  cases.push_back({"constant", constant, matte});
  cases.push_back({"two lights", both, matte});
  cases.push_back({"two lights, lerp", both, lerp});
  return cases;
}

// A unit vector at angle `angle` from `axis`.
glm::dvec3 turnedFrom(const glm::dvec3& axis, double angle, std::mt19937& random) {
  std::normal_distribution<double> normal;
  glm::dvec3 side;
  do {
    side = glm::cross(axis, glm::dvec3(normal(random), normal(random), normal(random)));
  } while (glm::length(side) < 1e-3);
  return std::cos(angle) * axis + std::sin(angle) * glm::normalize(side);
}

// Every polygon within the extent (center in the box, radius and spread at most the largest)
// has its bound — the double one and the fused estimate's float lanes — at most the block's;
// polygons placed at the worst case (the light 90° from the normal, the center nearest the
// light) reach it, to 1 part in 1000 and 0.01 where the light arrives unattenuated: a block
// bound made smaller by that much fails.
TEST(SummaryEstimate, TheBlockBoundIsAtLeastEveryPolygonsAndReachedAtTheWorstCase) {
  std::mt19937 random(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Camera camera{.position = {0.3, -0.2, 8.0}, .focalPoint = {0, 0, 0}};
  for (const LightCase& c : lightCases()) {
    const PreparedMaterial material(c.material);
    const auto lighting = detail::batchLighting(c.lights, camera, true);
    const auto batchMaterial = detail::batchMaterial(material);
    ASSERT_TRUE(lighting && batchMaterial) << c.name;
    const FlatErrorBound exact(c.lights, camera, true);
    for (const double spread : {0.0, 0.01, 0.2, 0.7}) {
      detail::MeshBoundExtent extent;
      extent.radius = 0.05f;
      extent.sinNormalSpread = static_cast<float>(std::sin(spread));
      extent.low = glm::dvec3(-1.0);
      extent.high = glm::dvec3(1.0);
      const glm::dvec3 surface(0.9, 0.7, 0.5);
      const std::optional<double> largest =
          detail::largestFlatBound(c.lights, material, surface, extent);
      ASSERT_TRUE(largest.has_value());
      const std::string name = c.name + ", spread " + std::to_string(spread);
      double worst = 0.0;
      const auto check = [&](const glm::dvec3& center, const glm::dvec3& normal, double radius,
                             double sine, const Color& cd) {
        PolygonShape shape;
        shape.center = center;
        shape.normal = normal;
        shape.radius = radius;
        shape.cosNormalSpread = std::sqrt(1.0 - sine * sine);
        const double b = exact.bound(shape, material, cd);
        const float lanes =
            detail::boundOneColumn(*lighting, *batchMaterial, center, normal, cd,
                                   static_cast<float>(radius), static_cast<float>(sine));
        EXPECT_LE(b, *largest) << name;
        if (!std::isnan(lanes)) {
          EXPECT_LE(lanes, *largest) << name;
        }
        worst = std::max(worst, b);
      };
      for (int i = 0; i < 2000; ++i) {  // anywhere within the extent
        const glm::dvec3 center(2 * unit(random) - 1, 2 * unit(random) - 1, 2 * unit(random) - 1);
        std::normal_distribution<double> normal;
        const glm::dvec3 n =
            glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
        const Color cd(static_cast<float>(unit(random) * 0.9),
                       static_cast<float>(unit(random) * 0.7),
                       static_cast<float>(unit(random) * 0.5));
        check(center, glm::dvec3(glm::vec3(n)), unit(random) * 0.05,
              unit(random) * std::sin(spread), cd);
      }
      // The worst case: per light, the center at the box's point nearest it and the normal 90°
      // from it (so the flat diffuse factor is 0 and a corner normal turned by the spread
      // meets the light's cone).
      for (const Light& light : c.lights.lights) {
        glm::dvec3 center(0.0), toLight(0.0, 0.0, 1.0);
        if (const auto* p = std::get_if<PointLight>(&light)) {
          center = glm::clamp(p->position, extent.low, extent.high);
          toLight = glm::normalize(p->position - center);
        } else if (const auto* d = std::get_if<DirectionalLight>(&light)) {
          toLight = -glm::normalize(d->direction);
        }
        for (int i = 0; i < 50; ++i)
          check(center, glm::dvec3(glm::vec3(turnedFrom(toLight, M_PI / 2, random))), 0.05,
                std::sin(spread), Color(0.9f, 0.7f, 0.5f));
      }
      std::printf("%-34s block bound %8.4f, largest polygon bound %8.4f\n", name.c_str(), *largest,
                  worst);
      // The margin for the float lanes' rounding (2·2^-16 of the light's reach) aside.
      if (c.name == "directional" || c.name == "point" || c.name == "constant") {
        EXPECT_GE(worst, *largest * (1.0 - 1e-3) - 0.01) << name << ": loose at its worst";
      }
    }
  }
}

TEST(SummaryEstimate, NotTakenForSpotLightsOrSpecularMaterials) {
  detail::MeshBoundExtent extent;
  extent.low = glm::dvec3(-1.0);
  extent.high = glm::dvec3(1.0);
  LightSet spot;
  spot.lights.push_back(SpotLight{});
  EXPECT_FALSE(
      detail::largestFlatBound(spot, PreparedMaterial(Material{}), glm::dvec3(1.0), extent));
  EXPECT_FALSE(detail::largestFlatBound(twoLights(), PreparedMaterial(shinyMaterial()),
                                        glm::dvec3(1.0), extent));
}

// A scene's estimate both ways on one renderer: with the image (the per-pixel estimate's
// summary) and without (the summary-only estimate).
struct Both {
  QualityStats exact, fast;
};
Both estimateBoth(const Scene& scene, const Camera& camera, int threads = 2) {
  const QualitySettings image{.estimateError = true};
  QualitySettings summary = image;
  summary.errorEstimateImage = false;
  Renderer renderer;
  renderer.setThreadCount(threads);
  QualityRenderer quality(renderer);
  Framebuffer framebuffer(120, 90);
  Both both;
  both.exact = quality.render(scene, {}, camera, framebuffer, image);
  renderer.forgetPreviousFrame();
  both.fast = quality.render(scene, {}, camera, framebuffer, summary);
  EXPECT_TRUE(quality.errorEstimate().empty());
  return both;
}

void expectAtLeastThePerPixelEstimate(const std::string& name, const Both& both) {
  std::printf("%-34s per pixel: RMSE %6.2f max %6.2f; summary: RMSE %6.2f max %6.2f\n",
              name.c_str(), both.exact.predictedRmse, both.exact.predictedMaxError,
              both.fast.predictedRmse, both.fast.predictedMaxError);
  EXPECT_GT(both.exact.predictedMaxError, 0.5) << name;
  EXPECT_GE(both.fast.predictedMaxError, both.exact.predictedMaxError) << name;
  EXPECT_GE(both.fast.predictedRmse, both.exact.predictedRmse) << name;
  EXPECT_LE(both.fast.predictedMaxError, 255.0) << name;
  EXPECT_LE(both.fast.predictedRmse, both.fast.predictedMaxError) << name;
}

// The summary against the per-pixel estimate (the ErrorEstimate image's, the summary it gives)
// on spheres from 8 to 128 segments under each light: its maximum and RMSE are at least
// those (how much more is printed).
TEST(SummaryEstimate, AtLeastThePerPixelEstimate) {
  const Camera camera = fitCamera(makeUvSphere(8, 5), {0.2, -0.3, -1});
  for (const LightCase& c : lightCases()) {
    for (const int segments : {8, 32, 128}) {
      const Mesh sphere = makeUvSphere(segments, segments / 2 + 1);
      Scene scene = oneMeshScene(sphere.view(), c.material, c.lights);
      scene.meshes[0].mesh.version = 1;
      expectAtLeastThePerPixelEstimate(c.name + ", " + std::to_string(segments) + " segments",
                                       estimateBoth(scene, camera));
    }
  }
}

// Polygon colors (the summary takes Cd ≤ 1 for them, and the colour part sees their
// differences), and a specular material (not taken: the same numbers as the per-pixel one).
TEST(SummaryEstimate, AtLeastThePerPixelEstimateWithPolygonColorsAndSpecular) {
  Mesh sphere = makeUvSphere(32, 17);
  for (std::size_t p = 0; p < sphere.polygonCount(); ++p)
    sphere.polygonColors.push_back(
        Rgba8{static_cast<std::uint8_t>(p * 37), 200, static_cast<std::uint8_t>(p * 11), 255});
  Material matte;
  matte.diffuse = 0.9;
  const Camera camera = fitCamera(sphere, {0.2, -0.3, -1});
  expectAtLeastThePerPixelEstimate(
      "polygon colors", estimateBoth(oneMeshScene(sphere.view(), matte, twoLights()), camera));
  sphere.polygonColors.clear();
  const Both shiny =
      estimateBoth(oneMeshScene(sphere.view(), shinyMaterial(), twoLights()), camera);
  EXPECT_EQ(shiny.fast.predictedRmse, shiny.exact.predictedRmse);
  EXPECT_EQ(shiny.fast.predictedMaxError, shiny.exact.predictedMaxError);
}

class SummaryEstimateTargets : public EveryTargetTest {};

// The same predicted RMSE and maximum on 1, 2 and 8 threads and every instruction set.
TEST_F(SummaryEstimateTargets, TheSameNumbersOnEveryThreadCountAndInstructionSet) {
  const Mesh sphere = makeUvSphere(48, 25);
  Material matte;
  matte.diffuse = 0.9;
  const Scene scene = oneMeshScene(sphere.view(), matte, twoLights());
  const Camera camera = fitCamera(sphere, {0.2, -0.3, -1});
  std::optional<QualityStats> first;
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    detail::useSimdTarget(target.bits);
    for (const int threads : {1, 2, 8}) {
      const QualityStats fast = estimateBoth(scene, camera, threads).fast;
      if (!first) first = fast;
      EXPECT_GT(fast.predictedRmse, 0.0);
      EXPECT_EQ(fast.predictedRmse, first->predictedRmse) << target.name << ", " << threads;
      EXPECT_EQ(fast.predictedMaxError, first->predictedMaxError) << target.name << ", " << threads;
    }
  }
}

// The covered span of a row (EstimateRows.h: coveredSpan, which skips background four vectors
// at a time) is its definition on every instruction set: rows of every width to 300 with
// background runs of random length at either end and inside, and rows of background only.
TEST_F(SummaryEstimateTargets, CoveredSpanIsItsDefinitionOnEveryInstructionSet) {
  std::mt19937 random(7);
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    detail::useSimdTarget(target.bits);
    for (int width = 1; width <= 300; ++width) {
      for (int trial = 0; trial < 4; ++trial) {
        std::vector<std::int32_t> ids(static_cast<std::size_t>(width), -1);
        const int a = static_cast<int>(random() % (width + 1)),
                  b = static_cast<int>(random() % (width + 1));
        for (int x = std::min(a, b); x < std::max(a, b); ++x)
          ids[x] = random() % 3 == 0 ? -1 : static_cast<std::int32_t>(random() % 1000);
        int first = 0, last = width;
        while (first < width && ids[first] < 0)
          ++first;
        while (last > first && ids[last - 1] < 0)
          --last;
        const std::array<int, 2> span = detail::coveredSpan(ids.data(), width);
        EXPECT_EQ(span[0], first) << target.name << ", width " << width;
        EXPECT_EQ(span[1], last) << target.name << ", width " << width;
      }
    }
  }
}

}  // namespace
}  // namespace facet::testing
