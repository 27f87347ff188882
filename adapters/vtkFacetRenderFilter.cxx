#include "vtkFacetRenderFilter.h"
#include "vtkFacetRenderFilterInternals.h"

#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkFacetRenderFilter);
vtkCxxSetObjectMacro(vtkFacetRenderFilter, Camera, vtkCamera);
vtkCxxSetObjectMacro(vtkFacetRenderFilter, Property, vtkProperty);
vtkCxxSetObjectMacro(vtkFacetRenderFilter, Controller, vtkMultiProcessController);

//------------------------------------------------------------------------------
vtkFacetRenderFilter::vtkFacetRenderFilter()
  : Internals(new vtkInternals)
{
  this->Lights = vtkLightCollection::New();
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

//------------------------------------------------------------------------------
vtkFacetRenderFilter::~vtkFacetRenderFilter()
{
  this->SetCamera(nullptr);
  this->SetProperty(nullptr);
  this->SetController(nullptr);
  this->Lights->Delete();
  delete this->Internals;
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::AddLight(vtkLight* light)
{
  this->Lights->AddItem(light);
  this->Modified();
}

void vtkFacetRenderFilter::RemoveLight(vtkLight* light)
{
  this->Lights->RemoveItem(light);
  this->Modified();
}

void vtkFacetRenderFilter::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}

//------------------------------------------------------------------------------
vtkProperty* vtkFacetRenderFilter::GetProperty()
{
  if (!this->Property)
  {
    this->Property = vtkProperty::New();
    this->Property->SetInterpolationToFlat(); // what Facet renders
  }
  return this->Property;
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::SetNumberOfThreads(int threads)
{
  if (vtkFacetImageRenderer::CheckThreadCount(this, threads, this->NumberOfThreads) &&
    threads != this->NumberOfThreads)
  {
    this->NumberOfThreads = threads;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
bool vtkFacetRenderFilter::CanComposite()
{
  return vtkFacetCompositor::IsAvailable();
}

//------------------------------------------------------------------------------
const char* vtkFacetRenderFilter::GetRenderPlan()
{
  return this->Internals->Image.GetPlan().c_str();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkFacetRenderFilter::GetMTime()
{
  vtkFacetColoringMapper* coloring = this->Internals->Coloring;
  // The coloring mapper's own settings; its lookup table is looked at below.
  vtkMTimeType time = std::max(
    { this->Superclass::GetMTime(), this->Lights->GetMTime(), coloring->vtkObject::GetMTime() });
  for (vtkObject* object :
    { static_cast<vtkObject*>(this->Camera), static_cast<vtkObject*>(this->Property) })
  {
    if (object)
    {
      time = std::max(time, object->GetMTime());
    }
  }
  // The lookup table, unless its last change was the execution's own preparation (built,
  // given the scalar range), which must not make the next Update execute again.
  if (vtkScalarsToColors* table = coloring->GetLookupTableIfSet())
  {
    if (table->GetMTime() != this->Internals->Actor.GetPreparedTableTime(table))
    {
      time = std::max(time, table->GetMTime());
    }
  }
  vtkCollectionSimpleIterator iterator;
  this->Lights->InitTraversal(iterator);
  while (vtkLight* light = this->Lights->GetNextLight(iterator))
  {
    time = std::max(time, light->GetMTime());
  }
  return time;
}

//------------------------------------------------------------------------------
int vtkFacetRenderFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkFacetRenderFilter::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  return vtkFacetImageRenderer::RequestInformation(
    this, outputVector->GetInformationObject(0), this->Size[0], this->Size[1]);
}

//------------------------------------------------------------------------------
int vtkFacetRenderFilter::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // Across processes each renders its piece of the input, the one VTK's parallel pipeline
  // gives a process: piece = rank, pieces = processes, no ghost cells (they would be drawn
  // twice).
  if (vtkFacetCompositor::IsParallel(this->Controller))
  {
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(),
      this->Controller->GetLocalProcessId());
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(),
      this->Controller->GetNumberOfProcesses());
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkFacetRenderFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInternals& internals = *this->Internals;
  vtkFacetMessages& messages = internals.Messages;
  internals.Image.Start(this);

  // The actor: the input's polygons, colored as the mapper colors them, with the property's
  // material (each kept from the last execution while unchanged).
  facet::Scene scene;
  if (internals.Actor.Update(
        internals.ActorOf(this, input), this->DetectClosedSurfaces != 0, messages))
  {
    internals.Actor.AddTo(scene);
  }
  internals.Image.ConversionDone();

  // The camera, fitted across processes to the union of all pieces' bounds (all render one
  // view), and the lights.
  const bool parallel = vtkFacetCompositor::IsParallel(this->Controller);
  double bounds[6];
  internals.BoundsOf(this, input, parallel, bounds);
  const facet::Camera camera = internals.ViewOf(this, bounds, scene);

  // Render straight into the output's arrays in the quality mode asked for, then composite
  // across processes.
  vtkFacetFrame frame{ scene,
    camera,
    internals.SettingsOf(this, parallel),
    internals.QualityOf(this, parallel),
    {},
    internals.Actor.GetNumberOfConversions() };
  frame.MapIds = internals.CellLabels(frame.Image);
  const bool rendered = frame.Render(output, internals.Image, internals.Quality, messages);
  if (parallel)
  {
    internals.Composite(this, output, rendered);
  }
  return messages.Report(this, output);
}

//------------------------------------------------------------------------------
vtkFacetImageRenderer::IdMap vtkFacetRenderFilter::vtkInternals::CellLabels(
  const vtkFacetImageRenderer::Settings& settings)
{
  if (!settings.CellIds)
  {
    return {};
  }
  const bool ranks = settings.RankIds;
  vtkDataArray* globalIds = ranks ? this->GlobalIds : nullptr;
  return [this, ranks, globalIds](const std::int32_t* polygonIds, vtkIdType begin, vtkIdType end) {
    vtkIdType* cellIds = this->Image.GetCellIds()->GetPointer(0);
    // Streamed past the caches unless the compositor reads them back at once.
    this->Actor.CellIdsOf(polygonIds, cellIds, begin, end, !ranks && this->Image.StreamsIdPlanes());
    if (ranks)
    {
      this->Compositor.LabelPixels(
        globalIds, cellIds, this->Image.GetRankIds()->GetPointer(0), begin, end);
    }
  };
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "Background: (" << this->Background[0] << ", " << this->Background[1] << ", "
     << this->Background[2] << "), alpha " << this->BackgroundAlpha << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "FitCameraToInput: " << this->FitCameraToInput << "\n";
  os << indent << "ActiveCamera: " << this->GetActiveCamera()
     << (this->Camera && !this->FitCameraToInput ? "" : " (automatic)") << "\n";
  os << indent << "Lights: " << this->Lights->GetNumberOfItems() << "\n";
  os << indent << "AutomaticLightCreation: " << this->AutomaticLightCreation << "\n";
  os << indent << "AmbientLightColor: (" << this->AmbientLightColor[0] << ", "
     << this->AmbientLightColor[1] << ", " << this->AmbientLightColor[2] << ")\n";
  os << indent << "TwoSidedLighting: " << this->TwoSidedLighting << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "MaximumError: " << this->MaximumError << "\n";
  os << indent << "ComputeError: " << this->ComputeError << "\n";
  os << indent << "EstimateError: " << this->EstimateError << "\n";
  os << indent << "ErrorEstimateArray: " << this->ErrorEstimateArray << "\n";
  os << indent << "OutputDepth: " << this->OutputDepth << "\n";
  os << indent << "OutputCellIds: " << this->OutputCellIds << "\n";
  os << indent << "LightCullingTolerance: " << this->LightCullingTolerance << "\n";
  os << indent << "IncrementalRendering: " << this->IncrementalRendering << "\n";
  os << indent << "Property: " << this->Property << "\n";
  this->Internals->PrintColoring(this, os, indent);
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent
     << "VisibilityMode: " << (this->VisibilityMode == PainterSort ? "PainterSort" : "ZBuffer")
     << "\n";
  os << indent << "DetectClosedSurfaces: " << this->DetectClosedSurfaces << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "CompositeRank: " << this->CompositeRank << "\n";
  os << indent << "CompositeToAllRanks: " << this->CompositeToAllRanks << "\n";
  const char* strategies[] = { "Automatic", "BinarySwap", "Tree", "RadixK" };
  os << indent << "CompositeStrategy: " << strategies[this->CompositeStrategy] << "\n";
}
