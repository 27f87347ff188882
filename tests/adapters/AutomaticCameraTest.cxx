// vtkFacetRenderFilter's automatic camera (no SetCamera): vtkRenderer::ResetCamera's result to
// the bit for ordinary input, finite and usable for input with non-finite or huge points
// (issue 7, defect 4), and given to the user by GetActiveCamera (issue 7, friction a).

#include "AdapterTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace facet_test;

namespace {
constexpr int ViewWidth = 160, ViewHeight = 120;

// Every parameter vtkRenderer::ResetCamera sets, and the view up it keeps.
std::vector<double> CameraValues(vtkCamera* camera)
{
  std::vector<double> values;
  for (const double* v : { camera->GetPosition(), camera->GetFocalPoint(), camera->GetViewUp() })
  {
    values.insert(values.end(), v, v + 3);
  }
  const double* range = camera->GetClippingRange();
  values.insert(
    values.end(), { range[0], range[1], camera->GetViewAngle(), camera->GetParallelScale() });
  return values;
}

std::string Describe(const std::vector<double>& values)
{
  std::ostringstream text;
  text.precision(17);
  for (double v : values)
  {
    text << v << " ";
  }
  return text.str();
}

// The camera a VTK user gets from vtkRenderer::ResetCamera on these bounds.
std::vector<double> VtkResetCamera(const double bounds[6], int width, int height)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetAspect(static_cast<double>(width) / height, 1.0);
  renderer->SetNearClippingPlaneTolerance(0.001);
  renderer->ResetCamera(bounds);
  return CameraValues(renderer->GetActiveCamera());
}

vtkSmartPointer<vtkPolyData> Sphere()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(18);
  sphere->SetCenter(1000.0, -50.0, 3.0);
  sphere->SetRadius(0.01);
  sphere->Update();
  return sphere->GetOutput();
}

// The sphere with extra points: each used by one more triangle (with two sphere points).
vtkSmartPointer<vtkPolyData> SphereWith(const std::vector<std::array<double, 3>>& extra)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(Sphere());
  for (const auto& point : extra)
  {
    const vtkIdType ids[3] = { 0, 1, mesh->GetPoints()->InsertNextPoint(point.data()) };
    mesh->GetPolys()->InsertNextCell(3, ids);
  }
  return mesh;
}

// Renders with the automatic camera, which must not give an error.
vtkSmartPointer<vtkFacetRenderFilter> Render(vtkPolyData* input, int width, int height)
{
  auto filter = vtkSmartPointer<vtkFacetRenderFilter>::New();
  filter->SetInputData(input);
  filter->SetSize(width, height);
  MessageCounter errors(filter, vtkCommand::ErrorEvent);
  filter->Update();
  EXPECT_EQ(errors.Count, 0) << errors.Last;
  return filter;
}

bool AllFinite(const std::vector<double>& values)
{
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}
}

//------------------------------------------------------------------------------
TEST(AutomaticCamera, IsVtkRenderersResetCameraToTheBit)
{
  vtkSmartPointer<vtkPolyData> sphere = Sphere();
  for (const auto& [width, height] : { std::pair{ ViewWidth, ViewHeight }, std::pair{ 90, 300 } })
  {
    vtkSmartPointer<vtkFacetRenderFilter> filter = Render(sphere, width, height);
    const std::vector<double> ours = CameraValues(filter->GetActiveCamera());
    const std::vector<double> theirs = VtkResetCamera(sphere->GetBounds(), width, height);
    EXPECT_EQ(ours, theirs) << width << " x " << height << "\nours   " << Describe(ours)
                            << "\ntheirs " << Describe(theirs);
    EXPECT_NE(CellIdAt(filter->GetOutput(), width / 2, height / 2), -1) << "in the middle";
  }
}

//------------------------------------------------------------------------------
TEST(AutomaticCamera, LeavesNonFinitePointsOutOfTheBounds)
{
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vtkSmartPointer<vtkPolyData> sphere = Sphere();
  vtkSmartPointer<vtkPolyData> spoiled =
    SphereWith({ { inf, 0.0, 0.0 }, { 1000.0, -inf, 3.0 }, { nan, 1.0, 2.0 } });
  spoiled->GetPoints()->InsertNextPoint(inf, inf, inf); // used by no cell
  vtkSmartPointer<vtkFacetRenderFilter> clean = Render(sphere, ViewWidth, ViewHeight);
  auto filter = vtkSmartPointer<vtkFacetRenderFilter>::New();
  filter->SetInputData(spoiled);
  filter->SetSize(ViewWidth, ViewHeight);
  MessageCounter errors(filter, vtkCommand::ErrorEvent);
  MessageCounter warnings(filter, vtkCommand::WarningEvent);
  filter->Update();
  EXPECT_EQ(errors.Count, 0) << errors.Last;
  EXPECT_EQ(warnings.Count, 1) << "the skipped cells: " << warnings.Last;
  const std::vector<double> ours = CameraValues(filter->GetActiveCamera());
  const std::vector<double> theirs = VtkResetCamera(sphere->GetBounds(), ViewWidth, ViewHeight);
  EXPECT_EQ(ours, theirs) << "\nours   " << Describe(ours) << "\ntheirs " << Describe(theirs);
  int covered = 0;
  for (int y = 0; y < ViewHeight; ++y)
  {
    for (int x = 0; x < ViewWidth; ++x)
    {
      ASSERT_EQ(RgbaAt(filter->GetOutput(), x, y), RgbaAt(clean->GetOutput(), x, y))
        << "the sphere renders as without the spoiled cells, at " << x << ", " << y;
      covered += CellIdAt(filter->GetOutput(), x, y) >= 0;
    }
  }
  EXPECT_GT(covered, ViewWidth * ViewHeight / 10);
}

