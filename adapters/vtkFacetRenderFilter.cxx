#include "vtkFacetRenderFilter.h"

#include "vtkAbstractMapper.h"
#include "vtkCamera.h"
#include "vtkFacetActorConverter.h"
#include "vtkFacetColoringMapper.h"
#include "vtkFacetCompositor.h"
#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFacetPolyDataConverter.h"
#include "vtkFacetQuality.h"
#include "vtkFacetSceneConverter.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <string>
#include <vector>

//------------------------------------------------------------------------------
class vtkFacetRenderFilter::vtkInternals
{
public:
  vtkFacetImageRenderer Image;
  vtkFacetActorConverter Actor;
  vtkFacetQuality Quality; // shading modes, supersampling, error estimate and measurement
  vtkNew<vtkFacetColoringMapper> Coloring; // the coloring settings, a vtkMapper's
  vtkNew<vtkCamera> AutomaticCamera;       // fitted at every execution without a camera
  vtkFacetMessages Messages;
  vtkFacetCompositor Compositor;     // with other processes: one camera, one image
  vtkDataArray* GlobalIds = nullptr; // across processes: the input's usable global cell ids

  // The mapper's coloring, with the array an input array to process names (ParaView's array
  // selection) in place of the mapper's.
  vtkFacetScalarColors::Settings ColoringOf(vtkFacetRenderFilter* filter);
  // The filter's camera, or the automatic camera: a copy of the filter's camera
  // (FitCameraToInput) or VTK's default camera, fitted to `bounds`.
  vtkCamera* CameraFor(vtkCamera* camera, bool fit, const double bounds[6], int width, int height);

  // The settings an execution assembles, each from the filter's.
  static vtkFacetSceneConverter::LightOptions LightOptionsOf(vtkFacetRenderFilter* filter);
  vtkFacetActorConverter::Actor ActorOf(vtkFacetRenderFilter* filter, vtkPolyData* input);
  static vtkFacetImageRenderer::Settings SettingsOf(vtkFacetRenderFilter* filter, bool parallel);
  // Across processes (`composited`) every rank keeps its per-pixel estimate to composite.
  static vtkFacetQuality::Settings QualityOf(vtkFacetRenderFilter* filter, bool composited);
  static bool Estimates(vtkFacetRenderFilter* filter)
  {
    return filter->EstimateError || filter->ErrorEstimateArray;
  }

  // The camera to render with, fitted to `bounds` if automatic, and the scene's lights.
  facet::Camera ViewOf(vtkFacetRenderFilter* filter, const double bounds[6], facet::Scene& scene);
  // Renders in the quality mode asked for, with its reports; false after an error.
  bool Render(vtkFacetRenderFilter* filter,
    vtkPolyData* input,
    const facet::Scene& scene,
    const facet::Camera& camera,
    vtkFacetImageRenderer::Settings& settings,
    vtkImageData* output);

  // The bounds to fit the automatic camera to: the input's finite points, across processes
  // those of every piece (this is where the processes first meet: the compositor's Prepare,
  // which also learns whether the input's global cell ids fit the compositor's payload).
  void BoundsOf(vtkFacetRenderFilter* filter, vtkPolyData* input, bool parallel, double bounds[6]);
  // Turns polygon ids into CellId (across processes: global ids if the input has them, and
  // the rank in RankId); nothing without CellId.
  vtkFacetImageRenderer::IdMap CellLabels(const vtkFacetImageRenderer::Settings& settings);
  // Across processes Depth, CellId and ErrorEstimate are made to composite by: removed if not
  // asked for.
  static void RemoveArraysNotAsked(vtkFacetRenderFilter* filter, vtkImageData* output);
};

//------------------------------------------------------------------------------
vtkFacetScalarColors::Settings vtkFacetRenderFilter::vtkInternals::ColoringOf(
  vtkFacetRenderFilter* filter)
{
  vtkFacetScalarColors::Settings coloring = vtkFacetScalarColors::Settings::Of(this->Coloring);
  vtkInformation* array = filter->GetInputArrayInformation(0);
  const char* name = array->Get(vtkDataObject::FIELD_NAME());
  const int association = array->Has(vtkDataObject::FIELD_ASSOCIATION())
    ? array->Get(vtkDataObject::FIELD_ASSOCIATION())
    : -1;
  if (name && *name &&
    (association == vtkDataObject::FIELD_ASSOCIATION_POINTS ||
      association == vtkDataObject::FIELD_ASSOCIATION_CELLS))
  {
    coloring.ScalarMode = association == vtkDataObject::FIELD_ASSOCIATION_POINTS
      ? VTK_SCALAR_MODE_USE_POINT_FIELD_DATA
      : VTK_SCALAR_MODE_USE_CELL_FIELD_DATA;
    coloring.ArrayAccessMode = VTK_GET_ARRAY_BY_NAME;
    coloring.ArrayName = name;
  }
  return coloring;
}

