#include "FrameTransform.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include "Vector.h"
#include "facet/Conventions.h"

namespace facet::detail {
namespace {

// The perspective near distance the clipper uses: the camera's, but at least 2^-480 (about
// 1e-144) while the far plane is beyond it. A new vertex on the near plane gets d = n·h, and
// h goes down to kShrink (2^-520) for points beyond kLargeCoordinate: n·h must stay a normal
// number for x/d and y/d to be finite. Nothing nearer than 1e-144 can be told from the eye in
// a float depth key anyway (keys n/d of the scene would underflow).
double clippingNear(const Camera& camera) {
  constexpr double kSmallestNear = 0x1p-480;
  if (camera.parallelProjection || !(camera.farClip > 2.0 * kSmallestNear)) return camera.nearClip;
  return std::max(camera.nearClip, kSmallestNear);
}

}  // namespace

FrameTransform::FrameTransform(const Camera& camera, int width, int height)
    : eye_(camera.position),
      parallel_(camera.parallelProjection),
      near_(clippingNear(camera)),
      far_(camera.farClip),
      depthFromKeyOffset_(parallel_ ? 0.0 : 1.0 / (1.0 - near_ / far_)),
      depthFromKeyScale_(parallel_ ? -1.0 / (far_ - near_) : -depthFromKeyOffset_),
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
  // Clip x and y as OpenGL computes them; d and h replace its z and w (see ClipPoint).
  const glm::dmat4 projection = clipFromView(camera, static_cast<double>(width) / height);
  clipX_ = {projection[0][0], projection[1][0], projection[2][0], projection[3][0]};
  clipY_ = {projection[0][1], projection[1][1], projection[2][1], projection[3][1]};
}

double FrameTransform::planeDistance(const ClipPoint& c, int plane) const {
  switch (plane) {
    case 0:
      return c.d - near_ * c.h;  // near:   d ≥ n·h
    case 1:
      return far_ * c.h - c.d;  // far:    d ≤ f·h
    case 2:
      return guardX_ * clipW(c) + c.x;  // left:   x ≥ −g·w
    case 3:
      return guardX_ * clipW(c) - c.x;  // right:  x ≤ g·w
    case 4:
      return guardY_ * clipW(c) + c.y;  // bottom: y ≥ −g·w
    default:
      return guardY_ * clipW(c) - c.y;  // top:    y ≤ g·w
  }
}

void FrameTransform::placeOnPlane(ClipPoint& c, int plane) const {
  switch (plane) {
    case 0:
      c.d = near_ * c.h;
      break;
    case 1:
      c.d = far_ * c.h;
      break;
    case 2:
      c.x = -guardX_ * clipW(c);
      break;
    case 3:
      c.x = guardX_ * clipW(c);
      break;
    case 4:
      c.y = -guardY_ * clipW(c);
      break;
    default:
      c.y = guardY_ * clipW(c);
      break;
  }
}

double FrameTransform::viewPlaneDistance(const ClipPoint& c, int plane) const {
  switch (plane) {
    case 2:
      return clipW(c) + c.x;
    case 3:
      return clipW(c) - c.x;
    case 4:
      return clipW(c) + c.y;
    case 5:
      return clipW(c) - c.y;
    default:
      return planeDistance(c, plane);  // near and far
  }
}

// toClip's bits for each corner (this file is compiled -ffp-contract=off, as are the lanes of
// HiddenBlockCorners.cpp): a corner's eye-relative coordinates are each one of the box's six
// differences, so the rotation's nine products of a coordinate, taken once for low and once
// for high (18 instead of 72), are the products toClip takes; glm's dot sums them as
// (a + b) + c. The clip rows' products stay per corner.
bool FrameTransform::clipCorners(const Box& box, ClipPoint (&corners)[8]) const {
  const glm::dvec3 relative[2] = {box.low - eye_, box.high - eye_};
  // toClip would scale a corner beyond kLargeCoordinate (or NaN): refused, as below.
  if (!(largestMagnitude(relative[0]) <= kLargeCoordinate) ||
      !(largestMagnitude(relative[1]) <= kLargeCoordinate) ||
      std::isnan(relative[0].x + relative[0].y + relative[0].z + relative[1].x + relative[1].y +
                 relative[1].z)) {
    return false;
  }
  glm::dvec3 byX[2], byY[2], byZ[2];  // (right, up, back) times one coordinate
  for (int k = 0; k < 2; ++k) {
    byX[k] = glm::dvec3(right_.x, up_.x, back_.x) * relative[k].x;
    byY[k] = glm::dvec3(right_.y, up_.y, back_.y) * relative[k].y;
    byZ[k] = glm::dvec3(right_.z, up_.z, back_.z) * relative[k].z;
  }
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 view = byX[i & 1] + byY[(i >> 1) & 1] + byZ[(i >> 2) & 1];
    const glm::dvec4 view4(view, 1.0);
    ClipPoint& c = corners[i];
    c = {glm::dot(clipX_, view4), glm::dot(clipY_, view4), -view.z, 1.0};
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.d)) return false;
  }
  return true;
}

