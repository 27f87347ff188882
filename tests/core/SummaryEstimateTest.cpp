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
#include "facet/PolygonNormal.h"
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

// One of `values`, drawn from `random`.
template <class Random, class... Values>
auto pickOne(Random& random, Values... values) {
  const std::array options{values...};
  return options[random() % options.size()];
}

// A point light's attenuation for a scene `size` wide: none, of constant factor, steep
// (a0 down to 1e-6, a1 and a2 to 1/size and 1/size²) or by a falloff distance from a hundredth
// of the size to a hundred times it.
template <class Random>
Attenuation randomAttenuation(Random& random, double size) {
  const auto pick = [&](auto... values) { return pickOne(random, values...); };
  switch (random() % 4) {
    case 0:
      return NoAttenuation{};
    case 1:
      return QuadraticAttenuation{pick(0.5, 2.0), 0.0, 0.0};
    case 2:
      return QuadraticAttenuation{pick(1e-6, 1e-3, 1.0), pick(0.0, 1.0 / size),
                                  pick(0.0, 1.0 / (size * size))};
    default:
      return FalloffDistanceAttenuation{pick(0.01, 0.3, 0.5, 2.0, 100.0) * size};
  }
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
      detail::BlockExtent extent;
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

// The same at the edges of the derivation, on random blocks of triangles: boxes from 1e-3
// to 100 wide at 0, 1e6 and 1e9 from the origin; point lights inside the box, on a polygon,
// just outside and far, unattenuated, of constant factor, steeply attenuated (a0 down to
// 1e-6) and by a falloff distance; directional lights; the eye inside the box; one- and
// two-sided; Lambert and Lerp; spreads to 90°. Each polygon's bound — the double one at its
// center and at that center rounded to float (the shade's sums), and the float lanes' — is
// at most the block's, as the resolve reads them (EstimateRows.h: fixedBoundOf).
TEST(SummaryEstimate, TheBlockBoundHoldsAtTheEdgesOfItsDerivation) {
  std::mt19937 random(2111);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto pick = [&](auto... values) { return pickOne(random, values...); };
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double offset = pick(0.0, 1e6, 1e9), size = pick(1e-3, 1.0, 100.0);
    const glm::dvec3 origin = offset * glm::dvec3(unit(random), -unit(random), unit(random));
    const auto inBox = [&] {
      return origin + size * glm::dvec3(unit(random), unit(random), unit(random));
    };
    // Triangles in the box, some tiny, some as wide as the box.
    struct Triangle {
      std::array<glm::dvec3, 3> corners;
      glm::dvec3 center, normal;
      float radius, sine;
    };
    std::vector<Triangle> triangles;
    detail::BlockExtent extent;
    for (int t = 0; t < 6; ++t) {
      Triangle triangle;
      const glm::dvec3 a = inBox();
      const double scale = size * pick(1e-4, 0.05, 1.0);
      for (glm::dvec3& corner : triangle.corners) {
        corner = glm::clamp(a + scale * glm::dvec3(unit(random), unit(random), unit(random)),
                            origin, origin + size);
      }
      const std::optional<glm::dvec3> normal =
          triangleNormal(triangle.corners[0], triangle.corners[1], triangle.corners[2]);
      if (!normal) continue;
      triangle.normal = glm::dvec3(glm::vec3(*normal));
      triangle.center = (triangle.corners[0] + triangle.corners[1] + triangle.corners[2]) / 3.0;
      double radius = 0.0;
      for (const glm::dvec3& corner : triangle.corners)
        radius = std::max(radius, glm::length(corner - triangle.center));
      triangle.radius = detail::roundedUp(radius);
      triangle.sine = pick(0.0f, 1e-6f, 0.3f, 0.99f, 2.0f) * static_cast<float>(unit(random));
      for (const glm::dvec3& corner : triangle.corners)
        extent.add(triangle.radius, triangle.sine, corner);
      triangles.push_back(triangle);
    }
    if (triangles.empty()) continue;
    LightSet lights;
    const int count = 1 + static_cast<int>(random() % 3);
    for (int l = 0; l < count; ++l) {
      const Triangle& near = triangles[random() % triangles.size()];
      glm::dvec3 position;
      switch (random() % 5) {
        case 0:
          position = inBox();
          break;
        case 1:
          position = near.center;
          break;  // on the polygon
        case 2:
          position = near.corners[0] + 1e-3 * size * near.normal;
          break;
        case 3:
          position = origin - size * glm::dvec3(unit(random), 0.5, 2.0);
          break;
        default:
          position = origin + 1e3 * size * glm::dvec3(unit(random), -1, 0.3);
          break;
      }
      Attenuation attenuation = NoAttenuation{};
      switch (random() % 5) {
        case 0:
          break;
        case 1:
          attenuation = QuadraticAttenuation{2.0, 0.0, 0.0};
          break;
        case 2:
          attenuation = QuadraticAttenuation{pick(1e-6, 1e-2, 1.0), pick(0.0, 0.5, 3.0),
                                             pick(0.0, 1e-4, 1.0, 100.0)};
          break;
        case 3:
          attenuation = FalloffDistanceAttenuation{pick(1e-3, 0.1, 10.0) * size};
          break;
        default:
          lights.lights.push_back(DirectionalLight{
              glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, -unit(random) - 0.01), Color(0.9f),
              1.0});
          continue;
      }
      lights.lights.push_back(PointLight{position, Color(0.8f, 1.0f, 0.6f), 1.0, attenuation});
    }
    Material material;
    material.diffuse = pick(0.3, 0.9, 1.0);
    if (random() % 2) {
      material.diffuseModel = DiffuseModel::Lerp;
      material.lerpAmbient = pick(0.0, 0.2);
      material.lerpFull = pick(0.5, 1.0);
    }
    const PreparedMaterial prepared(material);
    const bool twoSided = random() % 2 == 0;
    Camera camera{
        .position = random() % 3 == 0 ? inBox() : origin + 5.0 * size * glm::dvec3(0.2, -0.3, 1.0),
        .focalPoint = origin + 0.5 * size};
    const glm::dvec3 surface(0.9, 0.7, 1.0);
    const Color cd(0.9f, 0.7f, 1.0f);
    const std::optional<double> block = detail::largestFlatBound(lights, prepared, surface, extent);
    ASSERT_TRUE(block.has_value());
    const detail::EstimateBound blockFixed = detail::fixedBoundOf(detail::roundedUp(*block));
    const FlatErrorBound exact(lights, camera, twoSided);
    const auto lighting = detail::batchLighting(lights, camera, twoSided);
    const auto batchMaterial = detail::batchMaterial(prepared);
    for (const Triangle& triangle : triangles) {
      for (const glm::dvec3& center : {triangle.center, glm::dvec3(glm::vec3(triangle.center))}) {
        PolygonShape shape;
        shape.center = center;
        shape.normal = triangle.normal;
        shape.radius = triangle.radius;
        shape.cosNormalSpread =
            triangle.sine >= 1.0f
                ? 0.0
                : std::sqrt(1.0 - static_cast<double>(triangle.sine) * triangle.sine);
        const float b = detail::roundedUp(exact.bound(shape, prepared, cd));
        std::string name = "trial " + std::to_string(trial) + ", offset " + std::to_string(offset) +
                           ", size " + std::to_string(size) + ", radius " +
                           std::to_string(triangle.radius) + ", sine " +
                           std::to_string(triangle.sine) + ": block " + std::to_string(*block);
        EXPECT_LE(detail::fixedBoundOf(b), blockFixed) << name << ", double " << b;
        if (lighting && batchMaterial) {
          const float lanes =
              detail::boundOneColumn(*lighting, *batchMaterial, center, triangle.normal, cd,
                                     triangle.radius, triangle.sine);
          if (!std::isnan(lanes)) {
            EXPECT_LE(detail::fixedBoundOf(lanes), blockFixed) << name << ", lanes " << lanes;
          }
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 10000);
}

// Where the block bound is tightest: a one-triangle block, a sliver lying across the light's
// direction in its plane (the box's nearest point as near as the center, the flat diffuse
// factor 0 or nearly, a corner normal turned by the spread toward the light), at 0 to 1e9
// from the origin and 1e-6 to 1e3 wide, the light 1.0001 to 1e6 widths away
// (randomAttenuation's) or directional; Lambert and Lerp. The double bound and the float lanes
// never exceed the block's, as numbers (not only as the resolve's fixed point); the lanes come
// within 2e-5 of it, and at most three quarters of the block's margin for their rounding (2·2^-16
// of each light's reach) is theirs.
TEST(SummaryEstimate, TheBlockBoundHoldsWhereItIsTightest) {
  std::mt19937_64 random(24);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto pick = [&](auto... values) { return pickOne(random, values...); };
  double closest = 0.0, leastSpare = 1.0;
  int checked = 0;
  for (int trial = 0; trial < 60000; ++trial) {
    const double offset = pick(0.0, 1.0, 1e3, 1e6, 1e9), size = pick(1e-6, 1e-3, 1.0, 1e3);
    const glm::dvec3 origin =
        offset * glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5);
    // Long in x, thin in y, flat in z (its box as thin as itself across the light).
    const double thin = size * pick(1e-6, 1e-3, 0.1);
    const std::array<glm::dvec3, 3> corners{
        origin + glm::dvec3(-size, -thin, 0.0), origin + glm::dvec3(size, -thin, 0.0),
        origin + glm::dvec3((unit(random) - 0.5) * size, thin, 0.0)};
    const std::optional<glm::dvec3> normal = triangleNormal(corners[0], corners[1], corners[2]);
    if (!normal) continue;
    const glm::dvec3 center = (corners[0] + corners[1] + corners[2]) / 3.0;
    double exactRadius = 0.0;
    for (const glm::dvec3& corner : corners)
      exactRadius = std::max(exactRadius, glm::length(corner - center));
    const float radius = detail::roundedUp(exactRadius);
    const float sine = pick(0.0f, 1e-5f, 1e-3f, 0.1f, 0.5f, 0.9f, 0.999f) *
                       static_cast<float>(pick(1.0, unit(random)));
    detail::BlockExtent extent;
    for (const glm::dvec3& corner : corners)
      extent.add(radius, sine, corner);
    // The light across the sliver (y), along it (x) or anywhere, in its plane or tilted a little.
    const double tilt = pick(0.0, 1e-6, 1e-3, 0.05, 0.3) * (unit(random) - 0.5);
    glm::dvec3 direction(0.0, std::cos(tilt), std::sin(tilt));
    if (random() % 3 == 1) direction = glm::dvec3(std::cos(tilt), 0.0, std::sin(tilt));
    if (random() % 3 == 2)
      direction = glm::normalize(
          glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5) + 1e-3);
    const Attenuation attenuation = randomAttenuation(random, size);
    LightSet lights;
    if (random() % 6 == 0) {
      lights.lights.push_back(DirectionalLight{-direction, Color(pick(1.0f, 0.8f)), 1.0});
    } else {
      const double distance = size * pick(1.0001, 1.01, 1.5, 3.0, 10.0, 1e3, 1e6);
      lights.lights.push_back(
          PointLight{center + distance * direction, Color(pick(1.0f, 0.8f)), 1.0, attenuation});
    }
    Material material;
    material.diffuse = pick(1.0, 0.9, 0.3);
    if (random() % 3 == 0) {
      material.diffuseModel = DiffuseModel::Lerp;
      material.lerpAmbient = pick(0.0, 0.2, 0.9);
      material.lerpFull = pick(1.0, 0.5, 3.0);
    }
    const PreparedMaterial prepared(material);
    const float gray = pick(1.0f, 0.9f, 0.7f);
    const std::optional<detail::BlockBoundSetup> setup =
        detail::prepareBlockBound(lights, prepared, glm::dvec3(gray));
    ASSERT_TRUE(setup.has_value());
    const double block = detail::largestFlatBound(*setup, extent);
    detail::BlockBoundSetup withoutMargin = *setup;
    withoutMargin.kappa = 0.0;
    const double margin = block - detail::largestFlatBound(withoutMargin, extent);
    const Camera camera{.position = center + glm::dvec3(0.0, 0.0, 5.0 * size + 1.0),
                        .focalPoint = center};
    const bool twoSided = random() % 2 == 0;
    const auto lighting = detail::batchLighting(lights, camera, twoSided);
    const auto batchMaterial = detail::batchMaterial(prepared);
    PolygonShape shape;
    shape.center = center;
    shape.normal = glm::dvec3(glm::vec3(*normal));
    shape.radius = radius;
    shape.cosNormalSpread = sine >= 1.0f ? 0.0 : std::sqrt(1.0 - static_cast<double>(sine) * sine);
    const double exact =
        FlatErrorBound(lights, camera, twoSided).bound(shape, prepared, Color(gray));
    const std::string name = "trial " + std::to_string(trial);
    EXPECT_LE(exact, block) << name;
    if (!lighting || !batchMaterial) continue;  // coefficients beyond the float lanes' range
    const float lanes = detail::boundOneColumn(*lighting, *batchMaterial, center, shape.normal,
                                               Color(gray), radius, sine);
    if (std::isnan(lanes)) continue;
    EXPECT_LE(lanes, block) << name;
    ++checked;
    if (block >= 255.0) continue;  // capped
    closest = std::max(closest, lanes / block);
    if (margin > 0.0) leastSpare = std::min(leastSpare, (block - lanes) / margin);
  }
  std::printf("tightest: the lanes %.7f of the block, %.3f of its margin to spare\n", closest,
              leastSpare);
  EXPECT_GT(checked, 40000);
  EXPECT_GT(closest, 1.0 - 2e-5);
  EXPECT_GT(leastSpare, 0.25);
}

