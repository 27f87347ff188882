/**
 * @class   vtkFacetSceneConverter
 * @brief   Private: vtkCamera and vtkLights as Facet's camera and lights, meaning exactly
 *          what VTK's renderer makes of them: the part of a scene that is the renderer's,
 *          not an actor's (vtkFacetActorConverter).
 *
 * Camera: view angle (vertical, or horizontal converted with the image aspect), parallel
 * scale, window center and the clipping range as given, for the image's aspect. Off-axis
 * projection, view shear, the model transform matrix, user (view) transforms and an explicit
 * projection matrix are not rendered yet: a warning, said once, names those the camera uses.
 *
 * Lights: headlights sit at the camera looking at its focal point; camera lights are placed
 * with vtkCamera::GetCameraLightTransformMatrix; scene lights use their transformed position
 * and focal point. Non-positional lights are directional (focal point − position); positional
 * lights are point lights with vtkLight's AttenuationValues, spot lights when the cone angle is
 * at most 90 degrees (cos^Exponent cone, as VTK's shaders). vtkFacetLight adds the linear
 * angular falloff and the falloff-distance attenuation. A light's color is its diffuse color
 * times its intensity. Switched-off lights are skipped. When the lights do not follow the
 * camera (vtkRenderer::LightFollowCamera off), every light is where its transformed
 * position and focal point put it, as VTK leaves them.
 */

#ifndef vtkFacetSceneConverter_h
#define vtkFacetSceneConverter_h

#include "facet/Camera.h"
#include "facet/Light.h"

class vtkCamera;
class vtkFacetMessages;
class vtkLightCollection;

class vtkFacetSceneConverter
{
public:
  /// The camera for a width × height image; what it does that is not rendered goes to
  /// `messages`.
  static facet::Camera ConvertCamera(vtkCamera* camera,
    int width,
    int height,
    vtkFacetMessages& messages);

  /// How the lights of a collection are placed.
  struct LightOptions
  {
    /// Add the headlight vtkRenderer::CreateLight creates (default: no).
    bool AddHeadlight = false;
    /// Place headlights and camera lights from the camera (default: yes).
    bool FollowCamera = true;
    /// The scene ambient light's color, RGB (default: none, as VTK's OpenGL renderer).
    double AmbientColor[3] = { 0.0, 0.0, 0.0 };
  };

  /**
   * What lights a scene, as VTK's OpenGL renderer tells its cases apart ("lighting
   * complexity"): no light switched on (surfaces show unlit), one headlight alone (whose
   * highlight VTK's shader computes its own way), or any other lights.
   */
  enum class Lighting
  {
    Unlit,
    Headlight,
    Lights
  };
  static Lighting LightingOf(vtkLightCollection* lights, const LightOptions& options);

  /**
   * The switched-on lights, plus the scene ambient light. Lights that cannot shine (a
   * direction of zero length) are skipped with a warning in `messages`.
   */
  static facet::LightSet ConvertLights(vtkLightCollection* lights,
    vtkCamera* camera,
    const LightOptions& options,
    vtkFacetMessages& messages);

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
