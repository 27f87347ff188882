#pragma once

/// @file Reference.h
/// What every converged reference image shares: rays through the rasterizer's own camera
/// model, a fixed many-samples-per-pixel pattern, and a deterministic multi-threaded loop
/// that averages the samples into a FloatImage.
///
/// A reference is the image a perfect renderer would show: per pixel, the area average
/// (box filter over the pixel square) of the saturated color of the surface seen through
/// each point of the pixel, composited over the background. It converges as the samples
/// grow; the error a renderer's image has against it (ImageMetrics.h) is the renderer's as
/// long as the reference changes less than that when its samples double (tested).
/// References: AnalyticReference.h (a sphere and a plane, exact), MeshReference.h in the
/// facet_reference library (any mesh, Phong-shaded, traced with Embree).

#include <cstdint>
#include <functional>
#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "facet/Camera.h"
#include "facet/Color.h"
#include "facet/FloatImage.h"

namespace facet {

/// A ray in world coordinates: the points origin + t·direction for t in [tNear, tFar].
struct Ray {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0, 0.0, -1.0};  ///< unit length
  double tNear = 0.0;                    ///< where it crosses the near clipping plane
  double tFar = 0.0;                     ///< where it crosses the far clipping plane
};

/// Rays through window points, by the rasterizer's camera model: inverse(clipFromView) and
/// the camera's frame (viewFromWorld), window x, y in pixels with (0, 0) the bottom-left
/// corner of the image, so pixel (x, y)'s center is (x + 0.5, y + 0.5) (Conventions.h).
/// A surface point the ray meets at t in [tNear, tFar] is between the clipping planes, so
/// exactly the points the rasterizer keeps are reachable.
class CameraRays {
 public:
  /// Throws facet::Error for an invalid camera (validate) or a side outside
  /// [1, kMaxImageSide].
  CameraRays(const Camera& camera, int width, int height);

  /// The ray through window point (x, y). Perspective: from the eye; parallel: from the
  /// eye's plane, along the view direction (tNear may then be negative).
  Ray through(const glm::dvec2& window) const;

  /// Unit vector from a surface point hit by `ray` toward the viewer, as the rasterizer's
  /// lighting takes it: −direction (toward the eye in perspective, against the view
  /// direction in parallel projection).
  static glm::dvec3 toViewer(const Ray& ray) { return -ray.direction; }

 private:
  glm::dvec3 eye_;
  glm::dvec3 right_, up_, back_;  // the camera's frame, world coordinates
  // The window point's image on the near plane, in view space, is affine in the window
  // coordinates (the inverse projection's w is constant there): origin + x·perX + y·perY.
  glm::dvec3 nearOrigin_, nearPerX_, nearPerY_;
  bool parallel_;
  double nearClip_, farClip_;
};

/// Sample `index` of pixel (x, y), as an offset in [0, 1)² from the pixel's bottom-left
/// corner. The pattern is the 2D Sobol sequence (van der Corput in x, Sobol's second
/// dimension in y) with a random digit scramble (XOR) fixed per pixel by a hash of (x, y):
/// Kollig & Keller 2002, "Efficient multidimensional sampling". Every prefix of 2^m samples
/// is a (0, m, 2)-net — each of the 2^m elementary boxes of any shape holds exactly one
/// sample — so edges and gradients converge about as 1/N rather than 1/√N, and the first N
/// samples of a 2N-sample pixel are the N-sample pixel. The scramble decorrelates
/// neighbouring pixels, so the remaining error looks like noise, not a pattern.
/// Deterministic: the same (x, y, index) gives the same offset everywhere.
glm::dvec2 referenceSampleOffset(int x, int y, std::uint32_t index);

/// The same pattern for one pixel, with its scramble hashed once: offset(i) equals
/// referenceSampleOffset(x, y, i).
class PixelSamplePattern {
 public:
  PixelSamplePattern(int x, int y);
  glm::dvec2 offset(std::uint32_t index) const;

 private:
  std::uint32_t scrambleX_, scrambleY_;
};

/// Reports progress in [0, 1] on the calling thread; return false to stop early.
using ReferenceProgress = std::function<bool(double fraction)>;

struct ReferenceOptions {
  /// Samples per pixel; powers of two keep the (0, m, 2)-net property above. (default: 64)
  int samplesPerPixel = 64;
  /// Threads that trace, the caller's included; 0 means one per hardware thread. The image
  /// is the same bytes for every thread count. (default: 0)
  int threads = 0;
  /// Light back faces with their normal turned toward the viewer, as the Renderer does by
  /// default. (default: on)
  bool twoSidedLighting = true;
  /// Color of pixels (and parts of pixels) the surface does not cover, saturated to [0, 1]
  /// as the rasterizer's output is. (default: black)
  Color background{0.0f};
  ReferenceProgress progress{};  ///< (default: none)
};

/// Throws facet::Error naming the first invalid option (samples outside [1, 2^20], threads
/// outside [0, 1024], a background channel that is negative or not finite).
void validate(const ReferenceOptions& options);

/// What one sample sees: the surface's color (saturated on the way, so NaN counts as 0), or
/// nothing (background). Called from several threads at once; must not throw.
using SampleTracer = std::function<std::optional<Color>(const Ray& ray)>;

struct ReferenceRender {
  FloatImage image;
  /// How much the last doubling of the samples changed the image, for free: the RMSE (8-bit
  /// units, ImageMetrics.h) between `image` and the image of its first half of samples —
  /// which is, to the bit, the image of samplesPerPixel / 2. Converged when below 0.25.
  /// Empty for one sample per pixel, or when aborted.
  std::optional<double> convergence;
  bool aborted = false;  ///< the progress callback stopped it: the rows not done are empty
  double seconds = 0.0;  ///< wall-clock time of the whole render
};

/// Traces options.samplesPerPixel rays through every pixel of a width × height image
/// (referenceSampleOffset, CameraRays) and averages what they see (the background where
/// they see nothing) into color and coverage; the first half's average gives
/// `convergence`. Rows are spread over the threads; each pixel's samples are summed in index
/// order in double, so the result does not depend on the thread count. Throws facet::Error
/// for invalid options, camera or size.
ReferenceRender renderReference(const Camera& camera, int width, int height,
                                const ReferenceOptions& options, const SampleTracer& trace);

}  // namespace facet
