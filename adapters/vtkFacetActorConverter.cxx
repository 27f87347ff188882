// VTK-HeaderTest-Exclude: vtkFacetActorConverter.h
#include "vtkFacetActorConverter.h"

#include "vtkBoundingBox.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFacetMessages.h"
#include "vtkFacetPropertyConverter.h"
#include "vtkFloatArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <set>
#include <string>

namespace {
// The polydata of `data` (itself, or the leaves of a composite dataset, in iteration order);
// the classes of other leaves go to `skipped`.
std::vector<vtkPolyData*> PolyDataOf(vtkDataObject* data, std::set<std::string>& skipped)
{
  std::vector<vtkPolyData*> parts;
  const auto add = [&](vtkDataObject* leaf) {
    if (auto* polyData = vtkPolyData::SafeDownCast(leaf))
    {
      parts.push_back(polyData);
    }
    else if (leaf)
    {
      skipped.insert(leaf->GetClassName());
    }
  };
  auto* composite = vtkCompositeDataSet::SafeDownCast(data);
  if (!composite)
  {
    add(data);
    return parts;
  }
  auto iterator = vtk::TakeSmartPointer(composite->NewIterator());
  iterator->SkipEmptyNodesOn();
  for (iterator->InitTraversal(); !iterator->IsDoneWithTraversal(); iterator->GoToNextItem())
  {
    add(iterator->GetCurrentDataObject());
  }
  return parts;
}
}

//------------------------------------------------------------------------------
bool vtkFacetActorConverter::Update(const Actor& actor,
  bool detectClosedSurfaces,
  vtkFacetMessages& messages)
{
  std::set<std::string> skipped;
  const std::vector<vtkPolyData*> data = PolyDataOf(actor.Data, skipped);
  if (!skipped.empty())
  {
    messages.AddWarning("skipped data of type " +
      vtkFacetMessages::List({ skipped.begin(), skipped.end() }) + ": Facet renders vtkPolyData");
  }
  const std::string unrendered = vtkFacetPropertyConverter::Unrendered(actor.Property);
  if (!unrendered.empty())
  {
    messages.AddWarningOnce("the property asks for " + unrendered +
      ", which Facet does not render yet: it renders opaque surfaces (said once)");
  }
  while (this->Parts.size() < data.size())
  {
    this->Parts.push_back(std::make_unique<Part>());
  }
  this->Parts.resize(data.size());
  this->NumberOfPolygons = 0;
  bool renderable = true;
  for (std::size_t i = 0; i < data.size(); ++i)
  {
    Part& part = *this->Parts[i];
    part.FirstPolygon = this->NumberOfPolygons;
    renderable =
      this->UpdatePart(part, data[i], actor, detectClosedSurfaces, messages) && renderable;
    this->NumberOfPolygons +=
      static_cast<std::int64_t>(part.Polys.mesh.polygons.count + part.Strips.mesh.polygons.count);
  }
  return renderable;
}

