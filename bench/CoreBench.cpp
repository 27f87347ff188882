// Core rasterizer throughput at 1920 × 1080: spheres of 20k, 500k and 2M triangles and a few
// large overlapping polygons, on 1 and 2 threads. Every frame includes the clear.
//
//   build/bench/facet_bench                       # all
//   build/bench/facet_bench --benchmark_filter=Sphere/500000
//
// Counters: triangles/s (input polygons per second) and fragments/s (fill rate, pixel writes incl.
// overdraw), and the heap peak during the benchmark (mesh + framebuffer + renderer) as a ratio of
// the bytes of the mesh plus the framebuffer (target: at most 2).

#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "HeapCounter.h"
#include "facet/Renderer.h"
#include "support/TestMeshes.h"

namespace facet::bench {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;

// A mesh the way VTK hands it over: float points, 64-bit offsets and connectivity.
struct VtkLikeMesh {
  std::vector<float> xyz;
  std::vector<std::int64_t> offsets, connectivity;
  bool closed = false;
  MeshView view() const {
    return {PointArray::ofXyz(xyz), PolygonArray::of(offsets, connectivity), {}, closed};
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
  const int theta = triangles == 20000 ? 100 : triangles == 500000 ? 500 : 1000;
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

// closed = 1: the mesh carries the MeshView::closedSurface hint, computed once here (as the
// VTK filter does once per input): hidden back faces are skipped. closed = 0: every face
// is drawn, as VTK's renderer does.
void BM_Sphere(benchmark::State& state) {
  const std::size_t baseline = heapBytesInUse();
  SphereCase sphere = sphereWithTriangles(state.range(0));
  sphere.mesh.closed = state.range(2) != 0 && isClosedSurface(sphere.mesh.view());
  if (state.range(2) != 0 && !sphere.mesh.closed) state.SkipWithError("sphere not closed");
  resetHeapPeak();
  Renderer renderer;
  renderer.setThreadCount(static_cast<int>(state.range(1)));
  Framebuffer framebuffer(kWidth, kHeight);
  const Scene scene = benchScene(sphere.mesh.view(), sphere.camera);
  RenderStats stats = renderer.render(scene, sphere.camera, framebuffer);  // warm: buffers grow
  for (auto _ : state) {
    stats = renderer.render(scene, sphere.camera, framebuffer);
    benchmark::DoNotOptimize(framebuffer.color().data());
  }
  reportCounters(state, stats, sphere.mesh.bytes(), framebuffer.byteSize(), baseline);
}
BENCHMARK(BM_Sphere)
    ->ArgNames({"triangles", "threads", "closed"})
    ->ArgsProduct({{20000, 500000, 2000000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

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

}  // namespace
}  // namespace facet::bench

BENCHMARK_MAIN();
