// Quality modes (QualityRenderer.h): Gouraud and Phong against closed forms and the exact
// sphere, supersampling on silhouettes, the flat-shading bound (FlatErrorBound.h) against the
// Phong image, the adaptive budget, and the same bytes for any thread count in every mode.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../support/ReferenceScenes.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "facet/AnalyticReference.h"
#include "facet/Error.h"
#include "facet/ImageMetrics.h"
#include "facet/QualityRenderer.h"

namespace facet {
namespace {

using testing::fitCamera;
using testing::makeUvSphere;

struct Output {
  Framebuffer framebuffer;
  QualityStats stats;
  std::vector<float> estimate;
};

Output renderQuality(const Scene& scene, const Camera& camera, int width, int height,
                     const QualitySettings& settings, int threads = 2,
                     std::span<const ShadingMesh> shading = {}) {
  Renderer renderer;
  renderer.setThreadCount(threads);
  QualityRenderer quality(renderer);
  Output out{Framebuffer(width, height), {}, {}};
  out.stats = quality.render(scene, shading, camera, out.framebuffer, settings);
  out.estimate.assign(quality.errorEstimate().begin(), quality.errorEstimate().end());
  return out;
}

int channelDifference(Rgba8 a, Rgba8 b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

// The lit sphere the reference tests use, as a mesh scene and as the exact sphere.
Scene sphereScene(const Mesh& sphere) {
  return testing::oneMeshScene(sphere.view(), testing::shinyMaterial(), testing::twoLights());
}
AnalyticScene exactSphere() {
  AnalyticScene scene;
  scene.spheres.push_back({glm::dvec3(0.0), 1.0, testing::shinyMaterial()});
  scene.lights = testing::twoLights();
  return scene;
}
Camera sphereCamera() {
  return fitCamera(makeUvSphere(8, 5), {0.2, -0.3, -1});
}

TEST(QualityRenderer, FlatOneSampleIsTheRendererWithOrWithoutEstimate) {
  const Mesh sphere = makeUvSphere(24, 13);
  const Scene scene = sphereScene(sphere);
  const Camera camera = sphereCamera();
  const auto plain = testing::renderScene(scene, camera, 80, 60);
  for (const bool estimate : {false, true}) {
    const Output out = renderQuality(scene, camera, 80, 60, {.estimateError = estimate});
    EXPECT_TRUE(std::ranges::equal(out.framebuffer.color(), plain.framebuffer.color()));
    EXPECT_TRUE(std::ranges::equal(out.framebuffer.depth(), plain.framebuffer.depth()));
    EXPECT_TRUE(std::ranges::equal(out.framebuffer.polygonId(), plain.framebuffer.polygonId()));
    EXPECT_EQ(out.estimate.empty(), !estimate);
    EXPECT_EQ(out.stats.samplesReshaded, 0u);
  }
}

TEST(QualityRenderer, SameBytesForAnyThreadCountInEveryMode) {
  const Mesh sphere = makeUvSphere(20, 11);
  const Mesh box = testing::makeBox({-1.6, -1.2, -0.5}, {-0.9, 1.2, 0.4});
  Scene scene = sphereScene(sphere);
  scene.meshes.push_back({box.view(), Material{}});
  const Camera camera = sphereCamera();
  std::vector<QualitySettings> modes;
  for (const int samples : {1, 4, 16}) {
    for (const Shading shading : {Shading::Flat, Shading::Gouraud, Shading::Phong})
      modes.push_back({shading, samples, std::nullopt, true});
    modes.push_back({Shading::Flat, samples, 6.0, true});
  }
  for (const QualitySettings& mode : modes) {
    const Output one = renderQuality(scene, camera, 72, 40, mode, 1);
    for (const int threads : {2, 8}) {
      const Output many = renderQuality(scene, camera, 72, 40, mode, threads);
      const char* name = mode.maximumError ? "adaptive" : toString(mode.shading);
      EXPECT_TRUE(std::ranges::equal(one.framebuffer.color(), many.framebuffer.color()))
          << name << " x" << mode.samplesPerPixel << ", " << threads << " threads";
      EXPECT_TRUE(std::ranges::equal(one.framebuffer.depth(), many.framebuffer.depth())) << name;
      EXPECT_TRUE(std::ranges::equal(one.framebuffer.polygonId(), many.framebuffer.polygonId()))
          << name;
      EXPECT_EQ(one.estimate, many.estimate) << name;
      EXPECT_EQ(one.stats.samplesReshaded, many.stats.samplesReshaded) << name;
    }
  }
}

// Colors given at the points, unlit (ambient light 1, so C = Cd): Gouraud and Phong both show
// the colors interpolated with perspective-correct weights, which for a point of the plane
// z = 0 are its barycentric coordinates in the triangle.
TEST(QualityRenderer, PointColorsAreInterpolatedPerspectiveCorrectly) {
  Mesh triangle;
  triangle.addPoint({-1.0, -1.0, 0.0});
  triangle.addPoint({1.5, -0.8, 0.0});
  triangle.addPoint({-0.6, 1.4, 0.0});
  triangle.addPolygon({0, 1, 2});
  const std::vector<Rgba8> colors = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}};
  MeshView view = triangle.view();
  view.pointColors = colors;
  LightSet unlit;
  unlit.ambient = {Color(1.0f), 1.0};
  const Scene scene = testing::oneMeshScene(view, Material{}, unlit);
  Camera camera;
  camera.position = {0.4, -2.0, 1.6};  // oblique: affine interpolation in the window would fail
  camera.focalPoint = {0.0, 0.0, 0.0};
  camera.viewAngleDegrees = 70.0;
  const int width = 96, height = 80;
  const CameraRays rays(camera, width, height);
  for (const Shading shading : {Shading::Gouraud, Shading::Phong}) {
    const Output out = renderQuality(scene, camera, width, height, {.shading = shading});
    int checked = 0, worst = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        if (out.framebuffer.polygonIdAt(x, y) < 0) continue;
        const Ray ray = rays.through({x + 0.5, y + 0.5});
        const glm::dvec3 p = ray.origin - ray.direction * (ray.origin.z / ray.direction.z);
        // Barycentric coordinates of p in the triangle, in the plane.
        const glm::dvec2 a(-1.0, -1.0), b(1.5, -0.8), c(-0.6, 1.4);
        const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        const double wb = ((p.x - a.x) * (c.y - a.y) - (c.x - a.x) * (p.y - a.y)) / area;
        const double wc = ((b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y)) / area;
        const double wa = 1.0 - wb - wc;
        if (std::min({wa, wb, wc}) < 0.0) continue;  // center just outside: clamped, skip
        const Rgba8 expected = toRgba8(Color(wa, wb, wc));
        worst = std::max(worst, channelDifference(out.framebuffer.colorAt(x, y), expected));
        ++checked;
      }
    }
    EXPECT_GT(checked, 1000) << toString(shading);
    EXPECT_LE(worst, 1) << toString(shading);
  }
}

