#pragma once

// World → clip → window for one frame, in double precision relative to the eye, so that data
// far from the origin (1e6, 1e9) projects like data at the origin.

#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "facet/Camera.h"

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

class FrameTransform {
 public:
  FrameTransform(const Camera& camera, int width, int height);

  glm::dvec4 toClip(const glm::dvec3& world) const;
  std::uint32_t outcode(const glm::dvec4& clip) const;
  // Signed distance-like value of the clip point to plane `plane` (≥ 0 inside).
  double planeDistance(const glm::dvec4& clip, int plane) const;
  // Window coordinates of a clip point that is inside the guard band and in front of the
  // eye (w > 0).
  WindowVertex toWindow(const glm::dvec4& clip) const;
  WindowVertex project(const glm::dvec3& world) const;

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
