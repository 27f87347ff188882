// vtkFacetRendererToImageFilter without an X server: what a vtkRenderer holds becomes the
// image (actors under their full matrices, ids, composite data, coloring, lights,
// background, camera, size), what Facet cannot render is named once, and Update renders
// again exactly when the scene changed. VTK's OpenGL mappers are linked only for their
// factory (vtkPolyDataMapper::New); no window is opened.

#include "AdapterTestUtilities.h"

#include "vtkActor.h"
#include "vtkActor2D.h"
#include "vtkAssembly.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkCompositePolyDataMapper.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDoubleArray.h"
#include "vtkFacetRendererToImageFilter.h"
#include "vtkImageActor.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLookupTable.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkVolume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <set>
#include <string>

using namespace facet_test;

namespace {
constexpr int Width = 160, Height = 120;

vtkSmartPointer<vtkActor> ActorOf(vtkPolyData* data)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetInterpolationToFlat();
  return actor;
}

// Squares [x0, x1] × [y0, y1] at height z, one cell each.
vtkSmartPointer<vtkPolyData> Squares(std::initializer_list<std::array<double, 5>> squares)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  for (const auto& s : squares)
  {
    AddSquare(points, polys, s[0], s[1], s[2], s[3], s[4]);
  }
  return PolyData(points, polys);
}

// A renderer showing the surface colors exactly: the pixel camera, no light (VTK shows
// Ka·Ca + Kd·Cd unlit), a black background.
vtkSmartPointer<vtkRenderer> UnlitRenderer()
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetActiveCamera(PixelCamera(Width, Height));
  renderer->AutomaticLightCreationOff();
  return renderer;
}

vtkSmartPointer<vtkFacetRendererToImageFilter> Grab(vtkRenderer* renderer)
{
  auto grab = vtkSmartPointer<vtkFacetRendererToImageFilter>::New();
  grab->SetRenderer(renderer);
  grab->SetSize(Width, Height);
  return grab;
}

vtkSmartPointer<vtkPolyData> Sphere(double radius, int resolution = 24)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution);
  sphere->SetRadius(radius);
  sphere->Update();
  return sphere->GetOutput();
}

// The same bytes in an array of both images.
void ExpectSameArray(vtkImageData* a, vtkImageData* b, const char* name)
{
  vtkDataArray* x = a->GetPointData()->GetArray(name);
  vtkDataArray* y = b->GetPointData()->GetArray(name);
  ASSERT_TRUE(x && y) << name;
  ASSERT_EQ(x->GetNumberOfValues(), y->GetNumberOfValues()) << name;
  long different = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfValues(); ++i)
  {
    different += x->GetVariantValue(i) != y->GetVariantValue(i);
  }
  EXPECT_EQ(different, 0) << name << " values differ";
}

long Covered(vtkImageData* image)
{
  long covered = 0;
  for (int y = 0; y < image->GetDimensions()[1]; ++y)
  {
    for (int x = 0; x < image->GetDimensions()[0]; ++x)
    {
      covered += CellIdAt(image, x, y) >= 0;
    }
  }
  return covered;
}
}

//------------------------------------------------------------------------------
TEST(Actors, ActorIdIsThePropIndexAndCellIdTheCellOfItsPolyData)
{
  vtkSmartPointer<vtkRenderer> renderer = UnlitRenderer();
  vtkSmartPointer<vtkActor> first =
    ActorOf(Squares({ { 10, 10, 50, 50, 0 }, { 60, 10, 100, 50, 0 } }));
  vtkSmartPointer<vtkActor> second =
    ActorOf(Squares({ { 20, 60, 40, 110, 0 }, { 40, 30, 80, 70, 5 } }));
  vtkSmartPointer<vtkActor> hidden = ActorOf(Squares({ { 120, 10, 150, 110, 0 } }));
  hidden->VisibilityOff();
  renderer->AddActor(first);                              // prop 0
  renderer->AddVolume(vtkSmartPointer<vtkVolume>::New()); // prop 1: skipped
  renderer->AddActor(second);                             // prop 2
  renderer->AddActor(hidden);                             // prop 3: invisible
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  MessageCounter warnings(grab, vtkCommand::WarningEvent);
  MessageCounter errors(grab, vtkCommand::ErrorEvent);
  grab->Update();
  vtkImageData* image = grab->GetOutput();
  EXPECT_EQ(errors.Count, 0) << errors.Last;
  EXPECT_EQ(ActorIdAt(image, 15, 15), 0);
  EXPECT_EQ(CellIdAt(image, 15, 15), 0);
  EXPECT_EQ(ActorIdAt(image, 90, 15), 0);
  EXPECT_EQ(CellIdAt(image, 90, 15), 1);
  EXPECT_EQ(ActorIdAt(image, 25, 100), 2);
  EXPECT_EQ(CellIdAt(image, 25, 100), 0);
  EXPECT_EQ(ActorIdAt(image, 45, 45), 2) << "the second actor's square is nearer";
  EXPECT_EQ(CellIdAt(image, 45, 45), 1);
  EXPECT_EQ(ActorIdAt(image, 130, 60), -1) << "invisible";
  EXPECT_EQ(CellIdAt(image, 130, 60), -1);
  EXPECT_EQ(ActorIdAt(image, 5, 115), -1);
  EXPECT_EQ(warnings.Count, 1);
  EXPECT_NE(warnings.Last.find("Volume"), std::string::npos) << warnings.Last;
  EXPECT_EQ(warnings.Last.find("Visibility"), std::string::npos) << warnings.Last;
}

