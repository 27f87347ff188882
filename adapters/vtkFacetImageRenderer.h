/**
 * @class   vtkFacetImageRenderer
 * @brief   Private: renders a Facet scene into a vtkImageData: the part of an execution that
 *          both front ends share.
 *
 * Render makes the output a width × height image (extent (0, W-1, 0, H-1, 0, 0), spacing
 * 1, origin 0, row 0 at the bottom) with point data `RGBA` (the scalars), `Depth`, `CellId`
 * and, for vtkFacetRendererToImageFilter, `ActorId` (for vtkFacetRenderFilter across MPI
 * processes, `RankId`). The arrays of the last execution are
 * reused when nobody else holds them (re-rendering then allocates and page-faults nothing;
 * the pipeline empties the output before every execution, so this class keeps its own
 * references), and large ones are 2 MiB-aligned with transparent huge pages advised (tile
 * traversal otherwise misses the TLB, see facet/HugePageAllocator.h). It renders straight
 * into RGBA and Depth, reporting progress (0.05 to 0.95) and
 * stopping when the algorithm's AbortExecute is set; the front end's IdMap turns the
 * renderer's polygon ids into CellId (and ActorId) band by band as the render resolves them
 * (Renderer::ResolvedRowsCallback, its ids still in cache; after the render, by a pass over the
 * image, when it drew a sample grid or stopped), on the renderer's threads; then the field
 * data says what the render did and cost: `FacetRenderSeconds`, `FacetPhaseSeconds`,
 * `FacetCounts`, `FacetMeshConverted`, `FacetRenderPlan` (RenderStats::describe) and the plan
 * in numbers: `FacetRenderPath` (Path: 0 full, 1 re-shade, 2 resolve, facet::RenderPath),
 * `FacetRenderPlanRulesAllowed`, `FacetRenderPlanRulesFired` (0 or 1) and
 * `FacetRenderPlanRulesSkipped` (the work each left out: lights, polygons, triangles, shades
 * or back faces, RenderPlan.h), one named component per rule, and `FacetRenderPlanLightCulling`
 * (Lights, Dark, OutsideCone, BelowTolerance, Tolerance, ErrorBound, ErrorBound8Bit). Those
 * arrays too are the last execution's, refilled in place, when nobody else holds them
 * (vtkFacetFieldArray).
 *
 * Incremental rendering (facet/Renderer.h): the renderer's depth and polygon-id planes are
 * the same and untouched from one execution to the next, so an execution whose meshes carry
 * the versions of the last (MeshView::version, colorVersion) and whose camera is unchanged
 * re-shades or resolves the last frame. The depth plane is the output's Depth array (no
 * copy) until an execution finds that array held by somebody else (ParaView's
 * representations hold it) or composited into: that execution renders in full into a plane
 * of this class's own, kept from then on and copied into Depth. Output arrays somebody
 * holds are never written again: that execution's are new.
 */

#ifndef vtkFacetImageRenderer_h
#define vtkFacetImageRenderer_h

#include "vtkDoubleArray.h" // the members below: complete for the implicit destructor
#include "vtkFacetBackgroundSpans.h"
#include "vtkFacetFieldArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"
#include "vtkUnsignedCharArray.h" // a member below

#include "facet/HugePageAllocator.h"
#include "facet/IdPlane.h"
#include "facet/Renderer.h"

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>

class vtkAlgorithm;
class vtkFacetMessages;
class vtkFloatArray;
class vtkImageData;
class vtkInformation;
class vtkObject;
class vtkUnsignedCharArray;

class vtkFacetImageRenderer
{
public:
  /// The image and the renderer's settings that are not the scene's.
  struct Settings
  {
    int Width = 640;
    int Height = 480;
    bool Depth = true;     ///< add the Depth array (off: no window depth is computed)
    bool CellIds = true;   ///< add the CellId array
    bool ActorIds = false; ///< add the ActorId array
    bool RankIds = false;  ///< add the RankId array (vtkFacetCompositor fills it)
    /// The front end writes into the output planes after Render (vtkFacetCompositor): the
    /// renderer's depth plane is then one of this class's own, copied into Depth, so that the
    /// next render can still reuse the frame it holds.
    bool Composited = false;
    /// The IdMap writes CellId alone and every background pixel alike (vtkFacetRenderFilter's
    /// CellLabels without RankId): a kept CellId plane then skips the background the last
    /// frame left in it (vtkFacetBackgroundSpans).
    bool CellIdsOnly = false;
    facet::RenderRules Rules; ///< which rules may leave work out, incremental rendering
    int Threads = 0;          ///< 0: one per hardware thread
    facet::Visibility Visibility = facet::Visibility::ZBuffer;
    bool TwoSidedLighting = true;
    double Background[3] = { 0.0, 0.0, 0.0 };
    double BackgroundAlpha = 1.0;
    /// Renders in place of Renderer::render when set (the filter's quality modes,
    /// vtkFacetQuality), with the renderer set up as above.
    std::function<facet::RenderStats(facet::Renderer&,
      const facet::Scene&,
      const facet::Camera&,
      const facet::FramebufferView&)>
      RenderWith;
  };

