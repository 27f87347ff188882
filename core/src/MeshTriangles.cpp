#include "facet/MeshTriangles.h"

#include <cmath>
#include <limits>
#include <string>

#include "MeshAccess.h"
#include "Triangulate.h"
#include "Validate.h"
#include "facet/PolygonNormal.h"

namespace facet {
namespace {

bool allFinite(std::span<const glm::dvec3> corners) {
  for (const glm::dvec3& c : corners) {
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) return false;
  }
  return true;
}

// The rasterizer's set-up (Setup.cpp) cuts polygons the same way: a triangle as it is; a
// larger polygon, if it has a normal, by Triangulate.h's rules.
void triangulate(std::span<const glm::dvec3> corners, detail::TriangulationScratch& scratch,
                 std::vector<detail::LocalTriangle>& triangles) {
  triangles.clear();
  if (corners.size() < 3 || !allFinite(corners)) return;
  if (corners.size() == 3) {
    triangles.push_back({0, 1, 2});
    return;
  }
  const std::optional<glm::dvec3> normal = polygonNormal(corners);
  if (!normal) return;
  detail::triangulatePolygon(corners, *normal, scratch, triangles);
}

}  // namespace

std::vector<MeshTriangle> triangulateMesh(const MeshView& mesh) {
  validate(mesh);
  if (mesh.polygons.connectivitySize >= std::numeric_limits<std::uint32_t>::max()) {
    detail::fail("triangulateMesh", "got " + std::to_string(mesh.polygons.connectivitySize) +
                                        " corners; at most 2^32 − 2 are supported");
  }
  std::vector<MeshTriangle> result;
  detail::withTypedMesh(mesh, [&](auto points, auto polygons) {
    std::vector<glm::dvec3> corners;
    detail::TriangulationScratch scratch;
    std::vector<detail::LocalTriangle> local;
    for (std::size_t p = 0; p < mesh.polygons.count; ++p) {
      corners.clear();
      for (std::size_t k = 0; k < polygons.size(p); ++k)
        corners.push_back(points[polygons.pointId(p, k)]);
      triangulate(corners, scratch, local);
      const std::size_t begin = polygons.begin(p);
      for (const detail::LocalTriangle& t : local) {
        MeshTriangle triangle;
        triangle.polygon = static_cast<std::uint32_t>(p);
        for (int i = 0; i < 3; ++i) {
          triangle.corner[i] = static_cast<std::uint32_t>(begin + t[i]);
          triangle.point[i] = static_cast<std::uint32_t>(polygons.pointId(p, t[i]));
        }
        result.push_back(triangle);
      }
    }
  });
  return result;
}

}  // namespace facet