//------------------------------------------------------------------------------
vtkCamera* vtkFacetRenderFilter::vtkInternals::CameraFor(vtkCamera* camera,
  bool fit,
  const double bounds[6],
  int width,
  int height)
{
  if (camera && !fit)
  {
    return camera;
  }
  // The direction of view, view up and projection stay; with no camera, VTK's defaults (at
  // (0, 0, 1) looking down -Z), whatever the user did to the last automatic camera.
  vtkNew<vtkCamera> fresh;
  this->AutomaticCamera->DeepCopy(camera ? camera : fresh.Get());
  vtkFacetSceneConverter::FitCamera(this->AutomaticCamera, bounds, width, height);
  return this->AutomaticCamera;
}

//------------------------------------------------------------------------------
vtkFacetSceneConverter::LightOptions vtkFacetRenderFilter::vtkInternals::LightOptionsOf(
  vtkFacetRenderFilter* filter)
{
  vtkFacetSceneConverter::LightOptions lights;
  lights.AddHeadlight = filter->AutomaticLightCreation && filter->Lights->GetNumberOfItems() == 0;
  std::copy_n(filter->AmbientLightColor, 3, lights.AmbientColor);
  return lights;
}

//------------------------------------------------------------------------------
vtkFacetActorConverter::Actor vtkFacetRenderFilter::vtkInternals::ActorOf(
  vtkFacetRenderFilter* filter,
  vtkPolyData* input)
{
  vtkFacetActorConverter::Actor actor;
  actor.Data = input;
  actor.Coloring = this->ColoringOf(filter);
  actor.Property = filter->GetProperty();
  actor.Lighting = vtkFacetSceneConverter::LightingOf(filter->Lights, LightOptionsOf(filter));
  // Without a light the filter's surfaces are lit by nothing but the ambient light, as they
  // always have been, not shown unlit.
  if (actor.Lighting == vtkFacetSceneConverter::Lighting::Unlit)
  {
    actor.Lighting = vtkFacetSceneConverter::Lighting::Lights;
  }
  return actor;
}

//------------------------------------------------------------------------------
vtkFacetImageRenderer::Settings vtkFacetRenderFilter::vtkInternals::SettingsOf(
  vtkFacetRenderFilter* filter,
  bool parallel)
{
  vtkFacetImageRenderer::Settings settings;
  settings.Width = filter->Size[0];
  settings.Height = filter->Size[1];
  settings.Threads = filter->NumberOfThreads;
  settings.Visibility = filter->VisibilityMode == PainterSort ? facet::Visibility::PainterSort
                                                              : facet::Visibility::ZBuffer;
  settings.TwoSidedLighting = filter->TwoSidedLighting != 0;
  std::copy_n(filter->Background, 3, settings.Background);
  settings.BackgroundAlpha = filter->BackgroundAlpha;
  settings.Depth = filter->OutputDepth || parallel;
  settings.CellIds = filter->OutputCellIds || parallel;
  settings.RankIds = settings.Composited = parallel;
  settings.Rules.lightTolerance = filter->LightCullingTolerance;
  settings.Rules.incremental = filter->IncrementalRendering != 0;
  return settings;
}

