// The rules that leave work out (RenderPlan.h): each fires where it should, the plan names it,
// and the image keeps the same bytes as with the rule off (or stays within the bound the plan
// reports), on 1 and 2 threads.

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "LightCulling.h"
#include "Plan.h"
#include "facet/Error.h"

namespace facet::testing {
namespace {

// Renders with the rules as given and with `rule` off, on 1 and 2 threads, and checks that
// every plane keeps its bytes; `mustFire`: the rule also left work out. Returns the render
// with the rule (2 threads).
Rendered expectSameBytesWithout(Rule rule, const Scene& scene, const Camera& camera, int width,
                                int height, RenderOptions options = {}, bool mustFire = true) {
  RenderOptions off = options;
  off.threads = 1;
  switch (rule) {
    case Rule::LightsThatReachNothing:
      off.rules.lightsThatReachNothing = false;
      break;
    case Rule::GeometryOutsideView:
      off.rules.geometryOutsideView = false;
      break;
    case Rule::HiddenGeometry:
      off.rules.hiddenGeometry = HierarchicalZ::Off;
      break;
    case Rule::AmbientOnly:
      off.rules.ambientOnly = false;
      break;
    case Rule::OneColor:
      off.rules.oneColor = false;
      break;
    case Rule::ClosedSurfaces:
      off.rules.closedSurfaces = false;
      break;
  }
  const Rendered reference = renderScene(scene, camera, width, height, off);
  EXPECT_FALSE(reference.stats.plan.rule(rule).allowed);
  Rendered on;
  for (int threads : {1, 2}) {
    options.threads = threads;
    on = renderScene(scene, camera, width, height, options);
    EXPECT_EQ(differingPixels(on.framebuffer, reference.framebuffer), 0u)
        << ruleName(rule) << ", " << threads << " threads\n"
        << on.stats.describe();
  }
  EXPECT_GT(reference.stats.pixelsCovered, 0u);
  if (mustFire) {
    EXPECT_TRUE(on.stats.plan.rule(rule).fired) << on.stats.describe();
  }
  return on;
}

LightSet oneDirectionalLight() {
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1, -0.5, -1}, Color(0.8f), 1.0});
  return lights;
}

TEST(LightsThatReachNothing, DarkLightsAndConesThatMissAreLeftOutWithTheSameBytes) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  LightSet lights = oneDirectionalLight();
  lights.lights.push_back(PointLight{{0, 1, 1}, Color(1.0f), 0.0});                     // [1] dark
  lights.lights.push_back(DirectionalLight{{0, 0, -1}, Color(0.0f), 2.0});              // [2] black
  lights.lights.push_back(SpotLight{{0, 0, 1}, {0, 0, 1}, Color(1.0f), 5.0});           // [3] away
  lights.lights.push_back(SpotLight{{0, 0.1, 1}, {0, 0, -1}, Color(1, 0.5f, 0), 1.0});  // [4] hits
  lights.lights.push_back(
      SpotLight{{2, 0, 0},
                {0, 1, 0},
                Color(1.0f),
                3.0,
                NoAttenuation{},
                ExponentSpotCone{60.0, 1.0}});  // [5] 2 units beside the bunny, shining up
  Material material;
  material.specular = 0.3;
  const Rendered r = expectSameBytesWithout(Rule::LightsThatReachNothing,
                                            oneMeshScene(bunny.view(), material, lights),
                                            fitCamera(bunny), 320, 240);
  const RenderPlan::LightCulling& report = r.stats.plan.lightCulling;
  EXPECT_EQ(report.lights, 6u);
  EXPECT_EQ(report.dark, 2u);
  EXPECT_EQ(report.outsideCone, 2u);
  EXPECT_EQ(report.culledMask, 0b101110u);
  EXPECT_EQ(report.errorBound8Bit, 0) << "nothing left out that could change a byte";
  EXPECT_TRUE(r.stats.plan.rule(Rule::LightsThatReachNothing).fired);
  EXPECT_NE(r.stats.describe().find("2 outside their cone"), std::string::npos)
      << r.stats.describe();
}

