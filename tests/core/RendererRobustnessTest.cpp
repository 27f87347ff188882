// Bad input gets a clear error; odd input renders without NaN, crash or stray writes.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/common.hpp>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "facet/Error.h"

namespace facet::testing {
namespace {

std::string errorOf(const Scene& scene, const Camera& camera, int width = 32, int height = 32) {
  Renderer renderer;
  Framebuffer fb(width, height);
  try {
    renderer.render(scene, camera, fb);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

Camera frontCamera() {
  Camera camera;
  camera.position = {0, 0, 5};
  camera.nearClip = 1.0;
  camera.farClip = 10.0;
  return camera;
}

TEST(RendererErrors, PointIdOutOfRangeIsNamed) {
  Mesh mesh = makeBox({-1, -1, -1}, {1, 1, 1});
  mesh.connectivity[7] = 42;
  const std::string message = errorOf(oneMeshScene(mesh.view()), frontCamera());
  EXPECT_NE(message.find("connectivity[7] is 42"), std::string::npos) << message;
  EXPECT_NE(message.find("polygon 1"), std::string::npos) << message;
  mesh.connectivity[7] = -1;
  EXPECT_NE(errorOf(oneMeshScene(mesh.view()), frontCamera()).find("is -1"), std::string::npos);
}

TEST(RendererErrors, BadOffsetsAreNamed) {
  Mesh mesh = makeBox({-1, -1, -1}, {1, 1, 1});
  mesh.offsets[3] = 2;
  EXPECT_NE(errorOf(oneMeshScene(mesh.view()), frontCamera()).find("offsets[3] is 2"),
            std::string::npos);
  mesh = makeBox({-1, -1, -1}, {1, 1, 1});
  mesh.offsets.back() = 1000;
  EXPECT_NE(errorOf(oneMeshScene(mesh.view()), frontCamera()).find("past the end"),
            std::string::npos);
  mesh = makeBox({-1, -1, -1}, {1, 1, 1});
  mesh.offsets[0] = 1;
  EXPECT_NE(errorOf(oneMeshScene(mesh.view()), frontCamera()).find("offsets[0] is 1"),
            std::string::npos);
}

// Renderer::plan bounds the points: a mesh without point data is an error there too, not a
// read through a null pointer (the core fuzzer's seed corpus found it).
TEST(RendererErrors, PlanNamesAMeshWithoutPointData) {
  Mesh mesh = makeBox({-1, -1, -1}, {1, 1, 1});
  MeshView view = mesh.view();
  view.points.data = nullptr;
  const Scene scene = oneMeshScene(view);
  Renderer renderer;
  try {
    renderer.plan(scene, frontCamera(), 32, 32);
    ADD_FAILURE() << "plan() accepted a mesh whose points are null";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("points"), std::string::npos) << e.what();
  }
  EXPECT_EQ(errorOf(scene, frontCamera()).empty(), false) << "render() rejects it as well";
}

TEST(RendererErrors, BadCameraSizeLightsAndMaterialsAreNamed) {
  const Mesh box = makeBox({-1, -1, -1}, {1, 1, 1});
  Camera camera = frontCamera();
  camera.focalPoint = camera.position;
  EXPECT_NE(errorOf(oneMeshScene(box.view()), camera).find("Camera.focalPoint"), std::string::npos);
  camera = frontCamera();
  camera.viewUp = {0, 0, 1};
  EXPECT_NE(errorOf(oneMeshScene(box.view()), camera).find("Camera.viewUp"), std::string::npos);
  camera = frontCamera();
  camera.nearClip = 0.0;
  EXPECT_NE(errorOf(oneMeshScene(box.view()), camera).find("nearClip"), std::string::npos);
  camera = frontCamera();
  camera.farClip = 0.5;
  EXPECT_NE(errorOf(oneMeshScene(box.view()), camera).find("farClip"), std::string::npos);

  Material material;
  material.diffuse = std::nan("");
  EXPECT_NE(errorOf(oneMeshScene(box.view(), material), frontCamera())
                .find("Scene.meshes[0].Material.diffuse"),
            std::string::npos);
  LightSet lights;
  lights.lights.push_back(SpotLight{});
  std::get<SpotLight>(lights.lights[0]).direction = {0, 0, 0};
  EXPECT_NE(
      errorOf(oneMeshScene(box.view(), {}, lights), frontCamera()).find("lights[0].direction"),
      std::string::npos);

  EXPECT_THROW(Framebuffer(0, 10), Error);
  EXPECT_THROW(Framebuffer(10, 100000), Error);
  Renderer renderer;
  EXPECT_THROW(renderer.setThreadCount(-1), Error);
}

TEST(RendererErrors, NothingIsPaintedWhenTheInputIsBad) {
  Mesh mesh = makeBox({-1, -1, -1}, {1, 1, 1});
  Renderer renderer;
  Framebuffer fb(16, 16);
  std::fill(fb.color().begin(), fb.color().end(), Rgba8{1, 2, 3, 4});
  mesh.connectivity[0] = 99;
  EXPECT_THROW(renderer.render(oneMeshScene(mesh.view()), frontCamera(), fb), Error);
  EXPECT_EQ(fb.colorAt(8, 8), (Rgba8{1, 2, 3, 4}));
}

TEST(RendererRobustness, PolygonsWithNonFinitePointsAreSkippedAndCounted) {
  Mesh mesh = makeBox({-1, -1, -1}, {1, 1, 1});
  mesh.points[7] = {std::nan(""), 1.0, 1.0};  // used by 3 faces
  const Rendered r = renderScene(oneMeshScene(mesh.view()), frontCamera(), 64, 64);
  EXPECT_EQ(r.stats.polygonsNonFinite, 3u);
  mesh.points[7] = {std::numeric_limits<double>::infinity(), 1.0, 1.0};
  EXPECT_EQ(renderScene(oneMeshScene(mesh.view()), frontCamera(), 64, 64).stats.polygonsNonFinite,
            3u);
  for (float depth : r.framebuffer.depth())
    ASSERT_TRUE(depth >= 0.0f && depth <= 1.0f);
}

TEST(RendererRobustness, DegeneratePolygonsAreSkippedAndCounted) {
  Mesh mesh;
  for (glm::dvec3 p : {glm::dvec3{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {0, 1, 0}})
    mesh.addPoint(p);
  mesh.addPolygon({0, 1, 2});                       // collinear
  mesh.addPolygon({0, 0, 0});                       // one point
  mesh.addPolygon({0, 1, 2, 1});                    // back and forth
  mesh.offsets.push_back(mesh.offsets.back() + 2);  // two points only
  mesh.connectivity.insert(mesh.connectivity.end(), {0, 3});
  LightSet lights;
  lights.lights.push_back(DirectionalLight{});
  const Rendered r = renderScene(oneMeshScene(mesh.view(), {}, lights), frontCamera(), 32, 32);
  EXPECT_EQ(r.stats.polygonsDegenerate, 4u);
  EXPECT_EQ(r.stats.pixelsCovered, 0u);
}

TEST(RendererRobustness, EmptySceneGivesTheBackground) {
  Renderer renderer;
  renderer.setBackground(Color(0.2f, 0.4f, 0.6f), 0.5f);
  Framebuffer fb(33, 17);
  const RenderStats stats = renderer.render(Scene{}, frontCamera(), fb);
  EXPECT_EQ(stats.pixelsCovered, 0u);
  for (std::size_t i = 0; i < fb.pixelCount(); ++i) {
    ASSERT_EQ(fb.color()[i], (Rgba8{51, 102, 153, 128}));
    ASSERT_EQ(fb.depth()[i], 1.0f);
    ASSERT_EQ(fb.polygonId()[i], Framebuffer::kBackgroundId);
  }
}

// Counts pixels whose polygon id differs (the silhouette and every interior edge) and the
// largest per-channel color difference.
struct ImageDifference {
  std::size_t ids = 0;
  int color = 0;
};
ImageDifference differenceOf(const Framebuffer& a, const Framebuffer& b) {
  ImageDifference d;
  for (std::size_t i = 0; i < a.pixelCount(); ++i) {
    d.ids += a.polygonId()[i] != b.polygonId()[i];
    const Rgba8 p = a.color()[i], q = b.color()[i];
    d.color = std::max({d.color, std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
  }
  return d;
}

// Far from the origin the picture is the unit scene's: the camera transform works on
// eye-relative doubles. The sphere's points lie on a 2^-12 grid, so that moving them by up to
// 1e12 (below 2^40, where doubles still resolve 2^-13) is exact: any difference would be the
// renderer's. Positions, polygons and silhouette are then identical; only the lit colors of
// a point light may move by 1/255, as polygon centers are summed in absolute coordinates.
TEST(RendererRobustness, TranslationInvariantFarFromTheOrigin) {
  Mesh sphere = makeUvSphere(40, 40, 1.0);
  for (glm::dvec3& p : sphere.points)
    p = glm::round(p * 4096.0) / 4096.0;
  LightSet lights;
  lights.ambient.intensity = 0.2;
  lights.lights.push_back(PointLight{{2.0, 3.0, 4.0}, Color(1.0f), 1.0, NoAttenuation{}});
  Camera here = fitCamera(sphere, {0.3, 0.2, -1.0});
  here.position = glm::round(here.position * 4096.0) / 4096.0;
  const Rendered reference = renderScene(oneMeshScene(sphere.view(), {}, lights), here, 200, 150);
  EXPECT_GT(reference.stats.pixelsCovered, 3000u);
  for (int exponent = 3; exponent <= 12; ++exponent) {
    const double offset = std::pow(10.0, exponent);
    const glm::dvec3 shift(offset, -offset, offset);
    Mesh moved = sphere;
    for (glm::dvec3& p : moved.points)
      p += shift;
    LightSet movedLights = lights;
    std::get<PointLight>(movedLights.lights[0]).position += shift;
    Camera there = here;
    there.position += shift;
    there.focalPoint += shift;
    const Rendered r = renderScene(oneMeshScene(moved.view(), {}, movedLights), there, 200, 150);
    const ImageDifference d = differenceOf(r.framebuffer, reference.framebuffer);
    EXPECT_EQ(d.ids, 0u) << "offset " << offset;
    EXPECT_LE(d.color, 1) << "offset " << offset;
  }
}

// Scaled by 1e-12 … 1e12 (camera and clipping range too) the picture is the unit scene's:
// everything from view space on is relative (depth keys n/d included), so only the rounding
// of the scaled coordinates (2^-53) differs — far below the 1/256-pixel grid.
TEST(RendererRobustness, TinyAndHugeScalesRenderAlike) {
  const Mesh unit = makeUvSphere(24, 24, 1.0);
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1, -2, -3}});
  const Camera camera = fitCamera(unit, {0, 0, -1});
  const Rendered reference = renderScene(oneMeshScene(unit.view(), {}, lights), camera, 120, 90);
  EXPECT_GT(reference.stats.pixelsCovered, 1500u);
  for (int exponent = -12; exponent <= 12; exponent += 2) {
    const double scale = std::pow(10.0, exponent);
    Mesh scaled = unit;
    for (glm::dvec3& p : scaled.points)
      p *= scale;
    Camera c = camera;
    c.position *= scale;
    c.focalPoint *= scale;
    c.nearClip *= scale;
    c.farClip *= scale;
    const Rendered r = renderScene(oneMeshScene(scaled.view(), {}, lights), c, 120, 90);
    const ImageDifference d = differenceOf(r.framebuffer, reference.framebuffer);
    EXPECT_EQ(d.ids, 0u) << "scale " << scale;
    EXPECT_LE(d.color, 1) << "scale " << scale;
  }
}

TEST(RendererRobustness, CameraInsideTheMeshAndGeometryBehindIt) {
  const Mesh sphere = makeUvSphere(30, 30, 10.0);
  Camera inside;
  inside.position = {0.5, 0.2, 0.1};
  inside.focalPoint = {0.5, 0.2, -1.0};
  inside.nearClip = 0.01;
  inside.farClip = 100.0;
  const Rendered r = renderScene(oneMeshScene(sphere.view()), inside, 64, 48);
  EXPECT_EQ(r.stats.pixelsCovered, 64u * 48u) << "the inside of a sphere fills the view";
  EXPECT_GT(r.stats.trianglesClipped, 0u);
}

TEST(RendererProgress, ReportsIncreasingFractionsAndCanAbort) {
  const Mesh sphere = makeUvSphere(200, 200);
  const Scene scene = oneMeshScene(sphere.view());
  const Camera camera = fitCamera(sphere);
  Renderer renderer;
  renderer.setThreadCount(2);
  double last = -1.0;
  int calls = 0;
  renderer.setProgressCallback([&](double fraction) {
    EXPECT_GE(fraction, last);
    EXPECT_LE(fraction, 1.0);
    last = fraction;
    ++calls;
    return true;
  });
  Framebuffer fb(256, 256);
  EXPECT_FALSE(renderer.render(scene, camera, fb).aborted);
  EXPECT_GT(calls, 3);
  EXPECT_GT(last, 0.9);

  renderer.setProgressCallback([](double fraction) { return fraction < 0.3; });
  const RenderStats stopped = renderer.render(scene, camera, fb);
  EXPECT_TRUE(stopped.aborted);
  for (std::int32_t id : fb.polygonId())
    ASSERT_EQ(id, Framebuffer::kBackgroundId);
}

// A callback that throws: render() rethrows once every thread has left the phase (the
// workers ran on while the caller unwound: a crash or a double free, 3 runs of 3), and the
// renderer's next frame is the one a fresh renderer draws.
TEST(RendererProgress, ACallbackThatThrowsLeavesTheRendererUsable) {
  const Mesh sphere = makeUvSphere(256, 256);
  const Scene scene = oneMeshScene(sphere.view());
  const Camera camera = fitCamera(sphere);
  Renderer fresh;
  fresh.setThreadCount(2);
  Framebuffer expected(320, 240);
  fresh.render(scene, camera, expected);

  Renderer renderer;
  renderer.setThreadCount(2);
  Framebuffer fb(320, 240);
  for (int stopAt = 1; stopAt <= 24; ++stopAt) {
    int calls = 0;
    renderer.setProgressCallback([&](double) {
      if (++calls == stopAt) throw std::runtime_error("stop");
      return true;
    });
    try {
      renderer.render(scene, camera, fb);
    } catch (const std::runtime_error&) {
    }
  }
  renderer.setProgressCallback({});
  renderer.render(scene, camera, fb);
  EXPECT_TRUE(std::ranges::equal(fb.color(), expected.color()));
  EXPECT_TRUE(std::ranges::equal(fb.polygonId(), expected.polygonId()));
}

// An exception from a callback in the middle of an incremental sequence: the planes then hold
// part of a frame that the renderer's history must not take for the last one. Rendering the
// frame before it again draws in full, the bytes of a fresh renderer (not a stale resolve).
TEST(RendererProgress, ACallbackThatThrowsMidSequenceLeavesNoStaleFrame) {
  const Mesh sphere = makeUvSphere(120, 120);
  Scene scene = oneMeshScene(sphere.view());
  scene.meshes[0].mesh.version = 1;  // incremental paths possible
  const Camera first = fitCamera(sphere);
  Camera moved = first;
  moved.position += glm::dvec3(0.3, 0.2, 0.0);
  Renderer fresh;
  Framebuffer expected(160, 120);
  fresh.render(scene, first, expected);

  for (const bool fromProgress : {false, true}) {
    Renderer renderer;
    renderer.setThreadCount(2);
    Framebuffer fb(160, 120);
    renderer.render(scene, first, fb);
    std::atomic<int> calls = 0;  // the rows callback runs on the resolve's threads
    if (fromProgress) {
      renderer.setProgressCallback([&](double) {
        if (++calls == 4) throw std::runtime_error("stop");
        return true;
      });
    } else {
      renderer.setResolvedRowsCallback([&](const FramebufferView&, int, int, int, int) {
        if (++calls == 3) throw std::runtime_error("stop");
      });
    }
    EXPECT_THROW(renderer.render(scene, moved, fb), std::runtime_error);
    renderer.setProgressCallback({});
    renderer.setResolvedRowsCallback({});
    const RenderStats again = renderer.render(scene, first, fb);
    EXPECT_EQ(again.plan.path, RenderPath::Full) << "from the progress callback: " << fromProgress;
    EXPECT_TRUE(std::ranges::equal(fb.polygonId(), expected.polygonId()));
    EXPECT_TRUE(std::ranges::equal(fb.color(), expected.color()));
  }
}

// Every row comes once per render, on whichever path (full, or the incremental resolve of a
// new background), with the caller's planes and the pixels render() returns: snapshots taken
// in the callback equal the framebuffer afterwards.
TEST(RendererResolvedRows, EveryRowOnceWithItsFinalPixels) {
  const Mesh sphere = makeUvSphere(120, 120);
  Scene scene = oneMeshScene(sphere.view());
  scene.meshes[0].mesh.version = 1;  // so that a new background is only a resolve
  const Camera camera = fitCamera(sphere);
  Renderer renderer;
  renderer.setThreadCount(3);
  Framebuffer fb(131, 67);  // bands of 8 rows: the last one short
  const FramebufferView view = fb.view();
  std::vector<int> calls(67);
  std::vector<Rgba8> colors(fb.pixelCount());
  std::vector<float> depths(fb.pixelCount());
  std::vector<std::int32_t> ids(fb.pixelCount());
  std::atomic<int> narrowed{0};  // bands with background tiles left out
  renderer.setResolvedRowsCallback(
      [&](const FramebufferView& target, int y0, int y1, int x0, int x1) {
        EXPECT_EQ(target.color, view.color);
        EXPECT_EQ(target.depth, view.depth);
        EXPECT_EQ(target.polygonId, view.polygonId);
        ASSERT_LE(0, y0);
        ASSERT_LE(y0, y1);
        ASSERT_LT(y1, target.height);
        const std::size_t begin = static_cast<std::size_t>(y0) * target.width;
        const std::size_t end = static_cast<std::size_t>(y1 + 1) * target.width;
        std::copy(target.color + begin, target.color + end, colors.begin() + begin);
        std::copy(target.depth + begin, target.depth + end, depths.begin() + begin);
        std::copy(target.polygonId + begin, target.polygonId + end, ids.begin() + begin);
        // Outside columns [x0, x1) the band shows the background.
        EXPECT_LE(0, x0);
        EXPECT_LE(x0, x1);
        EXPECT_LE(x1, target.width);
        if (x1 - x0 < target.width) ++narrowed;
        for (int y = y0; y <= y1; ++y) {
          ++calls[y];  // rows of one band: no other thread's
          const std::int32_t* row = target.polygonId + static_cast<std::size_t>(y) * target.width;
          for (int x = 0; x < target.width; ++x)
            if (x < x0 || x >= x1) {
              EXPECT_LT(row[x], 0) << x << ", " << y;
            }
        }
      });
  const std::pair<Color, RenderPath> frames[] = {{Color(0.0f), RenderPath::Full},
                                                 {Color(0.2f, 0.3f, 0.4f), RenderPath::Resolve}};
  for (const auto& [background, path] : frames) {
    renderer.setBackground(background);
    std::fill(calls.begin(), calls.end(), 0);
    narrowed = 0;
    const RenderStats stats = renderer.render(scene, camera, fb);
    EXPECT_GT(narrowed, 0);
    SCOPED_TRACE(stats.plan.pathReason);
    EXPECT_EQ(stats.plan.path, path);
    EXPECT_EQ(std::count(calls.begin(), calls.end(), 1), 67);
    EXPECT_TRUE(std::ranges::equal(colors, fb.color()));
    EXPECT_TRUE(std::ranges::equal(ids, fb.polygonId()));
    EXPECT_EQ(std::memcmp(depths.data(), fb.depth().data(), depths.size() * sizeof(float)), 0);
    EXPECT_GT(stats.pixelsCovered, 0u);
  }
  renderer.setResolvedRowsCallback({});
}

TEST(RendererParallelFor, ATaskThatThrowsIsRethrownAfterEveryThreadLeft) {
  Renderer renderer;
  renderer.setThreadCount(4);
  std::vector<int> ran(64, 0);
  EXPECT_THROW(renderer.parallelFor(64, 1,
                                    [&](std::size_t begin, std::size_t) {
                                      if (begin == 5) throw std::out_of_range("block 5");
                                      ran[begin] = 1;
                                    }),
               std::out_of_range);
  EXPECT_EQ(ran[5], 0);
  // The pool is whole again: every block of the next job runs.
  std::fill(ran.begin(), ran.end(), 0);
  renderer.parallelFor(64, 1, [&](std::size_t begin, std::size_t) { ran[begin] = 1; });
  EXPECT_EQ(std::count(ran.begin(), ran.end(), 1), 64);
}

TEST(RenderPlan, LeavesOutWhatTheSceneDoesNotNeed) {
  const Mesh box = makeBox({-1, -1, -1}, {1, 1, 1});
  Renderer renderer;
  RenderPlan ambientOnly = renderer.plan(oneMeshScene(box.view()), frontCamera(), 64, 48);
  EXPECT_FALSE(ambientOnly.directLighting);
  EXPECT_FALSE(ambientOnly.polygonCenters);
  EXPECT_FALSE(ambientOnly.viewerDirection);
  EXPECT_NE(ambientOnly.describe().find("normals skipped"), std::string::npos)
      << ambientOnly.describe();

  LightSet lights;
  lights.lights.push_back(PointLight{});
  lights.lights.push_back(DirectionalLight{{0, 0, -1}, Color(0.0f), 1.0});  // black: left out
  Material shiny;
  shiny.specular = 0.5;
  const RenderPlan lit =
      renderer.plan(oneMeshScene(box.view(), shiny, lights), frontCamera(), 64, 48);
  EXPECT_TRUE(lit.directLighting);
  EXPECT_TRUE(lit.positionalLights);
  EXPECT_TRUE(lit.specular);
  EXPECT_TRUE(lit.polygonCenters);
  EXPECT_EQ(lit.polygons, 6u);
  EXPECT_EQ(lit.tilesX * lit.tileSize >= 64, true);

  LightSet dark;
  dark.lights.push_back(DirectionalLight{{0, 0, -1}, Color(1.0f), 0.0});  // zero intensity
  EXPECT_FALSE(renderer.plan(oneMeshScene(box.view()), frontCamera(), 8, 8).specular);
  EXPECT_FALSE(
      renderer.plan(oneMeshScene(box.view(), shiny, dark), frontCamera(), 8, 8).directLighting);
}

}  // namespace
}  // namespace facet::testing
