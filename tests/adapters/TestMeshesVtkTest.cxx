// The tests' sphere generator against vtkSphereSource (VTK 9.1) itself: with
// UvSphereOrder::vtkSphereSource it lists the same points (as float, VTK's default output
// precision) and the same triangles, corner for corner, so the core-only benchmarks can time
// the order the VTK filter's users hand over (bench/PhaseTimes.cpp's ORDER).

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"

#include "support/TestMeshes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <tuple>

namespace {

struct Resolution
{
  int Theta, Phi;
  double Radius;
  glm::dvec3 Center;
};

class SphereAsVtkSphereSource : public ::testing::TestWithParam<Resolution>
{
};

TEST_P(SphereAsVtkSphereSource, ListsTheSamePointsAndTriangles)
{
  const Resolution r = GetParam();
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(r.Theta);
  source->SetPhiResolution(r.Phi);
  source->SetRadius(r.Radius);
  source->SetCenter(r.Center.x, r.Center.y, r.Center.z);
  source->Update();
  vtkPolyData* expected = source->GetOutput();
  const facet::Mesh sphere = facet::testing::makeUvSphere(
    r.Theta, r.Phi, r.Radius, r.Center, facet::testing::UvSphereOrder::vtkSphereSource);

  ASSERT_EQ(static_cast<vtkIdType>(sphere.points.size()), expected->GetNumberOfPoints());
  int differentPoints = 0;
  for (vtkIdType i = 0; i < expected->GetNumberOfPoints(); ++i)
  {
    double p[3];
    expected->GetPoint(i, p);
    const glm::dvec3& q = sphere.points[i];
    if (static_cast<float>(q.x) != static_cast<float>(p[0]) ||
      static_cast<float>(q.y) != static_cast<float>(p[1]) ||
      static_cast<float>(q.z) != static_cast<float>(p[2]))
    {
      ADD_FAILURE() << "point " << i << ": " << q.x << " " << q.y << " " << q.z << " against "
                    << p[0] << " " << p[1] << " " << p[2];
      if (++differentPoints == 5)
        return;
    }
  }

  ASSERT_EQ(static_cast<vtkIdType>(sphere.offsets.size() - 1), expected->GetNumberOfPolys());
  auto polygons = vtk::TakeSmartPointer(expected->GetPolys()->NewIterator());
  std::int64_t polygon = 0;
  for (polygons->GoToFirstCell(); !polygons->IsDoneWithTraversal();
       polygons->GoToNextCell(), ++polygon)
  {
    vtkIdType size;
    const vtkIdType* corners;
    polygons->GetCurrentCell(size, corners);
    const std::int64_t first = sphere.offsets[polygon];
    ASSERT_EQ(size, sphere.offsets[polygon + 1] - first) << "polygon " << polygon;
    for (vtkIdType c = 0; c < size; ++c)
      ASSERT_EQ(corners[c], sphere.connectivity[first + c])
        << "polygon " << polygon << " corner " << c;
  }
}

// The smallest sphere, odd and even resolutions, a radius and centre not 1 and 0, and
// facet_phase_times' 20k-triangle sphere.
INSTANTIATE_TEST_SUITE_P(Resolutions,
  SphereAsVtkSphereSource,
  ::testing::Values(Resolution{ 3, 3, 1.0, glm::dvec3(0.0) },
    Resolution{ 5, 6, 0.5, glm::dvec3(0.0) },
    Resolution{ 8, 5, 1.0, glm::dvec3(0.0) },
    Resolution{ 17, 11, 2.5, glm::dvec3(1.0, -2.0, 0.25) },
    Resolution{ 100, 102, 1.0, glm::dvec3(0.0) }));

} // namespace
