// Incremental rendering (Renderer.h): after a render, one whose lights, materials, colors or
// two-sided lighting alone changed re-shades the kept frame, one whose background alone
// changed only resolves it, and anything else renders in full. Every path gives the bytes a
// full render by a fresh renderer gives, on 1 and 2 threads.

#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "facet/Error.h"

namespace facet::testing {
namespace {

// How a renderer is set up; the same for the incremental renderer and the fresh one.
struct Settings {
  int threads = 2;
  Visibility visibility = Visibility::ZBuffer;
  bool twoSidedLighting = true;
  Color background{0.1f, 0.2f, 0.3f};
  bool depthOutput = true;
  RenderRules rules = {};
};

void apply(Renderer& renderer, const Settings& s) {
  renderer.setThreadCount(s.threads);
  renderer.setVisibility(s.visibility);
  renderer.setTwoSidedLighting(s.twoSidedLighting);
  renderer.setBackground(s.background, 0.75f);
  renderer.setDepthOutput(s.depthOutput);
  renderer.setRules(s.rules);
}

// A bunny and a box of its own colors, both versioned, under a mix of lights.
struct World {
  Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  Mesh box = makeBox({-0.12, 0.02, -0.08}, {-0.06, 0.1, 0.0});
  Scene scene;
  Camera camera = fitCamera(bunny, {0.3, -0.2, -1.0});

