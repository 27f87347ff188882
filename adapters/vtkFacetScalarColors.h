/**
 * @class   vtkFacetScalarColors
 * @brief   Private: per-polygon colors from a vtkPolyData's scalars, the way a vtkMapper
 *          colors by data.
 *
 * The settings are a vtkMapper's (Settings::Of), whether the mapper is an actor's or the
 * one holding vtkFacetRenderFilter's coloring. The scalars are found with
 * vtkAbstractMapper::GetScalars (scalar mode, array access mode, array name or id) and mapped
 * with vtkScalarsToColors::MapScalars (color mode, component), so colors are the exact bytes
 * VTK's own mappers use; unsigned char RGB(A) arrays are used directly under the default
 * color mode. The lookup table is prepared as vtkMapper::MapScalars prepares it: the array's
 * own table if it has one, else the mapper's; built (vtkScalarsToColors::Build, which leaves
 * alone a table whose values the user inserted); given the scalar range unless
 * UseLookupTableScalarRange. Cell scalars color each polygon (and every triangle of a strip);
 * point scalars are averaged per polygon, as flat shading shows one color per polygon
 * (VTK's OpenGL mapper interpolates them across the polygon even when flat shading), and
 * kept per point for the Gouraud and Phong modes, which interpolate them. With
 * InterpolateScalarsBeforeMapping on, where vtkMapper::CanUseTextureMapForColoring would
 * (point scalars mapped through a table that is not indexed, not direct colors), those modes
 * interpolate the scalars instead and map them per sample: the scalar texture is made as
 * vtkMapper::MapScalarsToTexture makes its color texture (the table's colors and the
 * below- and above-range colors in a row, the NaN color in a second; per point a texture
 * coordinate, on a log scale when the table has one), so the bytes are VTK's. The result is
 * kept while the input, the settings and the table are unchanged.
 */

#ifndef vtkFacetScalarColors_h
#define vtkFacetScalarColors_h

#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"
#include "vtkType.h"

#include "facet/Color.h"
#include "facet/Mesh.h"

#include <span>
#include <string>
#include <vector>

class vtkDataArray;
class vtkFacetMessages;
class vtkFacetPolyDataConverter;
class vtkMapper;
class vtkPolyData;
class vtkScalarsToColors;

class vtkFacetScalarColors
{
public:
  /// Everything vtkMapper consults to color by data.
  struct Settings
  {
    bool ScalarVisibility = true;
    int ScalarMode = 0;
    int ColorMode = 0;
    int ArrayAccessMode = 0;
    int ArrayId = -1;
    std::string ArrayName;
    int ArrayComponent = 0;
    vtkScalarsToColors* LookupTable = nullptr; // never null from Of
    double ScalarRange[2] = { 0.0, 1.0 };
    bool UseLookupTableScalarRange = false;
    /// Gouraud and Phong map the interpolated scalars per sample (ScalarTexture); flat
    /// shading shows one color per polygon either way.
    bool InterpolateScalarsBeforeMapping = false;

    /// The mapper's settings; creates its default lookup table if it has none, as
    /// vtkMapper::GetLookupTable does.
    static Settings Of(vtkMapper* mapper);
    bool operator==(const Settings& other) const = default;
  };

  /**
   * Recomputes the colors when the mesh was converted again or the settings or the table
   * changed. A color array that cannot be used is a warning in `messages`; the polygons
   * then take the property's color.
   */
  void Update(vtkPolyData* input,
    const vtkFacetPolyDataConverter& mesh,
    const Settings& settings,
    vtkFacetMessages& messages);

  /// One color per polygon and per strip triangle; empty without scalar coloring.
  std::span<const facet::Rgba8> PolygonColors() const { return this->Polygon; }
  std::span<const facet::Rgba8> StripColors() const { return this->Strip; }
  /// With point scalars, one color per point (mapped, then interpolated by the Gouraud and
  /// Phong modes: InterpolateScalarsBeforeMapping off); empty otherwise.
  std::span<const facet::Rgba8> PointColors() const { return this->Point; }
  /// With point scalars to map per sample (InterpolateScalarsBeforeMapping, see above), the
  /// texture of the Gouraud and Phong modes (facet::MeshView::scalarTexture); empty otherwise.
  facet::ColorTexture ScalarTexture() const
  {
    return { this->Coordinates, this->Texels, this->Texels.size() / 2 };
  }
  bool HasColors() const { return !this->Polygon.empty() || !this->Strip.empty(); }

  /// The colors' MeshView::colorVersion: when they were last computed, on VTK's clock (so
  /// never given twice).
  vtkMTimeType GetVersion() const { return this->Computed.GetMTime(); }

  /// The table the last Update prepared (null: none) and its MTime once prepared.
  vtkScalarsToColors* GetPreparedTable() const { return this->LastTable; }
  vtkMTimeType GetPreparedTableTime() const { return this->LastTableTime; }

private:
  static vtkScalarsToColors* PrepareLookupTable(vtkDataArray* scalars, const Settings& settings);
  void ComputeTexture(vtkDataArray* scalars, vtkScalarsToColors* table, int colorMode);
  std::string Compute(vtkDataArray* scalars,
    bool cellScalars,
    vtkScalarsToColors* table,
    vtkPolyData* input,
    const vtkFacetPolyDataConverter& mesh,
    const Settings& settings);

  // What the kept colors were computed from: the settings and the table as prepared.
  Settings Last;
  vtkScalarsToColors* LastTable = nullptr; // identity only
  vtkMTimeType LastTableTime = 0;
  bool Valid = false;
  vtkTimeStamp Computed;
  std::string Warning; // said again at every execution that keeps these colors
  std::vector<facet::Rgba8> Polygon;
  std::vector<facet::Rgba8> Strip;
  std::vector<facet::Rgba8> Point;
  std::vector<float> Coordinates;   // (s, t) per point
  std::vector<facet::Rgba8> Texels; // width × 2
};

#endif
