/**
 * @class   vtkFacetRendererToImageFilter
 * @brief   Renders what a vtkRenderer holds into vtkImageData on the CPU: a drop-in for
 *          vtkWindowToImageFilter that needs no window, no OpenGL context and no GPU.
 *
 * Give it a renderer and a size, Update, and the output is the image vtkFacetRenderFilter
 * makes (extent (0, W-1, 0, H-1, 0, 0), row 0 at the bottom; point data `RGBA`, the scalars,
 * `Depth` in [0, 1] with 1 = background, `CellId`; the same field data) plus `ActorId`
 * (int): the index, in the renderer's prop order (vtkRenderer::GetViewProps), of the prop
 * that drew the pixel; -1 for background. `CellId` is the cell in the polydata the pixel's
 * actor drew (for a composite mapper, in that block's polydata).
 *
 * The renderer is read, never rendered (its Render is not called) and barely touched: like
 * vtkRenderer::Render, the first execution creates its camera if it has none, fitted to its
 * visible props as ResetCamera fits it (for this image's aspect).
 * - Props: every visible vtkActor (also inside a vtkAssembly) whose mapper is a
 *   vtkPolyDataMapper, or a composite mapper (vtkCompositePolyDataMapper,
 *   vtkCompositePolyDataMapper2) over a composite dataset of polydata, or a vtkDataSetMapper
 *   over polydata. The mapper's input pipeline is updated first (unless the mapper is
 *   Static). Each actor renders under its full matrix (position, orientation, scale,
 *   origin, user matrix, user transform; an assembly's too), with its vtkProperty and its
 *   mapper's coloring by data (scalar visibility, scalar mode, color mode, array, component,
 *   lookup table, scalar range, UseLookupTableScalarRange, InterpolateScalarsBeforeMapping). Other
 * props (volumes, 2D actors, text, images, glyph mappers...) are skipped, with one warning naming
 * their classes. Per-block display attributes of a vtkCompositePolyDataMapper2 (block colors,
 *   visibilities) live in VTK's OpenGL module and are not read.
 * - The active camera, for this image's aspect: view angle or parallel scale, window center,
 *   clipping range as given. What Facet's camera cannot do yet (view shear, off-axis
 *   projection, model/user transforms) is named in a warning, said once.
 * - Lights: headlights, camera lights (a vtkLightKit's among them) and scene lights, placed
 *   as vtkRenderer places them (LightFollowCamera); with none switched on, the headlight
 *   vtkRenderer would create (AutomaticLightCreation), or, without one, unlit colors, as VTK
 *   shows them. No scene ambient light: VTK's OpenGL renderer has none.
 * - Background color, its alpha when the render window has alpha bit planes (else opaque,
 *   as such a window reads back), the gradient background (Background at the bottom,
 *   Background2 at the top, resolved per row as VTK's OpenGL renderer draws it),
 *   TwoSidedLighting. Shadows, a textured background, SSAO and image-based lighting are not
 *   rendered yet (a warning, said once).
 *
 * Shading follows each actor's property Interpolation as VTK's OpenGL mapper does: for data
 * with point normals (in world coordinates under the actor's matrix), VTK_GOURAUD
 * (vtkProperty's default) lights the corners and interpolates, VTK_PHONG lights every pixel,
 * VTK_FLAT one color per polygon; data without point normals is shaded flat whatever the
 * interpolation, as VTK shows it (its shaders then take the face normal). Point scalars are
 * interpolated as the mapper's InterpolateScalarsBeforeMapping says. SamplesPerPixel
 * supersamples and MaximumError shades adaptively (facet's QualityRenderer.h); every render
 * estimates its flat-shading error (EstimateError, field data `FacetErrorEstimate`). Everything is
 * opaque: a warning, said once per actor, names what an actor's property asks for beyond
 * that, and an actor's texture or backface property. Errors and warnings of an
 * execution are reported at its end, one vtkErrorMacro and one vtkWarningMacro. Long renders report
 * progress and stop when AbortExecute is set.
 *
 * Update renders again when something the renderer holds changed (its settings, camera,
 * lights, props and their properties, matrices, mappers and mapper inputs, whose pipelines
 * are brought up to date to find out, as vtkRenderer's backing store does); Modified forces
 * it. Conversions of unchanged actors are kept, so moving the camera only renders.
 *
 * Example (Python):
 * @code{.py}
 * import vtkmodules.vtkRenderingOpenGL2  # the mappers' factory; no window is opened
 * from facet import vtkFacetRendererToImageFilter
 * ...                                    # a vtkRenderer with actors, lights, a camera
 * grab = vtkFacetRendererToImageFilter()
 * grab.SetRenderer(renderer)
 * grab.SetSize(800, 600)
 * grab.Update()
 * image = grab.GetOutput()               # RGBA, Depth, CellId, ActorId
 * @endcode
 *
 * @sa vtkFacetRenderFilter vtkWindowToImageFilter
 */

