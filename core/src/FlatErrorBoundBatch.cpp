// FlatErrorBoundBatch.h: FlatErrorBound::bound (FlatErrorBound.cpp, which has the derivation)
// in SIMD lanes, compiled once per instruction set by Highway's foreach_target (this file
// includes itself) and dispatched at run time. Every operation below is the scalar bound's
// operation on the same double operands in the same order — IEEE addition, multiplication,
// division and square root are correctly rounded on every instruction set, and the file is
// compiled without contraction into fused multiply-adds — so a lane gives the scalar bound's
// bytes. Comparisons take the scalar code's branches as masks. The helpers are forced inline
// (GCC left some as calls, their vectors passed through memory).

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "FlatErrorBoundBatch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <cstddef>

#include "FlatErrorBoundBatch.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

// FlatErrorBound.cpp's Angle: a cosine and a sine.
struct Angles {
  V cos, sin;
};

HWY_INLINE Angles straight(D d) {
  return {hn::Set(d, -1.0), hn::Zero(d)};
}

HWY_INLINE Angles select(M where, const Angles& yes, const Angles& no) {
  return {hn::IfThenElse(where, yes.cos, no.cos), hn::IfThenElse(where, yes.sin, no.sin)};
}

// Angle::ofCosine (the lanes hold no NaN: finite inputs).
HWY_INLINE Angles ofCosine(D d, V c) {
  c = hn::Min(hn::Max(c, hn::Set(d, -1.0)), hn::Set(d, 1.0));
  return {c, hn::Sqrt(hn::Max(hn::Zero(d), hn::Set(d, 1.0) - c * c))};
}

// Angle::ofConeSine.
HWY_INLINE Angles ofConeSine(D d, V s) {
  const M inside = s < hn::Set(d, 1.0);
  const Angles cone{hn::Sqrt(hn::Set(d, 1.0) - s * s), s};
  return select(inside, cone, straight(d));
}

// Angle::operator+.
HWY_INLINE Angles add(D d, const Angles& a, const Angles& b) {
  const V minusOne = hn::Set(d, -1.0);
  const Angles sum{a.cos * b.cos - a.sin * b.sin, a.sin * b.cos + a.cos * b.sin};
  const M past = hn::Or(hn::Or(a.cos <= minusOne, b.cos <= minusOne),
                        hn::Or(sum.sin < hn::Zero(d), hn::Not(sum.cos > minusOne)));
  return select(past, straight(d), sum);
}

// cosineRange: the cosines of θ + Δ and θ − Δ clamped to [0, π].
struct Range {
  V lo, hi;
};
HWY_INLINE Range cosineRange(D d, const Angles& theta, const Angles& spread) {
  const V one = hn::Set(d, 1.0);
  const V hi =
      hn::IfThenElse(theta.cos >= spread.cos, one, theta.cos * spread.cos + theta.sin * spread.sin);
  return {add(d, theta, spread).cos, hn::Min(hi, one)};
}

// attenuationFactor at distances ≥ 0.
HWY_INLINE V attenuation(D d, const BatchLighting::Source& light, V distance) {
  using Falloff = BatchLighting::Source::Falloff;
  switch (light.falloff) {
    case Falloff::None:
      return hn::Set(d, 1.0);
    case Falloff::Constant:
      return hn::Set(d, light.factor);
    case Falloff::Quadratic: {
      const V linearTerm = light.linear == 0.0 ? hn::Zero(d) : hn::Set(d, light.linear) * distance;
      const V quadraticTerm =
          light.quadratic == 0.0 ? hn::Zero(d) : hn::Set(d, light.quadratic) * distance * distance;
      const V denominator = hn::Set(d, light.constant) + linearTerm + quadraticTerm;
      const V factor = hn::Set(d, 1.0) / hn::Max(denominator, hn::Set(d, 1.0 / kMaxAttenuation));
      return hn::IfThenZeroElse(hn::IsNaN(denominator), factor);
    }
    case Falloff::Distance: {
      const V far = hn::Set(d, light.distance) / distance;
      const V factor = hn::IfThenElseZero(far > hn::Zero(d), far);
      return hn::IfThenElse(distance <= hn::Set(d, light.distance), hn::Set(d, 1.0), factor);
    }
  }
  return hn::Set(d, 1.0);
}

HWY_INLINE V diffuseOf(D d, const BatchMaterial& material, V cosine) {
  const V lit = hn::Min(hn::Max(cosine, hn::Zero(d)), hn::Set(d, 1.0));
  if (!material.lerp) return lit;
  return hn::Set(d, material.lerpAmbient) +
         hn::Set(d, material.lerpFull - material.lerpAmbient) * lit;
}

