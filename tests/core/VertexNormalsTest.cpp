// Corner normals with vtkPolyDataNormals' meaning: closed forms (cube, sphere), the feature
// angle's definition checked edge by edge on fandisk, flipped polygons, degenerate input.
// The comparison with vtkPolyDataNormals itself is tests/adapters/VertexNormalsVtkTest.cxx.

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../support/TestMeshes.h"
#include "facet/Error.h"
#include "facet/Lighting.h"
#include "facet/PolygonNormal.h"
#include "facet/QualityRenderer.h"
#include "facet/Renderer.h"
#include "facet/VertexNormals.h"

namespace facet {
namespace {

using testing::makeBox;
using testing::makeUvSphere;
using testing::readObj;
using testing::sharedMeshPath;

glm::dvec3 cornerNormal(const VertexNormals& normals, const Mesh& mesh, std::size_t polygon,
                        std::size_t k) {
  return normals.normals[normals.cornerNormal[mesh.offsets[polygon] + k]];
}

glm::dvec3 faceNormal(const Mesh& mesh, std::size_t polygon) {
  std::vector<glm::dvec3> corners;
  for (auto k = mesh.offsets[polygon]; k < mesh.offsets[polygon + 1]; ++k)
    corners.push_back(mesh.points[mesh.connectivity[k]]);
  return newellNormal(corners).value_or(glm::dvec3(0.0));
}

void reverse(Mesh& mesh, std::size_t polygon) {
  std::reverse(mesh.connectivity.begin() + mesh.offsets[polygon],
               mesh.connectivity.begin() + mesh.offsets[polygon + 1]);
}

void expectAllFinite(const VertexNormals& normals) {
  for (const glm::dvec3& n : normals.normals) {
    ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
  }
}

TEST(VertexNormals, CubeCornersKeepTheirFaceNormals) {
  const Mesh cube = makeBox({-1, -2, -3}, {1, 2, 3});
  const VertexNormals normals = computeVertexNormals(cube.view());
  ASSERT_EQ(normals.cornerNormal.size(), 24u);
  EXPECT_EQ(normals.normals.size(), 24u) << "90° edges are all sharp: 3 normals per corner";
  EXPECT_EQ(normals.splitPoints, 8u);
  for (std::size_t p = 0; p < cube.polygonCount(); ++p) {
    for (std::size_t k = 0; k < 4; ++k) {
      const glm::dvec3 n = cornerNormal(normals, cube, p, k);
      EXPECT_LT(glm::length(n - faceNormal(cube, p)), 1e-15) << "polygon " << p << " corner " << k;
      EXPECT_EQ(normals.point[normals.cornerNormal[cube.offsets[p] + k]],
                cube.connectivity[cube.offsets[p] + k]);
    }
  }
}

TEST(VertexNormals, FeatureAngleAbove90SmoothsTheCubeToItsDiagonals) {
  const Mesh cube = makeBox({-1, -1, -1}, {1, 1, 1});
  const VertexNormals normals = computeVertexNormals(cube.view(), {.featureAngleDegrees = 91.0});
  EXPECT_EQ(normals.normals.size(), 8u);
  EXPECT_EQ(normals.splitPoints, 0u);
  for (std::size_t i = 0; i < normals.normals.size(); ++i) {
    const glm::dvec3 diagonal = glm::normalize(cube.points[normals.point[i]]);
    EXPECT_LT(glm::length(normals.normals[i] - diagonal), 1e-15) << "point " << normals.point[i];
  }
}

TEST(VertexNormals, FineSphereNormalsAreRadial) {
  // The unweighted sum (vtkPolyDataNormals') leans toward the wider triangles of a UV
  // sphere by about a tenth of the angle between rings; the error shrinks with it.
  for (const int phi : {33, 129}) {
    const Mesh sphere = makeUvSphere(2 * (phi - 1), phi, 2.0, {1, 2, 3});
    const VertexNormals normals = computeVertexNormals(sphere.view());
    EXPECT_EQ(normals.splitPoints, 0u);
    EXPECT_EQ(normals.normals.size(), sphere.points.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < normals.normals.size(); ++i) {
      const glm::dvec3 radial = sphere.points[normals.point[i]] - glm::dvec3(1, 2, 3);
      worst = std::max(worst, angleBetweenDegrees(normals.normals[i], radial));
    }
    const double ringStep = 180.0 / (phi - 1);
    EXPECT_LT(worst, 0.12 * ringStep) << phi << " rings";
  }
}

// The manifold edges of a mesh: (low point, high point) → the polygons using it.
std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> edgesOf(
    const Mesh& mesh) {
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> edges;
  for (std::size_t p = 0; p < mesh.polygonCount(); ++p) {
    const auto n = mesh.offsets[p + 1] - mesh.offsets[p];
    for (std::int64_t k = 0; k < n; ++k) {
      const auto a = mesh.connectivity[mesh.offsets[p] + k];
      const auto b = mesh.connectivity[mesh.offsets[p] + (k + 1) % n];
      edges[std::minmax(a, b)].push_back(p);
    }
  }
  return edges;
}

std::size_t cornerOf(const Mesh& mesh, std::size_t polygon, std::int64_t point) {
  for (auto k = mesh.offsets[polygon]; k < mesh.offsets[polygon + 1]; ++k) {
    if (mesh.connectivity[k] == point) return static_cast<std::size_t>(k);
  }
  ADD_FAILURE() << "point " << point << " not in polygon " << polygon;
  return 0;
}

// In blocks on the renderer's threads: the same normals, in the same order, for 1, 2 and 8
// threads as on the caller's alone — on fandisk (creases: points with several normals, one
// block) and on a sphere of many blocks of points, some of its polygons flipped and one
// degenerate (every counter counted in the blocks).
TEST(VertexNormals, SameForAnyThreadCount) {
  Mesh sphere = makeUvSphere(160, 90);  // 14k points: four blocks
  for (std::size_t p = 0; p < sphere.polygonCount(); p += 97)
    reverse(sphere, p);
  sphere.points[sphere.connectivity[sphere.offsets[5] + 1]] =
      sphere.points[sphere.connectivity[sphere.offsets[5]]];  // polygon 5 loses its area
  for (const Mesh& mesh : {readObj(sharedMeshPath("fandisk.obj")), sphere}) {
    const VertexNormals alone = computeVertexNormals(mesh.view());
    EXPECT_GT(alone.splitPoints, 0u);
    for (const int threads : {1, 2, 8}) {
      Renderer renderer;
      renderer.setThreadCount(threads);
      const VertexNormals spread = computeVertexNormals(mesh.view(), {}, parallelOn(renderer));
      EXPECT_EQ(spread.normals, alone.normals) << threads << " threads";
      EXPECT_EQ(spread.cornerNormal, alone.cornerNormal) << threads << " threads";
      EXPECT_EQ(spread.point, alone.point) << threads << " threads";
      EXPECT_EQ(spread.splitPoints, alone.splitPoints);
      EXPECT_EQ(spread.inconsistentEdges, alone.inconsistentEdges);
      EXPECT_EQ(spread.degeneratePolygons, alone.degeneratePolygons);
    }
    // What the blocks join must be the definition, not only the same for every thread
    // count: each corner's normal belongs to the corner's point, the normals come point by
    // point, and each is unit (or zero, for the degenerate polygon's corners alone).
    ASSERT_EQ(alone.cornerNormal.size(), mesh.connectivity.size());
    for (std::size_t c = 0; c < mesh.connectivity.size(); ++c) {
      ASSERT_LT(alone.cornerNormal[c], alone.point.size()) << "corner " << c;
      ASSERT_EQ(alone.point[alone.cornerNormal[c]], mesh.connectivity[c]) << "corner " << c;
    }
    EXPECT_TRUE(std::ranges::is_sorted(alone.point));
    for (const glm::dvec3& n : alone.normals) {
      const double length = glm::length(n);
      EXPECT_TRUE(length == 0.0 || std::abs(length - 1.0) < 1e-12) << length;
    }
  }
}

// The feature angle's definition, edge by edge: across a smooth edge both polygons share the
// normal at both ends; across a sharp edge they do not, at every end where at least two
// sharp edges meet (one sharp edge alone cannot cut the disk of polygons around a point).
TEST(VertexNormals, FandiskKeepsItsCreases) {
  const Mesh fandisk = readObj(sharedMeshPath("fandisk.obj"));
  const VertexNormals normals = computeVertexNormals(fandisk.view());
  const auto edges = edgesOf(fandisk);
  std::map<std::int64_t, int> sharpEdgesAt;
  for (const auto& [edge, polygons] : edges) {
    ASSERT_EQ(polygons.size(), 2u) << "fandisk is a closed manifold";
    if (angleBetweenDegrees(faceNormal(fandisk, polygons[0]), faceNormal(fandisk, polygons[1])) >=
        30.0) {
      ++sharpEdgesAt[edge.first];
      ++sharpEdgesAt[edge.second];
    }
  }
  std::size_t sharp = 0, smooth = 0;
  for (const auto& [edge, polygons] : edges) {
    const double angle =
        angleBetweenDegrees(faceNormal(fandisk, polygons[0]), faceNormal(fandisk, polygons[1]));
    for (const std::int64_t point : {edge.first, edge.second}) {
      const bool shared = normals.cornerNormal[cornerOf(fandisk, polygons[0], point)] ==
                          normals.cornerNormal[cornerOf(fandisk, polygons[1], point)];
      if (angle < 30.0) {
        EXPECT_TRUE(shared) << "smooth edge " << edge.first << "-" << edge.second << " at "
                            << angle;
        ++smooth;
      } else if (sharpEdgesAt[point] >= 2) {
        EXPECT_FALSE(shared) << "crease " << edge.first << "-" << edge.second << " at " << angle;
        ++sharp;
      }
    }
  }
  std::printf("fandisk: %zu points, %zu normals, %zu split points, %zu crease ends, %zu smooth\n",
              fandisk.points.size(), normals.normals.size(), normals.splitPoints, sharp, smooth);
  EXPECT_GT(sharp, 100u) << "fandisk has creases";
  EXPECT_GT(normals.splitPoints, 50u);
}

TEST(VertexNormals, FlippedPolygonsStillGetSmoothNormals) {
  Mesh sphere = makeUvSphere(48, 25);
  std::set<std::size_t> flipped;
  for (std::size_t p = 0; p < sphere.polygonCount(); p += 7) {
    reverse(sphere, p);
    flipped.insert(p);
  }
  const VertexNormals normals = computeVertexNormals(sphere.view());
  EXPECT_EQ(normals.splitPoints, 0u);
  EXPECT_GT(normals.inconsistentEdges, flipped.size()) << "each flipped triangle has 3 such edges";
  double worst = 0.0;
  for (std::size_t p = 0; p < sphere.polygonCount(); ++p) {
    for (std::size_t k = 0; k < 3; ++k) {
      // In the polygon's own orientation: inward for the flipped ones.
      const glm::dvec3 radial = sphere.points[sphere.connectivity[sphere.offsets[p] + k]];
      const double sign = flipped.count(p) ? -1.0 : 1.0;
      worst =
          std::max(worst, angleBetweenDegrees(cornerNormal(normals, sphere, p, k), sign * radial));
    }
  }
  EXPECT_LT(worst, 2.0);
}

TEST(VertexNormals, DegeneratePolygonsGiveZeroNotNaN) {
  Mesh mesh;
  const auto a = mesh.addPoint({0, 0, 0}), b = mesh.addPoint({1, 0, 0}),
             c = mesh.addPoint({0, 1, 0}), d = mesh.addPoint({2, 0, 0}),
             e = mesh.addPoint({std::nan(""), 0, 0}), f = mesh.addPoint({1, 1, 0});
  mesh.addPolygon({a, b, c});     // fine
  mesh.addPolygon({a, d, b});     // collinear: zero area
  mesh.addPolygon({a, c, e});     // a NaN point
  mesh.addPolygon({b, f, f, c});  // repeated point: still has an area and a normal
  mesh.addPolygon({c, c, c});     // one point three times
  const VertexNormals normals = computeVertexNormals(mesh.view());
  expectAllFinite(normals);
  EXPECT_EQ(normals.degeneratePolygons, 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(cornerNormal(normals, mesh, 1, k), glm::dvec3(0.0));
    EXPECT_EQ(cornerNormal(normals, mesh, 2, k), glm::dvec3(0.0));
    EXPECT_EQ(cornerNormal(normals, mesh, 4, k), glm::dvec3(0.0));
  }
  EXPECT_LT(glm::length(cornerNormal(normals, mesh, 0, 1) - glm::dvec3(0, 0, 1)), 1e-15);
  EXPECT_LT(glm::length(cornerNormal(normals, mesh, 3, 1) - glm::dvec3(0, 0, 1)), 1e-15);
}

TEST(VertexNormals, InputPointNormalsAreUsedNormalized) {
  const Mesh sphere = makeUvSphere(16, 9);
  std::vector<glm::vec3> given(sphere.points.begin(), sphere.points.end());
  for (glm::vec3& n : given)
    n *= 3.0f;                 // not unit: normalized on the way
  given[5] = glm::vec3(0.0f);  // unusable: replaced by the face normals around point 5
  const VertexNormals normals = fromPointNormals(sphere.view(), PointArray::of(given));
  expectAllFinite(normals);
  std::size_t replaced = 0;
  for (std::size_t p = 0; p < sphere.polygonCount(); ++p) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto point = sphere.connectivity[sphere.offsets[p] + k];
      const glm::dvec3 n = cornerNormal(normals, sphere, p, k);
      const glm::dvec3 expected =
          point == 5 ? faceNormal(sphere, p) : glm::normalize(sphere.points[point]);
      EXPECT_LT(glm::length(n - expected), 1e-6) << "polygon " << p << " point " << point;
      replaced += point == 5;
    }
  }
  EXPECT_EQ(normals.replacedNormals, replaced);
  EXPECT_GT(replaced, 0u);
  EXPECT_EQ(normals.normals.size(), sphere.points.size() - 1 + replaced);
}

