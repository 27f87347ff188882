// What the flat-shading error estimate (QualityRenderer, estimateError) adds to a frame: the
// filter's scene in the core alone (a UV sphere, one unattenuated positional light at the
// eye, every face drawn, 1920 × 1080, 2 threads), the camera turning 0.5° a frame. Two
// renderers side by side, the estimate off and on, alternate frame by frame, so the load of
// the moment weighs on both alike; CPU time of the process (CLOCK_PROCESS_CPUTIME_ID).
//
//   facet_estimate_cost [segments...] [--frames N] [--rounds R] [--phases] [--only off|on]
//                       [--per-pixel] [--headlight] [--threads T] [--size W H]
//
// Per sphere (segments around; ~2·segments² triangles: 500 → 500k, 1000 → 2M) and round:
// the median CPU of a frame off and on and the ratio, the estimate's own wall time outside the
// render (QualityStats::estimateSeconds: 0.0 when the render's shade and resolve take it, as
// here), and the first frame's CPU off and on, and its wall time on (on: the vertex normals
// and the polygons' bound terms, found once per mesh version). bench/estimate-cost.md has the
// figures.
//
// --phases: after each row, the median wall ms of each of the render's phases off and on, and
// the QualityRenderer's own time around the render (QualityStats::totalSeconds less the
// render's): where the estimate's CPU goes, phase by phase.
// --only off|on: renders with that renderer alone (both still take the first frame), so that
// callgrind or perf stat counts one side; the other side's columns then read 0.
// --per-pixel: the estimate asks for the ErrorEstimate image too, which takes the per-pixel
// estimate (every polygon's bound per frame, the 3 × 3 rule with it) in place of the
// summary-only one (QualityRenderer.cpp, estimateSummary): its cost and figures to compare.
// --headlight: the light is the filter's default, vtkRenderer's headlight (not positional: a
// DirectionalLight from the eye to the focal point), in place of the point light at the eye.
// --threads T: the renderers' thread count (2 by default; 1 for per-phase on-CPU profiles).
// --size W H: the image's size (1920 × 1080 by default; 3840 2160: the filter's 4K frames).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "TurningView.h"
#include "facet/QualityRenderer.h"
#include "support/TestMeshes.h"

namespace {

using namespace facet;

double cpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

enum class Side { Both, Off, On };

int threadCount = 2;                        // --threads
int imageWidth = 1920, imageHeight = 1080;  // --size

// Per frame, the wall seconds of the render's phases and of the QualityRenderer around it.
struct PhaseSeconds {
  static constexpr int kCount = 7;
  static constexpr const char* kNames[kCount] = {
      "validate", "transform", "set-up", "raster", "shade+resolve", "render", "around render"};
  std::vector<double> seconds[kCount];

