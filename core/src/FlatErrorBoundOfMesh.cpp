// largestFlatBound (FlatErrorBoundOfMesh.h): FlatErrorBound.cpp's bound, its worst case over
// every polygon of a block, for diffuse materials under directional and point lights.
//
// Derivation (the steps of FlatErrorBound.cpp, with the angle θ between the flat normal and
// the light taken at its worst instead of per polygon):
//  1. A polygon's interpolated normals lie within α of its flat normal, α ≤ A, the block's
//     largest spread; a point light at P sees the polygon's ball (center c, radius r) within
//     β = asin(r/|P − c|) ≤ asin(R/d_lo) = B, R the largest radius, d_lo the distance from P
//     to the block's box (c lies in the box). So ∠(N, L) is within Δ = A + B of the flat θ.
//  2. c(t) = clamp(cos t, 0, 1) moves by at most sin Δ (Δ ≤ 90°; else 1) between angles
//     |a − b| ≤ Δ in [0, π], whatever θ: for a < b ≤ 90°, cos a − cos b = ∫_a^b sin t dt ≤
//     ∫_{90°−(b−a)}^{90°} sin t dt = sin(b − a) (sin rises on [0, 90°]); for a < 90° < b it
//     is cos a = sin(90° − a) ≤ sin(b − a); past 90° both are 0. So the diffuse factor
//     D = clamp(N·L) (Lambert) or A_l + (F_l − A_l)·clamp(N·L) (Lerp) is within
//     δ = slope·sin Δ of the flat one (slope 1, or |F_l − A_l|), and |D| ≤ D_max (1, or
//     max(|A_l|, |F_l|)).
//  3. Light arriving: the distances from P to the polygon's ball, [d − r, d + r], lie in
//     [max(0, d_lo − R), d_hi + R] (d_hi: to the box's farthest corner), so the attenuation
//     E lies in [E_lo, E_hi], its factors there (non-increasing in distance), and a
//     polygon's own range of E is at most S = min(E_hi − E_lo, 2R·|E'|max), |E'|max the
//     steepest slope over those distances (steepestSlope).
//  4. |E·D − E_f·D_f| ≤ |E − E_f|·|D| + E_f·|D − D_f| ≤ S·D_max + E_hi·δ,
//     which is at least FlatErrorBound.cpp's deviation max(E_hi·D_hi − E_f·D_f,
//     E_f·D_f − E_lo·D_lo) of every polygon (its D_hi, D_lo are within δ of D_f, by 2).
//  5. Per channel Kd·Cd ⊙ Σ over lights, Cd at most `surface`; capped at 1, times 255.
// The float lanes the fused estimate takes (boundShadeColumns) lie above the double bound by
// at most κ·E_hi per light (κ = 2^-16·D', D' = max(1, |A_l|, |F_l|, |F_l − A_l|)) and Kd
// rounded up by 2^-20 (FlatErrorBoundBatch.cpp); here each light adds twice that, Kd is
// taken 2^-18 higher and the sum 2^-30 relatively, which covers them and this double
// arithmetic's own rounding (a few dozen operations of relative error 2^-53).
// Specular terms (their exponent's alignment, the viewer's cone) and spot cones are left to
// the per-polygon estimate: nothing is returned.

#include "FlatErrorBoundOfMesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "Overloaded.h"
#include "Radiance.h"