//------------------------------------------------------------------------------
// One actor (its cell ids straight from its converter, streamed in a large image) and the
// same with a second actor beside it (the lookup per pixel): ActorId and CellId pixel by
// pixel against the grid of squares drawn, polys after a vertex and a line, at 1031 × 1030
// and 160 × 120.
TEST(Actors, OneActorsCellIdsAreItsCellsInLargeAndSmallImages)
{
  constexpr int side = 4; // each square covers side × side pixel centers
  for (const auto& [width, height] : { std::pair{ 1031, 1030 }, std::pair{ Width, Height } })
  {
    for (const bool twoActors : { false, true })
    {
      SCOPED_TRACE(std::to_string(width) + (twoActors ? ", two actors" : ", one actor"));
      const int columns = (width - 13) / side, rows = (height - 7) / side;
      vtkSmartPointer<vtkPolyData> data = SquareGridAfterVertsAndALine(columns, rows, side, 1);
      auto renderer = vtkSmartPointer<vtkRenderer>::New();
      renderer->SetActiveCamera(PixelCamera(width, height));
      renderer->AutomaticLightCreationOff();
      if (twoActors) // prop 0: a square in the top right corner, the grid is prop 1
      {
        renderer->AddActor(
          ActorOf(Squares({ { width - 10.0, height - 5.0, width - 2.0, height - 1.0, 0 } })));
      }
      renderer->AddActor(ActorOf(data));
      vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
      grab->SetSize(width, height);
      grab->Update();
      vtkImageData* image = grab->GetOutput();
      const int gridActor = twoActors ? 1 : 0;
      std::size_t differing = 0;
      for (int y = 0; y < height; ++y)
      {
        for (int x = 0; x < width; ++x)
        {
          const int i = x / side, j = y / side;
          const bool grid = i < columns && j < rows;
          const bool corner =
            twoActors && x >= width - 10 && x < width - 2 && y >= height - 5 && y < height - 1;
          const vtkIdType cell = grid ? 2 + j * columns + i : corner ? 0 : -1;
          const int actor = grid ? gridActor : corner ? 0 : -1;
          if ((CellIdAt(image, x, y) != cell || ActorIdAt(image, x, y) != actor) &&
            ++differing <= 5)
          {
            ADD_FAILURE() << "pixel " << x << ", " << y << ": cell " << CellIdAt(image, x, y)
                          << ", actor " << ActorIdAt(image, x, y) << "; expected " << cell << ", "
                          << actor;
          }
        }
      }
      EXPECT_EQ(differing, 0u);
    }
  }
}

//------------------------------------------------------------------------------
// An actor's full matrix renders as its points transformed by vtkTransform (in double) and
// rendered by vtkFacetRenderFilter: the same bytes, for a general matrix and for one that
// mirrors a closed surface (whose back faces may then not be skipped).
TEST(Transform, FullMatrixRendersAsTheTransformedPointsToTheBit)
{
  vtkSmartPointer<vtkPolyData> sphere = Sphere(20.0);
  vtkNew<vtkMatrix4x4> user;
  user->SetElement(0, 1, 0.3); // a shear
  user->SetElement(1, 3, 4.0);
  vtkNew<vtkTransform> userTransform;
  userTransform->RotateZ(10.0);
  for (bool mirror : { false, true })
  {
    SCOPED_TRACE(mirror ? "mirrored" : "general");
    vtkSmartPointer<vtkActor> actor = ActorOf(sphere);
    actor->SetOrigin(3.0, -2.0, 1.0);
    actor->SetPosition(80.0, 55.0, -10.0);
    actor->SetOrientation(20.0, -35.0, 50.0);
    actor->SetScale(mirror ? -1.5 : 1.5, 0.8, 1.1);
    if (mirror)
    {
      actor->SetUserTransform(userTransform);
    }
    else
    {
      actor->SetUserMatrix(user);
    }
    actor->GetMapper()->ScalarVisibilityOff();
    vtkNew<vtkRenderer> renderer;
    renderer->SetActiveCamera(PixelCamera(Width, Height));
    renderer->AddActor(actor);
    vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
    grab->Update();

    vtkNew<vtkTransform> matrix;
    matrix->SetMatrix(actor->GetMatrix());
    vtkNew<vtkPoints> world;
    world->SetDataTypeToDouble();
    matrix->TransformPoints(sphere->GetPoints(), world);
    vtkNew<vtkPolyData> transformed;
    transformed->ShallowCopy(sphere);
    transformed->SetPoints(world);
    vtkNew<vtkFacetRenderFilter> filter;
    filter->SetInputData(transformed);
    filter->SetSize(Width, Height);
    filter->SetCamera(renderer->GetActiveCamera());
    filter->SetAmbientLightColor(0.0, 0.0, 0.0); // VTK's renderer has none
    filter->SetProperty(actor->GetProperty());
    filter->ScalarVisibilityOff();
    filter->Update();

    EXPECT_GT(Covered(grab->GetOutput()), 1000);
    for (const char* name : { "RGBA", "Depth", "CellId" })
    {
      ExpectSameArray(grab->GetOutput(), filter->GetOutput(), name);
    }
  }
}

