// Newell normals: all vertices count, degenerate polygons report "no normal".

#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "facet/PolygonNormal.h"

namespace facet {
namespace {

void expectVectorNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(NewellNormal, CounterClockwiseTriangleFacesPlusZ) {
  const std::vector<glm::dvec3> triangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const auto n = newellNormal(triangle);
  ASSERT_TRUE(n.has_value());
  expectVectorNear(*n, {0, 0, 1}, 1e-15);
}

TEST(NewellNormal, FirstThreeVerticesCollinear) {
  // A cross product of the first three vertices would be zero here.
  const std::vector<glm::dvec3> polygon = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 0, 1}, {0, 0, 1}};
  const auto n = newellNormal(polygon);
  ASSERT_TRUE(n.has_value());
  expectVectorNear(*n, {0, -1, 0}, 1e-15);
}

TEST(NewellNormal, ConcavePolygon) {
  const std::vector<glm::dvec3> arrow = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {2, 1, 0}, {0, 4, 0}};
  const auto n = newellNormal(arrow);
  ASSERT_TRUE(n.has_value());
  expectVectorNear(*n, {0, 0, 1}, 1e-15);
}

TEST(NewellNormal, SlightlyNonPlanarQuadGetsTheAverageNormal) {
  const std::vector<glm::dvec3> quad = {{0, 0, 0}, {1, 0, 0.01}, {1, 1, 0}, {0, 1, 0.01}};
  const auto n = newellNormal(quad);
  ASSERT_TRUE(n.has_value());
  expectVectorNear(*n, {0, 0, 1}, 1e-3);
}

TEST(NewellNormal, ZeroAreaReportsNoNormal) {
  EXPECT_FALSE(newellNormal(std::vector<glm::dvec3>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}));
  EXPECT_FALSE(newellNormal(std::vector<glm::dvec3>{{5, 5, 5}, {5, 5, 5}, {5, 5, 5}}));
  EXPECT_FALSE(newellNormal(std::vector<glm::dvec3>{{0, 0, 0}, {1, 0, 0}}));
  // Goes out and comes back along the same line: zero vector area.
  EXPECT_FALSE(newellNormal(std::vector<glm::dvec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 0, 0}}));
}

TEST(NewellNormal, NonFiniteReportsNoNormal) {
  const double nan = std::nan("");
  EXPECT_FALSE(newellNormal(std::vector<glm::dvec3>{{0, 0, 0}, {1, 0, 0}, {0, nan, 0}}));
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(newellNormal(std::vector<glm::dvec3>{{0, 0, 0}, {inf, 0, 0}, {0, 1, 0}}));
  // Huge but finite is fine: the computation is scale-free.
  const auto huge = newellNormal(std::vector<glm::dvec3>{{0, 0, 0}, {1e300, 0, 0}, {0, 1e300, 0}});
  ASSERT_TRUE(huge.has_value());
  expectVectorNear(*huge, {0, 0, 1}, 1e-15);
}

TEST(NewellNormal, FarFromTheOriginLikeAtTheOrigin) {
  const glm::dvec3 far(1e9, -3e9, 7e8);
  // Unit-sized: at 1e9 a double resolves 1.2e-7, so the normal can agree to about 1e-6.
  const std::vector<glm::dvec3> local = {{0, 0, 0}, {1, 0, 0}, {1, 2, 1}};
  std::vector<glm::dvec3> shifted;
  for (const auto& v : local)
    shifted.push_back(v + far);
  const auto a = newellNormal(local);
  const auto b = newellNormal(shifted);
  ASSERT_TRUE(a && b);
  expectVectorNear(*b, *a, 1e-6);
}

TEST(NewellNormal, TinyAndHugeScalesAgree) {
  for (double scale : {1e-300, 1e-150, 1e-6, 1.0, 1e6, 1e150, 1e300}) {
    const std::vector<glm::dvec3> triangle = {
        {0, 0, 0}, {scale, 0, 0}, {0, 0, -scale}};  // faces +Y
    const auto n = newellNormal(triangle);
    ASSERT_TRUE(n.has_value()) << "scale " << scale;
    expectVectorNear(*n, {0, 1, 0}, 1e-12);
  }
}