// A point light so far from the polygons (1e200, 1e300 away) that the square of its
// distance overflows: the renderer still lights them from its direction and at its distance
// (Lighting.cpp, towardLight), so each polygon's bound and its block's are at least the
// difference between the flat color and a Phong sample at the center whose normal is turned
// within the spread toward the light — edge-on (the flat color unlit), unattenuated and by a
// falloff distance beyond the light's (all of the light arriving).
TEST(SummaryEstimate, TheBoundsHoldForLightsBeyondTheSquaresRange) {
  const std::array<glm::dvec3, 3> corners{glm::dvec3(-0.5, -0.3, 0.0), glm::dvec3(0.5, -0.3, 0.0),
                                          glm::dvec3(0.0, 0.6, 0.0)};
  const glm::dvec3 center = (corners[0] + corners[1] + corners[2]) / 3.0, normal(0.0, 0.0, 1.0);
  double radius = 0.0;
  for (const glm::dvec3& corner : corners)
    radius = std::max(radius, glm::length(corner - center));
  const double spread = 0.3;
  detail::BlockExtent extent;
  for (const glm::dvec3& corner : corners)
    extent.add(detail::roundedUp(radius), static_cast<float>(std::sin(spread)), corner);
  Material matte;
  matte.diffuse = 0.9;
  const PreparedMaterial material(matte);
  const Color cd(0.8f);
  const Camera camera{.position = {0.3, -0.2, 8.0}, .focalPoint = {0, 0, 0}};
  for (const double distance : {1e200, 1e300}) {
    for (const Attenuation& attenuation :
         {Attenuation{NoAttenuation{}}, Attenuation{FalloffDistanceAttenuation{1.5e300}}}) {
      LightSet lights;
      lights.lights.push_back(
          PointLight{center + glm::dvec3(distance, 0.0, 0.0), Color(1.0f), 1.0, attenuation});
      const Shader shader(lights);
      SurfaceSample sample;
      sample.position = center;
      sample.normal = normal;
      sample.color = cd;
      const Color flat = shader.shade(sample, material);
      const double turn = 0.99 * spread;  // toward the light
      sample.normal = glm::dvec3(std::sin(turn), 0.0, std::cos(turn));
      const Color phong = shader.shade(sample, material);
      const double difference = 255.0 * std::abs(phong.r - flat.r);
      PolygonShape shape;
      shape.center = center;
      shape.normal = normal;
      shape.radius = radius;
      shape.cosNormalSpread = std::cos(spread);
      const double polygon = FlatErrorBound(lights, camera, true).bound(shape, material, cd);
      const std::optional<double> block =
          detail::largestFlatBound(lights, material, glm::dvec3(cd.r), extent);
      ASSERT_TRUE(block.has_value());
      char name[64];
      std::snprintf(name, sizeof name, "distance %g, attenuation %zu", distance,
                    attenuation.index());
      EXPECT_GT(difference, 40.0) << name;  // 255 · 0.9 · 0.8 · sin 0.297 = 53.7
      EXPECT_GE(polygon, difference) << name;
      EXPECT_GE(*block, polygon) << name;
    }
  }
}

