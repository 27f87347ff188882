// What vtkFacetRenderFilter::Update() costs beyond the core's frame, measured in one process
// so that the machine's load falls on both alike: the filter renders vtkSphereSource's sphere
// at 1920 × 1080 with a camera turning every frame (RGBA + Depth + CellId output), and a bare
// facet::Renderer renders the same arrays (float points, VTK's 64-bit cells, the same
// camera and light) into a facet::Framebuffer, frame by frame in turn. Per side: the median
// wall and CPU time (all threads of the process) per frame, and the page faults per frame;
// then the median of each phase of Update() (its FacetPhaseSeconds; "outside" is the
// Update() less the filter's own FacetRenderSeconds: the executive and the field data) and of
// the core frame's phases.
//
// A third side, "bench mesh", is facet_bench's BM_Sphere frame at the same camera: the
// makeUvSphere mesh (vtkSphereSource's topology, but its triangles listed ring by ring where
// vtkSphereSource lists them meridian by meridian) with BM_Sphere's unattenuated light. The
// per-frame ratios say how much of "Update closed against core closed" in `make bench-peers`
// is the filter and how much is the two benches drawing differently ordered meshes
// (bench/filter_overhead.md, id24).
//
//   build/bin/facet_filter_overhead THETA CLOSED [THREADS] [FRAMES] [WIDTH HEIGHT]
//                                   [--no-estimate] [--turn=DEGREES] [--per-frame]
//                                   [--bench-lit-as-filter] [--no-cell-ids]
//   build/bin/facet_filter_overhead 500 0 2 20      # 500k triangles, every face
//   build/bin/facet_filter_overhead 1000 1 1 20     # 2M triangles, closed, one thread
//   build/bin/facet_filter_overhead 500 1 2 10 3840 2160   # at 4K
//   build/bin/facet_filter_overhead 500 1 2 10 --no-estimate --turn=36  # bench-peers' turn
//
// (THETA: vtkSphereSource's theta resolution, phi = theta + 2: 2·theta² triangles.)
// --no-estimate: the filter's EstimateError off, as bench/filter_speed.py and
// `make bench-peers` time it (on by default, as the filter's default). --turn: the degrees
// the camera turns before each frame (default 0.5; bench-peers' Update() turns 360 / frames,
// facet_bench's BM_Sphere 1 from the fitted view). --per-frame: each frame's times.
// --bench-lit-as-filter: the bench mesh lit as the filter lights (VTK's attenuation 1, 0, 0),
// so that "core / bench mesh" is the two meshes' order alone. --no-cell-ids: the filter's
// OutputCellIds off (RGBA and Depth, as the core side writes), so that "Update/core" is the
// filter less its 64-bit CellId plane.

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFacetRenderFilter.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTypeInt64Array.h"

#include "facet/Framebuffer.h"
#include "facet/Renderer.h"
#include "support/TestMeshes.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace {
struct Sample {
  double wall = 0.0, cpu = 0.0, faults = 0.0;
};

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double minorFaults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_minflt + usage.ru_majflt);
}

template <class Work>
Sample timed(Work&& work) {
  const auto wall = std::chrono::steady_clock::now();
  const double cpu = processCpuSeconds(), faults = minorFaults();
  work();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count(),
          processCpuSeconds() - cpu, minorFaults() - faults};
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

double median(const std::vector<Sample>& samples, double Sample::*field) {
  std::vector<double> values;
  for (const Sample& s : samples)
    values.push_back(s.*field);
  return median(values);
}

// Each field's median.
Sample median(const std::vector<Sample>& samples) {
  return {median(samples, &Sample::wall), median(samples, &Sample::cpu),
          median(samples, &Sample::faults)};
}

// Per phase, its seconds in each frame.
struct PhaseSeries {
  std::vector<const char*> names;
  std::vector<std::vector<double>> seconds;

