// VTK-HeaderTest-Exclude: vtkFacetImageRenderer.h
#include "vtkFacetImageRenderer.h"

#include "vtkAlgorithm.h"
#include "vtkDoubleArray.h"
#include "vtkFacetMessages.h"
#include "vtkFacetSeconds.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "facet/Conventions.h"
#include "facet/Error.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <algorithm>
#include <atomic>
#include <cstdlib>

namespace {
// Memory for an image plane that the renderer writes directly: 2 MiB-aligned and advised
// to use transparent huge pages when large, as HugePageAllocator lays its buffers out. Released
// with free(), which VTK calls.
void* AllocatePlane(std::size_t bytes)
{
  constexpr std::size_t hugePage = facet::HugePageAllocator<char>::kHugePage;
  if (bytes < hugePage)
  {
    return std::malloc(std::max<std::size_t>(bytes, 1));
  }
  const auto layout = facet::HugePageAllocator<char>::layoutOf(bytes);
  // aligned_alloc takes a multiple of the alignment (ASan enforces it): the part past
  // layout.allocated is address space the plane never touches, so never resident.
  const std::size_t multiple = (layout.allocated + hugePage - 1) / hugePage * hugePage;
  void* plane = std::aligned_alloc(hugePage, multiple);
#if defined(__linux__)
  if (plane)
  {
    madvise(plane, layout.advised, MADV_HUGEPAGE);
  }
#endif
  return plane;
}

// An output plane: the one kept from the last execution when nobody else holds it any more
// and it has the right shape, else a new one. Never an array somebody may still be reading.
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

}

