// The mesh reference: exact where the mesh is the surface (a quad), converging to the
// analytic sphere as its tessellation grows, deterministic, orientation-proof, far-data-proof,
// and converged as its samples double.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "../support/ReferenceScenes.h"
#include "../support/TestMeshes.h"
#include "facet/AnalyticReference.h"
#include "facet/Error.h"
#include "facet/ImageMetrics.h"
#include "facet/MeshReference.h"

namespace facet {
namespace {

using testing::fitCamera;
using testing::makeUvSphere;
using testing::pixelCamera;
using testing::readObj;
using testing::sharedMeshPath;
using testing::shinyMaterial;
using testing::twoLights;

Scene sceneOf(const Mesh& mesh, const Material& material = shinyMaterial(),
              const LightSet& lights = twoLights()) {
  Scene scene;
  scene.meshes.push_back({mesh.view(), material});
  scene.lights = lights;
  return scene;
}

void reverse(Mesh& mesh, std::size_t polygon) {
  std::reverse(mesh.connectivity.begin() + mesh.offsets[polygon],
               mesh.connectivity.begin() + mesh.offsets[polygon + 1]);
}

ImageError printed(const char* what, const ImageError& error) {
  std::printf("%s: RMSE %.4f, max %.3f, silhouette pixels %zu of %zu\n", what, error.rmse,
              error.maxError, error.silhouettePixels, error.coveredPixels);
  return error;
}

// A flat parallelogram is its own exact tessellation: the mesh reference must draw the
// analytic plane, to float rounding at the edges (Embree's test) and to 1e-6 inside.
TEST(MeshReference, ParallelogramIsTheAnalyticPlane) {
  AnalyticPlane plane;
  plane.origin = {3.2, 4.1, 0};
  plane.edgeU = {37.5, 2.2, 0};
  plane.edgeV = {5.2, 21.1, 0};
  plane.material = shinyMaterial();
  Mesh quad;
  quad.addPolygon({quad.addPoint(plane.origin), quad.addPoint(plane.origin + plane.edgeU),
                   quad.addPoint(plane.origin + plane.edgeU + plane.edgeV),
                   quad.addPoint(plane.origin + plane.edgeV)});
  AnalyticScene analytic;
  analytic.planes.push_back(plane);
  analytic.lights = twoLights();
  const Camera camera = pixelCamera(48, 32);
  const ReferenceOptions options{.samplesPerPixel = 16};
  const FloatImage mesh = renderMeshReference(sceneOf(quad), camera, 48, 32, options).image;
  const FloatImage exact = renderAnalyticReference(analytic, camera, 48, 32, options).image;
  std::size_t edgeDifferences = 0, interior = 0;
  for (std::size_t i = 0; i < mesh.pixelCount(); ++i) {
    edgeDifferences += mesh.coverage[i] != exact.coverage[i];
    if (mesh.coverage[i] == 1.0f && exact.coverage[i] == 1.0f) {
      ++interior;
      EXPECT_LT(glm::length(glm::dvec3(mesh.color[i] - exact.color[i])), 1e-6) << "pixel " << i;
    }
  }
  EXPECT_LE(edgeDifferences, 2u) << "samples on the edges within float rounding";
  EXPECT_GT(interior, 500u);
}

// The surface color is the quality modes' (pointColorAt): point colors interpolated, or
// point scalars mapped per sample. Unlit (C = Cd), a rectangle over the whole image whose
// left points are red and right points blue shows, per pixel, the blend at its center
// (the average of a linear function, to the sample pattern); with scalars s from 0 to 1 left to
// right through a 4-entry table, a pixel inside one entry's band shows that entry exactly.
TEST(MeshReference, PointColorsAndScalarsAreTheQualityModes) {
  const int width = 48, height = 32;
  Mesh rectangle;
  rectangle.addPolygon({rectangle.addPoint({-1, -1, 0}), rectangle.addPoint({49, -1, 0}),
                        rectangle.addPoint({49, 33, 0}), rectangle.addPoint({-1, 33, 0})});
  const std::vector<Rgba8> colors = {
      {255, 0, 0, 255}, {0, 0, 255, 255}, {0, 0, 255, 255}, {255, 0, 0, 255}};
  const std::vector<float> st = {0.0f, 0.49f, 1.0f, 0.49f, 1.0f, 0.49f, 0.0f, 0.49f};
  const std::vector<Rgba8> texels = {{255, 0, 0, 255},   {0, 255, 0, 255}, {0, 0, 255, 255},
                                     {255, 255, 0, 255}, {9, 9, 9, 255},   {9, 9, 9, 255},
                                     {9, 9, 9, 255},     {9, 9, 9, 255}};
  LightSet unlit;
  unlit.ambient = {Color(1.0f), 1.0};
  const ReferenceOptions options{.samplesPerPixel = 16};
  for (const bool scalars : {false, true}) {
    Scene scene = sceneOf(rectangle, Material{}, unlit);
    scene.meshes[0].mesh.pointColors = colors;
    if (scalars) scene.meshes[0].mesh.scalarTexture = {st, texels, 4};
    const FloatImage image =
        renderMeshReference(scene, pixelCamera(width, height), width, height, options).image;
    int checked = 0;
    double worst = 0.0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const double s0 = (x + 1.0) / 50.0, s1 = (x + 2.0) / 50.0;  // across the pixel
        Color expected((1.0 - (s0 + s1) / 2), 0.0f, (s0 + s1) / 2);
        if (scalars) {
          const int band = static_cast<int>(4.0 * s0);
          if (static_cast<int>(4.0 * s1) != band && 4.0 * s1 != band + 1) continue;
          const Rgba8 t = texels[band];
          expected = Color(t.r, t.g, t.b) / 255.0f;
        }
        worst = std::max(
            worst, static_cast<double>(glm::length(image.color[image.indexOf(x, y)] - expected)));
        ++checked;
      }
    }
    std::printf("%s: %d pixels, largest difference %.2g\n", scalars ? "scalars" : "colors", checked,
                worst);
    EXPECT_GT(checked, 1000);
    // The blend is linear, so a pixel shows its value at the mean of its 16 sample offsets,
    // each in its own sixteenth of the pixel's width: within 1/32 pixel of the center, so
    // within (1/32)/50 per channel (two channels vary). The bands are exact.
    EXPECT_LT(worst, scalars ? 1e-6 : std::sqrt(2.0) / 32.0 / 50.0);
  }
}

