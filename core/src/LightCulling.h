#pragma once

// Rule::LightsThatReachNothing: the lights that can change no polygon's color, left out of
// the shading before it starts. Flat shading lights a polygon at its center, which lies in
// its mesh's bounding box, so a light is judged against the boxes:
// - a zero intensity or black color adds nothing anywhere;
// - a spot light whose cone (closed, widened by kConeMarginDegrees for rounding) misses
//   every box has a spot factor of 0 at every center: an exact cone-versus-box test;
// - a positional light's contribution to a channel is at most its radiance × the
//   attenuation at the box's nearest point (attenuation only falls with distance) × the
//   material's gain (Kd·Cd·max diffuse factor + Ks·Cs); a light whose bound is at most the
//   tolerance (or exactly 0: some factor is 0) is left out, and the bounds of those left
//   out add up to the error bound the plan reports.

#include <span>

#include <glm/vec3.hpp>

#include "Box.h"
#include "facet/Light.h"
#include "facet/RenderPlan.h"
#include "facet/Scene.h"

namespace facet::detail {

// Extra angle added to a cone before testing it: far above the rounding of the angles the
// shading computes (acos of a rounded cosine is off by at most ~1e-6 degrees near 0°).
inline constexpr double kConeMarginDegrees = 1e-5;

// What the lights are judged against: each mesh's bounding box (empty for a mesh without
// finite points) with its material and colors.
struct LightTargets {
  std::span<const SceneMesh> meshes;
  std::span<const Box> bounds;  // per mesh
};

// Whether any light would be judged by the boxes (spot lights, or a tolerance above 0 with
// positional lights): otherwise the boxes need not be known.
bool lightCullingNeedsBounds(const LightSet& lights, double tolerance);

// Copies into `kept` the lights that may reach some mesh and reports the others.
void cullLights(const LightSet& lights, const LightTargets& targets, double tolerance,
                LightSet& kept, RenderPlan::LightCulling& report);

// True when no point of the box lies within `halfAngleDegrees` (+ kConeMarginDegrees) of
// the unit axis as seen from the apex: the closed cone and the box are disjoint. Exact:
// minimizes the angle over the box's vertices, edges and faces (the cone's distance is a
// convex function of the point, so its minimum over the box lies where it is stationary on
// one of them).
bool coneMissesBox(const glm::dvec3& apex, const glm::dvec3& axis, double halfAngleDegrees,
                   const Box& box);

}  // namespace facet::detail