// An attenuation so steep (a quadratic coefficient of 1e200) that the square of its
// denominator overflows where the block's steepest slope is found: the light above a
// triangle along its normal, which spans E(d − r) − E(d) ≈ (2r/d)·E(d) of the light's, twice
// what the light's cone gives the block. Tiny numbers (E ~ 1e-200), compared as they are.
TEST(SummaryEstimate, TheBlockBoundHoldsWhereTheAttenuationsSlopeOverflows) {
  const std::array<glm::dvec3, 3> corners{glm::dvec3(-0.5, -0.3, 0.0), glm::dvec3(0.5, -0.3, 0.0),
                                          glm::dvec3(0.0, 0.6, 0.0)};
  const glm::dvec3 center = (corners[0] + corners[1] + corners[2]) / 3.0;
  double radius = 0.0;
  for (const glm::dvec3& corner : corners)
    radius = std::max(radius, glm::length(corner - center));
  detail::BlockExtent extent;
  for (const glm::dvec3& corner : corners)
    extent.add(detail::roundedUp(radius), 0.0f, corner);
  LightSet lights;
  lights.lights.push_back(PointLight{center + glm::dvec3(0.0, 0.0, 4.0), Color(1.0f), 1.0,
                                     QuadraticAttenuation{1.0, 0.0, 1e200}});
  Material matte;
  matte.diffuse = 0.9;
  const PreparedMaterial material(matte);
  PolygonShape shape;
  shape.center = center;
  shape.normal = glm::dvec3(0.0, 0.0, 1.0);
  shape.radius = detail::roundedUp(radius);
  const Camera camera{.position = {0.3, -0.2, 8.0}, .focalPoint = {0, 0, 0}};
  const double polygon = FlatErrorBound(lights, camera, true).bound(shape, material, Color(1.0f));
  const std::optional<double> block =
      detail::largestFlatBound(lights, material, glm::dvec3(1.0), extent);
  ASSERT_TRUE(block.has_value());
  EXPECT_GT(polygon, 0.0);
  EXPECT_GE(*block, polygon);
}