// A box's corners keep their faces' normals (every edge is sharp at the 30° feature angle):
// under a directional light and a parallel view, Phong is flat, and the bound says so.
TEST(QualityRenderer, PhongOfSharpFacesIsFlatAndTheBoundIsZero) {
  const Mesh box = testing::makeBox({-1, -1, -1}, {1, 1, 1});
  Material material = testing::shinyMaterial();
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1, -2, -3}, Color(0.9f)});
  const Scene scene = testing::oneMeshScene(box.view(), material, lights);
  Camera camera = fitCamera(box, {-0.5, -0.6, -1});
  camera.parallelProjection = true;
  camera.parallelScale = 2.0;
  const Output flat = renderQuality(scene, camera, 64, 64, {.estimateError = true});
  const Output phong = renderQuality(scene, camera, 64, 64, {.shading = Shading::Phong});
  int worst = 0, interior = 0;
  for (int y = 1; y + 1 < 64; ++y) {
    for (int x = 1; x + 1 < 64; ++x) {
      worst = std::max(worst, channelDifference(flat.framebuffer.colorAt(x, y),
                                                phong.framebuffer.colorAt(x, y)));
      // Inside a face the estimate is the bound (0) plus rounding; across an edge it also
      // counts the neighbour's color, which the converged image mixes in.
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          inside &=
              flat.framebuffer.polygonIdAt(x + dx, y + dy) == flat.framebuffer.polygonIdAt(x, y);
      if (!inside || flat.framebuffer.polygonIdAt(x, y) < 0) continue;
      EXPECT_EQ(flat.estimate[flat.framebuffer.indexOf(x, y)], 0.5f) << x << ", " << y;
      ++interior;
    }
  }
  EXPECT_LE(worst, 1);
  EXPECT_GT(interior, 1000);
  EXPECT_GT(flat.stats.predictedMaxError, 50.0);  // the box's edges
  EXPECT_GT(phong.stats.samplesReshaded, 1000u);
}

