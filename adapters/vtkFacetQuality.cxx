#include "vtkFacetQuality.h"

#include "vtkDoubleArray.h"
#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkUnsignedCharArray.h"

#include "facet/Error.h"
#include "facet/ImageMetrics.h"
#include "facet/MeshReference.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>

namespace {
// Samples per pixel of the mesh reference: converged (a change below 0.25/255 RMSE when
// doubled) for the bunny at 1080p (README, "Measuring error"); smaller images converge more
// slowly at the silhouette (Reference.h).
constexpr int kReferenceSamples = 128;

void AddPixelArray(vtkImageData* output, const char* name, std::span<const float> values)
{
  vtkNew<vtkFloatArray> array;
  array->SetName(name);
  array->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  output->GetPointData()->AddArray(array);
}

facet::Shading ShadingOf(int interpolation)
{
  return interpolation == VTK_PHONG ? facet::Shading::Phong
    : interpolation == VTK_GOURAUD  ? facet::Shading::Gouraud
                                    : facet::Shading::Flat;
}
}

//------------------------------------------------------------------------------
vtkFacetQuality::RenderFunction vtkFacetQuality::Prepare(const Settings& settings,
  vtkFacetMessages& messages)
{
  const int samples = settings.SamplesPerPixel;
  if (samples != 1 && samples != 4 && samples != 16)
  {
    messages.AddError("SamplesPerPixel is " + std::to_string(samples) + ", must be 1, 4 or 16");
    return {};
  }
  if (!(settings.MaximumError >= 0.0))
  {
    messages.AddError(
      "MaximumError is " + std::to_string(settings.MaximumError) + ", must be >= 0 (0: off)");
    return {};
  }
  this->Current = settings;
  this->Stats = {};
  this->Built = 0;
  const auto smooth = [](int interpolation) {
    return interpolation == VTK_GOURAUD || interpolation == VTK_PHONG;
  };
  const bool anySmooth = settings.MeshInterpolation.empty()
    ? smooth(settings.Interpolation)
    : std::any_of(settings.MeshInterpolation.begin(), settings.MeshInterpolation.end(), smooth);
  const bool reshades = anySmooth || settings.MaximumError > 0.0;
  if (!reshades && samples == 1 && !settings.EstimateError && !settings.ErrorEstimateArray &&
    !settings.ComputeError)
  {
    // The Renderer alone: nothing to prepare. The quality renderer goes (its estimate would not
    // be of the next frame) and so do the ShadingMeshes, though their keys would tell whether
    // they still hold: a mode that needs them builds them again.
    this->Keys.clear();
    this->Shading.clear();
    this->Quality.reset();
    return {};
  }
  // Flat shading with the estimate needs no ShadingMesh: the quality renderer keeps each
  // polygon's radius and normal spread per mesh version, 8 bytes per polygon.
  const bool shading = reshades || settings.ComputeError;
  if (!shading)
  {
    this->Keys.clear();
    this->Shading.clear();
  }
  return [this, shading](facet::Renderer& renderer,
           const facet::Scene& scene,
           const facet::Camera& camera,
           const facet::FramebufferView& target) {
    if (shading)
    {
      this->UpdateShading(scene, renderer);
    }
    facet::QualitySettings quality;
    quality.shading = ShadingOf(this->Current.Interpolation);
    for (const int interpolation : this->Current.MeshInterpolation)
    {
      quality.meshShading.push_back(ShadingOf(interpolation));
    }
    quality.samplesPerPixel = this->Current.SamplesPerPixel;
    if (this->Current.MaximumError > 0.0)
    {
      quality.maximumError = this->Current.MaximumError;
    }
    quality.estimateError = this->Current.EstimateError || this->Current.ErrorEstimateArray;
    quality.errorEstimateImage = this->Current.ErrorEstimateArray; // else the summary alone
    if (!this->Quality || this->QualityOf != &renderer)
    {
      this->Quality = std::make_unique<facet::QualityRenderer>(renderer);
      this->QualityOf = &renderer;
    }
    this->Stats = this->Quality->render(scene, this->Shading, camera, target, quality);
    this->RenderSeconds = this->Stats.totalSeconds;
    return this->Stats.render;
  };
}

//------------------------------------------------------------------------------
vtkFacetQuality::Key vtkFacetQuality::KeyOf(const facet::MeshView& mesh)
{
  // The version covers the points, the polygons and the point normals (the actor converter
  // gives a mesh a new one when its normals change); the color version matters only to the
  // corner color ranges, which exist with point colors or a scalar texture.
  const bool cornerColors = !mesh.pointColors.empty() || !mesh.scalarTexture.empty();
  return { mesh.points.data,
    mesh.polygons.offsets,
    mesh.polygons.connectivity,
    mesh.points.count,
    mesh.polygons.count,
    mesh.polygons.connectivitySize,
    mesh.version,
    cornerColors ? mesh.colorVersion : 0 };
}

