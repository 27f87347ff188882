/**
 * @class   vtkFacetSceneConverter
 * @brief   Private: vtkCamera, vtkLight and vtkProperty as Facet's camera, lights and
 *          material, meaning exactly what VTK's renderer makes of them.
 *
 * Camera: view angle (vertical, or horizontal converted with the image aspect), parallel
 * scale, window center and the clipping range as given. Off-axis projection, view shear and
 * model/user transforms are not rendered: a warning says so.
 *
 * Lights: headlights sit at the camera looking at its focal point; camera lights are placed
 * with vtkCamera::GetCameraLightTransformMatrix; scene lights use their transformed position
 * and focal point. Non-positional lights are directional (focal point − position); positional
 * lights are point lights with vtkLight's AttenuationValues, spot lights when the cone angle is
 * at most 90 degrees (cos^Exponent cone, as VTK's shaders). vtkFacetLight adds the linear
 * angular falloff and the falloff-distance attenuation. A light's color is its diffuse color
 * times its intensity. Switched-off lights are skipped.
 *
 * Material: vtkProperty's Ambient, Diffuse, Specular, SpecularPower, AmbientColor,
 * DiffuseColor, SpecularColor and BackfaceCulling. With scalar coloring the scalars replace
 * the ambient and diffuse colors, as in VTK. Opacity is ignored for now: everything renders
 * opaque.
 */

#ifndef vtkFacetSceneConverter_h
#define vtkFacetSceneConverter_h

#include "facet/Camera.h"
#include "facet/Light.h"
#include "facet/Material.h"

#include <string>

class vtkCamera;
class vtkLightCollection;
class vtkProperty;

class vtkFacetSceneConverter
{
public:
  /// The camera for a width × height image; `warning` names what is not rendered.
  static facet::Camera ConvertCamera(vtkCamera* camera,
    int width,
    int height,
    std::string& warning);

  /**
   * The lights, plus the scene ambient light. With no light at all and
   * `automaticLightCreation`, one headlight, as vtkRenderer creates. `warning` names lights
   * that were skipped.
   */
  static facet::LightSet ConvertLights(vtkLightCollection* lights,
    vtkCamera* camera,
    bool automaticLightCreation,
    const double ambientColor[3],
    std::string& warning);

  static facet::Material ConvertProperty(vtkProperty* property, bool scalarColoring);

  /**
   * Fits `camera` to `bounds` for a width × height image as vtkRenderer::ResetCamera does,
   * with the 0.001 near-plane tolerance of a 24-bit depth buffer; the result is VTK's, to the
   * bit, for bounds within ±kLargestBound. Bounds beyond are clamped to it, and bounds too
   * small to resolve against their distance from the origin are widened, so the camera is
   * always finite and usable. Uninitialized bounds leave the camera as it is.
   */
  static void FitCamera(vtkCamera* camera, const double bounds[6], int width, int height);

  /**
   * vtkCamera and the core square the camera's distance to its focal point: 1e100 keeps
   * that finite for the narrowest view (a 1 × 16384 image puts the camera 1e5 bounding radii
   * away) with room for products of a few such magnitudes.
   */
  static constexpr double kLargestBound = 1e100;
};

#endif
// VTK-HeaderTest-Exclude: vtkFacetSceneConverter.h
