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

/// A triangle whose largest angle has a sine at most this is degenerate (its corners are
/// collinear to within rounding: the cross product of two unit edge directions is good to
/// about 1e-16). Relative to its own angles, not its size, so a triangle 1 unit wide and
/// 1e15 long keeps its normal.
inline constexpr double kDegenerateSine = 1e-12;

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

namespace detail {

inline double largestMagnitude(const glm::dvec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

inline bool isFinite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// `v` scaled to unit length without overflow or underflow of its squares (any finite,
/// nonzero components: 1e-300 and 1e300 alike).
inline glm::dvec3 direction(const glm::dvec3& v) {
  const glm::dvec3 scaled = v / largestMagnitude(v);
  return scaled / glm::length(scaled);
}

/// triangleNormal for any finite corners, however long and thin the triangle: the cross
/// product of the unit directions of the two edges at the vertex opposite the longest edge.
/// That vertex has the largest angle and so (law of sines) the largest sine, and its edges
/// are the two shortest, so the rounding error of the cross product, about 1e-16 of
/// |u| |w|, is the smallest of the three vertices' (Shewchuk 1997, "Adaptive precision
/// floating-point arithmetic and fast robust geometric predicates", on choosing the
/// shortest edges).
inline std::optional<glm::dvec3> sliverNormal(const glm::dvec3& a, const glm::dvec3& b,
                                              const glm::dvec3& c) {
  // Differences of finite coordinates beyond ±DBL_MAX/2 overflow; dividing every corner by
  // 256 (exact) does not change the normal.
  const double largest = std::max({largestMagnitude(a), largestMagnitude(b), largestMagnitude(c)});
  const double scale = largest > 0x1p1020 ? 0x1p-8 : 1.0;
  const glm::dvec3 corners[3] = {a * scale, b * scale, c * scale};
  // Edge k runs from corner k+1 to corner k+2 (opposite corner k).
  double longest = -1.0;
  int apex = 0;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 edge = corners[(k + 2) % 3] - corners[(k + 1) % 3];
    const double size = largestMagnitude(edge);
    if (size > longest) longest = size, apex = k;
  }
  const glm::dvec3 toNext = corners[(apex + 1) % 3] - corners[apex];
  const glm::dvec3 toPrevious = corners[(apex + 2) % 3] - corners[apex];
  if (toNext == glm::dvec3(0.0) || toPrevious == glm::dvec3(0.0)) return std::nullopt;
  const glm::dvec3 cross = glm::cross(direction(toNext), direction(toPrevious));
  const double sine = glm::length(cross);
  if (!(sine > kDegenerateSine)) return std::nullopt;
  return cross / sine;
}

/// triangleNormal's common case, and what it computed on the way (MeshCache measures
/// blocks of triangles from the same cross product): `plain` when the numbers are well
/// inside double's range and the angle at a is clearly not degenerate.
struct TriangleCross {
  glm::dvec3 ab, ac, cross;
  double lengthSquared, abSquared, acSquared;
  bool plain;
  glm::dvec3 unitNormal() const { return cross * (1.0 / std::sqrt(lengthSquared)); }
};
inline TriangleCross triangleCross(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  TriangleCross t;
  t.ab = b - a;
  t.ac = c - a;
  t.cross = glm::cross(t.ab, t.ac);
  t.lengthSquared = glm::dot(t.cross, t.cross);
  t.abSquared = glm::dot(t.ab, t.ab);
  t.acSquared = glm::dot(t.ac, t.ac);
  // Squares of squares: safe only for moderate magnitudes.
  const bool moderate = t.lengthSquared > 1e-200 && t.lengthSquared < 1e200 &&
                        t.abSquared > 1e-100 && t.abSquared < 1e100 && t.acSquared > 1e-100 &&
                        t.acSquared < 1e100;
  // sin²(angle at a) = |ab × ac|² / (|ab|² |ac|²); the sine at a never exceeds the largest.
  t.plain =
      moderate && t.lengthSquared > kDegenerateSine * kDegenerateSine * t.abSquared * t.acSquared;
  return t;
}

}  // namespace detail

/// The unit normal of triangle abc (counter-clockwise faces it), or nothing when it is
/// degenerate: the sine of its largest angle is at most kDegenerateSine (its corners are
/// collinear to within rounding). A plain cross product when the numbers are well inside
/// double's range and the angle at a is clearly not degenerate (the common case);
/// detail::sliverNormal otherwise, which decides by the largest angle. Scale-free: a
/// triangle 1 unit wide and 1e300 long has a normal.
inline std::optional<glm::dvec3> triangleNormal(const glm::dvec3& a, const glm::dvec3& b,
                                                const glm::dvec3& c) {
  const detail::TriangleCross triangle = detail::triangleCross(a, b, c);
  if (triangle.plain) return triangle.unitNormal();
  if (!detail::isFinite(a) || !detail::isFinite(b) || !detail::isFinite(c)) return std::nullopt;
  return detail::sliverNormal(a, b, c);
}

/// The normal Facet lights, orients and culls a polygon by: triangleNormal for a triangle;
/// otherwise newellNormal, or for a polygon whose Newell vector area cancels out (a bowtie),
/// alignedFanNormal.
template <class VertexAt>
std::optional<glm::dvec3> polygonNormal(std::size_t count, const VertexAt& vertexAt) {
  if (count == 3) return triangleNormal(vertexAt(0), vertexAt(1), vertexAt(2));
  if (std::optional<glm::dvec3> normal = newellNormal(count, vertexAt)) return normal;
  return alignedFanNormal(count, vertexAt);
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
