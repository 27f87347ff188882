#pragma once

/// @file PolygonNormal.h
/// Polygon normals by Newell's method, from all the vertices (and, for self-intersecting
/// polygons whose lobes cancel, from their fan triangles).

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

namespace detail {

/// Vertex i relative to vertex 0, in units of `unit`. Multiplying by the inverse is exact
/// enough and much cheaper, unless the inverse overflows.
template <class VertexAt>
glm::dvec3 relativeVertex(const VertexAt& vertexAt, std::size_t i, const glm::dvec3& origin,
                          double unit, double inverseUnit) {
  return std::isfinite(inverseUnit) ? (vertexAt(i) - origin) * inverseUnit
                                    : (vertexAt(i) - origin) / unit;
}

/// The largest extent of the vertices' bounding box (the unit the normal functions work in,
/// so that neither tiny (1e-200) nor huge (1e200) polygons underflow or overflow when
/// squared) and the box's squared diagonal in that unit; nothing when the extent is zero or
/// not finite.
struct PolygonExtent {
  double unit;
  double diagonalSquared;
};
template <class VertexAt>
std::optional<PolygonExtent> polygonExtent(std::size_t count, const VertexAt& vertexAt) {
  const glm::dvec3 origin = vertexAt(0);
  glm::dvec3 low{0.0}, high{0.0};
  for (std::size_t i = 1; i < count; ++i) {
    const glm::dvec3 v = vertexAt(i) - origin;
    low = glm::min(low, v);
    high = glm::max(high, v);
  }
  const glm::dvec3 extent = high - low;
  const double unit = std::max({extent.x, extent.y, extent.z});
  if (!(unit > 0.0) || !std::isfinite(unit)) return std::nullopt;
  return PolygonExtent{unit, glm::dot(extent / unit, extent / unit)};
}

/// Calls f(vertexAt, extent) with the polygon's extent, and nothing when it has none. The
/// normal does not depend on scale: when differences of the coordinates overflow (finite
/// coordinates beyond ±DBL_MAX/2), f gets the vertices divided by 256 (exactly) instead.
template <class VertexAt, class F>
auto withExtent(std::size_t count, const VertexAt& vertexAt, const F& f)
    -> std::optional<glm::dvec3> {
  if (const std::optional<PolygonExtent> extent = polygonExtent(count, vertexAt)) {
    return f(vertexAt, *extent);
  }
  const auto scaled = [&](std::size_t i) { return vertexAt(i) * 0x1p-8; };
  if (const std::optional<PolygonExtent> extent = polygonExtent(count, scaled)) {
    return f(scaled, *extent);
  }
  return std::nullopt;
}

/// `area` (in units of the extent²) as a unit normal, unless it is degenerate (see
/// kDegenerateAreaRatio) or not finite.
inline std::optional<glm::dvec3> unitNormalOf(const glm::dvec3& area, const PolygonExtent& extent) {
  const double length = glm::length(area);
  if (!std::isfinite(length) || !(length > kDegenerateAreaRatio * extent.diagonalSquared)) {
    return std::nullopt;
  }
  return area / length;
}

}  // namespace detail

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
  const double inverse = 1.0 / unit;
  glm::dvec3 previous = detail::relativeVertex(vertexAt, count - 1, origin, unit, inverse);
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3 current = detail::relativeVertex(vertexAt, i, origin, unit, inverse);
    sum.x += (previous.y - current.y) * (previous.z + current.z);
    sum.y += (previous.z - current.z) * (previous.x + current.x);
    sum.z += (previous.x - current.x) * (previous.y + current.y);
    previous = current;
  }
  return sum;
}

/// The unit normal of a polygon (counter-clockwise winding faces the normal), or nothing
/// when the polygon has fewer than 3 vertices, zero area (see kDegenerateAreaRatio), or
/// non-finite coordinates. Never NaN; any finite coordinates, up to ±DBL_MAX, work.
template <class VertexAt>
std::optional<glm::dvec3> newellNormal(std::size_t count, const VertexAt& vertexAt) {
  if (count < 3) return std::nullopt;
  return detail::withExtent(count, vertexAt, [count](const auto& at, const auto& extent) {
    return detail::unitNormalOf(newellAreaVector(count, at, extent.unit), extent);
  });
}

/// The normal of the plane of a self-intersecting polygon whose lobes cancel, such as a
/// bowtie (its Newell vector area is zero): the vector areas of its fan triangles from
/// vertex 0, each turned to agree with the largest one, summed. It faces the way the
/// largest fan triangle winds. Nothing when the polygon has no plane (all fan triangles
/// degenerate).
template <class VertexAt>
std::optional<glm::dvec3> alignedFanNormal(std::size_t count, const VertexAt& vertexAt) {
  if (count < 3) return std::nullopt;
  return detail::withExtent(count, vertexAt, [count](const auto& at, const auto& extent) {
    const glm::dvec3 origin = at(0);
    const double inverse = 1.0 / extent.unit;
    const auto fanArea = [&](std::size_t k) {
      return glm::cross(detail::relativeVertex(at, k, origin, extent.unit, inverse),
                        detail::relativeVertex(at, k + 1, origin, extent.unit, inverse));
    };
    glm::dvec3 largest{0.0};
    for (std::size_t k = 1; k + 1 < count; ++k) {
      const glm::dvec3 area = fanArea(k);
      if (glm::dot(area, area) > glm::dot(largest, largest)) largest = area;
    }
    glm::dvec3 sum{0.0};
    for (std::size_t k = 1; k + 1 < count; ++k) {
      const glm::dvec3 area = fanArea(k);
      sum += glm::dot(area, largest) < 0.0 ? -area : area;
    }
    return detail::unitNormalOf(sum, extent);
  });
}

/// The normal Facet lights, orients and culls a polygon by (of more than three vertices:
/// triangles use triangleNormal): newellNormal, or for a polygon whose Newell vector area
/// cancels out (a bowtie), alignedFanNormal.
template <class VertexAt>
std::optional<glm::dvec3> polygonNormal(std::size_t count, const VertexAt& vertexAt) {
  if (std::optional<glm::dvec3> normal = newellNormal(count, vertexAt)) return normal;
  return alignedFanNormal(count, vertexAt);
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

/// polygonNormal for a polygon given as a span of vertices.
inline std::optional<glm::dvec3> polygonNormal(std::span<const glm::dvec3> vertices) {
  return polygonNormal(vertices.size(), [&](std::size_t i) { return vertices[i]; });
}

}  // namespace facet
