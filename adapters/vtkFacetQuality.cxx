#include "vtkFacetQuality.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkUnsignedCharArray.h"

#include "facet/Error.h"
#include "facet/ImageMetrics.h"
#include "facet/MeshReference.h"

#include <algorithm>
#include <chrono>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <utility>

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

// The input's point normals as xyz doubles, or nothing (none, or not 3 components).
std::vector<double> NormalsOf(vtkPolyData* input)
{
  vtkDataArray* normals = input ? input->GetPointData()->GetNormals() : nullptr;
  if (!normals || normals->GetNumberOfComponents() != 3 ||
    normals->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    return {};
  }
  std::vector<double> xyz(3 * static_cast<std::size_t>(normals->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    normals->GetTuple(i, xyz.data() + 3 * i);
  }
  return xyz;
}
}

//------------------------------------------------------------------------------
vtkFacetQuality::RenderFunction vtkFacetQuality::Prepare(const facet::Scene& scene,
  vtkPolyData* input,
  const Settings& settings,
  bool converted,
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
    // The Renderer alone: nothing to prepare, nothing kept (the meshes may change unseen
    // meanwhile, and the quality renderer's estimate would not be of the next frame).
    this->Keys.clear();
    this->Shading.clear();
    this->Quality.reset();
    return {};
  }
  std::vector<Key> keys;
  for (const facet::SceneMesh& mesh : scene.meshes)
  {
    // The version too: an actor's world points move in place when its matrix changes.
    keys.emplace_back(mesh.mesh.points.data, mesh.mesh.polygons.count, mesh.mesh.version);
  }
  // The input's normals are attributes: new ones come without a new conversion.
  vtkDataArray* normalsArray = input ? input->GetPointData()->GetNormals() : nullptr;
  const std::pair<vtkDataArray*, vtkMTimeType> normalsSource{ normalsArray,
    normalsArray ? normalsArray->GetMTime() : 0 };
  if (converted || keys != this->Keys || normalsSource != this->NormalsSource)
  {
    this->NormalsSource = normalsSource;
    this->Keys.clear(); // a ShadingMesh that throws leaves nothing half-made behind
    this->Shading.clear();
    // New normals only when they differ: the quality renderer keeps what it derives from
    // them per mesh version, which their time joins below.
    std::vector<double> normals = NormalsOf(input);
    if (normals != this->Normals)
    {
      this->Normals.swap(normals);
      this->NormalsTime.Modified();
    }
  }
  // Flat shading with the estimate needs no ShadingMesh: the quality renderer keeps each
  // polygon's normal, extent, normal spread and center per mesh version, 48 bytes per polygon.
  const bool shading = reshades || settings.ComputeError;
  if (!shading)
  {
    this->Shading.clear();
  }
  return [this, shading, keys](facet::Renderer& renderer,
           const facet::Scene& given,
           const facet::Camera& camera,
           const facet::FramebufferView& target) {
    facet::Scene scene = given; // views only: cheap
    const std::size_t pointCount = this->Normals.size() / 3;
    for (facet::SceneMesh& mesh : scene.meshes)
    {
      if (pointCount > 0 && mesh.mesh.points.count == pointCount)
      {
        mesh.mesh.pointNormals = facet::PointArray::ofXyz(std::span<const double>(this->Normals));
        if (mesh.mesh.version != 0)
        {
          mesh.mesh.version = std::max<std::uint64_t>(mesh.mesh.version, this->NormalsTime);
        }
      }
    }
    if (shading && this->Shading.empty())
    {
      for (const facet::SceneMesh& mesh : scene.meshes)
      {
        this->Shading.emplace_back(mesh.mesh);
      }
    }
    this->Keys = keys;
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
void vtkFacetQuality::AddOutputs(const facet::Scene& scene,
  const facet::Camera& camera,
  const std::int32_t* polygonIds,
  const double background[3],
  bool twoSidedLighting,
  int threads,
  vtkImageData* output,
  vtkFacetMessages& messages)
{
  if (this->Current.EstimateError || this->Current.ErrorEstimateArray)
  {
    vtkFacetImageRenderer::AddNamedComponents<vtkDoubleArray>(output->GetFieldData(),
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
    vtkFacetImageRenderer::AddNamedComponents<vtkDoubleArray>(output->GetFieldData(),
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
