// Core rasterizer throughput at 1920 × 1080: spheres of 20k, 500k and 2M triangles (the VTK
// filter's frame: a versioned mesh, a turning camera) and a few large overlapping polygons,
// on 1 and 2 threads. Every frame includes the clear.
//
//   build/bench/facet_bench                       # all
//   build/bench/facet_bench --benchmark_filter=Sphere/500000
//
// Counters: triangles/s (input polygons per second) and fragments/s (fill rate, pixel writes incl.
// overdraw), and the heap peak during the benchmark (mesh + framebuffer + renderer) as a ratio of
// the bytes of the mesh plus the framebuffer (target: at most 2).
//
// BM_Saving: what each rule and each incremental path saves (README, "Leaving out work"), on
// scenes built to need little: per row, the frame with that work done anyway ("everything
// on") and the frame with the rule, rendered alternately in one run; `saving` is their ratio.
//
//   build/bin/facet_bench --benchmark_filter=Saving

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "HeapCounter.h"
#include "SetupBatch.h"
#include "TurningView.h"
#include "facet/Renderer.h"
#include "support/TestMeshes.h"

namespace facet::bench {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;

// A mesh the way VTK hands it over: float points, 64-bit offsets and connectivity.
struct VtkLikeMesh {
  std::vector<float> xyz;
  std::vector<std::int64_t> offsets, connectivity;
  std::vector<Rgba8> colors;
  bool closed = false;
  std::uint64_t version = 0;  // MeshView::version: 0, unversioned
  MeshView view() const {
    MeshView view{PointArray::ofXyz(xyz), PolygonArray::of(offsets, connectivity), colors, closed};
    view.version = version;
    return view;
  }
  std::size_t bytes() const {
    return xyz.size() * sizeof(float) +
           (offsets.size() + connectivity.size()) * sizeof(std::int64_t);
  }
};

VtkLikeMesh toVtkLike(const Mesh& mesh) {
  VtkLikeMesh out;
  for (const glm::dvec3& p : mesh.points) {
    out.xyz.insert(out.xyz.end(), {float(p.x), float(p.y), float(p.z)});
  }
  out.offsets = mesh.offsets;
  out.connectivity = mesh.connectivity;
  return out;
}

struct SphereCase {
  VtkLikeMesh mesh;
  Camera camera;
};

// vtkSphereSource's resolution for a triangle count: 2·theta·(phi − 2) triangles. The
// double-precision generator mesh is freed on return: a VTK user holds only the float one.
SphereCase sphereWithTriangles(std::int64_t triangles) {
  const int theta = static_cast<int>(std::lround(std::sqrt(triangles / 2.0)));
  const Mesh sphere = testing::makeUvSphere(theta, theta + 2);
  return {toVtkLike(sphere), testing::fitCamera(sphere)};
}

// The comparison's scene: one positional light at the camera, no scene ambient.
Scene benchScene(const MeshView& mesh, const Camera& camera) {
  Scene scene;
  scene.meshes.push_back({mesh, Material{}});
  scene.lights.ambient.intensity = 0.0;
  scene.lights.lights.push_back(PointLight{camera.position, Color(1.0f), 1.0, NoAttenuation{}});
  return scene;
}

void reportCounters(benchmark::State& state, const RenderStats& stats, std::size_t meshBytes,
                    std::size_t framebufferBytes, std::size_t baseline) {
  const double frames = static_cast<double>(state.iterations());
  state.counters["triangles/s"] =
      benchmark::Counter(frames * stats.plan.polygons, benchmark::Counter::kIsRate);
  state.counters["fragments/s"] =
      benchmark::Counter(frames * stats.fragmentsWritten, benchmark::Counter::kIsRate);
  state.counters["pixels"] = static_cast<double>(stats.pixelsCovered);
  const std::size_t peak = heapPeakBytes() - baseline;
  state.counters["peakMiB"] = peak / 1048576.0;
  state.counters["peak/(mesh+fb)"] = double(peak) / double(meshBytes + framebufferBytes);
  state.counters["setup%"] = 100.0 * stats.setupSeconds / stats.totalSeconds;
  state.counters["raster%"] = 100.0 * stats.rasterSeconds / stats.totalSeconds;
}

// The VTK filter's frame (TurningView.h): a versioned mesh, the camera turning a degree per
// frame. closed = 1: the mesh carries the MeshView::closedSurface hint, computed once here
// (as the VTK filter does once per input): hidden back faces are skipped. closed = 0: every
// face is drawn, as VTK's renderer does. The heap peak includes what the renderer keeps per
// mesh version (its face normals: 12 B per polygon).
void BM_Sphere(benchmark::State& state) {
  const std::size_t baseline = heapBytesInUse();
  SphereCase sphere = sphereWithTriangles(state.range(0));
  sphere.mesh.closed = state.range(2) != 0 && isClosedSurface(sphere.mesh.view());
  if (state.range(2) != 0 && !sphere.mesh.closed) state.SkipWithError("sphere not closed");
  sphere.mesh.version = 1;  // the filter's frame (TurningView.h)
  resetHeapPeak();
  Renderer renderer;
  renderer.setThreadCount(static_cast<int>(state.range(1)));
  Framebuffer framebuffer(kWidth, kHeight);
  Camera camera = sphere.camera;
  Scene scene = benchScene(sphere.mesh.view(), camera);
  // Warm: buffers grow. Its covered pixels are the fitted view's, the one the peers draw
  // (bench/check_peers.py compares them).
  const RenderStats fitted = renderer.render(scene, camera, framebuffer);
  RenderStats stats = fitted;
  for (auto _ : state) {
    turnView(camera, scene, kTurnDegreesPerFrame);
    stats = renderer.render(scene, camera, framebuffer);
    benchmark::DoNotOptimize(framebuffer.color().data());
  }
  reportCounters(state, stats, sphere.mesh.bytes(), framebuffer.byteSize(), baseline);
  state.counters["pixels"] = static_cast<double>(fitted.pixelsCovered);
}
BENCHMARK(BM_Sphere)
    ->ArgNames({"triangles", "threads", "closed"})
    ->ArgsProduct({{20000, 500000, 2000000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

// BM_Sphere's frame over one whole turn of the camera, a degree a frame, whatever the time it
// takes: the heap peak of every view (what the renderer keeps grows with the largest frame so
// far), the same on any machine. Its peakMiB is the README's peak memory.
BENCHMARK(BM_Sphere)
    ->Name("BM_SphereWholeTurn")
    ->ArgNames({"triangles", "threads", "closed"})
    ->ArgsProduct({{20000, 500000, 2000000}, {2}, {0, 1}})
    ->Iterations(360)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The closed-surface check (isClosedSurface), which the VTK filter runs once per input on
// its first Update(): the spheres as VTK hands them over (bench/closed_surface.md).
//
//   build/bin/facet_bench --benchmark_filter=ClosedSurface
void BM_ClosedSurface(benchmark::State& state) {
  const SphereCase sphere = sphereWithTriangles(state.range(0));
  bool closed = false;
  for (auto _ : state)
    closed = isClosedSurface(sphere.mesh.view());
  if (!closed) state.SkipWithError("sphere not closed");
}
BENCHMARK(BM_ClosedSurface)
    ->ArgNames({"triangles"})
    ->Arg(500000)
    ->Arg(2000000)
    ->Arg(8000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

// The set-up's batches (core/src/SetupBatch.h): the spheres' frames with batches off (every
// polygon through the per-triangle path) and on every instruction set this CPU has, from
// the best to the portable one, rendered in turn in one run. Counters: each variant's set-up
// phase and whole frame, the fastest of the run in ms (the machine is shared: the minimum
// is the frame least disturbed), on one thread also the frame's CPU time (the thread renders
// alone: waiting for a core does not count), and the speed-ups of the best target over
// batches off.
//
//   build/bin/facet_bench --benchmark_filter=SetupBatches
// The calling thread's CPU time: on one thread, the renderer's own.
double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void BM_SetupBatches(benchmark::State& state) {
  SphereCase sphere = sphereWithTriangles(state.range(0));
  sphere.mesh.closed = state.range(2) != 0 && isClosedSurface(sphere.mesh.view());
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  struct Variant {
    Variant(const char* n, bool b, std::int64_t t) : name(n), batches(b), target(t) {}
    const char* name;
    bool batches;
    std::int64_t target;
    Renderer renderer;
    Framebuffer framebuffer{kWidth, kHeight};
    double setupSeconds = 1e30, frameSeconds = 1e30, cpuSeconds = 1e30;
  };
  std::deque<Variant> variants;  // off, then every target, best first
  variants.emplace_back("off", false, 0);
  for (const detail::SimdTarget& target : targets)
    variants.emplace_back(target.name, true, target.bits);
  const Scene scene = benchScene(sphere.mesh.view(), sphere.camera);
  const auto render = [&](Variant& v) {
    detail::enableSetupBatches(v.batches);
    detail::useSimdTarget(v.target);
    const double cpuStart = threadCpuSeconds();
    const RenderStats stats = v.renderer.render(scene, sphere.camera, v.framebuffer);
    v.cpuSeconds = std::min(v.cpuSeconds, threadCpuSeconds() - cpuStart);
    benchmark::DoNotOptimize(v.framebuffer.color().data());
    v.setupSeconds = std::min(v.setupSeconds, stats.setupSeconds);
    v.frameSeconds = std::min(v.frameSeconds, stats.totalSeconds);
  };
  const bool oneThread = state.range(1) == 1;
  for (Variant& v : variants) {
    v.renderer.setThreadCount(static_cast<int>(state.range(1)));
    render(v);  // warm: buffers grow
    v.setupSeconds = v.frameSeconds = v.cpuSeconds = 1e30;
  }
  for (auto _ : state) {
    for (Variant& v : variants)
      render(v);
  }
  detail::enableSetupBatches(true);
  detail::useSimdTarget(0);
  for (const Variant& v : variants) {
    state.counters[std::string(v.name) + " setup ms"] = 1e3 * v.setupSeconds;
    state.counters[std::string(v.name) + " frame ms"] = 1e3 * v.frameSeconds;
    if (oneThread) state.counters[std::string(v.name) + " frame cpu ms"] = 1e3 * v.cpuSeconds;
  }
  const Variant &off = variants[0], &best = variants[1];
  state.counters["setup speed-up"] = off.setupSeconds / best.setupSeconds;
  state.counters["frame speed-up"] = off.frameSeconds / best.frameSeconds;
  if (oneThread) state.counters["cpu speed-up"] = off.cpuSeconds / best.cpuSeconds;
  state.SetLabel(std::string("best: ") + best.name);
}
BENCHMARK(BM_SetupBatches)
    ->ArgNames({"triangles", "threads", "closed"})
    ->ArgsProduct({{500000, 2000000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(12);

// Eight screen-sized quads at different depths and tilts: fill rate with overdraw.
void BM_LargeOverlappingPolygons(benchmark::State& state) {
  const std::size_t baseline = heapBytesInUse();
  Mesh quads;
  for (int i = 0; i < 8; ++i) {
    const double z = -0.1 * i, tilt = 0.05 * (i - 4);
    const std::int64_t base = static_cast<std::int64_t>(quads.points.size());
    quads.addPoint({-1.2 + 0.02 * i, -1.1, z - tilt});
    quads.addPoint({1.2, -1.1 + 0.02 * i, z + tilt});
    quads.addPoint({1.2 - 0.02 * i, 1.1, z + tilt});
    quads.addPoint({-1.2, 1.1 - 0.02 * i, z - tilt});
    quads.addPolygon({base, base + 1, base + 2, base + 3});
  }
  const VtkLikeMesh mesh = toVtkLike(quads);
  resetHeapPeak();
  Camera camera;
  camera.position = {0, 0, 3.8};
  camera.nearClip = 1.0;
  camera.farClip = 10.0;
  Renderer renderer;
  renderer.setThreadCount(static_cast<int>(state.range(0)));
  Framebuffer framebuffer(kWidth, kHeight);
  const Scene scene = benchScene(mesh.view(), camera);
  RenderStats stats = renderer.render(scene, camera, framebuffer);  // warm: buffers grow
  for (auto _ : state) {
    stats = renderer.render(scene, camera, framebuffer);
    benchmark::DoNotOptimize(framebuffer.color().data());
  }
  reportCounters(state, stats, mesh.bytes(), framebuffer.byteSize(), baseline);
}
BENCHMARK(BM_LargeOverlappingPolygons)
    ->ArgNames({"threads"})
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// --- What each rule and incremental path saves ------------------------------------------------

// A scene and its camera, with the meshes it views.
struct SavingScene {
  std::vector<std::shared_ptr<const VtkLikeMesh>> meshes;
  Scene scene;
  Camera camera;
};

// One row of the table: the same frame rendered by two renderers, one doing the work the
// rule leaves out ("everything on") and one with the rule. `change` edits the scene or the
// renderer before every frame of the lean renderer (the incremental rows: a new light).
struct Comparison {
  const char* name;
  SavingScene (*make)();
  RenderRules lean;  // everything on: every rule off, incremental off
  void (*setUp)(Renderer& renderer, bool lean) = nullptr;
  void (*change)(Scene& scene, Renderer& renderer, int frame) = nullptr;
};

// Spheres are slow to build: one of each size for every row.
std::shared_ptr<const VtkLikeMesh> sphereMesh(int triangles, bool closed = false) {
  static std::map<std::pair<int, bool>, std::shared_ptr<const VtkLikeMesh>> spheres;
  auto& sphere = spheres[{triangles, closed}];
  if (!sphere) {
    auto mesh = std::make_shared<VtkLikeMesh>(sphereWithTriangles(triangles).mesh);
    mesh->closed = closed;
    sphere = mesh;
  }
  return sphere;
}

Camera sphereCamera() {
  static const Camera camera = testing::fitCamera(testing::makeUvSphere(16, 18));
  return camera;
}

SavingScene sphereScene(int triangles, LightSet lights, bool closed = false) {
  SavingScene s{{sphereMesh(triangles, closed)}, {}, sphereCamera()};
  s.scene.meshes.push_back({s.meshes[0]->view(), Material{}});
  s.scene.meshes[0].mesh.version = 1;  // measured once (GeometryOutsideView)
  s.scene.lights = std::move(lights);
  return s;
}

LightSet ambientOnly() {
  LightSet lights;
  lights.ambient.intensity = 3.0;
  return lights;
}

LightSet directional() {
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1.0, -0.5, -1.0}, Color(0.9f), 1.0});
  return lights;
}

LightSet headlight() {
  return benchScene({}, sphereCamera()).lights;
}

SavingScene ambientOneColor() {
  return sphereScene(500000, ambientOnly());
}

SavingScene ambientPolygonColors() {
  SavingScene s = ambientOneColor();
  auto mesh = std::make_shared<VtkLikeMesh>(*s.meshes[0]);
  const std::size_t polygons = mesh->offsets.size() - 1;
  for (std::size_t i = 0; i < polygons; ++i)
    mesh->colors.push_back({std::uint8_t(i * 7), std::uint8_t(i * 13), std::uint8_t(i * 31), 255});
  s.meshes[0] = mesh;
  s.scene.meshes[0].mesh = mesh->view();
  return s;
}

SavingScene directionalOneColor() {
  return sphereScene(500000, directional());
}

// Eight spot lights beside the sphere, pointing away from it, and the headlight.
SavingScene spotsOffTheMesh() {
  LightSet lights = headlight();
  for (int i = 0; i < 8; ++i) {
    const double a = i * 0.785398;
    const glm::dvec3 out(std::cos(a), std::sin(a), 0.3);
    lights.lights.push_back(SpotLight{2.0 * out, out, Color(1.0f), 1.0});
  }
  return sphereScene(500000, lights);
}

SavingScene closedSphere() {
  return sphereScene(500000, headlight(), true);
}

SavingScene headlitSphere() {
  return sphereScene(500000, headlight());
}

SavingScene headlitSphere2M() {
  return sphereScene(2000000, headlight());
}

// The 2M sphere seen from its side through a narrow view: the blocks of polygons (half rings
// of the UV sphere) far from the equator are outside it.
SavingScene zoomedSphere() {
  SavingScene s = headlitSphere2M();
  s.camera = testing::fitCamera(testing::makeUvSphere(16, 18), {-1.0, 0.0, 0.0});
  s.camera.viewAngleDegrees = 4.0;
  return s;
}

// Deep occlusion: 64 screen-filling layers of 8 × 8 quads, nearest first.
SavingScene stackedLayers() {
  auto mesh = std::make_shared<VtkLikeMesh>(toVtkLike(testing::makeStackedSquares(64, 8, true)));
  SavingScene s{{mesh}, {}, {}};
  s.camera.position = {0.0, 0.0, 2.0};
  s.camera.nearClip = 0.5;
  s.camera.farClip = 20.0;
  s.camera.viewAngleDegrees = 40.0;
  s.scene.meshes.push_back({mesh->view(), Material{}});
  s.scene.lights = directional();
  return s;
}

void depthOutputOff(Renderer& renderer, bool lean) {
  renderer.setDepthOutput(!lean);
}

// A different light in every frame: the lean renderer re-shades.
void newLight(Scene& scene, Renderer&, int frame) {
  std::get<PointLight>(scene.lights.lights[0]).intensity = frame % 2 ? 0.9 : 1.0;
}

// A different background in every frame: the lean renderer only resolves.
void newBackground(Scene&, Renderer& renderer, int frame) {
  renderer.setBackground(Color(frame % 2 ? 0.2f : 0.1f));
}

RenderRules everythingOn() {
  RenderRules rules;
  rules.lightsThatReachNothing = rules.geometryOutsideView = false;
  rules.hiddenGeometry = HierarchicalZ::Off;
  rules.ambientOnly = rules.oneColor = rules.closedSurfaces = rules.incremental = false;
  return rules;
}

// The rules with `rule` alone on (and incremental off): its saving alone.
RenderRules only(Rule rule) {
  RenderRules rules = everythingOn();
  switch (rule) {
    case Rule::LightsThatReachNothing:
      rules.lightsThatReachNothing = true;
      break;
    case Rule::GeometryOutsideView:
      rules.geometryOutsideView = true;
      break;
    case Rule::HiddenGeometry:
      rules.hiddenGeometry = HierarchicalZ::Auto;
      break;
    case Rule::AmbientOnly:
      rules.ambientOnly = true;
      break;
    case Rule::OneColor:
      rules.oneColor = true;
      break;
    case Rule::ClosedSurfaces:
      rules.closedSurfaces = true;
      break;
  }
  return rules;
}

RenderRules allRules() {
  RenderRules rules;
  rules.incremental = false;
  return rules;
}

RenderRules incremental() {
  RenderRules rules;
  rules.incremental = true;
  return rules;
}

RenderRules forcedCoarseDepth() {
  RenderRules rules = everythingOn();
  rules.hiddenGeometry = HierarchicalZ::On;
  return rules;
}

const std::vector<Comparison>& comparisons() {
  static const std::vector<Comparison> rows = {
      {"ambient only, one color (500k)", ambientOneColor, only(Rule::AmbientOnly)},
      {"ambient only, per-polygon colors (500k)", ambientPolygonColors, only(Rule::AmbientOnly)},
      {"ambient only, one color, every rule (500k)", ambientOneColor, allRules()},
      {"directional only, one color (500k)", directionalOneColor, only(Rule::OneColor)},
      {"spot lights off the mesh (500k)", spotsOffTheMesh, only(Rule::LightsThatReachNothing)},
      {"closed surface (500k)", closedSphere, only(Rule::ClosedSurfaces)},
      {"geometry outside the view (2M, side, 4 degrees)", zoomedSphere,
       only(Rule::GeometryOutsideView)},
      {"deep occlusion, hierarchical z auto (64 layers)", stackedLayers,
       only(Rule::HiddenGeometry)},
      {"sphere, hierarchical z forced on (2M)", headlitSphere2M, forcedCoarseDepth()},
      {"no depth output (500k)", headlitSphere, everythingOn(), depthOutputOff},
      {"re-light: lights changed, re-shade (2M)", headlitSphere2M, incremental(), nullptr,
       newLight},
      {"background changed, resolve only (2M)", headlitSphere2M, incremental(), nullptr,
       newBackground},
  };
  return rows;
}

// One renderer of a row, and its own copy of the scene to change.
struct Contender {
  Renderer renderer;
  Scene scene;
  Framebuffer framebuffer{kWidth, kHeight};

  RenderStats last;

  double frameSeconds(const Camera& camera) {
    const auto start = std::chrono::steady_clock::now();
    last = renderer.render(scene, camera, framebuffer);
    benchmark::DoNotOptimize(framebuffer.color().data());
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

// The lean frame must be the everything-on frame (colors and ids; depth may be off), else
// the row measures nothing worth having.
bool sameImage(const Contender& a, const Contender& b) {
  const auto& fa = a.framebuffer;
  const auto& fb = b.framebuffer;
  return std::equal(fa.color().begin(), fa.color().end(), fb.color().begin()) &&
         std::equal(fa.polygonId().begin(), fa.polygonId().end(), fb.polygonId().begin());
}

// What the lean render left out, for the row's label.
std::string leftOut(const RenderStats& stats) {
  std::string label = stats.plan.path == RenderPath::Full ? "" : stats.plan.pathReason;
  for (int r = 0; r < kRuleCount; ++r) {
    if (stats.plan.rules[r].fired) {
      label += (label.empty() ? "" : "; ") + std::string(ruleName(static_cast<Rule>(r))) + ": " +
               std::to_string(stats.plan.rules[r].skipped);
    }
  }
  return label;
}

void setUpContender(Contender& c, const Comparison& row, const SavingScene& s, bool lean) {
  c.renderer.setThreadCount(2);
  c.renderer.setRules(lean ? row.lean : everythingOn());
  if (row.setUp) row.setUp(c.renderer, lean);
  c.scene = s.scene;
}

void BM_Saving(benchmark::State& state) {
  const Comparison& row = comparisons().at(state.range(0));
  const SavingScene s = row.make();
  Contender everything, lean;
  setUpContender(everything, row, s, false);
  setUpContender(lean, row, s, true);
  everything.frameSeconds(s.camera);  // warm: buffers grow
  lean.frameSeconds(s.camera);
  double everythingSeconds = 0.0, leanSeconds = 0.0;
  int frame = 0;
  for (auto _ : state) {
    if (row.change) {
      row.change(everything.scene, everything.renderer, frame);
      row.change(lean.scene, lean.renderer, frame);
    }
    ++frame;
    everythingSeconds += everything.frameSeconds(s.camera);
    leanSeconds += lean.frameSeconds(s.camera);
  }
  if (!sameImage(everything, lean)) state.SkipWithError("the rule changed the image");
  state.SetLabel(std::string(row.name) + " [" + leftOut(lean.last) + "]");
  state.counters["everything ms"] = 1e3 * everythingSeconds / frame;
  state.counters["lean ms"] = 1e3 * leanSeconds / frame;
  state.counters["saving"] = everythingSeconds / leanSeconds;
}
BENCHMARK(BM_Saving)
    ->DenseRange(0, 11)
    ->ArgName("row")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(4.0);

}  // namespace
}  // namespace facet::bench

BENCHMARK_MAIN();