TEST(SummaryEstimate, NotTakenForSpotLightsOrSpecularMaterials) {
  detail::BlockExtent extent;
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

// The estimate's settings for the summary alone (no ErrorEstimate image).
QualitySettings summaryOnly() {
  QualitySettings summary{.estimateError = true};
  summary.errorEstimateImage = false;
  return summary;
}

// A renderer's summary that kept facts from earlier frames (`kept`) is a fresh renderer's, and
// at least the per-pixel estimate.
void expectAFreshRenderersNumbers(const std::string& name, const QualityStats& kept,
                                  const Scene& scene, const Camera& camera) {
  const Both fresh = estimateBoth(scene, camera);
  EXPECT_EQ(kept.predictedRmse, fresh.fast.predictedRmse) << name;
  EXPECT_EQ(kept.predictedMaxError, fresh.fast.predictedMaxError) << name;
  expectAtLeastThePerPixelEstimate(name, fresh);
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

// The blocks' facts are kept per mesh version: points changed in place under a new version
// (the sphere moved toward an attenuated light and stretched, then back) give the numbers a
// new renderer gives, at least the per-pixel estimate's; and two meshes whose polygon ids
// share a block (130 + 130 polygons) take the larger bound there.
TEST(SummaryEstimate, KeptPerMeshVersionAndSharedBlocksAcrossMeshes) {
  Mesh sphere = makeUvSphere(10, 8);  // 120 triangles
  Mesh other = makeUvSphere(10, 8, 0.5, {1.2, 0.3, 0.0});
  for (Mesh* mesh : {&sphere, &other}) {  // 130 polygons each: mesh 1's first ids in block 1
    for (int k = 0; k < 10; ++k) {
      const glm::dvec3 a = mesh->points[static_cast<std::size_t>(k)];
      mesh->addPolygon({mesh->addPoint(a), mesh->addPoint(a + glm::dvec3(0.01, 0, 0)),
                        mesh->addPoint(a + glm::dvec3(0, 0.01, 0.002))});
    }
  }
  Material matte;
  matte.diffuse = 0.9;
  LightSet lights;
  lights.lights.push_back(
      PointLight{{0.4, 0.5, 4.0}, Color(1.0f), 1.0, QuadraticAttenuation{1.0, 0.0, 0.05}});
  Scene scene = oneMeshScene(sphere.view(), matte, lights);
  scene.meshes.push_back(scene.meshes[0]);
  scene.meshes[1].mesh = other.view();
  scene.meshes[0].mesh.version = scene.meshes[1].mesh.version = 1;
  const Camera camera = fitCamera(makeUvSphere(8, 5, 2.0), {0.2, -0.3, -1});
  QualitySettings summary{.estimateError = true};
  summary.errorEstimateImage = false;
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer framebuffer(120, 90);
  const std::vector<glm::dvec3> original = sphere.points;
  for (const double stretch : {1.0, 1.8, 1.0}) {
    for (std::size_t i = 0; i < sphere.points.size(); ++i)
      sphere.points[i] =
          original[i] * glm::dvec3(stretch, stretch, 1.0) + glm::dvec3(0.0, 0.0, stretch - 1.0);
    ++scene.meshes[0].mesh.version;
    const QualityStats kept = quality.render(scene, {}, camera, framebuffer, summary);
    expectAFreshRenderersNumbers("stretch " + std::to_string(stretch), kept, scene, camera);
  }
}

// Under directional lights alone the blocks' bounds are kept per mesh version (they depend on
// the normals' spread, not on the camera or the lights' directions: BlockBoundSetup::
// cameraIndependent). One renderer turning the camera and the lights, then dimming a light,
// then a material of another diffuse weight, then the mesh's points moved under a new
// version, gives each frame a fresh renderer's numbers, at least the per-pixel estimate's.
TEST(SummaryEstimate, DirectionalBoundsAreKeptUntilTheLightsMaterialOrMeshChange) {
  Mesh sphere = makeUvSphere(40, 21);
  const std::vector<glm::dvec3> original = sphere.points;
  Material matte;
  matte.diffuse = 0.9;
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1, -1, -2}, Color(0.8f)});
  lights.lights.push_back(DirectionalLight{{1, 0.5, -1}, Color(0.6f, 0.5f, 0.4f)});
  Scene scene = oneMeshScene(sphere.view(), matte, lights);
  scene.meshes[0].mesh.version = 1;
  const QualitySettings summary = summaryOnly();
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer framebuffer(120, 90);
  std::vector<double> maxima;
  for (int k = 0; k < 7; ++k) {
    const double turn = 0.05 * k;
    std::get<DirectionalLight>(scene.lights.lights[0]).direction = {-1 + turn, -1, -2};
    if (k == 3) std::get<DirectionalLight>(scene.lights.lights[1]).intensity = 0.5;
    if (k == 4) scene.meshes[0].material.diffuse = 0.6;
    if (k == 5) {
      for (std::size_t i = 0; i < sphere.points.size(); ++i)
        sphere.points[i] = original[i] * glm::dvec3(1.6, 1.0, 1.0);
      ++scene.meshes[0].mesh.version;
    }
    const Camera camera = fitCamera(makeUvSphere(8, 5, 1.8), {0.1 * turn, -0.2, -1});
    const QualityStats kept = quality.render(scene, {}, camera, framebuffer, summary);
    expectAFreshRenderersNumbers("frame " + std::to_string(k), kept, scene, camera);
    maxima.push_back(kept.predictedMaxError);
  }
  // Dimming a light, a weaker material and a stretched sphere each moved the numbers.
  EXPECT_NE(maxima[3], maxima[2]);
  EXPECT_NE(maxima[4], maxima[3]);
  EXPECT_NE(maxima[5], maxima[4]);
}

