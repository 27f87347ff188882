// The time of each render phase for facet_bench's sphere (BM_Sphere: 1920 × 1080, one
// positional light at the eye, float points and 64-bit cells as VTK hands them over), over a
// fixed number of frames: the best of each phase, for comparing two builds phase by phase.
// A fixed frame count also makes the program's instruction count comparable between builds
// (valgrind --tool=callgrind), which the load of a shared machine does not change.
//
// By default the frames are the VTK filter's (TurningView.h): a versioned mesh, the camera
// (and the light at its eye) turning TURN = 1 degree about the sphere's axis every frame.
// TURN 0 keeps the camera still (a versioned mesh's frame is then reused: RenderPath::Resolve);
// VERSION 0 renders the mesh unversioned, validated and its normals computed every frame.
// START turns the camera that many degrees before the first frame: past 90 the sphere's far
// half comes first in mesh order (every face drawn: its back faces are binned before the
// front faces over them).
// ARRAYS picks the arrays' types as an adapter hands them over: f64 (the default: float
// points, 64-bit cells, the set-up instantiation the figures are for), d64, f32 or d32 (d:
// double points, as VTK's vtkPoints default; 32: 32-bit offsets and connectivity). The
// points are the same values in float or double, so the types change the code, not the mesh.
// ORDER picks the order the sphere lists its points and triangles in (testing::UvSphereOrder):
// ring (the default: ring by ring, facet_bench's) or vtk (exactly vtkSphereSource's, meridian
// by meridian: the VTK filter's users' sphere). The same surface is drawn either way. ORDER
// both renders the two in one process, frame by frame in turn at the same views, and prints
// each one's process CPU time a frame and their ratio (the measure that holds under load).
// CACHE picks the caches' state at each frame's start: warm (the default: the previous frame
// left them), cold (before each frame, outside the timed part, two threads write and read
// 64 MB of their own, twice the VM's 32 MB L3, as a VTK frame between two Updates would) or
// both (cold and warm frames in turn, which first alternating; each phase's median of either
// kind and their difference printed: what the cold caches cost a phase).
//
//   build/bin/facet_phase_times TRIANGLES CLOSED [FRAMES] [THREADS] [TURN] [VERSION] [START]
//                               [ARRAYS] [ORDER] [CACHE]
//   build/bin/facet_phase_times 500000 0 20 2
//
// It uses only the public API and the tests' sphere generator, so it also compiles against
// an older tree (bench/full_render_speed.md).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "TurningView.h"
#include "facet/Renderer.h"
#include "support/TestMeshes.h"

namespace {

using namespace facet;

struct Phases {
  double seconds[6] = {1e30, 1e30, 1e30, 1e30, 1e30, 1e30};
  void keepBest(const RenderStats& s) {
    const double now[6] = {s.validateSeconds, s.transformSeconds, s.setupSeconds,
                           s.rasterSeconds,   s.shadeSeconds,     s.totalSeconds};
    for (int i = 0; i < 6; ++i)
      seconds[i] = std::min(seconds[i], now[i]);
  }
};

// Each phase's times, every frame's, for medians.
struct PhaseSamples {
  std::vector<double> seconds[6];
  void add(const RenderStats& s) {
    const double now[6] = {s.validateSeconds, s.transformSeconds, s.setupSeconds,
                           s.rasterSeconds,   s.shadeSeconds,     s.totalSeconds};
    for (int i = 0; i < 6; ++i)
      seconds[i].push_back(now[i]);
  }
  double median(int phase) const {
    std::vector<double> v = seconds[phase];
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  }
};

// CACHE cold: two threads (the renderer's default thread count here) each write then read a
// 64 MB buffer of their own, so that neither core's L2 nor the shared L3 holds the mesh, the
// renderer's buffers or the framebuffer when the frame starts; not timed.
class CacheEvictor {
 public:
  void evict() {
    std::thread other([this] { sweep(buffers_[1]); });
    sweep(buffers_[0]);
    other.join();
  }

