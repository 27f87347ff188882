/**
 * @class   vtkFacetActorConverter
 * @brief   Private: what one actor contributes to a Facet scene: its polygons in world
 *          coordinates, colored as its mapper colors them, with its property's material.
 *
 * Both front ends use it: vtkFacetRenderFilter for its input (its own coloring, property,
 * no transform), vtkFacetRendererToImageFilter for every actor of a vtkRenderer. The data
 * is a vtkPolyData or a composite dataset of them (a composite mapper's input); each
 * polydata is a part, converted by vtkFacetPolyDataConverter, moved to world coordinates by
 * vtkFacetActorTransform and colored by vtkFacetScalarColors, and each step is kept while
 * what it depends on is unchanged. A part gives the scene up to two meshes, its polys and
 * its strip triangles, with one material (vtkFacetPropertyConverter) and, when its polydata
 * has point normals, those in world coordinates for the shading modes.
 *
 * Polygon ids count through the parts in order, from 0 for the actor's first polygon (the
 * scene numbers them from the actor's first mesh on); CellIdOf maps one back to the cell
 * of its part's vtkPolyData (verts, lines, polys, strips numbering).
 */

#ifndef vtkFacetActorConverter_h
#define vtkFacetActorConverter_h

#include "vtkFacetActorTransform.h"
#include "vtkFacetPolyDataConverter.h"
#include "vtkFacetScalarColors.h"
#include "vtkFacetSceneConverter.h"
#include "vtkTimeStamp.h"

#include "facet/Scene.h"

#include <cstdint>
#include <memory>
#include <vector>

class vtkDataArray;
class vtkDataObject;
class vtkFacetMessages;
class vtkMatrix4x4;
class vtkProperty;

class vtkFacetActorConverter
{
public:
  /// What an actor is made of.
  struct Actor
  {
    vtkDataObject* Data = nullptr; ///< a vtkPolyData, or a composite dataset of them
    vtkFacetScalarColors::Settings Coloring;
    vtkProperty* Property = nullptr;
    vtkMatrix4x4* Matrix = nullptr; ///< model to world; null: the identity
    /// What lights the scene (vtkFacetSceneConverter::LightingOf): without a light VTK
    /// shows every surface unlit, as with the property's Lighting off.
    vtkFacetSceneConverter::Lighting Lighting = vtkFacetSceneConverter::Lighting::Lights;
  };

  /**
   * Converts what changed since the last Update. Problems go to `messages`; returns false
   * when one is an error (the actor cannot be rendered).
   */
  bool Update(const Actor& actor, bool detectClosedSurfaces, vtkFacetMessages& messages);

  /// Appends the actor's meshes to the scene, in polygon id order.
  void AddTo(facet::Scene& scene) const;

  /// The polygons the actor adds to a scene (polys and strip triangles of all its parts).
  std::int64_t GetNumberOfPolygons() const { return this->NumberOfPolygons; }

  /// The cell of the actor's polygon `polygon` (0 = its first) in its part's vtkPolyData.
  vtkIdType CellIdOf(std::int64_t polygon) const;
  /// CellIdOf for the ids in [begin, end) of an id plane of the actor alone (-1: -1);
  /// `stream` as vtkFacetPolyDataConverter::CellIdsOf.
  void CellIdsOf(const std::int32_t* polygonIds,
    vtkIdType* cellIds,
    vtkIdType begin,
    vtkIdType end,
    bool stream) const;

  /// How many parts the last Update converted (0: every conversion was kept).
  int GetNumberOfConversions() const;

  /// The bounds of the actor's world points with finite coordinates (see
  /// vtkFacetPolyDataConverter::ComputeFiniteBounds); uninitialized when there is none.
  void GetFiniteBounds(double bounds[6]);

  /**
   * The MTime `table` had when the last Update prepared it for coloring (0: it did not),
   * so that an algorithm can tell its own preparation (build, range) from a user's change.
   */
  vtkMTimeType GetPreparedTableTime(vtkScalarsToColors* table) const;

private:
  struct Part
  {
    vtkFacetPolyDataConverter Geometry;
    vtkFacetActorTransform Transform;
    vtkFacetScalarColors Colors;
    facet::SceneMesh Polys;  // world points, colors and material, ready to render
    facet::SceneMesh Strips; // the strip triangles, likewise
    std::int64_t FirstPolygon = 0;
    std::vector<double> Normals;     // world point normals, for a matrix other than the identity
    vtkMTimeType NormalsVersion = 0; // the version Normals were made for
    // The data's point normals as last seen (identity only, and MTime), and when they last
    // changed: an attribute, so no new conversion, yet the meshes' vertex normals.
    vtkDataArray* NormalsSource = nullptr;
    vtkMTimeType NormalsSourceTime = 0;
    vtkTimeStamp NormalsChanged;

    // The MeshView::version of the part's meshes for geometry of version `geometry`: the
    // world points' (vtkFacetActorTransform::Version), or later when the point normals
    // changed since (what is kept per version then follows them: the quality modes' vertex
    // normals, the estimate's normal spreads, Normals here).
    vtkMTimeType VersionOf(vtkMTimeType geometry, vtkPolyData* data);
    // The data's point normals (3 components, one per point) in world coordinates, for the
    // shading modes (MeshView::pointNormals), kept while `version` is; none without them.
    facet::PointArray WorldNormals(vtkPolyData* data, vtkMatrix4x4* matrix, vtkMTimeType version);
  };
  bool UpdatePart(Part& part,
    vtkPolyData* data,
    const Actor& actor,
    bool detectClosedSurfaces,
    vtkFacetMessages& messages);
  std::size_t PartOf(std::int64_t polygon) const;

  std::vector<std::unique_ptr<Part>> Parts;
  std::int64_t NumberOfPolygons = 0;
};

#endif