// Differences of coordinates near ±DBL_MAX overflow; the normal does not depend on scale,
// so such polygons (and triangles) still get theirs.
TEST(NewellNormal, CoordinatesSpanningTheWholeDoubleRange) {
  const double big = std::numeric_limits<double>::max();
  const std::vector<glm::dvec3> triangle = {{-big, -1, big}, {big, -1, big}, {0, -1, -big}};
  const auto n = newellNormal(triangle);
  ASSERT_TRUE(n.has_value());
  expectVectorNear(*n, {0, 1, 0}, 1e-12);
  const auto t = triangleNormal(triangle[0], triangle[1], triangle[2]);
  ASSERT_TRUE(t.has_value());
  expectVectorNear(*t, {0, 1, 0}, 1e-12);
}

// A bowtie's lobes cancel: Newell's vector area is zero, polygonNormal still finds its plane
// (oriented as its larger fan triangle); a polygon with no plane has no normal at all.
TEST(PolygonNormal, BowtieGetsThePlaneOfItsFanTriangles) {
  const std::vector<glm::dvec3> bowtie = {{-1, -1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, 1, 0}};
  EXPECT_FALSE(newellNormal(bowtie).has_value());
  const auto n = polygonNormal(bowtie);
  ASSERT_TRUE(n.has_value());
  EXPECT_NEAR(std::abs(n->z), 1.0, 1e-15);
  const std::vector<glm::dvec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  expectVectorNear(*polygonNormal(square), {0, 0, 1}, 1e-15);
  const std::vector<glm::dvec3> collinear = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  EXPECT_FALSE(polygonNormal(collinear).has_value());
}

// A triangle is degenerate by its angles, not its size: 1 unit wide and 1e15 or 1e300 long
// (a strip across the whole image) keeps its normal, whichever corner comes first.
TEST(TriangleNormal, LongThinTrianglesKeepTheirNormal) {
  for (const double length : {1e6, 1e15, 1e300}) {
    const glm::dvec3 a{-0.5, -0.5, 0.0}, b{0.5, -0.5, 0.0}, c{0.0, length, 0.0};
    for (const auto& [p, q, r] : {std::tuple{a, b, c}, std::tuple{c, a, b}, std::tuple{b, c, a}}) {
      const std::optional<glm::dvec3> n = triangleNormal(p, q, r);
      ASSERT_TRUE(n) << "length " << length;
      expectVectorNear(*n, {0, 0, 1}, 1e-15);
      const std::vector<glm::dvec3> corners{p, q, r};
      EXPECT_EQ(polygonNormal(corners), n) << "polygonNormal of a triangle is triangleNormal";
    }
  }
}

TEST(TriangleNormal, TinyTrianglesKeepTheirNormal) {
  const double s = 1e-300;
  const auto n = triangleNormal({0, 0, 0}, {0, s, 0}, {0, 0, s});
  ASSERT_TRUE(n);
  expectVectorNear(*n, {1, 0, 0}, 1e-15);
}

// Collinear to within rounding: the sine of the largest angle is below kDegenerateSine.
TEST(TriangleNormal, NearlyCollinearCornersHaveNoNormal) {
  EXPECT_FALSE(triangleNormal({0, 0, 0}, {1, 0, 0}, {2, 0, 0}));
  EXPECT_FALSE(triangleNormal({0, 0, 0}, {2, 1e-13, 0}, {1, 0, 0}));
  EXPECT_FALSE(triangleNormal({1e15, 0, 0}, {-1e15, 1e-300, 0}, {0, 0, 0}));
  EXPECT_TRUE(triangleNormal({0, 0, 0}, {2, 1e-9, 0}, {1, 0, 0}));
}

TEST(TriangleNormal, NonFiniteOrCoincidentCornersHaveNoNormal) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(triangleNormal({0, 0, 0}, {1, 0, 0}, {0, inf, 0}));
  EXPECT_FALSE(triangleNormal({0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}));
  EXPECT_FALSE(triangleNormal({1, 2, 3}, {1, 2, 3}, {0, 1, 0}));
  const double huge = std::numeric_limits<double>::max();
  const auto n = triangleNormal({-huge, -huge, 0}, {huge, -huge, 0}, {0, huge, 0});
  ASSERT_TRUE(n);
  expectVectorNear(*n, {0, 0, 1}, 1e-15);
}

}  // namespace
}  // namespace facet