 private:
  static constexpr std::size_t kWords = (std::size_t{64} << 20) / sizeof(std::uint64_t);
  void sweep(std::vector<std::uint64_t>& buffer) {
    if (buffer.empty()) buffer.resize(kWords);
    ++pass_;
    for (std::size_t i = 0; i < buffer.size(); i += 8)  // one write a 64-byte line
      buffer[i] = pass_ + i;
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < buffer.size(); i += 8)
      sum += buffer[i];
    sink_ = sink_ + sum;
  }
  std::vector<std::uint64_t> buffers_[2];
  std::uint64_t pass_ = 0;
  volatile std::uint64_t sink_ = 0;
};

// FNV-1a over the last frame's color, depth and polygon-id bytes: two builds that must give
// the same bytes print the same number.
std::uint64_t fingerprint(const Framebuffer& framebuffer) {
  std::uint64_t hash = 14695981039346656037ull;
  const auto add = [&](const auto& plane) {
    for (const std::byte b : std::as_bytes(plane))
      hash = (hash ^ std::to_integer<std::uint64_t>(b)) * 1099511628211ull;
  };
  add(framebuffer.color());
  add(framebuffer.depth());
  add(framebuffer.polygonId());
  return hash;
}

// The sphere's arrays in the types ARRAYS names (see the top), kept alive for the view.
struct SphereArrays {
  std::vector<float> xyzFloat;
  std::vector<double> xyzDouble;
  std::vector<std::int32_t> offsets32, connectivity32;

  MeshView view(const Mesh& sphere, std::string_view arrays, bool closed) {
    for (const auto& p : sphere.points) {
      for (const double c : {p.x, p.y, p.z}) {
        xyzFloat.push_back(static_cast<float>(c));
        xyzDouble.push_back(static_cast<float>(c));  // the float points' values
      }
    }
    const bool doublePoints = arrays[0] == 'd';
    const PointArray points =
        doublePoints ? PointArray::ofXyz(xyzDouble) : PointArray::ofXyz(xyzFloat);
    if (arrays.substr(1) != "32") {
      return {points, PolygonArray::of(sphere.offsets, sphere.connectivity), {}, closed};
    }
    offsets32.assign(sphere.offsets.begin(), sphere.offsets.end());
    connectivity32.assign(sphere.connectivity.begin(), sphere.connectivity.end());
    return {points, PolygonArray::of(offsets32, connectivity32), {}, closed};
  }
};

// The options that pick the frames (see the top).
struct Options {
  int triangles = 0;
  bool closed = false;
  int frames = 20, threads = 2;
  double turn = bench::kTurnDegreesPerFrame;
  std::uint64_t version = 1;
  double start = 0.0;
  std::string_view arrays = "f64";
  std::string_view cache = "warm";
};

const char* nameOf(testing::UvSphereOrder order) {
  return order == testing::UvSphereOrder::vtkSphereSource ? "vtk" : "ring";
}

// facet_bench's sphere in one order, its light at the eye, its renderer and framebuffer.
struct SphereScene {
  Mesh sphere;
  SphereArrays storage;
  Scene scene;
  Camera camera;
  Renderer renderer;
  Framebuffer framebuffer{1920, 1080};

  SphereScene(const Options& o, testing::UvSphereOrder order) {
    // vtkSphereSource's resolution for a triangle count: 2·theta·(phi − 2) triangles, as
    // CoreBench's sphereWithTriangles picks it (the same spheres as facet_bench's).
    const int theta = static_cast<int>(std::lround(std::sqrt(o.triangles / 2.0)));
    sphere = testing::makeUvSphere(theta, theta + 2, 1.0, glm::dvec3(0.0), order);
    MeshView view = storage.view(sphere, o.arrays, o.closed);
    camera = testing::fitCamera(sphere);
    view.version = o.version;
    scene.meshes.push_back({view, Material{}});
    scene.lights.ambient.intensity = 0.0;
    scene.lights.lights.push_back(PointLight{camera.position, Color(1.0f), 1.0, NoAttenuation{}});
    if (o.start != 0.0) bench::turnView(camera, scene, o.start);
    renderer.setThreadCount(o.threads);
  }

