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

glm::dvec4 FrameTransform::toClip(const glm::dvec3& world) const {
  const glm::dvec3 relative = world - eye_;
  const glm::dvec4 view(glm::dot(right_, relative), glm::dot(up_, relative),
                        glm::dot(back_, relative), 1.0);
  return clipFromView_ * view;
}

double FrameTransform::planeDistance(const glm::dvec4& c, int plane) const {
  switch (plane) {
    case 0: return c.w + c.z;            // near:   z ≥ −w
    case 1: return c.w - c.z;            // far:    z ≤ w
    case 2: return guardX_ * c.w + c.x;  // left:   x ≥ −g·w
    case 3: return guardX_ * c.w - c.x;  // right:  x ≤ g·w
    case 4: return guardY_ * c.w + c.y;  // bottom: y ≥ −g·w
    default: return guardY_ * c.w - c.y; // top:    y ≤ g·w
  }
}

std::uint32_t FrameTransform::outcode(const glm::dvec4& c) const {
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(c.w)) {
    return kNonFinite;
  }
  std::uint32_t code = kInside;
  for (int plane = 0; plane < kClipPlaneCount; ++plane) {
    if (planeDistance(c, plane) < 0.0) code |= 1u << plane;
  }
  // In perspective, w ≤ 0 is at or behind the eye; the near plane (near > 0) excludes it.
  // Parallel projection has w = 1.
  return code;
}

WindowVertex FrameTransform::toWindow(const glm::dvec4& clip) const {
  const double inverseW = 1.0 / clip.w;
  const double x = (clip.x * inverseW + 1.0) * halfWidth_;
  const double y = (clip.y * inverseW + 1.0) * halfHeight_;
  const double z = (clip.z * inverseW + 1.0) * 0.5;
  WindowVertex v;
  // Round to nearest (ties to even) onto the 1/256-pixel grid: every later test is exact.
  v.x = static_cast<std::int32_t>(std::nearbyint(x * kSubpixelScale));
  v.y = static_cast<std::int32_t>(std::nearbyint(y * kSubpixelScale));
  // Clipped vertices on the near/far planes may round a hair outside [0, 1].
  v.z = static_cast<float>(z < 0.0 ? 0.0 : (z > 1.0 ? 1.0 : z));
  return v;
}

WindowVertex FrameTransform::project(const glm::dvec3& world) const {
  const glm::dvec4 clip = toClip(world);
  const std::uint32_t code = outcode(clip);
  if (code != kInside) {
    WindowVertex outside;
    outside.outcode = code;
    return outside;
  }
  return toWindow(clip);
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
