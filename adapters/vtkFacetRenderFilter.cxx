#include "vtkFacetRenderFilter.h"

#include "vtkAbstractMapper.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFacetPolyDataConverter.h"
#include "vtkFacetScalarColors.h"
#include "vtkFacetSceneConverter.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "facet/Conventions.h"
#include "facet/Error.h"
#include "facet/HugePageAllocator.h"
#include "facet/Renderer.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

namespace {
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Memory for an image plane that the renderer writes directly: 2 MiB-aligned and advised
// to use transparent huge pages when large (tile traversal otherwise misses the TLB, see
// facet/HugePageAllocator.h). Released with free(), which VTK calls.
void* AllocatePlane(std::size_t bytes)
{
  constexpr std::size_t hugePage = facet::HugePageAllocator<char>::kHugePage;
  if (bytes < hugePage)
  {
    return std::malloc(std::max<std::size_t>(bytes, 1));
  }
  const std::size_t rounded = (bytes + hugePage - 1) / hugePage * hugePage;
  void* plane = std::aligned_alloc(hugePage, rounded);
#if defined(__linux__)
  if (plane)
  {
    madvise(plane, rounded, MADV_HUGEPAGE);
  }
#endif
  return plane;
}

// An output plane: the one kept from the last execution when nobody else holds it any more
// and it has the right shape (re-rendering then allocates and page-faults nothing; the
// pipeline empties the output before every execution, so the filter keeps its own
// reference), else a new one. Never an array somebody may still be reading.
template<class ArrayType>
ArrayType* OutputArray(vtkSmartPointer<ArrayType>& kept,
  const char* name,
  int components,
  vtkIdType tuples)
{
  if (kept && kept->GetReferenceCount() == 1 && kept->GetNumberOfComponents() == components &&
    kept->GetNumberOfTuples() == tuples)
  {
    kept->Modified();
    return kept;
  }
  const vtkIdType values = tuples * components;
  using Value = typename ArrayType::ValueType;
  auto* memory =
    static_cast<Value*>(AllocatePlane(static_cast<std::size_t>(values) * sizeof(Value)));
  if (!memory)
  {
    kept = nullptr;
    return nullptr;
  }
  kept = vtkSmartPointer<ArrayType>::New();
  kept->SetName(name);
  kept->SetNumberOfComponents(components);
  kept->SetArray(memory, values, /*save=*/0, ArrayType::VTK_DATA_ARRAY_USER_DEFINED);
  kept->SetArrayFreeFunction(std::free);
  return kept;
}

template<class ArrayType>
void AddNamedComponents(vtkFieldData* fieldData,
  const char* name,
  std::initializer_list<std::pair<const char*, typename ArrayType::ValueType>> values)
{
  vtkNew<ArrayType> array;
  array->SetName(name);
  array->SetNumberOfComponents(static_cast<int>(values.size()));
  array->SetNumberOfTuples(1);
  int component = 0;
  for (const auto& [componentName, value] : values)
  {
    array->SetComponentName(component, componentName);
    array->SetTypedComponent(0, component++, value);
  }
  fieldData->AddArray(array);
}
}

//------------------------------------------------------------------------------
class vtkFacetRenderFilter::vtkInternals
{
public:
  facet::Renderer Renderer;
  facet::HugePageVector<std::int32_t> PolygonIds; // the renderer's id plane, before mapping
  vtkSmartPointer<vtkUnsignedCharArray> Rgba;     // the output planes, kept for reuse
  vtkSmartPointer<vtkFloatArray> Depth;
  vtkSmartPointer<vtkIdTypeArray> CellIds;
  vtkFacetPolyDataConverter Mesh;
  vtkFacetScalarColors Colors;
  vtkNew<vtkCamera> AutomaticCamera; // fitted at every execution without a camera
  std::string Plan;
  bool WarnedAboutProperty = false;

  static vtkFacetScalarColors::Settings ColoringOf(vtkFacetRenderFilter& filter);
  // The scene: polys (mesh 0) then strip triangles (mesh 1), as CellIdOf numbers them.
  facet::Scene MeshesOf(const facet::Material& material) const;
  // The filter's camera, or the automatic camera: a copy of the filter's camera (FitCameraToInput)
  // or VTK's default camera, fitted to the input's finite points.
  vtkCamera* CameraFor(vtkCamera* camera, bool fit, int width, int height);
  void AddFieldData(vtkImageData* output,
    const facet::RenderStats& stats,
    double conversionSeconds,
    double outputSeconds,
    double totalSeconds);
};