// 1e-9 of the magnitudes whose difference viewPlaneDistance takes.
double FrameTransform::margin(const ClipPoint& c, int plane) const {
  const double w = std::abs(clipW(c));
  switch (plane) {
    case 0:
      return 1e-9 * (std::abs(c.d) + std::abs(near_ * c.h));
    case 1:
      return 1e-9 * (std::abs(c.d) + std::abs(far_ * c.h));
    case 2:
    case 3:
      return 1e-9 * (w + std::abs(c.x));
    default:
      return 1e-9 * (w + std::abs(c.y));
  }
}

bool FrameTransform::boxOutsideView(const Box& box) const {
  ClipPoint corners[8];
  if (box.empty() || !clipCorners(box, corners)) return false;
  for (int plane = 0; plane < kClipPlaneCount; ++plane) {
    const auto outside = [&](const ClipPoint& c) {
      return viewPlaneDistance(c, plane) < -margin(c, plane);
    };
    if (std::all_of(std::begin(corners), std::end(corners), outside)) return true;
  }
  return false;
}

bool FrameTransform::boxInFrontOfNear(const Box& box) const {
  ClipPoint corners[8];
  if (box.empty() || !clipCorners(box, corners)) return false;
  return std::all_of(std::begin(corners), std::end(corners), [&](const ClipPoint& c) {
    return planeDistance(c, 0) > margin(c, 0) && clipW(c) > 0.0;
  });
}

bool FrameTransform::boxInsideClipVolume(const Box& box, ClipPoint (&corners)[8]) const {
  if (box.empty() || !clipCorners(box, corners)) return false;
  // planeDistance and margin unrolled (h is 1 here, clipCorners checked): the back-face
  // blocks' test runs this for thousands of boxes a frame.
  return std::all_of(std::begin(corners), std::end(corners), [&](const ClipPoint& c) {
    const double w = clipW(c);
    const double sideX = 1e-9 * (w + std::abs(c.x)), sideY = 1e-9 * (w + std::abs(c.y));
    return w > 0.0 && c.d - near_ > 1e-9 * (std::abs(c.d) + std::abs(near_)) &&
           far_ - c.d > 1e-9 * (std::abs(c.d) + std::abs(far_)) && guardX_ * w + c.x > sideX &&
           guardX_ * w - c.x > sideX && guardY_ * w + c.y > sideY && guardY_ * w - c.y > sideY;
  });
}

double FrameTransform::viewDistance(const glm::dvec3& world) const {
  return -glm::dot(back_, world - eye_);
}

glm::dvec3 FrameTransform::toViewer(const glm::dvec3& world) const {
  if (parallel_) return back_;
  const glm::dvec3 offset = eye_ - world;
  const double length = glm::length(offset);
  // Below 2^-510 the squared length is under DBL_MIN: subnormal (a length off by up to a
  // percent at 1e-161, not 0) or 0.
  constexpr double kShortestFromSquares = 0x1p-510;
  if (length >= kShortestFromSquares && std::isfinite(length)) return offset / length;
  // A distance beyond ~1e154 (or below ~1e-154) is finite although its square is not (or
  // is subnormal or 0): the direction from the offset scaled first. Only the eye at the point
  // (or an offset beyond double's range) has none: the view's back direction.
  if (const std::optional<UnitAndLength> robust = normalizeRobust(offset)) return robust->unit;
  return back_;
}

bool FrameTransform::facesViewer(const glm::dvec3& normal, const glm::dvec3& point) const {
  if (parallel_) return glm::dot(normal, back_) >= 0.0;
  // An eighth of each coordinate (exact): the offset and the dot product of a unit normal
  // with it then stay below DBL_MAX for any finite eye and point.
  const glm::dvec3 offset = eye_ * 0.125 - point * 0.125;
  return glm::dot(normal, offset) >= 0.0;
}

}  // namespace facet::detail