  void add(const QualityStats& s) {
    const double now[kCount] = {s.render.validateSeconds,
                                s.render.transformSeconds,
                                s.render.setupSeconds,
                                s.render.rasterSeconds,
                                s.render.shadeSeconds,
                                s.render.totalSeconds,
                                s.totalSeconds - s.render.totalSeconds};
    for (int i = 0; i < kCount; ++i)
      seconds[i].push_back(now[i]);
  }
};

double medianOrZero(const std::vector<double>& values) {
  return values.empty() ? 0.0 : median(values);
}

void printPhases(const PhaseSeconds& off, const PhaseSeconds& on) {
  std::printf("\n| phase | off, wall ms | on | on − off |\n|---|---:|---:|---:|\n");
  for (int i = 0; i < PhaseSeconds::kCount; ++i) {
    const double a = 1e3 * medianOrZero(off.seconds[i]), b = 1e3 * medianOrZero(on.seconds[i]);
    std::printf("| %s | %.2f | %.2f | %+.2f |\n", PhaseSeconds::kNames[i], a, b, b - a);
  }
  std::printf("\n");
}

void measure(int segments, int frames, int round, Side side, bool phases, bool perPixel,
             bool headlight) {
  const Mesh sphere = testing::makeUvSphere(segments, segments + 2);
  Camera camera = testing::fitCamera(sphere);
  Scene scene;
  SceneMesh mesh{sphere.view(), Material{}};
  mesh.mesh.version = 1;  // as the filter's input: the bound terms kept from frame to frame
  scene.meshes.push_back(mesh);
  PointLight light;
  light.position = camera.position;
  light.attenuation = QuadraticAttenuation{1.0, 0.0, 0.0};
  if (headlight) {
    scene.lights.lights.push_back(DirectionalLight{camera.focalPoint - camera.position});
  } else {
    scene.lights.lights.push_back(light);
  }
  scene.lights.ambient.intensity = 0.0;

  Renderer plainRenderer, estimatingRenderer;
  plainRenderer.setThreadCount(threadCount);
  estimatingRenderer.setThreadCount(threadCount);
  QualityRenderer plain(plainRenderer), estimating(estimatingRenderer);
  Framebuffer plainImage(imageWidth, imageHeight), estimatingImage(imageWidth, imageHeight);
  QualitySettings off, on;
  on.estimateError = true;
  on.errorEstimateImage = perPixel;  // off: the filter's default, the summary in field data

  double start = cpuSeconds();
  plain.render(scene, {}, camera, plainImage, off);
  const double firstOff = cpuSeconds() - start;
  start = cpuSeconds();
  const auto wallStart = std::chrono::steady_clock::now();
  QualityStats stats = estimating.render(scene, {}, camera, estimatingImage, on);
  const double firstOn = cpuSeconds() - start;
  const double firstOnWall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();

  std::vector<double> offSeconds, onSeconds, estimateSeconds;
  PhaseSeconds offPhases, onPhases;
  for (int i = 0; i < frames; ++i) {
    bench::turnView(camera, scene, 0.5);  // the light stays at the eye
    if (side != Side::On) {
      start = cpuSeconds();
      offPhases.add(plain.render(scene, {}, camera, plainImage, off));
      offSeconds.push_back(cpuSeconds() - start);
    }
    if (side != Side::Off) {
      start = cpuSeconds();
      stats = estimating.render(scene, {}, camera, estimatingImage, on);
      onSeconds.push_back(cpuSeconds() - start);
      estimateSeconds.push_back(stats.estimateSeconds);
      onPhases.add(stats);
    }
  }
  const double offCpu = medianOrZero(offSeconds), onCpu = medianOrZero(onSeconds);
  std::printf(
      "| %d | %zu | %d | %.1f | %.1f | %+.1f %% | %.1f | %.3f | %.3f | %.3f | %.4f | %.3f |\n",
      segments, sphere.polygonCount(), round, 1e3 * offCpu, 1e3 * onCpu,
      side == Side::Both ? 100.0 * (onCpu / offCpu - 1.0) : 0.0,
      1e3 * medianOrZero(estimateSeconds), firstOff, firstOn, firstOnWall, stats.predictedRmse,
      stats.predictedMaxError);
  if (phases) printPhases(offPhases, onPhases);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  int frames = 16, rounds = 3;
  Side side = Side::Both;
  bool phases = false, badSide = false, perPixel = false, headlight = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--phases") {
      phases = true;
    } else if (arg == "--per-pixel") {
      perPixel = true;
    } else if (arg == "--headlight") {
      headlight = true;
    } else if (arg == "--only" && i + 1 < argc) {
      const std::string which = argv[++i];
      side = which == "off" ? Side::Off : Side::On;
      badSide = which != "off" && which != "on";
    } else if (arg == "--frames" && i + 1 < argc) {
      frames = std::atoi(argv[++i]);
    } else if (arg == "--threads" && i + 1 < argc) {
      threadCount = std::atoi(argv[++i]);
    } else if (arg == "--size" && i + 2 < argc) {
      imageWidth = std::atoi(argv[++i]);
      imageHeight = std::atoi(argv[++i]);
    } else if (arg == "--rounds" && i + 1 < argc) {
      rounds = std::atoi(argv[++i]);
    } else {
      sizes.push_back(std::atoi(arg.c_str()));
    }
  }
  if (sizes.empty()) sizes = {500, 1000};
  if (frames < 1 || rounds < 1 || threadCount < 1 || imageWidth < 1 || imageHeight < 1 || badSide ||
      std::any_of(sizes.begin(), sizes.end(), [](int s) { return s < 3; })) {
    std::fprintf(
        stderr,
        "usage: facet_estimate_cost [segments >= 3 ...] [--frames N] [--rounds R]\n"
        "                           [--phases] [--only off|on] [--per-pixel] [--headlight]\n"
        "                           [--threads T] [--size W H]\n");
    return 2;
  }
  std::printf(
      "| segments | polygons | round | frame CPU ms, off | on | added | estimate wall ms "
      "| first frame CPU s, off | on | on, wall s | predicted RMSE | max |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int round = 1; round <= rounds; ++round) {
    for (const int segments : sizes)
      measure(segments, frames, round, side, phases, perPixel, headlight);
  }
}
