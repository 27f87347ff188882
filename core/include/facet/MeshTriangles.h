#pragma once

/// @file MeshTriangles.h
/// A mesh's polygons as the triangles the rasterizer draws, for renderers that need
/// triangles of their own (the mesh reference traces them with Embree).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Mesh.h"

namespace facet {

struct MeshTriangle {
  std::uint32_t polygon = 0;
  /// Indices into the polygons' connectivity array (so into VertexNormals::cornerNormal).
  std::array<std::uint32_t, 3> corner{};
  std::array<std::uint32_t, 3> point{};  ///< the corners' point ids
};

/// The rasterizer's triangulation of every polygon, in polygon order: a triangle as it is;
/// a larger polygon as a fan from corner 0 when convex and by ear clipping in its plane
/// otherwise, each triangle counter-clockwise about the polygon's Newell normal. Polygons
/// with a non-finite point, and larger polygons without a normal (degenerate), give none.
/// Validates the mesh (throws facet::Error; also for 2^32 or more corners).
std::vector<MeshTriangle> triangulateMesh(const MeshView& mesh);

/// Point i of a point array, in double.
inline glm::dvec3 pointAt(const PointArray& points, std::size_t i) {
  if (points.type == PointArray::Type::Float32) {
    const float* xyz = static_cast<const float*>(points.data) + 3 * i;
    return {xyz[0], xyz[1], xyz[2]};
  }
  const double* xyz = static_cast<const double*>(points.data) + 3 * i;
  return {xyz[0], xyz[1], xyz[2]};
}

}  // namespace facet
