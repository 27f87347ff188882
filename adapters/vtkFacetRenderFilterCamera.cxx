// vtkFacetRenderFilter's camera, the one set or the automatic one fitted to the input, and
// the scene's lights seen from it.
#include "vtkFacetRenderFilterInternals.h"

#include "vtkFacetPolyDataConverter.h"
#include "vtkPolyData.h"

#include <vector>

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
