#pragma once

// Triangulation of polygons with more than three vertices, in the polygon's own plane (world
// space, so the result does not depend on the camera).

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
  std::vector<std::uint32_t> remaining;
};

// Projects the vertices onto the coordinate plane most orthogonal to `normal`, oriented so
// that a polygon counter-clockwise about `normal` stays counter-clockwise. Relative to
// vertex 0.
void projectToPolygonPlane(std::span<const glm::dvec3> vertices, const glm::dvec3& normal,
                           std::vector<glm::dvec2>& projected);

// True when no corner of the projected polygon turns clockwise (collinear corners allowed):
// a fan from corner 0 then covers it exactly.
bool isConvex(std::span<const glm::dvec2> projected);

// Ear clipping (O(n²)): appends n − 2 triangles covering a simple polygon, counter-clockwise
// in the projected plane. For a self-intersecting polygon, which has no exact
// triangulation, it still terminates with n − 2 triangles.
void earClip(std::span<const glm::dvec2> projected, TriangulationScratch& scratch,
             std::vector<LocalTriangle>& triangles);

}  // namespace facet::detail