TEST(MeshReference, FineSphereConvergesToTheAnalyticSphere) {
  AnalyticScene analytic;
  analytic.spheres.push_back({{0, 0, 0}, 1.0, shinyMaterial()});
  analytic.lights = twoLights();
  const Camera camera = fitCamera(makeUvSphere(8, 5), {0.2, -0.3, -1});
  const ReferenceOptions options{.samplesPerPixel = 16};
  const FloatImage exact = renderAnalyticReference(analytic, camera, 160, 120, options).image;
  double previous = INFINITY;
  for (const int segments : {32, 128, 512}) {
    const Mesh sphere = makeUvSphere(segments, segments / 2 + 1);
    const FloatImage phong = renderMeshReference(sceneOf(sphere), camera, 160, 120, options).image;
    const ImageError error = compareImages(exact, phong);
    std::printf(
        "%3d segments, Phong reference vs exact sphere: RMSE %.4f (interior %.4f), max %.3f\n",
        segments, error.rmse, error.interiorRmse, error.maxError);
    EXPECT_LT(error.interiorRmse, previous);
    previous = error.interiorRmse;
  }
  // Inside the silhouette the shading matches; on it, a sample can still fall in the sliver
  // between the polygon and the circle.
  EXPECT_LT(previous, 0.02);
}

TEST(MeshReference, SameBytesForAnyThreadCount) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  const Scene scene = sceneOf(bunny);
  const Camera camera = fitCamera(bunny, {0.3, -0.2, -1});
  const auto one = renderMeshReference(scene, camera, 96, 72, {.samplesPerPixel = 8, .threads = 1});
  for (const int threads : {2, 5}) {
    const auto many =
        renderMeshReference(scene, camera, 96, 72, {.samplesPerPixel = 8, .threads = threads});
    EXPECT_EQ(one.image.color, many.image.color) << threads << " threads";
    EXPECT_EQ(one.image.coverage, many.image.coverage) << threads << " threads";
  }
}

TEST(MeshReference, FlippedPolygonsLookTheSame) {
  const Mesh sphere = makeUvSphere(48, 25);
  Mesh flipped = sphere;
  for (std::size_t p = 0; p < flipped.polygonCount(); p += 3)
    reverse(flipped, p);
  const Camera camera = fitCamera(sphere, {0.2, -0.3, -1});
  const ReferenceOptions options{.samplesPerPixel = 8};
  const auto a = renderMeshReference(sceneOf(sphere), camera, 96, 72, options);
  const auto b = renderMeshReference(sceneOf(flipped), camera, 96, 72, options);
  const ImageError error = printed("flipped vs consistent", compareImages(a.image, b.image));
  EXPECT_LT(error.maxError, 1e-3);
}