// Flat against the exact sphere: Phong and Gouraud are below it at every tessellation, and
// Phong below Gouraud; 16 samples per pixel are below 1 on the silhouette.
TEST(QualityRenderer, SmoothShadingBeatsFlatOnTheExactSphere) {
  const int width = 160, height = 120;
  const Camera camera = sphereCamera();
  const FloatImage reference =
      renderAnalyticReference(exactSphere(), camera, width, height, {.samplesPerPixel = 64}).image;
  for (const int segments : {12, 24, 48}) {
    const Mesh sphere = makeUvSphere(segments, segments / 2 + 1);
    const Scene scene = sphereScene(sphere);
    const auto error = [&](Shading shading) {
      const Output out = renderQuality(scene, camera, width, height, {.shading = shading});
      return compareImages(reference, toFloatImage(out.framebuffer)).interiorRmse;
    };
    const double flat = error(Shading::Flat), gouraud = error(Shading::Gouraud),
                 phong = error(Shading::Phong);
    std::printf("%3d segments: interior RMSE flat %.3f, Gouraud %.3f, Phong %.3f\n", segments, flat,
                gouraud, phong);
    EXPECT_LT(phong, flat) << segments;
    EXPECT_LT(phong, gouraud) << segments;
    // Coarser, lighting only the corners misses the highlight about as much as flat does.
    if (segments >= 24) {
      EXPECT_LT(gouraud, flat) << segments;
    }
  }
}

// RMSE over the pixels the exact sphere covers only in part.
double silhouetteRmse(const FloatImage& reference, const Framebuffer& image) {
  const ImageError error = compareImages(reference, toFloatImage(image));
  double squares = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < reference.pixelCount(); ++i) {
    if (reference.coverage[i] > 0.0f && reference.coverage[i] < 1.0f) {
      squares += double(error.errorImage[i]) * error.errorImage[i];
      ++count;
    }
  }
  return std::sqrt(squares / double(count));
}

TEST(QualityRenderer, SixteenSamplesBeatOneOnTheSilhouette) {
  const int width = 120, height = 90;
  const Camera camera = sphereCamera();
  const FloatImage reference =
      renderAnalyticReference(exactSphere(), camera, width, height, {.samplesPerPixel = 256}).image;
  const Mesh sphere = makeUvSphere(64, 33);
  const Scene scene = sphereScene(sphere);
  double previous = INFINITY;
  for (const int samples : {1, 4, 16}) {
    const Output out = renderQuality(scene, camera, width, height,
                                     {.shading = Shading::Phong, .samplesPerPixel = samples});
    const double rmse = silhouetteRmse(reference, out.framebuffer);
    std::printf("%2d samples: silhouette RMSE %.2f\n", samples, rmse);
    EXPECT_LT(rmse, previous) << samples;
    previous = rmse;
  }
}

// The estimate bounds flat against Phong at the same samples: each flat pixel is within its
// estimate (plus 0.5 for rounding the Phong image) of the Phong pixel, on every pixel.
TEST(QualityRenderer, EstimateBoundsFlatAgainstPhongOnEveryPixel) {
  const Camera camera = sphereCamera();
  for (const int segments : {8, 16, 32, 64}) {
    const Mesh sphere = makeUvSphere(segments, segments / 2 + 1);
    const Scene scene = sphereScene(sphere);
    for (const int samples : {1, 4}) {
      const Output flat =
          renderQuality(scene, camera, 96, 72, {.samplesPerPixel = samples, .estimateError = true});
      const Output phong = renderQuality(scene, camera, 96, 72,
                                         {.shading = Shading::Phong, .samplesPerPixel = samples});
      double worstRatio = 0.0, measuredSquares = 0.0;
      std::size_t covered = 0;
      for (std::size_t i = 0; i < flat.framebuffer.pixelCount(); ++i) {
        if (flat.framebuffer.polygonId()[i] < 0) continue;
        const int difference =
            channelDifference(flat.framebuffer.color()[i], phong.framebuffer.color()[i]);
        EXPECT_LE(difference, flat.estimate[i] + 0.5)
            << segments << " segments, " << samples << " samples, pixel " << i;
        worstRatio = std::max(worstRatio, difference / (flat.estimate[i] + 0.5));
        measuredSquares += double(difference) * difference;
        ++covered;
      }
      std::printf(
          "%2d segments x%d: predicted RMSE %6.2f max %6.2f; measured against Phong "
          "RMSE %6.2f; tightest pixel at %.0f %% of its bound\n",
          segments, samples, flat.stats.predictedRmse, flat.stats.predictedMaxError,
          std::sqrt(measuredSquares / double(covered)), 100.0 * worstRatio);
    }
  }
}