// review25: the kept directional bounds across the other changes that reach them: a light
// added, per-polygon colors on and off (the surface bound turns 1), a point light in between
// (the bounds then found each frame) and back to the directional setup kept before it. Each
// frame has a fresh renderer's numbers.
TEST(SummaryEstimate, DirectionalBoundsFollowLightsColorsAndPointLightFrames) {
  Mesh sphere = makeUvSphere(40, 21);
  Material matte;
  matte.diffuse = 0.9;
  matte.color = Color(0.3f, 0.4f, 0.5f);
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1, -1, -2}, Color(0.8f)});
  Scene scene = oneMeshScene(sphere.view(), matte, lights);
  scene.meshes[0].mesh.version = 1;
  const std::vector<Rgba8> colors(sphere.polygonCount(), Rgba8{230, 240, 250, 255});
  const QualitySettings summary = summaryOnly();
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer framebuffer(120, 90);
  std::vector<double> maxima;
  for (int k = 0; k < 6; ++k) {
    if (k == 1) scene.lights.lights.push_back(DirectionalLight{{1, 0.5, -1}, Color(0.9f)});
    if (k == 2) scene.meshes[0].mesh.polygonColors = colors;
    if (k == 3) scene.meshes[0].mesh.polygonColors = {};
    if (k == 4)
      scene.lights.lights[0] = PointLight{{0.0, 0.0, 9.0}, Color(0.8f), 1.0, NoAttenuation{}};
    if (k == 5) scene.lights.lights[0] = DirectionalLight{{-1, -1, -2}, Color(0.8f)};
    const Camera camera = fitCamera(makeUvSphere(8, 5, 1.8), {0.02 * k, -0.2, -1});
    const QualityStats kept = quality.render(scene, {}, camera, framebuffer, summary);
    expectAFreshRenderersNumbers("frame " + std::to_string(k), kept, scene, camera);
    maxima.push_back(kept.predictedMaxError);
  }
  EXPECT_NE(maxima[1], maxima[0]);  // a second light
  EXPECT_NE(maxima[2], maxima[1]);  // the colors
}

