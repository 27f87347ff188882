#pragma once

/// @file Lighting.h
/// The color of a surface point: the whole composition in one formula.
///
/// With SpecularMix::Add (the default):
///
///     C = saturate( Ka·Ca  +  Cd ⊙ A  +  Kd·Cd ⊙ Σᵢ Eᵢ·Dᵢ  +  Ks·Cs ⊙ Σᵢ Eᵢ·Sᵢ )
///
///   Cd   surface color: the polygon's color, else Material::color
///   Ca   Material::ambientColor, else Cd
///   Cs   Material::specularColor
///   A    scene ambient light: AmbientLight::color × max(0, intensity)
///   Eᵢ   light i arriving at the point: color × max(0, intensity) × attenuation(dᵢ) ×
///        spot(angleᵢ); directional lights have neither attenuation nor spot
///   Dᵢ   Lambert: max(0, N·Lᵢ);  Lerp: a + (f − a)·clamp(N·Lᵢ, 0, 1)
///   Sᵢ   0 where N·Lᵢ ≤ 0 (the face is turned away from the light), else
///        Phong: max(0, Rᵢ·V)^n with Rᵢ = 2(N·Lᵢ)N − Lᵢ;  Blinn-Phong: max(0, N·Hᵢ)^n with
///        Hᵢ = normalize(Lᵢ + V)
///   N unit normal; Lᵢ unit vector from the point toward light i; V unit vector toward the
///   viewer; ⊙ per-channel product; saturate clamps each channel to [0, 1] once, at the end.
///
/// With SpecularMix::Blend, per channel c:
///
///     C꜀ = (1 − f꜀)·C0꜀ + f꜀·Cs꜀,   f꜀ = min(1, Ks·Σᵢ Eᵢ꜀·Sᵢ),
///     C0 = saturate( Ka·Ca + Cd ⊙ A + Kd·Cd ⊙ Σᵢ Eᵢ·Dᵢ )
///
/// which for one white light of intensity 1 is the note's f·light + (1 − f)·diffuse.
///
/// Reductions (tested): with A = 0 this is VTK's ambient + diffuse + specular
/// (Ka·Ca + Kd·Cd⊙ΣEᵢDᵢ + Ks·Cs⊙ΣEᵢSᵢ, Phong specular); with Ka = 0, Kd = 1, Ks = 0 it is
/// Sixth 3D's Cd ⊙ (A + Σᵢ Eᵢ·max(0, N·Lᵢ)).
///
/// Edge cases, chosen behaviour (tested):
/// - Every result is finite and in [0, 1], for every finite input; NaN never leaves.
/// - A point light exactly at the surface point (d = 0) lights it head-on: Lᵢ = N, with the
///   attenuation at d = 0 (spot lights measure the angle of −N from their axis).
/// - Negative intensities count as 0: a light never subtracts.
/// - Shininess 0 gives Sᵢ = 1 wherever the face is lit; huge shininess (1e6) gives a
///   vanishing, finite highlight.
/// - Unbounded products stay finite: light color × intensity, material coefficients and
///   colors are capped at kMaxRadiance before they multiply, far above anything that does
///   not saturate to white anyway.

#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Color.h"
#include "facet/Light.h"
#include "facet/Material.h"

