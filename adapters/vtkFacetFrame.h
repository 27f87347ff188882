/**
 * @class   vtkFacetFrame
 * @brief   Private: what an execution of either front end renders, once its scene and camera
 *          are converted, and the steps that render it (the quality mode prepared, the image
 *          rendered, the mode's outputs added).
 */

#ifndef vtkFacetFrame_h
#define vtkFacetFrame_h

#include "vtkFacetImageRenderer.h"
#include "vtkFacetQuality.h"

#include "facet/Camera.h"
#include "facet/Scene.h"

class vtkFacetMessages;
class vtkImageData;

struct vtkFacetFrame
{
  const facet::Scene& Scene;
  const facet::Camera& Camera;
  vtkFacetImageRenderer::Settings Image; ///< its RenderWith is the quality mode's (Render)
  vtkFacetQuality::Settings Quality;
  vtkFacetImageRenderer::IdMap MapIds; ///< the front end's ids from the polygon ids
  int Conversions = 0;                 ///< the polydata this execution converted

  /**
   * Renders into `output` with `image` in `quality`'s mode (vtkFacetQuality::Prepare,
   * vtkFacetImageRenderer::Render) and adds the mode's outputs (vtkFacetQuality::AddOutputs).
   * False, with an error in `messages`, when no image was rendered.
   */
  bool Render(vtkImageData* output,
    vtkFacetImageRenderer& image,
    vtkFacetQuality& quality,
    vtkFacetMessages& messages);
};

#endif
// VTK-HeaderTest-Exclude: vtkFacetFrame.h
