#pragma once

// Typed access to a MeshView's arrays. Hot loops are instantiated per (point type, index
// type) once per mesh, so no per-vertex type dispatch happens (llvmpipe's habit: pick the
// routine once).

#include <cstddef>
#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

#include "facet/Mesh.h"

namespace facet::detail {

template <class Scalar>
struct Points {
  const Scalar* xyz;
  glm::dvec3 operator[](std::size_t i) const {
    return {static_cast<double>(xyz[3 * i]), static_cast<double>(xyz[3 * i + 1]),
            static_cast<double>(xyz[3 * i + 2])};
  }
};

template <class Index>
struct Polygons {
  using IndexType = Index;
  const Index* offsets;
  const Index* connectivity;
  std::size_t begin(std::size_t polygon) const {
    return static_cast<std::size_t>(offsets[polygon]);
  }
  std::size_t size(std::size_t polygon) const {
    return static_cast<std::size_t>(offsets[polygon + 1] - offsets[polygon]);
  }
  std::size_t pointId(std::size_t polygon, std::size_t corner) const {
    return static_cast<std::size_t>(connectivity[offsets[polygon] + corner]);
  }
};

// Polygons known to be triangles stored in order (offsets[p] = 3p, MeshFacts::allTriangles):
// the same answers as Polygons without reading the offsets.
template <class Index>
struct Triangles {
  const Index* connectivity;
  std::size_t begin(std::size_t polygon) const { return 3 * polygon; }
  static constexpr std::size_t size(std::size_t) { return 3; }
  std::size_t pointId(std::size_t polygon, std::size_t corner) const {
    return static_cast<std::size_t>(connectivity[3 * polygon + corner]);
  }
};

template <class Index>
Triangles<Index> asTriangles(Polygons<Index> polygons) {
  return {polygons.connectivity};
}

// Calls f(Points<float|double>, Polygons<int32|int64>) with the mesh's actual types.
template <class F>
decltype(auto) withTypedMesh(const MeshView& mesh, F&& f) {
  auto withPolygons = [&](auto points) -> decltype(auto) {
    if (mesh.polygons.type == PolygonArray::Type::Int32) {
      return f(points, Polygons<std::int32_t>{
                           static_cast<const std::int32_t*>(mesh.polygons.offsets),
                           static_cast<const std::int32_t*>(mesh.polygons.connectivity)});
    }
    return f(points,
             Polygons<std::int64_t>{static_cast<const std::int64_t*>(mesh.polygons.offsets),
                                    static_cast<const std::int64_t*>(mesh.polygons.connectivity)});
  };
  if (mesh.points.type == PointArray::Type::Float32) {
    return withPolygons(Points<float>{static_cast<const float*>(mesh.points.data)});
  }
  return withPolygons(Points<double>{static_cast<const double*>(mesh.points.data)});
}

// The first structural problem in polygons [begin, end), if any. Built without allocating;
// formatted (allocating) only when thrown.
struct MeshProblem {
  enum class Kind { DecreasingOffset, OffsetPastConnectivity, PointIdOutOfRange };
  Kind kind;
  std::size_t polygon;
  std::size_t position;  // index into offsets or connectivity
  std::int64_t value;
};

// Checks the arrays' sizes and the first offset (O(1)); throws facet::Error.
void validateMeshHeader(const MeshView& mesh, std::size_t meshIndex);
// Checks offsets and point ids of polygons [begin, end); never throws.
std::optional<MeshProblem> findMeshProblem(const MeshView& mesh, std::size_t begin,
                                           std::size_t end);
[[noreturn]] void throwMeshProblem(const MeshProblem& problem, std::size_t meshIndex);

}  // namespace facet::detail
