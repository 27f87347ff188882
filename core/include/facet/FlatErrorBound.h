#pragma once

/// @file FlatErrorBound.h
/// How far flat shading can be from Phong shading, per polygon, from the geometry alone: the
/// error estimate Facet reports with every render (QualityRenderer.h) and the rule the
/// adaptive mode shades by.
///
/// Flat shading lights a polygon once, at its center c with its face normal N_f
/// (Renderer.h). Phong shading (the mesh reference, MeshReference.h, and Shading::Phong)
/// lights every point x of it with the corner normals interpolated, N(x). The bound holds
/// for every x of the polygon, in 8-bit units of the largest channel difference:
///
///     |flat − Phong(x)| ≤ bound(polygon)   for every point x of the polygon,
///
/// before either is rounded to 8 bits. The derivation is in FlatErrorBound.cpp; what it
/// uses: the angle between N_f and the corner normals, the polygon's radius against the
/// distances to the lights and the eye, the lights' attenuation and cones over that range,
/// and the material's diffuse and specular terms (with its exponent).

#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "facet/Camera.h"
#include "facet/Color.h"
#include "facet/Light.h"
#include "facet/Lighting.h"

namespace facet {

/// The camera-independent facts about a polygon that the bound needs (ShadingMesh keeps one
/// per polygon).
struct PolygonShape {
  /// Unit normal as flat shading takes it (triangleNormal / polygonNormal); zero for a
  /// degenerate polygon, whose bound is then the largest possible.
  glm::dvec3 normal{0.0};
  glm::dvec3 center{0.0};  ///< mean of the corners: where flat shading lights it
  double radius = 0.0;     ///< largest distance of a corner from the center
  /// The smallest cosine between `normal` and a corner normal (−1 when some corner normal
  /// is zero): every interpolated normal lies within this cone of the face normal.
  double cosNormalSpread = 1.0;
  /// With point colors (interpolated by Gouraud and Phong, while flat shading takes the
  /// polygon's color): the per-channel range of the corners' colors, in [0, 1].
  bool pointColors = false;
  Color cornerColorLow{0.0f}, cornerColorHigh{0.0f};
};

/// Bounds for one camera, lights and lighting side. Cheap per polygon (a few dozen
/// operations per light); built once per frame.
class FlatErrorBound {
 public:
  /// Throws facet::Error for invalid lights or camera.
  FlatErrorBound(const LightSet& lights, const Camera& camera, bool twoSidedLighting);

  /// The bound above for one polygon of surface color `surface` (its flat color's Cd), in
  /// 8-bit units, in [0, 255].
  double bound(const PolygonShape& polygon, const PreparedMaterial& material,
               const Color& surface) const;

  /// Unit vector from a point toward the viewer, as the renderer lights it.
  glm::dvec3 toViewer(const glm::dvec3& point) const;
  /// Whether the viewer sees the back of a plane through `point` with unit `normal`.
  bool seenFromBack(const glm::dvec3& point, const glm::dvec3& normal) const {
    return glm::dot(normal, toViewer(point)) < 0.0;
  }

 private:
  LightSet lights_;
  glm::dvec3 ambient_{0.0};
  glm::dvec3 eye_{0.0};
  glm::dvec3 viewDirection_{0.0, 0.0, -1.0};
  bool parallel_ = false;
  bool twoSided_ = true;
};

}  // namespace facet
