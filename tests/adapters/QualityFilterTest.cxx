// vtkFacetRenderFilter's quality modes (vtkFacetQuality): the property's Interpolation picks
// the shading without a warning, supersampling and the error budget, the estimate in every
// render's field data, the measured error against the mesh reference, and bad settings.

#include "AdapterTestUtilities.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkElevationFilter.h"
#include "vtkFacetRenderFilter.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace {
using facet_test::FieldValue;

// Counts the warnings and errors a filter reports.
struct Messages
{
  int Warnings = 0, Errors = 0;
  std::string Last;
  vtkNew<vtkCallbackCommand> Callback;
  explicit Messages(vtkObject* object)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback([](vtkObject*, unsigned long event, void* self, void* text) {
      auto* m = static_cast<Messages*>(self);
      (event == vtkCommand::WarningEvent ? m->Warnings : m->Errors)++;
      m->Last = static_cast<const char*>(text);
    });
    object->AddObserver(vtkCommand::WarningEvent, this->Callback);
    object->AddObserver(vtkCommand::ErrorEvent, this->Callback);
  }
};

vtkSmartPointer<vtkFacetRenderFilter> SphereFilter(int resolution, int interpolation)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution);
  sphere->Update();
  auto filter = vtkSmartPointer<vtkFacetRenderFilter>::New();
  filter->SetInputData(sphere->GetOutput());
  filter->SetSize(96, 72);
  filter->GetProperty()->SetInterpolation(interpolation);
  filter->GetProperty()->SetSpecular(0.4);
  filter->GetProperty()->SetSpecularPower(20.0);
  return filter;
}

int LargestDifference(vtkImageData* a, vtkImageData* b)
{
  auto* ca = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  auto* cb = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars());
  int largest = 0;
  for (vtkIdType i = 0; i < ca->GetNumberOfValues(); ++i)
  {
    largest = std::max(largest, std::abs(ca->GetValue(i) - cb->GetValue(i)));
  }
  return largest;
}

TEST(QualityFilter, InterpolationPicksTheShadingWithoutAWarning)
{
  auto flat = SphereFilter(24, VTK_FLAT);
  flat->Update();
  for (const int interpolation : { VTK_GOURAUD, VTK_PHONG })
  {
    auto smooth = SphereFilter(24, interpolation);
    Messages messages(smooth);
    smooth->Update();
    EXPECT_EQ(messages.Warnings + messages.Errors, 0) << messages.Last;
    EXPECT_GT(LargestDifference(flat->GetOutput(), smooth->GetOutput()), 10) << interpolation;
    EXPECT_NE(smooth->GetOutput()->GetPointData()->GetArray("CellId"), nullptr);
  }
  // PBR is not rendered: still named once.
  auto pbr = SphereFilter(24, VTK_PBR);
  Messages messages(pbr);
  pbr->Update();
  EXPECT_EQ(messages.Warnings, 1);
  EXPECT_NE(messages.Last.find("Physically based"), std::string::npos) << messages.Last;
}

TEST(QualityFilter, EstimateReportedWithEveryRender)
{
  auto filter = SphereFilter(16, VTK_FLAT);
  EXPECT_TRUE(filter->GetEstimateError()) << "on by default";
  filter->Update();
  const double predictedRmse =
    FieldValue(filter->GetOutput(), "FacetErrorEstimate", "PredictedRMSE");
  const double predictedMax = FieldValue(filter->GetOutput(), "FacetErrorEstimate", "PredictedMax");
  EXPECT_GT(predictedRmse, 0.5);
  EXPECT_GE(predictedMax, predictedRmse);
  EXPECT_EQ(filter->GetOutput()->GetPointData()->GetArray("ErrorEstimate"), nullptr);
  EXPECT_EQ(filter->GetOutput()->GetFieldData()->GetArray("FacetError"), nullptr);

  filter->ErrorEstimateArrayOn();
  filter->Update();
  auto* estimate =
    vtkFloatArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetArray("ErrorEstimate"));
  ASSERT_NE(estimate, nullptr);
  EXPECT_EQ(estimate->GetNumberOfValues(), 96 * 72);
  // Without the array the summary may take one bound per block of polygons in place of each
  // polygon's (QualityRenderer.h, errorEstimateImage): at least the image's, and its own then.
  EXPECT_LE(estimate->GetValueRange()[1], predictedMax);
  EXPECT_FLOAT_EQ(estimate->GetValueRange()[1],
    FieldValue(filter->GetOutput(), "FacetErrorEstimate", "PredictedMax"));

  // Off: the plain rasterizer, the same image, no estimate.
  vtkNew<vtkImageData> with;
  with->DeepCopy(filter->GetOutput());
  filter->EstimateErrorOff();
  filter->ErrorEstimateArrayOff();
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetFieldData()->GetArray("FacetErrorEstimate"), nullptr);
  EXPECT_EQ(LargestDifference(with, filter->GetOutput()), 0);
}

