// vtkFacetRendererToImageFilter against VTK's own OpenGL renderer on scenes built for VTK:
// several actors under different matrices (position, orientation, scale, origin, user
// matrix, user transform, a mirror), properties and lookup tables, a vtkLightKit, scene
// lights, both composite mappers, parallel and perspective cameras with window centers, a
// gradient background, unlit surfaces, specular highlights under VTK's automatic headlight. The
// same renderer is rendered by both; the images agree within the filter's agreement tolerances
// (silhouettes within 0.5 % of the covered pixels, median color difference at most 2/255), ActorId
// names the prop VTK drew there (an id pass: every actor unlit in its own color), and the
// background is VTK's to the byte. The figures are printed for README.md.
//
// Needs an X server: make test runs it under tests/plugin/xvfb_run.sh.

#include "AdapterTestUtilities.h"
#include "VtkOpenGLReference.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCompositePolyDataMapper.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkConeSource.h"
#include "vtkCubeSource.h"
#include "vtkCylinderSource.h"
#include "vtkDoubleArray.h"
#include "vtkFacetRendererToImageFilter.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkLightKit.h"
#include "vtkLookupTable.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

using namespace facet_test;

namespace {
constexpr int Width = 640, Height = 480;

// The algorithm's output with a cell array `name` (active scalars if `active`): a smooth
// pattern over the cells, so neighbouring polygons differ.
vtkSmartPointer<vtkPolyData> WithCellValues(vtkAlgorithm* source, const char* name, bool active)
{
  source->Update();
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->DeepCopy(vtkPolyData::SafeDownCast(source->GetOutputDataObject(0)));
  vtkNew<vtkDoubleArray> values;
  values->SetName(name);
  for (vtkIdType cell = 0; cell < data->GetNumberOfCells(); ++cell)
  {
    values->InsertNextValue(std::sin(0.37 * cell) + 0.5 * std::cos(0.11 * cell));
  }
  if (active)
  {
    data->GetCellData()->SetScalars(values);
  }
  else
  {
    data->GetCellData()->AddArray(values);
  }
  return data;
}

vtkSmartPointer<vtkLookupTable> Table(double hueFrom, double hueTo, int values)
{
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  table->SetHueRange(hueFrom, hueTo);
  table->SetNumberOfTableValues(values);
  return table;
}

vtkSmartPointer<vtkActor> FlatActor(vtkMapper* mapper)
{
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetInterpolationToFlat();
  return actor;
}

vtkSmartPointer<vtkActor> FlatActor(vtkPolyData* data)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  return FlatActor(mapper);
}

