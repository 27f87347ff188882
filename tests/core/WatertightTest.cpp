// Watertightness, the fill rule and coverage: every pixel center inside a tessellated shape
// is painted exactly once, none outside, whatever the tessellation, rotation or clipping.
//
// Shapes are drawn coplanar in painter's order, so every fragment is written and counted:
// fragmentsWritten == pixelsCovered means no pixel was painted twice, and comparing the
// coverage with an exact winding-number test of the shape's outline finds any crack.

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"

namespace facet::testing {
namespace {

constexpr int kFrameWidth = 160, kFrameHeight = 120;

RenderOptions painterOptions(int threads = 2) {
  RenderOptions options;
  options.threads = threads;
  options.visibility = Visibility::PainterSort;
  return options;
}

// Compares coverage with the outline's inside (pixels whose center lies exactly on the
// outline are skipped: the outline's own edges are not shared, so either answer is right).
void expectCoverageMatchesOutline(const Rendered& rendered,
                                  const std::vector<FixedPoint>& outline) {
  EXPECT_EQ(rendered.stats.fragmentsWritten, rendered.stats.pixelsCovered)
      << "some pixel was painted more than once";
  int mismatches = 0, inside = 0;
  const Framebuffer& fb = rendered.framebuffer;
  for (int y = 0; y < fb.height(); ++y) {
    for (int x = 0; x < fb.width(); ++x) {
      bool onBoundary = false;
      const bool expected = windingNumber(outline, x, y, onBoundary) != 0;
      if (onBoundary) continue;
      inside += expected;
      const bool covered = fb.polygonIdAt(x, y) != Framebuffer::kBackgroundId;
      if (covered != expected && ++mismatches <= 5) {
        ADD_FAILURE() << "pixel (" << x << ", " << y << ") "
                      << (covered ? "covered" : "not covered") << " but the outline says "
                      << (expected ? "inside" : "outside");
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(inside, 100) << "the test shape should cover a good part of the image";
}

// A fan of triangles around a center, vertices at non-integer positions on the 1/256 grid.
void checkFan(glm::dvec2 center, double radius, int triangles, double rotation, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  Mesh mesh;
  mesh.addPoint({snapToSubpixel(center.x), snapToSubpixel(center.y), 0.0});
  std::vector<FixedPoint> outline;
  for (int i = 0; i < triangles; ++i) {
    const double angle = rotation + 2.0 * M_PI * (i + jitter(random)) / triangles;
    const double x = snapToSubpixel(center.x + radius * std::cos(angle));
    const double y = snapToSubpixel(center.y + radius * std::sin(angle));
    mesh.addPoint({x, y, 0.0});
    outline.push_back(toFixed(x, y));
  }
  for (int i = 0; i < triangles; ++i)
    mesh.addPolygon({0, 1 + i, 1 + (i + 1) % triangles});
  const Rendered rendered =
      renderScene(oneMeshScene(mesh.view()), pixelCamera(kFrameWidth, kFrameHeight), kFrameWidth,
                  kFrameHeight, painterOptions());
  SCOPED_TRACE("fan center (" + std::to_string(center.x) + ", " + std::to_string(center.y) +
               ") radius " + std::to_string(radius));
  expectCoverageMatchesOutline(rendered, outline);
}

// A grid of quads, each split into two triangles, rotated about its center.
void checkGrid(glm::dvec2 origin, double cell, int cells, double rotation) {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double half = 0.5 * cell * cells;
  Mesh mesh;
  auto gridPoint = [&](int i, int j) {
    const double u = i * cell - half, v = j * cell - half;
    return glm::dvec2(snapToSubpixel(origin.x + c * u - s * v),
                      snapToSubpixel(origin.y + s * u + c * v));
  };
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const glm::dvec2 p = gridPoint(i, j);
      mesh.addPoint({p.x, p.y, 0.0});
    }
  }
  const auto id = [&](int i, int j) { return std::int64_t{j} * (cells + 1) + i; };
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      // Alternate the diagonal so both orientations of shared edges occur.
      if ((i + j) % 2 == 0) {
        mesh.addPolygon({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        mesh.addPolygon({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        mesh.addPolygon({id(i, j), id(i + 1, j), id(i, j + 1)});
        mesh.addPolygon({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  }
  std::vector<FixedPoint> outline;
  for (int i = 0; i < cells; ++i)
    outline.push_back(toFixed(gridPoint(i, 0).x, gridPoint(i, 0).y));
  for (int j = 0; j < cells; ++j)
    outline.push_back(toFixed(gridPoint(cells, j).x, gridPoint(cells, j).y));
  for (int i = cells; i > 0; --i)
    outline.push_back(toFixed(gridPoint(i, cells).x, gridPoint(i, cells).y));
  for (int j = cells; j > 0; --j)
    outline.push_back(toFixed(gridPoint(0, j).x, gridPoint(0, j).y));
  const Rendered rendered =
      renderScene(oneMeshScene(mesh.view()), pixelCamera(kFrameWidth, kFrameHeight), kFrameWidth,
                  kFrameHeight, painterOptions());
  SCOPED_TRACE("grid rotation " + std::to_string(rotation));
  expectCoverageMatchesOutline(rendered, outline);
}

TEST(Watertight, FanAroundACenter) {
  checkFan({80.37, 60.81}, 45.3, 37, 0.0, 1);
  checkFan({80.5, 60.5}, 40.0, 64, 0.1, 2);  // center exactly on a pixel center
}

TEST(Watertight, GridOfSplitQuads) {
  checkGrid({80.21, 59.93}, 7.13, 12, 0.0);
  checkGrid({80.5, 60.5}, 8.0, 10, 0.0);  // edges through pixel centers
}

TEST(Watertight, RotatedGrids) {
  for (double degrees : {3.0, 17.0, 45.0, 71.3, 90.0, 133.0}) {
    checkGrid({79.77, 60.13}, 6.61, 12, degrees * M_PI / 180.0);
  }
}

TEST(Watertight, PartlyOffScreen) {
  checkFan({10.3, 100.7}, 70.0, 29, 0.2, 3);
  checkGrid({150.1, 5.3}, 9.7, 14, 0.3);
}

TEST(Watertight, BeyondTheGuardBand) {
  // Vertices tens of thousands of pixels away: the guard-band planes clip these triangles.
  checkFan({80.37, 60.81}, 60000.0, 7, 0.05, 4);
  checkGrid({80.2, 60.1}, 5000.0, 16, 0.4);
}

// A floor grid seen from a low camera looking down: the near plane cuts through the
// visible floor, so the front triangles are clipped in homogeneous space.
TEST(Watertight, ClippedByTheNearPlane) {
  const double extent = 20.0;
  const Mesh floor = makeFloorGrid(40, extent);
  const Camera camera = nearClippedFloorCamera();
  const Rendered rendered =
      renderScene(oneMeshScene(floor.view()), camera, kFrameWidth, kFrameHeight, painterOptions());
  EXPECT_GT(rendered.stats.trianglesClipped, 0u);
  EXPECT_EQ(rendered.stats.fragmentsWritten, rendered.stats.pixelsCovered)
      << "some pixel was painted more than once";

  // Independent expectation: the ray through each pixel center hits the floor square at a
  // depth between near and far. Pixels where the answer changes within half a pixel are
  // boundary pixels and skipped.
  const glm::dvec3 forward = glm::normalize(camera.focalPoint - camera.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.viewUp));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(M_PI / 6.0), aspect = double(kFrameWidth) / kFrameHeight;
  auto covers = [&](double wx, double wy) {
    const double nx = 2.0 * wx / kFrameWidth - 1.0, ny = 2.0 * wy / kFrameHeight - 1.0;
    const glm::dvec3 ray = forward + nx * tanHalf * aspect * right + ny * tanHalf * up;
    if (ray.z >= 0.0) return false;
    const double t = -camera.position.z / ray.z;  // depth along forward equals t
    const glm::dvec3 hit = camera.position + t * ray;
    return t >= camera.nearClip && t <= camera.farClip && std::abs(hit.x) <= extent &&
           std::abs(hit.y) <= extent;
  };
  int checked = 0, mismatches = 0;
  for (int y = 0; y < kFrameHeight; ++y) {
    for (int x = 0; x < kFrameWidth; ++x) {
      const bool expected = covers(x + 0.5, y + 0.5);
      bool boundary = false;
      for (double dx : {0.0, 1.0}) {
        for (double dy : {0.0, 1.0})
          boundary |= covers(x + dx, y + dy) != expected;
      }
      if (boundary) continue;
      ++checked;
      const bool covered = rendered.framebuffer.polygonIdAt(x, y) != Framebuffer::kBackgroundId;
      if (covered != expected && ++mismatches <= 5) {
        ADD_FAILURE() << "pixel (" << x << ", " << y << ") covered " << covered << ", expected "
                      << expected;
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(checked, kFrameWidth * kFrameHeight / 2);
}

TEST(FillRule, SamplesOnASharedDiagonalBelongToExactlyOneTriangle) {
  Mesh square;  // corners on pixel centers: the diagonal passes through 8 of them
  square.addPoint({0.5, 0.5, 0.0});
  square.addPoint({8.5, 0.5, 0.0});
  square.addPoint({8.5, 8.5, 0.0});
  square.addPoint({0.5, 8.5, 0.0});
  square.addPolygon({0, 1, 2});  // lower right: the diagonal 2→0 is its left edge
  square.addPolygon({0, 2, 3});  // upper left: the diagonal 0→2 is its right edge
  const Rendered r =
      renderScene(oneMeshScene(square.view()), pixelCamera(16, 16), 16, 16, painterOptions());
  EXPECT_EQ(r.stats.fragmentsWritten, r.stats.pixelsCovered);
  for (int i = 1; i < 8; ++i) {
    EXPECT_EQ(r.framebuffer.polygonIdAt(i, i), 0) << "diagonal sample " << i << " (top-left rule)";
  }
  // Outline edges: left (x = 0.5, owned) and top (y = 8.5, owned) are in; right and bottom not.
  EXPECT_NE(r.framebuffer.polygonIdAt(0, 4), Framebuffer::kBackgroundId) << "left edge";
  EXPECT_EQ(r.framebuffer.polygonIdAt(8, 4), Framebuffer::kBackgroundId) << "right edge";
  EXPECT_EQ(r.framebuffer.polygonIdAt(4, 0), Framebuffer::kBackgroundId) << "bottom edge";
  EXPECT_NE(r.framebuffer.polygonIdAt(4, 8), Framebuffer::kBackgroundId) << "top edge";
}

TEST(FillRule, HorizontalAndVerticalSharedEdgesThroughSampleRows) {
  Mesh mesh;  // two triangles stacked on a horizontal edge at y = 4.5, two side by side at x = 12.5
  for (glm::dvec3 p : {glm::dvec3{1.3, 1.2, 0},
                       {7.9, 4.5, 0},
                       {1.1, 4.5, 0},
                       {5.2, 8.8, 0},
                       {12.5, 1.1, 0},
                       {12.5, 9.3, 0},
                       {9.2, 5.1, 0},
                       {15.7, 4.9, 0}}) {
    mesh.addPoint(p);
  }
  mesh.addPolygon({0, 1, 2});  // below y = 4.5: the edge 1→2 runs leftward, its top edge
  mesh.addPolygon({2, 1, 3});  // above
  mesh.addPolygon({4, 5, 6});  // left of x = 12.5: the edge 4→5 runs upward, its right edge
  mesh.addPolygon({4, 7, 5});  // right: the edge 5→4 runs downward, its left edge
  const Rendered r =
      renderScene(oneMeshScene(mesh.view()), pixelCamera(17, 10), 17, 10, painterOptions());
  EXPECT_EQ(r.stats.fragmentsWritten, r.stats.pixelsCovered);
  for (int x = 2; x <= 6; ++x)
    EXPECT_EQ(r.framebuffer.polygonIdAt(x, 4), 0) << "x " << x;
  for (int y = 2; y <= 7; ++y)
    EXPECT_EQ(r.framebuffer.polygonIdAt(12, y), 3) << "y " << y;
}

TEST(Coverage, RandomTrianglesCoverTheirAreaWithinThePerimeter) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-20.0, 276.0);
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    glm::dvec2 p[3];
    for (auto& v : p)
      v = {snapToSubpixel(coordinate(random)), snapToSubpixel(coordinate(random))};
    // Clip the expectation to the image by keeping triangles inside it.
    bool inside = true;
    for (auto& v : p)
      inside &= v.x >= 0 && v.y >= 0 && v.x <= 256 && v.y <= 256;
    if (!inside) continue;
    Mesh mesh;
    for (auto& v : p)
      mesh.addPoint({v.x, v.y, 0.0});
    mesh.addPolygon({0, 1, 2});
    const Rendered r = renderScene(oneMeshScene(mesh.view()), pixelCamera(256, 256), 256, 256);
    const double area = 0.5 * std::abs((p[1].x - p[0].x) * (p[2].y - p[0].y) -
                                       (p[2].x - p[0].x) * (p[1].y - p[0].y));
    const double perimeter =
        glm::length(p[1] - p[0]) + glm::length(p[2] - p[1]) + glm::length(p[0] - p[2]);
    EXPECT_NEAR(double(r.stats.pixelsCovered), area, perimeter + 1.0)
        << "triangle (" << p[0].x << "," << p[0].y << ") (" << p[1].x << "," << p[1].y << ") ("
        << p[2].x << "," << p[2].y << ")";
    ++checked;
  }
  EXPECT_GT(checked, 30);
}

}  // namespace
}  // namespace facet::testing