//------------------------------------------------------------------------------
int vtkFacetImageRenderer::RequestInformation(vtkAlgorithm* algorithm,
  vtkInformation* outInfo,
  int width,
  int height)
{
  if (width < 1 || height < 1 || width > facet::kMaxImageSide || height > facet::kMaxImageSide)
  {
    vtkErrorWithObjectMacro(algorithm,
      "Size is " << width << " x " << height << "; each side must be in [1, "
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
vtkFloatArray* vtkFacetImageRenderer::GetDepth() const
{
  return this->Depth;
}

vtkIntArray* vtkFacetImageRenderer::GetRankIds() const
{
  return this->RankIds;
}

//------------------------------------------------------------------------------
bool vtkFacetImageRenderer::CheckThreadCount(vtkObject* object, int threads, int current)
{
  if (threads < 0 || threads > 1024)
  {
    vtkErrorWithObjectMacro(object,
      "SetNumberOfThreads(" << threads << "): the thread count must be in [0, 1024] "
                            << "(0: one per hardware thread); keeping " << current);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkFacetImageRenderer::Start(vtkAlgorithm* algorithm)
{
  this->Algorithm = algorithm;
  this->StartTime = Clock::now();
  this->ConversionSeconds = 0.0;
  algorithm->UpdateProgress(0.0);
}

void vtkFacetImageRenderer::ConversionDone()
{
  this->ConversionSeconds = vtkFacetSecondsSince(this->StartTime);
  this->Algorithm->UpdateProgress(0.05);
}

//------------------------------------------------------------------------------
bool vtkFacetImageRenderer::Allocate(const Settings& settings,
  vtkImageData* output,
  vtkFacetMessages& messages)
{
  const int width = settings.Width, height = settings.Height;
  const vtkIdType pixels = static_cast<vtkIdType>(width) * height;
  output->SetExtent(0, width - 1, 0, height - 1, 0, 0);
  output->SetSpacing(1.0, 1.0, 1.0);
  output->SetOrigin(0.0, 0.0, 0.0);
  // The output's own references go first: vtkImageData::PrepareForNewData keeps the last
  // execution's scalars in it (for image filters that allocate alike), and that reference
  // alone must not make RGBA look held by somebody else (a new 8 MB plane at 1080p at every
  // execution, faulted in and zeroed by the kernel).
  vtkPointData* pointData = output->GetPointData();
  pointData->Initialize();
  // The renderer's depth plane must stay as the last render left it (incremental
  // rendering). It is the output's Depth array until somebody else holds that array (ParaView's
  // representations do) or a compositor writes into it; from then on it is a plane of this
  // class's own, copied into Depth.
  this->OwnDepthPlane = this->OwnDepthPlane || settings.Composited ||
    (this->Depth && this->Depth->GetReferenceCount() > 1);
  pointData->SetScalars(OutputArray(this->Rgba, "RGBA", 4, pixels));
  // An array not asked for is released, not kept.
  const auto add = [&](auto& kept, bool wanted, const char* name) {
    if (!wanted)
    {
      kept = nullptr;
      return true;
    }
    pointData->AddArray(OutputArray(kept, name, 1, pixels));
    return kept != nullptr;
  };
  // The last frame's CellId, if nobody marked it modified since (OutputArray marks it below).
  const vtkIdTypeArray* lastCellIds =
    this->CellIds && this->CellIds->GetMTime() == this->CellIdsWrittenTime ? this->CellIds.Get()
                                                                           : nullptr;
  const bool allocated = add(this->Depth, settings.Depth, "Depth") &&
    add(this->CellIds, settings.CellIds, "CellId") &&
    add(this->ActorIds, settings.ActorIds, "ActorId") &&
    add(this->RankIds, settings.RankIds, "RankId");
  // CellId alone, in the plane the last frame wrote at this size, may skip the background
  // it already holds.
  this->SkipsBackgroundIds = allocated && settings.CellIdsOnly && this->CellIds &&
    this->CellIds == lastCellIds && width == this->Width && height == this->Height;
  if (!this->SkipsBackgroundIds)
  {
    this->CellIdSpans.Forget(width, height);
  }
  if (!this->Rgba || !allocated)
  {
    messages.AddError("cannot allocate the " + std::to_string(width) + " x " +
      std::to_string(height) + " output image");
    return false;
  }
  this->PolygonIds.resize(static_cast<std::size_t>(pixels));
  this->RenderDepth.resize(settings.Depth && this->OwnDepthPlane ? pixels : 0);
  this->Width = width;
  this->Height = height;
  return true;
}

//------------------------------------------------------------------------------
bool vtkFacetImageRenderer::Render(const facet::Scene& scene,
  const facet::Camera& camera,
  const Settings& settings,
  vtkImageData* output,
  const IdMap& mapIds,
  int conversions,
  vtkFacetMessages& messages)
{
  if (messages.HasErrors() || !this->Allocate(settings, output, messages))
  {
    return false;
  }
  // The renderer's planes: kept from one execution to the next, untouched in between, so
  // that it can reuse the frame they hold.
  float* depth = !settings.Depth ? nullptr
    : this->OwnDepthPlane        ? this->RenderDepth.data()
                                 : this->Depth->GetPointer(0);
  const facet::FramebufferView target{ this->Width,
    this->Height,
    reinterpret_cast<facet::Rgba8*>(this->Rgba->GetPointer(0)),
    depth,
    this->PolygonIds.data() };
  // The arrays made from the renderer's planes (CellId from the ids, Depth copied from the
  // renderer's own plane), for pixels [begin, end) whose render is final.
  const std::int32_t* polygonIds = this->PolygonIds.data();
  const float* renderDepth = this->RenderDepth.empty() ? nullptr : this->RenderDepth.data();
  const auto writeOutput = [&](vtkIdType begin, vtkIdType end) {
    if (renderDepth)
    {
      std::copy(renderDepth + begin, renderDepth + end, this->Depth->GetPointer(0) + begin);
    }
    if (mapIds)
    {
      mapIds(polygonIds, begin, end);
    }
  };
  // A band's CellId: only where this frame's or the last one's ids are not background.
  // The renderer says which columns may show a polygon: the ids outside are not read.
  const auto writeBandIds = [&](vtkIdType firstRow, vtkIdType endRow, int shownX0, int shownX1) {
    if (!this->SkipsBackgroundIds)
    {
      mapIds(polygonIds, firstRow * this->Width, endRow * this->Width);
      return;
    }
    this->CellIdSpans.WriteChanged(
      polygonIds, firstRow, endRow, shownX0, shownX1, [&](vtkIdType begin, vtkIdType end) {
        mapIds(polygonIds, begin, end);
      });
  };
  const bool writesOutput = mapIds || renderDepth;
  std::atomic<int> rowsWritten{ 0 };
  struct Unhook // the callback refers to this frame: gone with it, also on an exception
  {
    facet::Renderer& Renderer;
    ~Unhook() { this->Renderer.setResolvedRowsCallback({}); }
  } unhook{ this->Renderer };
  facet::RenderStats stats;
  try
  {
    this->Renderer.setThreadCount(settings.Threads);
    this->Renderer.setVisibility(settings.Visibility);
    this->Renderer.setTwoSidedLighting(settings.TwoSidedLighting);
    this->Renderer.setDepthOutput(settings.Depth);
    this->Renderer.setRules(settings.Rules);
    const double* b = settings.Background;
    this->Renderer.setBackground(
      facet::Color(static_cast<float>(b[0]), static_cast<float>(b[1]), static_cast<float>(b[2])),
      static_cast<float>(settings.BackgroundAlpha));
    vtkAlgorithm* algorithm = this->Algorithm;
    this->Renderer.setProgressCallback([algorithm](double fraction) {
      algorithm->UpdateProgress(0.05 + 0.9 * fraction);
      return !algorithm->GetAbortExecute();
    });
    // Each band of the image as soon as the resolve leaves it, its ids still in cache, in
    // place of a pass over the planes after the render (1.4-1.6 ms at 1080p): only bands of
    // this image (not of a quality mode's sample grid).
    this->Renderer.setResolvedRowsCallback(!writesOutput
        ? facet::Renderer::ResolvedRowsCallback{}
        : [&](const facet::FramebufferView& view, int y0, int y1, int x0, int x1) {
            if (view.polygonId == polygonIds && view.width == this->Width)
            {
              const vtkIdType begin = static_cast<vtkIdType>(y0) * this->Width,
                              end = static_cast<vtkIdType>(y1 + 1) * this->Width;
              if (renderDepth)
              {
                std::copy(
                  renderDepth + begin, renderDepth + end, this->Depth->GetPointer(0) + begin);
              }
              if (mapIds)
              {
                writeBandIds(y0, y1 + 1, x0, x1);
              }
              rowsWritten += y1 - y0 + 1;
            }
          });
    stats = settings.RenderWith ? settings.RenderWith(this->Renderer, scene, camera, target)
                                : this->Renderer.render(scene, camera, target);
  }
  catch (const facet::Error& e)
  {
    messages.AddError(std::string("cannot render: ") + e.what());
    return false;
  }
  if (stats.polygonsNonFinite > 0)
  {
    messages.AddWarning("skipped " + std::to_string(stats.polygonsNonFinite) +
      " cells that use points with NaN or infinite coordinates");
  }
  // A pass over the whole image when the bands did not write it: after a render that stopped
  // (it then cleared the image), or one whose resolved bands were not this image's rows, each
  // once (a quality mode that renders a sample grid).
  const Clock::time_point outputStart = Clock::now();
  if (writesOutput && (stats.aborted || rowsWritten != this->Height))
  {
    this->CellIdSpans.Forget(this->Width, this->Height); // every id written
    this->ForEachPixelBlock(writeOutput);
  }
  this->CellIdsWrittenTime = this->CellIds ? this->CellIds->GetMTime() : 0;
  this->OutputSeconds = vtkFacetSecondsSince(outputStart);
  this->AddFieldData(output, stats, conversions);
  this->Algorithm->UpdateProgress(1.0);
  return true;
}

//------------------------------------------------------------------------------
void vtkFacetImageRenderer::ForEachPixelBlock(
  const std::function<void(vtkIdType begin, vtkIdType end)>& work)
{
  // Memory-bound and elementwise: on the renderer's threads.
  this->Renderer.parallelFor(static_cast<std::size_t>(this->Width) * this->Height,
    std::size_t{ 1 } << 16,
    [&](std::size_t begin, std::size_t end) {
      work(static_cast<vtkIdType>(begin), static_cast<vtkIdType>(end));
    });
}

//------------------------------------------------------------------------------
void vtkFacetImageRenderer::AddFieldData(vtkImageData* output,
  const facet::RenderStats& stats,
  int conversions)
{
  vtkFieldData* fieldData = output->GetFieldData();
  fieldData->Initialize();
  FieldArrays& fields = this->Fields;
  fields.RenderSeconds.AddTo(
    fieldData, "FacetRenderSeconds", { { "Total", vtkFacetSecondsSince(this->StartTime) } });
  fields.PhaseSeconds.AddTo(fieldData,
    "FacetPhaseSeconds",
    { { "Conversion", this->ConversionSeconds },
      { "Validate", stats.validateSeconds },
      { "Transform", stats.transformSeconds },
      { "Setup", stats.setupSeconds },
      { "Raster", stats.rasterSeconds },
      { "Shade", stats.shadeSeconds },
      { "Output", this->OutputSeconds } });
  const auto count = [](std::size_t n) { return static_cast<vtkIdType>(n); };
  fields.Counts.AddTo(fieldData,
    "FacetCounts",
    { { "Polygons", count(stats.plan.polygons) },
      { "PolygonsDrawn", count(stats.polygonsDrawn) },
      { "PolygonsShaded", count(stats.polygonsShaded) },
      { "PolygonsCulled", count(stats.polygonsCulled) },
      { "PolygonsOutside", count(stats.polygonsOutside) },
      { "PolygonsDegenerate", count(stats.polygonsDegenerate) },
      { "PolygonsNonFinite", count(stats.polygonsNonFinite) },
      { "PolygonsHidden", count(stats.polygonsHidden) },
      { "TrianglesBinned", count(stats.trianglesBinned) },
      { "TrianglesClipped", count(stats.trianglesClipped) },
      { "FragmentsWritten", count(stats.fragmentsWritten) },
      { "PixelsCovered", count(stats.pixelsCovered) } });
  fields.MeshConverted.AddTo(fieldData, "FacetMeshConverted", { { "Converted", conversions } });
  this->Plan = stats.describe();
  fields.Plan.AddTo(fieldData, "FacetRenderPlan", this->Plan);
  this->AddPlanNumbers(fieldData, stats.plan);
}

//------------------------------------------------------------------------------
void vtkFacetImageRenderer::AddPlanNumbers(vtkFieldData* fieldData, const facet::RenderPlan& plan)
{
  FieldArrays& fields = this->Fields;
  fields.Path.AddTo(fieldData, "FacetRenderPath", { { "Path", static_cast<int>(plan.path) } });
  // One component per rule, named as facet::Rule names it.
  static_assert(facet::kRuleCount == 6, "name the new rule here");
  static constexpr const char* names[facet::kRuleCount] = { "LightsThatReachNothing",
    "GeometryOutsideView",
    "HiddenGeometry",
    "AmbientOnly",
    "OneColor",
    "ClosedSurfaces" };
  const auto rule = [&](std::size_t r) -> const facet::RuleOutcome& { return plan.rules[r]; };
  fields.RulesAllowed.AddTo(fieldData, "FacetRenderPlanRulesAllowed", names, [&](std::size_t r) {
    return static_cast<int>(rule(r).allowed);
  });
  fields.RulesFired.AddTo(fieldData, "FacetRenderPlanRulesFired", names, [&](std::size_t r) {
    return static_cast<int>(rule(r).fired);
  });
  fields.RulesSkipped.AddTo(fieldData, "FacetRenderPlanRulesSkipped", names, [&](std::size_t r) {
    return static_cast<vtkIdType>(rule(r).skipped);
  });
  const facet::RenderPlan::LightCulling& lights = plan.lightCulling;
  fields.LightCulling.AddTo(fieldData,
    "FacetRenderPlanLightCulling",
    { { "Lights", static_cast<double>(lights.lights) },
      { "Dark", static_cast<double>(lights.dark) },
      { "OutsideCone", static_cast<double>(lights.outsideCone) },
      { "BelowTolerance", static_cast<double>(lights.belowTolerance) },
      { "Tolerance", lights.tolerance },
      { "ErrorBound", lights.errorBound },
      { "ErrorBound8Bit", static_cast<double>(lights.errorBound8Bit) } });
}

//------------------------------------------------------------------------------
void vtkFacetImageRenderer::AddToReport(vtkImageData* output, const std::string& lines)
{
  this->Plan += lines;
  vtkFieldData* fieldData = output->GetFieldData();
  if (auto* plan = vtkStringArray::SafeDownCast(fieldData->GetAbstractArray("FacetRenderPlan")))
  {
    plan->SetValue(0, this->Plan);
  }
  if (vtkDataArray* total = fieldData->GetArray("FacetRenderSeconds"))
  {
    total->SetComponent(0, 0, vtkFacetSecondsSince(this->StartTime));
  }
}
