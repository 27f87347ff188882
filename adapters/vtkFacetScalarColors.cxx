#include "vtkFacetScalarColors.h"

#include "vtkAbstractMapper.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFacetMessages.h"
#include "vtkFacetPolyDataConverter.h"
#include "vtkLookupTable.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkScalarsToColors.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
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

// vtkMapper::CanUseTextureMapForColoring for point scalars: not for an indexed table, nor for
// colors given directly.
bool UsesTexture(const vtkFacetScalarColors::Settings& settings,
  vtkScalarsToColors* table,
  vtkDataArray* scalars)
{
  const bool direct = settings.ColorMode == VTK_COLOR_MODE_DIRECT_SCALARS ||
    (settings.ColorMode == VTK_COLOR_MODE_DEFAULT && vtkUnsignedCharArray::SafeDownCast(scalars));
  return settings.InterpolateScalarsBeforeMapping && !table->GetIndexedLookup() && !direct;
}

// vtkMapper's ScalarToTextureCoordinate (VTK 9.1, vtkMapper.cxx): s across the padded range,
// clamped to ±1000 as VTK clamps it; t = 0.49 for a number, 1 (the NaN row) for NaN.
void TextureCoordinate(double value, double paddedMin, double inverseWidth, float* st)
{
  if (std::isnan(value))
  {
    st[0] = 0.5f;
    st[1] = 1.0f;
    return;
  }
  st[0] = std::clamp(static_cast<float>((value - paddedMin) * inverseWidth), -1000.0f, 1000.0f);
  st[1] = 0.49f;
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
    this->Coordinates.clear();
    this->Texels.clear();
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
    if (UsesTexture(settings, table, scalars))
    {
      this->ComputeTexture(scalars, table, settings.ColorMode);
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

//------------------------------------------------------------------------------
void vtkFacetScalarColors::ComputeTexture(vtkDataArray* scalars,
  vtkScalarsToColors* table,
  int colorMode)
{
  // vtkMapper::MapScalarsToTexture (VTK 9.1): a row of the table's colors with the below-
  // and above-range colors at its ends (texel i at the scalar range[0] + (i - 1/2)·k), a row
  // of the NaN color, and a texture coordinate per point over the range padded by one texel.
  double range[2] = { table->GetRange()[0], table->GetRange()[1] };
  const bool logScale = table->UsingLogScale() != 0;
  if (logScale)
  {
    vtkLookupTable::GetLogRange(range, range);
  }
  const vtkIdType tableColors = table->GetNumberOfAvailableColors();
  vtkIdType width = tableColors + 2;
  if (width > 65538) // VTK's cap: a table of 2^24 colors would make an absurd texture
  {
    width = 8192;
  }
  const double k = (range[1] - range[0]) / static_cast<double>(width - 2);
  vtkNew<vtkDoubleArray> ramp;
  ramp->SetNumberOfTuples(2 * width);
  for (vtkIdType i = 0; i < width; ++i)
  {
    const double value = range[0] + static_cast<double>(i) * k - k / 2.0;
    ramp->SetValue(i, logScale ? std::pow(10.0, value) : value);
    ramp->SetValue(width + i, vtkMath::Nan());
  }
  vtkSmartPointer<vtkUnsignedCharArray> texels =
    vtk::TakeSmartPointer(table->MapScalars(ramp, colorMode, 0, VTK_RGBA));
  if (!texels || texels->GetNumberOfComponents() != 4)
  {
    return; // no texture: the point colors are interpolated
  }
  this->Texels.resize(static_cast<std::size_t>(2 * width));
  for (vtkIdType i = 0; i < 2 * width; ++i)
  {
    this->Texels[i] = ColorAt(texels->GetPointer(0), i);
  }

  const double texel = (range[1] - range[0]) / static_cast<double>(tableColors);
  const double paddedMin = range[0] - texel, inverseWidth = 1.0 / (range[1] - range[0] + 2 * texel);
  const int components = scalars->GetNumberOfComponents();
  const int component = table->GetVectorMode() == vtkScalarsToColors::MAGNITUDE && components > 1
    ? -1
    : table->GetVectorComponent();
  const bool magnitude = component < 0 || component >= components;
  const double tableRange[2] = { table->GetRange()[0], table->GetRange()[1] };
  this->Coordinates.resize(2 * static_cast<std::size_t>(this->Point.size()));
  for (std::size_t p = 0; p < this->Point.size(); ++p)
  {
    double value = 0.0;
    if (magnitude)
    {
      for (int c = 0; c < components; ++c)
      {
        value += scalars->GetComponent(static_cast<vtkIdType>(p), c) *
          scalars->GetComponent(static_cast<vtkIdType>(p), c);
      }
      value = std::sqrt(value);
    }
    else
    {
      value = scalars->GetComponent(static_cast<vtkIdType>(p), component);
    }
    if (logScale)
    {
      value = vtkLookupTable::ApplyLogScale(value, tableRange, range);
    }
    TextureCoordinate(value, paddedMin, inverseWidth, &this->Coordinates[2 * p]);
  }
}