//------------------------------------------------------------------------------
void vtkFacetQuality::UpdateShading(const facet::Scene& scene, facet::Renderer& renderer)
{
  const facet::ParallelFor parallel = facet::parallelOn(renderer); // the vertex normals
  const std::size_t meshes = scene.meshes.size();
  this->Shading.resize(meshes);
  this->Keys.resize(meshes);
  for (std::size_t m = 0; m < meshes; ++m)
  {
    const facet::MeshView& mesh = scene.meshes[m].mesh;
    const Key key = KeyOf(mesh);
    if (key != this->Keys[m] || mesh.version == 0)
    {
      this->Keys[m] = {}; // a ShadingMesh that throws leaves nothing that claims to be its
      this->Shading[m] = facet::ShadingMesh(mesh, {}, parallel);
      this->Keys[m] = key;
      ++this->Built;
    }
  }
}

//------------------------------------------------------------------------------
void vtkFacetQuality::AddOutputs(const facet::Scene& scene,
  const facet::Camera& camera,
  const std::int32_t* polygonIds,
  const double background[3],
  bool twoSidedLighting,
  int threads,
  vtkImageData* output,
  vtkFacetMessages& messages)
{
  if (!this->Shading.empty())
  {
    this->ShadingMeshesField.AddTo(output->GetFieldData(),
      "FacetShadingMeshes",
      { { "Built", static_cast<double>(this->Built) },
        { "Kept", static_cast<double>(this->Shading.size() - this->Built) } });
  }
  if (this->Current.EstimateError || this->Current.ErrorEstimateArray)
  {
    this->EstimateField.AddTo(output->GetFieldData(),
      "FacetErrorEstimate",
      { { "PredictedRMSE", this->Stats.predictedRmse },
        { "PredictedMax", this->Stats.predictedMaxError },
        { "Seconds", this->Stats.estimateSeconds } });
  }
  if (this->Current.ErrorEstimateArray && this->Quality && !this->Quality->errorEstimate().empty())
  {
    AddPixelArray(output, "ErrorEstimate", this->Quality->errorEstimate());
  }
  if (!this->Current.ComputeError)
  {
    return;
  }
  int extent[6];
  output->GetExtent(extent);
  const int width = extent[1] + 1, height = extent[3] + 1;
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(output->GetPointData()->GetScalars());
  if (!rgba || static_cast<std::size_t>(rgba->GetNumberOfTuples()) != pixels)
  {
    return;
  }
  try
  {
    std::vector<facet::VertexNormals> normals;
    for (const facet::ShadingMesh& mesh : this->Shading)
    {
      normals.push_back(mesh.normals);
    }
    facet::ReferenceOptions options;
    options.samplesPerPixel = kReferenceSamples;
    options.threads = threads;
    options.twoSidedLighting = twoSidedLighting;
    options.background = facet::Color(static_cast<float>(background[0]),
      static_cast<float>(background[1]),
      static_cast<float>(background[2]));
    const facet::ReferenceRender reference =
      facet::renderMeshReference(scene, camera, width, height, options, normals);
    const facet::FloatImage image =
      facet::toFloatImage({ reinterpret_cast<const facet::Rgba8*>(rgba->GetPointer(0)), pixels },
        { polygonIds, pixels },
        width,
        height);
    const facet::ImageError error = facet::compareImages(reference.image, image);
    this->ErrorField.AddTo(output->GetFieldData(),
      "FacetError",
      { { "RMSE", error.rmse },
        { "Max", error.maxError },
        { "PSNR", std::min(error.psnr, 1e9) },
        { "SSIM", error.ssim.value_or(1.0) },
        { "SilhouetteFraction", error.silhouetteFraction },
        { "ReferenceSeconds", reference.seconds },
        { "RenderSeconds", this->RenderSeconds } });
    AddPixelArray(output, "Error", error.errorImage);
  }
  catch (const facet::Error& e)
  {
    messages.AddWarning(std::string("cannot compute the error: ") + e.what());
  }
}

//------------------------------------------------------------------------------
void vtkFacetQuality::SummarizeEstimateArray(vtkImageData* output)
{
  auto* estimate = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("ErrorEstimate"));
  auto* summary =
    vtkDoubleArray::SafeDownCast(output->GetFieldData()->GetArray("FacetErrorEstimate"));
  if (!estimate || !summary)
  {
    return;
  }
  // QualityStats' definition: over the pixels with an estimate (a polygon covers one of
  // their samples).
  double sumOfSquares = 0.0, maximum = 0.0;
  vtkIdType estimated = 0;
  for (vtkIdType i = 0; i < estimate->GetNumberOfValues(); ++i)
  {
    const double value = estimate->GetValue(i);
    if (value != 0.0)
    {
      sumOfSquares += value * value;
      maximum = std::max(maximum, value);
      ++estimated;
    }
  }
  const double rmse =
    estimated > 0 ? std::sqrt(sumOfSquares / static_cast<double>(estimated)) : 0.0;
  for (int c = 0; c < summary->GetNumberOfComponents(); ++c)
  {
    const std::string name = summary->GetComponentName(c) ? summary->GetComponentName(c) : "";
    if (name == "PredictedRMSE" || name == "PredictedMax")
    {
      summary->SetComponent(0, c, name == "PredictedRMSE" ? rmse : maximum);
    }
  }
}
