// Concave, non-planar and many-sided polygons fill exactly their area; a polygon is lit,
// culled and kept as a whole; self-intersecting polygons are fanned as VTK does.

#include <cmath>
#include <string>
#include <variant>
#include <vector>

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

// --- Facing, culling and self-intersection: a polygon is lit, culled and kept as a whole. ---

// A camera on +z looking at the origin, and a headlight (a directional light along the view)
// with no ambient: a polygon facing the viewer is white (Kd·cos 0 = 1), one seen from its
// back is white too with two-sided lighting, and black without it.
Camera headOnCamera(double distance = 6.0) {
  Camera camera;
  camera.position = {0, 0, distance};
  camera.nearClip = 0.1 * distance;
  camera.farClip = 10.0 * distance;
  return camera;
}

// Pixels per world unit in the z = 0 plane for headOnCamera (30° view angle).
double pixelsPerUnit(int imageSize, double distance = 6.0) {
  return imageSize / (2.0 * distance * std::tan(M_PI / 12.0));
}

LightSet headlight() {
  LightSet lights;
  lights.ambient.intensity = 0.0;
  lights.lights.push_back(DirectionalLight{{0, 0, -1}});
  return lights;
}

// Points on a circle of `radius` in the z = 0 plane, counter-clockwise seen from +z, with
// every `step`-th point taken (step 2 of 5 points: a pentagram).
Mesh starPolygon(int points, int step, double radius = 1.0, double innerRadius = 0.0) {
  Mesh mesh;
  std::vector<std::int64_t> ids;
  for (int i = 0; i < points; ++i) {
    const double angle = 2.0 * M_PI * ((i * step) % points) / points;
    const double r = (innerRadius > 0.0 && i % 2 == 1) ? innerRadius : radius;
    ids.push_back(mesh.addPoint({r * std::cos(angle), r * std::sin(angle), 0.0}));
  }
  mesh.addPolygon(ids);
  return mesh;
}

// Counts covered pixels and those whose color is not exactly `expected`.
struct Coverage {
  std::size_t covered = 0, wrongColor = 0;
};
Coverage coverageOf(const Framebuffer& fb, Rgba8 expected) {
  Coverage c;
  for (std::size_t i = 0; i < fb.pixelCount(); ++i) {
    if (fb.polygonId()[i] == Framebuffer::kBackgroundId) continue;
    ++c.covered;
    c.wrongColor += fb.color()[i] != expected;
  }
  return c;
}

constexpr Rgba8 kWhite{255, 255, 255, 255};

// Issue 7, defect 2: a fan of 700+ slivers used to contain one whose snapped window area was
// negative, which marked the whole disk as seen from its back: black under a headlight.
TEST(PolygonFacing, ManyVertexDiskFacingTheHeadlightIsWhiteAtEverySize) {
  for (int vertices : {700, 5000}) {
    const Mesh disk = starPolygon(vertices, 1);
    for (int size : {64, 199, 512, 1024}) {
      const Rendered r =
          renderScene(oneMeshScene(disk.view(), {}, headlight()), headOnCamera(), size, size);
      const Coverage c = coverageOf(r.framebuffer, kWhite);
      const double expectedArea = M_PI * std::pow(pixelsPerUnit(size), 2);
      SCOPED_TRACE(std::to_string(vertices) + " vertices, " + std::to_string(size) + " px");
      EXPECT_NEAR(double(c.covered), expectedArea, 0.02 * expectedArea + 4 * size);
      EXPECT_EQ(c.wrongColor, 0u);
      EXPECT_EQ(r.stats.polygonsDrawn, 1u);
    }
  }
}

// The same disk seen from behind: one polygon, lit from its back as a whole (white with
// two-sided lighting, black without), and culled as a whole.
TEST(PolygonFacing, ManyVertexDiskSeenFromBehindIsOneBackFace) {
  const Mesh disk = starPolygon(5000, 1);
  Camera behind = headOnCamera();
  behind.position = {0, 0, -6};
  LightSet lights = headlight();
  std::get<DirectionalLight>(lights.lights[0]).direction = {0, 0, 1};
  RenderOptions oneSided;
  oneSided.twoSidedLighting = false;
  const Rendered lit = renderScene(oneMeshScene(disk.view(), {}, lights), behind, 300, 300);
  const Rendered dark =
      renderScene(oneMeshScene(disk.view(), {}, lights), behind, 300, 300, oneSided);
  EXPECT_EQ(coverageOf(lit.framebuffer, kWhite).wrongColor, 0u);
  EXPECT_EQ(coverageOf(dark.framebuffer, Rgba8{0, 0, 0, 255}).wrongColor, 0u);
  EXPECT_GT(coverageOf(lit.framebuffer, kWhite).covered, 10000u);

  Material culled;
  culled.backfaceCulling = true;
  const Rendered none = renderScene(oneMeshScene(disk.view(), culled, lights), behind, 300, 300);
  EXPECT_EQ(none.stats.pixelsCovered, 0u);
  EXPECT_EQ(none.stats.polygonsCulled, 1u);
  const Rendered front =
      renderScene(oneMeshScene(disk.view(), culled, headlight()), headOnCamera(), 300, 300);
  EXPECT_EQ(front.stats.pixelsCovered, lit.stats.pixelsCovered) << "kept whole, slivers too";
  EXPECT_EQ(front.stats.polygonsCulled, 0u);
}

