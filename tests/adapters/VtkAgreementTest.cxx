// vtkFacetRenderFilter against VTK's own OpenGL renderer on the same vtkPolyData, camera and
// light: silhouettes (coverage) are the same to the pixel, flat-shaded colors under a
// directional light differ by at most 1/255 per channel away from edges, and pixels whose
// polygon differs lie on an edge between that polygon and its neighbour (the two renderers
// snap vertices from differently rounded projections), a small fraction of the image. These
// are the figures README.md states. With Gouraud and Phong interpolation (the mesh's normals
// from vtkPolyDataNormals, as a VTK user computes them): silhouettes within 0.5 % and the
// median color difference within 2/255.
//
// Needs an X server: make test runs it under xvfb-run (Debian's VTK has no OSMesa/EGL).

#include "AdapterTestUtilities.h"
#include "VtkOpenGLReference.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

using namespace facet_test;

namespace {
constexpr int Width = 800, Height = 600;

struct Scene
{
  vtkSmartPointer<vtkPolyData> Mesh;
  vtkSmartPointer<vtkCamera> Camera;
  vtkSmartPointer<vtkLight> Light;
  double Color[3] = { 0.85, 0.7, 0.55 };
  int Interpolation = VTK_FLAT;
  double Specular = 0.0; // with power 20
  // Colored by the point scalars "Height" through a 12-color table over their range, with
  // InterpolateScalarsBeforeMapping as given; null: the property's color.
  vtkSmartPointer<vtkLookupTable> Table;
  bool InterpolateScalarsBeforeMapping = false;
};

// Point scalars "Height" (the points' y) and a 12-color rainbow over their range: large
// bands, so that mapping per pixel and interpolating mapped colors look different.
void ColorByHeight(Scene& scene)
{
  vtkNew<vtkPolyData> mesh;
  mesh->ShallowCopy(scene.Mesh);
  vtkNew<vtkFloatArray> height;
  height->SetName("Height");
  height->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    height->SetValue(p, static_cast<float>(mesh->GetPoint(p)[1]));
  }
  mesh->GetPointData()->SetScalars(height);
  scene.Mesh = mesh;
  scene.Table = vtkSmartPointer<vtkLookupTable>::New();
  scene.Table->SetNumberOfTableValues(12);
  scene.Table->SetRange(height->GetRange());
  scene.Table->Build();
}

// The mapper's (or the filter's) coloring for the scene: by "Height" or not at all.
template<class Coloring>
void SetColoring(Coloring* coloring, const Scene& scene)
{
  coloring->SetScalarVisibility(scene.Table != nullptr);
  if (scene.Table)
  {
    coloring->SetLookupTable(scene.Table);
    coloring->SetScalarRange(scene.Table->GetRange());
    coloring->SetInterpolateScalarsBeforeMapping(scene.InterpolateScalarsBeforeMapping);
  }
}

Scene LoadScene(const std::string& mesh, double azimuth, double elevation)
{
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName((std::string(FACET_SHARED_DATA_DIR) + "/meshes/" + mesh).c_str());
  reader->Update();
  Scene scene;
  scene.Mesh = reader->GetOutput();
  // The camera a VTK user would get: reset to the bounds, then turned.
  vtkNew<vtkRenderer> fit;
  fit->SetAspect(static_cast<double>(Width) / Height, 1.0);
  scene.Camera = fit->GetActiveCamera();
  fit->ResetCamera(scene.Mesh->GetBounds());
  scene.Camera->Azimuth(azimuth);
  scene.Camera->Elevation(elevation);
  scene.Camera->OrthogonalizeViewUp();
  fit->ResetCameraClippingRange(scene.Mesh->GetBounds());
  scene.Light = vtkSmartPointer<vtkLight>::New();
  scene.Light->SetLightTypeToSceneLight();
  scene.Light->SetPosition(1.0, 2.0, 3.0); // directional: shines from (1, 2, 3) toward 0
  scene.Light->SetFocalPoint(0.0, 0.0, 0.0);
  scene.Light->SetColor(1.0, 0.95, 0.9);
  return scene;
}

