// The converged references' foundations: camera rays that land where the rasterizer projects,
// the sample pattern's stratification, the analytic sphere and plane against closed forms,
// determinism, convergence, and the first measurement of flat shading's error against
// tessellation.

#include <cmath>
#include <cstdio>
#include <set>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "../support/ReferenceScenes.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "facet/AnalyticReference.h"
#include "facet/Error.h"
#include "facet/ImageMetrics.h"

namespace facet {
namespace {

using testing::fitCamera;
using testing::makeUvSphere;
using testing::pixelCamera;

// Window coordinates of a world point by the rasterizer's transforms.
glm::dvec2 project(const Camera& camera, int width, int height, const glm::dvec3& world) {
  const glm::dvec4 clip = clipFromView(camera, static_cast<double>(width) / height) *
                          viewFromWorld(camera) * glm::dvec4(world, 1.0);
  return {(clip.x / clip.w + 1.0) * 0.5 * width, (clip.y / clip.w + 1.0) * 0.5 * height};
}

double viewDepth(const Camera& camera, const glm::dvec3& world) {
  return -(viewFromWorld(camera) * glm::dvec4(world, 1.0)).z;
}

void expectRaysLandOnTheirPixels(const Camera& camera, int width, int height) {
  const CameraRays rays(camera, width, height);
  for (const glm::dvec2 window : {glm::dvec2(0.5, 0.5), glm::dvec2(width - 0.5, 3.25),
                                  glm::dvec2(0.37 * width, 0.81 * height)}) {
    const Ray ray = rays.through(window);
    EXPECT_NEAR(glm::length(ray.direction), 1.0, 1e-15);
    for (const double t : {ray.tNear, 0.5 * (ray.tNear + ray.tFar), ray.tFar}) {
      const glm::dvec2 landed = project(camera, width, height, ray.origin + t * ray.direction);
      EXPECT_NEAR(landed.x, window.x, 1e-9 * width) << "t " << t;
      EXPECT_NEAR(landed.y, window.y, 1e-9 * height) << "t " << t;
    }
    const double near = viewDepth(camera, ray.origin + ray.tNear * ray.direction);
    const double far = viewDepth(camera, ray.origin + ray.tFar * ray.direction);
    EXPECT_NEAR(near, camera.nearClip, 1e-9 * camera.farClip);
    EXPECT_NEAR(far, camera.farClip, 1e-9 * camera.farClip);
  }
}

TEST(CameraRays, PerspectiveRaysLandWhereTheRasterizerProjects) {
  Camera camera;
  camera.position = {3, -2, 7};
  camera.focalPoint = {0.5, 0.2, -1};
  camera.viewUp = {0.2, 1, 0.1};
  camera.viewAngleDegrees = 40;
  camera.nearClip = 0.5;
  camera.farClip = 50;
  camera.windowCenter = {0.3, -0.2};
  expectRaysLandOnTheirPixels(camera, 320, 200);
}

TEST(CameraRays, ParallelRaysLandWhereTheRasterizerProjects) {
  Camera camera = pixelCamera(64, 48);
  camera.nearClip = -5.0;  // parallel projection allows a near plane behind the eye
  expectRaysLandOnTheirPixels(camera, 64, 48);
  // pixelCamera maps world x, y to window x, y.
  const Ray ray = CameraRays(camera, 64, 48).through({10.5, 20.25});
  EXPECT_NEAR(ray.origin.x, 10.5, 1e-12);
  EXPECT_NEAR(ray.origin.y, 20.25, 1e-12);
  EXPECT_EQ(ray.direction, glm::dvec3(0, 0, -1));
}

// Every prefix of 2^m samples is a (0, m, 2)-net: each elementary box of area 2^−m, of every
// shape 2^−a × 2^−(m−a), holds exactly one sample.
TEST(ReferenceSamples, EveryPowerOfTwoPrefixIsANet) {
  for (const auto& [x, y] : {std::pair(0, 0), std::pair(17, 3), std::pair(1919, 1079)}) {
    for (int m = 0; m <= 8; ++m) {
      const std::uint32_t count = 1u << m;
      for (int a = 0; a <= m; ++a) {
        std::set<std::pair<int, int>> boxes;
        for (std::uint32_t s = 0; s < count; ++s) {
          const glm::dvec2 p = referenceSampleOffset(x, y, s);
          ASSERT_TRUE(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
          boxes.emplace(static_cast<int>(p.x * (1 << a)), static_cast<int>(p.y * (1 << (m - a))));
        }
        EXPECT_EQ(boxes.size(), count) << "pixel " << x << "," << y << " m " << m << " a " << a;
      }
    }
  }
}

TEST(ReferenceSamples, DeterministicAndDifferentPerPixel) {
  EXPECT_EQ(referenceSampleOffset(5, 9, 3), referenceSampleOffset(5, 9, 3));
  EXPECT_NE(referenceSampleOffset(5, 9, 3), referenceSampleOffset(6, 9, 3));
  EXPECT_NE(referenceSampleOffset(5, 9, 3), referenceSampleOffset(5, 10, 3));
}

// Parallel projection, one pixel per world unit: a sphere of radius R covers π R² pixels.
TEST(AnalyticReference, SphereCoversItsDisk) {
  const int size = 64;
  const double radius = 20.0;
  AnalyticScene scene;
  scene.spheres.push_back({{32.3, 31.7, 0.0}, radius, Material{}});
  const ReferenceRender render =
      renderAnalyticReference(scene, pixelCamera(size, size), size, size, {.samplesPerPixel = 256});
  double area = 0.0;
  for (const float c : render.image.coverage)
    area += c;
  // The error is the boundary pixels' sampling error: ~2πR pixels, each off by ≲ 1/256.
  EXPECT_NEAR(area, M_PI * radius * radius, 2.0 * M_PI * radius / 256.0);
  EXPECT_EQ(render.image.coverage[render.image.indexOf(32, 32)], 1.0f);
  EXPECT_EQ(render.image.coverage[render.image.indexOf(2, 2)], 0.0f);
  EXPECT_FALSE(render.aborted);
}

// A white sphere under a directional light shining straight at it, no ambient: the color is
// N·L = cos of the angle from the view axis, i.e. √(1 − r²/R²) at distance r from the center.
TEST(AnalyticReference, SphereIsLitByLambertsLaw) {
  const int size = 64;
  const double radius = 24.0;
  AnalyticScene scene;
  scene.spheres.push_back({{32.0, 32.0, 0.0}, radius, Material{}});
  scene.lights.ambient.intensity = 0.0;
  scene.lights.lights.push_back(DirectionalLight{{0, 0, -1}});
  const ReferenceRender render =
      renderAnalyticReference(scene, pixelCamera(size, size), size, size, {.samplesPerPixel = 64});
  for (const int x : {32, 40, 44, 50}) {
    // The pixel's mean of √(1 − r²/R²): the center value, plus the curvature's share.
    const double r = x + 0.5 - 32.0;
    const double expected = std::sqrt(1.0 - r * r / (radius * radius));
    EXPECT_NEAR(render.image.color[render.image.indexOf(x, 31)].g, expected, 2e-3) << "x " << x;
  }
}

AnalyticPlane square(double x0, double y0, double x1, double y1) {
  AnalyticPlane plane;
  plane.origin = {x0, y0, 0.0};
  plane.edgeU = {x1 - x0, 0.0, 0.0};
  plane.edgeV = {0.0, y1 - y0, 0.0};
  return plane;
}

// An edge through the pixels' middle covers exactly half of every 2^m sample pattern (the
// net's 1/2 × 2^−(m−1) boxes each hold one sample): coverage is exactly 0.5.
TEST(AnalyticReference, PlaneEdgeThroughPixelMiddlesCoversExactlyHalf) {
  AnalyticScene scene;
  scene.planes.push_back(square(10.5, -5.0, 40.0, 40.0));
  const ReferenceRender render =
      renderAnalyticReference(scene, pixelCamera(32, 16), 32, 16, {.samplesPerPixel = 64});
  for (int y = 0; y < 16; ++y) {
    EXPECT_EQ(render.image.coverage[render.image.indexOf(10, y)], 0.5f) << "row " << y;
    EXPECT_EQ(render.image.coverage[render.image.indexOf(9, y)], 0.0f);
    EXPECT_EQ(render.image.coverage[render.image.indexOf(11, y)], 1.0f);
  }
}

TEST(AnalyticReference, BackFacesAreTurnedToTheViewerOrCulled) {
  AnalyticScene scene;
  AnalyticPlane plane = square(0, 0, 16, 16);
  std::swap(plane.edgeU, plane.edgeV);  // faces −z, away from the camera
  scene.planes.push_back(plane);
  scene.lights.ambient.intensity = 0.0;
  scene.lights.lights.push_back(DirectionalLight{{0, 0, -1}});
  const auto colorAt = [&](bool twoSided) {
    const auto render = renderAnalyticReference(
        scene, pixelCamera(8, 8), 8, 8, {.samplesPerPixel = 4, .twoSidedLighting = twoSided});
    return render.image.color[render.image.indexOf(4, 4)];
  };
  EXPECT_EQ(colorAt(true), Color(1.0f));
  EXPECT_EQ(colorAt(false), Color(0.0f));
  scene.planes[0].material.backfaceCulling = true;
  const auto culled =
      renderAnalyticReference(scene, pixelCamera(8, 8), 8, 8, {.samplesPerPixel = 4});
  EXPECT_EQ(culled.image.coverage[culled.image.indexOf(4, 4)], 0.0f);
}

TEST(AnalyticReference, NearPlaneCutsTheSphereOpen) {
  // The camera sits outside the sphere, but the near plane cuts its front cap off: through
  // the cut the rays meet the inside (a back face), as the rasterizer's clipping shows it.
  Camera camera;
  camera.position = {0, 0, 5};
  camera.nearClip = 4.5;
  camera.farClip = 20;
  AnalyticScene scene;
  scene.spheres.push_back({});
  const auto render = renderAnalyticReference(scene, camera, 32, 32, {.samplesPerPixel = 4});
  EXPECT_EQ(render.image.coverage[render.image.indexOf(16, 16)], 1.0f);
  const Ray center = CameraRays(camera, 32, 32).through({16.5, 16.5});
  EXPECT_GT(center.tNear, 4.0) << "the front of the sphere, at t = 4, is clipped";
}

AnalyticScene litSphereScene() {
  AnalyticScene scene;
  scene.spheres.push_back({{0, 0, 0}, 1.0, testing::shinyMaterial()});
  scene.lights = testing::twoLights();
  return scene;
}

TEST(AnalyticReference, SameBytesForAnyThreadCount) {
  const AnalyticScene scene = litSphereScene();
  const Camera camera = fitCamera(makeUvSphere(8, 5), {0.2, -0.3, -1});
  const auto one =
      renderAnalyticReference(scene, camera, 96, 64, {.samplesPerPixel = 16, .threads = 1});
  for (const int threads : {2, 3, 8}) {
    const auto many =
        renderAnalyticReference(scene, camera, 96, 64, {.samplesPerPixel = 16, .threads = threads});
    EXPECT_EQ(one.image.color, many.image.color) << threads << " threads";
    EXPECT_EQ(one.image.coverage, many.image.coverage) << threads << " threads";
  }
}

TEST(AnalyticReference, ProgressCanStopIt) {
  int calls = 0;
  const auto render = renderAnalyticReference(
      litSphereScene(), fitCamera(makeUvSphere(8, 5)), 32, 32,
      {.samplesPerPixel = 1, .threads = 1, .progress = [&](double) { return ++calls < 3; }});
  EXPECT_TRUE(render.aborted);
  EXPECT_EQ(calls, 3);
}

TEST(AnalyticReference, BadInputIsNamed) {
  const Camera camera = pixelCamera(8, 8);
  AnalyticScene scene;
  scene.spheres.push_back({{0, 0, 0}, 0.0, Material{}});
  EXPECT_THROW(renderAnalyticReference(scene, camera, 8, 8), Error);
  scene.spheres[0] = {{std::nan(""), 0, 0}, 1.0, Material{}};
  EXPECT_THROW(renderAnalyticReference(scene, camera, 8, 8), Error);
  scene.spheres.clear();
  AnalyticPlane flat;
  flat.edgeV = 2.0 * flat.edgeU;
  scene.planes.push_back(flat);
  EXPECT_THROW(renderAnalyticReference(scene, camera, 8, 8), Error);
  scene.planes.clear();
  EXPECT_THROW(renderAnalyticReference(scene, camera, 8, 8, {.samplesPerPixel = 0}), Error);
  EXPECT_THROW(renderAnalyticReference(scene, camera, 0, 8), Error);
  EXPECT_THROW(renderAnalyticReference(scene, camera, 8, 8, {.background = Color(-1.0f)}), Error);
}

// A render says how much its last doubling of samples changed it: exactly the RMSE between it
// and the render with half the samples (the first half of the pattern is that render).
TEST(AnalyticReference, ConvergenceIsTheChangeFromHalfTheSamples) {
  const AnalyticScene scene = litSphereScene();
  const Camera camera = fitCamera(makeUvSphere(8, 5), {0.2, -0.3, -1});
  const auto render = [&](int samples) {
    return renderAnalyticReference(scene, camera, 64, 48, {.samplesPerPixel = samples});
  };
  const ReferenceRender full = render(16);
  ASSERT_TRUE(full.convergence.has_value());
  EXPECT_EQ(*full.convergence, compareImages(full.image, render(8).image).rmse);
  EXPECT_GT(*full.convergence, 0.0);
  EXPECT_FALSE(render(1).convergence.has_value());
}

// Converged: doubling the samples changes the image by less than 0.25/255 RMSE. The change
// is the silhouette's (interior shading converges much faster), so the count needed falls as
// the image grows: 256 here at a quarter of 1080p; 1080p itself needs 64 (README).
TEST(AnalyticReference, ConvergesAsSamplesDouble) {
  const Camera camera = fitCamera(makeUvSphere(8, 5), {0.2, -0.3, -1});
  const ReferenceRender render =
      renderAnalyticReference(litSphereScene(), camera, 480, 270, {.samplesPerPixel = 256});
  std::printf("128 -> 256 samples at 480x270: RMSE change %.4f / 255\n", *render.convergence);
  EXPECT_LT(*render.convergence, 0.25);
}

// The first real measurement of error against tessellation: a UV sphere flat-shaded by the
// rasterizer, against the exact sphere, at growing resolution.
TEST(AnalyticReference, FlatSphereErrorFallsWithTessellation) {
  const AnalyticScene scene = litSphereScene();
  const int width = 320, height = 240;
  const Camera camera = fitCamera(makeUvSphere(8, 5), {0.2, -0.3, -1});
  const FloatImage reference =
      renderAnalyticReference(scene, camera, width, height, {.samplesPerPixel = 64}).image;
  double previousRmse = INFINITY, previousInterior = INFINITY;
  for (const int segments : {8, 16, 32, 64, 128}) {
    const Mesh sphere = makeUvSphere(segments, segments / 2 + 1);
    Scene flat = testing::oneMeshScene(sphere.view(), scene.spheres[0].material, scene.lights);
    const auto rendered = testing::renderScene(flat, camera, width, height);
    const ImageError error = compareImages(reference, toFloatImage(rendered.framebuffer));
    std::printf(
        "%4d segments: RMSE %6.3f, interior %6.3f, max %5.1f, PSNR %5.2f dB, SSIM %.4f, "
        "silhouette %.2f %%\n",
        segments, error.rmse, error.interiorRmse, error.maxError, error.psnr, *error.ssim,
        100.0 * error.silhouetteFraction);
    EXPECT_LT(error.rmse, previousRmse) << segments << " segments";
    EXPECT_LT(error.interiorRmse, previousInterior) << segments << " segments";
    previousRmse = error.rmse;
    previousInterior = error.interiorRmse;
  }
}

}  // namespace
}  // namespace facet
