#pragma once

// The view the benches time: the one the VTK filter's Update() renders while a user turns the
// camera. The mesh carries a version (the filter gives its meshes one), so validation and the
// face normals are done once per version, not per frame; the camera turns about the vertical
// axis through its focal point between frames, with the headlight at its eye, so that no frame
// is the last one again. A fixed camera on a versioned mesh would time the renderer reusing
// its last frame (~1 ms: RenderPath::Resolve); an unversioned mesh would time a validation
// and the normals no Update() pays (bench/frame-phases-issue11.md, section 0).

#include <cmath>
#include <variant>

#include "facet/Camera.h"
#include "facet/Scene.h"

namespace facet::bench {

// Degrees the benches' camera turns per frame, as an interactive view does.
constexpr double kTurnDegreesPerFrame = 1.0;

// The camera turned by `degrees` about the y axis through its focal point.
inline Camera turned(Camera camera, double degrees) {
  const double c = std::cos(degrees * M_PI / 180.0), s = std::sin(degrees * M_PI / 180.0);
  const glm::dvec3 r = camera.position - camera.focalPoint;
  camera.position = camera.focalPoint + glm::dvec3(c * r.x + s * r.z, r.y, -s * r.x + c * r.z);
  return camera;
}

// Turns `camera` by `degrees` and moves the scene's headlight (its first light: a point light
// at the eye, or a directional one from the eye to the focal point) with it.
inline void turnView(Camera& camera, Scene& scene, double degrees) {
  camera = turned(camera, degrees);
  Light& headlight = scene.lights.lights.at(0);
  if (auto* directional = std::get_if<DirectionalLight>(&headlight)) {
    directional->direction = camera.focalPoint - camera.position;
  } else {
    std::get<PointLight>(headlight).position = camera.position;
  }
}

}  // namespace facet::bench
