// vtkFacetRenderFilter: conversion of vtkPolyData (strips, cell ids, colors), cameras as
// vtkCamera defines them, lights, errors, caching and progress. No X server needed.

#include "AdapterTestUtilities.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkElevationFilter.h"
#include "vtkFacetLight.h"
#include "vtkFloatArray.h"
#include "vtkLookupTable.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkStripper.h"
#include "vtkTriangleFilter.h"

#include "facet/IdPlane.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace facet_test;

namespace {
constexpr int FilterWidth = 160, FilterHeight = 120;

vtkSmartPointer<vtkCamera> PixelCamera()
{
  return facet_test::PixelCamera(FilterWidth, FilterHeight);
}

// A filter showing exactly the surface colors: Ka = 1 with the ambient color being the
// surface color, Kd = 0, no lights at all.
vtkSmartPointer<vtkFacetRenderFilter> UnlitFilter(vtkPolyData* input)
{
  auto filter = vtkSmartPointer<vtkFacetRenderFilter>::New();
  filter->SetInputData(input);
  filter->SetSize(FilterWidth, FilterHeight);
  filter->SetCamera(PixelCamera());
  filter->AutomaticLightCreationOff();
  filter->SetAmbientLightColor(0.0, 0.0, 0.0);
  filter->GetProperty()->SetAmbient(1.0);
  filter->GetProperty()->SetDiffuse(0.0);
  return filter;
}

vtkSmartPointer<vtkPolyData> StripSphere()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(18);
  sphere->SetRadius(40.0);
  sphere->SetCenter(80.0, 60.0, 0.0);
  vtkNew<vtkStripper> stripper;
  stripper->SetInputConnection(sphere->GetOutputPort());
  stripper->Update();
  return stripper->GetOutput();
}
}

//------------------------------------------------------------------------------
TEST(Conversion, StripsRenderWithTheWindingVtkGivesThem)
{
  vtkSmartPointer<vtkPolyData> strips = StripSphere();
  ASSERT_GT(strips->GetNumberOfStrips(), 0);
  ASSERT_EQ(strips->GetNumberOfPolys(), 0);
  vtkNew<vtkTriangleFilter> triangles; // VTK's own strip decomposition
  triangles->SetInputData(strips);
  triangles->Update();

  // One-sided lighting and back-face culling: a triangle wound the wrong way would vanish
  // or darken, so equal images mean equal winding.
  const auto render = [](vtkPolyData* input) {
    auto filter = vtkSmartPointer<vtkFacetRenderFilter>::New();
    filter->SetInputData(input);
    filter->SetSize(FilterWidth, FilterHeight);
    filter->SetCamera(PixelCamera());
    filter->TwoSidedLightingOff();
    filter->GetProperty()->BackfaceCullingOn();
    filter->Update();
    return vtkSmartPointer<vtkImageData>(filter->GetOutput());
  };
  vtkSmartPointer<vtkImageData> fromStrips = render(strips);
  vtkSmartPointer<vtkImageData> fromTriangles = render(triangles->GetOutput());
  int covered = 0;
  for (int y = 0; y < FilterHeight; ++y)
  {
    for (int x = 0; x < FilterWidth; ++x)
    {
      ASSERT_EQ(RgbaAt(fromStrips, x, y), RgbaAt(fromTriangles, x, y)) << x << ", " << y;
      covered += CellIdAt(fromStrips, x, y) >= 0;
    }
  }
  EXPECT_GT(covered, 4000);
}

//------------------------------------------------------------------------------
TEST(Conversion, CellIdsCountVertsLinesPolysStrips)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  for (int i = 0; i < 2; ++i)
  {
    const vtkIdType v = points->InsertNextPoint(5.0 + i, 5.0, 0.0);
    verts->InsertNextCell(1, &v);
  }
  const vtkIdType lineIds[2] = { 0, 1 };
  lines->InsertNextCell(2, lineIds);
  AddSquare(points, polys, 10.3, 10.3, 40.7, 40.7);                      // cell 3
  const vtkIdType concave[6] = { points->InsertNextPoint(50.2, 10.2, 0), // cell 4: an L
    points->InsertNextPoint(90.2, 10.2, 0),
    points->InsertNextPoint(90.2, 20.2, 0),
    points->InsertNextPoint(60.2, 20.2, 0),
    points->InsertNextPoint(60.2, 50.2, 0),
    points->InsertNextPoint(50.2, 50.2, 0) };
  polys->InsertNextCell(6, concave);
  const vtkIdType strip[4] = { points->InsertNextPoint(100.1, 60.1, 0), // cell 5
    points->InsertNextPoint(150.1, 60.1, 0),
    points->InsertNextPoint(100.1, 110.1, 0),
    points->InsertNextPoint(150.1, 110.1, 0) };
  strips->InsertNextCell(4, strip);
  vtkNew<vtkPolyData> input;
  input->SetPoints(points);
  input->SetVerts(verts);
  input->SetLines(lines);
  input->SetPolys(polys);
  input->SetStrips(strips);

  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  MessageCounter warnings(filter, vtkCommand::WarningEvent);
  filter->Update();
  vtkImageData* image = filter->GetOutput();
  EXPECT_EQ(warnings.Count, 1);
  EXPECT_NE(warnings.Last.find("skipped 2 vertex and 1 line cells"), std::string::npos)
    << warnings.Last;
  EXPECT_EQ(CellIdAt(image, 20, 20), 3);
  EXPECT_EQ(CellIdAt(image, 55, 40), 4) << "the L's upright";
  EXPECT_EQ(CellIdAt(image, 80, 15), 4) << "the L's foot";
  EXPECT_EQ(CellIdAt(image, 80, 40), -1) << "inside the L's bounding box, outside the L";
  EXPECT_EQ(CellIdAt(image, 110, 70), 5) << "first strip triangle";
  EXPECT_EQ(CellIdAt(image, 140, 100), 5) << "second strip triangle";
  EXPECT_EQ(CellIdAt(image, 5, 100), -1);
}

