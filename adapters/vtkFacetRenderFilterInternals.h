/**
 * @class   vtkFacetRenderFilter::vtkInternals
 * @brief   Private: what vtkFacetRenderFilter keeps between executions, and the steps of an
 *          execution, kept out of the filter's public header.
 *
 * An execution turns the filter's settings into those of the shared pieces (the actor
 * converter, the image renderer, the quality modes, the compositor), picks the camera and
 * lights, renders, and across MPI processes composites. Each concept has its file:
 * - vtkFacetRenderFilterSettings.cxx: the pieces' settings, each from the filter's;
 * - vtkFacetRenderFilterColoring.cxx: the coloring, a vtkMapper's settings the filter holds;
 * - vtkFacetRenderFilterCamera.cxx: the camera set or the automatic one, and the lights;
 * - vtkFacetRenderFilterParallel.cxx: the filter across processes (bounds, ids, compositing);
 * - vtkFacetRenderFilter.cxx: the filter itself and the render.
 */

#ifndef vtkFacetRenderFilterInternals_h
#define vtkFacetRenderFilterInternals_h

#include "vtkFacetRenderFilter.h"

#include "vtkCamera.h"
#include "vtkFacetActorConverter.h"
#include "vtkFacetColoringMapper.h"
#include "vtkFacetCompositor.h"
#include "vtkFacetFrame.h"
#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFacetQuality.h"
#include "vtkFacetScalarColors.h"
#include "vtkFacetSceneConverter.h"
#include "vtkNew.h"

#include "facet/Camera.h"
#include "facet/Scene.h"

class vtkDataArray;
class vtkImageData;
class vtkPolyData;

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

  // The settings an execution assembles, each from the filter's (Settings.cxx).
  static vtkFacetSceneConverter::LightOptions LightOptionsOf(vtkFacetRenderFilter* filter);
  vtkFacetActorConverter::Actor ActorOf(vtkFacetRenderFilter* filter, vtkPolyData* input);
  static vtkFacetImageRenderer::Settings SettingsOf(vtkFacetRenderFilter* filter, bool parallel);
  // Across processes (`composited`) every rank keeps its per-pixel estimate to composite.
  static vtkFacetQuality::Settings QualityOf(vtkFacetRenderFilter* filter, bool composited);
  static vtkFacetCompositor::Settings CompositeSettingsOf(vtkFacetRenderFilter* filter,
    vtkDataArray* globalIds);
  static bool Estimates(vtkFacetRenderFilter* filter)
  {
    return filter->EstimateError || filter->ErrorEstimateArray;
  }

  // The mapper's coloring, with the array an input array to process names (ParaView's array
  // selection) in place of the mapper's (Coloring.cxx).
  vtkFacetScalarColors::Settings ColoringOf(vtkFacetRenderFilter* filter);
  // PrintSelf's lines for the coloring settings.
  void PrintColoring(vtkFacetRenderFilter* filter, ostream& os, vtkIndent indent);

  // The filter's camera, or the automatic camera: a copy of the filter's camera
  // (FitCameraToInput) or VTK's default camera, fitted to `bounds` (Camera.cxx).
  vtkCamera* CameraFor(vtkCamera* camera, bool fit, const double bounds[6], int width, int height);
  // The camera to render with, fitted to `bounds` if automatic, and the scene's lights.
  facet::Camera ViewOf(vtkFacetRenderFilter* filter, const double bounds[6], facet::Scene& scene);

  // The bounds to fit the automatic camera to: the input's finite points, across processes
  // those of every piece (this is where the processes first meet: the compositor's Prepare,
  // which also learns whether the input's global cell ids fit the compositor's payload)
  // (Parallel.cxx).
  void BoundsOf(vtkFacetRenderFilter* filter, vtkPolyData* input, bool parallel, double bounds[6]);
  // Turns polygon ids into CellId (across processes: global ids if the input has them, and
  // the rank in RankId); nothing without CellId (vtkFacetRenderFilter.cxx).
  vtkFacetImageRenderer::IdMap CellLabels(const vtkFacetImageRenderer::Settings& settings);
  // Across processes: composites this rank's render (`rendered`: false after an error) into
  // `output`, the image of all pieces, and leaves out what was made only to composite by.
  void Composite(vtkFacetRenderFilter* filter, vtkImageData* output, bool rendered);
  // Across processes Depth, CellId and ErrorEstimate are made to composite by: removed if not
  // asked for.
  static void RemoveArraysNotAsked(vtkFacetRenderFilter* filter, vtkImageData* output);
};

#endif
// VTK-HeaderTest-Exclude: vtkFacetRenderFilterInternals.h