TEST(LightsThatReachNothing, ToleranceStaysWithinTheReportedBound) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  LightSet lights = oneDirectionalLight();
  // About 0.003 of full color over the bunny (1/(1 + 0.0001·(12²))): below a tolerance of 0.01.
  lights.lights.push_back(PointLight{{0, 0, 12}, Color(1.0f), 0.0035, QuadraticAttenuation{}});
  const Scene scene = oneMeshScene(bunny.view(), {}, lights);
  const Camera camera = fitCamera(bunny);
  RenderOptions tolerant;
  tolerant.rules.lightTolerance = 0.01;
  const Rendered kept = renderScene(scene, camera, 320, 240);
  const Rendered culled = renderScene(scene, camera, 320, 240, tolerant);
  EXPECT_EQ(kept.stats.plan.lightCulling.belowTolerance, 0u) << "tolerance 0: it adds light";
  const RenderPlan::LightCulling& report = culled.stats.plan.lightCulling;
  ASSERT_EQ(report.belowTolerance, 1u);
  EXPECT_GT(report.errorBound, 0.003);
  EXPECT_LE(report.errorBound, 0.01);
  EXPECT_GE(report.errorBound8Bit, 1);
  const int difference = largestChannelDifference(kept.framebuffer, culled.framebuffer);
  EXPECT_LE(difference, report.errorBound8Bit) << culled.stats.describe();
  EXPECT_GT(difference, 0) << "the light did add something the bound had to cover";
  EXPECT_THROW(Renderer().setRules({.lightTolerance = -1.0}), Error);
}

// A light so far that its distance's square overflows still reaches at full strength when
// its falloff distance is farther still: the culling's distance must not become +inf.
TEST(LightsThatReachNothing, LightsBeyondTheSquaresRangeAreJudgedAtTheirDistance) {
  const Mesh sphere = makeUvSphere(16, 8);
  LightSet lights;
  lights.lights.push_back(
      PointLight{{0, 0, 1e200}, Color(1.0f), 1.0, FalloffDistanceAttenuation{1e300}});
  const Scene scene = oneMeshScene(sphere.view(), {}, lights);
  RenderOptions tolerant;
  tolerant.rules.lightTolerance = 0.01;
  const Rendered culled = renderScene(scene, fitCamera(sphere), 64, 48, tolerant);
  EXPECT_EQ(culled.stats.plan.lightCulling.belowTolerance, 0u) << culled.stats.describe();
  const Rendered kept = renderScene(scene, fitCamera(sphere), 64, 48);
  EXPECT_EQ(largestChannelDifference(kept.framebuffer, culled.framebuffer), 0);
}

// The exact cone test against an independent minimization of the angle over the box's
// surface (pattern search on each face: the set of points within an angle < 90° of the
// axis is convex, so the angle has no other minimum on a face).
double smallestAngleDegrees(const glm::dvec3& apex, const glm::dvec3& axis,
                            const detail::Box& box) {
  const auto angleAt = [&](const glm::dvec3& p) {
    const glm::dvec3 w = p - apex;
    return glm::degrees(std::atan2(glm::length(glm::cross(w, axis)), glm::dot(w, axis)));
  };
  double smallest = 180.0;
  for (int face = 0; face < 6; ++face) {
    const int n = face / 2, u = (n + 1) % 3, v = (n + 2) % 3;
    const auto pointAt = [&](double s, double t) {
      glm::dvec3 p;
      p[n] = face % 2 ? box.high[n] : box.low[n];
      p[u] = box.low[u] + std::clamp(s, 0.0, 1.0) * (box.high[u] - box.low[u]);
      p[v] = box.low[v] + std::clamp(t, 0.0, 1.0) * (box.high[v] - box.low[v]);
      return p;
    };
    double bestS = 0.5, bestT = 0.5, best = 180.0;
    for (int i = 0; i <= 20; ++i) {
      for (int j = 0; j <= 20; ++j) {
        const double a = angleAt(pointAt(i / 20.0, j / 20.0));
        if (a < best) best = a, bestS = i / 20.0, bestT = j / 20.0;
      }
    }
    for (double step = 0.05; step > 1e-12; step *= 0.5) {
      for (bool moved = true; moved;) {
        moved = false;
        for (const auto& [ds, dt] :
             {std::pair{step, 0.0}, {-step, 0.0}, {0.0, step}, {0.0, -step}}) {
          const double s = std::clamp(bestS + ds, 0.0, 1.0), t = std::clamp(bestT + dt, 0.0, 1.0);
          const double a = angleAt(pointAt(s, t));
          if (a < best) best = a, bestS = s, bestT = t, moved = true;
        }
      }
    }
    smallest = std::min(smallest, best);
  }
  return smallest;
}

