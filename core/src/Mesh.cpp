#include "facet/Mesh.h"

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "MeshAccess.h"
#include "Validate.h"
#include "facet/Error.h"

namespace facet {
namespace detail {
namespace {

std::string meshName(std::size_t meshIndex) {
  return meshIndex == SIZE_MAX ? "MeshView" : "Scene.meshes[" + std::to_string(meshIndex) + "]";
}

template <class Index>
std::optional<MeshProblem> findProblem(const Index* offsets, const Index* connectivity,
                                       std::size_t connectivitySize, std::size_t pointCount,
                                       std::size_t begin, std::size_t end) {
  using Kind = MeshProblem::Kind;
  for (std::size_t p = begin; p < end; ++p) {
    const std::int64_t first = offsets[p];
    const std::int64_t last = offsets[p + 1];
    if (last < first) return MeshProblem{Kind::DecreasingOffset, p, p + 1, last};
    if (static_cast<std::uint64_t>(last) > connectivitySize) {
      return MeshProblem{Kind::OffsetPastConnectivity, p, p + 1, last};
    }
    for (std::int64_t k = first; k < last; ++k) {
      const std::int64_t id = connectivity[k];
      if (id < 0 || static_cast<std::uint64_t>(id) >= pointCount) {
        return MeshProblem{Kind::PointIdOutOfRange, p, static_cast<std::size_t>(k), id};
      }
    }
  }
  return std::nullopt;
}

}  // namespace

void validateMeshHeader(const MeshView& mesh, std::size_t meshIndex) {
  const auto name = [&](const char* field) { return meshName(meshIndex) + field; };
  if (mesh.points.count > 0 && mesh.points.data == nullptr) {
    fail(name(".points.data"), "is null but points.count is " + std::to_string(mesh.points.count));
  }
  if (mesh.polygons.count == 0) return;
  if (mesh.polygons.offsets == nullptr) {
    fail(name(".polygons.offsets"),
         "is null but polygons.count is " + std::to_string(mesh.polygons.count));
  }
  if (mesh.polygons.connectivitySize > 0 && mesh.polygons.connectivity == nullptr) {
    fail(name(".polygons.connectivity"),
         "is null but connectivitySize is " + std::to_string(mesh.polygons.connectivitySize));
  }
  const std::int64_t firstOffset = mesh.polygons.type == PolygonArray::Type::Int32
                                       ? static_cast<const std::int32_t*>(mesh.polygons.offsets)[0]
                                       : static_cast<const std::int64_t*>(mesh.polygons.offsets)[0];
  if (firstOffset != 0) {
    fail(name(".polygons.offsets[0]"), "is " + std::to_string(firstOffset) + ", must be 0");
  }
  if (!mesh.polygonColors.empty() && mesh.polygonColors.size() != mesh.polygons.count) {
    fail(name(".polygonColors"), "has " + std::to_string(mesh.polygonColors.size()) +
                                     " entries for " + std::to_string(mesh.polygons.count) +
                                     " polygons");
  }
}

std::optional<MeshProblem> findMeshProblem(const MeshView& mesh, std::size_t begin,
                                           std::size_t end) {
  const PolygonArray& p = mesh.polygons;
  if (p.type == PolygonArray::Type::Int32) {
    return findProblem(static_cast<const std::int32_t*>(p.offsets),
                       static_cast<const std::int32_t*>(p.connectivity), p.connectivitySize,
                       mesh.points.count, begin, end);
  }
  return findProblem(static_cast<const std::int64_t*>(p.offsets),
                     static_cast<const std::int64_t*>(p.connectivity), p.connectivitySize,
                     mesh.points.count, begin, end);
}

void throwMeshProblem(const MeshProblem& problem, std::size_t meshIndex) {
  const std::string name = meshName(meshIndex);
  const std::string value = std::to_string(problem.value);
  const std::string polygon = " (polygon " + std::to_string(problem.polygon) + ")";
  switch (problem.kind) {
    case MeshProblem::Kind::DecreasingOffset:
      fail(name + ".polygons.offsets[" + std::to_string(problem.position) + "]",
           "is " + value + ", less than the offset before it" + polygon);
    case MeshProblem::Kind::OffsetPastConnectivity:
      fail(name + ".polygons.offsets[" + std::to_string(problem.position) + "]",
           "is " + value + ", past the end of the connectivity" + polygon);
    case MeshProblem::Kind::PointIdOutOfRange:
      fail(name + ".polygons.connectivity[" + std::to_string(problem.position) + "]",
           "is " + value + ", outside [0, points.count)" + polygon);
  }
  throw Error(name + ": invalid mesh");
}

}  // namespace detail

void validate(const MeshView& mesh) {
  detail::validateMeshHeader(mesh, SIZE_MAX);
  if (const auto problem = detail::findMeshProblem(mesh, 0, mesh.polygons.count)) {
    detail::throwMeshProblem(*problem, SIZE_MAX);
  }
}

namespace {

void requireCount(std::size_t count, std::size_t points, const char* name) {
  if (count != 0 && count != points) {
    detail::fail(name, "has " + std::to_string(count) + " entries for " + std::to_string(points) +
                           " points; give one per point or none");
  }
}

void requireTexture(const ColorTexture& texture, std::size_t points) {
  if (texture.empty()) return;
  requireCount(texture.coordinates.size() / 2, points, "MeshView.scalarTexture.coordinates");
  if (texture.coordinates.size() % 2 != 0 || texture.width == 0 ||
      texture.texels.size() != 2 * texture.width) {
    detail::fail("MeshView.scalarTexture",
                 "has " + std::to_string(texture.coordinates.size()) + " coordinates and " +
                     std::to_string(texture.texels.size()) + " texels for width " +
                     std::to_string(texture.width) +
                     "; give (s, t) per point and width × 2 texels");
  }
}

}  // namespace

void validatePointData(const MeshView& mesh) {
  validate(mesh);
  requireCount(mesh.pointNormals.count, mesh.points.count, "MeshView.pointNormals");
  requireCount(mesh.pointColors.size(), mesh.points.count, "MeshView.pointColors");
  requireTexture(mesh.scalarTexture, mesh.points.count);
}

std::optional<Color> pointColorAt(const MeshView& mesh, const std::array<std::uint32_t, 3>& corners,
                                  const glm::dvec3& w) {
  if (!mesh.scalarTexture.empty()) {
    const std::span<const float> st = mesh.scalarTexture.coordinates;
    glm::dvec2 sum(0.0);
    for (int k = 0; k < 3; ++k)
      sum += w[k] * glm::dvec2(st[2 * corners[k]], st[2 * corners[k] + 1]);
    const Rgba8 c = mesh.scalarTexture.lookup(sum.x, sum.y);
    return Color(c.r, c.g, c.b) / 255.0f;
  }
  if (mesh.pointColors.empty()) return std::nullopt;
  glm::dvec3 sum(0.0);
  for (int k = 0; k < 3; ++k) {
    const Rgba8 c = mesh.pointColors[corners[k]];
    sum += w[k] * glm::dvec3(Color(c.r, c.g, c.b) / 255.0f);
  }
  return Color(sum);
}

namespace {

// The half-edges of a mesh grouped by the point they leave (a counting sort by point id: two
// linear passes, 4 bytes per half-edge with 32-bit offsets), each group then sorted by the
// point it reaches. It replaced a radix sort of 64-bit edge keys (four passes over 16 bytes
// per half-edge): 2-3x faster at 0.5M-8M triangles (bench/closed_surface.md). Offsets are
// 32-bit where they fit: 64-bit ones throughout took 10-35 % more CPU time at 2M-8M
// triangles (the same file; the counting pass increments first[] at random, and a smaller
// array stays more in cache).
template <class Offset>
struct HalfEdges {
  std::vector<Offset> first;      // first[a] .. first[a + 1]: the half-edges leaving point a
  std::vector<std::uint32_t> to;  // the point each reaches (point ids are < 2^31 here)
  std::span<const std::uint32_t> leaving(std::size_t a) const {
    return {to.data() + first[a], to.data() + first[a + 1]};
  }
};

// Every polygon's half-edges (k -> k + 1), or nothing if a polygon has fewer than 3 points.
template <class Offset, class Polys>
std::optional<HalfEdges<Offset>> halfEdgesOf(const MeshView& mesh, const Polys& polygons) {
  HalfEdges<Offset> edges;
  // Counted at from + 2, summed, then filled through first[from + 1]: afterwards first[a] is
  // where a's half-edges start and first[a + 1] where they end.
  edges.first.assign(mesh.points.count + 2, 0);
  for (std::size_t p = 0; p < mesh.polygons.count; ++p) {
    if (polygons.size(p) < 3) return std::nullopt;
  }
  for (std::size_t p = 0; p < mesh.polygons.count; ++p) {
    for (std::size_t k = polygons.begin(p), end = polygons.begin(p + 1); k < end; ++k)
      ++edges.first[static_cast<std::size_t>(polygons.connectivity[k]) + 2];
  }
  for (std::size_t a = 2; a < edges.first.size(); ++a)
    edges.first[a] += edges.first[a - 1];
  edges.to.resize(mesh.polygons.connectivitySize);
  for (std::size_t p = 0; p < mesh.polygons.count; ++p) {
    const std::size_t begin = polygons.begin(p), end = polygons.begin(p + 1);
    for (std::size_t k = begin; k < end; ++k) {
      const auto from = static_cast<std::size_t>(polygons.connectivity[k]);
      const auto to = polygons.connectivity[k + 1 < end ? k + 1 : begin];
      edges.to[edges.first[from + 1]++] = static_cast<std::uint32_t>(to);
    }
  }
  return edges;
}

// Closed and consistently oriented: every half-edge a -> b is the only one from a to b, is no
// loop (a != b), and its twin b -> a exists. Then every edge has exactly two faces, which
// traverse it in opposite directions.
template <class Offset>
bool pairsUp(HalfEdges<Offset>& edges, std::size_t pointCount) {
  for (std::size_t a = 0; a < pointCount; ++a) {
    const auto begin = edges.to.begin() + edges.first[a],
               end = edges.to.begin() + edges.first[a + 1];
    std::sort(begin, end);
    if (std::adjacent_find(begin, end) != end) return false;
  }
  for (std::size_t a = 0; a < pointCount; ++a) {
    for (const std::uint32_t b : edges.leaving(a)) {
      const std::span<const std::uint32_t> back = edges.leaving(b);
      if (b == a || !std::binary_search(back.begin(), back.end(), static_cast<std::uint32_t>(a)))
        return false;
    }
  }
  return true;
}

}  // namespace

bool isClosedSurface(const MeshView& mesh) {
  validate(mesh);
  if (mesh.polygons.count == 0 || mesh.points.count >= (std::size_t{1} << 31)) return false;
  return detail::withTypedMesh(mesh, [&](auto points, auto polygons) {
    const auto closedAndOriented = [&](auto offset) {
      auto edges = halfEdgesOf<decltype(offset)>(mesh, polygons);
      return edges && pairsUp(*edges, mesh.points.count);
    };
    const bool paired = mesh.polygons.connectivitySize < (std::size_t{1} << 32)
                            ? closedAndOriented(std::uint32_t{})
                            : closedAndOriented(std::uint64_t{});
    if (!paired) return false;
    // Oriented outward: a positive enclosed volume (six times the signed volume, by the
    // divergence theorem, about the points' mean to keep the sum well conditioned).
    glm::dvec3 center(0.0);
    for (std::size_t i = 0; i < mesh.points.count; ++i)
      center += points[i];
    center /= static_cast<double>(mesh.points.count);
    double volume = 0.0;
    for (std::size_t p = 0; p < mesh.polygons.count; ++p) {
      const glm::dvec3 a = points[polygons.pointId(p, 0)] - center;
      for (std::size_t k = 1; k + 1 < polygons.size(p); ++k) {
        volume += glm::dot(a, glm::cross(points[polygons.pointId(p, k)] - center,
                                         points[polygons.pointId(p, k + 1)] - center));
      }
    }
    return volume > 0.0;
  });
}

}  // namespace facet
