#pragma once

/// @file Mesh.h
/// Polygon meshes as the renderer reads them: non-owning views over arrays laid out the way
/// VTK stores them (xyz-interleaved float or double points; a cell array's offsets and
/// connectivity in 32- or 64-bit integers), so an adapter can hand its arrays over without
/// copying. `Mesh` is a small owning mesh for callers that build geometry themselves.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
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

/// Point scalars mapped per sample through a color table, as VTK's OpenGL mapper does with
/// vtkMapper's InterpolateScalarsBeforeMapping on (vtkMapper::MapScalarsToTexture): each
/// point has a texture coordinate (s, t), the Gouraud and Phong modes interpolate it across
/// the polygon, and each sample takes the texel nearest the interpolated coordinate, edges
/// clamped (OpenGL's GL_NEAREST and GL_CLAMP_TO_EDGE, VTK's color texture defaults). So a
/// polygon whose scalars span several table entries shows each entry's color in bands, where
/// interpolating mapped colors would blend the corner colors.
struct ColorTexture {
  /// Two per point, (s, t): s runs along the table (0 to 1 over its width), t picks the row.
  std::span<const float> coordinates{};
  /// `width` × 2 texels, row 0 first: VTK puts the table's colors in row 0 (with the below-
  /// and above-range colors at its ends) and the NaN color all along row 1, and gives
  /// points t = 0.49 (a number) or 1 (NaN), so NaN spreads almost up to its neighbours.
  std::span<const Rgba8> texels{};
  std::size_t width = 0;

  bool empty() const { return coordinates.empty(); }
  /// The texel nearest (s, t) with the edges clamped; NaN counts as 0.
  Rgba8 lookup(double s, double t) const { return texels[row(t) * width + column(s)]; }
  /// The column of s and the row of t: texel i covers [i, i + 1) / size, edges clamped.
  std::size_t column(double s) const { return nearest(s, width); }
  static std::size_t row(double t) { return nearest(t, 2); }

 private:
  static std::size_t nearest(double u, std::size_t size) {
    const double scaled = u * static_cast<double>(size);
    return scaled > 0.0 ? std::min(static_cast<std::size_t>(std::min(scaled, 1e18)), size - 1)
                        : std::size_t{0};
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
  /// Optional point scalars to map per sample (vtkMapper's InterpolateScalarsBeforeMapping
  /// on): the Gouraud and Phong modes interpolate them and look the color up in the table;
  /// they win over pointColors there. The flat Renderer ignores them. (default: empty)
  ColorTexture scalarTexture{};
};

/// validate(mesh), and the arrays per point: pointNormals, pointColors and the
/// scalarTexture's coordinates hold one entry per point or none, and a scalarTexture has
/// width × 2 texels (throws facet::Error naming the array).
void validatePointData(const MeshView& mesh);

/// The color the Gouraud and Phong modes (and the mesh reference) give a point of a triangle
/// whose corners are the mesh's points `corners`, at weights `w` (barycentric, summing to 1):
/// the scalars interpolated and looked up when the mesh has a scalarTexture, else the
/// pointColors interpolated; empty when it has neither (the polygon's color then holds).
/// The mesh must have passed validatePointData.
std::optional<Color> pointColorAt(const MeshView& mesh, const std::array<std::uint32_t, 3>& corners,
                                  const glm::dvec3& w);

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
/// facet::Error). Linear in the number of edges (with a sort of each point's few edges) and
/// 4 bytes per edge: for once per mesh, not per frame.
bool isClosedSurface(const MeshView& mesh);

}  // namespace facet
