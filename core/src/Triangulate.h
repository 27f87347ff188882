#pragma once

// Triangulation of polygons with more than three vertices, in the polygon's own plane (world
// space, so the result does not depend on the camera).
//
// - Convex polygons: a fan from vertex 0.
// - Simple concave polygons (collinear runs, repeated points, touching vertices included):
//   ear clipping, which covers exactly the polygon.
// - Self-intersecting polygons (two edges cross): a fan from vertex 0, as VTK's OpenGL mapper
//   draws every polygon (vtkOpenGLIndexBufferObject::AppendTriangleIndexBuffer, VTK 9.1).
//   Each fan triangle is painted whatever its own winding, so a bowtie shows both lobes (and,
//   as in VTK, the region the two fan triangles share); the whole polygon is lit and culled
//   with one normal (polygonNormal, PolygonNormal.h). A self-intersecting polygon has no
//   inside that both the even-odd and nonzero rules agree on, and drawing it as VTK does is
//   what a VTK user sees elsewhere.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace facet::detail {

using LocalTriangle = std::array<std::uint32_t, 3>;  // corner indices within the polygon

// Scratch memory kept between polygons and between renders, so triangulating allocates
// nothing once warmed up.
struct TriangulationScratch {
  std::vector<glm::dvec2> projected;
  std::vector<std::uint32_t> remaining;  // earClip
  std::vector<std::uint32_t> edgeOrder;  // selfIntersects
};

// Projects the vertices onto the coordinate plane most orthogonal to `normal`, oriented so
// that a polygon counter-clockwise about `normal` stays counter-clockwise. Relative to
// vertex 0.
void projectToPolygonPlane(std::span<const glm::dvec3> vertices, const glm::dvec3& normal,
                           std::vector<glm::dvec2>& projected);

// True when no corner of the projected polygon turns clockwise (collinear corners allowed).
// Such a polygon is convex, and a fan from corner 0 covers it exactly, or it winds around
// more than once (a pentagram), self-intersects, and is fanned by that rule.
bool isConvex(std::span<const glm::dvec2> projected);

// True when two edges of the closed outline cross, each strictly across the other's line.
// Touching is not crossing (a repeated point, a vertex on another edge, collinear overlaps):
// ear clipping handles those. A sweep over x: O(n log n) plus the pairs of edges whose
// x-extents overlap.
bool selfIntersects(std::span<const glm::dvec2> projected, TriangulationScratch& scratch);

// Ear clipping (O(n²)): appends n − 2 triangles covering a simple polygon, counter-clockwise
// in the projected plane. It terminates with n − 2 triangles for any input (when no ear is
// left, from rounding, it cuts a corner anyway).
void earClip(std::span<const glm::dvec2> projected, TriangulationScratch& scratch,
             std::vector<LocalTriangle>& triangles);

}  // namespace facet::detail