// One group of lanes' polygons: center, unit normal, radius, spread (a sine), surface color.
struct Lanes {
  V center[3], normal[3], radius, sine, surface[3];
};

// The bounds of a group of lanes; NaN where the scalar bound treats the polygon apart.
HWY_INLINE V boundLanes(D d, const BatchLighting& lighting, const BatchMaterial& material,
                        const Lanes& in) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V cx = in.center[0], cy = in.center[1], cz = in.center[2];
  V nx = in.normal[0], ny = in.normal[1], nz = in.normal[2];
  const V radius = in.radius;
  // A zero normal (degenerate) is the scalar bound's to bound.
  M bounded = hn::Not(hn::And(hn::And(nx == zero, ny == zero), nz == zero));

  // Toward the viewer, as FlatErrorBound::bound finds it: only its sign against the normal is
  // read (the viewer's cone enters the specular term only), so it stays unnormalized.
  V vx = hn::Set(d, lighting.viewer.x), vy = hn::Set(d, lighting.viewer.y),
    vz = hn::Set(d, lighting.viewer.z);
  if (!lighting.parallel) {
    vx = hn::Set(d, lighting.eye.x) - cx, vy = hn::Set(d, lighting.eye.y) - cy,
    vz = hn::Set(d, lighting.eye.z) - cz;
    const V squared = vx * vx + vy * vy + vz * vz;
    bounded = hn::And(bounded, hn::And(squared > hn::Set(d, 1e-300), squared < hn::Set(d, 1e300)));
  }
  if (lighting.twoSided) {
    const M back = nx * vx + ny * vy + nz * vz < zero;
    nx = hn::IfThenElse(back, hn::Neg(nx), nx);
    ny = hn::IfThenElse(back, hn::Neg(ny), ny);
    nz = hn::IfThenElse(back, hn::Neg(nz), nz);
  }
  // The normal's cone: the kept sine as a cosine (cosineOfSpread), then as an Angle.
  const V sine = in.sine;
  const V cosSpread = hn::IfThenZeroElse(sine >= one, hn::Sqrt(one - sine * sine));
  const Angles normalAngle = select(cosSpread > zero, ofCosine(d, cosSpread), straight(d));

  V sum[3] = {zero, zero, zero};
  for (const BatchLighting::Source& light : lighting.lights) {
    V lx = hn::Set(d, light.position.x), ly = hn::Set(d, light.position.y),
      lz = hn::Set(d, light.position.z);
    Angles lightAngle{one, zero};
    V factorLo = one, factorFlat = one, factorHi = one;
    if (!light.directional) {
      const V ox = lx - cx, oy = ly - cy, oz = lz - cz;
      const V distance = hn::Sqrt(ox * ox + oy * oy + oz * oz);
      // Not finite or zero: the scalar bound lights by the normal then (FlatErrorBound.cpp).
      bounded = hn::And(bounded, hn::And(distance > zero, distance < hn::Inf(d)));
      const V inverse = one / distance;
      lx = ox * inverse, ly = oy * inverse, lz = oz * inverse;
      lightAngle = ofConeSine(d, radius * inverse);
      const V near = hn::Max(zero, distance - radius), far = distance + radius;
      factorLo = attenuation(d, light, far);
      factorFlat = attenuation(d, light, distance);
      factorHi = attenuation(d, light, near);
    }
    const V cosine = nx * lx + ny * ly + nz * lz;
    const Range lit = cosineRange(d, ofCosine(d, cosine), add(d, normalAngle, lightAngle));
    const V diffuseLo = diffuseOf(d, material, lit.lo), diffuseHi = diffuseOf(d, material, lit.hi);
    const V low = hn::Min(diffuseLo, diffuseHi), flat = diffuseOf(d, material, cosine),
            high = hn::Max(diffuseLo, diffuseHi);
    const double radiance[3] = {light.radiance.x, light.radiance.y, light.radiance.z};
    for (int c = 0; c < 3; ++c) {
      const V r = hn::Set(d, radiance[c]);
      const V eLo = r * factorLo, eFlat = r * factorFlat, eHi = r * factorHi;
      const V hi = eHi * high, f = eFlat * flat, lo = eLo * low;
      sum[c] = sum[c] + hn::Max(hn::Max(hi - f, f - lo), zero);
    }
  }
  // No specular and one color per polygon: the total is Kd·Cd ⊙ Σ deviations, capped at 1.
  const V kd = hn::Set(d, material.diffuse);
  V largest = zero;
  for (int c = 0; c < 3; ++c) {
    const V total = hn::Min(kd * in.surface[c] * sum[c], one);
    largest = c == 0 ? total : hn::Max(largest, total);
  }
  const V bound =
      hn::IfThenElse(hn::IsFinite(largest), hn::Set(d, 255.0) * largest, hn::Set(d, 255.0));
  return hn::IfThenElse(bounded, bound, hn::NaN(d));
}