// Perspective, a light kit, four actors under four kinds of matrix, two lookup tables.
vtkSmartPointer<vtkRenderer> PerspectiveSceneWithALightKit()
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(0.08, 0.1, 0.15);

  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetThetaResolution(40);
  sphereSource->SetPhiResolution(30);
  vtkSmartPointer<vtkActor> sphere = FlatActor(WithCellValues(sphereSource, "wave", true));
  sphere->GetMapper()->SetScalarModeToUseCellData();
  sphere->GetMapper()->SetLookupTable(Table(0.667, 0.0, 256));
  sphere->GetMapper()->SetScalarRange(-1.5, 1.5);
  sphere->SetPosition(-1.6, 0.2, 0.0);
  sphere->SetOrientation(10.0, 30.0, -20.0);
  sphere->SetScale(1.0, 0.7, 1.3);
  renderer->AddActor(sphere);

  vtkNew<vtkConeSource> coneSource;
  coneSource->SetResolution(32);
  coneSource->SetHeight(2.0);
  coneSource->SetRadius(0.8);
  coneSource->Update();
  vtkSmartPointer<vtkActor> cone = FlatActor(coneSource->GetOutput());
  cone->SetOrigin(0.0, -0.5, 0.0);
  cone->SetOrientation(0.0, 0.0, 40.0);
  vtkNew<vtkMatrix4x4> user;
  user->SetElement(0, 3, 1.6);
  user->SetElement(1, 3, 0.3);
  user->SetElement(2, 3, -0.4);
  user->SetElement(0, 1, 0.2); // a shear
  cone->SetUserMatrix(user);
  cone->GetProperty()->SetColor(0.9, 0.6, 0.2);
  cone->GetProperty()->SetAmbient(0.15);
  cone->GetProperty()->SetAmbientColor(0.2, 0.2, 0.6);
  cone->GetProperty()->SetDiffuse(0.8);
  renderer->AddActor(cone);

  vtkNew<vtkCubeSource> cubeSource;
  cubeSource->Update();
  vtkSmartPointer<vtkActor> cube = FlatActor(cubeSource->GetOutput());
  vtkNew<vtkTransform> transform;
  transform->Translate(0.2, -1.4, 0.3);
  transform->RotateX(25.0);
  transform->RotateY(35.0);
  cube->SetUserTransform(transform);
  cube->SetScale(-1.2, 0.6, 0.9); // a mirror
  cube->GetProperty()->SetColor(0.3, 0.8, 0.4);
  renderer->AddActor(cube);

  vtkNew<vtkCylinderSource> cylinderSource;
  cylinderSource->SetResolution(24);
  vtkSmartPointer<vtkActor> cylinder = FlatActor(WithCellValues(cylinderSource, "bands", true));
  cylinder->GetMapper()->SetLookupTable(Table(0.1, 0.5, 8));
  cylinder->GetMapper()->SetScalarRange(-1.5, 1.5);
  cylinder->SetPosition(0.3, 1.4, -0.8);
  cylinder->SetOrientation(90.0, 0.0, 0.0);
  renderer->AddActor(cylinder);

  vtkNew<vtkLightKit> lightKit;
  lightKit->AddLightsToRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(1.5, 2.0, 7.5);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetViewAngle(35.0);
  camera->SetWindowCenter(0.05, -0.04);
  renderer->ResetCameraClippingRange();
  return renderer;
}

// Parallel projection, two colored scene lights, both composite mappers, a color array by
// name, a gradient background.
vtkSmartPointer<vtkRenderer> ParallelCompositeSceneWithSceneLights()
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->GradientBackgroundOn();
  renderer->SetBackground(0.05, 0.05, 0.1);
  renderer->SetBackground2(0.3, 0.4, 0.6);

  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-2.0, -2.0, 0.0);
  plane->SetPoint1(2.0, -2.0, 0.0);
  plane->SetPoint2(-2.0, 2.0, 0.0);
  plane->SetResolution(12, 12);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0.0, 0.0, 0.8);
  ball->SetRadius(0.8);
  ball->SetThetaResolution(24);
  ball->SetPhiResolution(16);
  vtkNew<vtkConeSource> spike;
  spike->SetCenter(1.2, 1.0, 0.6);
  spike->SetDirection(0.0, 0.0, 1.0);
  spike->SetResolution(20);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, WithCellValues(plane, "value", false));
  blocks->SetBlock(1, WithCellValues(ball, "value", false));
  blocks->SetBlock(2, WithCellValues(spike, "value", false));
  vtkNew<vtkCompositePolyDataMapper2> mapper;
  mapper->SetInputDataObject(blocks);
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray("value");
  vtkSmartPointer<vtkLookupTable> table = Table(0.8, 0.2, 64);
  table->SetRange(-1.5, 1.5);
  mapper->SetLookupTable(table);
  mapper->UseLookupTableScalarRangeOn();
  vtkSmartPointer<vtkActor> ground = FlatActor(mapper);
  ground->SetOrientation(-50.0, 0.0, 20.0);
  renderer->AddActor(ground);

  vtkNew<vtkMultiBlockDataSet> pair;
  for (unsigned block = 0; block < 2; ++block)
  {
    vtkNew<vtkSphereSource> source;
    source->SetCenter(block == 0 ? -2.6 : 2.6, -1.6, 0.0);
    source->SetRadius(0.5);
    source->Update();
    pair->SetBlock(block, source->GetOutput());
  }
  vtkNew<vtkCompositePolyDataMapper> pairMapper;
  pairMapper->SetInputDataObject(pair);
  vtkSmartPointer<vtkActor> spheres = FlatActor(pairMapper);
  spheres->GetProperty()->SetColor(0.85, 0.75, 0.7);
  renderer->AddActor(spheres);

  const double lights[2][7] = { { 1.0, 1.0, 2.0, 1.0, 0.9, 0.8, 0.8 },
    { -2.0, 0.5, 1.0, 0.4, 0.5, 1.0, 0.5 } };
  for (const auto& l : lights)
  {
    vtkNew<vtkLight> light; // a scene light, directional
    light->SetPosition(l[0], l[1], l[2]);
    light->SetFocalPoint(0.0, 0.0, 0.0);
    light->SetColor(l[3], l[4], l[5]);
    light->SetIntensity(l[6]);
    renderer->AddLight(light);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetPosition(0.0, -3.0, 6.0);
  camera->SetFocalPoint(0.0, 0.0, 0.4);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetParallelScale(3.2);
  camera->SetWindowCenter(-0.06, 0.03);
  renderer->ResetCameraClippingRange();
  return renderer;
}