// The largest channel difference between a Facet pixel and a VTK one.
int LargestDifference(const std::array<int, 4>& rgba, const unsigned char* reference)
{
  int difference = 0;
  for (int c = 0; c < 3; ++c)
  {
    difference = std::max(difference, std::abs(rgba[c] - reference[c]));
  }
  return difference;
}

vtkSmartPointer<vtkRenderWindow> RenderOffScreen(vtkRenderer* renderer)
{
  return facet_test::RenderOffScreen(renderer, Width, Height);
}

// VTK's OpenGL pipeline: flat interpolation, no multisampling, RGB and depth read back.
struct VtkImages
{
  vtkSmartPointer<vtkImageData> Color;
  vtkSmartPointer<vtkImageData> Depth;
};

VtkImages RenderWithVtk(const Scene& scene)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(scene.Mesh);
  SetColoring(mapper.Get(), scene);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetInterpolation(scene.Interpolation);
  actor->GetProperty()->SetSpecular(scene.Specular);
  actor->GetProperty()->SetSpecularPower(20.0);
  actor->GetProperty()->SetColor(scene.Color[0], scene.Color[1], scene.Color[2]);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.0, 0.0, 0.0);
  renderer->SetActiveCamera(scene.Camera);
  renderer->AddLight(scene.Light);
  renderer->AutomaticLightCreationOff();
  vtkSmartPointer<vtkRenderWindow> window = RenderOffScreen(renderer);
  return { ReadBack(window, false), ReadBack(window, true) };
}

// VTK's polygon at each pixel: every cell colored by its id + 1 (RGB, 24 bits), unlit,
// read back. 0 is the background.
std::vector<vtkIdType> RenderIdsWithVtk(const Scene& scene)
{
  vtkNew<vtkPolyData> mesh;
  mesh->ShallowCopy(scene.Mesh);
  vtkNew<vtkUnsignedCharArray> ids;
  ids->SetNumberOfComponents(3);
  ids->SetNumberOfTuples(mesh->GetNumberOfCells());
  for (vtkIdType cell = 0; cell < mesh->GetNumberOfCells(); ++cell)
  {
    for (int c = 0; c < 3; ++c)
    {
      ids->SetTypedComponent(cell, c, static_cast<unsigned char>((cell + 1) >> (8 * c)));
    }
  }
  mesh->GetCellData()->SetScalars(ids);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff(); // the scalar color itself, exactly
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetActiveCamera(scene.Camera);
  vtkSmartPointer<vtkImageData> image = ReadBack(RenderOffScreen(renderer), false);
  vtkDataArray* rgb = image->GetPointData()->GetScalars();
  std::vector<vtkIdType> cells(static_cast<std::size_t>(Width) * Height);
  for (std::size_t i = 0; i < cells.size(); ++i)
  {
    const auto channel = [&](int c) {
      return static_cast<vtkIdType>(rgb->GetComponent(static_cast<vtkIdType>(i), c));
    };
    cells[i] = (channel(0) | channel(1) << 8 | channel(2) << 16) - 1;
  }
  return cells;
}

vtkSmartPointer<vtkImageData> RenderWithFacet(const Scene& scene)
{
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputData(scene.Mesh);
  filter->SetSize(Width, Height);
  filter->SetCamera(scene.Camera);
  filter->AddLight(scene.Light);
  filter->SetAmbientLightColor(0.0, 0.0, 0.0); // VTK's renderer has no scene ambient
  SetColoring(filter.Get(), scene);
  filter->GetProperty()->SetColor(scene.Color[0], scene.Color[1], scene.Color[2]);
  filter->GetProperty()->SetInterpolation(scene.Interpolation);
  filter->GetProperty()->SetSpecular(scene.Specular);
  filter->GetProperty()->SetSpecularPower(20.0);
  filter->Update();
  return filter->GetOutput();
}