//------------------------------------------------------------------------------
TEST(Conversion, CellIdsSurviveNearPlaneClipping)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, -50.0, -50.0, 50.0, 50.0); // a floor the near plane cuts
  AddSquare(points, polys, -5.0, 60.0, 5.0, 70.0);    // something beyond it
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.0, -40.0, 5.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetClippingRange(20.0, 200.0);
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  filter->SetCamera(camera);
  filter->Update();
  vtkImageData* image = filter->GetOutput();
  EXPECT_GT(FieldValue(image, "FacetCounts", "TrianglesClipped"), 0.0);
  // Up the middle column: clipped away (background) at the bottom, then the floor.
  int clipRow = 0;
  while (clipRow < FilterHeight && CellIdAt(image, FilterWidth / 2, clipRow) == -1)
  {
    ++clipRow;
  }
  EXPECT_GT(clipRow, 5) << "the near plane removes the closest part of the floor";
  EXPECT_LT(clipRow, FilterHeight / 2);
  for (int y = clipRow; y < clipRow + 10; ++y)
  {
    EXPECT_EQ(CellIdAt(image, FilterWidth / 2, y), 0) << "row " << y;
  }
  int floor = 0;
  for (int y = 0; y < FilterHeight; ++y)
  {
    for (int x = 0; x < FilterWidth; ++x)
    {
      const vtkIdType id = CellIdAt(image, x, y);
      ASSERT_TRUE(id == -1 || id == 0 || id == 1) << id;
      floor += id == 0;
    }
  }
  EXPECT_GT(floor, FilterWidth * FilterHeight / 4);
}

//------------------------------------------------------------------------------
TEST(Coloring, CellScalarsThroughAnUnbuiltLookupTableGiveTheBuiltTablesBytes)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkDoubleArray> values;
  values->SetName("temperature");
  for (int i = 0; i < 5; ++i)
  {
    AddSquare(points, polys, 5.0 + 30.0 * i, 20.0, 30.0 + 30.0 * i, 100.0);
    values->InsertNextValue(-3.0 + 2.7 * i);
  }
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  input->GetCellData()->SetScalars(values);
  // The user's table, never built (vtkMapper builds it before mapping), and a built twin.
  vtkNew<vtkLookupTable> table, twin;
  for (vtkLookupTable* t : { table.Get(), twin.Get() })
  {
    t->SetHueRange(0.667, 0.0);
    t->SetNumberOfTableValues(17);
  }
  twin->Build();
  twin->SetRange(-4.0, 9.0);

  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  filter->SetLookupTable(table);
  filter->SetScalarRange(-4.0, 9.0);
  filter->Update();
  for (int i = 0; i < 5; ++i)
  {
    const unsigned char* expected = twin->MapValue(values->GetValue(i));
    const std::array<int, 4> pixel = RgbaAt(filter->GetOutput(), 17 + 30 * i, 60);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_EQ(pixel[c], expected[c]) << "square " << i << " channel " << c;
    }
  }
  EXPECT_EQ(table->GetRange()[0], -4.0) << "the table gets the scalar range, as vtkMapper sets it";
  EXPECT_EQ(table->GetRange()[1], 9.0);
}

