// How many samples per pixel a reference needs to converge (doubling them changes the image
// by less than 0.25/255 RMSE), and what it costs: the analytic sphere and the bunny's mesh
// reference at 1920 × 1080, each render with 16, 32, ... samples up to a maximum reporting how much
// its last doubling changed it (ReferenceRender::convergence).
//
//   build/bin/facet_reference_convergence [MAX_SAMPLES=256] [WIDTH=1920] [HEIGHT=1080]

#include <cstdio>
#include <cstdlib>
#include <functional>

#include "facet/AnalyticReference.h"
#include "facet/ImageMetrics.h"
#include "facet/MeshReference.h"
#include "support/ReferenceScenes.h"
#include "support/TestMeshes.h"

namespace {

using namespace facet;

// Renders with 16, 32, ... samples and prints how much each last doubling changed it.
void sweep(const char* name, int maxSamples, const std::function<ReferenceRender(int)>& render) {
  for (int samples = 16; samples <= maxSamples; samples *= 2) {
    const ReferenceRender r = render(samples);
    std::printf("%-8s %4d -> %4d samples: RMSE change %.4f %s; %.1f s\n", name, samples / 2,
                samples, *r.convergence, *r.convergence < 0.25 ? "converged" : "         ",
                r.seconds);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int maxSamples = argc > 1 ? std::atoi(argv[1]) : 256;
  const int width = argc > 2 ? std::atoi(argv[2]) : 1920;
  const int height = argc > 3 ? std::atoi(argv[3]) : 1080;
  std::printf("%d x %d, samples doubled from 16 to %d\n", width, height, maxSamples);

  AnalyticScene sphere;
  sphere.spheres.push_back({{0, 0, 0}, 1.0, testing::shinyMaterial()});
  sphere.lights = testing::twoLights();
  const Camera sphereCamera = testing::fitCamera(testing::makeUvSphere(8, 5), {0.2, -0.3, -1});
  sweep("sphere", maxSamples, [&](int samples) {
    return renderAnalyticReference(sphere, sphereCamera, width, height,
                                   {.samplesPerPixel = samples});
  });

  const Mesh bunny = testing::readObj(testing::sharedMeshPath("stanford-bunny.obj"));
  Scene scene;
  scene.meshes.push_back({bunny.view(), testing::shinyMaterial()});
  scene.lights = testing::twoLights();
  const Camera bunnyCamera = testing::fitCamera(bunny, {0.3, -0.2, -1});
  sweep("bunny", maxSamples, [&](int samples) {
    return renderMeshReference(scene, bunnyCamera, width, height, {.samplesPerPixel = samples});
  });
}
