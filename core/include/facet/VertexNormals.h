#pragma once

/// @file VertexNormals.h
/// Normals at polygon corners, for shading that interpolates across a polygon (Gouraud,
/// Phong) and for the mesh reference (MeshReference.h).
///
/// computeVertexNormals means what vtkPolyDataNormals (VTK 9.1) means with Splitting on:
/// - every polygon has a unit normal, Newell's (PolygonNormal.h), as vtkPolygon's;
/// - at each point, the polygons around it fall into groups: two polygons sharing an edge
///   through the point are in one group when their normals differ by less than the feature
///   angle (strictly: cos angle > cos featureAngle) — an edge bent further is sharp, and
///   shading keeps it as a crease. An edge used by more than two polygons (non-manifold) is
///   sharp too, as in vtkPolyDataNormals;
/// - a group's normal is the normalized sum of its polygons' unit normals (unweighted, as
///   vtkPolyDataNormals sums them).
///
/// Orientation is not assumed consistent. Two polygons sharing an edge are wound
/// consistently when they run along it in opposite directions; when they run the same way,
/// one of them is flipped, and its normal is compared and summed reversed. Each corner's
/// normal is then given in its own polygon's orientation (it points to the side that
/// polygon's counter-clockwise winding faces), so a renderer that turns back faces' normals
/// toward the viewer lights a flipped polygon like its neighbours. vtkPolyDataNormals with
/// Consistency on reaches the same groups by reordering the flipped polygons in its output
/// (its normal at a reordered polygon's corner is then ours reversed, as that polygon's
/// winding is); with Consistency off it splits every edge between polygons of opposite
/// winding. On consistently oriented meshes all three agree (tested against VTK).
/// Around one point the relative orientations must agree (a disk around a point always
/// does); an edge whose orientation contradicts the group's is treated as sharp.
///
/// Degenerate polygons (no Newell normal: zero area or non-finite points) join no group, as
/// in VTK up to a feature angle of 90° (their zero normal fails the test), and their corners
/// get the zero vector: they have no area to shade. No NaN ever comes out.
///
/// Not VTK's: vtkPolyData::GetCellEdgeNeighbors also calls a polygon of four or more corners
/// a neighbour across the line between two of its non-adjacent corners; only real edges
/// count here.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Mesh.h"
#include "facet/ParallelFor.h"

namespace facet {

/// Corner normals, shaped for a rasterizer: polygon i's corner k has the normal
/// normals[cornerNormal[offsets[i] + k]] (indexed like the connectivity array). Corners
/// that share a point and a smooth group share one entry, so lighting per entry is lighting
/// per vertex (Gouraud), and every entry belongs to one point (`point`).
struct VertexNormals {
  std::vector<glm::dvec3> normals;          ///< unit, or zero for degenerate polygons
  std::vector<std::uint32_t> cornerNormal;  ///< one per corner: an index into `normals`
  std::vector<std::uint32_t> point;         ///< per entry of `normals`: its point id

  std::size_t splitPoints = 0;         ///< points that got more than one normal
  std::size_t inconsistentEdges = 0;   ///< edges whose two polygons run the same way
  std::size_t degeneratePolygons = 0;  ///< polygons without a normal
  std::size_t replacedNormals = 0;     ///< input normals replaced (see fromPointNormals)
};

struct VertexNormalOptions {
  /// Edges between polygons whose normals differ by at least this angle, in degrees, in
  /// [0, 180], stay sharp (vtkPolyDataNormals::FeatureAngle). 180 keeps every manifold
  /// edge smooth. (default: 30)
  double featureAngleDegrees = 30.0;
};

/// Corner normals computed from the geometry, as described above, in blocks of polygons and
/// of points through `parallel` (the same result for any threads: each block numbers its
/// normals, and the blocks are joined in point order). Validates the mesh (throws
/// facet::Error naming the problem, or a feature angle outside [0, 180], or a mesh of 2^32 or
/// more corners). O(corners · valence).
VertexNormals computeVertexNormals(const MeshView& mesh, const VertexNormalOptions& options = {},
                                   const ParallelFor& parallel = {});

/// Corner normals from the mesh's own point normals (one xyz per point, float or double,
/// as vtkPointData::GetNormals stores them), used as given apart from normalizing: the
/// input's meaning wins, as in VTK's mappers. A point normal that is zero or not finite is
/// replaced, at each corner using that point, by its polygon's Newell normal (zero for a
/// degenerate polygon) and counted in replacedNormals. Throws facet::Error for an invalid
/// mesh or a normal count other than the point count.
VertexNormals fromPointNormals(const MeshView& mesh, const PointArray& pointNormals);

}  // namespace facet