//------------------------------------------------------------------------------
// Issue 7, defect 1: the default lookup table was read unbuilt (uninitialized colors that
// changed from run to run). Every pixel must show the mean of its polygon's point colors as
// VTK's own vtkLookupTable maps them, in two filters alike.
TEST(Coloring, TheDefaultLookupTableMapsAsVtksOwn)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(18);
  sphere->SetRadius(40.0);
  sphere->SetCenter(80.0, 60.0, 0.0);
  vtkNew<vtkElevationFilter> elevation; // point scalars in [0, 1], bottom to top
  elevation->SetInputConnection(sphere->GetOutputPort());
  elevation->SetLowPoint(0.0, 20.0, 0.0);
  elevation->SetHighPoint(0.0, 100.0, 0.0);
  elevation->Update();
  vtkPolyData* input = elevation->GetPolyDataOutput();

  // VTK's mapping: vtkMapper's default table (a vtkLookupTable, built) over its default
  // scalar range (0, 1).
  vtkNew<vtkLookupTable> reference;
  reference->Build();
  reference->SetRange(0.0, 1.0);
  auto pointColors = vtk::TakeSmartPointer(
    reference->MapScalars(input->GetPointData()->GetScalars(), VTK_COLOR_MODE_DEFAULT, 0));
  const auto expectedAt = [&](vtkIdType cell) {
    vtkIdType count;
    const vtkIdType* ids;
    input->GetCellPoints(cell, count, ids);
    std::array<int, 4> mean{};
    for (int c = 0; c < 4; ++c)
    {
      double sum = 0.0;
      for (vtkIdType k = 0; k < count; ++k)
      {
        sum += pointColors->GetValue(4 * ids[k] + c);
      }
      mean[c] = static_cast<int>(std::lround(sum / count));
    }
    return mean;
  };

  vtkSmartPointer<vtkFacetRenderFilter> first = UnlitFilter(input), second = UnlitFilter(input);
  first->Update();
  second->Update();
  double ours[3] = { 0, 0, 0 }, theirs[3] = { 0, 0, 0 };
  int covered = 0, mismatches = 0, lowestRed = 255, highestRed = 0;
  for (int y = 0; y < FilterHeight; ++y)
  {
    for (int x = 0; x < FilterWidth; ++x)
    {
      ASSERT_EQ(RgbaAt(first->GetOutput(), x, y), RgbaAt(second->GetOutput(), x, y))
        << "two runs differ at " << x << ", " << y;
      const vtkIdType cell = CellIdAt(first->GetOutput(), x, y);
      if (cell < 0)
      {
        continue;
      }
      ++covered;
      const std::array<int, 4> pixel = RgbaAt(first->GetOutput(), x, y);
      const std::array<int, 4> expected = expectedAt(cell);
      for (int c = 0; c < 3; ++c)
      {
        ours[c] += pixel[c];
        theirs[c] += expected[c];
      }
      lowestRed = std::min(lowestRed, pixel[0]);
      highestRed = std::max(highestRed, pixel[0]);
      if (pixel[0] != expected[0] || pixel[1] != expected[1] || pixel[2] != expected[2])
      {
        if (++mismatches <= 5)
        {
          ADD_FAILURE() << "pixel " << x << ", " << y << " (cell " << cell << ") is " << pixel[0]
                        << "," << pixel[1] << "," << pixel[2] << "; VTK's table gives "
                        << expected[0] << "," << expected[1] << "," << expected[2];
        }
      }
    }
  }
  ASSERT_GT(covered, 4000);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_EQ(ours[c] / covered, theirs[c] / covered) << "mean of channel " << c;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_LT(lowestRed, 40) << "blue at the bottom";
  EXPECT_GT(highestRed, 215) << "red at the top";
}

//------------------------------------------------------------------------------
TEST(Coloring, UnsignedCharColorsAreUsedDirectly)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, 10.0, 10.0, 70.0, 70.0);
  AddSquare(points, polys, 90.0, 10.0, 150.0, 70.0);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetNumberOfComponents(3);
  colors->InsertNextTuple3(200, 17, 99);
  colors->InsertNextTuple3(3, 250, 128);
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  input->GetCellData()->SetScalars(colors);
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 40, 40), (std::array<int, 4>{ 200, 17, 99, 255 }));
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 120, 40), (std::array<int, 4>{ 3, 250, 128, 255 }));
  filter->ScalarVisibilityOff();
  filter->GetProperty()->SetColor(0.0, 0.5, 1.0);
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 40, 40), (std::array<int, 4>{ 0, 128, 255, 255 }));
}

//------------------------------------------------------------------------------
TEST(Coloring, PointScalarsAreAveragedPerPolygon)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, 10.0, 10.0, 70.0, 70.0);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetNumberOfComponents(4);
  colors->InsertNextTuple4(255, 0, 0, 255);
  colors->InsertNextTuple4(0, 255, 0, 255);
  colors->InsertNextTuple4(0, 0, 255, 255);
  colors->InsertNextTuple4(255, 255, 255, 255);
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  input->GetPointData()->SetScalars(colors);
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 40, 40), (std::array<int, 4>{ 128, 128, 128, 255 }));
  filter->SetScalarModeToUseCellData(); // no cell scalars: the property's color
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 40, 40), (std::array<int, 4>{ 255, 255, 255, 255 }));
}