  void add(std::initializer_list<std::pair<const char*, double>> phases) {
    if (names.empty()) {
      for (const auto& phase : phases)
        names.push_back(phase.first);
      seconds.resize(names.size());
    }
    std::size_t i = 0;
    for (const auto& phase : phases)
      seconds[i++].push_back(phase.second);
  }
  // The median of each phase, and its best (on a loaded machine the steadier of the two for
  // comparing builds phase by phase).
  void print(const char* title) const {
    std::printf("  %s, median ms:", title);
    for (std::size_t i = 0; i < names.size(); ++i)
      std::printf(" %s %.2f", names[i], 1e3 * median(seconds[i]));
    std::printf("\n  %s, best ms:", title);
    for (std::size_t i = 0; i < names.size(); ++i)
      std::printf(" %s %.2f", names[i],
                  1e3 * *std::min_element(seconds[i].begin(), seconds[i].end()));
    std::printf("\n");
  }
};

// The filter's phases of its last execution (vtkFacetImageRenderer's field data), with the
// time of the Update() outside them.
void addFilterPhases(PhaseSeries& series, vtkImageData* output, double updateSeconds) {
  vtkFieldData* fields = output->GetFieldData();
  vtkDataArray* phases = fields->GetArray("FacetPhaseSeconds");
  const double total = fields->GetArray("FacetRenderSeconds")->GetComponent(0, 0);
  const auto phase = [&](int i) { return phases->GetComponent(0, i); };
  series.add({{"conversion", phase(0)},
              {"validate", phase(1)},
              {"transform", phase(2)},
              {"setup", phase(3)},
              {"raster", phase(4)},
              {"shade+resolve", phase(5)},
              {"output", phase(6)},
              {"render total", total},
              {"outside", updateSeconds - total}});
}

void addCorePhases(PhaseSeries& series, const facet::RenderStats& s) {
  series.add({{"validate", s.validateSeconds},
              {"transform", s.transformSeconds},
              {"setup", s.setupSeconds},
              {"raster", s.rasterSeconds},
              {"shade+resolve", s.shadeSeconds},
              {"total", s.totalSeconds}});
}

// The frame's work counts, in thousands (printed by PhaseSeries as if milliseconds).
void addCoreCounts(PhaseSeries& series, const facet::RenderStats& s) {
  const auto thousands = [](std::size_t n) { return 1e-6 * static_cast<double>(n); };
  series.add({{"drawn", thousands(s.polygonsDrawn)},
              {"culled", thousands(s.polygonsCulled)},
              {"binned", thousands(s.trianglesBinned)},
              {"hidden", thousands(s.trianglesHidden)},
              {"fragments", thousands(s.fragmentsWritten)},
              {"shaded", thousands(s.polygonsShaded)}});
}

// The filter's camera conversion for a plain perspective vtkCamera (vtkFacetSceneConverter).
facet::Camera cameraOf(vtkCamera* camera) {
  const auto vec = [](const double* v) { return glm::dvec3(v[0], v[1], v[2]); };
  facet::Camera c;
  c.position = vec(camera->GetPosition());
  c.focalPoint = vec(camera->GetFocalPoint());
  c.viewUp = vec(camera->GetViewUp());
  c.viewAngleDegrees = camera->GetViewAngle();
  c.nearClip = camera->GetClippingRange()[0];
  c.farClip = camera->GetClippingRange()[1];
  return c;
}
// facet_bench's BM_Sphere mesh (bench/CoreBench.cpp): makeUvSphere's order, float points,
// 64-bit cells, versioned, the closed-surface hint when asked.
struct BenchMesh {
  std::vector<float> xyz;
  std::vector<std::int64_t> offsets, connectivity;
  facet::MeshView view;

  BenchMesh(int theta, bool closed) {
    // vtkSphereSource's radius (0.5), for the same camera; BM_Sphere's radius 1 with a camera
    // fitted to it draws the same image.
    const facet::Mesh sphere = facet::testing::makeUvSphere(theta, theta + 2, 0.5);
    for (const glm::dvec3& p : sphere.points)
      xyz.insert(xyz.end(), {float(p.x), float(p.y), float(p.z)});
    offsets = sphere.offsets;
    connectivity = sphere.connectivity;
    view.points = facet::PointArray::ofXyz(xyz);
    view.polygons = facet::PolygonArray::of(offsets, connectivity);
    view.version = 1;
    view.closedSurface = closed && facet::isClosedSurface(view);
  }
};