TEST(LightsThatReachNothing, ConeVersusBoxIsExact) {
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(1.0, 179.0);
  int misses = 0, hits = 0, nearMisses = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const glm::dvec3 center(3 * unit(random), 3 * unit(random), 3 * unit(random));
    const glm::dvec3 half(0.05 + std::abs(unit(random)), 0.05 + std::abs(unit(random)),
                          0.05 + std::abs(unit(random)));
    const detail::Box box{center - half, center + half};
    const glm::dvec3 apex(3 * unit(random), 3 * unit(random), 3 * unit(random));
    const glm::dvec3 axis = glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)));
    const double halfAngle = angle(random);
    if (box.contains(apex)) continue;
    const double smallest = smallestAngleDegrees(apex, axis, box);
    // Within the test's margin of the cone (LightCulling.h): either answer is right.
    if (std::abs(smallest - halfAngle) < 10 * detail::kConeMarginDegrees) continue;
    const bool missed = detail::coneMissesBox(apex, axis, halfAngle, box);
    ASSERT_EQ(missed, smallest > halfAngle)
        << "trial " << trial << ": smallest angle " << smallest << ", cone " << halfAngle;
    (missed ? misses : hits) += 1;
    nearMisses += missed && smallest < halfAngle + 1.0;
  }
  EXPECT_GT(misses, 500);
  EXPECT_GT(hits, 500);
  EXPECT_GT(nearMisses, 10) << "boxes within a degree of the cone, which a sphere test keeps";
}

Mesh denseSphere() {
  return makeUvSphere(200, 150);
}

TEST(GeometryOutsideView, BlocksOutsideTheViewAreNotSetUpAndTheBytesStay) {
  const Mesh sphere = denseSphere();
  MeshView view = sphere.view();
  view.version = 1;  // blocks are measured once per version
  // From the side: the rings around the poles (whole blocks) leave the small view.
  Camera camera = fitCamera(sphere, {1, 0, 0});
  camera.viewAngleDegrees = 6.0;
  for (Visibility visibility : {Visibility::ZBuffer, Visibility::PainterSort}) {
    for (bool closed : {false, true}) {
      view.closedSurface = closed;
      RenderOptions options;
      options.visibility = visibility;
      const Rendered r = expectSameBytesWithout(Rule::GeometryOutsideView,
                                                oneMeshScene(view, {}, oneDirectionalLight()),
                                                camera, 200, 150, options);
      const RenderPlan& plan = r.stats.plan;
      EXPECT_EQ(plan.blocksTested, (sphere.polygonCount() + 1023) / 1024);
      EXPECT_GT(plan.blocksOutside, plan.blocksTested / 2) << plan.describe();
      EXPECT_GT(plan.rule(Rule::GeometryOutsideView).skipped, sphere.polygonCount() / 2);
      EXPECT_GE(r.stats.polygonsOutside, plan.rule(Rule::GeometryOutsideView).skipped);
    }
  }
}

TEST(GeometryOutsideView, ClosedMeshesCutByTheNearPlaneKeepEveryBlock) {
  const Mesh sphere = denseSphere();
  MeshView view = sphere.view();
  view.version = 1;
  view.closedSurface = true;
  Camera camera = fitCamera(sphere);
  camera.nearClip = glm::length(camera.position - camera.focalPoint);  // through the center
  const Rendered r = renderScene(oneMeshScene(view), camera, 200, 150);
  EXPECT_EQ(r.stats.plan.blocksTested, 0u) << "its back faces are drawn: no block is culled";
  EXPECT_EQ(r.stats.closedMeshesSkippingBackFaces, 0u);
}

