#include "vtkFacetScalarColors.h"

#include "vtkAbstractMapper.h"
#include "vtkDataArray.h"
#include "vtkFacetMessages.h"
#include "vtkFacetPolyDataConverter.h"
#include "vtkLookupTable.h"
#include "vtkMapper.h"
#include "vtkPolyData.h"
#include "vtkScalarsToColors.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>

namespace {
facet::Rgba8 ColorAt(const unsigned char* rgba, vtkIdType tuple)
{
  const unsigned char* c = rgba + 4 * tuple;
  return { c[0], c[1], c[2], c[3] };
}

// The mean of a polygon's point colors, rounded to nearest.
template<class PointIdAt>
facet::Rgba8 AverageColor(const unsigned char* rgba, std::size_t count, const PointIdAt& pointId)
{
  unsigned sum[4] = { 0, 0, 0, 0 };
  for (std::size_t k = 0; k < count; ++k)
  {
    const unsigned char* c = rgba + 4 * pointId(k);
    for (int i = 0; i < 4; ++i)
    {
      sum[i] += c[i];
    }
  }
  // Rounded half up in integers: lround(sum / count) without its library call (the quotient
  // is never within double rounding of a half unless it is one).
  const auto mean = [&](int i) {
    return static_cast<std::uint8_t>((2 * std::size_t{ sum[i] } + count) / (2 * count));
  };
  return { mean(0), mean(1), mean(2), mean(3) };
}

template<class Index>
void AveragePerPolygon(const facet::PolygonArray& polygons,
  const unsigned char* rgba,
  std::vector<facet::Rgba8>& colors)
{
  const auto* offsets = static_cast<const Index*>(polygons.offsets);
  const auto* connectivity = static_cast<const Index*>(polygons.connectivity);
  colors.resize(polygons.count);
  for (std::size_t p = 0; p < polygons.count; ++p)
  {
    const std::size_t first = static_cast<std::size_t>(offsets[p]);
    const std::size_t count = static_cast<std::size_t>(offsets[p + 1]) - first;
    colors[p] = count == 0
      ? facet::Rgba8{}
      : AverageColor(rgba, count, [&](std::size_t k) { return connectivity[first + k]; });
  }
}

void AveragePerPolygon(const facet::PolygonArray& polygons,
  const unsigned char* rgba,
  std::vector<facet::Rgba8>& colors)
{
  if (polygons.type == facet::PolygonArray::Type::Int32)
  {
    AveragePerPolygon<std::int32_t>(polygons, rgba, colors);
  }
  else
  {
    AveragePerPolygon<std::int64_t>(polygons, rgba, colors);
  }
}
}

//------------------------------------------------------------------------------
vtkFacetScalarColors::Settings vtkFacetScalarColors::Settings::Of(vtkMapper* mapper)
{
  Settings s;
  s.ScalarVisibility = mapper->GetScalarVisibility() != 0;
  s.ScalarMode = mapper->GetScalarMode();
  s.ColorMode = mapper->GetColorMode();
  s.ArrayAccessMode = mapper->GetArrayAccessMode();
  s.ArrayId = mapper->GetArrayId();
  s.ArrayName = mapper->GetArrayName() ? mapper->GetArrayName() : "";
  s.ArrayComponent = mapper->GetArrayComponent();
  s.LookupTable = mapper->GetLookupTable();
  mapper->GetScalarRange(s.ScalarRange);
  s.UseLookupTableScalarRange = mapper->GetUseLookupTableScalarRange() != 0;
  s.InterpolateScalarsBeforeMapping = mapper->GetInterpolateScalarsBeforeMapping() != 0;
  return s;
}

