#include "facet/Camera.h"

#include <cmath>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "Validate.h"

namespace facet {

void validate(const Camera& camera) {
  detail::requireFinite(camera.position, "Camera.position");
  detail::requireFinite(camera.focalPoint, "Camera.focalPoint");
  detail::requireNonZeroDirection(camera.viewUp, "Camera.viewUp");
  detail::requireFinite(camera.windowCenter.x, "Camera.windowCenter.x");
  detail::requireFinite(camera.windowCenter.y, "Camera.windowCenter.y");
  const glm::dvec3 direction = camera.focalPoint - camera.position;
  if (direction == glm::dvec3(0.0)) {
    detail::fail("Camera.focalPoint", "equals Camera.position " +
                                          detail::formatVector(camera.position) +
                                          ": there is no view direction");
  }
  // Parallel within rounding: the sideways axis would be noise.
  const glm::dvec3 unitDirection = glm::normalize(direction);
  const glm::dvec3 unitUp = glm::normalize(camera.viewUp);
  if (glm::length(glm::cross(unitDirection, unitUp)) < 1e-12) {
    detail::fail("Camera.viewUp",
                 "is " + detail::formatVector(camera.viewUp) + ", parallel to the view direction");
  }
  detail::requireFinite(camera.nearClip, "Camera.nearClip");
  detail::requireFinite(camera.farClip, "Camera.farClip");
  if (camera.parallelProjection) {
    detail::requirePositive(camera.parallelScale, "Camera.parallelScale");
  } else {
    detail::requireInRange(camera.viewAngleDegrees, 0.0, 180.0, "Camera.viewAngleDegrees");
    if (camera.viewAngleDegrees == 0.0 || camera.viewAngleDegrees == 180.0) {
      detail::fail("Camera.viewAngleDegrees",
                   "is " + detail::formatValue(camera.viewAngleDegrees) + ", must be in (0, 180)");
    }
    detail::requirePositive(camera.nearClip, "Camera.nearClip (perspective)");
  }
  if (!(camera.nearClip < camera.farClip)) {
    detail::fail("Camera.farClip", "is " + detail::formatValue(camera.farClip) +
                                       ", must be greater than Camera.nearClip " +
                                       detail::formatValue(camera.nearClip));
  }
}

glm::dmat4 viewFromWorld(const Camera& camera) {
  return glm::lookAtRH(camera.position, camera.focalPoint, camera.viewUp);
}

glm::dmat4 clipFromView(const Camera& camera, double aspect) {
  // vtkCamera::ComputeProjectionTransform, for a vertical view angle.
  const glm::dvec2 center = camera.windowCenter;
  if (camera.parallelProjection) {
    const double height = camera.parallelScale;
    const double width = height * aspect;
    return glm::orthoRH_NO((center.x - 1.0) * width, (center.x + 1.0) * width,
                           (center.y - 1.0) * height, (center.y + 1.0) * height, camera.nearClip,
                           camera.farClip);
  }
  const double height = camera.nearClip * std::tan(glm::radians(camera.viewAngleDegrees) / 2.0);
  const double width = height * aspect;
  return glm::frustumRH_NO((center.x - 1.0) * width, (center.x + 1.0) * width,
                           (center.y - 1.0) * height, (center.y + 1.0) * height, camera.nearClip,
                           camera.farClip);
}

}  // namespace facet