void BoundBatchLanes(const BatchLighting& lighting, const BatchMaterial& material,
                     BoundBatch& batch, std::size_t count) {
  const D d;
  for (std::size_t lane = 0; lane < count; lane += hn::Lanes(d)) {
    Lanes in;
    for (int k = 0; k < 3; ++k) {
      in.center[k] = hn::Load(d, batch.center[k] + lane);
      in.normal[k] = hn::Load(d, batch.normal[k] + lane);
      in.surface[k] = hn::Load(d, batch.surface[k] + lane);
    }
    in.radius = hn::Load(d, batch.radius + lane);
    in.sine = hn::Load(d, batch.sinNormalSpread + lane);
    hn::Store(boundLanes(d, lighting, material, in), d, batch.bound + lane);
  }
}

// The shade phase's columns (ShadeBatch.h) and the centers its lanes divided out, surfaces as
// FlatErrorBound::bound reads them (capped), bounds rounded up to float (roundedUp: a float below
// the double goes one step up; NaN stays NaN).
void ShadeColumnsLanes(const BatchLighting& lighting, const BatchMaterial& material,
                       const ShadeBatch& batch, const ShadeBatchCenters& centers,
                       const float* radius, const float* sine, std::size_t count, float* bounds,
                       EstimateBound* fixed) {
  const D d;
  const hn::Rebind<float, D> df;
  const hn::Rebind<std::uint32_t, D> du;
  const hn::Rebind<std::int32_t, D> di;
  const hn::Rebind<EstimateBound, D> dq;
  for (std::size_t lane = 0; lane < count; lane += hn::Lanes(d)) {
    Lanes in;
    for (int k = 0; k < 3; ++k) {
      in.center[k] = hn::Load(d, centers.xyz[k] + lane);
      in.normal[k] = hn::Load(d, batch.normal[k] + lane);
      in.surface[k] = hn::Min(hn::PromoteTo(d, hn::LoadU(df, batch.color[k] + lane)) + hn::Zero(d),
                              hn::Set(d, kMaxRadiance));
    }
    in.radius = hn::PromoteTo(d, hn::LoadU(df, radius + lane));
    in.sine = hn::PromoteTo(d, hn::LoadU(df, sine + lane));
    const V bound = boundLanes(d, lighting, material, in);
    const auto nearest = hn::DemoteTo(df, bound);
    // Masks do not change lane width here: the comparison carried over as 1 or 0.
    const V belowD = hn::IfThenElseZero(hn::PromoteTo(d, nearest) < bound, hn::Set(d, 1.0));
    const auto below = hn::RebindMask(du, hn::DemoteTo(df, belowD) > hn::Zero(df));
    const auto bits = hn::BitCast(du, nearest);
    const auto up = hn::BitCast(df, hn::IfThenElse(below, bits + hn::Set(du, 1u), bits));
    hn::StoreU(up, df, bounds + lane);  // bounds are ≥ 0
    // fixedBoundOf: ⌈min(b, 255)·kEstimateUnit⌉ + 1, NaN as 255 (exact: a power-of-two
    // scaling, an integer below 2^24).
    const auto capped =
        hn::IfThenElse(up < hn::Set(df, 255.0f), hn::Max(up, hn::Zero(df)), hn::Set(df, 255.0f));
    const auto q =
        hn::ConvertTo(di, hn::Ceil(capped * hn::Set(df, kEstimateUnit))) + hn::Set(di, 1);
    hn::StoreU(hn::DemoteTo(dq, q), dq, fixed + lane);
  }
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <glm/geometric.hpp>

#include "Overloaded.h"
#include "Radiance.h"

namespace facet::detail {

HWY_EXPORT(BoundBatchLanes);
HWY_EXPORT(ShadeColumnsLanes);

void boundBatch(const BatchLighting& lighting, const BatchMaterial& material, BoundBatch& batch,
                std::size_t count) {
  HWY_DYNAMIC_DISPATCH(BoundBatchLanes)(lighting, material, batch, count);
}

void boundShadeColumns(const BatchLighting& lighting, const BatchMaterial& material,
                       const ShadeBatch& batch, const ShadeBatchCenters& centers,
                       const float* radius, const float* sine, float* bounds,
                       EstimateBound* fixed) {
  HWY_DYNAMIC_DISPATCH(ShadeColumnsLanes)
  (lighting, material, batch, centers, radius, sine, batch.count, bounds, fixed);
}

ShadeBoundCollector::ShadeBoundCollector(EstimateHook* hook, const SceneMesh* mesh,
                                         std::size_t firstPolygon, bool centers)
    : first_(firstPolygon), hasCenters_(centers) {
  if (!hook) return;
  mesh_ = hook->meshOf(mesh);
  if (mesh_ == hook->meshCount || !hook->terms[mesh_]) return;
  hook_ = hook;
  hook_->bounded[mesh_].store(true, std::memory_order_relaxed);
  terms_ = hook->terms[mesh_];
  // Without centers the lights are directional and the normal already faces the side seen:
  // the bound of the polygon as lit, as under a parallel view (EstimateHook.h).
  lighting_ = centers ? hook->lighting : hook->facingLighting;
  if (lighting_ && hook->materials[mesh_]) material_ = &*hook->materials[mesh_];
}

void ShadeBoundCollector::bound(const ShadeBatch& batch) {
  if (material_) {
    boundShadeColumns(*lighting_, *material_, batch, centers_, radius_, sine_, lanes_, fixed_);
  }
  for (std::size_t lane = 0; lane < batch.count; ++lane) {
    const std::size_t id = first_ + polygons_[lane];
    float out = lanes_[lane];
    EstimateBound fixed = fixed_[lane];
    if (radius_[lane] < 0.0f || !material_ || std::isnan(out)) {
      if (radius_[lane] < 0.0f) {
        out = 255.0f;  // no normal: FlatErrorBound::bound's largest
      } else {
        const glm::dvec3 center(centers_.xyz[0][lane], centers_.xyz[1][lane],
                                centers_.xyz[2][lane]);
        const glm::dvec3 normal(batch.normal[0][lane], batch.normal[1][lane],
                                batch.normal[2][lane]);
        out = hook_->boundOne(mesh_, polygons_[lane], hasCenters_ ? &center : nullptr, normal);
      }
      fixed = fixedBoundOf(out);
    }
    hook_->bounds[id] = out;
    hook_->fixedBounds[id] = fixed;
  }
}

namespace {
void setFalloff(BatchLighting::Source& source, const Attenuation& attenuation) {
  using Falloff = BatchLighting::Source::Falloff;
  std::visit(Overloaded{
                 [&](const NoAttenuation&) { source.falloff = Falloff::None; },
                 [&](const QuadraticAttenuation& q) {
                   if (q.linear == 0.0 && q.quadratic == 0.0) {  // distances here are ≥ 0
                     source.falloff = Falloff::Constant;
                     source.factor = attenuationFactor(q, 0.0);
                     return;
                   }
                   source.falloff = Falloff::Quadratic;
                   source.constant = q.constant;
                   source.linear = q.linear;
                   source.quadratic = q.quadratic;
                 },
                 [&](const FalloffDistanceAttenuation& f) {
                   source.falloff = Falloff::Distance;
                   source.distance = f.distance;
                 },
             },
             attenuation);
}
}  // namespace

std::optional<BatchMaterial> batchMaterial(const PreparedMaterial& material) {
  if (material.specular > 0.0) return std::nullopt;
  return BatchMaterial{material.diffuse, material.material.diffuseModel != DiffuseModel::Lambert,
                       material.lerpAmbient, material.lerpFull};
}

std::optional<BatchLighting> batchLighting(const LightSet& lights, const Camera& camera,
                                           bool twoSidedLighting) {
  BatchLighting lighting;
  lighting.eye = camera.position;
  lighting.viewer = -glm::normalize(camera.focalPoint - camera.position);
  lighting.parallel = camera.parallelProjection;
  lighting.twoSided = twoSidedLighting;
  for (const Light& light : lights.lights) {
    if (std::holds_alternative<SpotLight>(light)) return std::nullopt;
    BatchLighting::Source source;
    if (const auto* directional = std::get_if<DirectionalLight>(&light)) {
      source.directional = true;
      source.position = -glm::normalize(directional->direction);
      source.radiance = boundRadianceOf(directional->color, directional->intensity);
    } else {
      const PointLight& point = std::get<PointLight>(light);
      source.position = point.position;
      source.radiance = boundRadianceOf(point.color, point.intensity);
      setFalloff(source, point.attenuation);
    }
    lighting.lights.push_back(source);
  }
  return lighting;
}

}  // namespace facet::detail
#endif  // HWY_ONCE