//------------------------------------------------------------------------------
// ParaView's array selection names the color array with SetInputArrayToProcess(0, ...).
TEST(Coloring, InputArrayToProcessNamesThePointOrCellArray)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, 10.0, 10.0, 70.0, 70.0);
  vtkNew<vtkUnsignedCharArray> cellColors;
  cellColors->SetName("cellColors");
  cellColors->SetNumberOfComponents(3);
  cellColors->InsertNextTuple3(200, 17, 99);
  vtkNew<vtkUnsignedCharArray> pointColors;
  pointColors->SetName("pointColors");
  pointColors->SetNumberOfComponents(3);
  for (int i = 0; i < 4; ++i)
  {
    pointColors->InsertNextTuple3(10 + 20 * i, 60, 250);
  }
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  input->GetCellData()->AddArray(cellColors); // neither is the active scalars
  input->GetPointData()->AddArray(pointColors);
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  filter->GetProperty()->SetColor(1.0, 1.0, 1.0);
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 40, 40), (std::array<int, 4>{ 255, 255, 255, 255 }));

  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "cellColors");
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 40, 40), (std::array<int, 4>{ 200, 17, 99, 255 }));
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "pointColors");
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 40, 40), (std::array<int, 4>{ 40, 60, 250, 255 }));
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "");
  filter->Update(); // an empty name leaves ScalarMode in charge: no active scalars, no colors
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 40, 40), (std::array<int, 4>{ 255, 255, 255, 255 }));
}

//------------------------------------------------------------------------------
// Tiny triangles centered on points that VTK's composite projection matrix puts on pixel
// centers must cover exactly those pixels, for random perspective and parallel cameras with
// off-center window centers.
TEST(Camera, PointsLandWhereVtkCameraProjectsThem)
{
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(42);
  const auto uniform = [&](double low, double high) {
    random->Next();
    return random->GetRangeValue(low, high);
  };
  const double aspect = static_cast<double>(FilterWidth) / FilterHeight;
  for (int trial = 0; trial < 40; ++trial)
  {
    vtkNew<vtkCamera> camera;
    camera->SetPosition(uniform(-20, 20), uniform(-20, 20), uniform(10, 30));
    camera->SetFocalPoint(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    camera->SetViewUp(uniform(-0.3, 0.3), 1.0, uniform(-0.3, 0.3));
    camera->OrthogonalizeViewUp();
    camera->SetViewAngle(uniform(15, 60));
    camera->SetParallelProjection(trial % 2);
    camera->SetParallelScale(uniform(3, 12));
    camera->SetWindowCenter(uniform(-0.4, 0.4), uniform(-0.4, 0.4));
    camera->SetClippingRange(1.0, 100.0);

    // The world point on the focal plane that VTK maps to the center of pixel (px, py).
    const int px = static_cast<int>(uniform(0, FilterWidth - 1)),
              py = static_cast<int>(uniform(0, FilterHeight - 1));
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1), inverse);
    const auto unproject = [&](double wx, double wy, double ndcZ) {
      double ndc[4] = { 2.0 * wx / FilterWidth - 1.0, 2.0 * wy / FilterHeight - 1.0, ndcZ, 1.0 },
             world[4];
      inverse->MultiplyPoint(ndc, world);
      return std::array<double, 3>{ world[0] / world[3], world[1] / world[3], world[2] / world[3] };
    };
    vtkNew<vtkPoints> points;
    for (double angle : { 0.0, 2.1, 4.2 })
    {
      const auto p =
        unproject(px + 0.5 + 0.3 * std::cos(angle), py + 0.5 + 0.3 * std::sin(angle), 0.2);
      points->InsertNextPoint(p.data());
    }
    vtkNew<vtkCellArray> polys;
    const vtkIdType ids[3] = { 0, 1, 2 };
    polys->InsertNextCell(3, ids);
    vtkNew<vtkPolyData> triangle;
    triangle->SetPoints(points);
    triangle->SetPolys(polys);

    vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(triangle);
    filter->SetCamera(camera);
    filter->Update();
    vtkImageData* image = filter->GetOutput();
    SCOPED_TRACE("trial " + std::to_string(trial));
    EXPECT_EQ(FieldValue(image, "FacetCounts", "PixelsCovered"), 1.0);
    EXPECT_EQ(CellIdAt(image, px, py), 0) << "pixel " << px << ", " << py;
  }
}

//------------------------------------------------------------------------------
TEST(Camera, WithoutACameraTheViewIsResetToTheBounds)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(1000.0, -50.0, 3.0);
  sphere->SetRadius(0.01);
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputConnection(sphere->GetOutputPort());
  filter->SetSize(FilterWidth, FilterHeight);
  filter->Update();
  vtkImageData* image = filter->GetOutput();
  EXPECT_NE(CellIdAt(image, FilterWidth / 2, FilterHeight / 2), -1)
    << "the sphere is in the middle";
  EXPECT_EQ(CellIdAt(image, 2, 2), -1);
  const double covered = FieldValue(image, "FacetCounts", "PixelsCovered");
  EXPECT_GT(covered, 0.1 * FilterWidth * FilterHeight) << "and fills a good part of the view";
}