// A polygon without a normal (collinear corners) in view: it is in no block (its bound, 255,
// is the per-polygon estimate's); the summary is still at least the per-pixel estimate.
TEST(SummaryEstimate, AtLeastThePerPixelEstimateWithADegeneratePolygonInView) {
  Mesh sphere = makeUvSphere(32, 17);
  sphere.addPolygon({sphere.addPoint({-0.5, -0.5, 1.01}), sphere.addPoint({0.0, 0.0, 1.01}),
                     sphere.addPoint({0.5, 0.5, 1.01})});
  Material matte;
  matte.diffuse = 0.9;
  const Camera camera = fitCamera(sphere, {0.0, 0.0, -1});
  expectAtLeastThePerPixelEstimate(
      "degenerate", estimateBoth(oneMeshScene(sphere.view(), matte, twoLights()), camera));
}

// A shown polygon in no block: a backdrop so wide (1e160) that its radius overflows
// (QualityRenderer.cpp, termsOf: no terms), behind a sphere (within the fitted clipping range). The
// frame falls back to the per-polygon bounds: the numbers of the per-pixel estimate.
TEST(SummaryEstimate, FallsBackWhereAShownPolygonHasNoTerms) {
  Mesh sphere = makeUvSphere(32, 17);
  const double wide = 1e160;
  sphere.addPolygon({sphere.addPoint({-wide, -wide, -1.3}), sphere.addPoint({wide, -wide, -1.3}),
                     sphere.addPoint({wide, wide, -1.3}), sphere.addPoint({-wide, wide, -1.3})});
  Material matte;
  matte.diffuse = 0.9;
  const Camera camera = fitCamera(makeUvSphere(8, 5, 1.5), {0.0, 0.0, -1});
  const Both both = estimateBoth(oneMeshScene(sphere.view(), matte, twoLights()), camera);
  expectAtLeastThePerPixelEstimate("backdrop", both);
  // The blocks would give more (the sphere's are looser than its polygons').
  EXPECT_NEAR(both.fast.predictedRmse, both.exact.predictedRmse, 0.01);
  EXPECT_NEAR(both.fast.predictedMaxError, both.exact.predictedMaxError, 0.01);
}