//------------------------------------------------------------------------------
vtkFacetQuality::Settings vtkFacetRenderFilter::vtkInternals::QualityOf(
  vtkFacetRenderFilter* filter,
  bool composited)
{
  return { filter->GetProperty()->GetInterpolation(),
    filter->SamplesPerPixel,
    filter->MaximumError,
    filter->ComputeError != 0,
    filter->EstimateError != 0,
    filter->ErrorEstimateArray || (composited && Estimates(filter)) };
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::vtkInternals::BoundsOf(vtkFacetRenderFilter* filter,
  vtkPolyData* input,
  bool parallel,
  double bounds[6])
{
  this->Actor.GetFiniteBounds(bounds);
  this->GlobalIds = nullptr;
  if (!parallel)
  {
    return;
  }
  this->GlobalIds = vtkFacetCompositor::GlobalIdsOf(input, this->Messages);
  if (this->Messages.HasErrors())
  {
    vtkMath::UninitializeBounds(bounds); // this piece adds nothing
  }
  vtkFacetCompositor::Settings composite;
  composite.Width = filter->Size[0];
  composite.Height = filter->Size[1];
  composite.Target = filter->CompositeRank;
  composite.ToAllRanks = filter->CompositeToAllRanks != 0;
  composite.Method = static_cast<vtkFacetCompositor::Strategy>(filter->CompositeStrategy);
  composite.WithEstimate = Estimates(filter);
  composite.CellIdsFit48Bits = vtkFacetCompositor::CellIdsFit48Bits(this->GlobalIds);
  this->Compositor.Prepare(filter->Controller, composite, bounds, this->Messages);
}

//------------------------------------------------------------------------------
facet::Camera vtkFacetRenderFilter::vtkInternals::ViewOf(vtkFacetRenderFilter* filter,
  const double bounds[6],
  facet::Scene& scene)
{
  const int width = filter->Size[0], height = filter->Size[1];
  vtkCamera* camera =
    this->CameraFor(filter->Camera, filter->FitCameraToInput != 0, bounds, width, height);
  const facet::Camera view =
    vtkFacetSceneConverter::ConvertCamera(camera, width, height, this->Messages);
  scene.lights = vtkFacetSceneConverter::ConvertLights(
    filter->Lights, camera, LightOptionsOf(filter), this->Messages);
  return view;
}

//------------------------------------------------------------------------------
bool vtkFacetRenderFilter::vtkInternals::Render(vtkFacetRenderFilter* filter,
  vtkPolyData* input,
  const facet::Scene& scene,
  const facet::Camera& camera,
  vtkFacetImageRenderer::Settings& settings,
  vtkImageData* output)
{
  const int conversions = this->Actor.GetNumberOfConversions();
  settings.RenderWith =
    this->Quality.Prepare(QualityOf(filter, settings.Composited), this->Messages);
  if (!this->Image.Render(
        scene, camera, settings, output, this->CellLabels(settings), conversions, this->Messages))
  {
    return false;
  }
  this->Quality.AddOutputs(scene,
    camera,
    this->Image.GetPolygonIds(),
    settings.Background,
    settings.TwoSidedLighting,
    filter->NumberOfThreads,
    output,
    this->Messages);
  return true;
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
    this->Actor.CellIdsOf(polygonIds, cellIds, begin, end);
    if (ranks)
    {
      this->Compositor.LabelPixels(
        globalIds, cellIds, this->Image.GetRankIds()->GetPointer(0), begin, end);
    }
  };
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::vtkInternals::RemoveArraysNotAsked(vtkFacetRenderFilter* filter,
  vtkImageData* output)
{
  if (!filter->OutputDepth)
  {
    output->GetPointData()->RemoveArray("Depth");
  }
  if (!filter->OutputCellIds)
  {
    output->GetPointData()->RemoveArray("CellId");
  }
  if (!filter->ErrorEstimateArray)
  {
    output->GetPointData()->RemoveArray("ErrorEstimate");
  }
}

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
vtkCamera* vtkFacetRenderFilter::GetActiveCamera()
{
  return this->Camera && !this->FitCameraToInput ? this->Camera
                                                 : this->Internals->AutomaticCamera.Get();
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::ResetCamera(vtkCamera* camera, vtkPolyData* input, int width, int height)
{
  if (!camera || !input || width < 1 || height < 1)
  {
    return;
  }
  std::vector<double> copy;
  double bounds[6];
  vtkFacetPolyDataConverter::ComputeFiniteBounds(
    vtkFacetPolyDataConverter::PointsOf(input->GetPoints(), copy), bounds);
  vtkFacetSceneConverter::FitCamera(camera, bounds, width, height);
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
// Coloring: vtkMapper's settings, held by the coloring mapper.
#define vtkFacetColoringSetting(name, type)                                                        \
  void vtkFacetRenderFilter::Set##name(type value)                                                 \
  {                                                                                                \
    this->Internals->Coloring->Set##name(value);                                                   \
  }                                                                                                \
  type vtkFacetRenderFilter::Get##name()                                                           \
  {                                                                                                \
    return this->Internals->Coloring->Get##name();                                                 \
  }
vtkFacetColoringSetting(ScalarVisibility, vtkTypeBool);
vtkFacetColoringSetting(ScalarMode, int);
vtkFacetColoringSetting(ColorMode, int);
vtkFacetColoringSetting(ArrayComponent, int);
vtkFacetColoringSetting(LookupTable, vtkScalarsToColors*);
vtkFacetColoringSetting(UseLookupTableScalarRange, vtkTypeBool);
vtkFacetColoringSetting(InterpolateScalarsBeforeMapping, vtkTypeBool);
#undef vtkFacetColoringSetting

void vtkFacetRenderFilter::SetScalarModeToDefault()
{
  this->SetScalarMode(VTK_SCALAR_MODE_DEFAULT);
}
void vtkFacetRenderFilter::SetScalarModeToUsePointData()
{
  this->SetScalarMode(VTK_SCALAR_MODE_USE_POINT_DATA);
}
void vtkFacetRenderFilter::SetScalarModeToUseCellData()
{
  this->SetScalarMode(VTK_SCALAR_MODE_USE_CELL_DATA);
}
void vtkFacetRenderFilter::SetScalarModeToUsePointFieldData()
{
  this->SetScalarMode(VTK_SCALAR_MODE_USE_POINT_FIELD_DATA);
}
void vtkFacetRenderFilter::SetScalarModeToUseCellFieldData()
{
  this->SetScalarMode(VTK_SCALAR_MODE_USE_CELL_FIELD_DATA);
}
void vtkFacetRenderFilter::SetColorModeToDefault()
{
  this->SetColorMode(VTK_COLOR_MODE_DEFAULT);
}
void vtkFacetRenderFilter::SetColorModeToMapScalars()
{
  this->SetColorMode(VTK_COLOR_MODE_MAP_SCALARS);
}
void vtkFacetRenderFilter::SetColorModeToDirectScalars()
{
  this->SetColorMode(VTK_COLOR_MODE_DIRECT_SCALARS);
}

void vtkFacetRenderFilter::SetScalarRange(double minimum, double maximum)
{
  this->Internals->Coloring->SetScalarRange(minimum, maximum);
}
void vtkFacetRenderFilter::SetScalarRange(const double range[2])
{
  this->SetScalarRange(range[0], range[1]);
}
double* vtkFacetRenderFilter::GetScalarRange()
{
  return this->Internals->Coloring->GetScalarRange();
}

// vtkMapper::SelectColorArray also sets ArrayComponent to -1 (the magnitude); the filter
// has always kept it.
void vtkFacetRenderFilter::SelectColorArray(int arrayId)
{
  this->Internals->Coloring->SetArrayId(arrayId);
  this->Internals->Coloring->SetArrayAccessMode(VTK_GET_ARRAY_BY_ID);
}
void vtkFacetRenderFilter::SelectColorArray(const char* arrayName)
{
  this->Internals->Coloring->SetArrayName(arrayName);
  this->Internals->Coloring->SetArrayAccessMode(VTK_GET_ARRAY_BY_NAME);
}
const char* vtkFacetRenderFilter::GetArrayName()
{
  const char* name = this->Internals->Coloring->GetArrayName();
  return name && *name ? name : nullptr;
}
int vtkFacetRenderFilter::GetArrayId()
{
  return this->Internals->Coloring->GetArrayId();
}
int vtkFacetRenderFilter::GetArrayAccessMode()
{
  return this->Internals->Coloring->GetArrayAccessMode();
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

  // Render straight into the output's arrays, then composite across processes.
  vtkFacetImageRenderer::Settings settings = internals.SettingsOf(this, parallel);
  const bool rendered = internals.Render(this, input, scene, camera, settings, output);
  if (parallel)
  {
    internals.Compositor.Composite(internals.Image,
      output,
      rendered,
      messages,
      vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("ErrorEstimate")));
    if (vtkFacetCompositor::IsAvailable() && output->GetNumberOfPoints() > 0)
    {
      vtkFacetQuality::SummarizeEstimateArray(output); // the composited image's, not the piece's
    }
    internals.RemoveArraysNotAsked(this, output);
    if (this->ComputeError)
    {
      // Each rank's measurement is of its own piece, not of the composited pixels.
      messages.AddWarningOnce("ComputeError across processes measures each process's piece "
                              "against that piece's reference: FacetError describes this "
                              "rank's piece, and the composited image has no Error array");
      output->GetPointData()->RemoveArray("Error");
    }
  }
  return messages.Report(this, output);
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
  vtkFacetColoringMapper* coloring = this->Internals->Coloring;
  os << indent << "ScalarVisibility: " << coloring->GetScalarVisibility() << "\n";
  os << indent << "ScalarMode: " << coloring->GetScalarModeAsString() << "\n";
  os << indent << "ColorMode: " << coloring->GetColorModeAsString() << "\n";
  os << indent << "ArrayName: " << (this->GetArrayName() ? this->GetArrayName() : "(none)") << "\n";
  os << indent << "ArrayId: " << coloring->GetArrayId() << "\n";
  os << indent << "ArrayComponent: " << coloring->GetArrayComponent() << "\n";
  os << indent << "LookupTable: " << coloring->GetLookupTableIfSet() << "\n";
  os << indent << "ScalarRange: (" << coloring->GetScalarRange()[0] << ", "
     << coloring->GetScalarRange()[1] << ")\n";
  os << indent << "UseLookupTableScalarRange: " << coloring->GetUseLookupTableScalarRange() << "\n";
  os << indent
     << "InterpolateScalarsBeforeMapping: " << coloring->GetInterpolateScalarsBeforeMapping()
     << "\n";
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