  World() {
    for (std::size_t i = 0; i < box.polygonCount(); ++i)
      box.polygonColors.push_back({std::uint8_t(40 * i), 200, std::uint8_t(255 - 30 * i), 255});
    scene.meshes.push_back({bunny.view(), Material{}});
    scene.meshes.push_back({box.view(), Material{}});
    scene.meshes[0].mesh.version = 1;
    scene.meshes[1].mesh.version = 1;
    scene.meshes[1].mesh.colorVersion = 1;
    scene.meshes[0].material.specular = 0.4;
    scene.lights.lights.push_back(DirectionalLight{{-1, -0.5, -1}, Color(0.7f), 1.0});
    scene.lights.lights.push_back(PointLight{camera.position, Color(0.5f, 0.4f, 0.3f), 1.0});
  }
};

// What one render draws, and how.
struct Frame {
  const Scene& scene;
  const Camera& camera;
  Settings settings = {};
};

// Renders `after` with a renderer that has just rendered `before` into the same framebuffer,
// and with a fresh renderer; checks the bytes agree and the incremental render took `path`.
void expectPath(const Frame& before, const Frame& after, RenderPath path,
                const std::string& change) {
  for (int threads : {1, 2}) {
    Settings s1 = before.settings, s2 = after.settings;
    s1.threads = s2.threads = threads;
    Renderer incremental;
    apply(incremental, s1);
    Framebuffer framebuffer(220, 170);
    incremental.render(before.scene, before.camera, framebuffer);
    apply(incremental, s2);
    const RenderStats stats = incremental.render(after.scene, after.camera, framebuffer);

    Renderer fresh;
    apply(fresh, s2);
    fresh.setThreadCount(3 - threads);  // and any thread count
    Framebuffer reference(220, 170);
    const RenderStats full = fresh.render(after.scene, after.camera, reference);

    EXPECT_EQ(stats.plan.path, path) << change << ": " << stats.plan.pathReason;
    EXPECT_EQ(differingPixels(framebuffer, reference), 0u)
        << change << ", " << threads << " threads\n"
        << stats.describe();
    EXPECT_GT(full.pixelsCovered, 0u);
    EXPECT_EQ(stats.pixelsCovered, full.pixelsCovered) << change;
    if (path != RenderPath::Full) {
      EXPECT_EQ(stats.transformSeconds + stats.setupSeconds + stats.rasterSeconds, 0.0) << change;
    }
  }
}

// The world's frame, then `after` with the same camera and settings.
void expectPath(const World& world, const Scene& after, RenderPath path, const std::string& change,
                const Settings& settings = {}) {
  expectPath({world.scene, world.camera, settings}, {after, world.camera, settings}, path, change);
}

TEST(Incremental, NewLightsReshadeWithTheSameBytes) {
  World world;
  Scene moved = world.scene;
  std::get<PointLight>(moved.lights.lights[1]).position += glm::dvec3(0.1, 0.2, 0.0);
  expectPath(world, moved, RenderPath::Reshade, "a point light moved");

  Scene spot = world.scene;
  spot.lights.lights.push_back(
      SpotLight{world.camera.position, world.camera.focalPoint - world.camera.position});
  spot.lights.ambient.intensity = 0.3;
  expectPath(world, spot, RenderPath::Reshade, "a spot light added, ambient changed");

  Scene ambientOnly = world.scene;
  ambientOnly.lights.lights.clear();
  expectPath(world, ambientOnly, RenderPath::Reshade, "every direct light removed");

  Scene dark = world.scene;
  std::get<DirectionalLight>(dark.lights.lights[0]).intensity = 0.0;  // culled by the rule
  expectPath(world, dark, RenderPath::Reshade, "a light turned off");
}

TEST(Incremental, NewMaterialsReshadeWithTheSameBytes) {
  World world;
  Scene changed = world.scene;
  changed.meshes[0].material.color = Color(0.9f, 0.3f, 0.2f);
  changed.meshes[0].material.specular = 0.0;
  changed.meshes[1].material.diffuse = 0.3;
  expectPath(world, changed, RenderPath::Reshade, "materials changed");
}

TEST(Incremental, NewColorsReshadeWithTheSameBytes) {
  World world;
  Mesh recolored = world.box;
  for (Rgba8& c : recolored.polygonColors)
    c = {c.b, c.r, c.g, 255};
  Scene other = world.scene;  // other arrays: a new identity
  other.meshes[1].mesh.polygonColors = recolored.polygonColors;
  expectPath(world, other, RenderPath::Reshade, "another color array");

  // In place: the promise is a new colorVersion.
  Scene before = world.scene;
  Scene after = world.scene;
  after.meshes[1].mesh.colorVersion = 2;
  for (int threads : {1, 2}) {
    Mesh box = world.box;
    before.meshes[1].mesh.polygonColors = after.meshes[1].mesh.polygonColors = box.polygonColors;
    Renderer incremental;
    Settings settings;
    settings.threads = threads;
    apply(incremental, settings);
    Framebuffer framebuffer(220, 170);
    incremental.render(before, world.camera, framebuffer);
    box.polygonColors[3] = {255, 0, 0, 255};
    const RenderStats stats = incremental.render(after, world.camera, framebuffer);
    EXPECT_EQ(stats.plan.path, RenderPath::Reshade) << stats.plan.pathReason;
    Renderer fresh;
    apply(fresh, settings);
    Framebuffer expected(220, 170);
    fresh.render(after, world.camera, expected);
    EXPECT_EQ(differingPixels(framebuffer, expected), 0u) << threads << " threads";
  }
}

TEST(Incremental, TwoSidedLightingReshades) {
  World world;
  Settings on, off;
  off.twoSidedLighting = false;
  expectPath({world.scene, world.camera, on}, {world.scene, world.camera, off}, RenderPath::Reshade,
             "two-sided lighting turned off");
}

TEST(Incremental, ANewBackgroundOnlyResolves) {
  World world;
  Settings before, after;
  after.background = Color(0.9f, 0.8f, 0.1f);
  expectPath({world.scene, world.camera, before}, {world.scene, world.camera, after},
             RenderPath::Resolve, "the background changed");
  expectPath(world, world.scene, RenderPath::Resolve, "nothing changed");
}

TEST(Incremental, PathsWithoutDepthOutputAndInPaintersOrder) {
  World world;
  Scene moved = world.scene;
  std::get<DirectionalLight>(moved.lights.lights[0]).direction = {1, 0, -1};
  Settings noDepth;
  noDepth.depthOutput = false;
  expectPath(world, moved, RenderPath::Reshade, "lights, no depth output", noDepth);
  Settings painter;
  painter.visibility = Visibility::PainterSort;
  expectPath(world, moved, RenderPath::Reshade, "lights, painter's order", painter);
  Settings closed;
  World closedWorld;
  closedWorld.scene.meshes[1].mesh.closedSurface = true;  // the box; its back faces skipped
  Scene closedMoved = closedWorld.scene;
  closedMoved.lights = moved.lights;
  expectPath(closedWorld, closedMoved, RenderPath::Reshade, "lights, a closed mesh", closed);
}

TEST(Incremental, GeometryCameraAndTargetChangesRenderInFull) {
  World world;
  Camera turned = world.camera;
  turned.position += glm::dvec3(0.01, 0.0, 0.0);
  expectPath({world.scene, world.camera}, {world.scene, turned}, RenderPath::Full,
             "camera changed");

  Scene bumped = world.scene;
  bumped.meshes[0].mesh.version = 2;  // the caller edited the points in place
  expectPath(world, bumped, RenderPath::Full, "a new geometry version");

  Scene unversioned = world.scene;
  unversioned.meshes[0].mesh.version = 0;
  expectPath(world, unversioned, RenderPath::Full, "an unversioned mesh");
  expectPath({unversioned, world.camera}, {unversioned, world.camera}, RenderPath::Full,
             "unversioned, nothing else changed");

  Scene culling = world.scene;
  culling.meshes[1].material.backfaceCulling = true;
  expectPath(world, culling, RenderPath::Full, "back-face culling turned on");

  Scene fewer = world.scene;
  fewer.meshes.pop_back();
  expectPath(world, fewer, RenderPath::Full, "a mesh removed");

  Settings rulesOff;
  rulesOff.rules.incremental = false;
  expectPath(world, world.scene, RenderPath::Full, "incremental rendering off", rulesOff);
  Settings painter;
  painter.visibility = Visibility::PainterSort;
  expectPath({world.scene, world.camera}, {world.scene, world.camera, painter}, RenderPath::Full,
             "visibility changed");
}

TEST(Incremental, AnotherFramebufferOrAForgottenFrameRendersInFull) {
  World world;
  Renderer renderer;
  Framebuffer a(120, 90), b(120, 90);
  EXPECT_EQ(renderer.render(world.scene, world.camera, a).plan.path, RenderPath::Full);
  EXPECT_EQ(renderer.render(world.scene, world.camera, a).plan.path, RenderPath::Resolve);
  EXPECT_EQ(renderer.render(world.scene, world.camera, b).plan.path, RenderPath::Full);
  renderer.forgetPreviousFrame();
  EXPECT_EQ(renderer.render(world.scene, world.camera, b).plan.path, RenderPath::Full);
  EXPECT_EQ(differingPixels(a, b), 0u);
}

TEST(Incremental, AStoppedRenderIsNotReused) {
  World world;
  Renderer renderer;
  apply(renderer, {});
  Framebuffer framebuffer(120, 90);
  renderer.render(world.scene, world.camera, framebuffer);
  Scene moved = world.scene;
  std::get<PointLight>(moved.lights.lights[1]).intensity = 0.5;
  renderer.setProgressCallback([](double) { return false; });
  const RenderStats stopped = renderer.render(moved, world.camera, framebuffer);
  EXPECT_TRUE(stopped.aborted);
  EXPECT_EQ(stopped.plan.path, RenderPath::Reshade);
  renderer.setProgressCallback(nullptr);
  const RenderStats next = renderer.render(moved, world.camera, framebuffer);
  EXPECT_EQ(next.plan.path, RenderPath::Full) << next.plan.pathReason;
  Renderer fresh;
  apply(fresh, {});
  Framebuffer expected(120, 90);
  fresh.render(moved, world.camera, expected);
  EXPECT_EQ(differingPixels(framebuffer, expected), 0u);
}

// A two-pass frame (every face drawn: its front pass writes a deferred back face's facing byte
// as front-facing, and the back pass, a later phase, rewrites it: Setup.cpp, kDeferBackFaces)
// stopped at each of its progress reports, then rendered again after a change a completed frame
// would re-shade: in full, the bytes of a fresh renderer (the stopped frame's facing bytes are
// not re-shaded). Completed, it is re-shaded: the back faces seen through the band, lit two-sided
// from the back pass's bytes, as a fresh renderer lights them. 1 and 2 threads.
TEST(Incremental, AStoppedTwoPassFrameIsNotReshaded) {
  const Mesh banded = sphereWithBand(120);
  Scene scene;
  scene.meshes.push_back({banded.view(), Material{}});
  scene.meshes[0].mesh.version = 1;
  const Camera camera = fitCamera(banded, {0.3, -0.2, -1.0});
  scene.lights.lights.push_back(PointLight{camera.position, Color(1.0f), 1.0});
  Scene changed = scene;
  std::get<PointLight>(changed.lights.lights[0]).intensity = 0.6;
  for (int threads : {1, 2}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    Settings settings;
    settings.threads = threads;
    Renderer fresh, renderer;
    apply(fresh, settings);
    apply(renderer, settings);
    Framebuffer expected(320, 240), framebuffer(320, 240);
    fresh.render(changed, camera, expected);
    int reports = 0;
    renderer.setProgressCallback([&](double) { return ++reports > 0; });
    const RenderStats first = renderer.render(scene, camera, framebuffer);
    ASSERT_TRUE(first.plan.twoPassFrame);
    ASSERT_GT(reports, 2);
    renderer.setProgressCallback(nullptr);
    EXPECT_EQ(renderer.render(changed, camera, framebuffer).plan.path, RenderPath::Reshade);
    EXPECT_EQ(differingPixels(framebuffer, expected), 0u);
    int aborted = 0;
    for (int stopAt = 1; stopAt <= reports; ++stopAt) {
      SCOPED_TRACE("stopped at report " + std::to_string(stopAt));
      renderer.forgetPreviousFrame();
      int calls = 0;
      renderer.setProgressCallback([&](double) { return ++calls < stopAt; });
      const RenderStats stopped = renderer.render(scene, camera, framebuffer);
      aborted += stopped.aborted ? 1 : 0;
      renderer.setProgressCallback(nullptr);
      const RenderStats next = renderer.render(changed, camera, framebuffer);
      EXPECT_EQ(next.plan.path, stopped.aborted ? RenderPath::Full : RenderPath::Reshade);
      EXPECT_EQ(differingPixels(framebuffer, expected), 0u);
    }
    EXPECT_GT(aborted, reports / 4) << "of " << reports << " reports";  // 2 threads: counts vary
  }
}

TEST(Incremental, ASequenceOfChangesKeepsMatchingFullRenders) {
  World world;
  for (int threads : {1, 2}) {
    Settings settings;
    settings.threads = threads;
    Renderer incremental, fresh;
    apply(incremental, settings);
    Framebuffer framebuffer(200, 150), expected(200, 150);
    Scene scene = world.scene;
    Camera camera = world.camera;
    const std::vector<std::pair<RenderPath, std::function<void()>>> steps = {
        {RenderPath::Full, [] {}},
        {RenderPath::Reshade, [&] { scene.lights.ambient.intensity = 0.6; }},
        {RenderPath::Resolve, [&] { settings.background = Color(1.0f); }},
        {RenderPath::Reshade, [&] { scene.meshes[0].material.color = Color(0.2f, 0.9f, 0.4f); }},
        {RenderPath::Full,
         [&] {
           camera.viewUp = {0.1, 1.0, 0.0};
         }},
        {RenderPath::Reshade, [&] { scene.lights.lights.pop_back(); }},
        {RenderPath::Resolve, [] {}},
    };
    for (std::size_t i = 0; i < steps.size(); ++i) {
      steps[i].second();
      apply(incremental, settings);
      apply(fresh, settings);
      fresh.forgetPreviousFrame();
      const RenderStats stats = incremental.render(scene, camera, framebuffer);
      fresh.render(scene, camera, expected);
      EXPECT_EQ(stats.plan.path, steps[i].first) << "step " << i << ": " << stats.plan.pathReason;
      EXPECT_EQ(differingPixels(framebuffer, expected), 0u)
          << "step " << i << ", " << threads << " threads\n"
          << stats.describe();
    }
  }
}

TEST(Incremental, TheReportSaysWhichPathRanAndWhy) {
  World world;
  Renderer renderer;
  Framebuffer framebuffer(120, 90);
  const RenderStats full = renderer.render(world.scene, world.camera, framebuffer);
  Scene dimmer = world.scene;
  dimmer.lights.ambient.intensity = 0.2;
  const RenderStats reshade = renderer.render(dimmer, world.camera, framebuffer);
  const std::string text = reshade.describe();
  for (const char* expected : {"path: re-shade the previous frame", "(the lights changed)",
                               "transform 0, set-up 0, raster 0", "rules (off / idle / fired"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << " in\n" << text;
  }
  EXPECT_STREQ(full.plan.pathReason, "no previous frame to reuse");
  EXPECT_GT(full.rasterSeconds, 0.0);
  EXPECT_GT(reshade.shadeSeconds, 0.0);
  EXPECT_EQ(reshade.polygonsDrawn, full.polygonsDrawn) << "the frame's counts are kept";
  EXPECT_STREQ(reshade.plan.rasterRoutine, full.plan.rasterRoutine);
}

// A versioned mesh is shaded from the face normals kept per version (MeshCache), an
// unversioned one from normals computed every frame: the same bytes.
TEST(Incremental, KeptFaceNormalsShadeToTheSameBytes) {
  const World world;
  Scene unversioned = world.scene;
  for (SceneMesh& mesh : unversioned.meshes)
    mesh.mesh.version = mesh.mesh.colorVersion = 0;
  for (int threads : {1, 2}) {
    Settings settings;
    settings.threads = threads;
    Renderer kept, computed;
    apply(kept, settings);
    apply(computed, settings);
    Framebuffer a(220, 170), b(220, 170);
    const RenderStats stats = kept.render(world.scene, world.camera, a);
    computed.render(unversioned, world.camera, b);
    EXPECT_GT(stats.pixelsCovered, 0u);
    EXPECT_EQ(differingPixels(a, b), 0u) << threads << " threads";
  }
}

}  // namespace
}  // namespace facet::testing