//------------------------------------------------------------------------------
void vtkFacetScalarColors::Update(vtkPolyData* input,
  const vtkFacetPolyDataConverter& mesh,
  const Settings& settings,
  vtkFacetMessages& messages)
{
  int cellFlag = 0;
  vtkDataArray* scalars = settings.ScalarVisibility ? vtkAbstractMapper::GetScalars(input,
                                                        settings.ScalarMode,
                                                        settings.ArrayAccessMode,
                                                        settings.ArrayId,
                                                        settings.ArrayName.c_str(),
                                                        cellFlag)
                                                    : nullptr;
  // Prepared before the comparison: setting the range may modify the table.
  vtkScalarsToColors* table = scalars ? PrepareLookupTable(scalars, settings) : nullptr;
  const vtkMTimeType tableTime = table ? table->GetMTime() : 0;
  if (!(this->Valid && !mesh.InputChangedLastUpdate() && settings == this->Last &&
        table == this->LastTable && tableTime == this->LastTableTime))
  {
    this->Polygon.clear();
    this->Strip.clear();
    this->Point.clear();
    this->Last = settings;
    this->LastTable = table;
    this->LastTableTime = tableTime;
    this->Valid = true;
    this->Computed.Modified();
    if (scalars)
    {
      this->Warning = this->Compute(scalars, cellFlag != 0, table, input, mesh, settings);
    }
    else
    {
      this->Warning =
        !settings.ScalarVisibility || (settings.ArrayName.empty() && settings.ArrayId < 0)
        ? std::string()
        : "no array '" + settings.ArrayName + "' to color by; using the property's color";
    }
  }
  if (!this->Warning.empty())
  {
    messages.AddWarning(this->Warning);
  }
}

//------------------------------------------------------------------------------
vtkScalarsToColors* vtkFacetScalarColors::PrepareLookupTable(vtkDataArray* scalars,
  const Settings& settings)
{
  // vtkMapper::MapScalars, except that an array's own table is built too (an unbuilt
  // vtkLookupTable holds uninitialized colors) and the mapper is left as it is.
  vtkScalarsToColors* table = scalars->GetLookupTable();
  if (!table)
  {
    table = settings.LookupTable;
  }
  table->Build();
  if (!settings.UseLookupTableScalarRange)
  {
    table->SetRange(settings.ScalarRange);
  }
  return table;
}

//------------------------------------------------------------------------------
std::string vtkFacetScalarColors::Compute(vtkDataArray* scalars,
  bool cellScalars,
  vtkScalarsToColors* table,
  vtkPolyData* input,
  const vtkFacetPolyDataConverter& mesh,
  const Settings& settings)
{
  // vtkMapper maps component 0 when the array has no component ArrayComponent.
  const int component =
    settings.ArrayComponent < scalars->GetNumberOfComponents() ? settings.ArrayComponent : 0;
  vtkSmartPointer<vtkUnsignedCharArray> colors =
    vtk::TakeSmartPointer(table->MapScalars(scalars, settings.ColorMode, component, VTK_RGBA));
  if (!colors || colors->GetNumberOfComponents() != 4)
  {
    return "the lookup table gave no RGBA colors; using the property's color";
  }
  const unsigned char* rgba = colors->GetPointer(0);
  const vtkIdType tuples = colors->GetNumberOfTuples();

  if (!cellScalars)
  {
    if (tuples < input->GetNumberOfPoints())
    {
      return "the point scalars have fewer tuples than points; using the property's color";
    }
    AveragePerPolygon(mesh.Polygons().polygons, rgba, this->Polygon);
    AveragePerPolygon(mesh.StripTriangles().polygons, rgba, this->Strip);
    this->Point.resize(static_cast<std::size_t>(input->GetNumberOfPoints()));
    for (vtkIdType p = 0; p < input->GetNumberOfPoints(); ++p)
    {
      this->Point[p] = ColorAt(rgba, p);
    }
    return {};
  }
  // Cell (or field) data, indexed by vtkPolyData cell id.
  const vtkIdType firstPoly = mesh.GetNumberOfVerts() + mesh.GetNumberOfLines();
  const vtkIdType firstStrip = firstPoly + mesh.GetNumberOfPolys();
  if (tuples < firstStrip + mesh.GetNumberOfStrips())
  {
    return "the cell scalars have fewer tuples than cells; using the property's color";
  }
  this->Polygon.resize(static_cast<std::size_t>(mesh.GetNumberOfPolys()));
  for (vtkIdType p = 0; p < mesh.GetNumberOfPolys(); ++p)
  {
    this->Polygon[p] = ColorAt(rgba, firstPoly + p);
  }
  this->Strip.resize(mesh.StripTriangles().polygons.count);
  for (std::size_t t = 0; t < this->Strip.size(); ++t)
  {
    this->Strip[t] = ColorAt(rgba, firstStrip + mesh.StripOfTriangle(t));
  }
  return {};
}