// A concave ten-pointed star (simple: ear clipping) facing the headlight is white.
TEST(PolygonFacing, ConcaveStarFacingTheHeadlightIsWhite) {
  for (int points : {10, 400, 4000}) {
    const Mesh star = starPolygon(points, 1, 1.0, points > 10 ? 0.97 : 0.4);
    for (int size : {80, 333, 1000}) {
      const Rendered r =
          renderScene(oneMeshScene(star.view(), {}, headlight()), headOnCamera(), size, size);
      const Coverage c = coverageOf(r.framebuffer, kWhite);
      SCOPED_TRACE(std::to_string(points) + " points, " + std::to_string(size) + " px");
      EXPECT_GT(c.covered, std::size_t(0.05 * size * size));
      EXPECT_EQ(c.wrongColor, 0u);
    }
  }
}

// Issue 7, defect 6: a pentagram (self-intersecting, winding twice around its center) is
// fanned from vertex 0 like VTK, lit with its own normal: white, not black.
TEST(SelfIntersecting, PentagramIsLitWithItsNormal) {
  const Mesh pentagram = starPolygon(5, 2);
  for (int size : {64, 300}) {
    const Rendered r =
        renderScene(oneMeshScene(pentagram.view(), {}, headlight()), headOnCamera(), size, size);
    const Coverage c = coverageOf(r.framebuffer, kWhite);
    EXPECT_GT(c.covered, std::size_t(0.05 * size * size)) << size << " px";
    EXPECT_EQ(c.wrongColor, 0u) << size << " px";
  }
}

// A bowtie's two lobes wind opposite ways, so its Newell vector area is zero (it used to be
// dropped as degenerate). VTK fans it from vertex 0 and draws both lobes; so do we, lit
// with the normal of its plane.
TEST(SelfIntersecting, BowtieCoversBothLobes) {
  Mesh bowtie;
  for (glm::dvec3 p : {glm::dvec3{-1, -1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, 1, 0}})
    bowtie.addPoint(p);
  bowtie.addPolygon({0, 1, 2, 3});
  const int size = 200;
  const Rendered r =
      renderScene(oneMeshScene(bowtie.view(), {}, headlight()), headOnCamera(), size, size);
  const Framebuffer& fb = r.framebuffer;
  const int unit = int(pixelsPerUnit(size)), center = size / 2;
  EXPECT_EQ(fb.polygonIdAt(center - unit / 2, center), 0) << "left lobe";
  EXPECT_EQ(fb.polygonIdAt(center + unit / 2, center), 0) << "right lobe";
  EXPECT_EQ(fb.polygonIdAt(center, center + unit / 2), Framebuffer::kBackgroundId)
      << "above the crossing: outside both lobes";
  // The fan's two triangles also both cover the region below the crossing, as VTK's do: the
  // square of side 2 but its top quarter.
  const Coverage c = coverageOf(fb, kWhite);
  const double fan = 3.0 * pixelsPerUnit(size) * pixelsPerUnit(size);
  EXPECT_NEAR(double(c.covered), fan, 0.05 * fan);
  EXPECT_EQ(c.wrongColor, 0u);
}

// --- Degenerate and extreme polygons: each renders its exact coverage or is counted. ---