// Whether two cells of the mesh share a point position (OBJ readers may duplicate points):
// neighbours on the surface.
bool Adjacent(vtkPolyData* mesh, vtkIdType a, vtkIdType b)
{
  vtkIdType countA, countB;
  const vtkIdType *pointsA, *pointsB;
  mesh->GetCellPoints(a, countA, pointsA);
  mesh->GetCellPoints(b, countB, pointsB);
  for (vtkIdType i = 0; i < countA; ++i)
  {
    for (vtkIdType j = 0; j < countB; ++j)
    {
      double p[3], q[3];
      mesh->GetPoint(pointsA[i], p);
      mesh->GetPoint(pointsB[j], q);
      if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2])
      {
        return true;
      }
    }
  }
  return false;
}

// Which polygon each covered pixel shows: where the renderers disagree, VTK's polygon is a
// neighbour of ours on the surface, so the pixel lies on the edge (or corner) between them.
void CompareOwners(const Scene& scene, vtkImageData* facet, long covered)
{
  const std::vector<vtkIdType> vtkIds = RenderIdsWithVtk(scene);
  long differentOwner = 0, notNeighbours = 0;
  for (int y = 0; y < Height; ++y)
  {
    for (int x = 0; x < Width; ++x)
    {
      const vtkIdType ours = CellIdAt(facet, x, y);
      const vtkIdType theirs = vtkIds[static_cast<std::size_t>(y) * Width + x];
      if (ours < 0 || theirs < 0 || ours == theirs)
      {
        continue;
      }
      ++differentOwner;
      if (!Adjacent(scene.Mesh, ours, theirs) && ++notNeighbours <= 5)
      {
        ADD_FAILURE() << "pixel (" << x << ", " << y << "): Facet shows cell " << ours
                      << ", VTK cell " << theirs << ", which is not its neighbour";
      }
    }
  }
  std::printf("  %ld pixels (%.4f %% of the covered) show a neighbouring polygon\n",
    differentOwner,
    100.0 * differentOwner / covered);
  EXPECT_EQ(notNeighbours, 0);
  EXPECT_LE(differentOwner, 0.001 * covered) << "a few edge pixels";
}

void Compare(const std::string& mesh, double azimuth, double elevation)
{
  SCOPED_TRACE(mesh + ", azimuth " + std::to_string(azimuth));
  const Scene scene = LoadScene(mesh, azimuth, elevation);
  const VtkImages vtk = RenderWithVtk(scene);
  vtkSmartPointer<vtkImageData> facet = RenderWithFacet(scene);
  ASSERT_EQ(vtk.Color->GetDimensions()[0], Width);
  auto* vtkDepth = vtkFloatArray::SafeDownCast(vtk.Depth->GetPointData()->GetScalars());
  auto* vtkColor = vtkUnsignedCharArray::SafeDownCast(vtk.Color->GetPointData()->GetScalars());
  ASSERT_NE(vtkDepth, nullptr);
  ASSERT_NE(vtkColor, nullptr);
  const int vtkComponents = vtkColor->GetNumberOfComponents();

  const auto vtkCovered = [&](int x, int y) {
    return vtkDepth->GetValue(PixelIndex(vtk.Depth, x, y)) < 1.0f;
  };
  long covered = 0, silhouetteDifferences = 0, interior = 0, colorMismatches = 0;
  int worst = 0;
  for (int y = 0; y < Height; ++y)
  {
    for (int x = 0; x < Width; ++x)
    {
      const vtkIdType id = CellIdAt(facet, x, y);
      const bool ours = id >= 0, theirs = vtkCovered(x, y);
      covered += theirs;
      silhouetteDifferences += ours != theirs;
      // Away from edges: the 3x3 neighbourhood is covered in both renderers and has one
      // color in ours, so it does not matter which of two coplanar triangles owns the pixel.
      bool inside = ours && theirs && x > 0 && y > 0 && x + 1 < Width && y + 1 < Height;
      const std::array<int, 4> center = inside ? RgbaAt(facet, x, y) : std::array<int, 4>{};
      for (int dy = -1; inside && dy <= 1; ++dy)
      {
        for (int dx = -1; inside && dx <= 1; ++dx)
        {
          inside = vtkCovered(x + dx, y + dy) && RgbaAt(facet, x + dx, y + dy) == center;
        }
      }
      if (!inside)
      {
        continue;
      }
      ++interior;
      const std::array<int, 4> rgba = RgbaAt(facet, x, y);
      const unsigned char* reference =
        vtkColor->GetPointer(vtkComponents * PixelIndex(vtk.Color, x, y));
      const int difference = LargestDifference(rgba, reference);
      worst = std::max(worst, difference);
      if (difference > 1 && ++colorMismatches <= 5)
      {
        ADD_FAILURE() << "pixel (" << x << ", " << y << ") Facet " << rgba[0] << "," << rgba[1]
                      << "," << rgba[2] << " VTK " << int(reference[0]) << "," << int(reference[1])
                      << "," << int(reference[2]);
      }
    }
  }
  std::printf("%s azimuth %g: %ld covered, %ld silhouette differences (%.3f %%), %ld interior "
              "pixels, worst color difference %d/255\n",
    mesh.c_str(),
    azimuth,
    covered,
    silhouetteDifferences,
    100.0 * silhouetteDifferences / covered,
    interior,
    worst);
  EXPECT_GT(covered, Width * Height / 10);
  EXPECT_EQ(silhouetteDifferences, 0) << "silhouettes to the pixel";
  EXPECT_GT(interior, covered / 20) << "enough pixels away from edges to compare colors";
  EXPECT_LE(worst, 1) << "colors to 1/255";
  EXPECT_EQ(colorMismatches, 0);
  CompareOwners(scene, facet, covered);
}