// No light at all (VTK shows Ka·Ca + Kd·Cd) and no camera (the first render makes one).
vtkSmartPointer<vtkRenderer> UnlitSceneWithoutACamera()
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->AutomaticLightCreationOff();
  renderer->SetBackground(0.9, 0.9, 0.85);
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetThetaResolution(30);
  sphereSource->SetPhiResolution(20);
  vtkSmartPointer<vtkActor> sphere = FlatActor(WithCellValues(sphereSource, "wave", true));
  sphere->GetMapper()->SetScalarRange(-1.5, 1.5);
  sphere->GetProperty()->SetAmbient(0.3);
  sphere->GetProperty()->SetDiffuse(0.6);
  renderer->AddActor(sphere);
  vtkNew<vtkCubeSource> cubeSource;
  cubeSource->SetCenter(1.5, 0.0, -0.5);
  cubeSource->Update();
  vtkSmartPointer<vtkActor> cube = FlatActor(cubeSource->GetOutput());
  cube->GetProperty()->SetAmbientColor(0.6, 0.1, 0.1);
  cube->GetProperty()->SetAmbient(0.5);
  cube->GetProperty()->SetDiffuseColor(0.1, 0.3, 0.6);
  cube->GetProperty()->SetDiffuse(0.7);
  renderer->AddActor(cube);
  return renderer;
}

// VTK's own headlight (none added) on shiny surfaces: with a headlight alone VTK's shader
// takes the highlight as (N·V)^power, which is Blinn-Phong's with the light at the eye.
vtkSmartPointer<vtkRenderer> ShinySurfacesUnderTheAutomaticHeadlight()
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetThetaResolution(48);
  sphereSource->SetPhiResolution(36);
  sphereSource->Update();
  vtkSmartPointer<vtkActor> sphere = FlatActor(sphereSource->GetOutput());
  sphere->GetProperty()->SetColor(0.8, 0.3, 0.2);
  sphere->GetProperty()->SetSpecular(0.6);
  sphere->GetProperty()->SetSpecularPower(15.0);
  renderer->AddActor(sphere);
  vtkNew<vtkCubeSource> cubeSource;
  cubeSource->SetCenter(1.2, 0.3, -0.4);
  cubeSource->Update();
  vtkSmartPointer<vtkActor> cube = FlatActor(cubeSource->GetOutput());
  cube->SetOrientation(20.0, 30.0, 0.0);
  cube->GetProperty()->SetColor(0.3, 0.5, 0.9);
  cube->GetProperty()->SetSpecular(0.3);
  cube->GetProperty()->SetSpecularPower(40.0);
  renderer->AddActor(cube);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.5, 0.8, 5.0);
  camera->SetFocalPoint(0.4, 0.1, 0.0);
  renderer->ResetCameraClippingRange();
  return renderer;
}

