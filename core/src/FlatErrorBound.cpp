// The bound of FlatErrorBound.h: how far flat shading (one color per polygon, lit at its
// center c with its face normal N_f) can be from Phong shading at any point x of the polygon.
//
// Derivation. Every direction the formula of Lighting.h reads turns, over the polygon, by an
// angle we can bound from the polygon's shape; angles obey the triangle inequality on the
// sphere, ∠(a, c) ≤ ∠(a, b) + ∠(b, c), the inequality used throughout.
//
//  1. Normal. Phong's N(x) is the normalized convex combination of the corner normals n_k.
//     When every n_k is within α < 90° of N_f, so is N(x): the cone {v : ∠(v, N_f) ≤ α} is
//     convex. So ∠(N_f, N(x)) ≤ α (α ≥ 90°: no bound, π).
//  2. Directions to a point light at P and to the eye. x lies in the ball of radius r (the
//     largest corner distance) around c, which a point at distance d > r sees within a cone
//     of half-angle asin(r/d): ∠(L(c), L(x)) ≤ β_L = asin(r/d), ∠(V(c), V(x)) ≤ β_V
//     likewise (parallel projection: β_V = 0; a directional light: β_L = 0; d ≤ r: π).
//  3. Light arriving. Attenuation is non-increasing in distance, spot cones non-increasing in
//     the angle from the axis, so over distances [d − r, d + r] and angles [γ − β_L, γ + β_L]
//     the light E(x) lies in [E_lo, E_hi], the factors at the ends.
//  4. Diffuse. ∠(N, L) is within Δ = α + β_L of the flat ∠(N_f, L_f) = θ, so
//     N·L ∈ [cos(θ + Δ), cos(θ − Δ)] (angles clamped to [0, π]); the diffuse factor is
//     monotone in N·L.
//  5. Specular, Phong: R is L turned by a half-turn about N; two half-turns about axes α
//     apart differ by a rotation of 2α, so ∠(R_f, R) ≤ 2α + β_L and ∠(R, V) is within
//     Δ = 2α + β_L + β_V of the flat ∠(R_f, V_f). Blinn-Phong: H = (L + V)/|L + V|, and
//     normalizing moves a vector by at most 2|u − v|/|u|, so ∠(H_f, H) ≤
//     2 asin(min(1, (|L_f − L| + |V_f − V|)/|L_f + V_f|)) and Δ = α + that. The alignment a
//     (R·V or N·H) then lies in [cos(φ + Δ), cos(φ − Δ)] around the flat angle φ, and
//     x ↦ x^n is monotone on [0, 1], so S(x) ∈ [a_lo^n, a_hi^n] (0 where N·L can be ≤ 0).
//     This is where the exponent enters: a sharp highlight (large n) far from the polygon's
//     alignment stays small at a_hi, one near it swings over its whole range.
//  6. Products of non-negative intervals: E·D ∈ [E_lo·D_lo, E_hi·D_hi], and the flat value
//     E_f·D_f lies inside, so |E_f·D_f − E(x)·D(x)| ≤ max(E_hi·D_hi − E_f·D_f,
//     E_f·D_f − E_lo·D_lo); likewise for E·S.
//  7. The sum: per channel, |C_f − C(x)| ≤ Kd·Cd ⊙ Σᵢ dev(EᵢDᵢ) + Ks·Cs ⊙ Σᵢ dev(EᵢSᵢ)
//     (+ the surface color's spread times everything it multiplies, when point colors vary
//     over the polygon); saturate is 1-Lipschitz, so the clamped colors differ by no more.
//     SpecularMix::Blend: |ΔC| ≤ |ΔC0| + |Δf|·max(1, Cs), f = min(1, Ks·Σ E·S).
// The largest channel, times 255, is the bound. Rounding an image to 8 bits adds at most 0.5.

#include "facet/FlatErrorBound.h"

#include <algorithm>
#include <cmath>