// A bare core renderer drawing one mesh with a headlight (VTK's positional light at the
// camera, attenuated as given) into a framebuffer of its own.
struct CoreSide {
  facet::Scene scene;
  facet::Renderer renderer;
  facet::Framebuffer framebuffer;
  facet::Attenuation attenuation;
  facet::RenderStats stats;

  CoreSide(const facet::MeshView& mesh, int threads, int width, int height,
           facet::Attenuation lightAttenuation)
      : framebuffer(width, height), attenuation(lightAttenuation) {
    scene.meshes.push_back({mesh, facet::Material{}});
    scene.lights.ambient.intensity = 0.0;
    renderer.setThreadCount(threads);
  }
  void render(vtkCamera* camera) {
    const facet::Camera view = cameraOf(camera);
    scene.lights.lights = {facet::PointLight{view.position, facet::Color(1.0f), 1.0, attenuation}};
    stats = renderer.render(scene, view, framebuffer);
  }
};

// The median of the ratios a[i] / b[i] of frames rendered one after the other.
double medianRatio(const std::vector<Sample>& a, const std::vector<Sample>& b,
                   double Sample::*field) {
  std::vector<double> ratios;
  for (std::size_t i = 0; i < a.size(); ++i)
    ratios.push_back(a[i].*field / b[i].*field);
  return median(ratios);
}
}  // namespace

