/**
 * @class   vtkFacetPolyDataConverter
 * @brief   Private: the polygons and triangle strips of a vtkPolyData as Facet meshes.
 *
 * Polygons are read in place: the cell array's offsets and connectivity (32- or 64-bit) and
 * float or double points are handed to the core without a copy; other point types are
 * copied to double. Triangle strips are decoded into triangles with the alternating winding
 * VTK uses (vtkTriangleStrip::DecomposeStrip). The result is kept while the input's geometry
 * (the vtkPolyData itself, its points and cells: not its point and cell data) is unchanged,
 * so a new camera, new lights or new scalars re-render without converting, validating or
 * checking closedness again. Verts
 * and lines are not rendered: every Update counts them in a warning.
 *
 * Polygon ids in the Facet scene: the polygons of mesh 0 (the input's polys), then the
 * triangles of mesh 1 (its strips). CellIdOf maps them back to vtkPolyData cell ids
 * (verts, lines, polys, strips, as vtkPolyData::GetCell numbers them).
 */

#ifndef vtkFacetPolyDataConverter_h
#define vtkFacetPolyDataConverter_h

#include "vtkType.h"

#include "facet/Mesh.h"

#include <cstdint>
#include <vector>

class vtkFacetMessages;
class vtkPoints;
class vtkPolyData;

class vtkFacetPolyDataConverter
{
public:
  /**
   * Converts the input unless it is the one converted last and unchanged since. Returns
   * false, with an error in `messages`, for input the renderer cannot take (more than
   * 2^31 - 1 polygons or points); point ids are checked by the renderer.
   */
  bool Update(vtkPolyData* input, bool detectClosedSurfaces, vtkFacetMessages& messages);

  /// Whether the last Update converted (false: the cached conversion was reused).
  bool ConvertedLastUpdate() const { return this->Converted; }
  /// Whether the input changed at all since the Update before (converted, or only its
  /// attributes: scalars, normals).
  bool InputChangedLastUpdate() const { return this->InputChanged; }

  /// The meshes to render: polys first, strip triangles second; either may be empty. Their
  /// MeshView::version is the geometry's: the points' and polys' MTimes when read in place,
  /// the conversion's time for arrays copied here (strips, points of other types).
  const facet::MeshView& Polygons() const { return this->PolygonView; }
  const facet::MeshView& StripTriangles() const { return this->StripView; }

  /// The vtkPolyData cell id of a Facet polygon id; -1 for the background id (-1).
  vtkIdType CellIdOf(std::int32_t polygonId) const;
  /// CellIdOf for the ids in [begin, end) of an image's id plane; `stream`: stores around
  /// the caches, for a large plane (facet/IdPlane.h, vtkFacetImageRenderer::StreamsIdPlanes).
  void CellIdsOf(const std::int32_t* polygonIds,
    vtkIdType* cellIds,
    vtkIdType begin,
    vtkIdType end,
    bool stream) const;

  /// The strip (0-based, among the strips) that produced strip triangle `triangle`.
  vtkIdType StripOfTriangle(std::size_t triangle) const { return this->StripOf[triangle]; }

  vtkIdType GetNumberOfVerts() const { return this->NumberOfVerts; }
  vtkIdType GetNumberOfLines() const { return this->NumberOfLines; }
  vtkIdType GetNumberOfPolys() const { return this->NumberOfPolys; }
  vtkIdType GetNumberOfStrips() const { return this->NumberOfStrips; }

  /// Forgets the cached conversion (and every pointer into the last input).
  void Reset();

  /**
   * The bounds of the converted input's points whose coordinates are all finite (see
   * ComputeFiniteBounds), computed once per conversion.
   */
  const double* GetFiniteBounds();

  /**
   * Points as Facet reads them: float and double xyz in place, other types copied to double
   * into `copy`.
   */
  static facet::PointArray PointsOf(vtkPoints* points, std::vector<double>& copy);

  /**
   * (xmin, xmax, ymin, ymax, zmin, zmax) of the points whose three coordinates are finite:
   * vtkPolyData::GetBounds without the points the render skips with their cells;
   * uninitialized (vtkMath::AreBoundsInitialized is false) when there is none.
   */
  static void ComputeFiniteBounds(const facet::PointArray& points, double bounds[6]);

private:
  bool Convert(vtkPolyData* input, bool detectClosedSurfaces, vtkFacetMessages& messages);
  void ConvertPolys(vtkPolyData* input);
  void ConvertStrips(vtkPolyData* input);

  const vtkPolyData* Input = nullptr; // identity only, never dereferenced
  vtkMTimeType InputTime = 0;         // its whole MTime, attributes included
  vtkMTimeType GeometryTime = 0;      // what the conversion read (GeometryTimeOf)
  bool DetectedClosedSurfaces = false;
  bool Converted = false;
  bool InputChanged = false;

  vtkIdType NumberOfVerts = 0;
  vtkIdType NumberOfLines = 0;
  vtkIdType NumberOfPolys = 0;
  vtkIdType NumberOfStrips = 0;

  facet::PointArray Points;
  std::vector<double> PointCopy; // only for point types other than float and double
  double FiniteBounds[6] = { 0, 0, 0, 0, 0, 0 };
  bool FiniteBoundsComputed = false;
  facet::MeshView PolygonView;
  facet::MeshView StripView;
  std::vector<std::int64_t> StripOffsets;
  std::vector<std::int64_t> StripConnectivity;
  std::vector<vtkIdType> StripOf;
};

#endif
// VTK-HeaderTest-Exclude: vtkFacetPolyDataConverter.h