// The per-polygon bounds are sized only by the frames that take them (the per-polygon path, or
// the summary's fallback): one renderer taking, frame by frame, the summary, its fallback (first
// on a renderer that never sized them, then on more ids than the last per-polygon frame's), the
// per-pixel estimate with the image and without (a specular material), gives each frame the
// numbers, and the image, of a fresh renderer; the fallback's are the per-pixel estimate's.
TEST(SummaryEstimate, FramesAlternatingThePathsGiveAFreshRenderersNumbers) {
  Mesh sphere = makeUvSphere(32, 17);
  Mesh backdropped = sphere;  // FallsBackWhereAShownPolygonHasNoTerms's
  const double wide = 1e160;
  backdropped.addPolygon(
      {backdropped.addPoint({-wide, -wide, -1.3}), backdropped.addPoint({wide, -wide, -1.3}),
       backdropped.addPoint({wide, wide, -1.3}), backdropped.addPoint({-wide, wide, -1.3})});
  Material matte;
  matte.diffuse = 0.9;
  const Scene plain = oneMeshScene(sphere.view(), matte, twoLights());
  const Scene fallback = oneMeshScene(backdropped.view(), matte, twoLights());
  const Scene shiny = oneMeshScene(sphere.view(), shinyMaterial(), twoLights());
  const QualitySettings image{.estimateError = true};
  QualitySettings summary = image;
  summary.errorEstimateImage = false;
  struct Step {
    std::string name;
    const Scene& scene;
    const QualitySettings& settings;
  };
  const std::vector<Step> steps{
      {"summary", plain, summary},       {"fallback, first", fallback, summary},
      {"image", plain, image},           {"specular", shiny, summary},
      {"summary again", plain, summary}, {"fallback, more ids", fallback, summary},
      {"image again", plain, image},     {"summary last", plain, summary}};
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer framebuffer(120, 90);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const Step& step = steps[k];
    const Camera camera =
        fitCamera(makeUvSphere(8, 5, 1.5), {0.02 * static_cast<double>(k), -0.01, -1.0});
    const QualityStats kept = quality.render(step.scene, {}, camera, framebuffer, step.settings);
    Renderer freshRenderer;
    QualityRenderer fresh(freshRenderer);
    Framebuffer freshFramebuffer(120, 90);
    const QualityStats once = fresh.render(step.scene, {}, camera, freshFramebuffer, step.settings);
    EXPECT_GT(kept.predictedMaxError, 0.5) << step.name;
    EXPECT_EQ(kept.predictedRmse, once.predictedRmse) << step.name;
    EXPECT_EQ(kept.predictedMaxError, once.predictedMaxError) << step.name;
    EXPECT_EQ(quality.errorEstimate().size(), fresh.errorEstimate().size()) << step.name;
    EXPECT_TRUE(std::equal(quality.errorEstimate().begin(), quality.errorEstimate().end(),
                           fresh.errorEstimate().begin(), fresh.errorEstimate().end()))
        << step.name;
    if (&step.scene != &fallback) continue;
    // The fallback's numbers are the per-pixel estimate's (FallsBackWhereAShownPolygonHasNoTerms).
    Renderer imageRenderer;
    QualityRenderer perPixel(imageRenderer);
    const QualityStats exact = perPixel.render(step.scene, {}, camera, freshFramebuffer, image);
    EXPECT_NEAR(kept.predictedRmse, exact.predictedRmse, 0.01) << step.name;
    EXPECT_NEAR(kept.predictedMaxError, exact.predictedMaxError, 0.01) << step.name;
  }
}