// Every actor unlit in its own color, red = its prop index + 1, on black: VTK's ActorId.
void PaintPropIndices(vtkRenderer* renderer)
{
  renderer->GradientBackgroundOff();
  renderer->SetBackground(0.0, 0.0, 0.0);
  vtkCollectionSimpleIterator iterator;
  renderer->GetViewProps()->InitTraversal(iterator);
  int index = 0;
  while (vtkProp* prop = renderer->GetViewProps()->GetNextProp(iterator))
  {
    if (auto* actor = vtkActor::SafeDownCast(prop))
    {
      actor->GetMapper()->ScalarVisibilityOff();
      vtkProperty* property = actor->GetProperty();
      property->LightingOff();
      property->SetAmbient(0.0);
      property->SetDiffuse(1.0);
      property->SetDiffuseColor((index + 1) / 255.0, 0.0, 0.0);
    }
    ++index;
  }
}

struct Figures
{
  long Covered = 0; // by VTK
  long SilhouetteDifferences = 0;
  long ActorDifferences = 0;                   // among pixels both cover
  long BackgroundDifferences = 0;              // among pixels neither covers
  int Median = 0, Percentile95 = 0, Worst = 0; // color, max over RGB, pixels both cover
};

// Renders with Facet, then with VTK, then VTK's id pass (which repaints the actors).
Figures Compare(vtkRenderer* renderer)
{
  vtkNew<vtkFacetRendererToImageFilter> grab;
  grab->SetRenderer(renderer);
  grab->SetSize(Width, Height);
  MessageCounter errors(grab, vtkCommand::ErrorEvent);
  grab->Update();
  EXPECT_EQ(errors.Count, 0) << errors.Last;
  vtkImageData* facet = grab->GetOutput();

  vtkSmartPointer<vtkRenderWindow> window = RenderOffScreen(renderer, Width, Height);
  vtkSmartPointer<vtkImageData> color = ReadBack(window, false);
  vtkSmartPointer<vtkImageData> depth = ReadBack(window, true);
  PaintPropIndices(renderer);
  window->Render();
  vtkSmartPointer<vtkImageData> ids = ReadBack(window, false);
  window->RemoveRenderer(renderer);

  auto* vtkColor = vtkUnsignedCharArray::SafeDownCast(color->GetPointData()->GetScalars());
  auto* vtkIds = vtkUnsignedCharArray::SafeDownCast(ids->GetPointData()->GetScalars());
  auto* vtkDepth = vtkFloatArray::SafeDownCast(depth->GetPointData()->GetScalars());
  const int components = vtkColor->GetNumberOfComponents();
  Figures figures;
  long histogram[256] = {};
  long both = 0;
  for (int y = 0; y < Height; ++y)
  {
    for (int x = 0; x < Width; ++x)
    {
      const vtkIdType i = PixelIndex(facet, x, y);
      const bool theirs = vtkDepth->GetValue(i) < 1.0f, ours = CellIdAt(facet, x, y) >= 0;
      figures.Covered += theirs;
      figures.SilhouetteDifferences += theirs != ours;
      const std::array<int, 4> rgba = RgbaAt(facet, x, y);
      int difference = 0;
      for (int c = 0; c < 3; ++c)
      {
        difference =
          std::max(difference, std::abs(rgba[c] - vtkColor->GetValue(components * i + c)));
      }
      if (!theirs && !ours)
      {
        figures.BackgroundDifferences += difference > 0;
      }
      if (theirs && ours)
      {
        ++both;
        ++histogram[difference];
        figures.ActorDifferences += ActorIdAt(facet, x, y) != vtkIds->GetValue(components * i) - 1;
      }
    }
  }
  long seen = 0;
  for (int d = 0; d < 256; ++d)
  {
    if (histogram[d] == 0)
    {
      continue;
    }
    figures.Median = seen < (both + 1) / 2 ? d : figures.Median;
    figures.Percentile95 = seen < both * 95 / 100 ? d : figures.Percentile95;
    seen += histogram[d];
    figures.Worst = d;
  }
  return figures;
}