namespace facet::detail {
namespace {

// sin(min(a + b, 90°)) for angles of sines sa, sb in [0, 1] (≥ 1: 90°).
double sineOfSum(double sa, double sb) {
  if (!(sa < 1.0) || !(sb < 1.0)) return 1.0;
  const double ca = std::sqrt((1.0 - sa) * (1.0 + sa)), cb = std::sqrt((1.0 - sb) * (1.0 + sb));
  if (ca * cb - sa * sb <= 0.0) return 1.0;  // a + b ≥ 90°
  return std::min(1.0, sa * cb + ca * sb);
}

// The distances from p to the nearest and farthest points of the box.
double distanceToBox(const glm::dvec3& p, const glm::dvec3& low, const glm::dvec3& high) {
  return glm::length(p - glm::clamp(p, low, high));
}
double farthestInBox(const glm::dvec3& p, const glm::dvec3& low, const glm::dvec3& high) {
  return glm::length(glm::max(glm::abs(p - low), glm::abs(p - high)));
}

// A quadratic attenuation of constant term only (vtkLight's default, 1/a0 at every distance).
bool constantFactor(const Attenuation& attenuation) {
  const auto* q = std::get_if<QuadraticAttenuation>(&attenuation);
  return q && q->linear == 0.0 && q->quadratic == 0.0;
}

double largestMagnitude(const glm::dvec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// The largest |dE/dd| of the attenuation over distances [nearest, farthest] (∞ when it cannot
// say: min() above then takes E_hi − E_lo). Quadratic, E = 1/q(d) with q = a + b·d + c·d²:
// |E'| = q'/q², q' = b + 2c·d rising and q rising in d, so at most q'(farthest)/q(nearest)²
// (q raised to 1/kMaxAttenuation as attenuationFactor does, where E is flat). Falloff
// distance F: E = 1 up to F, F/d beyond, |E'| = F/d² ≤ F/max(F, nearest)².
double steepestSlope(const Attenuation& attenuation, double nearest, double farthest) {
  constexpr double kUnknown = std::numeric_limits<double>::infinity();
  return std::visit(Overloaded{
                        [](const NoAttenuation&) { return 0.0; },
                        [&](const QuadraticAttenuation& q) {
                          if (!(q.constant >= 0.0 && q.linear >= 0.0 && q.quadratic >= 0.0))
                            return kUnknown;
                          const double low = std::max(
                              q.constant + q.linear * nearest + q.quadratic * nearest * nearest,
                              1.0 / kMaxAttenuation);
                          const double slope =
                              (q.linear + 2.0 * q.quadratic * farthest) / (low * low);
                          return std::isfinite(slope) ? slope * (1.0 + 0x1p-40) : kUnknown;
                        },
                        [&](const FalloffDistanceAttenuation& f) {
                          if (!(f.distance > 0.0)) return kUnknown;
                          const double d = std::max(f.distance, nearest);
                          const double slope = f.distance / (d * d);
                          return std::isfinite(slope) ? slope * (1.0 + 0x1p-40) : kUnknown;
                        },
                    },
                    attenuation);
}

}  // namespace

std::optional<BlockBoundSetup> prepareBlockBound(const LightSet& lights, const PreparedMaterial& m,
                                                 const glm::dvec3& surface) {
  if (m.specular > 0.0) return std::nullopt;
  BlockBoundSetup setup;
  const bool lerp = m.material.diffuseModel == DiffuseModel::Lerp;
  setup.slope = lerp ? std::abs(m.lerpFull - m.lerpAmbient) : 1.0;
  setup.diffuseMax = lerp ? std::max(std::abs(m.lerpAmbient), std::abs(m.lerpFull)) : 1.0;
  setup.kappa = 2.0 * 0x1p-16 * std::max({1.0, setup.diffuseMax, setup.slope});
  setup.scale = m.diffuse * (1.0 + 0x1p-18) * glm::abs(surface);
  for (const Light& light : lights.lights) {
    BlockBoundSetup::Source source;
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
      source.radiance = boundRadianceOf(d->color, d->intensity);
    } else if (const auto* l = std::get_if<PointLight>(&light)) {
      source.point = l;
      source.radiance = boundRadianceOf(l->color, l->intensity);
      source.magnitude = largestMagnitude(l->position);
      source.unattenuated = std::holds_alternative<NoAttenuation>(l->attenuation);
      source.constant = constantFactor(l->attenuation);
      source.factor = attenuationFactor(l->attenuation, 0.0);
    } else {
      return std::nullopt;  // a spot light
    }
    setup.lights.push_back(source);
  }
  return setup;
}

double largestFlatBound(const BlockBoundSetup& setup, const MeshBoundExtent& extent) {
  const double radius = extent.radius;
  const bool empty = !(extent.low.x <= extent.high.x);
  const double boxMagnitude =
      empty ? 0.0 : std::max(largestMagnitude(extent.low), largestMagnitude(extent.high));
  glm::dvec3 sum(0.0);
  for (const BlockBoundSetup::Source& source : setup.lights) {
    double lightSine = 0.0, eLo = 1.0, eHi = 1.0, eSpan = 0.0;
    if (const PointLight* l = source.point; l && !empty) {
      // Widened by 2^-20 of the coordinates (their largest magnitude, times 2 > √3): above
      // the few roundings of these distances and of the float centers the shade's lanes
      // light (a few 2^-24 of the coordinates), which may lie that far outside the box.
      const double slack = 0x1p-19 * (source.magnitude + boxMagnitude);
      const double dLo = distanceToBox(l->position, extent.low, extent.high) - slack;
      lightSine = dLo > 0.0 ? radius / dLo : 2.0;  // NaN (a point at infinity): 1 below
      if (source.unattenuated) {
        // E = 1
      } else if (source.constant && slack < 0x1p-19 * 1e150) {
        // E = 1/a0 at every distance whose square does not overflow (coordinates below
        // 1e150: distances below 4e150).
        eHi = eLo = source.factor;
      } else {
        const double dHi = farthestInBox(l->position, extent.low, extent.high) + slack;
        const double closest = std::max(0.0, dLo - radius), furthest = dHi + radius;
        eHi = attenuationFactor(l->attenuation, closest);
        eLo = attenuationFactor(l->attenuation, furthest);
        // A polygon's own distances span 2r ≤ 2R: its light moves by at most 2R times the
        // attenuation's steepest slope over the box's distances.
        eSpan =
            std::min(eHi - eLo, 2.0 * radius * steepestSlope(l->attenuation, closest, furthest));
      }
    }
    const double delta = setup.slope * sineOfSum(extent.sinNormalSpread, lightSine);
    const double deviation = eSpan * setup.diffuseMax + eHi * delta + setup.kappa * eHi;
    sum += source.radiance * deviation;
  }
  const glm::dvec3 total = setup.scale * sum * (1.0 + 0x1p-30);
  const double largest = std::min(1.0, std::max({total.x, total.y, total.z}));
  return std::isfinite(largest) ? 255.0 * largest : 255.0;
}

std::optional<double> largestFlatBound(const LightSet& lights, const PreparedMaterial& m,
                                       const glm::dvec3& surface, const MeshBoundExtent& extent) {
  const std::optional<BlockBoundSetup> setup = prepareBlockBound(lights, m, surface);
  if (!setup) return std::nullopt;
  return largestFlatBound(*setup, extent);
}

}  // namespace facet::detail