#include "Overloaded.h"
#include "Radiance.h"
#include "Vector.h"
#include "facet/Error.h"

namespace facet {
namespace {

// An angle in [0, π] as its cosine and sine, so that the bound adds angles without a
// transcendental call (angle addition; a sum past π is clamped to π, where the ranges below
// are already the whole of [−1, 1]).
struct Angle {
  double cos = 1.0, sin = 0.0;

  static Angle straight() { return {-1.0, 0.0}; }
  static Angle ofCosine(double c) {
    c = std::clamp(c, -1.0, 1.0);  // NaN stays NaN and gives the widest ranges below
    return {c, std::sqrt(std::max(0.0, 1.0 - c * c))};
  }
  // The half-angle asin(s) of the cone a ball of radius r fills seen from distance d,
  // s = r/d; straight when the point is inside the ball.
  static Angle ofConeSine(double s) {
    if (!(s < 1.0)) return straight();
    return {std::sqrt(1.0 - s * s), s};
  }
  Angle operator+(const Angle& b) const {
    if (cos <= -1.0 || b.cos <= -1.0) return straight();
    const Angle sum{cos * b.cos - sin * b.sin, sin * b.cos + cos * b.sin};
    return sum.sin < 0.0 || !(sum.cos > -1.0) ? straight() : sum;  // past π
  }
};

// The cosines at the ends of [θ − Δ, θ + Δ] clamped to [0, π]: cos(θ + Δ) and, unless θ ≤ Δ
// (then 1), cos(θ − Δ) = cosθ·cosΔ + sinθ·sinΔ.
struct CosineRange {
  double lo, hi;
};
CosineRange cosineRange(const Angle& theta, const Angle& spread) {
  const double hi = theta.cos >= spread.cos ? 1.0 : theta.cos * spread.cos + theta.sin * spread.sin;
  return {(theta + spread).cos, std::min(hi, 1.0)};
}

double diffuseOf(const PreparedMaterial& m, double cosine) {
  const double lit = std::clamp(cosine, 0.0, 1.0);
  if (m.material.diffuseModel == DiffuseModel::Lambert) return lit;
  return m.lerpAmbient + (m.lerpFull - m.lerpAmbient) * lit;
}

double powerOf(const PreparedMaterial& m, double alignment) {
  return std::pow(std::clamp(alignment, 0.0, 1.0), m.specularPower);
}

// max(hi − f, f − lo) per channel, for lo ≤ f ≤ hi.
glm::dvec3 deviation(const glm::dvec3& lo, const glm::dvec3& f, const glm::dvec3& hi) {
  return glm::max(glm::max(hi - f, f - lo), glm::dvec3(0.0));
}

struct Interval {
  double lo, flat, hi;
};

// One light's spread over the polygon: its diffuse and specular deviations and the largest
// diffuse light it can give (which the surface color's spread multiplies).
struct LightTerms {
  glm::dvec3 diffuse{0.0}, specular{0.0}, diffuseHigh{0.0};
};

// Steps 2 to 6 of the derivation for one light.
LightTerms lightTerms(const Light& light, const PolygonShape& polygon, const glm::dvec3& normal,
                      const Angle& normalAngle, const glm::dvec3& viewer, const Angle& viewerAngle,
                      const PreparedMaterial& m) {
  glm::dvec3 toLight = normal, radiance{0.0};
  Angle lightAngle;
  Interval factor{1.0, 1.0, 1.0};  // attenuation × cone
  std::visit(
      detail::Overloaded{
          [&](const DirectionalLight& l) {
            toLight = -glm::normalize(l.direction);
            radiance = detail::boundRadianceOf(l.color, l.intensity);
          },
          [&](const auto& l) {  // point and spot lights
            radiance = detail::boundRadianceOf(l.color, l.intensity);
            const glm::dvec3 offset = l.position - polygon.center;
            double d = glm::length(offset);
            // One division, its reciprocal multiplied (as FlatErrorBoundBatch.cpp, where
            // divisions are much of a batch's time).
            double inverse = 1.0 / d;
            if (d > 0.0 && std::isfinite(d)) {
              toLight = offset * inverse;
            } else if (const auto unit = detail::normalizeRobust(offset); unit && d > 0.0) {
              // So far that the square overflows: the renderer lights the polygon from the
              // light's direction at its distance all the same (Lighting.cpp, towardLight).
              toLight = unit->unit;
              d = unit->length;
              inverse = 1.0 / d;
            }
            lightAngle = Angle::ofConeSine(d > 0.0 ? polygon.radius * inverse : 2.0);
            const double near = std::max(0.0, d - polygon.radius), far = d + polygon.radius;
            factor = {attenuationFactor(l.attenuation, far), attenuationFactor(l.attenuation, d),
                      attenuationFactor(l.attenuation, near)};
            if constexpr (std::is_same_v<std::decay_t<decltype(l)>, SpotLight>) {
              const Angle gamma = Angle::ofCosine(glm::dot(-toLight, glm::normalize(l.direction)));
              const CosineRange axis = cosineRange(gamma, lightAngle);
              factor.lo *= spotFactor(l.cone, axis.lo);
              factor.flat *= spotFactor(l.cone, gamma.cos);
              factor.hi *= spotFactor(l.cone, axis.hi);
            }
          },
      },
      light);
  const glm::dvec3 eLo = radiance * factor.lo, eF = radiance * factor.flat,
                   eHi = radiance * factor.hi;

  const double cosine = glm::dot(normal, toLight);
  const CosineRange lit = cosineRange(Angle::ofCosine(cosine), normalAngle + lightAngle);
  const Interval d{diffuseOf(m, lit.lo), diffuseOf(m, cosine), diffuseOf(m, lit.hi)};
  LightTerms terms;
  // The Lerp model may fall with N·L (lerpFull < lerpAmbient): order the ends.
  terms.diffuse = deviation(eLo * std::min(d.lo, d.hi), eF * d.flat, eHi * std::max(d.lo, d.hi));
  terms.diffuseHigh = eHi * std::max(d.lo, d.hi);
  if (m.specular <= 0.0) return terms;

  double alignment = 0.0;
  Angle spread = Angle::straight();
  if (m.material.specularModel == SpecularModel::Phong) {
    alignment = glm::dot(2.0 * std::min(cosine, 1.0) * normal - toLight, viewer);
    spread = normalAngle + normalAngle + lightAngle + viewerAngle;
  } else if (const auto half = detail::normalizeRobust(toLight + viewer)) {
    alignment = glm::dot(normal, half->unit);
    // |L_f − L| and |V_f − V| are the chords 2 sin(β/2) = √(2 − 2 cos β) of their angles.
    const double moved = (std::sqrt(std::max(0.0, 2.0 - 2.0 * lightAngle.cos)) +
                          std::sqrt(std::max(0.0, 2.0 - 2.0 * viewerAngle.cos))) /
                         half->length;
    const Angle halfTurn = Angle::ofConeSine(moved);  // asin(min(1, moved)), doubled below
    spread = normalAngle + halfTurn + halfTurn;
  }
  const CosineRange aligned = cosineRange(Angle::ofCosine(alignment), spread);
  const Interval s{lit.lo > 0.0 ? powerOf(m, aligned.lo) : 0.0,
                   cosine > 0.0 ? powerOf(m, alignment) : 0.0,
                   lit.hi > 0.0 ? powerOf(m, aligned.hi) : 0.0};
  terms.specular = deviation(eLo * s.lo, eF * s.flat, eHi * s.hi);
  return terms;
}

}  // namespace

FlatErrorBound::FlatErrorBound(const LightSet& lights, const Camera& camera, bool twoSidedLighting)
    : lights_(lights), twoSided_(twoSidedLighting) {
  validate(lights);
  validate(camera);
  ambient_ = detail::boundRadianceOf(lights.ambient.color, lights.ambient.intensity);
  eye_ = camera.position;
  viewDirection_ = glm::normalize(camera.focalPoint - camera.position);
  parallel_ = camera.parallelProjection;
}

glm::dvec3 FlatErrorBound::toViewer(const glm::dvec3& point) const {
  if (parallel_) return -viewDirection_;
  const glm::dvec3 offset = eye_ - point;
  const double length = glm::length(offset);
  if (length > 1e-150 && length < 1e150) return offset / length;  // the common case
  const auto unit = detail::normalizeRobust(offset);
  return unit ? unit->unit : -viewDirection_;
}

double FlatErrorBound::bound(const PolygonShape& polygon, const PreparedMaterial& m,
                             const Color& surface) const {
  if (polygon.normal == glm::dvec3(0.0)) return 255.0;  // no plane: nothing to say
  glm::dvec3 viewer = -viewDirection_;
  // Which side the viewer sees, by the sign of the normal's dot product with the direction
  // toward the viewer, unnormalized where it can be (FlatErrorBoundBatch.cpp takes it so,
  // without a square root and divisions).
  glm::dvec3 towardViewer = viewer;
  Angle viewerAngle;
  if (!parallel_) {  // toViewer, with the eye's distance kept for the viewer's cone
    const glm::dvec3 offset = eye_ - polygon.center;
    const double squared = glm::dot(offset, offset);
    const double eyeDistance = std::sqrt(squared);
    const bool common = squared > 1e-300 && squared < 1e300;  // toViewer's common case
    viewer = common ? offset / eyeDistance : toViewer(polygon.center);
    towardViewer = common ? offset : viewer;
    // The viewer's cone enters the specular term only.
    if (m.specular > 0.0)
      viewerAngle = Angle::ofConeSine(eyeDistance > 0.0 ? polygon.radius / eyeDistance : 2.0);
  }
  glm::dvec3 normal = polygon.normal;
  if (twoSided_ && glm::dot(normal, towardViewer) < 0.0) normal = -normal;
  // Beyond 90° the cone of corner normals is not convex: no bound on the normal's angle.
  const Angle normalAngle =
      polygon.cosNormalSpread > 0.0 ? Angle::ofCosine(polygon.cosNormalSpread) : Angle::straight();

  LightTerms sum;
  for (const Light& light : lights_.lights) {
    const LightTerms t = lightTerms(light, polygon, normal, normalAngle, viewer, viewerAngle, m);
    sum.diffuse += t.diffuse;
    sum.specular += t.specular;
    sum.diffuseHigh += t.diffuseHigh;
  }
  glm::dvec3 spreadColor(0.0);
  if (polygon.pointColors) {
    spreadColor = glm::max(glm::dvec3(polygon.cornerColorHigh - surface),
                           glm::dvec3(surface - polygon.cornerColorLow));
  }
  const glm::dvec3 surfaceHigh =
      glm::min(glm::dvec3(surface) + spreadColor, glm::dvec3(kMaxRadiance));
  const double ambientOfSurface = m.ambientColor ? 0.0 : m.ambient;
  const glm::dvec3 base = m.diffuse * surfaceHigh * sum.diffuse +
                          spreadColor * (ambientOfSurface + ambient_ + m.diffuse * sum.diffuseHigh);
  const glm::dvec3 specular = m.specular * m.specularColor * sum.specular;
  glm::dvec3 total = base + specular;
  if (m.material.specularMix == SpecularMix::Blend) {
    total = base + glm::min(m.specular * sum.specular, glm::dvec3(1.0)) *
                       glm::max(m.specularColor, glm::dvec3(1.0));
  }
  total = glm::min(total, glm::dvec3(1.0));  // two colors in [0, 1] differ by at most 1
  const double largest = std::max({total.x, total.y, total.z});
  return std::isfinite(largest) ? 255.0 * largest : 255.0;
}

}  // namespace facet