// Measured against the converged Phong reference: Phong is below flat, and flat's measured
// error is below its estimate (both over the same pixels, silhouettes included in the
// measurement only, so compare the interior-dominated RMSE loosely).
TEST(QualityFilter, ComputeErrorMeasuresAgainstTheMeshReference)
{
  double rmse[2] = { 0.0, 0.0 };
  int i = 0;
  for (const int interpolation : { VTK_FLAT, VTK_PHONG })
  {
    auto filter = SphereFilter(16, interpolation);
    filter->ComputeErrorOn();
    filter->Update();
    vtkImageData* out = filter->GetOutput();
    rmse[i++] = FieldValue(out, "FacetError", "RMSE");
    EXPECT_GT(FieldValue(out, "FacetError", "PSNR"), 0.0);
    EXPECT_GT(FieldValue(out, "FacetError", "SSIM"), 0.5);
    EXPECT_GE(FieldValue(out, "FacetError", "SilhouetteFraction"), 0.0);
    EXPECT_GT(FieldValue(out, "FacetError", "ReferenceSeconds"), 0.0);
    EXPECT_GT(FieldValue(out, "FacetError", "RenderSeconds"), 0.0);
    auto* error = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("Error"));
    ASSERT_NE(error, nullptr);
    EXPECT_FLOAT_EQ(error->GetValueRange()[1], FieldValue(out, "FacetError", "Max"));
  }
  std::printf("16 x 16 sphere: measured RMSE flat %.2f, Phong %.2f\n", rmse[0], rmse[1]);
  EXPECT_LT(rmse[1], rmse[0]);
}

TEST(QualityFilter, SupersamplingAndTheBudget)
{
  auto one = SphereFilter(32, VTK_PHONG);
  one->Update();
  auto sixteen = SphereFilter(32, VTK_PHONG);
  sixteen->SetSamplesPerPixel(16);
  sixteen->Update();
  EXPECT_GT(LargestDifference(one->GetOutput(), sixteen->GetOutput()), 30); // the silhouette

  auto adaptive = SphereFilter(32, VTK_FLAT);
  adaptive->SetMaximumError(2.0);
  adaptive->Update();
  EXPECT_LE(LargestDifference(one->GetOutput(), adaptive->GetOutput()), 3);
}

// A sample grid without depth output: the image's depth plane is not there to fill (it was
// written from the grid's center samples, and crashed); colors and cell ids as with it.
TEST(QualityFilter, SupersamplingWithoutDepthOutput)
{
  for (const int samples : { 4, 16 })
  {
    auto withDepth = SphereFilter(24, VTK_PHONG);
    withDepth->SetSamplesPerPixel(samples);
    withDepth->Update();
    auto withoutDepth = SphereFilter(24, VTK_PHONG);
    withoutDepth->SetSamplesPerPixel(samples);
    withoutDepth->OutputDepthOff();
    Messages messages(withoutDepth);
    withoutDepth->Update();
    EXPECT_EQ(messages.Errors, 0) << messages.Last;
    vtkPointData* data = withoutDepth->GetOutput()->GetPointData();
    EXPECT_EQ(data->GetArray("Depth"), nullptr);
    EXPECT_EQ(LargestDifference(withDepth->GetOutput(), withoutDepth->GetOutput()), 0);
    vtkDataArray* cells = data->GetArray("CellId");
    vtkDataArray* expected = withDepth->GetOutput()->GetPointData()->GetArray("CellId");
    ASSERT_NE(cells, nullptr);
    ASSERT_EQ(cells->GetNumberOfTuples(), expected->GetNumberOfTuples());
    for (vtkIdType i = 0; i < cells->GetNumberOfTuples(); ++i)
    {
      ASSERT_EQ(cells->GetTuple1(i), expected->GetTuple1(i)) << "pixel " << i;
    }
  }
}