//------------------------------------------------------------------------------
// A unit square in the plane z = 3 far from the origin: fitted, a camera looking down -z
// sees it fill the view, and one looking down -x sees it edge-on; the camera set is kept.
TEST(Camera, FitCameraToInputKeepsTheCamerasDirection)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, 999.5, -50.5, 1000.5, -49.5, 3.0);
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputData(input);
  filter->SetSize(FilterWidth, FilterHeight);
  filter->FitCameraToInputOn();
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.0, 0.0, 5.0);
  filter->SetCamera(camera);
  filter->Update();
  const double facing = FieldValue(filter->GetOutput(), "FacetCounts", "PixelsCovered");
  EXPECT_GT(facing, 0.2 * FilterWidth * FilterHeight);
  EXPECT_NE(CellIdAt(filter->GetOutput(), FilterWidth / 2, FilterHeight / 2), -1);
  const double* position = camera->GetPosition();
  EXPECT_TRUE(position[0] == 0.0 && position[1] == 0.0 && position[2] == 5.0)
    << "the camera set was moved to " << position[0] << ", " << position[1] << ", " << position[2];

  camera->SetPosition(5.0, 0.0, 0.0);
  filter->Update();
  const double edgeOn = FieldValue(filter->GetOutput(), "FacetCounts", "PixelsCovered");
  EXPECT_LT(edgeOn, 0.01 * facing) << "facing " << facing;

  filter->FitCameraToInputOff(); // the camera as set: the square is 995 units off its axis
  camera->SetPosition(0.0, 0.0, 5.0);
  filter->Update();
  EXPECT_EQ(FieldValue(filter->GetOutput(), "FacetCounts", "PixelsCovered"), 0.0);
}

//------------------------------------------------------------------------------
TEST(Lights, HeadlightByDefaultAndNoneWhenTurnedOff)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, 10.0, 10.0, 150.0, 110.0);
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputData(input);
  filter->SetSize(FilterWidth, FilterHeight);
  filter->SetCamera(PixelCamera());
  filter->SetAmbientLightColor(0.0, 0.0, 0.0);
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 80, 60)[0], 255) << "facing the headlight: full";
  filter->AutomaticLightCreationOff();
  filter->Update();
  EXPECT_EQ(RgbaAt(filter->GetOutput(), 80, 60)[0], 0) << "no light, no ambient: black";
}

//------------------------------------------------------------------------------
TEST(Lights, FacetLightLinearSpotFalloff)
{
  // A big square facing +z lit by a spot 100 above its center pointing down; no attenuation.
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  for (int i = 0; i < 80; ++i) // strips of 1 unit, so each shades at its own distance
  {
    AddSquare(points, polys, i, 0.0, i + 1.0, FilterHeight);
  }
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  vtkNew<vtkFacetLight> spot;
  spot->SetLightTypeToSceneLight();
  spot->PositionalOn();
  spot->SetPosition(0.0, 60.0, 100.0);
  spot->SetFocalPoint(0.0, 60.0, 0.0);
  spot->SetSpotModelToLinearFalloff();
  spot->SetFullIntensityAngle(20.0);
  spot->SetFalloffAngle(15.0);
  spot->SetAttenuationValues(1.0, 0.0, 0.0);
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  filter->GetProperty()->SetAmbient(0.0);
  filter->GetProperty()->SetDiffuse(1.0);
  filter->AddLight(spot);
  filter->Update();
  for (int x = 0; x < 80; ++x)
  {
    const double center = x + 0.5;
    const double angle = vtkMath::DegreesFromRadians(std::atan(center / 100.0));
    const double cone = angle <= 20.0 ? 1.0 : angle >= 35.0 ? 0.0 : (35.0 - angle) / 15.0;
    const double expected = 255.0 * std::cos(vtkMath::RadiansFromDegrees(angle)) * cone;
    EXPECT_NEAR(RgbaAt(filter->GetOutput(), x, 60)[0], expected, 1.0) << "x " << x;
  }
}

//------------------------------------------------------------------------------
TEST(Errors, PointIdsOutOfRangeGiveAnErrorAndAnEmptyOutput)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, 10.0, 10.0, 70.0, 70.0);
  const vtkIdType bad[3] = { 0, 1, 99 };
  polys->InsertNextCell(3, bad);
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  MessageCounter errors(filter, vtkCommand::ErrorEvent);
  filter->Update();
  EXPECT_EQ(errors.Count, 1);
  EXPECT_NE(errors.Last.find("is 99, outside [0, points.count)"), std::string::npos) << errors.Last;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