TEST(QualityRenderer, AdaptiveStaysWithinItsBudgetOfPhongAndKeepsFlatFacesFlat) {
  const Mesh sphere = makeUvSphere(48, 25);
  const Mesh box = testing::makeBox({-1.3, -1.0, -0.2}, {-0.4, 0.2, 1.2});
  // A directional light: flat faces are then exactly flat under Phong too (their bound is 0).
  LightSet light;
  light.lights.push_back(DirectionalLight{{-1, -1, -2}, Color(0.8f)});
  Scene scene = testing::oneMeshScene(sphere.view(), testing::shinyMaterial(), light);
  scene.meshes.push_back({box.view(), testing::shinyMaterial()});
  const Camera camera = sphereCamera();
  const Output phong = renderQuality(scene, camera, 96, 64, {.shading = Shading::Phong});
  std::size_t previousReshaded = 0;
  for (const double budget : {8.0, 4.0, 2.0, 1.0}) {
    const Output adaptive = renderQuality(scene, camera, 96, 64, {.maximumError = budget});
    int worst = 0;
    for (std::size_t i = 0; i < phong.framebuffer.pixelCount(); ++i) {
      worst = std::max(
          worst, channelDifference(adaptive.framebuffer.color()[i], phong.framebuffer.color()[i]));
    }
    std::printf("budget %.0f: %zu of %zu samples Phong-shaded, largest difference to Phong %d\n",
                budget, adaptive.stats.samplesReshaded, phong.stats.samplesReshaded, worst);
    EXPECT_LE(worst, budget + 0.5) << budget;
    EXPECT_LT(adaptive.stats.samplesReshaded, phong.stats.samplesReshaded) << budget;
    EXPECT_GE(adaptive.stats.samplesReshaded, previousReshaded) << budget;
    EXPECT_LT(adaptive.stats.polygonsReshaded, phong.stats.polygonsReshaded) << budget;
    previousReshaded = adaptive.stats.samplesReshaded;
  }
}

// A square facing the camera whose scalars run from s = 0 on its left edge to s = 1 on its
// right, mapped per sample through a four-entry table (InterpolateScalarsBeforeMapping): each
// pixel shows the entry its own s falls in — the bands, not a blend of the corner colors.
// Unlit (C = Cd) and under a half-intensity headlight (C = Cd / 2: Gouraud's black and white
// corner lighting, interpolated, is exact for every Cd).
TEST(QualityRenderer, ScalarsMappedPerSampleShowTheTableEntryOfTheirValue) {
  Mesh square;
  for (const auto& [x, y] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}})
    square.addPoint({x, y, 0.0});
  square.addPolygon({0, 1, 2, 3});
  const std::vector<float> st = {0.0f, 0.49f, 1.0f, 0.49f, 1.0f, 0.49f, 0.0f, 0.49f};
  const std::vector<Rgba8> texels = {
      {255, 0, 0, 255},     {0, 255, 0, 255},     {0, 0, 255, 255},     {255, 255, 255, 255},
      {128, 128, 128, 255}, {128, 128, 128, 255}, {128, 128, 128, 255}, {128, 128, 128, 255}};
  MeshView view = square.view();
  view.scalarTexture = {st, texels, 4};
  view.pointColors = std::vector<Rgba8>(4, Rgba8{9, 9, 9, 255});  // the texture wins
  LightSet unlit;
  unlit.ambient = {Color(1.0f), 1.0};
  LightSet headlight;
  headlight.ambient = {Color(0.0f), 0.0};
  headlight.lights.push_back(DirectionalLight{{0, 0, -1}, Color(1.0f), 0.5});
  Camera camera;
  camera.position = {0.0, 0.0, 2.0};
  camera.viewAngleDegrees = 70.0;
  const int width = 101, height = 64;
  const CameraRays rays(camera, width, height);
  for (const auto& [lights, scale] : {std::pair{unlit, 1.0f}, {headlight, 0.5f}}) {
    const Scene scene = testing::oneMeshScene(view, Material{}, lights);
    for (const Shading shading : {Shading::Gouraud, Shading::Phong}) {
      const Output out = renderQuality(scene, camera, width, height, {.shading = shading});
      int checked = 0, wrong = 0;
      std::vector<int> seen(4, 0);
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          if (out.framebuffer.polygonIdAt(x, y) < 0) continue;
          const Ray ray = rays.through({x + 0.5, y + 0.5});
          const double s =
              (ray.origin.x - ray.direction.x * ray.origin.z / ray.direction.z + 1) / 2;
          const double texel = 4.0 * s;
          if (std::abs(texel - std::round(texel)) < 1e-6 || s < 0.0 || s > 1.0) continue;
          const std::size_t entry = std::min<std::size_t>(3, static_cast<std::size_t>(texel));
          const Rgba8 t = texels[entry];
          const Rgba8 expected = toRgba8(scale * Color(t.r, t.g, t.b) / 255.0f);
          const Rgba8 got = out.framebuffer.colorAt(x, y);
          if (channelDifference(got, expected) > (scale == 1.0f ? 0 : 1)) {
            if (wrong++ < 5) {
              std::printf("%s (%d, %d): s %.4f, got %d %d %d, expected %d %d %d\n",
                          toString(shading), x, y, s, got.r, got.g, got.b, expected.r, expected.g,
                          expected.b);
            }
          }
          ++seen[entry];
          ++checked;
        }
      }
      EXPECT_GT(checked, 2000) << toString(shading);
      EXPECT_EQ(wrong, 0) << toString(shading) << " light scale " << scale;
      for (const int count : seen)
        EXPECT_GT(count, 300) << toString(shading);
    }
  }
}