// The summary against the per-pixel estimate on random scenes at the edges the block bound's
// tests take one polygon at a time, here through the render (terms, blocks, the resolve):
// spheres of 8 to 64 segments, 1e-3 to 1e3 wide at 0 to 1e6 from the origin, a point light
// 0.1 % to twice their radius off their surface (randomAttenuation's), with or without a
// directional light; Lambert and Lerp; seen from the light's side or the far one.
TEST(SummaryEstimate, AtLeastThePerPixelEstimateOnRandomScenesAtTheEdges) {
  std::mt19937_64 random(99);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto pick = [&](auto... values) { return pickOne(random, values...); };
  int lit = 0;
  for (int trial = 0; trial < 80; ++trial) {
    const double offset = pick(0.0, 1e3, 1e6), scale = pick(1e-3, 1.0, 1e3);
    const glm::dvec3 center = offset * glm::dvec3(unit(random), -unit(random), unit(random));
    const int segments = pick(8, 24, 64);
    const Mesh sphere = makeUvSphere(segments, segments / 2 + 1, scale, center);
    LightSet lights;
    const glm::dvec3 toward =
        glm::normalize(glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, -1.0));
    const double reach = scale * pick(1.001, 1.05, 1.3, 3.0);
    const Attenuation attenuation = randomAttenuation(random, scale);
    lights.lights.push_back(PointLight{center + reach * toward, Color(1.0f), 1.0, attenuation});
    if (random() % 2) lights.lights.push_back(DirectionalLight{{-1, -1, -2}, Color(0.5f)});
    Material material;
    material.diffuse = pick(0.5, 1.0);
    if (random() % 2) {
      material.diffuseModel = DiffuseModel::Lerp;
      material.lerpAmbient = pick(0.0, 0.3);
      material.lerpFull = pick(0.6, 1.0);
    }
    Scene scene = oneMeshScene(sphere.view(), material, lights);
    const Camera camera = fitCamera(sphere, random() % 4 == 0 ? toward : -toward);
    const Both both = estimateBoth(scene, camera, 2);
    const std::string name = "trial " + std::to_string(trial);
    lit += both.exact.predictedMaxError > 1.0;
    EXPECT_GE(both.fast.predictedMaxError, both.exact.predictedMaxError) << name;
    EXPECT_GE(both.fast.predictedRmse, both.exact.predictedRmse) << name;
  }
  EXPECT_GT(lit, 60);  // most scenes show their light's error
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