TEST(MeshReference, GivenNormalsAreUsed) {
  // Every normal +z, the light straight down −z, no ambient: Lambert is 1 everywhere, so the
  // whole sphere shows its plain color (computed normals would shade it round).
  const Mesh sphere = makeUvSphere(16, 9);
  const std::vector<glm::dvec3> up(sphere.points.size(), glm::dvec3(0, 0, 1));
  const VertexNormals given = fromPointNormals(sphere.view(), PointArray::of(up));
  LightSet light;
  light.ambient.intensity = 0.0;
  light.lights.push_back(DirectionalLight{{0, 0, -1}});
  const Scene scene = sceneOf(sphere, Material{}, light);
  const Camera camera = fitCamera(sphere);  // looks down −z
  const auto render =
      renderMeshReference(scene, camera, 64, 64, {.samplesPerPixel = 4}, std::span(&given, 1));
  std::size_t covered = 0;
  for (std::size_t i = 0; i < render.image.pixelCount(); ++i) {
    if (render.image.coverage[i] < 1.0f) continue;
    ++covered;
    EXPECT_EQ(render.image.color[i], Color(1.0f)) << i;
  }
  EXPECT_GT(covered, 500u);
}

TEST(MeshReference, BackFacesCulledWhenTheMaterialSaysSo) {
  Mesh quad;
  quad.addPolygon({quad.addPoint({0, 0, 0}), quad.addPoint({0, 32, 0}), quad.addPoint({32, 32, 0}),
                   quad.addPoint({32, 0, 0})});  // clockwise seen from +z: a back face
  Material culling;
  culling.backfaceCulling = true;
  const auto shown =
      renderMeshReference(sceneOf(quad), pixelCamera(16, 16), 16, 16, {.samplesPerPixel = 4});
  const auto culled = renderMeshReference(sceneOf(quad, culling), pixelCamera(16, 16), 16, 16,
                                          {.samplesPerPixel = 4});
  EXPECT_EQ(shown.image.coverage[shown.image.indexOf(8, 8)], 1.0f);
  EXPECT_EQ(culled.image.coverage[culled.image.indexOf(8, 8)], 0.0f);
}

TEST(MeshReference, DataFarFromTheOriginRendersAsAtTheOrigin) {
  const glm::dvec3 far(1e6, -2e6, 3e6);
  const Mesh sphere = makeUvSphere(32, 17);
  const Mesh moved = makeUvSphere(32, 17, 1.0, far);
  Camera camera = fitCamera(sphere, {0.2, -0.3, -1});
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1, -1, -2}});
  const ReferenceOptions options{.samplesPerPixel = 8};
  const auto here =
      renderMeshReference(sceneOf(sphere, shinyMaterial(), lights), camera, 96, 72, options);
  camera.position += far;
  camera.focalPoint += far;
  const auto there =
      renderMeshReference(sceneOf(moved, shinyMaterial(), lights), camera, 96, 72, options);
  const ImageError error = printed("at 1e6 vs at 0", compareImages(here.image, there.image));
  EXPECT_LT(error.rmse, 0.05);
}

// Converged: doubling the samples changes the bunny by less than 0.25/255 RMSE.
TEST(MeshReference, BunnyConvergesAsSamplesDouble) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  const Camera camera = fitCamera(bunny, {0.3, -0.2, -1});
  const ReferenceRender render =
      renderMeshReference(sceneOf(bunny), camera, 480, 270, {.samplesPerPixel = 256});
  std::printf("bunny 480x270, 128 -> 256 samples: RMSE change %.4f / 255\n", *render.convergence);
  EXPECT_LT(*render.convergence, 0.25);
}

TEST(MeshReference, BadInputIsNamed) {
  const Mesh sphere = makeUvSphere(8, 5);
  const Scene scene = sceneOf(sphere);
  const Camera camera = fitCamera(sphere);
  const VertexNormals wrong = computeVertexNormals(makeUvSphere(6, 4).view());
  EXPECT_THROW(MeshTracer(scene, camera.position, true, std::span(&wrong, 1)), Error);
  const VertexNormals right = computeVertexNormals(sphere.view());
  const VertexNormals two[2] = {right, right};
  EXPECT_THROW(MeshTracer(scene, camera.position, true, two), Error);
  Mesh broken = sphere;
  broken.connectivity[4] = -3;
  EXPECT_THROW(MeshTracer(sceneOf(broken), camera.position, true), Error);
  Scene badMaterial = scene;
  badMaterial.meshes[0].material.diffuse = -1.0;
  EXPECT_THROW(MeshTracer(badMaterial, camera.position, true), Error);
}

}  // namespace
}  // namespace facet
