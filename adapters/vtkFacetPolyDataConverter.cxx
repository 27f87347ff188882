#include "vtkFacetPolyDataConverter.h"

#include "vtkBoundingBox.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDoubleArray.h"
#include "vtkFacetMessages.h"
#include "vtkFloatArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"

#include "facet/Error.h"
#include "facet/IdPlane.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

namespace {
constexpr vtkIdType MaxFacetIds = std::numeric_limits<std::int32_t>::max();

vtkMTimeType TimeOf(vtkObject* object)
{
  return object ? object->GetMTime() : 0;
}

// The latest MTime of what the conversion reads: the vtkPolyData itself, its points and its
// cells, not its attributes (new scalars or normals are no new geometry).
vtkMTimeType GeometryTimeOf(vtkPolyData* input)
{
  return std::max({ input->vtkObject::GetMTime(),
    TimeOf(input->GetPoints()),
    TimeOf(input->GetVerts()),
    TimeOf(input->GetLines()),
    TimeOf(input->GetPolys()),
    TimeOf(input->GetStrips()) });
}
}

//------------------------------------------------------------------------------
void vtkFacetPolyDataConverter::Reset()
{
  *this = vtkFacetPolyDataConverter();
}

//------------------------------------------------------------------------------
namespace {
// The core's structure check (offsets and point ids), reported in the input's terms: "the
// input's polys: polygons.connectivity[5] is 7, outside [0, points.count) (polygon 1)".
bool ValidateIds(const facet::MeshView& mesh, const char* cells, vtkFacetMessages& messages)
{
  try
  {
    facet::validate(mesh);
    return true;
  }
  catch (const facet::Error& e)
  {
    std::string problem = e.what();
    const std::string prefix = "MeshView.";
    if (problem.compare(0, prefix.size(), prefix) == 0)
    {
      problem.erase(0, prefix.size());
    }
    messages.AddError(std::string("cannot render: the input's ") + cells + ": " + problem);
    return false;
  }
}
}