// Gouraud or Phong: the mesh with vtkPolyDataNormals' normals (30° feature angle, split),
// in both renderers. VTK's OpenGL2 shaders light every fragment with the interpolated normal
// for both; Facet's Gouraud lights the corners, so its highlights differ more.
struct SmoothAgreement
{
  long Covered = 0;
  long SilhouetteDifferences = 0;
  int Median = 0;
  int Percentile95 = 0;
};

SmoothAgreement CompareSmoothImages(const VtkImages& vtk, vtkImageData* facet)
{
  auto* vtkDepth = vtkFloatArray::SafeDownCast(vtk.Depth->GetPointData()->GetScalars());
  auto* vtkColor = vtkUnsignedCharArray::SafeDownCast(vtk.Color->GetPointData()->GetScalars());
  EXPECT_NE(vtkDepth, nullptr);
  EXPECT_NE(vtkColor, nullptr);
  if (!vtkDepth || !vtkColor)
  {
    return {};
  }
  const int vtkComponents = vtkColor->GetNumberOfComponents();
  long covered = 0, silhouetteDifferences = 0;
  std::vector<int> differences;
  for (int y = 0; y < Height; ++y)
  {
    for (int x = 0; x < Width; ++x)
    {
      const bool ours = CellIdAt(facet, x, y) >= 0;
      const bool theirs = vtkDepth->GetValue(PixelIndex(vtk.Depth, x, y)) < 1.0f;
      covered += theirs;
      silhouetteDifferences += ours != theirs;
      if (!ours || !theirs)
      {
        continue;
      }
      const std::array<int, 4> rgba = RgbaAt(facet, x, y);
      const unsigned char* reference =
        vtkColor->GetPointer(vtkComponents * PixelIndex(vtk.Color, x, y));
      const int difference = LargestDifference(rgba, reference);
      differences.push_back(difference);
    }
  }
  EXPECT_FALSE(differences.empty());
  if (differences.empty())
  {
    return {};
  }
  std::sort(differences.begin(), differences.end());
  return { covered,
    silhouetteDifferences,
    differences[differences.size() / 2],
    differences[differences.size() * 95 / 100] };
}