  /// Turns the polygon ids of pixels [begin, end) into the front end's id arrays.
  using IdMap = std::function<void(const std::int32_t* polygonIds, vtkIdType begin, vtkIdType end)>;

  /**
   * RequestInformation of a front end that renders width × height: the whole extent,
   * spacing, origin and RGBA scalars; for a size outside [1, kMaxImageSide] an error on
   * `algorithm`, the output emptied and 0.
   */
  static int RequestInformation(vtkAlgorithm* algorithm,
    vtkInformation* outInfo,
    int width,
    int height);

  /**
   * Whether `threads` is a thread count a front end takes (0 to 1024); if not, an error on
   * `object` that says `current` is kept.
   */
  static bool CheckThreadCount(vtkObject* object, int threads, int current);

  /// An execution of `algorithm` starts: the clock, progress 0.
  void Start(vtkAlgorithm* algorithm);
  /// The scene is converted: progress 0.05.
  void ConversionDone();

  vtkUnsignedCharArray* GetRgba() const { return this->Rgba; }
  vtkFloatArray* GetDepth() const;
  vtkIdTypeArray* GetCellIds() const { return this->CellIds; }
  vtkIntArray* GetActorIds() const { return this->ActorIds; }
  vtkIntArray* GetRankIds() const;
  void GetSize(int size[2]) const
  {
    size[0] = this->Width;
    size[1] = this->Height;
  }

  /**
   * Unless `messages` already holds an error: makes `output` the image described above,
   * renders into it, maps the ids and adds the field data (`conversions`: the polydata this
   * execution converted). Returns false, with an error in `messages`, when the memory
   * cannot be had or the core refuses the scene.
   */
  bool Render(const facet::Scene& scene,
    const facet::Camera& camera,
    const Settings& settings,
    vtkImageData* output,
    const IdMap& mapIds,
    int conversions,
    vtkFacetMessages& messages);

  /// Runs work(begin, end) over the pixels on the renderer's threads.
  void ForEachPixelBlock(const std::function<void(vtkIdType begin, vtkIdType end)>& work);

  /// Whether an IdMap streams its id planes past the caches (64-bit ids of this image make a
  /// plane of facet::kStreamedPlaneBytes or more).
  bool StreamsIdPlanes() const
  {
    return static_cast<std::size_t>(this->Width) * static_cast<std::size_t>(this->Height) *
      sizeof(vtkIdType) >=
      facet::kStreamedPlaneBytes;
  }

  /// The last render's polygon id plane (before the IdMap), width × height.
  const std::int32_t* GetPolygonIds() const { return this->PolygonIds.data(); }

  /// What the last render did and left out, counted and cost (RenderStats::describe; empty
  /// before the first).
  const std::string& GetPlan() const { return this->Plan; }

  /**
   * For work done after Render (compositing): appends `lines` to the plan (and to
   * `FacetRenderPlan`) and makes `FacetRenderSeconds` count until now.
   */
  void AddToReport(vtkImageData* output, const std::string& lines);

private:
  using Clock = std::chrono::steady_clock;
  bool Allocate(const Settings& settings, vtkImageData* output, vtkFacetMessages& messages);
  void AddFieldData(vtkImageData* output, const facet::RenderStats& stats, int conversions);
  void AddPlanNumbers(vtkFieldData* fieldData, const facet::RenderPlan& plan);

  facet::Renderer Renderer;
  facet::HugePageVector<std::int32_t> PolygonIds; // the renderer's id plane, before mapping
  vtkSmartPointer<vtkUnsignedCharArray> Rgba;     // the output planes, kept for reuse
  vtkSmartPointer<vtkFloatArray> Depth;
  vtkSmartPointer<vtkIdTypeArray> CellIds;
  vtkSmartPointer<vtkIntArray> ActorIds;
  vtkSmartPointer<vtkIntArray> RankIds;
  facet::HugePageVector<float> RenderDepth; // the renderer's depth plane, if OwnDepthPlane
  bool OwnDepthPlane = false; // the output's Depth was held by others or composited into
  // Where CellId may need writing: only the front end's ids of one plane, kept and
  // untouched since the last frame, can skip rows' background (vtkFacetBackgroundSpans).
  vtkFacetBackgroundSpans CellIdSpans;
  bool SkipsBackgroundIds = false; // this frame writes CellId within CellIdSpans only
  // CellId's MTime once the last frame wrote it: a later one means somebody changed the plane
  // since (and said so, as VTK asks), so its background is no longer known.
  vtkMTimeType CellIdsWrittenTime = 0;
  vtkAlgorithm* Algorithm = nullptr;
  int Width = 0;
  int Height = 0;
  Clock::time_point StartTime;
  double ConversionSeconds = 0.0;
  double OutputSeconds = 0.0;
  std::string Plan;
  // The field data, refilled in place while nobody else holds it (vtkFacetFieldArray).
  struct FieldArrays
  {
    vtkFacetFieldArray<vtkDoubleArray> RenderSeconds, PhaseSeconds, LightCulling;
    vtkFacetFieldArray<vtkIdTypeArray> Counts, MeshConverted, RulesSkipped;
    vtkFacetFieldArray<vtkIntArray> Path, RulesAllowed, RulesFired;
    vtkFacetFieldString Plan;
  } Fields;
};

#endif