//------------------------------------------------------------------------------
// Extents whose squares overflow (2e300), or whose difference does (±DBL_MAX). The camera is
// fitted to the bounds clamped to ±1e100, so a square of ±5e99 in front of the huge one
// fills the middle of the image.
TEST(AutomaticCamera, HugeBoundsGiveAFiniteCameraThatShowsTheData)
{
  for (double corner : { 1e300, std::numeric_limits<double>::max() })
  {
    SCOPED_TRACE("corners at +-" + std::to_string(corner / 1e300) + "e300");
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble(); // float has no 1e300
    vtkNew<vtkCellArray> polys;
    AddSquare(points, polys, -corner, -corner, corner, corner);
    AddSquare(points, polys, -5e99, -5e99, 5e99, 5e99, 1e99);
    vtkSmartPointer<vtkFacetRenderFilter> filter =
      Render(PolyData(points, polys), ViewWidth, ViewHeight);
    vtkCamera* camera = filter->GetActiveCamera();
    const std::vector<double> values = CameraValues(camera);
    EXPECT_TRUE(AllFinite(values)) << Describe(values);
    EXPECT_TRUE(std::isfinite(camera->GetDistance())) << camera->GetDistance();
    EXPECT_GT(camera->GetDistance(), 0.0);
    const double* direction = camera->GetDirectionOfProjection();
    EXPECT_EQ(direction[2], -1.0) << "VTK's default direction, kept";
    EXPECT_EQ(CellIdAt(filter->GetOutput(), ViewWidth / 2, ViewHeight / 2), 1);
    EXPECT_EQ(CellIdAt(filter->GetOutput(), ViewWidth / 2 + 10, ViewHeight / 2 - 10), 1);
  }
}

//------------------------------------------------------------------------------
// Points too close together to resolve against their distance from the origin: VTK's fit
// puts the camera on its focal point (the distance rounds away).
TEST(AutomaticCamera, DataTooSmallForItsPositionStillGetsAUsableCamera)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, 1e20, 1e20, 1e20 + 1e-10, 1e20 + 1e-10, 1e20);
  vtkSmartPointer<vtkFacetRenderFilter> filter =
    Render(PolyData(points, polys), ViewWidth, ViewHeight);
  vtkCamera* camera = filter->GetActiveCamera();
  EXPECT_GT(camera->GetDistance(), 0.0);
  EXPECT_TRUE(AllFinite(CameraValues(camera))) << Describe(CameraValues(camera));
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), ViewWidth * ViewHeight);
}

//------------------------------------------------------------------------------
TEST(AutomaticCamera, GetActiveCameraIsTheUsersOrTheFittedOne)
{
  vtkSmartPointer<vtkPolyData> sphere = Sphere();
  vtkNew<vtkFacetRenderFilter> filter;
  ASSERT_NE(filter->GetActiveCamera(), nullptr) << "never null, even before an Update";
  filter->SetInputData(sphere);
  filter->SetSize(ViewWidth, ViewHeight);
  filter->Update();
  vtkCamera* fitted = filter->GetActiveCamera();
  ASSERT_NE(fitted, nullptr);
  EXPECT_EQ(filter->GetCamera(), nullptr) << "the user set none";

  // Orbit from it as the header says: copy, turn, refit, set.
  vtkNew<vtkCamera> orbit;
  orbit->DeepCopy(fitted);
  orbit->Azimuth(90.0);
  vtkFacetRenderFilter::ResetCamera(orbit, sphere, ViewWidth, ViewHeight);
  filter->SetCamera(orbit);
  EXPECT_EQ(filter->GetActiveCamera(), orbit.Get());
  filter->Update();
  EXPECT_NE(CellIdAt(filter->GetOutput(), ViewWidth / 2, ViewHeight / 2), -1);
  // Turned 90 degrees about the view up (+y): the camera looks along -x.
  const double* direction = orbit->GetDirectionOfProjection();
  EXPECT_NEAR(direction[0], -1.0, 1e-12);
  const double* fittedFocal = fitted->GetFocalPoint();
  const double* orbitFocal = orbit->GetFocalPoint();
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(orbitFocal[i], fittedFocal[i]) << "the same bounds, the same focal point";
  }
  EXPECT_NEAR(orbit->GetDistance(), fitted->GetDistance(), 1e-12 * fitted->GetDistance());

  // A copy of the fitted camera renders what the automatic camera rendered.
  vtkSmartPointer<vtkFacetRenderFilter> automatic = Render(sphere, ViewWidth, ViewHeight);
  vtkNew<vtkCamera> copy;
  copy->DeepCopy(automatic->GetActiveCamera());
  filter->SetCamera(copy);
  filter->Update();
  for (int y = 0; y < ViewHeight; ++y)
  {
    for (int x = 0; x < ViewWidth; ++x)
    {
      ASSERT_EQ(RgbaAt(filter->GetOutput(), x, y), RgbaAt(automatic->GetOutput(), x, y));
    }
  }
}
