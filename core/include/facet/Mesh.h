#pragma once

/// @file Mesh.h
/// Polygon meshes as the renderer reads them: non-owning views over arrays laid out the way
/// VTK stores them (xyz-interleaved float or double points; a cell array's offsets and
/// connectivity in 32- or 64-bit integers), so an adapter can hand its arrays over without
/// copying. `Mesh` is a small owning mesh for callers that build geometry themselves.

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Color.h"

namespace facet {

/// Points: `count` xyz triples, interleaved, in float or double.
struct PointArray {
  enum class Type { Float32, Float64 };
  const void* data = nullptr;
  Type type = Type::Float64;
  std::size_t count = 0;

  static PointArray of(std::span<const glm::dvec3> points) {
    return {points.data(), Type::Float64, points.size()};
  }
  static PointArray of(std::span<const glm::vec3> points) {
    return {points.data(), Type::Float32, points.size()};
  }
  /// From a flat xyz array (length a multiple of 3), as vtkPoints stores it.
  static PointArray ofXyz(std::span<const float> xyz) {
    return {xyz.data(), Type::Float32, xyz.size() / 3};
  }
  static PointArray ofXyz(std::span<const double> xyz) {
    return {xyz.data(), Type::Float64, xyz.size() / 3};
  }
};

/// Polygons as vtkCellArray stores them: polygon i uses
/// connectivity[offsets[i] .. offsets[i+1]), so `offsets` has `count + 1` entries starting
/// at 0. Any vertex count ≥ 3; convex or concave; possibly slightly non-planar.
struct PolygonArray {
  enum class Type { Int32, Int64 };
  const void* offsets = nullptr;
  const void* connectivity = nullptr;
  Type type = Type::Int64;
  std::size_t count = 0;             ///< number of polygons
  std::size_t connectivitySize = 0;  ///< number of entries in `connectivity`

  static PolygonArray of(std::span<const std::int64_t> offsets,
                         std::span<const std::int64_t> connectivity) {
    return {offsets.data(), connectivity.data(), Type::Int64,
            offsets.empty() ? 0 : offsets.size() - 1, connectivity.size()};
  }
  static PolygonArray of(std::span<const std::int32_t> offsets,
                         std::span<const std::int32_t> connectivity) {
    return {offsets.data(), connectivity.data(), Type::Int32,
            offsets.empty() ? 0 : offsets.size() - 1, connectivity.size()};
  }
};

/// A mesh to render: points, polygons, and optionally one color per polygon (which replaces
/// the material color; alpha is ignored for now, everything renders opaque).
struct MeshView {
  PointArray points;
  PolygonArray polygons;
  std::span<const Rgba8> polygonColors{};  ///< empty, or one per polygon
  /// The polygons form closed surfaces wound counter-clockwise seen from outside, as
  /// isClosedSurface() decides (compute it once per mesh, not per frame). Seen from outside,
  /// such a surface shows only front faces, so while the whole mesh is in front of the near
  /// plane the renderer skips its back faces: same image, about half the work.
  /// Setting it on a mesh that is not closed loses the back faces. (default: false)
  bool closedSurface = false;
  /// Which version of the point and polygon arrays this view shows. 0: unversioned, the
  /// renderer reads and checks them anew every render. Any other value is a promise: while
  /// the arrays' addresses, types, counts and this number stay the same, so do their
  /// contents — bump it after editing points or polygons in place. The renderer then checks
  /// a mesh once per version (validation, bounding boxes), leaves out blocks of it outside
  /// the view, and re-renders a frame whose lights, materials or colors alone changed by
  /// re-shading the previous one (Renderer::render, "Incremental rendering"). Breaking the
  /// promise (editing in place without a new version) gives a stale image, or reads out of
  /// bounds when ids were changed. (default: 0)
  std::uint64_t version = 0;
  /// The same promise for polygonColors: bump it after editing colors in place. A new
  /// version of the colors alone re-shades; 0 treats non-empty colors as changed in every
  /// render. (default: 0)
  std::uint64_t colorVersion = 0;
  /// Optional normals at the points (one xyz per point, as vtkPointData::GetNormals stores
  /// them), for shading that interpolates across polygons (QualityRenderer.h): used as given
  /// instead of computed ones (VertexNormals.h). The flat Renderer ignores them.
  /// (default: none, count 0)
  PointArray pointNormals{nullptr, PointArray::Type::Float64, 0};
  /// Optional colors at the points, already mapped (vtkMapper's default,
  /// InterpolateScalarsBeforeMapping off), interpolated across polygons by the Gouraud and
  /// Phong modes (QualityRenderer.h); they win over polygonColors there. Alpha is ignored.
  /// The flat Renderer ignores them (give it polygonColors). (default: empty)
  std::span<const Rgba8> pointColors{};
};

/// An owning mesh with 64-bit indices, for building geometry by hand (examples, tests).
struct Mesh {
  std::vector<glm::dvec3> points;
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int64_t> connectivity;
  std::vector<Rgba8> polygonColors;  ///< empty, or one per polygon

  /// Appends a point and returns its index.
  std::int64_t addPoint(const glm::dvec3& p) {
    points.push_back(p);
    return static_cast<std::int64_t>(points.size()) - 1;
  }
  /// Appends a polygon from point indices.
  void addPolygon(std::initializer_list<std::int64_t> pointIds) {
    connectivity.insert(connectivity.end(), pointIds);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  void addPolygon(std::span<const std::int64_t> pointIds) {
    connectivity.insert(connectivity.end(), pointIds.begin(), pointIds.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  std::size_t polygonCount() const { return offsets.size() - 1; }

  MeshView view() const {
    MeshView view;
    view.points = PointArray::of(points);
    view.polygons = PolygonArray::of(offsets, connectivity);
    view.polygonColors = polygonColors;
    return view;
  }
};

/// Checks the structure of a mesh view and throws facet::Error naming the first problem:
/// null arrays with a non-zero count, offsets not starting at 0, decreasing or running past
/// the connectivity, a point id outside [0, points.count), or a color count that does not
/// match the polygon count. Reads every offset and id once. Non-finite point coordinates are
/// not an error: the polygons that use them are skipped and counted when rendering.
void validate(const MeshView& mesh);

/// True when every edge of the mesh is used exactly once in each direction (a closed,
/// consistently oriented surface, possibly several) and the enclosed signed volume is
/// positive (counter-clockwise seen from outside). Validates the mesh first (throws
/// facet::Error). O(E log E) in the number of edges: for once per mesh, not per frame.
bool isClosedSurface(const MeshView& mesh);

}  // namespace facet
