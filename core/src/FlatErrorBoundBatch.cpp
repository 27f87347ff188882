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

// The float lanes (below): a whole vector, two groups of double lanes (one on the scalar
// target, which has no vector twice as wide), so each float operation takes twice the lanes.
using DH = hn::Rebind<float, D>;  // as many as the double lanes
#if HWY_TARGET == HWY_SCALAR
using DF = DH;
constexpr int kDoubleGroups = 1;
#else
using DF = hn::Twice<DH>;
constexpr int kDoubleGroups = 2;
#endif
using VF = hn::Vec<DF>;
using MF = hn::Mask<DF>;

// FlatErrorBound.cpp's Angle: a cosine and a sine, in double or float lanes.
template <class VV>
struct AnglesOf {
  VV cos, sin;
};
using Angles = AnglesOf<V>;
using AnglesF = AnglesOf<VF>;

template <class DD>
HWY_INLINE AnglesOf<hn::Vec<DD>> straight(DD d) {
  return {hn::Set(d, -1), hn::Zero(d)};
}

template <class MM, class VV>
HWY_INLINE AnglesOf<VV> select(MM where, const AnglesOf<VV>& yes, const AnglesOf<VV>& no) {
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
template <class DD>
HWY_INLINE AnglesOf<hn::Vec<DD>> add(DD d, const AnglesOf<hn::Vec<DD>>& a,
                                     const AnglesOf<hn::Vec<DD>>& b) {
  const auto minusOne = hn::Set(d, -1);
  const AnglesOf<hn::Vec<DD>> sum{a.cos * b.cos - a.sin * b.sin, a.sin * b.cos + a.cos * b.sin};
  const auto past = hn::Or(hn::Or(a.cos <= minusOne, b.cos <= minusOne),
                           hn::Or(sum.sin < hn::Zero(d), hn::Not(sum.cos > minusOne)));
  return select(past, straight(d), sum);
}

// cosineRange: the cosines of θ + Δ and θ − Δ clamped to [0, π].
template <class VV>
struct RangeOf {
  VV lo, hi;
};
template <class DD>
HWY_INLINE RangeOf<hn::Vec<DD>> cosineRange(DD d, const AnglesOf<hn::Vec<DD>>& theta,
                                            const AnglesOf<hn::Vec<DD>>& spread) {
  const auto one = hn::Set(d, 1);
  const auto hi =
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
    const auto lit = cosineRange(d, ofCosine(d, cosine), add(d, normalAngle, lightAngle));
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

// ---------------------------------------------------------------------------------------
// The bound in float lanes (boundShadeColumns): the double bound's steps in float, where
// square roots and divisions cost a fraction, with a margin that keeps it a bound.
//
// Margin, proven to first order in u = 2^-24 (float's unit roundoff; IEEE +, −, ×, /, √
// round to nearest, relative error ≤ u; no fused multiply-adds). What stays in double:
// the offsets eye − c and P − c (c far from the origin: no cancellation in float) and the
// side seen. Angles are (cos, sin) pairs; a pair whose components are off by δc, δs
// (absolute) from a unit pair is off in angle by ≤ δc + δs and in norm by ≤ δc + δs, and
// then every cosine formed from it (cos(θ ± Δ), clamped or not) is off by at most the sum
// of its angles' and norms' errors (cos is 1-Lipschitz; a norm off by ε scales a cosine by
// 1 ± ε). No pair is taken as √(1 − c²) of a rounded cosine (that amplifies an error e to
// √(2e) near c = ±1):
//   - normal cone, sine s exact (kept float): cos = √((1 − s)(1 + s)): 1 − s exact for
//     s ≥ 1/2 (Sterbenz), else ≤ u; the product ≤ 3u relative, the root ≤ 2.5u. Pair:
//     angle 1.25u, norm 2.5u.
//   - light direction: o_f = float(P − c) (u per component: angle ≤ u); q = o_f·o_f ≤ 3u
//     relative (nonnegative terms); dist = √q ≤ 2.5u; 1/dist ≤ 3.5u; L = o_f/dist ≤ 4.5u per
//     component: angle ≤ 5.5u, |L| = 1 ± 4.5u. q is kept in [2^-100, 2^100] (normal floats,
//     no overflow), else the lane is the scalar bound's.
//   - light cone: s = r/dist ≤ 5.5u relative; its angle asin(s) would be off by 5.5u·tan β,
//     unbounded for a light on the surface, so s is rounded up instead: s·(1 + 2^-21) ≥
//     s(1 − 5.5u)(1 + 8u)(1 − u) > r/|P − c|, and the pair from it as the normal cone's
//     (≤ 1.25u short of its angle, norm 2.5u). A larger cone only widens the ranges.
//   - flat angle θ between n and L: cos = n_f·L ≤ 3u + the norms (n_f: u, L: 4.5u), sin =
//     |n_f × L| (each component ≤ 2u·(|a b| + |c d|), in all ≤ 3u, the root 2.5u): angle
//     ≤ 6.5u (directions) + 8.5u, norm ≤ 14u.
//   - Δ = normal cone + light cone: 2.5u (angles) + 2.8u (the sum's rounding); norm 7.8u.
//   - lo = cos(θ + Δ): ≤ 23u (angle) + 25u (norm) = 48u. hi = cos(θ − Δ), or 1 where
//     cos θ ≥ cos Δ: ≤ 48u, and where that test goes the other way than exact arithmetic
//     (|cos θ − cos Δ| ≤ 42u: the cosines' errors) 1 − cos(θ − Δ) ≤ |cos θ − cos Δ| (for
//     0 ≤ θ, Δ ≤ π: concave in θ, zero at the ends), so ≤ 90u in all. flat = n·L: 29u.
//     Diffuse (clamped: 1-Lipschitz; Lerp a + (b − a)·x: × |b − a|, + 4u·max(|a|, |b − a|)).
//   - light E = radiance × factor: radiance u; factor at dist ≤ 7u (1/(a0 + a1 d + a2 d²):
//     nonnegative terms; distance/d); the ends at near = max(0, dist(1 − 2^-20) − r) ≤
//     |P − c| − r and far = (dist + r)(1 + 2^-20) ≥ |P − c| + r, so by monotonicity E_hi and
//     E_lo are the factors at distances past the exact ones', each with ≤ 8u: no relative
//     error blows up where near → 0.
//   - per light and channel: |dev_f − dev| ≤ E_hi·D'·(90 + 29 + 48 + 8·3 + 4 products and
//     differences) u < 200u·E_hi·D', D' = max(1, |b − a|, |a|, |b|) (Lambert: 1).
// So each light adds kappa·E_hi with kappa = 2^-16·D' = 256u·D' to its deviations (more than
// the 200u above, the slack covering the second-order terms and the double bound's own
// rounding, below 2^-50), and Kd is rounded up by 2^-20 = 16u, covering the ≤ 5 roundings of
// the products and sums after (all terms nonnegative: surface colors are taken ≥ 0). A
// light's coefficients outside [2^-60, 2^20] (batchLighting) or a radius above 2^50 leave
// the lanes (far, d² overflows float): the double bound takes them. The lights' deviations
// are summed in float: n lights add ≤ (n − 1)u of the sum, within the slack for up to 32
// lights (batchLighting leaves more to the scalar bound). The randomized test
// (FlatErrorBoundBatchTest.cpp) checks float ≥ roundedUp(double) on extreme inputs.

// The angle asin(s) of a sine s ≥ 0, straight for s ≥ 1: its cosine √((1 − s)(1 + s)),
// accurate relative to itself near 90° (above).
HWY_INLINE AnglesF ofSineF(DF df, VF s) {
  const VF one = hn::Set(df, 1.0f);
  const AnglesF cone{hn::Sqrt(hn::Max((one - s) * (one + s), hn::Zero(df))), s};
  return select(s < one, cone, straight(df));
}

HWY_INLINE VF attenuationF(DF df, const BatchLighting::Source& light, VF distance) {
  using Falloff = BatchLighting::Source::Falloff;
  switch (light.falloff) {
    case Falloff::None:
      return hn::Set(df, 1.0f);
    case Falloff::Constant:
      return hn::Set(df, light.factorF);
    case Falloff::Quadratic: {
      const VF linearTerm =
          light.linearF == 0.0f ? hn::Zero(df) : hn::Set(df, light.linearF) * distance;
      const VF quadraticTerm = light.quadraticF == 0.0f
                                   ? hn::Zero(df)
                                   : hn::Set(df, light.quadraticF) * distance * distance;
      const VF denominator = hn::Set(df, light.constantF) + linearTerm + quadraticTerm;
      return hn::Set(df, 1.0f) /
             hn::Max(denominator, hn::Set(df, static_cast<float>(1.0 / kMaxAttenuation)));
    }
    case Falloff::Distance: {
      const VF reach = hn::Set(df, light.distanceF);
      return hn::IfThenElse(distance <= reach, hn::Set(df, 1.0f), reach / distance);
    }
  }
  return hn::Set(df, 1.0f);
}

HWY_INLINE VF diffuseOfF(DF df, const BatchMaterial& material, VF cosine) {
  const VF lit = hn::Min(hn::Max(cosine, hn::Zero(df)), hn::Set(df, 1.0f));
  if (!material.lerp) return lit;
  return hn::Set(df, material.lerpAmbientF) + hn::Set(df, material.lerpSpanF) * lit;
}

// The double lanes' values of a float group (kDoubleGroups of them, lowest first) in float.
HWY_INLINE VF demoted(const V (&groups)[kDoubleGroups]) {
  const DH dh;
#if HWY_TARGET == HWY_SCALAR
  return hn::DemoteTo(dh, groups[0]);
#else
  return hn::Combine(DF(), hn::DemoteTo(dh, groups[1]), hn::DemoteTo(dh, groups[0]));
#endif
}

// Double masks as a float one of the same lanes (Highway 1.0 has no mask demotion).
HWY_INLINE MF floatMask(D d, const M (&groups)[kDoubleGroups]) {
  V ones[kDoubleGroups];
  for (int g = 0; g < kDoubleGroups; ++g)
    ones[g] = hn::IfThenElseZero(groups[g], hn::Set(d, 1.0));
  return demoted(ones) > hn::Zero(DF());
}

// A float group's polygons as the shade's columns hold them: centers and normals in double,
// kDoubleGroups groups of double lanes.
struct DoubleColumns {
  V center[3][kDoubleGroups], normal[3][kDoubleGroups];
};

// The float bound of a group of lanes (the margin above); NaN where the double bound takes it.
HWY_INLINE VF boundLanesF(D d, DF df, const BatchLighting& lighting, const BatchMaterial& material,
                          const DoubleColumns& columns, VF radius, VF sine, const VF surface[3]) {
  const V zeroD = hn::Zero(d);
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  M boundedD[kDoubleGroups];
  V normal[3][kDoubleGroups];
  for (int g = 0; g < kDoubleGroups; ++g) {
    V nx = columns.normal[0][g], ny = columns.normal[1][g], nz = columns.normal[2][g];
    boundedD[g] = hn::Not(hn::And(hn::And(nx == zeroD, ny == zeroD), nz == zeroD));
    // The side seen, in double as the double bound takes it.
    V vx = hn::Set(d, lighting.viewer.x), vy = hn::Set(d, lighting.viewer.y),
      vz = hn::Set(d, lighting.viewer.z);
    if (!lighting.parallel) {
      vx = hn::Set(d, lighting.eye.x) - columns.center[0][g],
      vy = hn::Set(d, lighting.eye.y) - columns.center[1][g],
      vz = hn::Set(d, lighting.eye.z) - columns.center[2][g];
      const V squared = vx * vx + vy * vy + vz * vz;
      boundedD[g] =
          hn::And(boundedD[g], hn::And(squared > hn::Set(d, 1e-300), squared < hn::Set(d, 1e300)));
    }
    if (lighting.twoSided) {
      const M back = nx * vx + ny * vy + nz * vz < zeroD;
      nx = hn::IfThenElse(back, hn::Neg(nx), nx);
      ny = hn::IfThenElse(back, hn::Neg(ny), ny);
      nz = hn::IfThenElse(back, hn::Neg(nz), nz);
    }
    normal[0][g] = nx, normal[1][g] = ny, normal[2][g] = nz;
  }
  const VF fnx = demoted(normal[0]), fny = demoted(normal[1]), fnz = demoted(normal[2]);
  MF bounded = hn::And(floatMask(d, boundedD), radius <= hn::Set(df, 0x1p50f));
  const AnglesF normalAngle = ofSineF(df, sine);

  VF sum[3] = {zero, zero, zero}, reach[3] = {zero, zero, zero};
  for (const BatchLighting::Source& light : lighting.lights) {
    VF lx = hn::Set(df, light.directionF[0]), ly = hn::Set(df, light.directionF[1]),
       lz = hn::Set(df, light.directionF[2]);
    AnglesF lightAngle{one, zero};
    VF factorLo = one, factorFlat = one, factorHi = one;
    if (!light.directional) {
      V offset[3][kDoubleGroups];
      for (int k = 0; k < 3; ++k)
        for (int g = 0; g < kDoubleGroups; ++g)
          offset[k][g] = hn::Set(d, light.position[k]) - columns.center[k][g];
      const VF ox = demoted(offset[0]), oy = demoted(offset[1]), oz = demoted(offset[2]);
      const VF squared = ox * ox + oy * oy + oz * oz;
      bounded = hn::And(
          bounded, hn::And(squared >= hn::Set(df, 0x1p-100f), squared <= hn::Set(df, 0x1p100f)));
      const VF distance = hn::Sqrt(squared);
      const VF inverse = one / distance;
      lx = ox * inverse, ly = oy * inverse, lz = oz * inverse;
      lightAngle = ofSineF(df, radius * inverse * hn::Set(df, 1.0f + 0x1p-21f));
      const VF near = hn::Max(zero, distance * hn::Set(df, 1.0f - 0x1p-20f) - radius);
      const VF far = (distance + radius) * hn::Set(df, 1.0f + 0x1p-20f);
      factorLo = attenuationF(df, light, far);
      factorFlat = attenuationF(df, light, distance);
      factorHi = attenuationF(df, light, near);
    }
    const VF cosine = fnx * lx + fny * ly + fnz * lz;
    const VF crossX = fny * lz - fnz * ly, crossY = fnz * lx - fnx * lz,
             crossZ = fnx * ly - fny * lx;
    const AnglesF theta{cosine, hn::Sqrt(crossX * crossX + crossY * crossY + crossZ * crossZ)};
    const auto lit = cosineRange(df, theta, add(df, normalAngle, lightAngle));
    const VF diffuseLo = diffuseOfF(df, material, lit.lo),
             diffuseHi = diffuseOfF(df, material, lit.hi);
    const VF low = hn::Min(diffuseLo, diffuseHi), flat = diffuseOfF(df, material, cosine),
             high = hn::Max(diffuseLo, diffuseHi);
    for (int c = 0; c < 3; ++c) {
      const VF r = hn::Set(df, light.radianceF[c]);
      const VF eLo = r * factorLo, eFlat = r * factorFlat, eHi = r * factorHi;
      const VF hi = eHi * high, f = eFlat * flat, lo = eLo * low;
      sum[c] = sum[c] + hn::Max(hn::Max(hi - f, f - lo), zero);
      reach[c] = reach[c] + eHi;
    }
  }
  const VF kd = hn::Set(df, material.diffuseUp), kappa = hn::Set(df, material.kappa);
  VF largest = zero;
  for (int c = 0; c < 3; ++c) {
    const VF total = hn::Min(kd * surface[c] * (sum[c] + kappa * reach[c]), one);
    largest = c == 0 ? total : hn::Max(largest, total);
  }
  const VF full = hn::Set(df, 255.0f);
  const VF bound = hn::IfThenElse(hn::IsFinite(largest), full * largest, full);
  return hn::IfThenElse(bounded, bound, hn::NaN(df));
}

// The shade phase's columns (ShadeBatch.h) and the centers its lanes divided out, surfaces
// capped to [0, kMaxRadiance], bounds in float lanes (boundLanesF) and as fixed point.
void ShadeColumnsLanes(const BatchLighting& lighting, const BatchMaterial& material,
                       const ShadeBatch& batch, const ShadeBatchCenters& centers,
                       const float* radius, const float* sine, std::size_t count, float* bounds,
                       EstimateBound* fixed) {
  const D d;
  const DF df;
  const hn::Rebind<std::int32_t, DF> di;
  const hn::Rebind<EstimateBound, DF> dq;
  const std::size_t doubleLanes = hn::Lanes(d);
  for (std::size_t lane = 0; lane < count; lane += hn::Lanes(df)) {
    DoubleColumns columns;
    VF surface[3];
    for (int k = 0; k < 3; ++k) {
      for (int g = 0; g < kDoubleGroups; ++g) {
        columns.center[k][g] = hn::Load(d, centers.xyz[k] + lane + g * doubleLanes);
        columns.normal[k][g] = hn::Load(d, batch.normal[k] + lane + g * doubleLanes);
      }
      surface[k] = hn::Min(hn::Max(hn::LoadU(df, batch.color[k] + lane), hn::Zero(df)),
                           hn::Set(df, static_cast<float>(kMaxRadiance)));
    }
    const VF up = boundLanesF(d, df, lighting, material, columns, hn::LoadU(df, radius + lane),
                              hn::LoadU(df, sine + lane), surface);
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

// Whether every lane of [0, count) has its bound from the float lanes: a normal (radius ≥ 0)
// and a bound that is not NaN (ShadeBoundCollector::bound's fast path).
bool AllFromLanes(const float* radius, const float* bounds, std::size_t count) {
  const hn::ScalableTag<float> df;
  const std::size_t lanes = hn::Lanes(df);
  std::size_t lane = 0;
  for (; lane + lanes <= count; lane += lanes) {
    const auto r = hn::LoadU(df, radius + lane), b = hn::LoadU(df, bounds + lane);
    if (!hn::AllTrue(df, hn::And(r >= hn::Zero(df), b == b))) return false;
  }
  for (; lane < count; ++lane)
    if (!(radius[lane] >= 0.0f) || std::isnan(bounds[lane])) return false;
  return true;
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
HWY_EXPORT(AllFromLanes);

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

float boundOneColumn(const BatchLighting& lighting, const BatchMaterial& material,
                     const glm::dvec3& center, const glm::dvec3& normal, const Color& surface,
                     float radius, float sine) {
  ShadeBatch batch;
  ShadeBatchCenters centers;
  alignas(64) float radii[kShadeBatchSize] = {radius};
  alignas(64) float sines[kShadeBatchSize] = {sine};
  for (int k = 0; k < 3; ++k) {
    centers.xyz[k][0] = center[k];
    batch.normal[k][0] = normal[k];
    batch.color[k][0] = surface[k];
  }
  batch.count = 1;
  alignas(64) float bounds[kShadeBatchSize];
  alignas(64) EstimateBound fixed[kShadeBatchSize];
  boundShadeColumns(lighting, material, batch, centers, radii, sines, bounds, fixed);
  return bounds[0];
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
    if (allFromLanes(batch.count)) {
      storeLanes(batch.count);
      return;
    }
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

// Whether every lane's bound came out of the float lanes (AllFromLanes).
bool ShadeBoundCollector::allFromLanes(std::size_t count) const {
  return HWY_DYNAMIC_DISPATCH(AllFromLanes)(radius_, lanes_, count);
}

// The lanes' bounds stored by polygon id, in a loop with no test per lane (the saving
// measured in bench/estimate-cost.md; the hook's arrays are read into locals once).
void ShadeBoundCollector::storeLanes(std::size_t count) {
  float* const bounds = hook_->bounds + first_;
  EstimateBound* const fixedBounds = hook_->fixedBounds + first_;
  for (std::size_t lane = 0; lane < count; ++lane) {
    const std::size_t polygon = polygons_[lane];
    bounds[polygon] = lanes_[lane];
    fixedBounds[polygon] = fixed_[lane];
  }
}

namespace {
// Whether a coefficient is one the float lanes take: 0, or in [2^-60, 2^20] (their margin
// assumes normal floats and no overflow of a2·d², FlatErrorBoundBatch.cpp's comment).
bool inFloatRange(double coefficient) {
  return coefficient == 0.0 || (coefficient >= 0x1p-60 && coefficient <= 0x1p20);
}

// Sets the falloff; false when the float lanes do not take it.
bool setFalloff(BatchLighting::Source& source, const Attenuation& attenuation) {
  using Falloff = BatchLighting::Source::Falloff;
  return std::visit(Overloaded{
                        [&](const NoAttenuation&) {
                          source.falloff = Falloff::None;
                          return true;
                        },
                        [&](const QuadraticAttenuation& q) {
                          if (q.linear == 0.0 && q.quadratic == 0.0) {  // distances here are ≥ 0
                            source.falloff = Falloff::Constant;
                            source.factor = attenuationFactor(q, 0.0);
                            source.factorF = static_cast<float>(source.factor);
                            return true;
                          }
                          source.falloff = Falloff::Quadratic;
                          source.constant = q.constant;
                          source.linear = q.linear;
                          source.quadratic = q.quadratic;
                          source.constantF = static_cast<float>(q.constant);
                          source.linearF = static_cast<float>(q.linear);
                          source.quadraticF = static_cast<float>(q.quadratic);
                          return inFloatRange(q.constant) && inFloatRange(q.linear) &&
                                 inFloatRange(q.quadratic);
                        },
                        [&](const FalloffDistanceAttenuation& f) {
                          source.falloff = Falloff::Distance;
                          source.distance = f.distance;
                          source.distanceF = static_cast<float>(f.distance);
                          return f.distance >= 0x1p-60 && f.distance <= 0x1p60;
                        },
                    },
                    attenuation);
}
}  // namespace

std::optional<BatchMaterial> batchMaterial(const PreparedMaterial& material) {
  if (material.specular > 0.0) return std::nullopt;
  BatchMaterial batch{material.diffuse, material.material.diffuseModel != DiffuseModel::Lambert,
                      material.lerpAmbient, material.lerpFull};
  // The float lanes' margin (FlatErrorBoundBatch.cpp) assumes Kd ≥ 0 and diffuse values ≥ 0.
  if (!(batch.diffuse >= 0.0) || !(batch.diffuse <= kMaxRadiance)) return std::nullopt;
  if (batch.lerp && !(batch.lerpAmbient >= 0.0 && batch.lerpFull >= 0.0)) return std::nullopt;
  batch.diffuseUp = roundedUp(roundedUp(batch.diffuse) * (1.0 + 0x1p-20));
  batch.lerpAmbientF = static_cast<float>(batch.lerpAmbient);
  batch.lerpSpanF = static_cast<float>(batch.lerpFull - batch.lerpAmbient);
  const double reach = batch.lerp ? std::max({1.0, batch.lerpAmbient, batch.lerpFull,
                                              std::abs(batch.lerpFull - batch.lerpAmbient)})
                                  : 1.0;
  if (!(reach <= 0x1p40)) return std::nullopt;
  batch.kappa = roundedUp(0x1p-16 * reach);
  return batch;
}

std::optional<BatchLighting> batchLighting(const LightSet& lights, const Camera& camera,
                                           bool twoSidedLighting) {
  // The float lanes' margin is per light; summing n lights' deviations in float adds up to
  // (n − 1)u of the sum, which the slack above (56u a light) covers to ~57 lights. More go to
  // the scalar bound (the double lanes' bytes all the same).
  constexpr std::size_t kMaxBatchLights = 32;
  if (lights.lights.size() > kMaxBatchLights) return std::nullopt;
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
      for (int k = 0; k < 3; ++k)
        source.directionF[k] = static_cast<float>(source.position[k]);
    } else {
      const PointLight& point = std::get<PointLight>(light);
      source.position = point.position;
      source.radiance = boundRadianceOf(point.color, point.intensity);
      if (!setFalloff(source, point.attenuation)) return std::nullopt;
    }
    for (int k = 0; k < 3; ++k)
      source.radianceF[k] = static_cast<float>(source.radiance[k]);
    lighting.lights.push_back(source);
  }
  return lighting;
}

}  // namespace facet::detail
#endif  // HWY_ONCE
