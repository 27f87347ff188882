#pragma once

/// @file Light.h
/// Light sources, distance attenuation and spot cones, as plain value types.
/// Units and conventions: Conventions.h. How lights combine: Lighting.h.

#include <variant>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Color.h"

namespace facet {

// ---------------------------------------------------------------------------------------------
// Distance attenuation
// ---------------------------------------------------------------------------------------------

/// No distance attenuation: factor 1 at every distance.
struct NoAttenuation {
  friend bool operator==(const NoAttenuation&, const NoAttenuation&) = default;
};

/// factor = 1 / (constant + linear·d + quadratic·d²), d in world units.
///
/// This is VTK's `vtkLight::AttenuationValues` (and OpenGL's) form. The default
/// (1, 0, 0.0001) is Sixth 3D's 1/(1 + k·d²) with k = 0.0001, which gives 1, 0.5, 0.1 and
/// 1/26 ≈ 0.038 at d = 0, 100, 300, 500.
///
/// Note: the Sixth 3D shading guide prints 0.99, 0.52, 0.29 for d = 100, 300, 500. Its own
/// formula does not give those (0.52 and 0.29 would need k = 1e-5, 0.99 would need k = 1e-6);
/// Facet implements the formula, and the tests check the formula's values.
struct QuadraticAttenuation {
  double constant = 1.0;    ///< a0 (default: 1)
  double linear = 0.0;      ///< a1, per world unit (default: 0)
  double quadratic = 1e-4;  ///< a2, per world unit squared (default: 0.0001, Sixth 3D)
  friend bool operator==(const QuadraticAttenuation&, const QuadraticAttenuation&) = default;
};

/// The "falloff distance" model: full intensity within `distance` F of the light, F/d beyond
/// (half at 2F, a third at 3F).
struct FalloffDistanceAttenuation {
  double distance = 100.0;  ///< F in world units, ≥ 0 (default: 100)
  friend bool operator==(const FalloffDistanceAttenuation&,
                         const FalloffDistanceAttenuation&) = default;
};

using Attenuation = std::variant<NoAttenuation, QuadraticAttenuation, FalloffDistanceAttenuation>;

/// Largest attenuation factor: a quadratic denominator below 1/kMaxAttenuation (a light on
/// the surface with a0 = 0) is raised to it, so the factor stays finite. The final color
/// saturates long before this matters.
inline constexpr double kMaxAttenuation = 1e6;

/// The attenuation factor at distance d ≥ 0 from the light.
///
/// Behaviour at the edges (tested): d = 0 gives 1/a0 (quadratic) or 1 (falloff distance);
/// a denominator below 1/kMaxAttenuation gives kMaxAttenuation; d so large that d² overflows
/// gives 0; a NaN or negative d gives 0. Never NaN or infinite.
double attenuationFactor(const Attenuation& attenuation, double distance);
/// The same, for one kind of attenuation.
double attenuationFactor(const QuadraticAttenuation& attenuation, double distance);
double attenuationFactor(const FalloffDistanceAttenuation& attenuation, double distance);

// ---------------------------------------------------------------------------------------------
// Spot cones
// ---------------------------------------------------------------------------------------------

/// Spot cone (a), the "A Light Touch" spotlight: full intensity within
/// `fullIntensityAngleDegrees` of the axis, then falling linearly in angle to zero at
/// full + falloff, zero beyond. 20° + 15° gives full at 10°, half at 27.5°, zero past 35°.
/// A falloff of 0 gives a hard edge: full intensity up to and including the full angle.
struct LinearSpotCone {
  double fullIntensityAngleDegrees = 20.0;  ///< degrees, in [0, 180] (default: 20)
  double falloffAngleDegrees = 15.0;        ///< degrees, ≥ 0 (default: 15)
  friend bool operator==(const LinearSpotCone&, const LinearSpotCone&) = default;
};

/// Spot cone (b), vtkLight's model (ConeAngle, Exponent): zero outside `coneAngleDegrees`
/// of the axis, cos(angle)^exponent inside. As VTK's shaders do, a cone angle above 90°
/// means "no cone": the light shines in every direction with factor 1. At exactly 90° the
/// cone is the front hemisphere. At 0° only points exactly on the axis are lit.
struct ExponentSpotCone {
  double coneAngleDegrees = 30.0;  ///< half-angle in degrees, in [0, 180] (default: 30, VTK)
  double exponent = 1.0;           ///< ≥ 0 (default: 1, VTK)
  friend bool operator==(const ExponentSpotCone&, const ExponentSpotCone&) = default;
};

using SpotCone = std::variant<LinearSpotCone, ExponentSpotCone>;

/// The cone factor in [0, 1] for a point whose direction from the light makes an angle with
/// the spot axis whose cosine is `cosAngleFromAxis`. The cosine is clamped to [−1, 1] first
/// (a dot product of unit vectors can round slightly past 1; acos is never called on an
/// unclamped value). A NaN cosine gives 0.
double spotFactor(const SpotCone& cone, double cosAngleFromAxis);
/// The same, for one kind of cone.
double spotFactor(const LinearSpotCone& cone, double cosAngleFromAxis);
double spotFactor(const ExponentSpotCone& cone, double cosAngleFromAxis);

// ---------------------------------------------------------------------------------------------
// Lights
// ---------------------------------------------------------------------------------------------

/// Scene-wide ambient light (Sixth 3D's). It reaches every surface regardless of
/// orientation and is multiplied by the surface color (see Lighting.h).
struct AmbientLight {
  Color color{50.0f / 255.0f};  ///< (default: RGB (50, 50, 50)/255, as Sixth 3D)
  double intensity = 1.0;       ///< (default: 1). Negative counts as 0.
  friend bool operator==(const AmbientLight&, const AmbientLight&) = default;
};

/// A light infinitely far away: parallel rays, no attenuation.
struct DirectionalLight {
  /// Direction the light travels, from the light toward the scene, as vtkLight's
  /// FocalPoint − Position. Need not be unit length; must not be zero. (default: (0, 0, −1))
  glm::dvec3 direction{0.0, 0.0, -1.0};
  Color color{1.0f};       ///< (default: white)
  double intensity = 1.0;  ///< 1 = normal (default: 1). Negative counts as 0.
  friend bool operator==(const DirectionalLight&, const DirectionalLight&) = default;
};

/// A light at a point, shining in every direction.
struct PointLight {
  glm::dvec3 position{0.0};                          ///< world coordinates (default: origin)
  Color color{1.0f};                                 ///< (default: white)
  double intensity = 1.0;                            ///< 1 = normal (default: 1). Negative → 0.
  Attenuation attenuation = QuadraticAttenuation{};  ///< (default: Sixth 3D's 1/(1+0.0001·d²))
  friend bool operator==(const PointLight&, const PointLight&) = default;
};

/// A light at a point, shining into a cone around `direction`.
struct SpotLight {
  glm::dvec3 position{0.0};                          ///< world coordinates (default: origin)
  glm::dvec3 direction{0.0, 0.0, -1.0};              ///< cone axis, away from the light; not zero
  Color color{1.0f};                                 ///< (default: white)
  double intensity = 1.0;                            ///< 1 = normal (default: 1). Negative → 0.
  Attenuation attenuation = QuadraticAttenuation{};  ///< (default: Sixth 3D's)
  SpotCone cone = LinearSpotCone{};                  ///< (default: 20° + 15° linear falloff)
  friend bool operator==(const SpotLight&, const SpotLight&) = default;
};

using Light = std::variant<DirectionalLight, PointLight, SpotLight>;

/// Everything that lights a scene.
struct LightSet {
  AmbientLight ambient;       ///< (default: Sixth 3D's dim gray)
  std::vector<Light> lights;  ///< (default: none)
  friend bool operator==(const LightSet&, const LightSet&) = default;
};

/// Throws facet::Error naming the first invalid value: a non-finite number, a zero
/// direction, a negative attenuation coefficient or falloff distance, an angle outside
/// [0, 180] degrees, a negative exponent or a negative color channel.
void validate(const LightSet& lightSet);

}  // namespace facet
