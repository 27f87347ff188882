#pragma once

// Triangulation of polygons with more than three vertices, in the polygon's own plane (world
// space, so the result does not depend on the camera).
//
// - Convex polygons: a fan from vertex 0 (kLargestFan corners at most), balanced halving
//   beyond.
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
  std::vector<std::uint32_t> next, previous, reflexCorners;  // earClip
  std::vector<std::uint8_t> reflex;                          // earClip
  std::vector<std::uint32_t> edgeOrder;                      // selfIntersects
};

// Projects the vertices onto the coordinate plane most orthogonal to `normal`, oriented so
// that a polygon counter-clockwise about `normal` stays counter-clockwise. Relative to
// vertex 0.
void projectToPolygonPlane(std::span<const glm::dvec3> vertices, const glm::dvec3& normal,
                           std::vector<glm::dvec2>& projected);

// Appends triangles (corner indices, n − 2 of them) covering the projected polygon by the
// rules above: fan, balanced halving of a large convex polygon (kLargestFan), VTK's fan for
// a self-intersecting one, ear clipping for a concave one.
void triangulate(std::span<const glm::dvec2> projected, TriangulationScratch& scratch,
                 std::vector<LocalTriangle>& triangles);

// The polygon's corners (world space) triangulated in the plane of its `normal`
// (polygonNormal): projectToPolygonPlane, then triangulate. Set-up and the mesh reference
// both call this, so they cut every polygon the same way.
void triangulatePolygon(std::span<const glm::dvec3> corners, const glm::dvec3& normal,
                        TriangulationScratch& scratch, std::vector<LocalTriangle>& triangles);

// Convex polygons of more corners than this are split into triangles of balanced shape,
// whose bounding boxes sum to O(area · log n), where a fan's slivers would each span the
// polygon (a 10,000-gon would be painted as 9,998 slivers across it). Up to it, VTK's fan:
// the same triangles as VTK's for the quads and small polygons meshes are made of.
inline constexpr std::size_t kLargestFan = 16;

}  // namespace facet::detail
