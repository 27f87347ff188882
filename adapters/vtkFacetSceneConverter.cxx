#include "vtkFacetSceneConverter.h"

#include "vtkCamera.h"
#include "vtkFacetLight.h"
#include "vtkFacetMessages.h"
#include "vtkFacetPropertyConverter.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {
glm::dvec3 ToVec(const double v[3])
{
  return { v[0], v[1], v[2] };
}

glm::dvec3 Transform(vtkMatrix4x4* matrix, const double point[3])
{
  double in[4] = { point[0], point[1], point[2], 1.0 };
  double out[4];
  matrix->MultiplyPoint(in, out);
  return glm::dvec3(out[0], out[1], out[2]) / out[3];
}

bool PositionIsFocalPoint(vtkCamera* camera)
{
  const double* position = camera->GetPosition();
  const double* focal = camera->GetFocalPoint();
  return position[0] == focal[0] && position[1] == focal[1] && position[2] == focal[2];
}

// Bounds about their centers, 2^-40 of their largest coordinate wide: thousands of ulps, so
// a camera fitted to them is resolvably far from its focal point.
void WidenToResolve(double bounds[6])
{
  double largest = 0.0;
  for (int i = 0; i < 6; ++i)
  {
    largest = std::max(largest, std::abs(bounds[i]));
  }
  const double half = std::ldexp(largest, -40);
  for (int i = 0; i < 6; i += 2)
  {
    const double center = 0.5 * bounds[i] + 0.5 * bounds[i + 1];
    bounds[i] = center - half;
    bounds[i + 1] = center + half;
  }
}

// What vtkCamera does beyond Facet's camera, named, joined with commas and "and".
std::string UnrenderedCameraFeatures(vtkCamera* camera)
{
  std::vector<std::string> uses;
  if (camera->GetUseOffAxisProjection())
  {
    uses.push_back("an off-axis projection");
  }
  const double* shear = camera->GetViewShear();
  if (shear[0] != 0.0 || shear[1] != 0.0)
  {
    uses.push_back("view shear");
  }
  if (!camera->GetModelTransformMatrix()->IsIdentity())
  {
    uses.push_back("a model transform matrix");
  }
  if (camera->GetUserTransform())
  {
    uses.push_back("a user transform");
  }
  if (camera->GetUserViewTransform())
  {
    uses.push_back("a user view transform");
  }
  if (camera->GetUseExplicitProjectionTransformMatrix())
  {
    uses.push_back("an explicit projection matrix");
  }
  return vtkFacetMessages::List(uses);
}

// Whether Facet's camera projects as vtkCamera's composite projection for this aspect.
bool SameProjection(const facet::Camera& c, vtkCamera* camera, double aspect)
{
  const glm::dmat4 ours = facet::clipFromView(c, aspect) * facet::viewFromWorld(c);
  vtkMatrix4x4* theirs = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  double difference = 0.0, scale = 0.0;
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      difference = std::max(difference, std::abs(ours[j][i] - theirs->GetElement(i, j)));
      scale = std::max(scale, std::abs(theirs->GetElement(i, j)));
    }
  }
  return difference <= 1e-9 * scale;
}

facet::Attenuation AttenuationOf(vtkLight* light)
{
  auto* facetLight = vtkFacetLight::SafeDownCast(light);
  if (facetLight && facetLight->GetAttenuationModel() == vtkFacetLight::FalloffDistanceModel)
  {
    return facet::FalloffDistanceAttenuation{ facetLight->GetFalloffDistance() };
  }
  const double* a = light->GetAttenuationValues();
  return facet::QuadraticAttenuation{ a[0], a[1], a[2] };
}

