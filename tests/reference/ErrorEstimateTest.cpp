// The flat-shading error estimate (QualityRenderer.h, FlatErrorBound.h) against what it
// predicts: the converged Phong mesh reference. On the sphere sweep and the shared meshes,
// the measured error of every pixel away from the silhouette is within the estimate; and the
// quality modes' measured errors are ordered as they should be.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "../support/ReferenceScenes.h"
#include "../support/TestMeshes.h"
#include "facet/ImageMetrics.h"
#include "facet/MeshReference.h"
#include "facet/QualityRenderer.h"

namespace facet {
namespace {

using testing::fitCamera;

struct Measured {
  double worstExcess = -INFINITY;  // measured − estimate, largest over checked pixels
  std::size_t checked = 0;
  double predictedRmse = 0.0, measuredRmse = 0.0;
};

// Pixels whose 3 × 3 neighbourhood the reference covers fully and the render too.
bool awayFromSilhouette(const FloatImage& reference, const Framebuffer& image, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= image.width() || ny >= image.height()) return false;
      if (reference.coverage[reference.indexOf(nx, ny)] < 1.0f) return false;
      if (image.polygonIdAt(nx, ny) < 0) return false;
    }
  }
  return true;
}

Measured measure(const Mesh& mesh, const Material& material, const Camera& camera, int width,
                 int height, int samples) {
  Scene scene;
  scene.meshes.push_back({mesh.view(), material});
  scene.lights = testing::twoLights();
  const std::vector<ShadingMesh> shading{ShadingMesh(mesh.view())};
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer image(width, height);
  const QualityStats stats = quality.render(scene, shading, camera, image,
                                            {.samplesPerPixel = samples, .estimateError = true});
  const std::vector<VertexNormals> normals{shading[0].normals};
  const ReferenceRender reference =
      renderMeshReference(scene, camera, width, height, {.samplesPerPixel = 128}, normals);
  const ImageError error = compareImages(reference.image, toFloatImage(image));
  Measured m;
  m.predictedRmse = stats.predictedRmse;
  m.measuredRmse = error.rmse;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!awayFromSilhouette(reference.image, image, x, y)) continue;
      const std::size_t i = image.indexOf(x, y);
      m.worstExcess =
          std::max<double>(m.worstExcess, error.errorImage[i] - quality.errorEstimate()[i]);
      ++m.checked;
    }
  }
  return m;
}

// The reference's own remaining noise per pixel (it is converged in RMSE, 0.25/255, not to
// the last pixel): the slack the comparison allows.
constexpr double kReferenceNoise = 1.0;

void expectWithinEstimate(const std::string& name, const Measured& m) {
  std::printf(
      "%-24s predicted RMSE %6.2f, measured RMSE %6.2f; %zu pixels checked, worst "
      "measured − estimate %+.2f\n",
      name.c_str(), m.predictedRmse, m.measuredRmse, m.checked, m.worstExcess);
  EXPECT_GT(m.checked, 500u) << name;
  EXPECT_LE(m.worstExcess, kReferenceNoise) << name;
  EXPECT_GE(m.predictedRmse, m.measuredRmse * 0.5) << name;  // a bound, not a guess
}

TEST(ErrorEstimate, BoundsTheMeasuredErrorOnTheSphereSweep) {
  const Camera camera = fitCamera(testing::makeUvSphere(8, 5), {0.2, -0.3, -1});
  for (const int segments : {8, 32, 128}) {
    const Mesh sphere = testing::makeUvSphere(segments, segments / 2 + 1);
    for (const int samples : {1, 4}) {
      expectWithinEstimate("sphere " + std::to_string(segments) + " x" + std::to_string(samples),
                           measure(sphere, testing::shinyMaterial(), camera, 120, 90, samples));
    }
  }
}

TEST(ErrorEstimate, BoundsTheMeasuredErrorOnTheSharedMeshes) {
  for (const char* file : {"stanford-bunny.obj", "fandisk.obj"}) {
    const Mesh mesh = testing::readObj(testing::sharedMeshPath(file));
    const Camera camera = fitCamera(mesh, {0.3, -0.2, -1});
    expectWithinEstimate(file, measure(mesh, testing::shinyMaterial(), camera, 160, 120, 1));
  }
}

// The summary-only estimate (flat, one sample per pixel, no ErrorEstimate image: the filter's
// default; QualityRenderer.cpp, estimateSummary) under a matte material, which it takes: its
// maximum is at least the measured error of every pixel away from the silhouette, and its
// RMSE at least the measured RMSE (over every covered pixel, silhouettes included).
void expectWithinSummary(const std::string& name, const Mesh& mesh, const Camera& camera, int width,
                         int height) {
  Material matte;
  matte.diffuse = 0.9;
  Scene scene;
  scene.meshes.push_back({mesh.view(), matte});
  scene.lights = testing::twoLights();
  Renderer renderer;
  QualityRenderer quality(renderer);
  Framebuffer image(width, height);
  const QualityStats stats = quality.render(scene, {}, camera, image,
                                            {.estimateError = true, .errorEstimateImage = false});
  ASSERT_TRUE(quality.errorEstimate().empty());
  renderer.forgetPreviousFrame();
  Framebuffer imaged(width, height);  // the per-pixel estimate, for how much looser
  const QualityStats perPixel = quality.render(scene, {}, camera, imaged, {.estimateError = true});
  const ShadingMesh shading(mesh.view());
  const std::vector<VertexNormals> normals{shading.normals};
  const ReferenceRender reference =
      renderMeshReference(scene, camera, width, height, {.samplesPerPixel = 128}, normals);
  const ImageError error = compareImages(reference.image, toFloatImage(image));
  double worst = 0.0;
  std::size_t checked = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!awayFromSilhouette(reference.image, image, x, y)) continue;
      worst = std::max<double>(worst, error.errorImage[image.indexOf(x, y)]);
      ++checked;
    }
  }
  std::printf(
      "%-24s summary: predicted RMSE %6.2f max %6.2f (per pixel %6.2f, %6.2f); measured "
      "RMSE %6.2f, max away from the silhouette %6.2f (%zu pixels)\n",
      name.c_str(), stats.predictedRmse, stats.predictedMaxError, perPixel.predictedRmse,
      perPixel.predictedMaxError, error.rmse, worst, checked);
  EXPECT_GE(stats.predictedRmse, perPixel.predictedRmse) << name;
  EXPECT_GE(stats.predictedMaxError, perPixel.predictedMaxError) << name;
  EXPECT_GT(checked, 500u) << name;
  EXPECT_LE(worst, stats.predictedMaxError + kReferenceNoise) << name;
  EXPECT_GE(stats.predictedRmse, error.rmse) << name;
}

TEST(ErrorEstimate, SummaryBoundsTheMeasuredErrorOnTheSphereSweepAndSharedMeshes) {
  const Camera camera = fitCamera(testing::makeUvSphere(8, 5), {0.2, -0.3, -1});
  for (const int segments : {8, 32, 128}) {
    expectWithinSummary("matte sphere " + std::to_string(segments),
                        testing::makeUvSphere(segments, segments / 2 + 1), camera, 120, 90);
  }
  for (const char* file : {"stanford-bunny.obj", "fandisk.obj"}) {
    const Mesh mesh = testing::readObj(testing::sharedMeshPath(file));
    expectWithinSummary(std::string("matte ") + file, mesh, fitCamera(mesh, {0.3, -0.2, -1}), 160,
                        120);
  }
}

}  // namespace
}  // namespace facet