// Found by the filter fuzzer: point colors were averaged per polygon (and per strip
// triangle) through the ids before anything checked them, reading out of bounds. Ids are now
// validated once per conversion, before coloring reads through them.
TEST(Errors, PointIdsOutOfRangeWithPointColorsGiveAnErrorAndAnEmptyOutput)
{
  for (const bool strip : { false, true })
  {
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(0, 0, 0);
    points->InsertNextPoint(1, 0, 0);
    points->InsertNextPoint(0, 1, 0);
    vtkNew<vtkCellArray> cells;
    const vtkIdType bad[3] = { 0, 1, 1000000 };
    cells->InsertNextCell(3, bad);
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetNumberOfComponents(4);
    colors->SetNumberOfTuples(3);
    colors->Fill(255);
    vtkNew<vtkPolyData> input;
    input->SetPoints(points);
    if (strip)
    {
      input->SetStrips(cells);
    }
    else
    {
      input->SetPolys(cells);
    }
    input->GetPointData()->SetScalars(colors);
    vtkNew<vtkFacetRenderFilter> filter;
    filter->SetInputData(input);
    filter->SetSize(8, 8);
    MessageCounter errors(filter, vtkCommand::ErrorEvent);
    filter->Update();
    EXPECT_EQ(errors.Count, 1) << (strip ? "strip" : "polygon");
    EXPECT_NE(errors.Last.find("is 1000000, outside [0, points.count)"), std::string::npos)
      << errors.Last;
    EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  }
}

TEST(Errors, BadSizeGivesAnError)
{
  vtkNew<vtkPolyData> input;
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  MessageCounter errors(filter, vtkCommand::ErrorEvent);
  filter->SetSize(0, 100);
  filter->Update();
  EXPECT_GE(errors.Count, 1);
  EXPECT_NE(errors.Last.find("Size is 0 x 100"), std::string::npos) << errors.Last;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  filter->SetSize(20000, 10);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

// Issue 7: SetNumberOfThreads(-3) used to mean "all cores" without a word.
TEST(Errors, ThreadCountsOutsideTheRangeAreRefusedAndKeepThePreviousOne)
{
  vtkNew<vtkFacetRenderFilter> filter;
  MessageCounter errors(filter, vtkCommand::ErrorEvent);
  filter->SetNumberOfThreads(2);
  EXPECT_EQ(errors.Count, 0);
  const vtkMTimeType time = filter->GetMTime();
  for (int bad : { -3, -1, 1025 })
  {
    filter->SetNumberOfThreads(bad);
    EXPECT_EQ(filter->GetNumberOfThreads(), 2) << bad;
    EXPECT_NE(
      errors.Last.find("SetNumberOfThreads(" + std::to_string(bad) + ")"), std::string::npos)
      << errors.Last;
  }
  EXPECT_EQ(errors.Count, 3);
  EXPECT_EQ(filter->GetMTime(), time) << "nothing changed";
  filter->SetNumberOfThreads(0);
  EXPECT_EQ(filter->GetNumberOfThreads(), 0);
  EXPECT_EQ(errors.Count, 3);
}

TEST(Errors, NonFinitePointsSkipTheirCellsWithOneWarning)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  AddSquare(points, polys, 10.0, 10.0, 70.0, 70.0);
  AddSquare(points, polys, 90.0, 10.0, 150.0, 70.0);
  points->SetPoint(5, std::numeric_limits<double>::quiet_NaN(), 10.0, 0.0);
  vtkSmartPointer<vtkPolyData> input = PolyData(points, polys);
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  MessageCounter warnings(filter, vtkCommand::WarningEvent);
  filter->Update();
  EXPECT_EQ(warnings.Count, 1);
  EXPECT_NE(warnings.Last.find("skipped 1 cells"), std::string::npos) << warnings.Last;
  EXPECT_EQ(CellIdAt(filter->GetOutput(), 40, 40), 0);
  EXPECT_EQ(CellIdAt(filter->GetOutput(), 120, 40), -1);
}

TEST(Errors, EmptyInputGivesTheBackground)
{
  vtkNew<vtkPolyData> input;
  vtkSmartPointer<vtkFacetRenderFilter> filter = UnlitFilter(input);
  filter->SetBackground(0.2, 0.4, 0.6);
  filter->Update();
  vtkImageData* image = filter->GetOutput();
  EXPECT_EQ(image->GetNumberOfPoints(), FilterWidth * FilterHeight);
  EXPECT_EQ(RgbaAt(image, 3, 3), (std::array<int, 4>{ 51, 102, 153, 255 }));
  EXPECT_EQ(CellIdAt(image, 3, 3), -1);
}

