#include "vtkFacetRendererToImageFilter.h"
#include "vtkFacetRendererToImageFilterInternals.h"

#include "vtkCamera.h"
#include "vtkFacetFrame.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <map>

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkFacetRendererToImageFilter);
vtkCxxSetObjectMacro(vtkFacetRendererToImageFilter, Renderer, vtkRenderer);

//------------------------------------------------------------------------------
vtkFacetRendererToImageFilter::vtkFacetRendererToImageFilter()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkFacetRendererToImageFilter::~vtkFacetRendererToImageFilter()
{
  this->SetRenderer(nullptr);
  delete this->Internals;
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::GetEffectiveSize(int size[2])
{
  size[0] = this->Size[0];
  size[1] = this->Size[1];
  if (size[0] != 0 || size[1] != 0)
  {
    return;
  }
  vtkRenderWindow* window = this->Renderer ? this->Renderer->GetRenderWindow() : nullptr;
  const int* windowSize = window ? window->GetSize() : nullptr;
  if (windowSize && windowSize[0] > 0 && windowSize[1] > 0)
  {
    const int* rendererSize = this->Renderer->GetSize(); // its viewport, in pixels
    size[0] = rendererSize[0];
    size[1] = rendererSize[1];
    return;
  }
  size[0] = 640;
  size[1] = 480;
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::SetNumberOfThreads(int threads)
{
  if (vtkFacetImageRenderer::CheckThreadCount(this, threads, this->NumberOfThreads) &&
    threads != this->NumberOfThreads)
  {
    this->NumberOfThreads = threads;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
const char* vtkFacetRendererToImageFilter::GetRenderPlan()
{
  return this->Internals->Image.GetPlan().c_str();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkFacetRendererToImageFilter::GetMTime()
{
  // What changed since the last execution saw it: changes made during an execution, by the
  // user or by the execution itself (a lookup table built, a camera created), are in its
  // image and must not make the next Update render again.
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->Renderer)
  {
    const std::map<vtkObject*, vtkMTimeType>& seen = this->Internals->Seen;
    vtkInternals::ForEachSceneObject(this->Renderer, [&](vtkObject* object) {
      const auto found = object ? seen.find(object) : seen.end();
      if (object && (found == seen.end() || found->second != object->GetMTime()))
      {
        time = std::max(time, object->GetMTime());
      }
    });
  }
  return time;
}

//------------------------------------------------------------------------------
int vtkFacetRendererToImageFilter::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  int size[2];
  this->GetEffectiveSize(size);
  return vtkFacetImageRenderer::RequestInformation(
    this, outputVector->GetInformationObject(0), size[0], size[1]);
}

//------------------------------------------------------------------------------
int vtkFacetRendererToImageFilter::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInternals& internals = *this->Internals;
  vtkFacetMessages& messages = internals.Messages;
  vtkRenderer* renderer = this->Renderer;
  if (!renderer)
  {
    messages.AddError("no renderer to render: call SetRenderer");
    return messages.Report(this, output);
  }
  int size[2];
  this->GetEffectiveSize(size);
  internals.Image.Start(this);

  // The renderer's lights: with none on, the headlight vtkRenderer would create, or none.
  const vtkFacetSceneConverter::LightOptions lights = vtkInternals::LightOptionsOf(renderer);
  const vtkFacetSceneConverter::Lighting lighting =
    vtkFacetSceneConverter::LightingOf(renderer->GetLights(), lights);

  // The actors, then the camera (fitted to them if the renderer has none) and the lights.
  facet::Scene scene;
  internals.AddActors(renderer, lighting, this->DetectClosedSurfaces != 0, scene);
  internals.Image.ConversionDone();
  vtkCamera* camera = internals.CameraOf(renderer, size[0], size[1]);
  const facet::Camera facetCamera =
    vtkFacetSceneConverter::ConvertCamera(camera, size[0], size[1], messages);
  scene.lights =
    vtkFacetSceneConverter::ConvertLights(renderer->GetLights(), camera, lights, messages);
  vtkInternals::WarnAboutUnrendered(renderer, messages);
  vtkFacetImageRenderer::Settings settings;
  settings.Width = size[0];
  settings.Height = size[1];
  settings.ActorIds = true;
  settings.Threads = this->NumberOfThreads;
  settings.TwoSidedLighting = renderer->GetTwoSidedLighting() != 0;
  renderer->GetBackground(settings.Background);
  // A window without alpha bit planes (VTK's default) reads back opaque.
  vtkRenderWindow* window = renderer->GetRenderWindow();
  settings.BackgroundAlpha =
    window && window->GetAlphaBitPlanes() ? renderer->GetBackgroundAlpha() : 1.0;

  // Each actor's interpolation, the samples and the budget (vtkFacetQuality); polygon ids
  // become actor and cell ids.
  vtkFacetFrame frame{ scene, facetCamera, settings, {}, {}, internals.NumberOfConversions() };
  frame.Quality.SamplesPerPixel = this->SamplesPerPixel;
  frame.Quality.MaximumError = this->MaximumError;
  frame.Quality.EstimateError = this->EstimateError != 0;
  frame.Quality.ErrorEstimateArray = this->ErrorEstimateArray != 0;
  frame.Quality.MeshInterpolation = internals.MeshInterpolation;
  frame.MapIds = [&](const std::int32_t* polygonIds, vtkIdType begin, vtkIdType end) {
    internals.MapIds(renderer, polygonIds, begin, end);
  };
  // Render straight into the output's arrays.
  frame.Render(output, internals.Image, internals.Quality, messages);
  internals.RememberScene(renderer);
  return messages.Report(this, output);
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Renderer: " << this->Renderer << "\n";
  int size[2];
  this->GetEffectiveSize(size);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << " (renders at " << size[0]
     << " x " << size[1] << ")\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "DetectClosedSurfaces: " << this->DetectClosedSurfaces << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "MaximumError: " << this->MaximumError << "\n";
  os << indent << "EstimateError: " << this->EstimateError << "\n";
  os << indent << "ErrorEstimateArray: " << this->ErrorEstimateArray << "\n";
}
