#include "vtkFacetRendererToImageFilterInternals.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMapper.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <set>
#include <string>
#include <vector>

namespace {
bool AnyLightOn(vtkRenderer* renderer)
{
  vtkCollectionSimpleIterator iterator;
  renderer->GetLights()->InitTraversal(iterator);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(iterator))
  {
    if (light->GetSwitch())
    {
      return true;
    }
  }
  return false;
}
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::vtkInternals::ForEachSceneObject(vtkRenderer* renderer,
  const ObjectVisit& see)
{
  see(renderer);
  see(renderer->GetRenderWindow()); // its size, when it sets the image's
  see(renderer->IsActiveCameraCreated() ? renderer->GetActiveCamera() : nullptr);
  see(renderer->GetLights());
  vtkCollectionSimpleIterator lights;
  renderer->GetLights()->InitTraversal(lights);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(lights))
  {
    see(light);
  }
  see(renderer->GetViewProps());
  vtkCollectionSimpleIterator props;
  renderer->GetViewProps()->InitTraversal(props);
  while (vtkProp* prop = renderer->GetViewProps()->GetNextProp(props))
  {
    see(prop); // also an invisible one: its visibility may change
  }
  // Each rendered actor (with its property), its mapper (with its lookup table) and the
  // mapper's input, brought up to date, as vtkActor::GetRedrawMTime looks at them.
  std::set<std::string> skipped;
  ForEachActor(
    renderer,
    [&](int, vtkActor* actor, vtkMatrix4x4*) {
      see(actor); // its matrix is its own and its assembly's (the top prop's) MTime
      see(actor->GetMapper());
      see(InputOf(actor->GetMapper()));
    },
    skipped);
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::vtkInternals::RememberScene(vtkRenderer* renderer)
{
  this->Seen.clear();
  ForEachSceneObject(renderer, [&](vtkObject* object) {
    if (object)
    {
      this->Seen[object] = object->GetMTime();
    }
  });
}

//------------------------------------------------------------------------------
vtkCamera* vtkFacetRendererToImageFilter::vtkInternals::CameraOf(vtkRenderer* renderer,
  int width,
  int height)
{
  if (renderer->IsActiveCameraCreated())
  {
    return renderer->GetActiveCamera();
  }
  // What vtkRenderer::Render does to a renderer without a camera, for this image's aspect.
  vtkCamera* camera = renderer->GetActiveCamera();
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  vtkFacetSceneConverter::FitCamera(camera, bounds, width, height);
  return camera;
}

//------------------------------------------------------------------------------
vtkFacetSceneConverter::LightOptions vtkFacetRendererToImageFilter::vtkInternals::LightOptionsOf(
  vtkRenderer* renderer)
{
  vtkFacetSceneConverter::LightOptions lights;
  lights.AddHeadlight = !AnyLightOn(renderer) && renderer->GetAutomaticLightCreation();
  lights.FollowCamera = renderer->GetLightFollowCamera() || lights.AddHeadlight;
  return lights;
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::vtkInternals::WarnAboutUnrendered(vtkRenderer* renderer,
  vtkFacetMessages& messages)
{
  std::vector<std::string> asks;
  if (renderer->GetUseShadows())
  {
    asks.push_back("shadows (UseShadows)");
  }
  if (renderer->GetTexturedBackground())
  {
    asks.push_back("a textured background");
  }
  if (renderer->GetUseSSAO())
  {
    asks.push_back("ambient occlusion (UseSSAO)");
  }
  if (renderer->GetUseImageBasedLighting())
  {
    asks.push_back("image-based lighting");
  }
  if (!asks.empty())
  {
    messages.AddWarningOnce("the renderer asks for " + vtkFacetMessages::List(asks) +
      ", which Facet does not render yet (said once)");
  }
}
