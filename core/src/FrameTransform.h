#pragma once

// World → clip → window for one frame, in double precision relative to the eye, so that data
// far from the origin (1e6, 1e9) projects like data at the origin; and the depth key the
// depth test compares.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "Box.h"
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

// A point in Facet's clip coordinates: OpenGL's clip x and y, the view distance d (−z in view
// space; OpenGL's clip w in perspective) and the homogeneous weight h of the view-space point
// (OpenGL's clip w in parallel projection), all four times one positive scale. The scale does
// not move the point, so a point of any finite magnitude is represented without overflow
// (FrameTransform::toClip); every clip plane is linear in (x, y, d, h) and is written with the
// camera's near and far distances themselves (planeDistance), not with OpenGL's clip z, whose
// terms (f + n)/(f − n) and 2fn/(f − n) cancel and overflow.
struct ClipPoint {
  double x, y, d, h;
};

// The depth test compares depth keys, larger = nearer, rounded to float once per fragment:
// - perspective: n/d (1 at the near plane, n/f at the far plane), the reversed float depth
//   buffer (Reed, "Depth Precision Visualized", 2015). 1/d is affine in window coordinates,
//   and float keeps its relative precision 2^-24 at every distance, so surfaces whose
//   distances differ by a few 1e-7 of the distance resolve at any far/near ratio up to 2^126
//   (OpenGL's window depth, f(d − n)/(d(f − n)), rounds everything beyond ~1e7·n to 1);
// - parallel: n − d, minus the distance from the near plane. d itself is affine there, so a
//   float of the distance from the near plane resolves surfaces a few 1e-7 of that distance
//   apart (never coarser than relative to the eye distance when the near plane is in front
//   of the eye), and its window depth (d − n)/(f − n) keeps full float precision.
// The background is below every key.
inline constexpr float kBackgroundDepthKey = -std::numeric_limits<float>::infinity();

// A vertex in window space: x, y in fixed point (kSubpixelBits fraction bits) and the depth
// key. x, y, residues and depth are meaningful only when outcode is kInside.
struct WindowVertex {
  std::int32_t x = 0;
  std::int32_t y = 0;
  float depth = kBackgroundDepthKey;
  std::uint16_t outcode = kInside;
  // What snapping x and y to the grid left out, in 1/kResidueScale of a grid step (rounded):
  // coverage uses the snapped position, the depth plane the unsnapped one (Rasterizer.cpp).
  std::int8_t residueX = 0;
  std::int8_t residueY = 0;
};
// 16 bytes, the last four (outcode and residues) one little-endian word: TransformBatch.cpp
// stores vertices as four 32-bit words.
static_assert(sizeof(WindowVertex) == 16 && offsetof(WindowVertex, x) == 0 &&
              offsetof(WindowVertex, y) == 4 && offsetof(WindowVertex, depth) == 8 &&
              offsetof(WindowVertex, outcode) == 12 && offsetof(WindowVertex, residueX) == 14 &&
              offsetof(WindowVertex, residueY) == 15);
inline constexpr int kResidueBits = 8;
inline constexpr int kResidueScale = 1 << kResidueBits;

// Pixels of guard band on each side of the viewport. Window coordinates inside it stay below
// kMaxImageSide + 2·8192 < 2^15 pixels, i.e. 2^23 in fixed point, so every edge-function
// product fits comfortably in 64 bits.
inline constexpr double kGuardBandPixels = 8192.0;

// Round to nearest, ties to even, without a libm call (std::nearbyint is one on baseline
// x86-64): adding 1.5·2^52 pushes the fraction out of the mantissa in the default rounding
// mode. Exact for |x| < 2^51; window coordinates in the guard band stay below 2^23.
inline double roundToNearest(double x) {
  constexpr double kShift = 6755399441055744.0;  // 1.5 · 2^52
  return (x + kShift) - kShift;
}
inline std::int32_t roundToInteger(double x) {
  return static_cast<std::int32_t>(roundToNearest(x));
}

// Eye-relative coordinates above this magnitude are scaled down by kShrink (exactly: powers
// of two) before anything multiplies them, weight h = kShrink: every later product (the
// rotation, the projection's entries up to 2^400, the guard band's factor, the clipper's
// differences) then stays far below double's 2^1024, and h stays a normal number. So every
// finite point is projected and clipped as it is, out to ±DBL_MAX. Only a camera whose
// projection scales by more than 2^400 (a view angle below ~1e-118 degrees, or a parallel
// scale below ~1e-120 of the point's distance) can overflow a point's clip coordinates: its
// polygons are then skipped and counted as non-finite (RenderStats::polygonsNonFinite).
inline constexpr double kLargeCoordinate = 0x1p500;
inline constexpr double kShrink = 0x1p-520;

