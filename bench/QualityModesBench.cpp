// What each quality mode costs relative to flat shading, at 1920 × 1080, on spheres of 500k
// and 2M triangles (the shiny material and two lights of the reference tests), in one run:
// the median of several renders per mode, the mesh's ShadingMesh prepared once beforehand
// (as the filter keeps it between renders; its time is printed apart).
//
//   build/bin/facet_quality_bench            # Markdown table to stdout
//   build/bin/facet_quality_bench 500000     # one size

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "facet/QualityRenderer.h"
#include "support/ReferenceScenes.h"
#include "support/TestMeshes.h"

namespace {

using namespace facet;
using Clock = std::chrono::steady_clock;

constexpr int kWidth = 1920, kHeight = 1080;

struct Mode {
  std::string name;
  QualitySettings settings;
  int repeats;
};

double medianMs(std::vector<double> times) {
  std::sort(times.begin(), times.end());
  return times[times.size() / 2] * 1e3;
}

void benchSphere(int triangles) {
  const int theta = triangles >= 2000000 ? 1000 : 500;
  const Mesh sphere = testing::makeUvSphere(theta, theta + 2);
  const Camera camera = testing::fitCamera(sphere);
  Scene scene;
  scene.meshes.push_back({sphere.view(), testing::shinyMaterial()});
  scene.lights = testing::twoLights();
  const Clock::time_point prepareStart = Clock::now();
  const std::vector<ShadingMesh> shading{ShadingMesh(sphere.view())};
  const double prepareMs =
      std::chrono::duration<double, std::milli>(Clock::now() - prepareStart).count();

  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer image(kWidth, kHeight);
  const std::vector<Mode> modes = {
      {"flat", {}, 7},
      {"flat + estimate", {.estimateError = true}, 7},
      {"Gouraud", {.shading = Shading::Gouraud}, 7},
      {"Phong", {.shading = Shading::Phong}, 7},
      {"adaptive (e = 2)", {.maximumError = 2.0}, 7},
      {"flat x4", {.samplesPerPixel = 4}, 3},
      {"Phong x4", {.shading = Shading::Phong, .samplesPerPixel = 4}, 3},
      {"flat x16", {.samplesPerPixel = 16}, 3},
      {"Phong x16", {.shading = Shading::Phong, .samplesPerPixel = 16}, 3},
  };
  std::printf("\n%d triangles (%zu), %dx%d, %d threads; ShadingMesh prepared once in %.0f ms\n\n",
              triangles, sphere.polygonCount(), kWidth, kHeight, renderer.threadCount(), prepareMs);
  std::printf(
      "| mode | ms | x flat | raster ms | bounds + estimate ms | re-shade ms | samples re-shaded "
      "|\n|---|---:|---:|---:|---:|---:|---:|\n");
  double flatMs = 0.0;
  for (const Mode& mode : modes) {
    std::vector<double> times;
    QualityStats stats;
    quality.render(scene, shading, camera, image, mode.settings);  // warm-up
    for (int i = 0; i < mode.repeats; ++i) {
      stats = quality.render(scene, shading, camera, image, mode.settings);
      times.push_back(stats.totalSeconds);
    }
    const double ms = medianMs(times);
    if (mode.name == "flat") flatMs = ms;
    std::printf("| %s | %.1f | %.2f | %.1f | %.1f | %.1f | %zu |\n", mode.name.c_str(), ms,
                ms / flatMs, stats.render.totalSeconds * 1e3, stats.estimateSeconds * 1e3,
                stats.shadeSeconds * 1e3, stats.samplesReshaded);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1) {
    benchSphere(std::atoi(argv[1]));
    return 0;
  }
  for (const int triangles : {500000, 2000000})
    benchSphere(triangles);
}
