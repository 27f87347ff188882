/**
 * @class   vtkFacetScalarColors
 * @brief   Private: per-polygon colors from a vtkPolyData's scalars, the way vtkMapper
 *          colors by data.
 *
 * The scalars are found with vtkAbstractMapper::GetScalars (scalar mode, array access mode,
 * array name or id) and mapped with vtkScalarsToColors::MapScalars (color mode, component),
 * so colors are the exact bytes VTK's own mappers use; unsigned char RGB(A) arrays are used
 * directly under the default color mode. The lookup table is prepared as
 * vtkMapper::MapScalars prepares it: the array's own table if it has one, else the given one
 * or a default vtkLookupTable; built (vtkScalarsToColors::Build, which leaves alone a table
 * whose values the user inserted); given the scalar range unless UseLookupTableScalarRange.
 * Cell scalars color each polygon (and every triangle of a strip); point scalars are averaged
 * per polygon, as flat shading shows one color per polygon. The result is kept while the
 * input, the settings and the table are unchanged.
 */

#ifndef vtkFacetScalarColors_h
#define vtkFacetScalarColors_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "facet/Color.h"

#include <span>
#include <string>
#include <vector>

class vtkDataArray;
class vtkFacetPolyDataConverter;
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
    vtkScalarsToColors* LookupTable = nullptr; // null: a default vtkLookupTable
    double ScalarRange[2] = { 0.0, 1.0 };
    bool UseLookupTableScalarRange = false;
    bool operator==(const Settings& other) const;
  };

  /**
   * Recomputes the colors when the mesh was converted again or the settings changed.
   * Returns a warning for the caller to report (empty if none).
   */
  std::string Update(vtkPolyData* input,
    const vtkFacetPolyDataConverter& mesh,
    bool meshConverted,
    const Settings& settings);

  /// One color per polygon and per strip triangle; empty without scalar coloring.
  std::span<const facet::Rgba8> PolygonColors() const { return this->Polygon; }
  std::span<const facet::Rgba8> StripColors() const { return this->Strip; }

  /// The lookup table used when Settings::LookupTable is null, as vtkMapper creates one.
  vtkScalarsToColors* GetDefaultLookupTable();

private:
  vtkScalarsToColors* PrepareLookupTable(vtkDataArray* scalars, const Settings& settings);
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
  std::vector<facet::Rgba8> Polygon;
  std::vector<facet::Rgba8> Strip;
  vtkSmartPointer<vtkScalarsToColors> DefaultLookupTable;
};

#endif
// VTK-HeaderTest-Exclude: vtkFacetScalarColors.h