TEST(GeometryOutsideView, UnversionedMeshesAreNotMeasured) {
  const Mesh sphere = denseSphere();
  Camera camera = fitCamera(sphere, {1, 0, 0});
  camera.viewAngleDegrees = 6.0;
  const Rendered r = renderScene(oneMeshScene(sphere.view()), camera, 200, 150);
  EXPECT_EQ(r.stats.plan.blocksTested, 0u);
  EXPECT_FALSE(r.stats.plan.rule(Rule::GeometryOutsideView).fired);
}

TEST(HiddenGeometry, CoarseDepthSkipsTrianglesBehindAndKeepsTheBytes) {
  const Camera camera = pixelCamera(160, 120);
  for (bool frontToBack : {true, false}) {
    Mesh stack = makeStackedSquares(24, 4, frontToBack);
    for (glm::dvec3& p : stack.points)
      p = {80.0 + 70.0 * p.x, 60.0 + 55.0 * p.y, p.z};  // into the pixel camera's view
    RenderOptions options;
    options.rules.hiddenGeometry = HierarchicalZ::On;
    const Scene scene = oneMeshScene(stack.view(), {}, oneDirectionalLight());
    if (frontToBack) {
      const Rendered r =
          expectSameBytesWithout(Rule::HiddenGeometry, scene, camera, 160, 120, options);
      EXPECT_GT(r.stats.trianglesHidden, r.stats.trianglesBinned / 2) << r.stats.describe();
      EXPECT_GT(r.stats.plan.depthComplexity, detail::kCoarseDepthMinComplexity);
    } else {
      const Rendered r = renderScene(scene, camera, 160, 120, options);
      EXPECT_EQ(r.stats.trianglesHidden, 0u) << "nothing is behind what was drawn first";
    }
  }
}

TEST(HiddenGeometry, ForcedOnDenseMeshesKeepsTheBytes) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  RenderOptions options;
  options.rules.hiddenGeometry = HierarchicalZ::On;
  Camera camera = fitCamera(bunny, {0.2, -0.3, -1.0});
  camera.nearClip *= 1.3;  // clipped triangles too
  const Scene scene = oneMeshScene(bunny.view(), {}, oneDirectionalLight());
  const Rendered r =
      expectSameBytesWithout(Rule::HiddenGeometry, scene, camera, 640, 480, options, false);
  EXPECT_STREQ(r.stats.plan.rasterRoutine, "depth test, hierarchical z");
}

TEST(HiddenGeometry, AutoChoosesItForDeepLargeTrianglesOnly) {
  const Camera camera = pixelCamera(160, 120);
  Mesh stack = makeStackedSquares(24, 4, true);
  for (glm::dvec3& p : stack.points)
    p = {80.0 + 70.0 * p.x, 60.0 + 55.0 * p.y, p.z};
  const Rendered deep = renderScene(oneMeshScene(stack.view()), camera, 160, 120);
  EXPECT_STREQ(deep.stats.plan.rasterRoutine, "depth test, hierarchical z");
  EXPECT_TRUE(deep.stats.plan.rule(Rule::HiddenGeometry).fired);
  const Mesh sphere = denseSphere();
  const Rendered dense = renderScene(oneMeshScene(sphere.view()), fitCamera(sphere), 200, 150);
  EXPECT_STREQ(dense.stats.plan.rasterRoutine, "depth test") << dense.stats.plan.describe();
}

TEST(AmbientOnly, OneShadePerColorGivesTheSameBytes) {
  const Mesh beast = readObj(sharedMeshPath("beast.obj"));
  Mesh colored = beast;
  colored.polygonColors.resize(colored.polygonCount());
  for (std::size_t i = 0; i < colored.polygonCount(); ++i) {
    colored.polygonColors[i] = {static_cast<std::uint8_t>(i * 37),
                                static_cast<std::uint8_t>(i * 91),
                                static_cast<std::uint8_t>(i * 13), 255};
  }
  LightSet ambient;
  ambient.ambient = {Color(0.9f, 0.6f, 1.3f), 1.5};
  Material material;
  material.ambient = 0.4;
  material.ambientColor = Color(0.2f, 0.1f, 0.5f);
  material.specular = 0.5;  // no direct light: no highlight either
  material.specularMix = SpecularMix::Blend;
  const Camera camera = fitCamera(beast, {-0.3, -0.2, -1});
  for (const Mesh* mesh : {&std::as_const(beast), &std::as_const(colored)}) {
    const Rendered r = expectSameBytesWithout(
        Rule::AmbientOnly, oneMeshScene(mesh->view(), material, ambient), camera, 300, 250);
    EXPECT_TRUE(r.stats.plan.rule(Rule::AmbientOnly).fired);
    EXPECT_EQ(r.stats.plan.rule(Rule::AmbientOnly).skipped, r.stats.polygonsShaded);
    EXPECT_FALSE(r.stats.plan.directLighting);
  }
}

