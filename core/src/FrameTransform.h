#pragma once

// World → clip → window for one frame, in double precision relative to the eye, so that data
// far from the origin (1e6, 1e9) projects like data at the origin.

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "facet/Camera.h"
#include "facet/Conventions.h"

namespace facet::detail {

// Where a clip-space point lies relative to the clip volume. Left/right/bottom/top are the
// guard band's planes, not the viewport's: geometry inside the guard band is rasterized
// directly (the tiles clip it to the viewport), only geometry beyond it is clipped.
enum Outcode : std::uint32_t {
  kInside = 0,
  kBeyondNear = 1u << 0,
  kBeyondFar = 1u << 1,
  kBeyondLeft = 1u << 2,
  kBeyondRight = 1u << 3,
  kBeyondBottom = 1u << 4,
  kBeyondTop = 1u << 5,
  kNonFinite = 1u << 6,
};
inline constexpr int kClipPlaneCount = 6;

// A vertex in window space: x, y in fixed point (kSubpixelBits fraction bits), z the window
// depth in [0, 1]. x, y and z are meaningful only when outcode is kInside.
struct WindowVertex {
  std::int32_t x = 0;
  std::int32_t y = 0;
  float z = 1.0f;
  std::uint32_t outcode = kInside;
};

// Pixels of guard band on each side of the viewport. Window coordinates inside it stay below
// kMaxImageSide + 2·8192 < 2^15 pixels, i.e. 2^23 in fixed point, so every edge-function
// product fits comfortably in 64 bits.
inline constexpr double kGuardBandPixels = 8192.0;

// Round to nearest, ties to even, without a libm call (std::nearbyint is one on baseline
// x86-64): adding 1.5·2^52 pushes the fraction out of the mantissa in the default rounding
// mode. Exact for |x| < 2^51; window coordinates in the guard band stay below 2^23.
inline std::int32_t roundToInteger(double x) {
  constexpr double kShift = 6755399441055744.0;  // 1.5 · 2^52
  return static_cast<std::int32_t>((x + kShift) - kShift);
}

class FrameTransform {
 public:
  FrameTransform(const Camera& camera, int width, int height);

  // Inline: these run once per point of every mesh.
  glm::dvec4 toClip(const glm::dvec3& world) const {
    const glm::dvec3 relative = world - eye_;
    const glm::dvec4 view(glm::dot(right_, relative), glm::dot(up_, relative),
                          glm::dot(back_, relative), 1.0);
    return clipFromView_ * view;
  }
  std::uint32_t outcode(const glm::dvec4& c) const {
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(c.w)) {
      return kNonFinite;
    }
    // The planes of planeDistance, unrolled. In perspective, w ≤ 0 (at or behind the eye)
    // is beyond the near plane (near > 0); parallel projection has w = 1.
    const double gx = guardX_ * c.w, gy = guardY_ * c.w;
    return (c.w + c.z < 0.0 ? kBeyondNear : 0u) | (c.w - c.z < 0.0 ? kBeyondFar : 0u) |
           (gx + c.x < 0.0 ? kBeyondLeft : 0u) | (gx - c.x < 0.0 ? kBeyondRight : 0u) |
           (gy + c.y < 0.0 ? kBeyondBottom : 0u) | (gy - c.y < 0.0 ? kBeyondTop : 0u);
  }
  // Signed distance-like value of the clip point to plane `plane` (≥ 0 inside).
  double planeDistance(const glm::dvec4& clip, int plane) const;
  // Window coordinates of a clip point that is inside the guard band and in front of the
  // eye (w > 0).
  WindowVertex toWindow(const glm::dvec4& clip) const {
    const double inverseW = 1.0 / clip.w;
    const double x = (clip.x * inverseW + 1.0) * halfWidth_;
    const double y = (clip.y * inverseW + 1.0) * halfHeight_;
    const double z = (clip.z * inverseW + 1.0) * 0.5;
    WindowVertex v;
    // Round onto the 1/256-pixel grid: every later coverage test is exact.
    v.x = roundToInteger(x * kSubpixelScale);
    v.y = roundToInteger(y * kSubpixelScale);
    // Clipped vertices on the near/far planes may round a hair outside [0, 1].
    v.z = static_cast<float>(z < 0.0 ? 0.0 : (z > 1.0 ? 1.0 : z));
    return v;
  }
  WindowVertex project(const glm::dvec3& world) const {
    const glm::dvec4 clip = toClip(world);
    const std::uint32_t code = outcode(clip);
    if (code != kInside) {
      WindowVertex outside;
      outside.outcode = code;
      return outside;
    }
    return toWindow(clip);
  }

  // View-space depth (−Z, so larger is farther) for painter's sort.
  double viewDistance(const glm::dvec3& world) const;
  // Unit vector from a world point toward the viewer (parallel projection: the reverse of
  // the view direction).
  glm::dvec3 toViewer(const glm::dvec3& world) const;

 private:
  glm::dvec3 eye_;
  glm::dvec3 right_, up_, back_;  // rows of viewFromWorld's rotation
  glm::dmat4 clipFromView_;
  bool parallel_;
  double halfWidth_, halfHeight_;
  double guardX_, guardY_;  // guard band half-extent in NDC units
};

}  // namespace facet::detail