// The flat-shading bound sees every color a polygon's scalars can map to: a table black at
// both ends and white in the middle gives a polygon whose corners are black the whole range.
TEST(QualityRenderer, ShadingMeshColorRangeSpansTheTexelsBetweenTheCorners) {
  Mesh triangle;
  triangle.addPoint({0, 0, 0});
  triangle.addPoint({1, 0, 0});
  triangle.addPoint({0, 1, 0});
  triangle.addPolygon({0, 1, 2});
  const std::vector<float> st = {0.1f, 0.49f, 0.9f, 0.49f, 0.1f, 0.49f};
  const std::vector<Rgba8> texels = {{0, 0, 0, 255},   {255, 255, 255, 255}, {0, 0, 0, 255},
                                     {255, 0, 0, 255}, {255, 0, 0, 255},     {255, 0, 0, 255}};
  MeshView view = triangle.view();
  view.scalarTexture = {st, texels, 3};
  const ShadingMesh shading(view);
  EXPECT_TRUE(shading.shapes[0].pointColors);
  EXPECT_EQ(shading.shapes[0].cornerColorLow, Color(0.0f));
  EXPECT_EQ(shading.shapes[0].cornerColorHigh, Color(1.0f));  // the middle texel, not a corner's
}

// Each mesh with its own shading (a VTK scene's actors): the flat mesh's pixels are the
// Renderer's, the Phong mesh's are those of an all-Phong render.
TEST(QualityRenderer, EachMeshCanHaveItsOwnShading) {
  const Mesh sphere = makeUvSphere(20, 11);
  const Mesh other = testing::makeBox({-1.6, -1.2, -0.5}, {-0.9, 1.2, 0.4});
  Scene scene = sphereScene(sphere);
  scene.meshes.push_back({other.view(), testing::shinyMaterial()});
  const Camera camera = sphereCamera();
  const Output flat = renderQuality(scene, camera, 80, 60, {});
  const Output phong = renderQuality(scene, camera, 80, 60, {.shading = Shading::Phong});
  const Output mixed =
      renderQuality(scene, camera, 80, 60, {.meshShading = {Shading::Phong, Shading::Flat}});
  const auto sphereIds = static_cast<std::int32_t>(sphere.polygonCount());
  int differ = 0;
  for (std::size_t i = 0; i < mixed.framebuffer.pixelCount(); ++i) {
    const std::int32_t id = mixed.framebuffer.polygonId()[i];
    const Output& expected = id < sphereIds ? phong : flat;
    EXPECT_EQ(mixed.framebuffer.color()[i], expected.framebuffer.color()[i]) << i << " id " << id;
    differ += !(flat.framebuffer.color()[i] == phong.framebuffer.color()[i]);
  }
  EXPECT_GT(differ, 100);  // the two modes differ, so the test tells them apart
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer framebuffer(16, 16);
  EXPECT_THROW(quality.render(scene, {}, camera, framebuffer, {.meshShading = {Shading::Phong}}),
               Error);
}