void ExpectAgreement(const char* scene, const Figures& f)
{
  std::printf("%s: %ld pixels covered; silhouettes differ at %ld (%.3f %%), ActorId at %ld "
              "(%.3f %%); color difference median %d/255, 95th percentile %d/255, worst "
              "%d/255; background differs at %ld\n",
    scene,
    f.Covered,
    f.SilhouetteDifferences,
    100.0 * f.SilhouetteDifferences / f.Covered,
    f.ActorDifferences,
    100.0 * f.ActorDifferences / f.Covered,
    f.Median,
    f.Percentile95,
    f.Worst,
    f.BackgroundDifferences);
  EXPECT_GT(f.Covered, Width * Height / 10) << scene;
  EXPECT_LE(f.SilhouetteDifferences, 0.005 * f.Covered) << scene << ": silhouettes";
  EXPECT_LE(f.ActorDifferences, 0.005 * f.Covered) << scene << ": ActorId";
  EXPECT_LE(f.Median, 2) << scene << ": median color difference";
  EXPECT_EQ(f.BackgroundDifferences, 0) << scene << ": background";
}
}

TEST(RendererAgreement, PerspectiveSceneWithALightKit)
{
  vtkSmartPointer<vtkRenderer> renderer = PerspectiveSceneWithALightKit();
  ExpectAgreement("perspective, light kit, four matrices", Compare(renderer));
}

TEST(RendererAgreement, ParallelCompositeSceneWithSceneLights)
{
  vtkSmartPointer<vtkRenderer> renderer = ParallelCompositeSceneWithSceneLights();
  ExpectAgreement("parallel, composite mappers, scene lights, gradient", Compare(renderer));
}

TEST(RendererAgreement, UnlitSceneWithoutACamera)
{
  vtkSmartPointer<vtkRenderer> renderer = UnlitSceneWithoutACamera();
  ExpectAgreement("unlit, camera made by the first render", Compare(renderer));
}

TEST(RendererAgreement, ShinySurfacesUnderTheAutomaticHeadlight)
{
  vtkSmartPointer<vtkRenderer> renderer = ShinySurfacesUnderTheAutomaticHeadlight();
  ExpectAgreement("specular under VTK's automatic headlight", Compare(renderer));
}

// The camera the adapter makes for a renderer without one is the camera vtkRenderer::Render
// makes (ResetCamera on the visible props, with a 24-bit depth buffer's clipping tolerance).
TEST(RendererAgreement, ACameraIsMadeAsVtksRenderMakesIt)
{
  vtkSmartPointer<vtkRenderer> ours = UnlitSceneWithoutACamera();
  vtkSmartPointer<vtkRenderer> theirs = UnlitSceneWithoutACamera();
  vtkNew<vtkFacetRendererToImageFilter> grab;
  grab->SetRenderer(ours);
  grab->SetSize(Width, Height);
  grab->Update();
  RenderOffScreen(theirs, Width, Height)->RemoveRenderer(theirs);
  vtkCamera* a = ours->GetActiveCamera();
  vtkCamera* b = theirs->GetActiveCamera();
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_DOUBLE_EQ(a->GetPosition()[i], b->GetPosition()[i]) << i;
    EXPECT_DOUBLE_EQ(a->GetFocalPoint()[i], b->GetFocalPoint()[i]) << i;
  }
  EXPECT_DOUBLE_EQ(a->GetClippingRange()[0], b->GetClippingRange()[0]);
  EXPECT_DOUBLE_EQ(a->GetClippingRange()[1], b->GetClippingRange()[1]);
  EXPECT_DOUBLE_EQ(a->GetParallelScale(), b->GetParallelScale());
}