#ifndef vtkFacetRendererToImageFilter_h
#define vtkFacetRendererToImageFilter_h

#include "FacetRenderingModule.h" // For export macro
#include "vtkImageAlgorithm.h"

class vtkRenderer;

class FACETRENDERING_EXPORT vtkFacetRendererToImageFilter : public vtkImageAlgorithm
{
public:
  static vtkFacetRendererToImageFilter* New();
  vtkTypeMacro(vtkFacetRendererToImageFilter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The renderer whose scene to render (default: none, an error at execution).
   */
  void SetRenderer(vtkRenderer* renderer);
  vtkGetObjectMacro(Renderer, vtkRenderer);
  ///@}

  ///@{
  /**
   * Image size in pixels, width × height, at most 16384 per side (default: 0 × 0, meaning
   * the renderer's size in its render window when it has a window with a size, else
   * 640 × 480).
   */
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  /**
   * The size the next execution renders at: Size, or what 0 × 0 stands for.
   */
  void GetEffectiveSize(int size[2]);

  ///@{
  /**
   * Threads that render, from 0 to 1024; 0 means one per hardware thread (default: 0). The
   * image is the same bytes for every thread count. Other values are an error that keeps the
   * previous setting.
   */
  void SetNumberOfThreads(int threads);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Check, once per input, whether an actor's polygons form closed outward surfaces, to skip
   * back faces that cannot be seen (same image, faster), as vtkFacetRenderFilter (default:
   * on).
   */
  vtkSetMacro(DetectClosedSurfaces, vtkTypeBool);
  vtkGetMacro(DetectClosedSurfaces, vtkTypeBool);
  vtkBooleanMacro(DetectClosedSurfaces, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Samples per pixel: 1, 4 or 16, on an ordered 2 × 2 or 4 × 4 grid, averaged, as
   * vtkFacetRenderFilter's (default: 1). Depth, CellId and ActorId come from one fixed
   * sample nearest the pixel center. Other values are an error at execution.
   */
  vtkSetMacro(SamplesPerPixel, int);
  vtkGetMacro(SamplesPerPixel, int);
  ///@}

  ///@{
  /**
   * Adaptive quality, as vtkFacetRenderFilter's: an error budget in 8-bit units. Polygons
   * whose flat-shading error bound is within it stay flat, the others are shaded per pixel
   * (Phong), whatever their actor's interpolation. 0 turns it off and each actor's property
   * Interpolation decides (default: 0). Negative values are an error at execution.
   */
  vtkSetMacro(MaximumError, double);
  vtkGetMacro(MaximumError, double);
  ///@}

  ///@{
  /**
   * Estimate the render's flat-shading error, as vtkFacetRenderFilter's EstimateError: field
   * data `FacetErrorEstimate` (PredictedRMSE, PredictedMax, 8-bit units, and Seconds), per
   * pixel a bound on how far flat shading is from the converged Phong image of the actors
   * shown (whatever their interpolation, it is flat shading's estimate). Its cost is the
   * filter's (vtkFacetRenderFilter::SetEstimateError) (default: on).
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

  /**
   * What the last render did and left out, a few lines of text (empty before the first).
   */
  const char* GetRenderPlan();

  /**
   * Includes what the renderer holds (see the class description).
   */
  vtkMTimeType GetMTime() override;

protected:
  vtkFacetRendererToImageFilter();
  ~vtkFacetRendererToImageFilter() override;

  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkRenderer* Renderer = nullptr;
  int Size[2] = { 0, 0 };
  int NumberOfThreads = 0;
  vtkTypeBool DetectClosedSurfaces = 1;
  int SamplesPerPixel = 1;
  double MaximumError = 0.0;
  vtkTypeBool EstimateError = 1;
  vtkTypeBool ErrorEstimateArray = 0;

private:
  vtkFacetRendererToImageFilter(const vtkFacetRendererToImageFilter&) = delete;
  void operator=(const vtkFacetRendererToImageFilter&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