// The light as Facet sees it, given where it is and where it looks in world coordinates.
facet::Light ConvertLight(vtkLight* light, const glm::dvec3& position, const glm::dvec3& focal)
{
  const facet::Color color = vtkFacetPropertyConverter::ToColor(light->GetDiffuseColor());
  const double intensity = light->GetIntensity();
  if (!light->GetPositional())
  {
    return facet::DirectionalLight{ focal - position, color, intensity };
  }
  auto* facetLight = vtkFacetLight::SafeDownCast(light);
  if (facetLight && facetLight->GetSpotModel() == vtkFacetLight::LinearFalloff)
  {
    return facet::SpotLight{ position,
      focal - position,
      color,
      intensity,
      AttenuationOf(light),
      facet::LinearSpotCone{ facetLight->GetFullIntensityAngle(), facetLight->GetFalloffAngle() } };
  }
  if (light->GetConeAngle() <= 90.0)
  {
    return facet::SpotLight{ position,
      focal - position,
      color,
      intensity,
      AttenuationOf(light),
      facet::ExponentSpotCone{ std::max(light->GetConeAngle(), 0.0), light->GetExponent() } };
  }
  return facet::PointLight{ position, color, intensity, AttenuationOf(light) };
}
}

//------------------------------------------------------------------------------
facet::Camera vtkFacetSceneConverter::ConvertCamera(vtkCamera* camera,
  int width,
  int height,
  vtkFacetMessages& messages)
{
  const double aspect = static_cast<double>(width) / height;
  facet::Camera c;
  c.position = ToVec(camera->GetPosition());
  c.focalPoint = ToVec(camera->GetFocalPoint());
  c.viewUp = ToVec(camera->GetViewUp());
  c.parallelProjection = camera->GetParallelProjection() != 0;
  c.parallelScale = camera->GetParallelScale();
  c.viewAngleDegrees = camera->GetViewAngle();
  if (camera->GetUseHorizontalViewAngle() && !c.parallelProjection)
  {
    // tan(vertical / 2) = tan(horizontal / 2) / aspect
    c.viewAngleDegrees = vtkMath::DegreesFromRadians(
      2.0 * std::atan(std::tan(vtkMath::RadiansFromDegrees(c.viewAngleDegrees) / 2.0) / aspect));
  }
  const double* range = camera->GetClippingRange();
  c.nearClip = range[0];
  c.farClip = range[1];
  const double* center = camera->GetWindowCenter();
  c.windowCenter = { center[0], center[1] };

  const double* direction = camera->GetDirectionOfProjection();
  if (c.position != c.focalPoint && direction[0] == 0.0 && direction[1] == 0.0 &&
    direction[2] == 0.0)
  {
    // vtkCamera::SetPosition onto its focal point (or the reverse) leaves it degenerate: a
    // zero direction of projection and a focal point 1e-20 away. VTK draws nothing with it.
    messages.AddWarningOnce("the camera is degenerate: its position was set onto its focal "
                            "point, so vtkCamera has no direction of projection; rendering "
                            "from its position toward its focal point (said once)");
    return c;
  }
  std::string unrendered = UnrenderedCameraFeatures(camera);
  if (unrendered.empty() && !SameProjection(c, camera, aspect))
  {
    unrendered = "a projection that Facet's camera does not reproduce";
  }
  if (!unrendered.empty())
  {
    messages.AddWarningOnce("the camera uses " + unrendered +
      ", which Facet does not render yet; rendering its plain " +
      (c.parallelProjection ? "parallel" : "perspective") + " view (said once)");
  }
  return c;
}

//------------------------------------------------------------------------------
vtkFacetSceneConverter::Lighting vtkFacetSceneConverter::LightingOf(vtkLightCollection* lights,
  const LightOptions& options)
{
  // vtkOpenGLRenderer::UpdateLights: a positional light or a second light makes it "lights".
  int on = options.AddHeadlight ? 1 : 0;
  bool headlight = options.AddHeadlight;
  vtkCollectionSimpleIterator iterator;
  lights->InitTraversal(iterator);
  while (vtkLight* light = lights->GetNextLight(iterator))
  {
    if (light->GetSwitch())
    {
      ++on;
      headlight = light->LightTypeIsHeadlight() && !light->GetPositional();
    }
  }
  return on == 0 ? Lighting::Unlit : on == 1 && headlight ? Lighting::Headlight : Lighting::Lights;
}