TEST(AmbientOnly, OneColorMeshesTakeTheirMaterialColor) {
  const Mesh box = makeBox({-1, -1, -1}, {1, 1, 1});
  Material red;
  red.color = Color(1.0f, 0.0f, 0.0f);
  LightSet ambient;
  ambient.ambient = {Color(0.5f), 1.0};
  Camera camera;
  camera.position = {0, 0, 5};
  const Rendered r = renderScene(oneMeshScene(box.view(), red, ambient), camera, 40, 40);
  SurfaceSample sample;
  sample.color = red.color;
  EXPECT_EQ(r.framebuffer.colorAt(20, 20), toRgba8(shade(sample, red, ambient)));
  EXPECT_EQ(r.framebuffer.colorAt(20, 20).g, 0) << "red, not the gray of a white surface";
}

TEST(OneColor, NoColorFetchGivesTheSameBytes) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  LightSet lights = oneDirectionalLight();
  lights.lights.push_back(PointLight{{0.2, 0.3, 0.4}, Color(0.4f, 0.5f, 1.0f), 1.0});
  Material material;
  material.color = Color(0.8f, 0.7f, 0.2f);
  const Rendered r = expectSameBytesWithout(
      Rule::OneColor, oneMeshScene(bunny.view(), material, lights), fitCamera(bunny), 320, 240);
  EXPECT_EQ(r.stats.plan.rule(Rule::OneColor).skipped, 1u);
  EXPECT_STREQ(r.stats.plan.shadeRoutine, "lit at centers, diffuse, one color");
}

TEST(ClosedSurfaces, TurnedOffTheBackFacesAreDrawn) {
  const Mesh spot = readObj(sharedMeshPath("spot.obj"));
  MeshView closed = spot.view();
  closed.closedSurface = true;
  RenderOptions off;
  off.rules.closedSurfaces = false;
  const Scene scene = oneMeshScene(closed, {}, oneDirectionalLight());
  const Rendered skipping = renderScene(scene, fitCamera(spot), 200, 150);
  const Rendered drawing = renderScene(scene, fitCamera(spot), 200, 150, off);
  EXPECT_EQ(skipping.stats.closedMeshesSkippingBackFaces, 1u);
  EXPECT_TRUE(skipping.stats.plan.rule(Rule::ClosedSurfaces).fired);
  EXPECT_EQ(drawing.stats.closedMeshesSkippingBackFaces, 0u);
  EXPECT_GT(drawing.stats.polygonsDrawn, skipping.stats.polygonsDrawn);
  EXPECT_EQ(largestChannelDifference(skipping.framebuffer, drawing.framebuffer), 0);
}

TEST(DepthOutput, OffLeavesColorsAndIdsAndNeedsNoDepthPlane) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  const Scene scene = oneMeshScene(bunny.view(), {}, oneDirectionalLight());
  const Camera camera = fitCamera(bunny);
  const Rendered with = renderScene(scene, camera, 160, 120);
  Renderer renderer;
  renderer.setDepthOutput(false);
  Framebuffer without(160, 120);
  FramebufferView view = without.view();
  view.depth = nullptr;
  const RenderStats stats = renderer.render(scene, camera, view);
  EXPECT_FALSE(stats.plan.depthOutput);
  for (std::size_t i = 0; i < without.pixelCount(); ++i) {
    ASSERT_EQ(without.color()[i], with.framebuffer.color()[i]) << "pixel " << i;
    ASSERT_EQ(without.polygonId()[i], with.framebuffer.polygonId()[i]) << "pixel " << i;
  }
  renderer.setDepthOutput(true);
  EXPECT_THROW(renderer.render(scene, camera, view), Error) << "a null depth plane needs it off";
}

}  // namespace
}  // namespace facet::testing