namespace facet {

/// Cap applied to light color × intensity and to material coefficients and colors before
/// they multiply (see the edge cases above).
inline constexpr double kMaxRadiance = 1e6;

/// What the shading needs to know about one surface point.
struct SurfaceSample {
  glm::dvec3 position{0.0};            ///< world coordinates
  glm::dvec3 normal{0.0, 0.0, 1.0};    ///< unit normal, facing the side being lit
  glm::dvec3 toViewer{0.0, 0.0, 1.0};  ///< unit vector toward the eye (parallel: −view dir)
  Color color{1.0f};                   ///< Cd, the surface color
};

/// A Material with its coefficients and colors capped at kMaxRadiance once, for shading
/// many points with it.
struct PreparedMaterial {
  PreparedMaterial() : PreparedMaterial(Material{}) {}
  explicit PreparedMaterial(const Material& material);
  Material material;  ///< the models and flags, as given
  std::optional<glm::dvec3> ambientColor;
  glm::dvec3 specularColor{1.0};
  double ambient = 0.0, diffuse = 1.0, specular = 0.0, specularPower = 1.0;
  double lerpAmbient = 0.0, lerpFull = 1.0;
};

namespace detail {
struct ShaderAccess;

// The light loop a Shader runs, chosen when its lights are prepared: lights all of one kind
// (and attenuation) get a loop specialized for it, any mix a loop that tests each light.
enum class LightLoop { Directional, Point, PointQuadratic, PointFalloff, Mixed };

// A direct light as Shader keeps it (Lighting.cpp).
struct PreparedLight {
  enum class Kind { Directional, Point, Spot };
  Kind kind = Kind::Directional;
  glm::dvec3 position{0.0};
  glm::dvec3 direction{0.0};  // Directional: unit vector toward the light. Spot: unit axis.
  glm::dvec3 radiance{0.0};   // color × max(0, intensity), capped
  Attenuation attenuation;
  SpotCone cone;
};
}  // namespace detail

/// A LightSet validated and prepared once, so shading a polygon does no setup work.
/// Cheap to copy; holds no references to the LightSet it came from.
class Shader {
 public:
  /// Validates the lights (throws facet::Error naming the first bad value) and prepares them.
  explicit Shader(const LightSet& lightSet) { reset(lightSet); }
  /// No light at all, not even ambient.
  Shader() = default;

  /// Prepares another light set, reusing this shader's memory. On error (facet::Error) the
  /// shader is left without lights.
  void reset(const LightSet& lightSet);

  /// The color of one surface point under these lights, by the formula above. Finite, in
  /// [0, 1].
  Color shade(const SurfaceSample& sample, const Material& material) const;
  /// The same, with the material prepared once for many points.
  Color shade(const SurfaceSample& sample, const PreparedMaterial& material) const;

  /// True when some light's contribution depends on the point's position (point or spot
  /// lights); with only directional lights, equal normals give equal colors.
  bool hasPositionalLights() const { return hasPositionalLights_; }
  /// Number of direct (non-ambient) lights that can shed light; lights of zero intensity
  /// or black color are left out when the shader is prepared.
  std::size_t lightCount() const { return lights_.size(); }

 private:
  friend struct detail::ShaderAccess;  // the renderer picks the routine once per mesh

  // shade(), specialized for the light loop and for whether the material has a specular
  // term (PreparedMaterial::specular > 0).
  using Routine = Color (*)(const Shader& shader, const SurfaceSample& sample,
                            const PreparedMaterial& material);
  Routine routine(bool specular) const;
  template <detail::LightLoop kLoop, bool kSpecular>
  static Color shadeWith(const Shader& shader, const SurfaceSample& sample,
                         const PreparedMaterial& material);

  std::vector<detail::PreparedLight> lights_;
  glm::dvec3 ambient_{0.0};
  bool hasPositionalLights_ = false;
  detail::LightLoop loop_ = detail::LightLoop::Directional;
};

/// One-off convenience: Shader(lightSet).shade(sample, material).
Color shade(const SurfaceSample& sample, const Material& material, const LightSet& lightSet);

/// The diffuse factor Dᵢ for a given N·L (see the formula). Lambert: max(0, cosine);
/// Lerp: a + (f − a)·clamp(cosine, 0, 1). A NaN cosine gives 0.
double diffuseFactor(const Material& material, double cosine);

/// The angle between two vectors, in degrees, in [0, 180]. Computed as atan2(|a×b|, a·b) of
/// the unit vectors, which is accurate at every angle and never feeds acos a cosine that
/// rounded past 1: parallel vectors give exactly 0. Throws facet::Error for a zero-length or
/// non-finite vector.
double angleBetweenDegrees(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace facet