//------------------------------------------------------------------------------
facet::LightSet vtkFacetSceneConverter::ConvertLights(vtkLightCollection* lights,
  vtkCamera* camera,
  const LightOptions& options,
  vtkFacetMessages& messages)
{
  facet::LightSet set;
  set.ambient.color = vtkFacetPropertyConverter::ToColor(options.AmbientColor);
  set.ambient.intensity = 1.0;

  vtkSmartPointer<vtkLightCollection> effective = lights;
  if (options.AddHeadlight)
  {
    effective = vtkSmartPointer<vtkLightCollection>::New();
    vtkCollectionSimpleIterator kept;
    lights->InitTraversal(kept);
    while (vtkLight* light = lights->GetNextLight(kept))
    {
      effective->AddItem(light);
    }
    vtkNew<vtkLight> headlight; // vtkRenderer::CreateLight's light
    headlight->SetLightTypeToHeadlight();
    effective->AddItem(headlight);
  }

  vtkCollectionSimpleIterator iterator;
  effective->InitTraversal(iterator);
  int index = 0;
  while (vtkLight* light = effective->GetNextLight(iterator))
  {
    const int number = index++;
    if (!light->GetSwitch())
    {
      continue;
    }
    glm::dvec3 position, focal;
    if (!options.FollowCamera)
    {
      position = ToVec(light->GetTransformedPosition());
      focal = ToVec(light->GetTransformedFocalPoint());
    }
    else if (light->LightTypeIsHeadlight())
    {
      position = ToVec(camera->GetPosition());
      focal = ToVec(camera->GetFocalPoint());
    }
    else if (light->LightTypeIsCameraLight())
    {
      vtkMatrix4x4* toWorld = camera->GetCameraLightTransformMatrix();
      position = Transform(toWorld, light->GetPosition());
      focal = Transform(toWorld, light->GetFocalPoint());
    }
    else
    {
      position = ToVec(light->GetTransformedPosition());
      focal = ToVec(light->GetTransformedFocalPoint());
    }
    const facet::Light converted = ConvertLight(light, position, focal);
    if (position == focal && options.FollowCamera && light->LightTypeIsHeadlight())
    {
      continue; // the camera itself has no direction: its own error says so
    }
    if (position == focal && !std::holds_alternative<facet::PointLight>(converted))
    {
      messages.AddWarning("light " + std::to_string(number) +
        " has its focal point at its position, so no direction; skipped");
      continue;
    }
    set.lights.push_back(converted);
  }
  return set;
}

//------------------------------------------------------------------------------
void vtkFacetSceneConverter::FitCamera(vtkCamera* camera,
  const double bounds[6],
  int width,
  int height)
{
  if (!vtkMath::AreBoundsInitialized(bounds))
  {
    return;
  }
  double fitted[6];
  for (int i = 0; i < 6; ++i)
  {
    fitted[i] = std::clamp(bounds[i], -kLargestBound, kLargestBound);
  }
  double direction[3];
  camera->GetDirectionOfProjection(direction);
  vtkNew<vtkRenderer> renderer; // never rendered: only for ResetCamera
  renderer->SetActiveCamera(camera);
  renderer->SetAspect(static_cast<double>(width) / height, 1.0);
  renderer->SetNearClippingPlaneTolerance(0.001);
  renderer->ResetCamera(fitted);
  if (!PositionIsFocalPoint(camera))
  {
    return;
  }
  // The camera's distance rounded away against its position (a 1e-10 cell at 1e20), and
  // vtkCamera lost the direction with it: restore the direction, fit a resolvable box.
  camera->SetPosition(0.0, 0.0, 0.0);
  camera->SetFocalPoint(direction);
  WidenToResolve(fitted);
  renderer->ResetCamera(fitted);
}