  RenderStats render() { return renderer.render(scene, camera, framebuffer); }
  void turn(double degrees) {
    if (degrees != 0.0) bench::turnView(camera, scene, degrees);
  }
};

// The process's CPU time, every thread's: it stops while the threads are descheduled, so the
// ratio of two orders' sums holds under a shared machine's load where wall time does not.
double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

int run(const Options& o, testing::UvSphereOrder order) {
  SphereScene s(o, order);
  // The first frame: buffers grow, the versioned mesh is measured (the filter's first
  // Update()); not among the best.
  const RenderStats first = s.render();
  Phases best;
  RenderStats last;
  CacheEvictor evictor;
  Phases bestOf[2];            // CACHE both: [0] cold frames, [1] warm frames
  PhaseSamples samples[2];     // every frame's phases, cold and warm (warm only unless CACHE)
  std::vector<double> cpu[2];  // every frame's process CPU time, cold and warm
  for (int i = 0; i < o.frames; ++i) {
    s.turn(o.turn);
    const bool cold = o.cache == "cold" || (o.cache == "both" && i % 2 == 0);
    if (cold) evictor.evict();
    const double before = processCpuSeconds();
    last = s.render();
    cpu[cold ? 0 : 1].push_back(processCpuSeconds() - before);
    best.keepBest(last);
    bestOf[cold ? 0 : 1].keepBest(last);
    samples[cold ? 0 : 1].add(last);
  }
  static constexpr const char* kPhaseNames[6] = {"validate", "transform",     "setup",
                                                 "raster",   "shade+resolve", "total"};
  for (int kind = 0; kind < 2; ++kind) {
    if (samples[kind].seconds[0].empty()) continue;
    std::printf("%s frames (%zu), median ms:", kind == 0 ? "cold" : "warm",
                samples[kind].seconds[0].size());
    for (int p = 0; p < 6; ++p)
      std::printf(" %s %.3f", kPhaseNames[p], samples[kind].median(p) * 1e3);
    std::vector<double>& c = cpu[kind];
    std::nth_element(c.begin(), c.begin() + c.size() / 2, c.end());
    std::printf("; CPU %.3f; best ms:", c[c.size() / 2] * 1e3);
    for (int p = 0; p < 6; ++p)
      std::printf(" %s %.3f", kPhaseNames[p], bestOf[kind].seconds[p] * 1e3);
    std::printf("\n");
  }
  if (!samples[0].seconds[0].empty() && !samples[1].seconds[0].empty()) {
    std::printf("cold - warm, medians, ms:");
    for (int p = 0; p < 6; ++p)
      std::printf(" %s %+.3f", kPhaseNames[p], (samples[0].median(p) - samples[1].median(p)) * 1e3);
    std::printf("\n");
  }
  const double* t = best.seconds;
  std::printf(
      "%d triangles, closed %d, %d threads, turn %g from %g, version %llu, arrays %s, order %s, "
      "best of %d frames, ms: validate %.3f transform %.3f setup %.3f raster %.3f shade+resolve "
      "%.3f total %.3f; last frame: %zu fragments written, %zu back-facing blocks skipped, planes "
      "%016llx; first frame: validate %.3f total %.3f\n",
      o.triangles, int(o.closed), o.threads, o.turn, o.start,
      static_cast<unsigned long long>(o.version), std::string(o.arrays).c_str(), nameOf(order),
      o.frames, t[0] * 1e3, t[1] * 1e3, t[2] * 1e3, t[3] * 1e3, t[4] * 1e3, t[5] * 1e3,
      last.fragmentsWritten, last.plan.blocksBackFacing,
      static_cast<unsigned long long>(fingerprint(s.framebuffer)), first.validateSeconds * 1e3,
      first.totalSeconds * 1e3);
  return 0;
}