//------------------------------------------------------------------------------
vtkFacetScalarColors::Settings vtkFacetRenderFilter::vtkInternals::ColoringOf(
  vtkFacetRenderFilter& filter)
{
  vtkFacetScalarColors::Settings coloring;
  coloring.ScalarVisibility = filter.ScalarVisibility != 0;
  coloring.ScalarMode = filter.ScalarMode;
  coloring.ColorMode = filter.ColorMode;
  coloring.ArrayAccessMode = filter.ArrayAccessMode;
  coloring.ArrayId = filter.ArrayId;
  coloring.ArrayName = filter.ArrayName ? filter.ArrayName : "";
  coloring.ArrayComponent = filter.ArrayComponent;
  coloring.LookupTable = filter.LookupTable;
  coloring.ScalarRange[0] = filter.ScalarRange[0];
  coloring.ScalarRange[1] = filter.ScalarRange[1];
  coloring.UseLookupTableScalarRange = filter.UseLookupTableScalarRange != 0;

  // An input array to process that names a point or cell array (ParaView's array selection).
  vtkInformation* array = filter.GetInputArrayInformation(0);
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
facet::Scene vtkFacetRenderFilter::vtkInternals::MeshesOf(const facet::Material& material) const
{
  facet::Scene scene;
  if (this->Mesh.Polygons().polygons.count > 0)
  {
    facet::MeshView polygons = this->Mesh.Polygons();
    polygons.polygonColors = this->Colors.PolygonColors();
    scene.meshes.push_back({ polygons, material });
  }
  if (this->Mesh.StripTriangles().polygons.count > 0)
  {
    facet::MeshView strips = this->Mesh.StripTriangles();
    strips.polygonColors = this->Colors.StripColors();
    scene.meshes.push_back({ strips, material });
  }
  return scene;
}

//------------------------------------------------------------------------------
vtkCamera* vtkFacetRenderFilter::vtkInternals::CameraFor(vtkCamera* camera,
  bool fit,
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
  vtkFacetSceneConverter::FitCamera(
    this->AutomaticCamera, this->Mesh.GetFiniteBounds(), width, height);
  return this->AutomaticCamera;
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::vtkInternals::AddFieldData(vtkImageData* output,
  const facet::RenderStats& stats,
  double conversionSeconds,
  double outputSeconds,
  double totalSeconds)
{
  vtkFieldData* fieldData = output->GetFieldData();
  fieldData->Initialize();
  AddNamedComponents<vtkDoubleArray>(
    fieldData, "FacetRenderSeconds", { { "Total", totalSeconds } });
  AddNamedComponents<vtkDoubleArray>(fieldData,
    "FacetPhaseSeconds",
    { { "Conversion", conversionSeconds },
      { "Validate", stats.validateSeconds },
      { "Transform", stats.transformSeconds },
      { "Setup", stats.setupSeconds },
      { "Raster", stats.rasterSeconds },
      { "Shade", stats.shadeSeconds },
      { "Output", outputSeconds } });
  const auto count = [](std::size_t n) { return static_cast<vtkIdType>(n); };
  AddNamedComponents<vtkIdTypeArray>(fieldData,
    "FacetCounts",
    { { "Polygons", count(stats.plan.polygons) },
      { "PolygonsDrawn", count(stats.polygonsDrawn) },
      { "PolygonsShaded", count(stats.polygonsShaded) },
      { "PolygonsCulled", count(stats.polygonsCulled) },
      { "PolygonsOutside", count(stats.polygonsOutside) },
      { "PolygonsDegenerate", count(stats.polygonsDegenerate) },
      { "PolygonsNonFinite", count(stats.polygonsNonFinite) },
      { "TrianglesBinned", count(stats.trianglesBinned) },
      { "TrianglesClipped", count(stats.trianglesClipped) },
      { "FragmentsWritten", count(stats.fragmentsWritten) },
      { "PixelsCovered", count(stats.pixelsCovered) } });
  AddNamedComponents<vtkIdTypeArray>(
    fieldData, "FacetMeshConverted", { { "Converted", this->Mesh.ConvertedLastUpdate() ? 1 : 0 } });
  this->Plan = stats.plan.describe();
  vtkNew<vtkStringArray> plan;
  plan->SetName("FacetRenderPlan");
  plan->InsertNextValue(this->Plan);
  fieldData->AddArray(plan);
}

vtkStandardNewMacro(vtkFacetRenderFilter);
vtkCxxSetObjectMacro(vtkFacetRenderFilter, Camera, vtkCamera);
vtkCxxSetObjectMacro(vtkFacetRenderFilter, Property, vtkProperty);
vtkCxxSetObjectMacro(vtkFacetRenderFilter, LookupTable, vtkScalarsToColors);

//------------------------------------------------------------------------------
vtkFacetRenderFilter::vtkFacetRenderFilter()
  : Internals(new vtkInternals)
{
  this->Lights = vtkLightCollection::New();
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkFacetRenderFilter::~vtkFacetRenderFilter()
{
  this->SetCamera(nullptr);
  this->SetLookupTable(nullptr);
  this->SetProperty(nullptr);
  this->Lights->Delete();
  this->SetArrayName(nullptr);
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
  if (threads < 0 || threads > 1024)
  {
    vtkErrorMacro("SetNumberOfThreads(" << threads << "): the thread count must be in [0, 1024] "
                                        << "(0: one per hardware thread); keeping "
                                        << this->NumberOfThreads);
    return;
  }
  if (threads != this->NumberOfThreads)
  {
    this->NumberOfThreads = threads;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkScalarsToColors* vtkFacetRenderFilter::GetLookupTable()
{
  return this->LookupTable ? this->LookupTable : this->Internals->Colors.GetDefaultLookupTable();
}

//------------------------------------------------------------------------------
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

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::SelectColorArray(int arrayId)
{
  this->ArrayId = arrayId;
  this->ArrayAccessMode = VTK_GET_ARRAY_BY_ID;
  this->Modified();
}

void vtkFacetRenderFilter::SelectColorArray(const char* arrayName)
{
  this->SetArrayName(arrayName);
  this->ArrayAccessMode = VTK_GET_ARRAY_BY_NAME;
  this->Modified();
}

//------------------------------------------------------------------------------
const char* vtkFacetRenderFilter::GetRenderPlan()
{
  return this->Internals->Plan.c_str();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkFacetRenderFilter::GetMTime()
{
  vtkMTimeType time = std::max(this->Superclass::GetMTime(), this->Lights->GetMTime());
  for (vtkObject* object : { static_cast<vtkObject*>(this->Camera),
         static_cast<vtkObject*>(this->Property),
         static_cast<vtkObject*>(this->LookupTable) })
  {
    if (object)
    {
      time = std::max(time, object->GetMTime());
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
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int width = this->Size[0], height = this->Size[1];
  if (width < 1 || height < 1 || width > facet::kMaxImageSide || height > facet::kMaxImageSide)
  {
    vtkErrorMacro("Size is " << width << " x " << height << "; each side must be in [1, "
                             << facet::kMaxImageSide << "] pixels");
    vtkDataObject::GetData(outInfo)->Initialize();
    return 0;
  }
  int extent[6] = { 0, width - 1, 0, height - 1, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  double spacing[3] = { 1.0, 1.0, 1.0 }, origin[3] = { 0.0, 0.0, 0.0 };
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 4);
  return 1;
}

//------------------------------------------------------------------------------
int vtkFacetRenderFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const Clock::time_point start = Clock::now();
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInternals& internals = *this->Internals;
  const int width = this->Size[0], height = this->Size[1];
  const auto fail = [&](const std::string& message) {
    vtkErrorMacro(<< message);
    output->Initialize();
    return 0;
  };
  this->UpdateProgress(0.0);

  // Conversion: kept from the last execution while the input is unchanged.
  std::string problem;
  if (!internals.Mesh.Update(input, this->DetectClosedSurfaces != 0, problem))
  {
    return fail("cannot render: " + problem);
  }
  const vtkFacetPolyDataConverter& mesh = internals.Mesh;
  if (mesh.GetNumberOfVerts() + mesh.GetNumberOfLines() > 0)
  {
    vtkWarningMacro("skipped " << mesh.GetNumberOfVerts() << " vertex and "
                               << mesh.GetNumberOfLines()
                               << " line cells: Facet renders polygons and triangle strips");
  }
  const std::string colorWarning = internals.Colors.Update(
    input, mesh, mesh.ConvertedLastUpdate(), vtkInternals::ColoringOf(*this));
  if (!colorWarning.empty())
  {
    vtkWarningMacro(<< colorWarning);
  }
  const double conversionSeconds = SecondsSince(start);
  this->UpdateProgress(0.05);

  // The scene: meshes and material, camera, lights.
  vtkProperty* property = this->GetProperty();
  if (!internals.WarnedAboutProperty &&
    (property->GetInterpolation() != VTK_FLAT || property->GetOpacity() < 1.0 ||
      property->GetRepresentation() != VTK_SURFACE))
  {
    internals.WarnedAboutProperty = true;
    vtkWarningMacro("the property asks for Gouraud/Phong interpolation, translucency or a "
                    "non-surface representation; Facet renders opaque flat-shaded surfaces "
                    "(said once)");
  }
  const bool scalarColors =
    !internals.Colors.PolygonColors().empty() || !internals.Colors.StripColors().empty();
  facet::Scene scene =
    internals.MeshesOf(vtkFacetSceneConverter::ConvertProperty(property, scalarColors));
  vtkCamera* camera =
    internals.CameraFor(this->Camera, this->FitCameraToInput != 0, width, height);
  std::string warning;
  const facet::Camera facetCamera =
    vtkFacetSceneConverter::ConvertCamera(camera, width, height, warning);
  scene.lights = vtkFacetSceneConverter::ConvertLights(
    this->Lights, camera, this->AutomaticLightCreation != 0, this->AmbientLightColor, warning);
  if (!warning.empty())
  {
    vtkWarningMacro(<< warning);
  }

  // Render straight into the output's RGBA and Depth arrays.
  const vtkIdType pixels = static_cast<vtkIdType>(width) * height;
  output->SetExtent(0, width - 1, 0, height - 1, 0, 0);
  output->SetSpacing(1.0, 1.0, 1.0);
  output->SetOrigin(0.0, 0.0, 0.0);
  vtkPointData* pointData = output->GetPointData();
  auto* rgba = OutputArray(internals.Rgba, "RGBA", 4, pixels);
  auto* depth = OutputArray(internals.Depth, "Depth", 1, pixels);
  auto* cellIds = OutputArray(internals.CellIds, "CellId", 1, pixels);
  if (!rgba || !depth || !cellIds)
  {
    return fail("cannot allocate the " + std::to_string(width) + " x " + std::to_string(height) +
      " output image");
  }
  pointData->SetScalars(rgba);
  pointData->AddArray(depth);
  pointData->AddArray(cellIds);
  internals.PolygonIds.resize(static_cast<std::size_t>(pixels));
  const facet::FramebufferView target{ width,
    height,
    reinterpret_cast<facet::Rgba8*>(rgba->GetPointer(0)),
    depth->GetPointer(0),
    internals.PolygonIds.data() };

  facet::Renderer& renderer = internals.Renderer;
  facet::RenderStats stats;
  try
  {
    renderer.setThreadCount(this->NumberOfThreads);
    renderer.setVisibility(this->VisibilityMode == PainterSort ? facet::Visibility::PainterSort
                                                               : facet::Visibility::ZBuffer);
    renderer.setTwoSidedLighting(this->TwoSidedLighting != 0);
    renderer.setBackground(facet::Color(static_cast<float>(this->Background[0]),
                             static_cast<float>(this->Background[1]),
                             static_cast<float>(this->Background[2])),
      static_cast<float>(this->BackgroundAlpha));
    renderer.setProgressCallback([this](double fraction) {
      this->UpdateProgress(0.05 + 0.9 * fraction);
      return !this->GetAbortExecute();
    });
    stats = renderer.render(scene, facetCamera, target);
  }
  catch (const facet::Error& e)
  {
    return fail(std::string("cannot render: ") + e.what());
  }
  if (stats.polygonsNonFinite > 0)
  {
    vtkWarningMacro("skipped " << stats.polygonsNonFinite
                               << " cells that use points with NaN or infinite coordinates");
  }

  // Cell ids, then what it cost.
  const Clock::time_point outputStart = Clock::now();
  // Memory-bound and elementwise: on the renderer's threads.
  renderer.parallelFor(static_cast<std::size_t>(pixels),
    std::size_t{ 1 } << 16,
    [&](std::size_t begin, std::size_t end) {
      mesh.CellIdsOf(internals.PolygonIds.data(),
        cellIds->GetPointer(0),
        static_cast<vtkIdType>(begin),
        static_cast<vtkIdType>(end));
    });
  const double outputSeconds = SecondsSince(outputStart);

  internals.AddFieldData(output, stats, conversionSeconds, outputSeconds, SecondsSince(start));
  this->UpdateProgress(1.0);
  return 1;
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
  os << indent << "Property: " << this->Property << "\n";
  os << indent << "ScalarVisibility: " << this->ScalarVisibility << "\n";
  os << indent << "ScalarMode: " << this->ScalarMode << "\n";
  os << indent << "ColorMode: " << this->ColorMode << "\n";
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(none)") << "\n";
  os << indent << "ArrayId: " << this->ArrayId << "\n";
  os << indent << "ArrayComponent: " << this->ArrayComponent << "\n";
  os << indent << "LookupTable: " << this->LookupTable << "\n";
  os << indent << "ScalarRange: (" << this->ScalarRange[0] << ", " << this->ScalarRange[1] << ")\n";
  os << indent << "UseLookupTableScalarRange: " << this->UseLookupTableScalarRange << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent
     << "VisibilityMode: " << (this->VisibilityMode == PainterSort ? "PainterSort" : "ZBuffer")
     << "\n";
  os << indent << "DetectClosedSurfaces: " << this->DetectClosedSurfaces << "\n";
}