// An L-shape (concave) on quarter-pixel coordinates, [10.25, 50.25] × [10.25, 30.25] plus
// [10.25, 30.25] × [30.25, 60.25], its 6 corners listed counter-clockwise; `subdivide` extra
// points along every edge (collinear runs), each corner repeated `repeats` times.
Mesh lShape(int subdivide, int repeats) {
  const glm::dvec2 corners[6] = {{10.25, 10.25}, {50.25, 10.25}, {50.25, 30.25},
                                 {30.25, 30.25}, {30.25, 60.25}, {10.25, 60.25}};
  Mesh mesh;
  std::vector<std::int64_t> ids;
  for (int c = 0; c < 6; ++c) {
    const glm::dvec2 a = corners[c], b = corners[(c + 1) % 6];
    for (int r = 0; r < repeats; ++r)
      ids.push_back(mesh.addPoint({a.x, a.y, 0.0}));
    for (int k = 1; k <= subdivide; ++k) {
      const glm::dvec2 p = a + (b - a) * (double(k) / (subdivide + 1));
      ids.push_back(mesh.addPoint({p.x, p.y, 0.0}));
    }
  }
  mesh.addPolygon(ids);
  return mesh;
}
constexpr std::size_t kLShapeArea = 40 * 20 + 20 * 30;

TEST(DegeneratePolygons, CollinearRunsAndRepeatedPointsKeepTheExactCoverage) {
  for (int subdivide : {0, 1, 7, 50}) {
    for (int repeats : {1, 2, 5}) {
      const Mesh mesh = lShape(subdivide, repeats);
      const Rendered r = renderScene(oneMeshScene(mesh.view()), pixelCamera(64, 64), 64, 64);
      EXPECT_EQ(r.stats.pixelsCovered, kLShapeArea)
          << subdivide << " points per edge, corners " << repeats << " times";
      EXPECT_EQ(r.stats.fragmentsWritten, kLShapeArea) << "no pixel painted twice";
      EXPECT_EQ(r.framebuffer.polygonIdAt(40, 40), Framebuffer::kBackgroundId) << "the notch";
    }
  }
}

// Zero area (all points on a line, or all the same point) is counted degenerate, not drawn.
TEST(DegeneratePolygons, ZeroAreaIsCountedNotDrawn) {
  Mesh mesh;
  for (int i = 0; i < 8; ++i)
    mesh.addPoint({10.0 + i, 10.0 + 2 * i, 0.0});
  mesh.addPolygon({0, 1, 2, 3, 4, 5, 6, 7});  // collinear, going out
  mesh.addPolygon({0, 3, 7, 5, 2});           // collinear, back and forth
  mesh.addPolygon({4, 4, 4, 4});              // one point
  const Rendered r = renderScene(oneMeshScene(mesh.view()), pixelCamera(32, 32), 32, 32);
  EXPECT_EQ(r.stats.polygonsDegenerate, 3u);
  EXPECT_EQ(r.stats.pixelsCovered, 0u);
}

// A sliver of aspect 1e6, 2 pixels wide at its base and 2e6 pixels long, reaching far beyond
// the guard band: clipped, it covers exactly the one row of pixel centers it spans.
TEST(DegeneratePolygons, SliverOfAspectOneMillionCoversTheRowItSpans) {
  Mesh sliver;
  sliver.addPoint({-1e6, 19.5, 0.0});
  sliver.addPoint({1e6, 20.5, 0.0});
  sliver.addPoint({-1e6, 21.5, 0.0});
  sliver.addPolygon({0, 1, 2});
  const Rendered r = renderScene(oneMeshScene(sliver.view()), pixelCamera(64, 48), 64, 48);
  EXPECT_EQ(r.stats.pixelsCovered, 64u);
  for (int x = 0; x < 64; ++x)
    ASSERT_EQ(r.framebuffer.polygonIdAt(x, 20), 0) << x;
  EXPECT_GT(r.stats.trianglesClipped, 0u);
}

// 10,000-vertex polygons: a convex disk (fanned) and a concave gear of 5,000 teeth (ear
// clipping) cover their area to within their outline's pixels, all facing the headlight.
TEST(DegeneratePolygons, TenThousandVertexPolygons) {
  const int size = 400;
  const double unit = pixelsPerUnit(size);
  const Mesh disk = starPolygon(10000, 1);
  const Mesh gear = starPolygon(10000, 1, 1.0, 0.98);
  for (const Mesh* mesh : {&disk, &gear}) {
    const Rendered r =
        renderScene(oneMeshScene(mesh->view(), {}, headlight()), headOnCamera(), size, size);
    const double area = mesh == &disk ? M_PI * unit * unit : M_PI * std::pow(0.99 * unit, 2);
    const Coverage c = coverageOf(r.framebuffer, kWhite);
    EXPECT_NEAR(double(c.covered), area, 2.0 * M_PI * unit) << (mesh == &disk ? "disk" : "gear");
    EXPECT_EQ(c.wrongColor, 0u);
    EXPECT_EQ(r.stats.polygonsDrawn, 1u);
  }
}

}  // namespace
}  // namespace facet::testing