// ORDER both: the two orders' spheres rendered in one process, frame by frame in turn (which
// goes first alternates), at the same views; each frame's process CPU time summed per order.
int runBothOrders(const Options& o) {
  constexpr testing::UvSphereOrder kOrders[2] = {testing::UvSphereOrder::ringByRing,
                                                 testing::UvSphereOrder::vtkSphereSource};
  SphereScene ring(o, kOrders[0]), vtk(o, kOrders[1]);
  SphereScene* scenes[2] = {&ring, &vtk};
  for (SphereScene* s : scenes)
    s->render();  // the first frame: buffers grow, the mesh is measured
  double cpu[2] = {0.0, 0.0};
  Phases best[2];
  RenderStats last[2];
  CacheEvictor evictor;
  for (int i = 0; i < o.frames; ++i) {
    for (int k = 0; k < 2; ++k) {
      const int side = (i + k) % 2;
      scenes[side]->turn(o.turn);
      // CACHE cold or both: every frame cold here (both orders alike).
      if (o.cache != "warm") evictor.evict();
      const double before = processCpuSeconds();
      last[side] = scenes[side]->render();
      cpu[side] += processCpuSeconds() - before;
      best[side].keepBest(last[side]);
    }
  }
  for (int side = 0; side < 2; ++side) {
    const double* t = best[side].seconds;
    std::printf(
        "%d triangles, closed %d, %d threads, turn %g, order %s, %d frames: CPU %.3f ms a frame; "
        "best wall ms: transform %.3f setup %.3f raster %.3f shade+resolve %.3f total %.3f; last "
        "frame: %zu back-facing blocks skipped, planes %016llx\n",
        o.triangles, int(o.closed), o.threads, o.turn, nameOf(kOrders[side]), o.frames,
        cpu[side] / o.frames * 1e3, t[1] * 1e3, t[2] * 1e3, t[3] * 1e3, t[4] * 1e3, t[5] * 1e3,
        last[side].plan.blocksBackFacing,
        static_cast<unsigned long long>(fingerprint(scenes[side]->framebuffer)));
  }
  std::printf("CPU vtk / ring %.4f\n", cpu[1] / cpu[0]);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const int triangles = argc < 3 ? 0 : std::atoi(argv[1]);
  if (triangles < 18) {  // theta >= 3
    std::fprintf(
        stderr,
        "usage: %s TRIANGLES(>= 18, e.g. 20000, 500000, 2000000) CLOSED(0|1) [FRAMES] "
        "[THREADS] [TURN degrees per frame, default %g] [VERSION, default 1; 0: unversioned] "
        "[START degrees turned before the first frame, default 0] [ARRAYS f64|d64|f32|d32] "
        "[ORDER ring|vtk|both] [CACHE warm|cold|both]\n",
        argv[0], bench::kTurnDegreesPerFrame);
    return 2;
  }
  const std::string_view arrays = argc > 8 ? argv[8] : "f64";
  if (arrays != "f64" && arrays != "d64" && arrays != "f32" && arrays != "d32") {
    std::fprintf(stderr, "ARRAYS is f64, d64, f32 or d32, not %s\n", argv[8]);
    return 2;
  }
  const std::string_view order = argc > 9 ? argv[9] : "ring";
  if (order != "ring" && order != "vtk" && order != "both") {
    std::fprintf(stderr, "ORDER is ring, vtk or both, not %s\n", argv[9]);
    return 2;
  }
  const std::string_view cache = argc > 10 ? argv[10] : "warm";
  if (cache != "warm" && cache != "cold" && cache != "both") {
    std::fprintf(stderr, "CACHE is warm, cold or both, not %s\n", argv[10]);
    return 2;
  }
  Options options;
  options.cache = cache;
  options.triangles = triangles;
  options.closed = std::atoi(argv[2]) != 0;
  if (argc > 3) options.frames = std::atoi(argv[3]);
  if (argc > 4) options.threads = std::atoi(argv[4]);
  if (argc > 5) options.turn = std::atof(argv[5]);
  if (argc > 6) options.version = std::strtoull(argv[6], nullptr, 10);
  if (argc > 7) options.start = std::atof(argv[7]);
  options.arrays = arrays;
  if (order == "both") return runBothOrders(options);
  return run(options, order == "vtk" ? testing::UvSphereOrder::vtkSphereSource
                                     : testing::UvSphereOrder::ringByRing);
}