TEST(QualityFilter, BadSettingsAreErrorsWithAnEmptyOutput)
{
  for (const int samples : { 0, 2, 9 })
  {
    auto filter = SphereFilter(8, VTK_FLAT);
    filter->SetSamplesPerPixel(samples);
    Messages messages(filter);
    filter->Update();
    EXPECT_EQ(messages.Errors, 1);
    EXPECT_NE(
      messages.Last.find("SamplesPerPixel is " + std::to_string(samples)), std::string::npos)
      << messages.Last;
    EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  }
  auto filter = SphereFilter(8, VTK_FLAT);
  filter->SetMaximumError(-1.0);
  Messages messages(filter);
  filter->Update();
  EXPECT_EQ(messages.Errors, 1);
  EXPECT_NE(messages.Last.find("MaximumError"), std::string::npos) << messages.Last;
}

// The input's own point normals are what Gouraud and Phong interpolate: normals that all
// point one way make a sphere look like a flat disk.
TEST(QualityFilter, TheInputsPointNormalsAreUsed)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(24);
  sphere->Update();
  vtkNew<vtkPolyData> withNormals;
  withNormals->DeepCopy(sphere->GetOutput());
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(withNormals->GetNumberOfPoints());
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    normals->SetTuple3(i, 0.0, 0.0, 1.0);
  }
  withNormals->GetPointData()->SetNormals(normals);
  auto filter = SphereFilter(24, VTK_PHONG);
  filter->SetInputData(withNormals);
  vtkNew<vtkLight> light; // a directional light along the view: every pixel alike
  light->SetLightTypeToSceneLight();
  light->SetPosition(0, 0, 1);
  light->SetFocalPoint(0, 0, 0);
  filter->AddLight(light);
  filter->Update();
  auto* rgba =
    vtkUnsignedCharArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetScalars());
  auto* ids = vtkIdTypeArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetArray("CellId"));
  int low = 255, high = 0;
  for (vtkIdType i = 0; i < ids->GetNumberOfValues(); ++i)
  {
    if (ids->GetValue(i) < 0)
    {
      continue;
    }
    low = std::min<int>(low, rgba->GetValue(4 * i));
    high = std::max<int>(high, rgba->GetValue(4 * i));
  }
  EXPECT_LE(high - low, 2);
}

// Point scalars: flat shading shows one (averaged) color per polygon, Phong the colors
// interpolated across it (vtkMapper's InterpolateScalarsBeforeMapping off).
TEST(QualityFilter, PointColorsAreInterpolatedBySmoothShading)
{
  vtkNew<vtkPlaneSource> plane; // one quad
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(plane->GetOutputPort());
  elevation->SetLowPoint(-0.5, 0.0, 0.0);
  elevation->SetHighPoint(0.5, 0.0, 0.0);
  elevation->Update();
  std::size_t distinct[2] = { 0, 0 };
  int i = 0;
  for (const int interpolation : { VTK_FLAT, VTK_PHONG })
  {
    vtkNew<vtkFacetRenderFilter> filter;
    filter->SetInputData(elevation->GetOutput());
    filter->SetSize(64, 64);
    filter->GetProperty()->SetInterpolation(interpolation);
    filter->GetProperty()->LightingOff();
    filter->Update();
    auto* rgba =
      vtkUnsignedCharArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetScalars());
    std::set<int> colors;
    for (vtkIdType p = 0; p < rgba->GetNumberOfTuples(); ++p)
    {
      colors.insert(
        rgba->GetValue(4 * p) << 16 | rgba->GetValue(4 * p + 1) << 8 | rgba->GetValue(4 * p + 2));
    }
    distinct[i++] = colors.size();
  }
  EXPECT_LE(distinct[0], 2u); // the quad's one color and the background
  EXPECT_GT(distinct[1], 20u);
}
}
