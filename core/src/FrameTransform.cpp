#include "FrameTransform.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "facet/Conventions.h"

namespace facet::detail {

FrameTransform::FrameTransform(const Camera& camera, int width, int height)
    : eye_(camera.position),
      clipFromView_(clipFromView(camera, static_cast<double>(width) / height)),
      parallel_(camera.parallelProjection),
      halfWidth_(0.5 * width),
      halfHeight_(0.5 * height),
      guardX_(1.0 + kGuardBandPixels / (0.5 * width)),
      guardY_(1.0 + kGuardBandPixels / (0.5 * height)) {
  // viewFromWorld's rotation rows; its translation is applied as (world − eye) instead, in
  // double, before rotating, which is what keeps far-away data precise.
  const glm::dmat4 view = viewFromWorld(camera);
  right_ = {view[0][0], view[1][0], view[2][0]};
  up_ = {view[0][1], view[1][1], view[2][1]};
  back_ = {view[0][2], view[1][2], view[2][2]};
}

double FrameTransform::planeDistance(const glm::dvec4& c, int plane) const {
  switch (plane) {
    case 0:
      return c.w + c.z;  // near:   z ≥ −w
    case 1:
      return c.w - c.z;  // far:    z ≤ w
    case 2:
      return guardX_ * c.w + c.x;  // left:   x ≥ −g·w
    case 3:
      return guardX_ * c.w - c.x;  // right:  x ≤ g·w
    case 4:
      return guardY_ * c.w + c.y;  // bottom: y ≥ −g·w
    default:
      return guardY_ * c.w - c.y;  // top:    y ≤ g·w
  }
}

double FrameTransform::viewDistance(const glm::dvec3& world) const {
  return -glm::dot(back_, world - eye_);
}

glm::dvec3 FrameTransform::toViewer(const glm::dvec3& world) const {
  if (parallel_) return back_;
  const glm::dvec3 offset = eye_ - world;
  const double length = glm::length(offset);
  return length > 0.0 && std::isfinite(length) ? offset / length : back_;
}

}  // namespace facet::detail