TEST(VertexNormals, Int32AndFloatArraysGiveTheSameNormals) {
  const Mesh sphere = makeUvSphere(12, 7);
  const std::vector<glm::vec3> points(sphere.points.begin(), sphere.points.end());
  const std::vector<std::int32_t> offsets(sphere.offsets.begin(), sphere.offsets.end());
  const std::vector<std::int32_t> connectivity(sphere.connectivity.begin(),
                                               sphere.connectivity.end());
  MeshView narrow;
  narrow.points = PointArray::of(points);
  narrow.polygons = PolygonArray::of(offsets, connectivity);
  const VertexNormals a = computeVertexNormals(sphere.view()), b = computeVertexNormals(narrow);
  ASSERT_EQ(a.cornerNormal, b.cornerNormal);
  for (std::size_t i = 0; i < a.normals.size(); ++i)
    EXPECT_LT(glm::length(a.normals[i] - b.normals[i]), 1e-6);
}

TEST(VertexNormals, BadInputIsNamed) {
  const Mesh cube = makeBox({0, 0, 0}, {1, 1, 1});
  EXPECT_THROW(computeVertexNormals(cube.view(), {.featureAngleDegrees = -1.0}), Error);
  EXPECT_THROW(computeVertexNormals(cube.view(), {.featureAngleDegrees = std::nan("")}), Error);
  const std::vector<glm::dvec3> tooFew(3);
  EXPECT_THROW(fromPointNormals(cube.view(), PointArray::of(tooFew)), Error);
  Mesh broken = cube;
  broken.connectivity[2] = 99;
  EXPECT_THROW(computeVertexNormals(broken.view()), Error);
}

}  // namespace
}  // namespace facet
