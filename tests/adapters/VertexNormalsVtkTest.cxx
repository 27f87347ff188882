// facet::computeVertexNormals against vtkPolyDataNormals (VTK 9.1) itself, on fandisk (a CAD
// part with creases) and the Stanford bunny: the same split decisions and the same normals.
//
// Settings that correspond: FeatureAngle 30 = featureAngleDegrees 30; Splitting on (facet
// always splits at sharp edges); Consistency off, so VTK keeps every polygon's winding and
// its output polygons list the same corners in the same order (facet does not reorder
// either: it compares flipped neighbours reversed instead, which on these consistently
// oriented meshes never happens — the test checks that); AutoOrientNormals and FlipNormals
// off. Splitting adds points at the end and renumbers corners, so the comparison is per
// corner: two corners of the same input point share a VTK output point exactly when they
// share a facet normal, and the normals agree to 1e-6 (VTK stores them in float).

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"

#include "facet/VertexNormals.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {

struct Corners
{
  std::vector<std::int64_t> Offsets{ 0 };
  std::vector<std::int64_t> Connectivity;
};

Corners CornersOf(vtkCellArray* polys)
{
  Corners corners;
  auto cells = vtk::TakeSmartPointer(polys->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    cells->GetCurrentCell(size, ids);
    corners.Connectivity.insert(corners.Connectivity.end(), ids, ids + size);
    corners.Offsets.push_back(static_cast<std::int64_t>(corners.Connectivity.size()));
  }
  return corners;
}

vtkSmartPointer<vtkPolyData> ReadObj(const std::string& name)
{
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName((std::string(FACET_SHARED_DATA_DIR) + "/meshes/" + name).c_str());
  reader->Update();
  vtkSmartPointer<vtkPolyData> mesh = reader->GetOutput();
  return mesh;
}

void CompareWithVtk(const std::string& name)
{
  vtkSmartPointer<vtkPolyData> input = ReadObj(name);
  ASSERT_GT(input->GetNumberOfPolys(), 0) << name;
  std::vector<double> xyz(3 * input->GetNumberOfPoints());
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    input->GetPoint(i, &xyz[3 * i]);
  }
  const Corners in = CornersOf(input->GetPolys());
  facet::MeshView view;
  view.points = facet::PointArray::ofXyz(xyz);
  view.polygons = facet::PolygonArray::of(in.Offsets, in.Connectivity);
  const facet::VertexNormals ours = facet::computeVertexNormals(view, { 30.0 });
  EXPECT_EQ(ours.inconsistentEdges, 0u) << name << " is consistently oriented";

  vtkNew<vtkPolyDataNormals> vtk;
  vtk->SetInputData(input);
  vtk->SetFeatureAngle(30.0);
  vtk->SplittingOn();
  vtk->ConsistencyOff();
  vtk->AutoOrientNormalsOff();
  vtk->FlipNormalsOff();
  vtk->ComputePointNormalsOn();
  vtk->Update();
  vtkPolyData* output = vtk->GetOutput();
  const Corners out = CornersOf(output->GetPolys());
  vtkDataArray* vtkNormals = output->GetPointData()->GetNormals();
  ASSERT_EQ(out.Connectivity.size(), in.Connectivity.size()) << name;
  ASSERT_EQ(out.Offsets, in.Offsets) << name;

  // Split decisions: VTK output point <-> facet normal index must be one-to-one.
  std::map<std::int64_t, std::uint32_t> oursOfVtk;
  std::map<std::uint32_t, std::int64_t> vtkOfOurs;
  std::size_t splitMismatches = 0, normalMismatches = 0;
  double worst = 0.0;
  for (std::size_t k = 0; k < in.Connectivity.size(); ++k)
  {
    const std::int64_t theirs = out.Connectivity[k];
    const std::uint32_t mine = ours.cornerNormal[k];
    splitMismatches += oursOfVtk.emplace(theirs, mine).first->second != mine;
    splitMismatches += vtkOfOurs.emplace(mine, theirs).first->second != theirs;
    double n[3];
    vtkNormals->GetTuple(theirs, n);
    const glm::dvec3 difference = ours.normals[mine] - glm::dvec3(n[0], n[1], n[2]);
    const double distance = glm::length(difference);
    worst = std::max(worst, distance);
    normalMismatches += !(distance < 1e-6);
  }
  // VTK also keeps the points no polygon uses (the bunny has some); facet makes no normal
  // for them.
  std::printf("%s: %lld points in, %lld out of VTK (%zu used by polygons), %zu facet normals "
              "(%zu split points); largest normal difference %.3g\n",
    name.c_str(),
    static_cast<long long>(input->GetNumberOfPoints()),
    static_cast<long long>(output->GetNumberOfPoints()),
    oursOfVtk.size(),
    ours.normals.size(),
    ours.splitPoints,
    worst);
  EXPECT_EQ(splitMismatches, 0u) << name << ": corners grouped differently";
  EXPECT_EQ(ours.normals.size(), oursOfVtk.size()) << name;
  EXPECT_GT(ours.splitPoints, 0u) << name << " has edges sharper than 30 degrees";
  EXPECT_EQ(normalMismatches, 0u) << name << ": largest difference " << worst;
}

TEST(VertexNormalsVtk, FandiskAsVtkPolyDataNormals)
{
  CompareWithVtk("fandisk.obj");
}

TEST(VertexNormalsVtk, BunnyAsVtkPolyDataNormals)
{
  CompareWithVtk("stanford-bunny.obj");
}

} // namespace