//------------------------------------------------------------------------------
TEST(Output, ArraysExtentAndDeterminism)
{
  vtkSmartPointer<vtkPolyData> strips = StripSphere();
  vtkNew<vtkFacetRenderFilter> one, two;
  for (vtkFacetRenderFilter* filter : { one.Get(), two.Get() })
  {
    filter->SetInputData(strips);
    filter->SetSize(FilterWidth, FilterHeight);
    filter->SetCamera(PixelCamera());
  }
  one->SetNumberOfThreads(1);
  two->SetNumberOfThreads(2);
  one->Update();
  two->Update();
  vtkImageData* image = one->GetOutput();
  int extent[6];
  image->GetExtent(extent);
  EXPECT_EQ(extent[1], FilterWidth - 1);
  EXPECT_EQ(extent[3], FilterHeight - 1);
  EXPECT_EQ(extent[5], 0);
  EXPECT_STREQ(image->GetPointData()->GetScalars()->GetName(), "RGBA");
  EXPECT_TRUE(vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Depth")));
  EXPECT_TRUE(vtkIdTypeArray::SafeDownCast(image->GetPointData()->GetArray("CellId")));
  for (const char* name : { "RGBA", "Depth", "CellId" })
  {
    vtkDataArray* a = image->GetPointData()->GetArray(name);
    vtkDataArray* b = two->GetOutput()->GetPointData()->GetArray(name);
    const vtkIdType bytes = a->GetNumberOfValues() * a->GetDataTypeSize();
    EXPECT_EQ(std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0), bytes), 0) << name;
  }
  EXPECT_NE(std::string(one->GetRenderPlan()).find("z-buffer"), std::string::npos);
}

//------------------------------------------------------------------------------
// PrintSelf names the coloring settings (held by the coloring mapper) with their values,
// between the property and the thread count.
TEST(Output, PrintSelfShowsTheColoringSettingsInPlace)
{
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SelectColorArray("Elevation");
  filter->SetScalarRange(2.0, 3.0);
  filter->SetScalarModeToUseCellFieldData();
  std::ostringstream printed;
  filter->Print(printed);
  const std::string text = printed.str();
  const std::size_t property = text.find("Property: "),
                    mode = text.find("ScalarMode: UseCellFieldData\n"),
                    name = text.find("ArrayName: Elevation\n"),
                    range = text.find("ScalarRange: (2, 3)\n"),
                    threads = text.find("NumberOfThreads: 0\n");
  ASSERT_NE(threads, std::string::npos) << text;
  EXPECT_LT(property, mode) << text;
  EXPECT_LT(mode, name) << text;
  EXPECT_LT(name, range) << text;
  EXPECT_LT(range, threads) << text;
}

//------------------------------------------------------------------------------
// CellId is written band by band as the render resolves them, unless the render drew a
// sample grid (SamplesPerPixel) or stopped: then by a pass over the image. Either way every
// pixel's cell is the one drawn there (covered exactly where the depth is below 1), the
// error estimate does not change it, and a render stopped while resolving leaves only
// background ids.
TEST(Output, CellIdsAreTheCellsDrawnInEveryModeAndAfterAStop)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(48);
  sphere->Update();
  const vtkIdType cells = sphere->GetOutput()->GetNumberOfCells();
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputConnection(sphere->GetOutputPort());
  filter->SetSize(FilterWidth, FilterHeight);
  filter->SetNumberOfThreads(2);
  const auto cellIdsOf = [&] {
    vtkImageData* image = filter->GetOutput();
    auto* ids = vtkIdTypeArray::SafeDownCast(image->GetPointData()->GetArray("CellId"));
    auto* depth = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Depth"));
    std::vector<vtkIdType> values(
      ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfValues());
    for (vtkIdType i = 0; i < ids->GetNumberOfValues(); ++i)
    {
      const bool covered = depth->GetValue(i) < 1.0f;
      EXPECT_EQ(values[i] >= 0, covered) << "pixel " << i;
      EXPECT_LT(values[i], cells);
      EXPECT_GE(values[i], -1);
      if (::testing::Test::HasFailure())
      {
        break;
      }
    }
    return values;
  };
  std::vector<vtkIdType> estimated, plain;
  for (const bool estimate : { true, false })
  {
    SCOPED_TRACE(estimate ? "estimate" : "no estimate");
    filter->SetEstimateError(estimate);
    filter->Update();
    (estimate ? estimated : plain) = cellIdsOf();
  }
  EXPECT_EQ(estimated, plain);
  EXPECT_GT(std::count_if(plain.begin(), plain.end(), [](vtkIdType id) { return id >= 0; }), 1000);
  filter->SetSamplesPerPixel(4);
  filter->Update();
  const std::vector<vtkIdType> sampled = cellIdsOf();
  EXPECT_GT(
    std::count_if(sampled.begin(), sampled.end(), [](vtkIdType id) { return id >= 0; }), 1000);

  // Stopped while the resolve runs (progress 0.905 to 0.95 of the Update), and at its very end
  // (0.95: every band written, then the render stops and clears the image). One thread: the
  // caller resolves every band, so it reports each.
  filter->SetSamplesPerPixel(1);
  filter->SetNumberOfThreads(1);
  filter->IncrementalRenderingOff();
  for (double threshold : { 0.92, 0.949 })
  {
    SCOPED_TRACE(threshold);
    vtkNew<vtkCallbackCommand> stop;
    stop->SetClientData(&threshold);
    stop->SetCallback([](vtkObject* caller, unsigned long, void* data, void* fraction) {
      if (*static_cast<double*>(fraction) > *static_cast<double*>(data))
      {
        vtkAlgorithm::SafeDownCast(caller)->SetAbortExecute(1);
      }
    });
    const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, stop);
    filter->Modified();
    filter->Update();
    filter->SetAbortExecute(0);
    filter->RemoveObserver(tag);
    EXPECT_EQ(FieldValue(filter->GetOutput(), "FacetCounts", "PixelsCovered"), 0.0);
    const std::vector<vtkIdType> stopped = cellIdsOf();
    EXPECT_EQ(std::count(stopped.begin(), stopped.end(), vtkIdType{ -1 }),
      static_cast<std::ptrdiff_t>(stopped.size()));
  }
}