int main(int argc, char** argv) {
  bool estimate = true, perFrame = false, benchLitAsFilter = false, cellIds = true;
  double turnDegrees = 0.5;
  std::vector<char*> positional{argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    if (arg == "--no-estimate")
      estimate = false;
    else if (arg == "--per-frame")
      perFrame = true;
    else if (arg == "--bench-lit-as-filter")
      benchLitAsFilter = true;
    else if (arg == "--no-cell-ids")
      cellIds = false;
    else if (arg.substr(0, 7) == "--turn=")
      turnDegrees = std::atof(argv[i] + 7);
    else
      positional.push_back(argv[i]);
  }
  argc = static_cast<int>(positional.size());
  argv = positional.data();
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s THETA CLOSED [THREADS] [FRAMES] [WIDTH HEIGHT] [--no-estimate] "
                 "[--turn=DEGREES] [--per-frame] [--bench-lit-as-filter] [--no-cell-ids]\n",
                 argv[0]);
    return 2;
  }
  const int theta = std::atoi(argv[1]);
  const bool closed = std::atoi(argv[2]) != 0;
  const int threads = argc > 3 ? std::atoi(argv[3]) : 2;
  const int frames = argc > 4 ? std::atoi(argv[4]) : 20;
  const int width = argc > 6 ? std::atoi(argv[5]) : 1920;
  const int height = argc > 6 ? std::atoi(argv[6]) : 1080;

  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(theta);
  source->SetPhiResolution(theta + 2);
  source->Update();
  vtkPolyData* sphere = source->GetOutput();

  // bench/filter_speed.py's scene: the camera fitted by vtkRenderer, a positional light at it.
  vtkNew<vtkRenderer> fit;
  fit->SetAspect(double(width) / height, 1.0);
  vtkCamera* camera = fit->GetActiveCamera();
  fit->ResetCamera(sphere->GetBounds());
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetConeAngle(180);
  light->SetPosition(camera->GetPosition());
  light->SetFocalPoint(camera->GetFocalPoint());

  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputConnection(source->GetOutputPort());
  filter->SetSize(width, height);
  filter->SetCamera(camera);
  filter->AddLight(light);
  filter->SetAmbientLightColor(0, 0, 0);
  filter->SetNumberOfThreads(threads);
  filter->SetDetectClosedSurfaces(closed);
  filter->SetEstimateError(estimate);
  filter->SetOutputCellIds(cellIds);

  // The same arrays, straight into the core: a versioned mesh, as the filter's.
  facet::MeshView mesh;
  auto* points = vtkFloatArray::SafeDownCast(sphere->GetPoints()->GetData());
  mesh.points = facet::PointArray::ofXyz(
      std::span<const float>(points->GetPointer(0), 3 * points->GetNumberOfTuples()));
  vtkCellArray* polys = sphere->GetPolys();
  const auto int64s = [](auto* array) {
    return std::span<const std::int64_t>(
        reinterpret_cast<const std::int64_t*>(array->GetPointer(0)),
        static_cast<std::size_t>(array->GetNumberOfValues()));
  };
  mesh.polygons = facet::PolygonArray::of(int64s(polys->GetOffsetsArray64()),
                                          int64s(polys->GetConnectivityArray64()));
  mesh.version = 1;
  mesh.closedSurface = closed && facet::isClosedSurface(mesh);
  CoreSide core(mesh, threads, width, height, facet::QuadraticAttenuation{1.0, 0.0, 0.0});
  // BM_Sphere's frame at the same camera: its mesh and its light (no attenuation).
  const BenchMesh benchMesh(theta, closed);
  CoreSide bench(benchMesh.view, threads, width, height,
                 benchLitAsFilter ? facet::Attenuation{facet::QuadraticAttenuation{1.0, 0.0, 0.0}}
                                  : facet::Attenuation{facet::NoAttenuation{}});
  const auto renderCore = [&] { core.render(camera); };
  const auto renderBench = [&] { bench.render(camera); };

  const Sample firstUpdate = timed([&] { filter->Update(); });
  renderCore();
  renderBench();
  std::vector<Sample> updates, cores, benches;
  PhaseSeries updatePhases, corePhases, benchPhases, coreCounts, benchCounts;
  for (int f = 0; f < frames; ++f) {
    camera->Azimuth(turnDegrees);
    updates.push_back(timed([&] { filter->Update(); }));
    addFilterPhases(updatePhases, filter->GetOutput(), updates.back().wall);
    cores.push_back(timed(renderCore));
    addCorePhases(corePhases, core.stats);
    addCoreCounts(coreCounts, core.stats);
    benches.push_back(timed(renderBench));
    addCorePhases(benchPhases, bench.stats);
    addCoreCounts(benchCounts, bench.stats);
    if (perFrame)
      std::printf(
          "  frame %d at %.0f degrees, ms wall / CPU: Update %.2f / %.2f, core %.2f / "
          "%.2f, bench mesh %.2f / %.2f\n",
          f, (f + 1) * turnDegrees, 1e3 * updates.back().wall, 1e3 * updates.back().cpu,
          1e3 * cores.back().wall, 1e3 * cores.back().cpu, 1e3 * benches.back().wall,
          1e3 * benches.back().cpu);
  }
  const Sample u = median(updates), c = median(cores), b = median(benches);
  std::printf(
      "%d triangles, %d x %d, %s, %d threads, median of %d frames in turn: Update() %.1f ms "
      "(CPU %.1f ms, %.0f page faults), core %.1f ms (CPU %.1f ms, %.0f page faults); "
      "Update/core wall %.3f, CPU %.3f; first Update() %.3f s%s\n",
      2 * theta * theta, width, height, closed ? "closed" : "every face", threads, frames,
      1e3 * u.wall, 1e3 * u.cpu, u.faults, 1e3 * c.wall, 1e3 * c.cpu, c.faults, u.wall / c.wall,
      u.cpu / c.cpu, firstUpdate.wall,
      (std::string(estimate ? "" : "; estimate off") + (cellIds ? "" : "; no CellId")).c_str());
  std::printf(
      "  turn %.1f degrees per frame; bench mesh (BM_Sphere's) %.1f ms (CPU %.1f ms); "
      "median of the per-frame ratios, wall / CPU: Update/core %.3f / %.3f, "
      "core/bench mesh %.3f / %.3f, Update/bench mesh %.3f / %.3f\n",
      turnDegrees, 1e3 * b.wall, 1e3 * b.cpu, medianRatio(updates, cores, &Sample::wall),
      medianRatio(updates, cores, &Sample::cpu), medianRatio(cores, benches, &Sample::wall),
      medianRatio(cores, benches, &Sample::cpu), medianRatio(updates, benches, &Sample::wall),
      medianRatio(updates, benches, &Sample::cpu));
  updatePhases.print("Update()");
  corePhases.print("core");
  benchPhases.print("bench mesh");
  coreCounts.print("core, thousands");
  benchCounts.print("bench mesh, thousands");
  return 0;
}
