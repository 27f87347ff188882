/**
 * @class   vtkFacetRenderFilter
 * @brief   Renders vtkPolyData into vtkImageData on the CPU: Facet's flat-shading rasterizer
 *          as a pipeline stage, with no OpenGL context, display or GPU.
 *
 * Input port 0 takes vtkPolyData: its polygons (convex, concave or slightly non-planar) and
 * triangle strips render; verts and lines are skipped with one warning that counts them.
 *
 * The output is a vtkImageData of extent (0, W-1, 0, H-1, 0, 0), spacing 1, origin 0, row 0
 * at the bottom (as vtkWindowToImageFilter), with three point-data arrays:
 * - `RGBA`: unsigned char, 4 components, the active scalars;
 * - `Depth`: float window depth in [0, 1], 1 = background (VTK's z-buffer convention);
 * - `CellId`: vtkIdType, the input cell (vtkPolyData::GetCell numbering: verts, lines, polys,
 *   strips) seen at the pixel, -1 for background.
 * (OutputDepth and OutputCellIds off leave the last two out, and the work that makes them.)
 * Its field data holds `FacetRenderSeconds` (total), `FacetPhaseSeconds` (named components
 * per phase), `FacetCounts` (named components: polygons drawn, shaded, culled, pixels...),
 * `FacetMeshConverted` (1 when this execution converted the input, 0 when it reused the
 * conversion kept from the last one), `FacetShadingMeshes` (with Gouraud, Phong, MaximumError
 * or ComputeError: Built, the meshes whose triangles, vertex normals and corner color ranges
 * this execution made again, and Kept), `FacetRenderPlan` (text: what the render did, left out
 * and why, counted and cost) and the plan in numbers: `FacetRenderPath` (0 full, 1 re-shade,
 * 2 resolve), `FacetRenderPlanRulesAllowed`, `FacetRenderPlanRulesFired` and
 * `FacetRenderPlanRulesSkipped` (one component per rule, named LightsThatReachNothing,
 * GeometryOutsideView, HiddenGeometry, AmbientOnly, OneColor, ClosedSurfaces; skipped counts
 * the lights, polygons, triangles, shades or back-facing meshes each left out) and
 * `FacetRenderPlanLightCulling` (Lights, Dark, OutsideCone, BelowTolerance, Tolerance,
 * ErrorBound, ErrorBound8Bit).
 *
 * Scene settings mean what they mean on vtkRenderer, vtkActor and vtkMapper: a vtkCamera
 * (none: one fitted to the input's finite points by vtkRenderer::ResetCamera, which
 * GetActiveCamera returns after the execution), vtkLights (none: a
 * headlight, unless AutomaticLightCreation is off), a vtkProperty and vtkMapper's coloring by
 * data. vtkFacetLight adds the light models vtkLight lacks. The property's Interpolation
 * picks the shading: flat (per polygon, the default), Gouraud (lit per vertex) or Phong (lit
 * per pixel); SetSamplesPerPixel supersamples, SetMaximumError shades adaptively within an
 * error budget (vtkFacetQuality). The property's Opacity, Representation, edge visibility
 * and textures are not used yet: everything renders as opaque surfaces (a warning, said
 * once, names what the property asks for).
 * Every render estimates its own flat-shading error (EstimateError, on by default): field data
 * `FacetErrorEstimate` (PredictedRMSE, PredictedMax, 8-bit units, Seconds; point array
 * `ErrorEstimate` with ErrorEstimateArray on); SetComputeError renders the converged Phong
 * reference beside it and reports the measured error (`FacetError`, point array `Error`). Its
 * Lighting off shows the unlit colors, Ka·Ca + Kd·Cd, as VTK. Problems found during an execution
 * are reported at its end, errors in one vtkErrorMacro, warnings in one vtkWarningMacro.
 *
 * Distributed data (MPI): with a controller of more than one process (the global
 * controller by default, as VTK's parallel filters; pvbatch --mpi and pvserver set it),
 * every process renders the piece of the input it holds (the filter asks its input for
 * piece = rank of pieces = processes) with the same camera and lights, the automatic camera
 * being fitted to the union of all pieces' bounds, and the images are composited by depth
 * with IceT onto one process, CompositeRank. Its output is the whole image, exactly the
 * image one process would render of the whole input for opaque surfaces; the other
 * processes' outputs hold no pixels (an image of empty extent, with their field data),
 * unless CompositeToAllRanks. The output then has a fourth array, `RankId` (int, the rank
 * whose piece shows at the pixel, -1 for background), and CellId is the cell's id in that
 * rank's piece, or its global id when the input has global cell ids
 * (vtkCellData::GetGlobalIds). Equal depths from two pieces go to the lower rank. Field
 * data adds `FacetCompositeSeconds` (Total, Pack, IceT, Unpack), `FacetCompositeBytes`
 * (SentByThisRank, SentByAllRanks) and `FacetCompositeStrategy`; the render plan says the
 * same. The error estimate composites with the image, in the same 20 bytes a covered pixel
 * (with at most 65535 ranks and every CellId below 2^48; else in a second IceT composite of 8
 * bytes a covered pixel: bench/mpi_estimate_cost.py): each pixel's is that of the piece it shows,
 * and `FacetErrorEstimate` on the target summarizes the whole image (on the other processes, their
 * own piece); a cell with a corner in another piece has its vertex normals from its own piece's
 * cells. Every process must execute the filter with the same settings; one whose input is bad
 * reports its error and adds nothing to the image (the target warns of the missing piece), and the
 * others do not wait for it. A build without IceT (or without VTK's ParallelMPI) renders every
 * process's own piece and says so once.
 *
 * The pieces that make the scene are the ones vtkFacetRendererToImageFilter uses for each
 * actor of a vtkRenderer: the input is converted as an actor's mapper input is, colored as
 * its mapper colors it (the coloring settings here are a vtkMapper's), with the property's
 * material, under an identity matrix.
 *
 * Re-rendering is cheap: the converted mesh (validated, checked for closedness, its face
 * normals kept by the renderer) is kept while the input's geometry is unchanged (points and
 * cells are read in place when their types allow; new point or cell data is no new
 * geometry), so a new camera only renders, and
 * what changed decides how much (IncrementalRendering, judged by MTimes: of the input's
 * points, polys and strips for the geometry; of the scalars, the lookup table and the
 * coloring settings for the colors): new lights, a new property or new colors only re-shade
 * the last frame, a new background only recolors it. Long renders report progress and stop
 * when AbortExecute is set.
 *
 * Example (Python):
 * @code{.py}
 * from vtkmodules.vtkIOGeometry import vtkOBJReader
 * from facet import vtkFacetRenderFilter
 * reader = vtkOBJReader()
 * reader.SetFileName("bunny.obj")
 * render = vtkFacetRenderFilter()
 * render.SetInputConnection(reader.GetOutputPort())
 * render.SetSize(800, 600)
 * render.Update()
 * image = render.GetOutput()   # RGBA, Depth, CellId
 * @endcode
 *
 * @sa vtkFacetLight vtkFacetRendererToImageFilter vtkWindowToImageFilter
 */