//------------------------------------------------------------------------------
bool vtkFacetPolyDataConverter::Update(vtkPolyData* input,
  bool detectClosedSurfaces,
  vtkFacetMessages& messages)
{
  const bool sameInput = input == this->Input && input->GetMTime() == this->InputTime;
  this->Converted = false;
  if (!(input == this->Input && GeometryTimeOf(input) == this->GeometryTime &&
        detectClosedSurfaces == this->DetectedClosedSurfaces) &&
    !this->Convert(input, detectClosedSurfaces, messages))
  {
    return false;
  }
  this->InputChanged = this->Converted || !sameInput;
  this->InputTime = input->GetMTime();
  if (this->NumberOfVerts + this->NumberOfLines > 0)
  {
    messages.AddWarning("skipped " + std::to_string(this->NumberOfVerts) + " vertex and " +
      std::to_string(this->NumberOfLines) +
      " line cells: Facet renders polygons and triangle strips");
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkFacetPolyDataConverter::Convert(vtkPolyData* input,
  bool detectClosedSurfaces,
  vtkFacetMessages& messages)
{
  this->Reset();
  this->NumberOfVerts = input->GetNumberOfVerts();
  this->NumberOfLines = input->GetNumberOfLines();
  this->NumberOfPolys = input->GetNumberOfPolys();
  this->NumberOfStrips = input->GetNumberOfStrips();
  if (input->GetNumberOfPoints() > MaxFacetIds)
  {
    messages.AddError("cannot render: the input has " + std::to_string(input->GetNumberOfPoints()) +
      " points; Facet renders at most 2^31 - 1");
    return false;
  }
  this->Points = PointsOf(input->GetPoints(), this->PointCopy);
  this->ConvertPolys(input);
  this->ConvertStrips(input);
  if (this->NumberOfPolys + static_cast<vtkIdType>(this->StripOf.size()) > MaxFacetIds)
  {
    messages.AddError("cannot render: the input has " + std::to_string(this->NumberOfPolys) +
      " polygons and " + std::to_string(this->StripOf.size()) +
      " strip triangles; Facet renders at most 2^31 - 1");
    this->Reset();
    return false;
  }
  // Once per conversion, before anything (coloring, the closed-surface check, the render)
  // reads points through the ids.
  if (!ValidateIds(this->PolygonView, "polys", messages) ||
    !ValidateIds(this->StripView, "strips (as triangles)", messages))
  {
    this->Reset();
    return false;
  }
  if (detectClosedSurfaces)
  {
    this->PolygonView.closedSurface =
      this->NumberOfStrips == 0 && facet::isClosedSurface(this->PolygonView);
    this->StripView.closedSurface =
      this->NumberOfPolys == 0 && facet::isClosedSurface(this->StripView);
  }
  // The views' versions (MeshView::version). Arrays read in place take the latest MTime of
  // the points, the polys and the vtkPolyData itself (not its attributes: new scalars only
  // re-shade). VTK's clock only moves forward, so any edit made the VTK way (the array's,
  // the points' or the data's Modified) gives a new version. Arrays copied here are new at
  // every conversion: they take its time.
  vtkTimeStamp now;
  now.Modified();
  this->PolygonView.version = this->PointCopy.empty()
    ? std::max(
        { input->vtkObject::GetMTime(), TimeOf(input->GetPoints()), TimeOf(input->GetPolys()) })
    : now.GetMTime();
  this->StripView.version = now.GetMTime();
  this->Input = input;
  this->GeometryTime = GeometryTimeOf(input);
  this->DetectedClosedSurfaces = detectClosedSurfaces;
  this->Converted = true;
  return true;
}

//------------------------------------------------------------------------------
facet::PointArray vtkFacetPolyDataConverter::PointsOf(vtkPoints* points, std::vector<double>& copy)
{
  if (!points || points->GetNumberOfPoints() == 0)
  {
    return {};
  }
  const auto count = static_cast<std::size_t>(points->GetNumberOfPoints());
  vtkDataArray* data = points->GetData();
  if (auto* floats = vtkFloatArray::FastDownCast(data))
  {
    return { floats->GetPointer(0), facet::PointArray::Type::Float32, count };
  }
  if (auto* doubles = vtkDoubleArray::FastDownCast(data))
  {
    return { doubles->GetPointer(0), facet::PointArray::Type::Float64, count };
  }
  copy.resize(3 * count);
  for (std::size_t i = 0; i < count; ++i)
  {
    points->GetPoint(static_cast<vtkIdType>(i), &copy[3 * i]);
  }
  return facet::PointArray::ofXyz(std::span<const double>(copy));
}

//------------------------------------------------------------------------------
void vtkFacetPolyDataConverter::ComputeFiniteBounds(const facet::PointArray& points,
  double bounds[6])
{
  vtkBoundingBox box; // uninitialized until a point is added
  const auto add = [&](const auto* xyz) {
    for (std::size_t i = 0; i < points.count; ++i, xyz += 3)
    {
      const double x = xyz[0], y = xyz[1], z = xyz[2];
      if (std::isfinite(x) && std::isfinite(y) && std::isfinite(z))
      {
        box.AddPoint(x, y, z);
      }
    }
  };
  if (points.type == facet::PointArray::Type::Float32)
  {
    add(static_cast<const float*>(points.data));
  }
  else
  {
    add(static_cast<const double*>(points.data));
  }
  box.GetBounds(bounds);
}

//------------------------------------------------------------------------------
const double* vtkFacetPolyDataConverter::GetFiniteBounds()
{
  if (!this->FiniteBoundsComputed)
  {
    ComputeFiniteBounds(this->Points, this->FiniteBounds);
    this->FiniteBoundsComputed = true;
  }
  return this->FiniteBounds;
}

//------------------------------------------------------------------------------
void vtkFacetPolyDataConverter::ConvertPolys(vtkPolyData* input)
{
  this->PolygonView = {};
  this->PolygonView.points = this->Points;
  vtkCellArray* polys = input->GetPolys();
  if (!polys || polys->GetNumberOfCells() == 0)
  {
    return;
  }
  facet::PolygonArray& view = this->PolygonView.polygons;
  view.count = static_cast<std::size_t>(polys->GetNumberOfCells());
  view.connectivitySize = static_cast<std::size_t>(polys->GetNumberOfConnectivityIds());
  if (polys->IsStorage64Bit())
  {
    view.type = facet::PolygonArray::Type::Int64;
    view.offsets = polys->GetOffsetsArray64()->GetPointer(0);
    view.connectivity = polys->GetConnectivityArray64()->GetPointer(0);
  }
  else
  {
    view.type = facet::PolygonArray::Type::Int32;
    view.offsets = polys->GetOffsetsArray32()->GetPointer(0);
    view.connectivity = polys->GetConnectivityArray32()->GetPointer(0);
  }
}

//------------------------------------------------------------------------------
void vtkFacetPolyDataConverter::ConvertStrips(vtkPolyData* input)
{
  this->StripView = {};
  this->StripView.points = this->Points;
  vtkCellArray* strips = input->GetStrips();
  if (!strips || strips->GetNumberOfCells() == 0)
  {
    return;
  }
  this->StripOffsets.assign(1, 0);
  auto iterator = vtk::TakeSmartPointer(strips->NewIterator());
  vtkIdType strip = 0;
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal();
       iterator->GoToNextCell(), ++strip)
  {
    vtkIdType size;
    const vtkIdType* ids;
    iterator->GetCurrentCell(size, ids);
    // vtkTriangleStrip::DecomposeStrip: odd triangles swap their first two points, so every
    // triangle keeps the strip's orientation.
    for (vtkIdType k = 0; k + 2 < size; ++k)
    {
      const bool odd = (k % 2) == 1;
      this->StripConnectivity.push_back(odd ? ids[k + 1] : ids[k]);
      this->StripConnectivity.push_back(odd ? ids[k] : ids[k + 1]);
      this->StripConnectivity.push_back(ids[k + 2]);
      this->StripOffsets.push_back(static_cast<std::int64_t>(this->StripConnectivity.size()));
      this->StripOf.push_back(strip);
    }
  }
  this->StripView.polygons = facet::PolygonArray::of(this->StripOffsets, this->StripConnectivity);
}

//------------------------------------------------------------------------------
vtkIdType vtkFacetPolyDataConverter::CellIdOf(std::int32_t polygonId) const
{
  if (polygonId < 0)
  {
    return -1;
  }
  const vtkIdType first = this->NumberOfVerts + this->NumberOfLines;
  if (polygonId < this->NumberOfPolys)
  {
    return first + polygonId;
  }
  return first + this->NumberOfPolys + this->StripOf[polygonId - this->NumberOfPolys];
}

//------------------------------------------------------------------------------
void vtkFacetPolyDataConverter::CellIdsOf(const std::int32_t* polygonIds,
  vtkIdType* cellIds,
  vtkIdType begin,
  vtkIdType end,
  bool stream) const
{
  if (this->StripOf.empty())
  {
    // Polygons only: an offset, in the core's SIMD lanes (the same bytes as CellIdOf). Only
    // the address is cast: vtkIdType is long long, std::int64_t long, and widenPolygonIds
    // stores by SIMD stores and memcpy alone, never through a long lvalue (facet/IdPlane.h),
    // so the plane read back as vtkIdType aliases nothing the compiler may assume apart.
    static_assert(sizeof(vtkIdType) == sizeof(std::int64_t) && std::is_signed_v<vtkIdType> &&
        alignof(vtkIdType) == alignof(std::int64_t),
      "CellId is a signed 64-bit integer");
    facet::widenPolygonIds(polygonIds + begin,
      reinterpret_cast<std::int64_t*>(cellIds + begin),
      static_cast<std::size_t>(end - begin),
      this->NumberOfVerts + this->NumberOfLines,
      stream);
    return;
  }
  for (vtkIdType i = begin; i < end; ++i)
  {
    cellIds[i] = this->CellIdOf(polygonIds[i]);
  }
}
