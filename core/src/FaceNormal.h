#pragma once

// The unit normal flat shading lights a polygon by (PolygonNormal.h), rounded to float:
// 12 bytes per polygon, so that MeshCache can keep one per polygon and mesh version and the
// shade phase reads it instead of the polygon's points. Always rounded, kept or not, so a
// versioned and an unversioned mesh shade to the same bytes (float's 6e-8 relative error
// moves a color by about 1e-5 of an 8-bit step).

#include <cstddef>

#include <glm/vec3.hpp>

#include "facet/PolygonNormal.h"

namespace facet::detail {

// Zero for a polygon without a normal (degenerate: no area, or non-finite points).
template <class VertexAt>
glm::vec3 faceNormalOf(std::size_t count, const VertexAt& vertexAt) {
  const std::optional<glm::dvec3> normal = polygonNormal(count, vertexAt);
  return normal ? glm::vec3(*normal) : glm::vec3(0.0f);
}

}  // namespace facet::detail