#ifndef vtkFacetRenderFilter_h
#define vtkFacetRenderFilter_h

#include "FacetRenderingModule.h" // For export macro
#include "vtkImageAlgorithm.h"

class vtkCamera;
class vtkLight;
class vtkLightCollection;
class vtkMultiProcessController;
class vtkPolyData;
class vtkProperty;
class vtkScalarsToColors;

class FACETRENDERING_EXPORT vtkFacetRenderFilter : public vtkImageAlgorithm
{
public:
  static vtkFacetRenderFilter* New();
  vtkTypeMacro(vtkFacetRenderFilter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Image size in pixels, width × height (default: 640 × 480). At most 16384 per side.
   */
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  ///@{
  /**
   * Background color, RGB in [0, 1] (default: black) and its alpha (default: 1).
   */
  vtkSetVector3Macro(Background, double);
  vtkGetVector3Macro(Background, double);
  vtkSetClampMacro(BackgroundAlpha, double, 0.0, 1.0);
  vtkGetMacro(BackgroundAlpha, double);
  ///@}

  ///@{
  /**
   * The camera, used exactly as VTK uses it: view angle or parallel scale, window center and
   * clipping range as given (default: none, meaning the automatic camera: at every execution,
   * a new vtkCamera fitted to the input as ResetCamera fits it).
   */
  void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  /**
   * The camera to render with, as vtkRenderer::GetActiveCamera: the one set with SetCamera
   * (unless FitCameraToInput is on), else the automatic camera as the last execution fitted
   * it (before the first: a default vtkCamera). Never null. The automatic camera is fitted again at
   * every execution, so changing it changes nothing; to orbit from it, copy it and set the copy:
   * @code{.cpp}
   * vtkNew<vtkCamera> camera;
   * camera->DeepCopy(filter->GetActiveCamera());
   * camera->Azimuth(30.0);
   * vtkFacetRenderFilter::ResetCamera(camera, input, width, height); // optional: refit
   * filter->SetCamera(camera);
   * @endcode
   * ResetCamera after turning keeps the new direction and gives the clipping range for it
   * (turning alone can move part of the data in front of the near plane); it also resets
   * the view angle, so Zoom after it.
   */
  vtkCamera* GetActiveCamera();

  /**
   * Fits `camera` to `input` for a width × height image as the automatic camera is fitted:
   * vtkRenderer::ResetCamera (view direction and view up kept; focal point, position, a
   * 30 degree view angle, parallel scale and clipping range set, with a 24-bit depth
   * buffer's 0.001 near-plane tolerance) on the bounds of the points whose coordinates are
   * all finite, as the render skips cells with other points. The result is VTK's to the bit
   * for bounds within ±1e100; beyond, the bounds are clamped to ±1e100 so the camera stays
   * finite (its squared distance must not overflow), and data too small to resolve against
   * its distance from the origin gets a box the camera's position can resolve. With no
   * finite point the camera is left as it is.
   */
  static void ResetCamera(vtkCamera* camera, vtkPolyData* input, int width, int height);

  ///@{
  /**
   * Fit the camera to the input's bounds as vtkRenderer::ResetCamera does: the camera's
   * direction of view, view up and projection are kept; its focal point moves to the center
   * of the bounds, its view angle returns to 30 degrees, its distance (or parallel scale)
   * makes them fill the view, and its clipping range is reset. The camera set with SetCamera
   * is not changed: a copy is fitted. With no camera set, the camera is always fitted,
   * looking down -Z (default: off).
   */
  vtkSetMacro(FitCameraToInput, vtkTypeBool);
  vtkGetMacro(FitCameraToInput, vtkTypeBool);
  vtkBooleanMacro(FitCameraToInput, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Scene lights: headlights, camera lights and scene lights as vtkLight defines them
   * (positional, cone angle, exponent, attenuation values, intensity, diffuse color), and
   * vtkFacetLight's models (default: none).
   */
  void AddLight(vtkLight* light);
  void RemoveLight(vtkLight* light);
  void RemoveAllLights();
  vtkGetObjectMacro(Lights, vtkLightCollection);
  ///@}

  ///@{
  /**
   * With no light added, render with one headlight, as vtkRenderer does (default: on).
   */
  vtkSetMacro(AutomaticLightCreation, vtkTypeBool);
  vtkGetMacro(AutomaticLightCreation, vtkTypeBool);
  vtkBooleanMacro(AutomaticLightCreation, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Sixth 3D's scene ambient light, RGB, multiplied by the surface color (default:
   * 50/255 gray). Set it to 0 to match VTK's OpenGL renderer, which has none.
   */
  vtkSetVector3Macro(AmbientLightColor, double);
  vtkGetVector3Macro(AmbientLightColor, double);
  ///@}

  ///@{
  /**
   * Light a polygon seen from its back with its normal turned toward the camera, as
   * vtkRenderer does; off: lit as its winding says (default: on).
   */
  vtkSetMacro(TwoSidedLighting, vtkTypeBool);
  vtkGetMacro(TwoSidedLighting, vtkTypeBool);
  vtkBooleanMacro(TwoSidedLighting, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Surface material: color, ambient/diffuse/specular coefficients, specular color and
   * power, backface culling, and Interpolation: VTK_FLAT, VTK_GOURAUD or VTK_PHONG shading
   * (default: a vtkProperty with VTK's defaults but flat interpolation). Opacity, PBR and
   * representations other than surface are not used yet (one warning says so).
   */
  void SetProperty(vtkProperty* property);
  vtkProperty* GetProperty();
  ///@}

  ///@{
  /**
   * Color by data with the scalars, as vtkMapper does (default: on).
   */
  void SetScalarVisibility(vtkTypeBool visibility);
  vtkTypeBool GetScalarVisibility();
  void ScalarVisibilityOn() { this->SetScalarVisibility(1); }
  void ScalarVisibilityOff() { this->SetScalarVisibility(0); }
  ///@}

  ///@{
  /**
   * Which scalars color the surface, with vtkMapper's meaning and constants (default:
   * VTK_SCALAR_MODE_DEFAULT: point scalars, else cell scalars).
   */
  void SetScalarMode(int mode);
  int GetScalarMode();
  void SetScalarModeToDefault();
  void SetScalarModeToUsePointData();
  void SetScalarModeToUseCellData();
  void SetScalarModeToUsePointFieldData();
  void SetScalarModeToUseCellFieldData();
  ///@}

  ///@{
  /**
   * How scalars become colors, vtkMapper's meaning (default: VTK_COLOR_MODE_DEFAULT:
   * unsigned char scalars are colors, others go through the lookup table).
   */
  void SetColorMode(int mode);
  int GetColorMode();
  void SetColorModeToDefault();
  void SetColorModeToMapScalars();
  void SetColorModeToDirectScalars();
  ///@}

  ///@{
  /**
   * The array to color by with the field-data scalar modes (or any mode, by name), as
   * vtkMapper::SelectColorArray, but keeping ArrayComponent (default: none, the active
   * scalars).
   *
   * The array can also be named as VTK filters name their input arrays, which is how
   * ParaView's array selection names it: SetInputArrayToProcess(0, 0, 0, association, name)
   * with vtkDataObject::FIELD_ASSOCIATION_POINTS or FIELD_ASSOCIATION_CELLS colors by that
   * point or cell array, in place of ScalarMode and the array selected here (an empty name
   * leaves them in charge).
   */
  void SelectColorArray(int arrayId);
  void SelectColorArray(const char* arrayName);
  const char* GetArrayName();
  int GetArrayId();
  int GetArrayAccessMode();
  ///@}

  ///@{
  /**
   * The component of a multi-component array to map; -1 maps the magnitude (default: 0).
   */
  void SetArrayComponent(int component);
  int GetArrayComponent();
  ///@}

  ///@{
  /**
   * The lookup table mapping scalars to colors (default: none, meaning a vtkLookupTable
   * created on first use, as vtkMapper does).
   */
  void SetLookupTable(vtkScalarsToColors* table);
  vtkScalarsToColors* GetLookupTable();
  ///@}

  ///@{
  /**
   * The scalar range mapped onto the lookup table, unless UseLookupTableScalarRange
   * (default: 0 to 1, off), as vtkMapper.
   */
  void SetScalarRange(double minimum, double maximum);
  void SetScalarRange(const double range[2]);
  double* GetScalarRange() VTK_SIZEHINT(2);
  void SetUseLookupTableScalarRange(vtkTypeBool use);
  vtkTypeBool GetUseLookupTableScalarRange();
  void UseLookupTableScalarRangeOn() { this->SetUseLookupTableScalarRange(1); }
  void UseLookupTableScalarRangeOff() { this->SetUseLookupTableScalarRange(0); }
  ///@}

  ///@{
  /**
   * vtkMapper's InterpolateScalarsBeforeMapping (default: off). Off: point scalars are
   * mapped to colors at the points; Gouraud and Phong interpolate the colors. On: Gouraud and
   * Phong interpolate the scalars and map them per pixel through the lookup table, as VTK's
   * OpenGL mapper does with its color texture (where vtkMapper would use one: not for cell
   * scalars, an indexed table or direct colors). Flat shading shows one color per polygon,
   * the average of its points' mapped colors, either way.
   */
  void SetInterpolateScalarsBeforeMapping(vtkTypeBool interpolate);
  vtkTypeBool GetInterpolateScalarsBeforeMapping();
  void InterpolateScalarsBeforeMappingOn() { this->SetInterpolateScalarsBeforeMapping(1); }
  void InterpolateScalarsBeforeMappingOff() { this->SetInterpolateScalarsBeforeMapping(0); }
  ///@}

  ///@{
  /**
   * Threads that render, from 0 to 1024; 0 means one per hardware thread (default: 0). The
   * image is the same bytes for every thread count. Other values are an error that keeps the
   * previous setting.
   */
  void SetNumberOfThreads(int threads);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  enum VisibilityModes
  {
    ZBuffer = 0,
    PainterSort = 1
  };

  ///@{
  /**
   * How polygons hide each other (default: ZBuffer). PainterSort is Sixth 3D's painter's
   * algorithm by centroid depth; it cannot be right for intersecting polygons.
   */
  vtkSetClampMacro(VisibilityMode, int, ZBuffer, PainterSort);
  vtkGetMacro(VisibilityMode, int);
  void SetVisibilityModeToZBuffer() { this->SetVisibilityMode(ZBuffer); }
  void SetVisibilityModeToPainterSort() { this->SetVisibilityMode(PainterSort); }
  ///@}

  ///@{
  /**
   * Check, once per input, whether its polygons form closed outward surfaces; if so, back
   * faces that cannot be seen are skipped (the image is the same; about a third faster). The
   * check runs once per input, costing about two renders of it (0.14 s for 2M triangles)
   * (default: on).
   */
  vtkSetMacro(DetectClosedSurfaces, vtkTypeBool);
  vtkGetMacro(DetectClosedSurfaces, vtkTypeBool);
  vtkBooleanMacro(DetectClosedSurfaces, vtkTypeBool);
  ///@}

  ///@{
  /**
   * The processes that render the pieces of distributed data and composite them (default:
   * the global controller when the filter is made, vtkMultiProcessController's
   * GetGlobalController). None, or one process: the filter renders its input alone.
   */
  void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * The rank that receives the composited image (default: 0).
   */
  vtkSetMacro(CompositeRank, int);
  vtkGetMacro(CompositeRank, int);
  ///@}

  ///@{
  /**
   * Every rank receives the composited image, not only CompositeRank (default: off).
   */
  vtkSetMacro(CompositeToAllRanks, vtkTypeBool);
  vtkGetMacro(CompositeToAllRanks, vtkTypeBool);
  vtkBooleanMacro(CompositeToAllRanks, vtkTypeBool);
  ///@}

  enum CompositeStrategies
  {
    CompositeAutomatic = 0,
    CompositeBinarySwap = 1,
    CompositeTree = 2,
    CompositeRadixK = 3
  };

  ///@{
  /**
   * IceT's strategy for compositing the image (default: CompositeAutomatic, IceT's choice,
   * radix-k for most rank counts). The image is the same with every strategy.
   */
  vtkSetClampMacro(CompositeStrategy, int, CompositeAutomatic, CompositeRadixK);
  vtkGetMacro(CompositeStrategy, int);
  void SetCompositeStrategyToAutomatic() { this->SetCompositeStrategy(CompositeAutomatic); }
  void SetCompositeStrategyToBinarySwap() { this->SetCompositeStrategy(CompositeBinarySwap); }
  void SetCompositeStrategyToTree() { this->SetCompositeStrategy(CompositeTree); }
  void SetCompositeStrategyToRadixK() { this->SetCompositeStrategy(CompositeRadixK); }
  ///@}

  /**
   * Whether this build composites the pieces of MPI processes (it found IceT and VTK's
   * ParallelMPI).
   */
  static bool CanComposite();

  ///@{
  /**
   * Samples per pixel: 1, 4 or 16, on an ordered 2 × 2 or 4 × 4 grid, averaged (default: 1).
   * Depth and CellId come from one fixed sample nearest the pixel center (facet's
   * QualityRenderer.h). Other values are an error at execution.
   */
  vtkSetMacro(SamplesPerPixel, int);
  vtkGetMacro(SamplesPerPixel, int);
  ///@}

  ///@{
  /**
   * Adaptive quality: an error budget in 8-bit units. Polygons whose flat-shading error bound
   * is within it stay flat, the others are shaded per pixel (Phong); every pixel is then
   * within the budget of the Phong image. 0 turns it off and the property's Interpolation
   * decides (default: 0).
   */
  vtkSetMacro(MaximumError, double);
  vtkGetMacro(MaximumError, double);
  ///@}

  ///@{
  /**
   * Render the converged Phong mesh reference (128 samples per pixel, ray traced) beside the
   * image and report the measured error: field data `FacetError` (RMSE, Max, PSNR, SSIM,
   * SilhouetteFraction, ReferenceSeconds, RenderSeconds) and the point array `Error` (per
   * pixel, the largest channel difference, 8-bit units). Slow: for measuring. Across
   * processes each measures its own piece against its own piece's reference (the reference
   * is not composited): `FacetError` describes that piece, a warning says so, and the
   * composited image has no `Error` array (default: off).
   */
  vtkSetMacro(ComputeError, vtkTypeBool);
  vtkGetMacro(ComputeError, vtkTypeBool);
  vtkBooleanMacro(ComputeError, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Estimate the render's flat-shading error and put it in the field data
   * (`FacetErrorEstimate`: PredictedRMSE, PredictedMax, 8-bit units, and Seconds, its own
   * cost outside the render): per pixel a bound on how far flat shading is from the converged
   * Phong image. Once per mesh version (not per frame) it computes the vertex normals (on the
   * filter's threads) and keeps each polygon's radius and normal spread (8 bytes) and, per
   * block of 128 polygon ids, the largest of them and the block's box. Per render, in the
   * filter's default case (flat, one sample per pixel, no ErrorEstimateArray, point or
   * directional lights, no specular, one color per polygon) each block's worst case is
   * bounded before the render and the resolve estimates each band of pixels from those block
   * bounds as it resolves it, in integers; otherwise the shade phase bounds each polygon it
   * lights (in SIMD lanes for point and directional lights and a material without specular).
   * The block bounds are never below the polygons' own, so the summary is at least the
   * per-polygon estimate (a few percent looser on a smooth sphere, up to 2x where a block
   * mixes creased and flat polygons). A new background alone keeps the last estimate. Not
   * free: with a turning camera, 0.5M- or 2M-triangle spheres at 1920 x 1080, about 4.5 % of
   * the core's frame in the default case (8-11 % on the per-polygon path;
   * bench/estimate-cost.md), and once per mesh about as much as its first conversion (README,
   * "An estimate of a render's error"). Off, a flat one-sample
   * render is the plain rasterizer (default: on).
   */
  vtkSetMacro(EstimateError, vtkTypeBool);
  vtkGetMacro(EstimateError, vtkTypeBool);
  vtkBooleanMacro(EstimateError, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Add the per-pixel error estimate as the point array `ErrorEstimate` (8-bit units; the
   * field data then has its summary too, as with EstimateError) (default: off).
   */
  vtkSetMacro(ErrorEstimateArray, vtkTypeBool);
  vtkGetMacro(ErrorEstimateArray, vtkTypeBool);
  vtkBooleanMacro(ErrorEstimateArray, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Add the `Depth` array to the output (default: on). Off, window depths are not computed
   * at all (facet::Renderer::setDepthOutput); RGBA is the same bytes.
   */
  vtkSetMacro(OutputDepth, vtkTypeBool);
  vtkGetMacro(OutputDepth, vtkTypeBool);
  vtkBooleanMacro(OutputDepth, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Add the `CellId` array to the output (default: on). Off, polygon ids are not turned into
   * cell ids; RGBA is the same bytes. (Across MPI processes both are still computed, to
   * composite by, and left out of the output.)
   */
  vtkSetMacro(OutputCellIds, vtkTypeBool);
  vtkGetMacro(OutputCellIds, vtkTypeBool);
  vtkBooleanMacro(OutputCellIds, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Leave out a point or spot light whose contribution to every channel of every polygon is
   * at most this, in linear color units (0 to 1: black to full). The field data reports the
   * lights left out and the bound on the error they may make (`FacetRenderPlanLightCulling`:
   * ErrorBound, linear, and ErrorBound8Bit). Lights that add nothing at all (black, zero
   * intensity, a spot cone that misses the data) are always left out (default: 0: only
   * those).
   */
  vtkSetClampMacro(LightCullingTolerance, double, 0.0, 1.0);
  vtkGetMacro(LightCullingTolerance, double);
  ///@}

  ///@{
  /**
   * Reuse the last image where the change allows it, as the field data's `FacetRenderPath`
   * says: a change of only the lights, the property's material or colors, the lookup table
   * or the scalars re-shades the last frame (no transform, set-up or raster), a change of
   * only the background recolors it; a new camera, size or geometry renders in full. Each
   * gives the same bytes as a full render. The output arrays are reused while nobody else
   * holds them; held ones are never written again (the first execution that finds Depth
   * held renders in full, into a depth plane the filter keeps from then on). A modified
   * input vtkPolyData counts as new geometry, even if its points and cells are not (ParaView
   * modifies it before every execution: it renders in full there) (default: on).
   */
  vtkSetMacro(IncrementalRendering, vtkTypeBool);
  vtkGetMacro(IncrementalRendering, vtkTypeBool);
  vtkBooleanMacro(IncrementalRendering, vtkTypeBool);
  ///@}

  /**
   * What the last render did, left out and cost, a few lines of text (empty before the
   * first): the field data's `FacetRenderPlan`.
   */
  const char* GetRenderPlan();

  /**
   * Includes the camera, lights, property and lookup table.
   */
  vtkMTimeType GetMTime() override;

protected:
  vtkFacetRenderFilter();
  ~vtkFacetRenderFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int Size[2] = { 640, 480 };
  double Background[3] = { 0.0, 0.0, 0.0 };
  double BackgroundAlpha = 1.0;
  vtkCamera* Camera = nullptr;
  vtkTypeBool FitCameraToInput = 0;
  vtkLightCollection* Lights = nullptr;
  vtkTypeBool AutomaticLightCreation = 1;
  double AmbientLightColor[3] = { 50.0 / 255.0, 50.0 / 255.0, 50.0 / 255.0 };
  vtkTypeBool TwoSidedLighting = 1;
  vtkProperty* Property = nullptr;
  int NumberOfThreads = 0;
  int VisibilityMode = ZBuffer;
  vtkTypeBool DetectClosedSurfaces = 1;
  vtkMultiProcessController* Controller = nullptr;
  int CompositeRank = 0;
  vtkTypeBool CompositeToAllRanks = 0;
  int CompositeStrategy = CompositeAutomatic;
  int SamplesPerPixel = 1;
  double MaximumError = 0.0;
  vtkTypeBool ComputeError = 0;
  vtkTypeBool EstimateError = 1;
  vtkTypeBool ErrorEstimateArray = 0;
  vtkTypeBool OutputDepth = 1;
  vtkTypeBool OutputCellIds = 1;
  double LightCullingTolerance = 0.0;
  vtkTypeBool IncrementalRendering = 1;

private:
  vtkFacetRenderFilter(const vtkFacetRenderFilter&) = delete;
  void operator=(const vtkFacetRenderFilter&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
