// Bad input gets a clear error; odd input renders without NaN, crash or stray writes.

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

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

// Far from the origin the picture is the same as at the origin: the camera transform works
// on eye-relative doubles. (Points are double here; float input is as precise as it is.)
TEST(RendererRobustness, TranslationInvariantFarFromTheOrigin) {
  const Mesh sphere = makeUvSphere(40, 40, 1.0);
  LightSet lights;
  lights.ambient.intensity = 0.2;
  lights.lights.push_back(PointLight{{2.0, 3.0, 4.0}, Color(1.0f), 1.0, NoAttenuation{}});
  const Camera here = fitCamera(sphere, {0.3, 0.2, -1.0});
  const Rendered reference = renderScene(oneMeshScene(sphere.view(), {}, lights), here, 200, 150);
  for (double offset : {1e6, 1e9}) {
    Mesh moved = sphere;
    for (glm::dvec3& p : moved.points)
      p += glm::dvec3(offset, -offset, offset);
    LightSet movedLights = lights;
    std::get<PointLight>(movedLights.lights[0]).position += glm::dvec3(offset, -offset, offset);
    Camera there = here;
    there.position += glm::dvec3(offset, -offset, offset);
    there.focalPoint += glm::dvec3(offset, -offset, offset);
    const Rendered r = renderScene(oneMeshScene(moved.view(), {}, movedLights), there, 200, 150);
    std::size_t differentIds = 0, colorErrors = 0;
    for (std::size_t i = 0; i < r.framebuffer.pixelCount(); ++i) {
      differentIds += r.framebuffer.polygonId()[i] != reference.framebuffer.polygonId()[i];
      const Rgba8 a = r.framebuffer.color()[i], b = reference.framebuffer.color()[i];
      colorErrors += std::abs(a.r - b.r) > 1 || std::abs(a.g - b.g) > 1 || std::abs(a.b - b.b) > 1;
    }
    // At 1e9 a double resolves ~1e-7: sub-pixel snapping may move a handful of edge pixels.
    EXPECT_LE(differentIds, offset < 1e8 ? 0u : 40u) << "offset " << offset;
    EXPECT_LE(colorErrors, offset < 1e8 ? 0u : 40u) << "offset " << offset;
  }
}

TEST(RendererRobustness, TinyAndHugeScalesRenderAlike) {
  const Mesh unit = makeUvSphere(24, 24, 1.0);
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1, -2, -3}});
  const Camera camera = fitCamera(unit, {0, 0, -1});
  const Rendered reference = renderScene(oneMeshScene(unit.view(), {}, lights), camera, 120, 90);
  for (double scale : {1e-30, 1e-6, 1e6, 1e30}) {
    Mesh scaled = unit;
    for (glm::dvec3& p : scaled.points)
      p *= scale;
    Camera c = camera;
    c.position *= scale;
    c.focalPoint *= scale;
    c.nearClip *= scale;
    c.farClip *= scale;
    const Rendered r = renderScene(oneMeshScene(scaled.view(), {}, lights), c, 120, 90);
    std::size_t different = 0;
    for (std::size_t i = 0; i < r.framebuffer.pixelCount(); ++i) {
      different += r.framebuffer.polygonId()[i] != reference.framebuffer.polygonId()[i];
    }
    EXPECT_LE(different, 10u) << "scale " << scale;
    EXPECT_NEAR(double(r.stats.pixelsCovered), double(reference.stats.pixelsCovered), 10.0)
        << "scale " << scale;
    EXPECT_GT(r.stats.pixelsCovered, 1500u) << "scale " << scale;
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
