#pragma once

/// @file PolygonNormal.h
/// Polygon normals by Newell's method, from all the vertices.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace facet {

/// A polygon whose vector area is below this fraction of its bounding box's squared diagonal
/// has no normal: it is degenerate (collinear or coincident vertices) to within rounding.
inline constexpr double kDegenerateAreaRatio = 1e-12;

/// Newell's vector area of a polygon (twice the area, along the normal), counter-clockwise
/// positive. `vertexAt(i)` returns vertex i as a glm::dvec3 for i in [0, count).
///
/// Uses every vertex, so a polygon whose first three vertices are collinear still gets its
/// true normal, and a slightly non-planar polygon gets the least-squares plane's normal.
/// Coordinates are taken relative to vertex 0, so data far from the origin loses nothing,
/// and divided by `unit` (the result is in units of unit²), so that callers can keep tiny or
/// huge polygons from underflowing or overflowing.
template <class VertexAt>
glm::dvec3 newellAreaVector(std::size_t count, const VertexAt& vertexAt, double unit = 1.0) {
  glm::dvec3 sum{0.0};
  const glm::dvec3 origin = vertexAt(0);
  // Multiplying by the inverse is exact enough and much cheaper, unless it overflows.
  const double inverse = 1.0 / unit;
  const auto scaled = [&](const glm::dvec3& v) {
    return std::isfinite(inverse) ? (v - origin) * inverse : (v - origin) / unit;
  };
  glm::dvec3 previous = scaled(vertexAt(count - 1));
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3 current = scaled(vertexAt(i));
    sum.x += (previous.y - current.y) * (previous.z + current.z);
    sum.y += (previous.z - current.z) * (previous.x + current.x);
    sum.z += (previous.x - current.x) * (previous.y + current.y);
    previous = current;
  }
  return sum;
}

/// The unit normal of a polygon (counter-clockwise winding faces the normal), or nothing
/// when the polygon has fewer than 3 vertices, zero area (see kDegenerateAreaRatio), or
/// non-finite coordinates. Never NaN.
template <class VertexAt>
std::optional<glm::dvec3> newellNormal(std::size_t count, const VertexAt& vertexAt) {
  if (count < 3) return std::nullopt;
  const glm::dvec3 origin = vertexAt(0);
  glm::dvec3 low{0.0}, high{0.0};
  for (std::size_t i = 1; i < count; ++i) {
    const glm::dvec3 v = vertexAt(i) - origin;
    low = glm::min(low, v);
    high = glm::max(high, v);
  }
  // Work in units of the largest extent so that neither tiny (1e-200) nor huge (1e200)
  // polygons underflow or overflow when squared.
  const glm::dvec3 extent = high - low;
  const double scale = std::max({extent.x, extent.y, extent.z});
  if (!(scale > 0.0) || !std::isfinite(scale)) return std::nullopt;
  const glm::dvec3 area = newellAreaVector(count, vertexAt, scale);
  const double length = glm::length(area);
  const double diagonalSquared = glm::dot(extent / scale, extent / scale);
  if (!std::isfinite(length) || !(length > kDegenerateAreaRatio * diagonalSquared)) {
    return std::nullopt;
  }
  return area / length;
}

/// The unit normal of triangle abc (counter-clockwise faces it), or nothing when it is
/// degenerate (relative area below about kDegenerateAreaRatio, as for newellNormal). A plain cross
/// product when the numbers are well inside double's range (the common case); newellNormal
/// otherwise.
inline std::optional<glm::dvec3> triangleNormal(const glm::dvec3& a, const glm::dvec3& b,
                                                const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a;
  const glm::dvec3 cross = glm::cross(ab, ac);
  const double lengthSquared = glm::dot(cross, cross);
  const double extentSquared = std::max(glm::dot(ab, ab), glm::dot(ac, ac));
  // Squares of squares: safe only for moderate magnitudes.
  if (lengthSquared > 1e-200 && lengthSquared < 1e200 && extentSquared > 1e-100 &&
      extentSquared < 1e100) {
    // |ab × ac| vs the bounding-box diagonal² (within a factor 3 of max(|ab|², |ac|²)).
    if (!(lengthSquared >
          kDegenerateAreaRatio * kDegenerateAreaRatio * 9.0 * extentSquared * extentSquared)) {
      return std::nullopt;
    }
    return cross * (1.0 / std::sqrt(lengthSquared));
  }
  const glm::dvec3 corners[3] = {a, b, c};
  return newellNormal(3, [&](std::size_t i) { return corners[i]; });
}

/// newellNormal for a polygon given as a span of vertices.
inline std::optional<glm::dvec3> newellNormal(std::span<const glm::dvec3> vertices) {
  return newellNormal(vertices.size(), [&](std::size_t i) { return vertices[i]; });
}

}  // namespace facet