// FrameTransform's numbers, for project() in SIMD lanes (TransformBatch.cpp).
struct ProjectionConstants {
  glm::dvec3 eye, right, up, back;
  glm::dvec4 clipX, clipY;
  bool parallel;
  double near, far, halfWidth, halfHeight, guardX, guardY;
};

class FrameTransform {
 public:
  FrameTransform(const Camera& camera, int width, int height);

  ProjectionConstants constants() const {
    return {eye_,  right_, up_,        back_,       clipX_,  clipY_, parallel_,
            near_, far_,   halfWidth_, halfHeight_, guardX_, guardY_};
  }

  // Inline: these run once per point of every mesh.
  ClipPoint toClip(const glm::dvec3& world) const {
    glm::dvec3 relative = world - eye_;
    double h = 1.0;
    // Also taken for NaN and for a difference that overflowed.
    if (!(largestMagnitude(relative) <= kLargeCoordinate)) [[unlikely]] {
      relative = world * kShrink - eye_ * kShrink;
      h = kShrink;
    }
    const glm::dvec4 view(glm::dot(right_, relative), glm::dot(up_, relative),
                          glm::dot(back_, relative), h);
    return {glm::dot(clipX_, view), glm::dot(clipY_, view), -view.z, h};
  }
  std::uint32_t outcode(const ClipPoint& c) const {
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.d) || !std::isfinite(c.h)) {
      return kNonFinite;
    }
    // The planes of planeDistance, unrolled. A point at or behind the eye (w ≤ 0, possible in
    // perspective only) is beyond the near plane even when n·h underflows.
    const double w = clipW(c);
    const double gx = guardX_ * w, gy = guardY_ * w;
    return (c.d - near_ * c.h < 0.0 || !(w > 0.0) ? kBeyondNear : 0u) |
           (far_ * c.h - c.d < 0.0 ? kBeyondFar : 0u) | (gx + c.x < 0.0 ? kBeyondLeft : 0u) |
           (gx - c.x < 0.0 ? kBeyondRight : 0u) | (gy + c.y < 0.0 ? kBeyondBottom : 0u) |
           (gy - c.y < 0.0 ? kBeyondTop : 0u);
  }
  // Signed distance-like value of the clip point to plane `plane` (≥ 0 inside).
  double planeDistance(const ClipPoint& c, int plane) const;
  // Moves a point the clipper computed on plane `plane` exactly onto it, setting the one
  // coordinate the plane constrains (for the near plane d = n·h) instead of keeping the
  // interpolated value, which cancellation can leave on either side.
  void placeOnPlane(ClipPoint& c, int plane) const;
  // Window coordinates and depth key of a clip point inside the guard band and the near/far
  // range (w > 0). Clamping to the guard band only absorbs the rounding of points the
  // clipper put on its planes; it also keeps a point that is not inside from ever reaching
  // roundToInteger out of range.
  WindowVertex toWindow(const ClipPoint& c) const {
    const double inverseW = 1.0 / clipW(c);
    const double x = (clampToGuard(c.x * inverseW, guardX_) + 1.0) * halfWidth_;
    const double y = (clampToGuard(c.y * inverseW, guardY_) + 1.0) * halfHeight_;
    // Round onto the 1/256-pixel grid: every later coverage test is exact.
    const double fixedX = x * kSubpixelScale, fixedY = y * kSubpixelScale;
    const double snappedX = roundToNearest(fixedX), snappedY = roundToNearest(fixedY);
    WindowVertex v;
    v.x = static_cast<std::int32_t>(snappedX);
    v.y = static_cast<std::int32_t>(snappedY);
    v.residueX = residue(fixedX - snappedX);
    v.residueY = residue(fixedY - snappedY);
    v.depth = depthKey(c, inverseW);
    return v;
  }
  WindowVertex project(const glm::dvec3& world) const {
    const ClipPoint clip = toClip(world);
    const std::uint32_t code = outcode(clip);
    if (code != kInside) {
      WindowVertex outside;
      outside.outcode = code;
      return outside;
    }
    return toWindow(clip);
  }

  // Whether every point of the box is outside one plane of the view: a side of the viewport
  // (not of the guard band), the near or the far plane. Every triangle of such points then
  // covers no pixel center (Rule::GeometryOutsideView). Decided on the box's corners, with a
  // margin of 1e-9 of their clip coordinates' magnitudes (the planes are affine in the
  // point, and the points' own transforms round at 1e-16 of them); false for a box whose
  // corners are not finite or are beyond kLargeCoordinate from the eye.
  bool boxOutsideView(const Box& box) const;
  // Whether every point of the box is in front of the near plane, by the same margin.
  bool boxInFrontOfNear(const Box& box) const;
  // Whether every point of the box is inside the clip volume (near, far and the guard band's
  // planes) by the same margin, every corner in front of the eye: each point's outcode is
  // then kInside. `corners`: the box's corners in clip space.
  bool boxInsideClipVolume(const Box& box, ClipPoint (&corners)[8]) const;

  // Window depth (Conventions.h, "Depth") of a depth key, computed in double and rounded to
  // the nearest float: perspective (1 − n/d)/(1 − n/f) = f(d − n)/(d(f − n)), parallel
  // (d − n)/(f − n). Runs once per pixel.
  float windowDepth(float key) const {
    const double depth = depthFromKeyOffset_ + depthFromKeyScale_ * key;
    return depth > 0.0 ? (depth < 1.0 ? static_cast<float>(depth) : 1.0f) : 0.0f;
  }
  // Its terms, for windowDepth in SIMD lanes (Resolve.cpp).
  double depthFromKeyOffset() const { return depthFromKeyOffset_; }
  double depthFromKeyScale() const { return depthFromKeyScale_; }

  // View-space depth (−Z, so larger is farther) for painter's sort.
  double viewDistance(const glm::dvec3& world) const;
  // Unit vector from a world point toward the viewer (parallel projection: the reverse of
  // the view direction).
  glm::dvec3 toViewer(const glm::dvec3& world) const;
  // Whether the viewer sees the side of a surface at `point` that `normal` points to
  // (perspective: the eye is on that side of the surface's plane; parallel: the normal has a
  // component toward the viewer). Edge-on counts as facing. Exact in sign for any finite
  // input: no product overflows.
  bool facesViewer(const glm::dvec3& normal, const glm::dvec3& point) const;

 private:
  static double largestMagnitude(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  }
  // NaN becomes the upper bound. (Not std::fmin/fmax: those are libm calls.)
  static double clampToGuard(double ndc, double guard) {
    return ndc < guard ? (ndc > -guard ? ndc : -guard) : guard;
  }
  // A rounding remainder in [−0.5, 0.5] grid steps, times kResidueScale; ±128 (a tie) is
  // kept as ±127.
  static std::int8_t residue(double remainder) {
    const std::int32_t r = roundToInteger(remainder * kResidueScale);
    return static_cast<std::int8_t>(std::clamp(r, -127, 127));
  }
  double clipW(const ClipPoint& c) const { return parallel_ ? c.h : c.d; }
  // Plane `plane` of the view (planeDistance with the viewport's sides), ≥ 0 inside.
  double viewPlaneDistance(const ClipPoint& c, int plane) const;
  // The box's corners in clip space, unscaled; false when one is not finite or was scaled.
  bool clipCorners(const Box& box, ClipPoint (&corners)[8]) const;
  double margin(const ClipPoint& c, int plane) const;
  // `inverseW` is 1/d in perspective (h/d = 1/distance, so n·h cannot underflow for points
  // scaled by kShrink) and 1/h in parallel projection. Finite.
  float depthKey(const ClipPoint& c, double inverseW) const {
    constexpr double kLargest = std::numeric_limits<float>::max();
    const double key = parallel_ ? (near_ * c.h - c.d) * inverseW : near_ * (c.h * inverseW);
    return static_cast<float>(key < kLargest ? (key > -kLargest ? key : -kLargest) : kLargest);
  }

  glm::dvec3 eye_;
  glm::dvec3 right_, up_, back_;  // rows of viewFromWorld's rotation
  glm::dvec4 clipX_, clipY_;      // rows of clipFromView giving clip x and y
  bool parallel_;
  double near_, far_;
  // Window depth = offset + scale·key: perspective 1/(1 − n/f) and −1/(1 − n/f), parallel 0
  // and −1/(f − n) (0 when f − n overflows, near ±DBL_MAX: every depth then rounds to 0).
  double depthFromKeyOffset_, depthFromKeyScale_;
  double halfWidth_, halfHeight_;
  double guardX_, guardY_;  // guard band half-extent in NDC units
};

}  // namespace facet::detail