//------------------------------------------------------------------------------
// CellId of polys after verts and lines, pixel by pixel against the grid of squares drawn: in
// an image whose CellId plane is streamed past the caches (facet::kStreamedPlaneBytes or more,
// an odd width so that bands start at every alignment) and in one stored plainly.
TEST(Output, CellIdsOfPolysAfterVertsAndLinesInLargeAndSmallImages)
{
  constexpr int side = 4; // each square covers side × side pixel centers
  for (const auto& [width, height] : { std::pair{ 1031, 1030 }, std::pair{ 160, 120 } })
  {
    SCOPED_TRACE(std::to_string(width) + " x " + std::to_string(height));
    const bool streamed =
      static_cast<std::size_t>(width) * height * sizeof(vtkIdType) >= facet::kStreamedPlaneBytes;
    EXPECT_EQ(streamed, width > 1000);
    const int columns = (width - 13) / side, rows = (height - 7) / side; // background beyond
    vtkSmartPointer<vtkPolyData> data = SquareGridAfterVertsAndALine(columns, rows, side, 2);
    vtkNew<vtkFacetRenderFilter> filter;
    filter->SetInputData(data);
    filter->SetSize(width, height);
    filter->SetCamera(facet_test::PixelCamera(width, height));
    filter->SetNumberOfThreads(2);
    filter->Update();
    vtkImageData* image = filter->GetOutput();
    std::size_t differing = 0;
    for (int y = 0; y < height; ++y)
    {
      for (int x = 0; x < width; ++x)
      {
        const int i = x / side, j = y / side;
        const vtkIdType expected = i < columns && j < rows ? 3 + j * columns + i : -1;
        const vtkIdType cellId = CellIdAt(image, x, y);
        if (cellId != expected && ++differing <= 5)
        {
          ADD_FAILURE() << "pixel " << x << ", " << y << ": " << cellId << ", expected "
                        << expected;
        }
      }
    }
    EXPECT_EQ(differing, 0u);
  }
}

//------------------------------------------------------------------------------
TEST(Caching, ANewCameraReusesTheConvertedMesh)
{
  vtkSmartPointer<vtkPolyData> strips = StripSphere();
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputData(strips);
  filter->SetSize(FilterWidth, FilterHeight);
  vtkSmartPointer<vtkCamera> camera = PixelCamera();
  filter->SetCamera(camera);
  filter->Update();
  EXPECT_EQ(FieldValue(filter->GetOutput(), "FacetMeshConverted", "Converted"), 1.0);
  camera->Azimuth(10.0);
  filter->Update();
  EXPECT_EQ(FieldValue(filter->GetOutput(), "FacetMeshConverted", "Converted"), 0.0)
    << "only the camera changed";
  strips->GetPoints()->SetPoint(0, 80.0, 60.0, 45.0);
  strips->Modified();
  filter->Update();
  EXPECT_EQ(FieldValue(filter->GetOutput(), "FacetMeshConverted", "Converted"), 1.0)
    << "the input changed";
}

//------------------------------------------------------------------------------
// The execution builds the lookup table and gives it the scalar range: that is not a change
// that renders again; the user's change to the table is.
TEST(Caching, PreparingTheLookupTableIsNoChangeButChangingItIs)
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkLookupTable> table; // not built; its range (0, 1) becomes (-1, 2)
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputConnection(elevation->GetOutputPort());
  filter->SetSize(FilterWidth, FilterHeight);
  filter->SetLookupTable(table);
  filter->SetScalarRange(-1.0, 2.0);
  ExecutionCounter executions(filter);
  filter->Update();
  filter->Update();
  EXPECT_EQ(executions.Count, 1);
  EXPECT_EQ(table->GetRange()[0], -1.0);
  table->SetHueRange(0.2, 0.3);
  filter->Update();
  EXPECT_EQ(executions.Count, 2);
  filter->Update();
  EXPECT_EQ(executions.Count, 2);
}

//------------------------------------------------------------------------------
TEST(Progress, ReportedAndAbortable)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(300);
  sphere->SetPhiResolution(300);
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputConnection(sphere->GetOutputPort());
  filter->SetSize(400, 300);
  ExpectProgressReportedAndAbortable(filter, 400, 300, [&] {
    filter->IncrementalRenderingOff();
    filter->Modified();
  });
}