// Gouraud or Phong: the mesh with vtkPolyDataNormals' normals (30° feature angle, split),
// in both renderers, and with `scalars` colored by height (ColorByHeight) with
// InterpolateScalarsBeforeMapping on. VTK's OpenGL2 shaders light every fragment with the
// interpolated normal for both; Facet's Gouraud lights the corners, so its highlights differ
// more.
void CompareSmooth(const std::string& mesh,
  double azimuth,
  double elevation,
  int interpolation,
  double specular = 0.0,
  bool scalars = false)
{
  SCOPED_TRACE(mesh + (interpolation == VTK_PHONG ? ", Phong" : ", Gouraud"));
  Scene scene = LoadScene(mesh, azimuth, elevation);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(scene.Mesh);
  normals->Update();
  scene.Mesh = normals->GetOutput();
  scene.Interpolation = interpolation;
  scene.Specular = specular;
  if (scalars)
  {
    ColorByHeight(scene);
    scene.InterpolateScalarsBeforeMapping = true;
  }
  const VtkImages vtk = RenderWithVtk(scene);
  vtkSmartPointer<vtkImageData> facet = RenderWithFacet(scene);
  const SmoothAgreement agreement = CompareSmoothImages(vtk, facet);
  std::printf("%s %s%s azimuth %g: %ld covered, silhouette differences %.3f %%, color "
              "difference median %d/255, 95th percentile %d/255\n",
    mesh.c_str(),
    interpolation == VTK_PHONG ? "Phong" : "Gouraud",
    scalars ? " (scalars interpolated before mapping)" : "",
    azimuth,
    agreement.Covered,
    100.0 * agreement.SilhouetteDifferences / std::max(agreement.Covered, 1L),
    agreement.Median,
    agreement.Percentile95);
  EXPECT_GT(agreement.Covered, Width * Height / 10);
  EXPECT_LE(agreement.SilhouetteDifferences, 0.005 * agreement.Covered);
  EXPECT_LE(agreement.Median, 2);
  if (scalars)
  {
    // The control: Facet interpolating mapped colors (off) against VTK mapping per pixel
    // (on) is further off (on fandisk's large triangles by 33/255 at the 95th percentile, on
    // the bunny's pixel-sized ones by 3/255), so the agreement above is the mapping's.
    Scene off = scene;
    off.InterpolateScalarsBeforeMapping = false;
    vtkSmartPointer<vtkImageData> blended = RenderWithFacet(off);
    const SmoothAgreement control = CompareSmoothImages(vtk, blended);
    std::printf("  control, Facet with it off: median %d/255, 95th percentile %d/255\n",
      control.Median,
      control.Percentile95);
    EXPECT_GT(control.Percentile95, agreement.Percentile95);
  }
}
}

TEST(VtkAgreement, FandiskFlatFacets)
{
  Compare("fandisk.obj", 30.0, 20.0);
}

TEST(VtkAgreement, BunnyFromTheSide)
{
  Compare("stanford-bunny.obj", -60.0, 10.0);
}

TEST(VtkAgreement, SpotClosedMesh)
{
  Compare("spot.obj", 120.0, -15.0);
}

TEST(VtkAgreement, BunnyGouraud)
{
  CompareSmooth("stanford-bunny.obj", -60.0, 10.0, VTK_GOURAUD);
}

TEST(VtkAgreement, BunnyPhong)
{
  CompareSmooth("stanford-bunny.obj", -60.0, 10.0, VTK_PHONG);
}

TEST(VtkAgreement, BunnyPhongShiny)
{
  CompareSmooth("stanford-bunny.obj", -60.0, 10.0, VTK_PHONG, 0.4);
}

TEST(VtkAgreement, FandiskPhong)
{
  CompareSmooth("fandisk.obj", 30.0, 20.0, VTK_PHONG);
}

TEST(VtkAgreement, FandiskPhongScalarsInterpolatedBeforeMapping)
{
  CompareSmooth("fandisk.obj", 30.0, 20.0, VTK_PHONG, 0.0, true);
}

TEST(VtkAgreement, FandiskGouraudScalarsInterpolatedBeforeMapping)
{
  CompareSmooth("fandisk.obj", 30.0, 20.0, VTK_GOURAUD, 0.0, true);
}

TEST(VtkAgreement, BunnyPhongShinyScalarsInterpolatedBeforeMapping)
{
  CompareSmooth("stanford-bunny.obj", -60.0, 10.0, VTK_PHONG, 0.4, true);
}
