#pragma once

/// @file Camera.h
/// A camera that means what vtkCamera means, and the transforms it defines.
/// Conventions (view space, window, depth): Conventions.h.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace facet {

/// vtkCamera's parameters, with vtkCamera's defaults.
struct Camera {
  glm::dvec3 position{0.0, 0.0, 1.0};    ///< eye, world coordinates (default: (0, 0, 1))
  glm::dvec3 focalPoint{0.0, 0.0, 0.0};  ///< (default: origin)
  glm::dvec3 viewUp{0.0, 1.0, 0.0};      ///< need not be orthogonal (default: +Y)
  /// Vertical view angle in degrees, in (0, 180), for perspective projection (default: 30).
  double viewAngleDegrees = 30.0;
  bool parallelProjection = false;  ///< (default: perspective)
  /// Half the viewport height in world units, for parallel projection (default: 1).
  double parallelScale = 1.0;
  /// Near and far clipping distances from the eye along the view direction, used exactly as
  /// given (default: 0.01 and 1000.01, vtkCamera's). Perspective needs 0 < near < far;
  /// parallel projection needs near < far.
  double nearClip = 0.01;
  double farClip = 1000.01;
  /// Shifts the image center, in units of half the viewport (vtkCamera::WindowCenter);
  /// (1, 0) puts the focal point on the right edge. (default: (0, 0))
  glm::dvec2 windowCenter{0.0, 0.0};
  friend bool operator==(const Camera&, const Camera&) = default;
};

/// Throws facet::Error naming the first invalid value: a non-finite number, position equal
/// to the focal point, view-up parallel to the view direction, a view angle outside
/// (0, 180), a parallel scale ≤ 0, or a clipping range that is empty (or starts at ≤ 0 in
/// perspective).
void validate(const Camera& camera);

/// The view transform (vtkCamera::GetViewTransformMatrix): world to view space, where the
/// eye is at the origin looking down −Z. Double precision.
glm::dmat4 viewFromWorld(const Camera& camera);

/// The projection (vtkCamera::GetProjectionTransformMatrix(aspect, −1, 1)): view space to
/// clip space with OpenGL's NDC depth in [−1, 1]. `aspect` is width / height.
glm::dmat4 clipFromView(const Camera& camera, double aspect);

}  // namespace facet