TEST(QualityRenderer, BadSettingsAndMismatchedMeshesAreNamed) {
  const Mesh sphere = makeUvSphere(8, 5);
  const Scene scene = sphereScene(sphere);
  const Camera camera = sphereCamera();
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer framebuffer(16, 16);
  const auto message = [&](const QualitySettings& settings,
                           std::span<const ShadingMesh> shading = {}) {
    try {
      quality.render(scene, shading, camera, framebuffer, settings);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({.samplesPerPixel = 2}).find("samplesPerPixel is 2"), std::string::npos);
  EXPECT_NE(message({.maximumError = -1.0}).find("maximumError"), std::string::npos);
  const std::vector<ShadingMesh> two(2);
  EXPECT_NE(message({.shading = Shading::Phong}, two).find("2 ShadingMeshes for 1"),
            std::string::npos);
  Framebuffer huge(5000, 8);
  EXPECT_THROW(quality.render(scene, {}, camera, huge, {.samplesPerPixel = 16}), Error);
  MeshView badColors = sphere.view();
  const std::vector<Rgba8> three(3);
  badColors.pointColors = three;
  EXPECT_THROW(ShadingMesh{badColors}, Error);
  MeshView badTexture = sphere.view();
  const std::vector<float> coordinates(2 * sphere.points.size(), 0.5f);
  badTexture.scalarTexture = {coordinates, three, 2};  // 3 texels for a 2 × 2 table
  try {
    ShadingMesh{badTexture};
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scalarTexture"), std::string::npos) << e.what();
  }
}

// Flat shading with the estimate keeps per mesh version only each polygon's normal, extent and
// normal spread (rounded outward to float): the estimate is that of a ShadingMesh's shapes
// to float precision, and never below it.
// A QualityRenderer can be kept in a container or returned (no lock among its members).
static_assert(std::is_nothrow_move_constructible_v<QualityRenderer>);

// A moved QualityRenderer renders on, its kept extents and estimate spaces with it.
TEST(QualityRenderer, AMovedRendererGivesTheSameEstimate) {
  const Mesh sphere = makeUvSphere(24, 13);
  Scene scene = sphereScene(sphere);
  scene.meshes[0].mesh.version = 1;
  const Camera camera = sphereCamera();
  const QualitySettings settings{.estimateError = true};
  const Output fresh = renderQuality(scene, camera, 80, 60, settings);
  Renderer renderer;
  QualityRenderer first(renderer);
  Framebuffer framebuffer(80, 60);
  first.render(scene, {}, camera, framebuffer, settings);
  QualityRenderer moved(std::move(first));
  renderer.forgetPreviousFrame();  // found again, in the spaces moved along
  const QualityStats stats = moved.render(scene, {}, camera, framebuffer, settings);
  EXPECT_FALSE(stats.estimateKept);
  EXPECT_EQ(stats.predictedRmse, fresh.stats.predictedRmse);
  EXPECT_TRUE(std::ranges::equal(moved.errorEstimate(), fresh.estimate));
}

TEST(QualityRenderer, EstimateWithoutShadingMeshesIsTheShadingMeshOne) {
  const Mesh sphere = makeUvSphere(24, 13);
  Scene scene = sphereScene(sphere);
  scene.meshes[0].mesh.version = 1;
  const Camera camera = sphereCamera();
  const std::vector<ShadingMesh> shading{ShadingMesh(sphere.view())};
  for (const int samples : {1, 4}) {
    const QualitySettings settings{.samplesPerPixel = samples, .estimateError = true};
    const Output kept = renderQuality(scene, camera, 80, 60, settings);
    const Output given = renderQuality(scene, camera, 80, 60, settings, 2, shading);
    ASSERT_EQ(kept.estimate.size(), given.estimate.size());
    float largest = 0.0f;
    for (std::size_t i = 0; i < kept.estimate.size(); ++i) {
      EXPECT_GE(kept.estimate[i], given.estimate[i] - 1e-4f) << "pixel " << i;
      largest = std::max(largest, std::abs(kept.estimate[i] - given.estimate[i]));
    }
    EXPECT_LT(largest, 1e-3f) << samples << " samples";
    EXPECT_NEAR(kept.stats.predictedRmse, given.stats.predictedRmse, 1e-3);
    EXPECT_TRUE(std::ranges::equal(kept.framebuffer.color(), given.framebuffer.color()));
  }
}

// The estimate a flat render takes in its shade and resolve phases (EstimateHook.h) is the
// separate passes' to the byte: bounds from the shade's batches against bounds from each
// polygon's corners one by one, pixel estimates per resolve band against the pass over the
// finished image (at 4 samples per pixel the shade's bounds and that pass). The separate passes run
// when only the background changed and the image is wanted where the last render kept none. Every
// shade routine that bounds: lit at centers (a point light) or by directions only, lit in batches
// or polygon by polygon (an attenuated point light), a material the bound's batches take or not
// (specular).
TEST(QualityRenderer, FusedEstimateIsTheSeparatePassesBytes) {
  const Mesh sphere = makeUvSphere(24, 13);
  LightSet directional, attenuated;
  directional.lights.push_back(DirectionalLight{{-1, -1, -2}, Color(0.8f)});
  attenuated.lights.push_back(
      PointLight{{2, 1, 3}, Color(0.9f), 1.0, QuadraticAttenuation{1.0, 0.2, 0.05}});
  Material matte;
  matte.diffuse = 0.9;
  const std::pair<const char*, Scene> scenes[] = {
      {"two lights, specular", sphereScene(sphere)},
      {"two lights, matte", testing::oneMeshScene(sphere.view(), matte, testing::twoLights())},
      {"directional, matte", testing::oneMeshScene(sphere.view(), matte, directional)},
      {"attenuated, matte", testing::oneMeshScene(sphere.view(), matte, attenuated)}};
  const Camera camera = sphereCamera();
  for (const int samples : {1, 4}) {  // 4: bounds by the shade, the pass over the samples apart
    for (auto [name, scene] : scenes) {
      scene.meshes[0].mesh.version = 1;
      const QualitySettings image{.samplesPerPixel = samples, .estimateError = true};
      const Output fused = renderQuality(scene, camera, 80, 60, image);
      Renderer renderer;
      QualityRenderer quality(renderer);
      Framebuffer framebuffer(80, 60);
      QualitySettings summary = image;
      summary.errorEstimateImage = false;
      quality.render(scene, {}, camera, framebuffer, summary);
      renderer.setBackground(Color(0.2f, 0.3f, 0.4f));
      const QualityStats separate = quality.render(scene, {}, camera, framebuffer, image);
      ASSERT_EQ(separate.render.plan.path, RenderPath::Resolve) << name;
      ASSERT_FALSE(separate.estimateKept) << name;
      EXPECT_GT(fused.stats.predictedMaxError, 0.5) << name;
      EXPECT_EQ(fused.stats.predictedRmse, separate.predictedRmse) << name;
      EXPECT_EQ(fused.stats.predictedMaxError, separate.predictedMaxError) << name;
      const std::span<const float> passes = quality.errorEstimate();
      ASSERT_EQ(fused.estimate.size(), passes.size()) << name;
      std::size_t differ = 0;
      for (std::size_t i = 0; i < passes.size(); ++i)
        differ += fused.estimate[i] != passes[i];
      EXPECT_EQ(differ, 0u) << name << ", " << samples << " samples: pixels whose estimate differs";
    }
  }
}

// The resolve estimates bands of 32 rows, 8 at a time, and takes the rows either side of a band
// by polygon id: at heights that put a band's or a step's edge on every row position (1 row,
// not a multiple of 8 or 32, 1030) and widths with SIMD tails, with more threads than bands,
// its estimate and summary are the pass over the finished image's to the byte.
TEST(QualityRenderer, FusedEstimateIsTheSeparatePassesAtEveryBandEdge) {
  const Mesh sphere = makeUvSphere(24, 13);
  Scene scene = sphereScene(sphere);
  scene.meshes[0].mesh.version = 1;
  const Camera camera = sphereCamera();
  const QualitySettings image{.samplesPerPixel = 1, .estimateError = true};
  QualitySettings summary = image;
  summary.errorEstimateImage = false;
  const std::pair<int, int> sizes[] = {{37, 1},  {37, 2},  {37, 7},     {37, 9},
                                       {37, 31}, {37, 33}, {37, 41},    {37, 63},
                                       {37, 65}, {37, 70}, {1031, 1030}};
  for (const auto& [width, height] : sizes) {
    Renderer renderer;
    QualityRenderer quality(renderer);
    Framebuffer framebuffer(width, height);
    const QualityStats summed = quality.render(scene, {}, camera, framebuffer, summary);
    renderer.setBackground(Color(0.2f, 0.3f, 0.4f));  // the separate passes, the image made
    const QualityStats separate = quality.render(scene, {}, camera, framebuffer, image);
    ASSERT_FALSE(separate.estimateKept) << width << " x " << height;
    const std::span<const float> passes = quality.errorEstimate();
    EXPECT_GT(separate.predictedMaxError, 0.5) << width << " x " << height;
    EXPECT_EQ(summed.predictedRmse, separate.predictedRmse) << width << " x " << height;
    EXPECT_EQ(summed.predictedMaxError, separate.predictedMaxError) << width << " x " << height;
    for (const int threads : {1, 8}) {
      const Output fused = renderQuality(scene, camera, width, height, image, threads);
      EXPECT_EQ(fused.stats.predictedRmse, separate.predictedRmse)
          << width << " x " << height << ", " << threads << " threads";
      EXPECT_EQ(fused.stats.predictedMaxError, separate.predictedMaxError)
          << width << " x " << height << ", " << threads << " threads";
      EXPECT_TRUE(std::ranges::equal(fused.estimate, passes))
          << width << " x " << height << ", " << threads << " threads";
    }
  }
}

// Without the image (the filter's EstimateError without ErrorEstimateArray), the estimate's
// summary is the same numbers, and a new background keeps it.
TEST(QualityRenderer, EstimateSummaryWithoutTheImageIsTheSame) {
  const Mesh sphere = makeUvSphere(24, 13);
  Scene scene = sphereScene(sphere);
  scene.meshes[0].mesh.version = 1;
  const Camera camera = sphereCamera();
  for (const int samples : {1, 4}) {
    const QualitySettings withImage{.samplesPerPixel = samples, .estimateError = true};
    QualitySettings summary = withImage;
    summary.errorEstimateImage = false;
    const Output full = renderQuality(scene, camera, 80, 60, withImage);
    Renderer renderer;
    QualityRenderer quality(renderer);
    Framebuffer framebuffer(80, 60);
    const QualityStats stats = quality.render(scene, {}, camera, framebuffer, summary);
    EXPECT_TRUE(quality.errorEstimate().empty());
    EXPECT_GT(stats.predictedRmse, 0.0);
    EXPECT_EQ(stats.predictedRmse, full.stats.predictedRmse) << samples << " samples";
    EXPECT_EQ(stats.predictedMaxError, full.stats.predictedMaxError) << samples << " samples";

    renderer.setBackground(Color(0.2f, 0.3f, 0.4f));
    const QualityStats recolored = quality.render(scene, {}, camera, framebuffer, summary);
    EXPECT_EQ(recolored.render.plan.path, RenderPath::Resolve);
    EXPECT_EQ(recolored.predictedRmse, stats.predictedRmse);
    EXPECT_TRUE(quality.errorEstimate().empty());

    renderer.setBackground(Color(0.0f));  // the image asked for again: made, not kept
    quality.render(scene, {}, camera, framebuffer, withImage);
    EXPECT_TRUE(std::ranges::equal(quality.errorEstimate(), full.estimate));
  }
}

// The estimate follows the mesh's versions, lights and camera, and a render that only
// recolors the frame (a new background) keeps it: every time what a fresh renderer gives.
TEST(QualityRenderer, EstimateFollowsVersionsAndIsKeptWhenOnlyTheBackgroundChanges) {
  Mesh sphere = makeUvSphere(24, 13);
  Scene scene = sphereScene(sphere);
  scene.meshes[0].mesh.version = 1;
  const Camera camera = sphereCamera();
  const QualitySettings settings{.estimateError = true};
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer framebuffer(80, 60);
  const auto render = [&](const Scene& s) {
    const QualityStats stats = quality.render(s, {}, camera, framebuffer, settings);
    const Output fresh = renderQuality(s, camera, 80, 60, settings);
    EXPECT_TRUE(std::ranges::equal(quality.errorEstimate(), fresh.estimate));
    EXPECT_EQ(stats.predictedRmse, fresh.stats.predictedRmse);
    EXPECT_EQ(stats.predictedMaxError, fresh.stats.predictedMaxError);
    return stats;
  };
  const QualityStats first = render(scene);
  EXPECT_FALSE(first.estimateKept);
  const std::vector<float> firstEstimate(quality.errorEstimate().begin(),
                                         quality.errorEstimate().end());
  ASSERT_FALSE(firstEstimate.empty());
  ASSERT_GT(first.predictedMaxError, 0.0);

  // A new background: the frame is recolored, the estimate kept — not lost, not found again
  // (estimateKept), and not the estimate of a frame shown on the new background either: the
  // estimate ignores the background, so a fresh renderer finds the same numbers.
  renderer.setBackground(Color(0.2f, 0.3f, 0.4f));
  const QualityStats recolored = quality.render(scene, {}, camera, framebuffer, settings);
  EXPECT_EQ(recolored.render.plan.path, RenderPath::Resolve);
  EXPECT_TRUE(recolored.estimateKept);
  EXPECT_TRUE(std::ranges::equal(quality.errorEstimate(), firstEstimate));
  EXPECT_EQ(recolored.predictedRmse, first.predictedRmse);
  EXPECT_EQ(recolored.predictedMaxError, first.predictedMaxError);
  // Asked for the summary alone on the next recoloring: the kept estimate serves it (not
  // found again), its image goes.
  renderer.setBackground(Color(0.1f, 0.1f, 0.1f));
  QualitySettings summary = settings;
  summary.errorEstimateImage = false;
  const QualityStats summarized = quality.render(scene, {}, camera, framebuffer, summary);
  EXPECT_EQ(summarized.render.plan.path, RenderPath::Resolve);
  EXPECT_TRUE(summarized.estimateKept);
  EXPECT_TRUE(quality.errorEstimate().empty());
  EXPECT_EQ(summarized.predictedRmse, first.predictedRmse);
  EXPECT_EQ(summarized.predictedMaxError, first.predictedMaxError);
  // The image asked for again on a recoloring: the kept summary cannot give it, so it is
  // found again (and is the first frame's).
  renderer.setBackground(Color(0.3f, 0.1f, 0.1f));
  const QualityStats imaged = quality.render(scene, {}, camera, framebuffer, settings);
  EXPECT_EQ(imaged.render.plan.path, RenderPath::Resolve);
  EXPECT_FALSE(imaged.estimateKept);
  EXPECT_TRUE(std::ranges::equal(quality.errorEstimate(), firstEstimate));

  scene.lights.lights.pop_back();  // a new light set: the bounds change, the frame re-shades
  const QualityStats relit = render(scene);
  EXPECT_EQ(relit.render.plan.path, RenderPath::Reshade);
  EXPECT_NE(relit.predictedRmse, first.predictedRmse);

  for (glm::dvec3& p : sphere.points)  // edited in place, with a new version
    p.z *= 0.5;
  scene.meshes[0].mesh.version = 2;
  const QualityStats flattened = render(scene);
  EXPECT_NE(flattened.predictedRmse, relit.predictedRmse);
}

}  // namespace
}  // namespace facet
