// Concave, non-planar and many-sided polygons fill exactly their area.

#include <cmath>

#include <gtest/gtest.h>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"

namespace facet::testing {
namespace {

// A comb: a concave polygon whose fan from vertex 0 would cover the gaps between the teeth.
// Teeth span [x, x + 10] × [30.25, 70.25] for x = 10.25 + 20t; the base [10.25, right] ×
// [10.25, 30.25]. Edges lie on quarter pixels, never on a sample, so counts are exact.
Mesh comb(int teeth) {
  Mesh mesh;
  std::vector<std::int64_t> ids;
  const double right = 10.25 + 20.0 * (teeth - 1) + 10.0;
  ids.push_back(mesh.addPoint({10.25, 10.25, 0}));
  ids.push_back(mesh.addPoint({right, 10.25, 0}));
  for (int t = teeth - 1; t >= 0; --t) {
    const double x = 10.25 + 20.0 * t;
    ids.push_back(mesh.addPoint({x + 10.0, 70.25, 0}));
    ids.push_back(mesh.addPoint({x, 70.25, 0}));
    if (t > 0) {
      ids.push_back(mesh.addPoint({x, 30.25, 0}));
      ids.push_back(mesh.addPoint({x - 10.0, 30.25, 0}));
    }
  }
  mesh.addPolygon(ids);
  return mesh;
}

std::size_t combArea(int teeth) {
  return teeth * 10u * 40u + (20u * (teeth - 1) + 10u) * 20u;
}

TEST(Triangulation, ConcaveCombFillsExactlyItsArea) {
  const Mesh mesh = comb(5);
  const Rendered r = renderScene(oneMeshScene(mesh.view()), pixelCamera(128, 96), 128, 96);
  EXPECT_EQ(r.stats.pixelsCovered, combArea(5));
  EXPECT_EQ(r.framebuffer.polygonIdAt(25, 50), Framebuffer::kBackgroundId) << "a gap between teeth";
  EXPECT_EQ(r.framebuffer.polygonIdAt(15, 50), 0) << "a tooth";
}

TEST(Triangulation, ConcaveSeenFromEitherSide) {
  const Mesh mesh = comb(3);
  Camera below = pixelCamera(128, 96);
  below.position.z = -10.0;  // looking up at the back face; x is mirrored
  below.viewUp = {0, 1, 0};
  const Rendered r = renderScene(oneMeshScene(mesh.view()), below, 128, 96);
  EXPECT_EQ(r.stats.pixelsCovered, combArea(3));
}

TEST(Triangulation, SlightlyNonPlanarQuadsAndNgonsFromARealMesh) {
  // beast.obj: 32k quads plus pentagons and hexagons, likely non-planar.
  const Mesh beast = readObj(sharedMeshPath("beast.obj"));
  ASSERT_GT(beast.polygonCount(), 32000u);
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-0.3, -0.5, -1.0}});
  RenderOptions options;
  const Rendered r =
      renderScene(oneMeshScene(beast.view(), {}, lights), fitCamera(beast), 320, 240, options);
  EXPECT_GT(r.stats.pixelsCovered, 5000u);
  EXPECT_GT(r.stats.trianglesBinned, r.stats.polygonsDrawn) << "quads become two triangles";
  EXPECT_EQ(r.stats.polygonsNonFinite, 0u);
}

}  // namespace
}  // namespace facet::testing