//------------------------------------------------------------------------------
bool vtkFacetActorConverter::UpdatePart(Part& part,
  vtkPolyData* data,
  const Actor& actor,
  bool detectClosedSurfaces,
  vtkFacetMessages& messages)
{
  if (!part.Geometry.Update(data, detectClosedSurfaces, messages))
  {
    part.Polys = part.Strips = {};
    return false;
  }
  part.Colors.Update(data, part.Geometry, actor.Coloring, messages);
  const facet::PointArray world = part.Transform.Update(
    part.Geometry.Polygons().points, part.Geometry.ConvertedLastUpdate(), actor.Matrix);
  const vtkMTimeType version = part.VersionOf(part.Geometry.Polygons().version, data);
  const facet::PointArray normals = part.WorldNormals(data, actor.Matrix, version);
  const facet::Material material =
    vtkFacetPropertyConverter::Convert(actor.Property, part.Colors.HasColors(), actor.Lighting);
  const auto place =
    [&](facet::SceneMesh& placed, facet::MeshView mesh, std::span<const facet::Rgba8> colors) {
      mesh.points = world;
      mesh.version = part.VersionOf(mesh.version, data);
      mesh.polygonColors = colors;
      mesh.colorVersion = part.Colors.GetVersion();
      mesh.pointColors = part.Colors.PointColors();
      mesh.scalarTexture = part.Colors.ScalarTexture();
      mesh.pointNormals = normals;
      mesh.closedSurface = mesh.closedSurface && part.Transform.KeepsOrientation();
      placed = { mesh, material };
    };
  place(part.Polys, part.Geometry.Polygons(), part.Colors.PolygonColors());
  place(part.Strips, part.Geometry.StripTriangles(), part.Colors.StripColors());
  return true;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkFacetActorConverter::Part::VersionOf(vtkMTimeType geometry, vtkPolyData* data)
{
  vtkDataArray* normals = data->GetPointData()->GetNormals();
  const vtkMTimeType time = normals ? normals->GetMTime() : 0;
  if (normals != this->NormalsSource || time != this->NormalsSourceTime)
  {
    this->NormalsSource = normals;
    this->NormalsSourceTime = time;
    this->NormalsChanged.Modified();
  }
  // VTK's clock only moves forward: a stamp taken now is later than any version before.
  return std::max(this->Transform.Version(geometry), this->NormalsChanged.GetMTime());
}

//------------------------------------------------------------------------------
facet::PointArray vtkFacetActorConverter::Part::WorldNormals(vtkPolyData* data,
  vtkMatrix4x4* matrix,
  vtkMTimeType version)
{
  vtkDataArray* normals = data->GetPointData()->GetNormals();
  if (!normals || normals->GetNumberOfComponents() != 3 ||
    normals->GetNumberOfTuples() != data->GetNumberOfPoints())
  {
    return {};
  }
  auto* floats = vtkFloatArray::SafeDownCast(normals);
  auto* doubles = vtkDoubleArray::SafeDownCast(normals);
  const facet::PointArray model = floats ? facet::PointArray{ floats->GetPointer(0),
    facet::PointArray::Type::Float32,
    static_cast<std::size_t>(normals->GetNumberOfTuples()) }
    : doubles                            ? facet::PointArray{ doubles->GetPointer(0),
        facet::PointArray::Type::Float64,
        static_cast<std::size_t>(normals->GetNumberOfTuples()) }
                                         : facet::PointArray{};
  if (this->Transform.IsIdentity() && model.count > 0)
  {
    return model;
  }
  // Normals transform by the inverse transpose of the matrix's linear part; the core
  // normalizes them (VertexNormals.h: fromPointNormals). Kept while neither the normals nor
  // the world points change.
  if (version == this->NormalsVersion &&
    this->Normals.size() == 3 * static_cast<std::size_t>(normals->GetNumberOfTuples()))
  {
    return facet::PointArray::ofXyz(std::span<const double>(this->Normals));
  }
  this->NormalsVersion = version;
  double inverse[16];
  vtkMatrix4x4::Invert(matrix ? matrix->GetData() : vtkNew<vtkMatrix4x4>()->GetData(), inverse);
  this->Normals.resize(3 * static_cast<std::size_t>(normals->GetNumberOfTuples()));
  for (vtkIdType p = 0; p < normals->GetNumberOfTuples(); ++p)
  {
    double n[3];
    normals->GetTuple(p, n);
    for (int row = 0; row < 3; ++row)
    {
      this->Normals[3 * p + row] =
        inverse[row] * n[0] + inverse[4 + row] * n[1] + inverse[8 + row] * n[2];
    }
  }
  return facet::PointArray::ofXyz(std::span<const double>(this->Normals));
}

//------------------------------------------------------------------------------
void vtkFacetActorConverter::AddTo(facet::Scene& scene) const
{
  for (const auto& part : this->Parts)
  {
    for (const facet::SceneMesh* mesh : { &part->Polys, &part->Strips })
    {
      if (mesh->mesh.polygons.count > 0)
      {
        scene.meshes.push_back(*mesh);
      }
    }
  }
}

//------------------------------------------------------------------------------
std::size_t vtkFacetActorConverter::PartOf(std::int64_t polygon) const
{
  const auto after = std::upper_bound(this->Parts.begin(),
    this->Parts.end(),
    polygon,
    [](std::int64_t id, const std::unique_ptr<Part>& part) { return id < part->FirstPolygon; });
  return static_cast<std::size_t>(after - this->Parts.begin()) - 1;
}

//------------------------------------------------------------------------------
vtkIdType vtkFacetActorConverter::CellIdOf(std::int64_t polygon) const
{
  if (polygon < 0 || polygon >= this->NumberOfPolygons)
  {
    return -1;
  }
  const Part& part = *this->Parts[this->PartOf(polygon)];
  return part.Geometry.CellIdOf(static_cast<std::int32_t>(polygon - part.FirstPolygon));
}

//------------------------------------------------------------------------------
void vtkFacetActorConverter::CellIdsOf(const std::int32_t* polygonIds,
  vtkIdType* cellIds,
  vtkIdType begin,
  vtkIdType end,
  bool stream) const
{
  if (this->Parts.size() == 1)
  {
    this->Parts[0]->Geometry.CellIdsOf(polygonIds, cellIds, begin, end, stream);
    return;
  }
  for (vtkIdType i = begin; i < end; ++i)
  {
    cellIds[i] = this->CellIdOf(polygonIds[i]);
  }
}

//------------------------------------------------------------------------------
int vtkFacetActorConverter::GetNumberOfConversions() const
{
  return static_cast<int>(std::count_if(this->Parts.begin(),
    this->Parts.end(),
    [](const std::unique_ptr<Part>& part) { return part->Geometry.ConvertedLastUpdate(); }));
}

//------------------------------------------------------------------------------
void vtkFacetActorConverter::GetFiniteBounds(double bounds[6])
{
  vtkBoundingBox box;
  for (const auto& part : this->Parts)
  {
    double partBounds[6];
    if (part->Transform.IsIdentity())
    {
      std::copy_n(part->Geometry.GetFiniteBounds(), 6, partBounds);
    }
    else
    {
      vtkFacetPolyDataConverter::ComputeFiniteBounds(part->Polys.mesh.points, partBounds);
    }
    box.AddBounds(partBounds);
  }
  box.GetBounds(bounds);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkFacetActorConverter::GetPreparedTableTime(vtkScalarsToColors* table) const
{
  for (const auto& part : this->Parts)
  {
    if (table && part->Colors.GetPreparedTable() == table)
    {
      return part->Colors.GetPreparedTableTime();
    }
  }
  return 0;
}