//------------------------------------------------------------------------------
TEST(Transform, AssemblyPartsTakeTheAssemblysMatrixAndIndex)
{
  vtkSmartPointer<vtkRenderer> renderer = UnlitRenderer();
  vtkSmartPointer<vtkActor> alone = ActorOf(Squares({ { 0, 0, 20, 20, 0 } }));
  vtkSmartPointer<vtkActor> part = ActorOf(Squares({ { 0, 0, 20, 20, 0 } }));
  part->SetPosition(30.0, 0.0, 0.0);
  vtkNew<vtkAssembly> assembly;
  assembly->AddPart(part);
  assembly->SetPosition(50.0, 40.0, 0.0);
  renderer->AddActor(alone);
  renderer->AddActor(assembly);
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  grab->Update();
  vtkImageData* image = grab->GetOutput();
  EXPECT_EQ(ActorIdAt(image, 10, 10), 0);
  EXPECT_EQ(ActorIdAt(image, 90, 50), 1) << "the part, moved by its and the assembly's position";
  EXPECT_EQ(CellIdAt(image, 90, 50), 0);
  EXPECT_EQ(ActorIdAt(image, 60, 50), -1);
  EXPECT_EQ(ActorIdAt(image, 101, 50), -1);
}

//------------------------------------------------------------------------------
// Both composite mappers: every polydata block rendered with its own cell colors and ids,
// other blocks skipped with a warning that names them.
TEST(Composite, PolyDataBlocksRenderWithTheirCellsAndColors)
{
  vtkNew<vtkLookupTable> table;
  table->SetHueRange(0.667, 0.0);
  table->SetNumberOfTableValues(16);
  table->Build();
  vtkNew<vtkLookupTable> twin;
  twin->DeepCopy(table);
  twin->SetRange(0.0, 10.0);
  vtkNew<vtkMultiBlockDataSet> blocks;
  double value = 1.0;
  for (unsigned block : { 0u, 2u })
  {
    const double x = block == 0 ? 10.0 : 90.0;
    vtkSmartPointer<vtkPolyData> squares =
      Squares({ { x, 10, x + 50, 50, 0 }, { x, 60, x + 50, 100, 0 } });
    vtkNew<vtkDoubleArray> values;
    values->InsertNextValue(value);
    values->InsertNextValue(value + 3.0);
    value += 5.0;
    squares->GetCellData()->SetScalars(values);
    blocks->SetBlock(block, squares);
  }
  blocks->SetBlock(1, vtkSmartPointer<vtkImageData>::New());
  vtkSmartPointer<vtkMapper> mappers[] = { vtkSmartPointer<vtkCompositePolyDataMapper>::New(),
    vtkSmartPointer<vtkCompositePolyDataMapper2>::New() };
  for (vtkMapper* mapper : mappers)
  {
    SCOPED_TRACE(mapper->GetClassName());
    mapper->SetInputDataObject(blocks);
    mapper->SetLookupTable(table);
    mapper->SetScalarRange(0.0, 10.0);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetInterpolationToFlat();
    vtkSmartPointer<vtkRenderer> renderer = UnlitRenderer();
    renderer->AddActor(actor);
    vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
    MessageCounter warnings(grab, vtkCommand::WarningEvent);
    grab->Update();
    vtkImageData* image = grab->GetOutput();
    EXPECT_EQ(warnings.Count, 1);
    EXPECT_NE(warnings.Last.find("skipped data of type vtkImageData"), std::string::npos)
      << warnings.Last;
    const int xs[] = { 30, 110 }, ys[] = { 30, 80 };
    for (int block = 0; block < 2; ++block)
    {
      for (int cell = 0; cell < 2; ++cell)
      {
        const double scalar = 1.0 + 5.0 * block + 3.0 * cell;
        EXPECT_EQ(ActorIdAt(image, xs[block], ys[cell]), 0);
        EXPECT_EQ(CellIdAt(image, xs[block], ys[cell]), cell) << "block " << block;
        const unsigned char* color = twin->MapValue(scalar);
        const std::array<int, 4> pixel = RgbaAt(image, xs[block], ys[cell]);
        for (int c = 0; c < 3; ++c)
        {
          EXPECT_EQ(pixel[c], color[c]) << "block " << block << " cell " << cell;
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
// The mapper's coloring takes the path the filter's coloring takes: the same image.
TEST(Coloring, AMappersSettingsColorAsTheFiltersSame)
{
  vtkSmartPointer<vtkPolyData> squares = Squares({ { 10, 10, 50, 50, 0 },
    { 60, 10, 100, 50, 0 },
    { 10, 60, 50, 100, 0 },
    { 60, 60, 100, 100, 0 } });
  vtkNew<vtkDoubleArray> temperature;
  temperature->SetName("temperature");
  temperature->SetNumberOfComponents(2);
  for (int i = 0; i < 4; ++i)
  {
    temperature->InsertNextTuple2(10.0 * i, -3.0 * i);
  }
  squares->GetCellData()->AddArray(temperature); // not the active scalars
  vtkNew<vtkLookupTable> table;
  table->SetHueRange(0.1, 0.9);
  vtkSmartPointer<vtkActor> actor = ActorOf(squares);
  vtkMapper* mapper = actor->GetMapper();
  mapper->SetScalarModeToUseCellFieldData();
  mapper->ColorByArrayComponent("temperature", 1);
  mapper->SetLookupTable(table);
  mapper->SetScalarRange(-10.0, 0.0);
  vtkSmartPointer<vtkRenderer> renderer = UnlitRenderer();
  renderer->AddActor(actor);
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  grab->Update();

  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputData(squares);
  filter->SetSize(Width, Height);
  filter->SetCamera(renderer->GetActiveCamera());
  filter->AutomaticLightCreationOff();
  filter->SetAmbientLightColor(0.0, 0.0, 0.0);
  filter->SetProperty(actor->GetProperty());
  filter->GetProperty()->LightingOff(); // unlit, as the renderer without lights
  filter->SetScalarModeToUseCellFieldData();
  filter->SelectColorArray("temperature");
  filter->SetArrayComponent(1);
  filter->SetLookupTable(table);
  filter->SetScalarRange(-10.0, 0.0);
  filter->Update();
  ExpectSameArray(grab->GetOutput(), filter->GetOutput(), "RGBA");
  EXPECT_NE(RgbaAt(grab->GetOutput(), 30, 30), RgbaAt(grab->GetOutput(), 80, 80));
}

//------------------------------------------------------------------------------
// With no light switched on, VTK creates a headlight (AutomaticLightCreation) or shows the
// unlit colors Ka·Ca + Kd·Cd; the property's Lighting off shows those too. The renderer
// is not given a light.
TEST(Lights, WithoutALightOnVtksHeadlightOrTheUnlitColors)
{
  vtkSmartPointer<vtkActor> actor = ActorOf(Squares({ { 10, 10, 150, 110, 0 } }));
  vtkProperty* property = actor->GetProperty();
  property->SetAmbient(0.2);
  property->SetAmbientColor(1.0, 0.0, 0.0);
  property->SetDiffuse(0.5);
  property->SetDiffuseColor(0.0, 1.0, 0.0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetActiveCamera(PixelCamera(Width, Height));
  renderer->AddActor(actor);
  vtkNew<vtkLight> off;
  off->SwitchOff();
  renderer->AddLight(off);
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  const std::array<int, 4> headlit{ 51, 128, 0, 255 }; // Ka·Ca + Kd·Cd·cos 0
  const std::array<int, 4> unlit{ 51, 128, 0, 255 };   // Ka·Ca + Kd·Cd
  grab->Update();
  EXPECT_EQ(RgbaAt(grab->GetOutput(), 80, 60), headlit);
  EXPECT_EQ(renderer->GetLights()->GetNumberOfItems(), 1) << "no light added";

  // Headlit and unlit differ once the square is turned from the light.
  actor->SetOrigin(80.0, 60.0, 0.0);
  actor->SetOrientation(0.0, 60.0, 0.0);
  grab->Update();
  const std::array<int, 4> turned = RgbaAt(grab->GetOutput(), 80, 60);
  EXPECT_EQ(turned, (std::array<int, 4>{ 51, 64, 0, 255 })) << "Kd·Cd·cos 60°";
  renderer->AutomaticLightCreationOff();
  grab->Update();
  EXPECT_EQ(RgbaAt(grab->GetOutput(), 80, 60), unlit);
  renderer->AutomaticLightCreationOn();
  property->LightingOff();
  grab->Update();
  EXPECT_EQ(RgbaAt(grab->GetOutput(), 80, 60), unlit);
}

//------------------------------------------------------------------------------
// VTK 9.1's gradient: a quad with Background (truncated to bytes) at the bottom corners and
// Background2 at the top, interpolated at pixel centers.
TEST(Background, GradientIsResolvedPerRowAndAlphaIsOpaqueWithoutAlphaPlanes)
{
  vtkSmartPointer<vtkRenderer> renderer = UnlitRenderer();
  renderer->AddActor(ActorOf(Squares({ { 60, 40, 100, 80, 0 } })));
  renderer->GradientBackgroundOn();
  renderer->SetBackground(0.0, 1.0, 0.2);
  renderer->SetBackground2(1.0, 0.0, 0.7);
  renderer->SetBackgroundAlpha(0.0);
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  grab->Update();
  vtkImageData* image = grab->GetOutput();
  for (int y = 0; y < Height; ++y)
  {
    const double t = (y + 0.5) / Height;
    const std::array<int, 4> expected{ static_cast<int>(std::lround(255.0 * t)),
      static_cast<int>(std::lround(255.0 * (1.0 - t))),
      static_cast<int>(std::lround(51.0 + (178.0 - 51.0) * t)),
      255 };
    ASSERT_EQ(RgbaAt(image, 3, y), expected) << "row " << y;
    ASSERT_EQ(RgbaAt(image, Width - 1, y), expected) << "row " << y;
  }
  EXPECT_EQ(ActorIdAt(image, 80, 60), 0);
  EXPECT_EQ(RgbaAt(image, 80, 60), (std::array<int, 4>{ 255, 255, 255, 255 })) << "unlit white";
}

//------------------------------------------------------------------------------
// A renderer without a camera gets one as vtkRenderer::Render gives it (ResetCamera on the
// visible props), fitted for the image's aspect: the automatic camera of the filter.
TEST(Camera, ARendererWithoutOneGetsTheCameraRenderWouldGiveIt)
{
  vtkSmartPointer<vtkPolyData> sphere = Sphere(3.0);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(ActorOf(sphere));
  ASSERT_FALSE(renderer->IsActiveCameraCreated());
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  grab->SetSize(90, 160); // portrait: the fit depends on the aspect
  grab->Update();
  ASSERT_TRUE(renderer->IsActiveCameraCreated());
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkNew<vtkCamera> expected;
  vtkFacetRenderFilter::ResetCamera(expected, sphere, 90, 160);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(camera->GetPosition()[i], expected->GetPosition()[i]);
    EXPECT_EQ(camera->GetFocalPoint()[i], expected->GetFocalPoint()[i]);
  }
  EXPECT_EQ(camera->GetClippingRange()[0], expected->GetClippingRange()[0]);
  EXPECT_EQ(camera->GetClippingRange()[1], expected->GetClippingRange()[1]);
  EXPECT_GT(Covered(grab->GetOutput()), 1500) << "the whole sphere, its bounds fitted";
}

//------------------------------------------------------------------------------
TEST(Size, TheRenderersSizeInItsWindowElse640x480)
{
  vtkSmartPointer<vtkRenderer> renderer = UnlitRenderer();
  renderer->AddActor(ActorOf(Squares({ { 10, 10, 50, 50, 0 } })));
  vtkNew<vtkFacetRendererToImageFilter> grab;
  grab->SetRenderer(renderer);
  int size[2];
  grab->GetEffectiveSize(size);
  EXPECT_EQ(size[0], 640);
  EXPECT_EQ(size[1], 480);
  vtkNew<vtkRenderWindow> window; // never shown: only its size is read
  window->AddRenderer(renderer);
  window->SetSize(300, 200);
  grab->Update();
  int dimensions[3];
  grab->GetOutput()->GetDimensions(dimensions);
  EXPECT_EQ(dimensions[0], 300);
  EXPECT_EQ(dimensions[1], 200);
  renderer->SetViewport(0.0, 0.0, 0.5, 1.0);
  grab->Update();
  grab->GetOutput()->GetDimensions(dimensions);
  EXPECT_EQ(dimensions[0], 150) << "the renderer's viewport";
  grab->SetSize(64, 32);
  grab->Update();
  grab->GetOutput()->GetDimensions(dimensions);
  EXPECT_EQ(dimensions[0], 64);
  EXPECT_EQ(dimensions[1], 32);
  window->RemoveRenderer(renderer);
}

//------------------------------------------------------------------------------
// One warning names every kind of prop and feature Facet cannot render, once; the actors
// after the skipped props keep their indices.
TEST(Warnings, UnrenderablePropsAndFeaturesAreNamedOnce)
{
  vtkSmartPointer<vtkRenderer> renderer = UnlitRenderer();
  renderer->AddViewProp(vtkSmartPointer<vtkVolume>::New());
  renderer->AddViewProp(vtkSmartPointer<vtkActor2D>::New());
  renderer->AddViewProp(vtkSmartPointer<vtkImageActor>::New());
  vtkSmartPointer<vtkActor> actor = ActorOf(Squares({ { 10, 10, 50, 50, 0 } }));
  actor->GetProperty()->SetInterpolationToGouraud();
  actor->GetProperty()->SetOpacity(0.5);
  actor->SetBackfaceProperty(vtkSmartPointer<vtkProperty>::New());
  renderer->AddActor(actor);
  renderer->AddActor(vtkSmartPointer<vtkActor>::New()); // no mapper
  renderer->UseShadowsOn();
  renderer->GetActiveCamera()->SetViewShear(0.2, 0.0, 1.0);
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  MessageCounter warnings(grab, vtkCommand::WarningEvent);
  grab->Update();
  EXPECT_EQ(warnings.Count, 1);
  for (const char* named : { "Volume",
         "Actor2D",
         "ImageActor",
         "shadows",
         "view shear",
         "actor 3",
         "a backface property",
         "without a mapper",
         "opacity 0.5" })
  {
    EXPECT_NE(warnings.Last.find(named), std::string::npos) << named << " in " << warnings.Last;
  }
  EXPECT_EQ(warnings.Last.find("Gouraud"), std::string::npos) << "rendered, not named";
  EXPECT_EQ(ActorIdAt(grab->GetOutput(), 30, 30), 3);
  grab->Modified();
  grab->Update();
  EXPECT_EQ(warnings.Count, 1) << "said once: " << warnings.Last;
}

//------------------------------------------------------------------------------
// Each actor's interpolation, as VTK's OpenGL mapper shades it: with point normals (a
// vtkSphereSource makes them, turned with the actor) Phong and Gouraud shade smoothly;
// without, flat whatever the interpolation. SamplesPerPixel blends the silhouettes; bad settings
// are errors.
namespace {
struct QualityScene
{
  vtkSmartPointer<vtkRenderer> Renderer = vtkSmartPointer<vtkRenderer>::New();
  vtkSmartPointer<vtkActor> Smooth; // left, with point normals
  vtkSmartPointer<vtkActor> Bare;   // right, without
  QualityScene()
  {
    this->Renderer->SetActiveCamera(PixelCamera(Width, Height));
    this->Smooth = ActorOf(Sphere(35.0, 12));
    this->Smooth->SetPosition(40.0, 60.0, 0.0);
    vtkNew<vtkPolyData> bare;
    bare->ShallowCopy(Sphere(35.0, 12));
    bare->GetPointData()->SetNormals(nullptr);
    this->Bare = ActorOf(bare);
    this->Bare->SetPosition(120.0, 60.0, 0.0);
    this->Renderer->AddActor(this->Smooth);
    this->Renderer->AddActor(this->Bare);
  }
  // Distinct colors an actor shows, and its pixels' bytes.
  static std::pair<std::size_t, std::vector<int>> Pixels(vtkImageData* image, int actor)
  {
    std::set<std::array<int, 4>> colors;
    std::vector<int> bytes;
    for (int y = 0; y < Height; ++y)
    {
      for (int x = 0; x < Width; ++x)
      {
        if (ActorIdAt(image, x, y) == actor)
        {
          colors.insert(RgbaAt(image, x, y));
          bytes.insert(bytes.end(), { x, y, RgbaAt(image, x, y)[0], RgbaAt(image, x, y)[1] });
        }
      }
    }
    return { colors.size(), bytes };
  }
};
}

TEST(Quality, EachActorsInterpolationAsVtkShadesIt)
{
  QualityScene scene;
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(scene.Renderer);
  grab->Update();
  const auto [flatColors, flatSmooth] = QualityScene::Pixels(grab->GetOutput(), 0);
  const auto [bareColors, flatBare] = QualityScene::Pixels(grab->GetOutput(), 1);
  for (const int interpolation : { VTK_GOURAUD, VTK_PHONG })
  {
    scene.Smooth->GetProperty()->SetInterpolation(interpolation);
    scene.Bare->GetProperty()->SetInterpolation(interpolation);
    grab->Update();
    const auto [colors, smooth] = QualityScene::Pixels(grab->GetOutput(), 0);
    EXPECT_GT(colors, 3 * flatColors) << interpolation << ": smooth shading, many colors";
    EXPECT_EQ(QualityScene::Pixels(grab->GetOutput(), 1).second, flatBare)
      << interpolation << ": without point normals, flat as VTK shows it";
  }
  EXPECT_NE(QualityScene::Pixels(grab->GetOutput(), 0).second, flatSmooth);

  // Turning an actor turns its normals: the image is a fresh filter's, not the last shading.
  scene.Smooth->RotateX(90.0);
  grab->Update();
  vtkSmartPointer<vtkFacetRendererToImageFilter> fresh = Grab(scene.Renderer);
  fresh->Update();
  ExpectSameArray(grab->GetOutput(), fresh->GetOutput(), "RGBA");
}

TEST(Quality, SamplesPerPixelBlendTheSilhouettesAndBadSettingsAreErrors)
{
  QualityScene scene;
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(scene.Renderer);
  for (const int samples : { 1, 16 })
  {
    grab->SetSamplesPerPixel(samples);
    grab->Update();
    long blended = 0; // background pixels (no actor at their center sample) not black
    for (int y = 0; y < Height; ++y)
    {
      for (int x = 0; x < Width; ++x)
      {
        const std::array<int, 4> rgba = RgbaAt(grab->GetOutput(), x, y);
        blended += ActorIdAt(grab->GetOutput(), x, y) < 0 && rgba[0] + rgba[1] + rgba[2] > 0;
      }
    }
    std::printf("%d samples: %ld background pixels blended\n", samples, blended);
    EXPECT_EQ(blended > 50, samples == 16) << samples;
  }
  grab->SetMaximumError(2.0);
  grab->Update();
  EXPECT_GT(Covered(grab->GetOutput()), 0);
  MessageCounter errors(grab, vtkCommand::ErrorEvent);
  for (const auto& [samples, error] : { std::pair{ 3, 0.0 }, std::pair{ 1, -1.0 } })
  {
    const int before = errors.Count;
    grab->SetSamplesPerPixel(samples);
    grab->SetMaximumError(error);
    grab->Update();
    EXPECT_EQ(errors.Count, before + 1) << samples << " " << error;
    EXPECT_NE(errors.Last.find(samples == 3 ? "SamplesPerPixel is 3" : "MaximumError is -1"),
      std::string::npos)
      << errors.Last;
    EXPECT_EQ(grab->GetOutput()->GetNumberOfPoints(), 0) << "empty and valid";
  }
}

// Every render estimates its flat-shading error, as vtkFacetRenderFilter's: the summary in the
// field data, the per-pixel bound on request (0 on the background), and off the same image
// without it.
TEST(Quality, EstimateReportedWithEveryRenderOfTheScene)
{
  QualityScene scene;
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(scene.Renderer);
  EXPECT_TRUE(grab->GetEstimateError()) << "on by default, as the filter's";
  grab->Update();
  const double predictedRmse = FieldValue(grab->GetOutput(), "FacetErrorEstimate", "PredictedRMSE");
  const double predictedMax = FieldValue(grab->GetOutput(), "FacetErrorEstimate", "PredictedMax");
  EXPECT_GT(predictedRmse, 0.5) << "12-segment spheres, flat";
  EXPECT_GE(predictedMax, predictedRmse);
  EXPECT_EQ(grab->GetOutput()->GetPointData()->GetArray("ErrorEstimate"), nullptr);

  grab->ErrorEstimateArrayOn();
  grab->Update();
  vtkDataArray* estimate = grab->GetOutput()->GetPointData()->GetArray("ErrorEstimate");
  ASSERT_NE(estimate, nullptr);
  ASSERT_EQ(estimate->GetNumberOfValues(), Width * Height);
  // Without the array the summary may take one bound per block of polygons in place of each
  // polygon's (QualityRenderer.h, errorEstimateImage): at least the image's, and its own then.
  EXPECT_LE(static_cast<float>(estimate->GetRange()[1]), static_cast<float>(predictedMax));
  EXPECT_FLOAT_EQ(static_cast<float>(estimate->GetRange()[1]),
    static_cast<float>(FieldValue(grab->GetOutput(), "FacetErrorEstimate", "PredictedMax")));
  long onBackground = 0;
  for (int y = 0; y < Height; ++y)
  {
    for (int x = 0; x < Width; ++x)
    {
      onBackground +=
        ActorIdAt(grab->GetOutput(), x, y) < 0 && estimate->GetTuple1(y * Width + x) != 0;
    }
  }
  EXPECT_EQ(onBackground, 0) << "background pixels with an estimate";

  vtkNew<vtkImageData> with;
  with->DeepCopy(grab->GetOutput());
  grab->EstimateErrorOff();
  grab->ErrorEstimateArrayOff();
  grab->Update();
  EXPECT_EQ(grab->GetOutput()->GetFieldData()->GetArray("FacetErrorEstimate"), nullptr);
  ExpectSameArray(with, grab->GetOutput(), "RGBA");
}

//------------------------------------------------------------------------------
// Update renders again when, and only when, something in the scene changed; conversions
// are kept for what did not.
TEST(Updates, RenderAgainWhenTheSceneChangedAndOnlyThen)
{
  vtkNew<vtkSphereSource> source;
  source->SetRadius(30.0);
  source->SetCenter(80.0, 60.0, 0.0);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer; // no camera, default lookup table: the execution makes them
  renderer->AddActor(actor);
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  ExecutionCounter executions(grab);
  const auto converted = [&] {
    return FieldValue(grab->GetOutput(), "FacetMeshConverted", "Converted");
  };
  grab->Update();
  EXPECT_EQ(executions.Count, 1);
  EXPECT_EQ(converted(), 1.0);
  grab->Update();
  EXPECT_EQ(executions.Count, 1) << "nothing changed (the camera it made included)";

  struct Change
  {
    const char* What;
    std::function<void()> Make;
    double Converted;
  };
  vtkNew<vtkLight> light;
  const Change changes[] = {
    { "camera", [&] { renderer->GetActiveCamera()->Azimuth(10.0); }, 0.0 },
    { "actor position", [&] { actor->SetPosition(1.0, 0.0, 0.0); }, 0.0 },
    { "property", [&] { actor->GetProperty()->SetColor(1.0, 0.5, 0.0); }, 0.0 },
    { "lookup table",
      [&] { vtkLookupTable::SafeDownCast(mapper->GetLookupTable())->SetHueRange(0.2, 0.4); },
      0.0 },
    { "light added", [&] { renderer->AddLight(light); }, 0.0 },
    { "light", [&] { light->SetIntensity(0.5); }, 0.0 },
    { "background", [&] { renderer->SetBackground(0.1, 0.1, 0.1); }, 0.0 },
    { "source upstream", [&] { source->SetRadius(20.0); }, 1.0 },
  };
  for (const Change& change : changes)
  {
    const int before = executions.Count;
    change.Make();
    grab->Update();
    EXPECT_EQ(executions.Count, before + 1) << change.What;
    EXPECT_EQ(converted(), change.Converted) << change.What;
    grab->Update();
    EXPECT_EQ(executions.Count, before + 1) << change.What << ", then nothing";
  }
}

//------------------------------------------------------------------------------
TEST(Errors, NoRendererOrABadSizeGiveAnErrorAndAnEmptyOutput)
{
  vtkNew<vtkFacetRendererToImageFilter> grab;
  MessageCounter errors(grab, vtkCommand::ErrorEvent);
  grab->Update();
  EXPECT_EQ(errors.Count, 1);
  EXPECT_NE(errors.Last.find("SetRenderer"), std::string::npos) << errors.Last;
  EXPECT_EQ(grab->GetOutput()->GetNumberOfPoints(), 0);

  grab->SetRenderer(UnlitRenderer());
  grab->SetSize(0, 10);
  grab->Update();
  EXPECT_NE(errors.Last.find("Size is 0 x 10"), std::string::npos) << errors.Last;
  EXPECT_EQ(grab->GetOutput()->GetNumberOfPoints(), 0);
  grab->SetSize(16, 16);
  grab->Update();
  EXPECT_EQ(grab->GetOutput()->GetNumberOfPoints(), 256);

  const int before = errors.Count;
  grab->SetNumberOfThreads(-1);
  EXPECT_EQ(errors.Count, before + 1);
  EXPECT_EQ(grab->GetNumberOfThreads(), 0);
}

//------------------------------------------------------------------------------
TEST(Progress, ReportedAndAbortable)
{
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(ActorOf(Sphere(1.0, 300)));
  vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(renderer);
  grab->SetSize(400, 300);
  ExpectProgressReportedAndAbortable(
    grab, 400, 300, [&] { renderer->GetActiveCamera()->Azimuth(10.0); });
}

//------------------------------------------------------------------------------
// What the shading modes keep per actor between executions (vertex normals, each polygon's
// corner color range, which the error budget bounds by) follows a change of an attribute
// alone — the scalars' values, the lookup table's range, the point normals — for an actor
// in place and one moved by its matrix (whose normals are turned into a copy): the image is a
// fresh filter's.
namespace {
struct AttributeScene
{
  vtkSmartPointer<vtkRenderer> Renderer = vtkSmartPointer<vtkRenderer>::New();
  std::vector<vtkSmartPointer<vtkActor>> Actors;
  std::vector<vtkSmartPointer<vtkPolyData>> Data;

  explicit AttributeScene(int interpolation)
  {
    this->Renderer->SetActiveCamera(PixelCamera(Width, Height));
    for (const double x : { 45.0, 0.0 })
    {
      vtkNew<vtkSphereSource> sphere; // with point normals
      sphere->SetThetaResolution(16);
      sphere->SetPhiResolution(12);
      sphere->SetRadius(32.0);
      sphere->SetCenter(x, x == 0.0 ? 0.0 : 60.0, 0.0);
      sphere->Update();
      auto data = vtkSmartPointer<vtkPolyData>::New();
      data->DeepCopy(sphere->GetOutput());
      vtkNew<vtkDoubleArray> height;
      height->SetNumberOfTuples(data->GetNumberOfPoints());
      for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
      {
        height->SetValue(i, data->GetPoint(i)[1] - sphere->GetCenter()[1]);
      }
      data->GetPointData()->SetScalars(height);
      vtkSmartPointer<vtkActor> actor = ActorOf(data);
      actor->GetMapper()->SetScalarRange(-32.0, 32.0);
      actor->GetProperty()->SetInterpolation(interpolation);
      actor->GetProperty()->SetSpecular(0.3);
      if (x == 0.0)
      {
        actor->SetPosition(115.0, 60.0, 0.0);
      }
      this->Renderer->AddActor(actor);
      this->Actors.push_back(actor);
      this->Data.push_back(data);
    }
  }
};

std::string RgbaBytes(vtkImageData* image)
{
  vtkDataArray* rgba = image->GetPointData()->GetScalars();
  const auto* begin = static_cast<const char*>(rgba->GetVoidPointer(0));
  return { begin, begin + rgba->GetNumberOfValues() };
}

long DifferingPixels(const std::string& a, const std::string& b)
{
  long differing = 0;
  for (std::size_t i = 0; i + 4 <= std::min(a.size(), b.size()); i += 4)
  {
    differing += a.compare(i, 4, b, i, 4) != 0;
  }
  return differing;
}
}

TEST(Quality, AnAttributeChangeAloneReachesWhatTheModesKeep)
{
  struct Mode
  {
    const char* Name;
    int Interpolation;
    double MaximumError;
  };
  const std::pair<const char*, std::function<void(AttributeScene&)>> changes[] = {
    { "scalars",
      [](AttributeScene& scene) {
        for (vtkPolyData* data : scene.Data)
        {
          vtkDataArray* scalars = data->GetPointData()->GetScalars();
          for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
          {
            scalars->SetComponent(
              i, 0, 0.4 * scalars->GetComponent(i, 0) * scalars->GetComponent(i, 0) - 20.0);
          }
          scalars->Modified();
        }
      } },
    { "table range",
      [](AttributeScene& scene) {
        for (vtkActor* actor : scene.Actors)
        {
          actor->GetMapper()->SetScalarRange(-10.0, 60.0);
        }
      } },
    { "point normals",
      [](AttributeScene& scene) {
        for (vtkPolyData* data : scene.Data)
        {
          TiltPointNormals(data, 0.4);
        }
      } },
  };
  for (const Mode mode : { Mode{ "flat within 2", VTK_FLAT, 2.0 },
         { "Gouraud", VTK_GOURAUD, 0.0 },
         { "Phong", VTK_PHONG, 0.0 } })
  {
    for (const auto& [what, change] : changes)
    {
      AttributeScene scene(mode.Interpolation);
      vtkSmartPointer<vtkFacetRendererToImageFilter> grab = Grab(scene.Renderer);
      grab->SetMaximumError(mode.MaximumError);
      grab->Update();
      const std::string before = RgbaBytes(grab->GetOutput());
      change(scene);
      grab->Update();
      EXPECT_EQ(FieldValue(grab->GetOutput(), "FacetMeshConverted", "Converted"), 0.0);
      vtkSmartPointer<vtkFacetRendererToImageFilter> fresh = Grab(scene.Renderer);
      fresh->SetMaximumError(mode.MaximumError);
      fresh->Update();
      const std::string again = RgbaBytes(grab->GetOutput()),
                        expected = RgbaBytes(fresh->GetOutput());
      EXPECT_NE(expected, before) << mode.Name << ", " << what << ": the change shows";
      EXPECT_TRUE(again == expected)
        << mode.Name << ", " << what << ": " << DifferingPixels(again, expected)
        << " pixels differ from a fresh filter's";
    }
  }
}
