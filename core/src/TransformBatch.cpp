// TransformBatch.h: FrameTransform::project (FrameTransform.h) in SIMD lanes, compiled once per
// instruction set by Highway's foreach_target (this file includes itself) and dispatched at
// run time. Every operation below is project()'s operation on the same double operands in
// the same order (glm's dot products add (x + y) + z, and (x + y) + (z + w) for four terms);
// IEEE addition, multiplication and division are correctly rounded on every instruction set,
// and the file is compiled without contraction into fused multiply-adds (core/CMakeLists.txt),
// so a lane gives project()'s bytes. Comparisons take project()'s branches as masks; the one
// branch that changes the arithmetic, the rescaling of points beyond kLargeCoordinate from the
// eye, sends the lanes' whole group to project() itself. A NaN coordinate usually does not
// (x86's max returns its second operand for a NaN): its lane is computed here and, as in
// project(), its non-finite clip point makes it an outside vertex with kNonFinite.

#include <bit>
#include <cstdint>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "TransformBatch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "TransformBatch.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;
using DI = hn::Rebind<std::int32_t, D>;
using DU = hn::Rebind<std::uint32_t, D>;
using DF = hn::Rebind<float, D>;

// ProjectionConstants in every lane.
struct Constants {
  V eye[3], right[3], up[3], back[3], clipX[4], clipY[4];
  V near, far, halfWidth, halfHeight, guardX, guardY;
  bool parallel;

  Constants(D d, const ProjectionConstants& c) : parallel(c.parallel) {
    for (int k = 0; k < 3; ++k) {
      eye[k] = hn::Set(d, c.eye[k]), right[k] = hn::Set(d, c.right[k]);
      up[k] = hn::Set(d, c.up[k]), back[k] = hn::Set(d, c.back[k]);
    }
    for (int k = 0; k < 4; ++k)
      clipX[k] = hn::Set(d, c.clipX[k]), clipY[k] = hn::Set(d, c.clipY[k]);
    near = hn::Set(d, c.near), far = hn::Set(d, c.far);
    halfWidth = hn::Set(d, c.halfWidth), halfHeight = hn::Set(d, c.halfHeight);
    guardX = hn::Set(d, c.guardX), guardY = hn::Set(d, c.guardY);
  }
};

// Points i .. i + lanes − 1 as doubles (a float converts exactly).
HWY_INLINE void loadPoints(D d, const double* xyz, std::size_t i, V (&p)[3]) {
  hn::LoadInterleaved3(d, xyz + 3 * i, p[0], p[1], p[2]);
}
HWY_INLINE void loadPoints(D d, const float* xyz, std::size_t i, V (&p)[3]) {
  const DF df;
  hn::Vec<DF> x, y, z;
  hn::LoadInterleaved3(df, xyz + 3 * i, x, y, z);
  p[0] = hn::PromoteTo(d, x), p[1] = hn::PromoteTo(d, y), p[2] = hn::PromoteTo(d, z);
}

HWY_INLINE V dot3(const V (&a)[3], const V (&b)[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// clampToGuard, NaN to the upper bound.
HWY_INLINE V clampToGuard(V ndc, V guard) {
  return hn::IfThenElse(ndc < guard, hn::IfThenElse(ndc > hn::Neg(guard), ndc, hn::Neg(guard)),
                        guard);
}

HWY_INLINE V roundToNearest(D d, V x) {
  const V shift = hn::Set(d, 6755399441055744.0);  // 1.5 · 2^52, as FrameTransform.h
  return (x + shift) - shift;
}

// Window x or y (snapped, in fixed point) and the residue, as toWindow computes them.
struct Snapped {
  V fixed, residue;
};
HWY_INLINE Snapped snap(D d, V clip, V inverseW, V guard, V half) {
  const V window = (clampToGuard(clip * inverseW, guard) + hn::Set(d, 1.0)) * half;
  const V fixed = window * hn::Set(d, kSubpixelScale);
  const V snapped = roundToNearest(d, fixed);
  const V residue = roundToNearest(d, (fixed - snapped) * hn::Set(d, kResidueScale));
  return {snapped, hn::Min(hn::Max(residue, hn::Set(d, -127.0)), hn::Set(d, 127.0))};
}

// The bit `code` where `m` holds, as a double (outcodes are sums of distinct bits).
HWY_INLINE V bitWhere(D d, M m, std::uint32_t code) {
  return hn::IfThenElseZero(m, hn::Set(d, static_cast<double>(code)));
}

// One group of lanes whose points are all within kLargeCoordinate of the eye (h = 1): stores
// their vertices and returns their outcodes.
HWY_INLINE hn::Vec<DI> projectLanes(D d, const Constants& k, const V (&relative)[3],
                                    WindowVertex* vertices) {
  // toClip with h = 1: clip x = (cx0·vx + cx1·vy) + (cx2·vz + cx3·1).
  const V view[3] = {dot3(k.right, relative), dot3(k.up, relative), dot3(k.back, relative)};
  const V x = (k.clipX[0] * view[0] + k.clipX[1] * view[1]) + (k.clipX[2] * view[2] + k.clipX[3]);
  const V y = (k.clipY[0] * view[0] + k.clipY[1] * view[1]) + (k.clipY[2] * view[2] + k.clipY[3]);
  const V depth = hn::Neg(view[2]);

  // outcode
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const M finite = hn::And(hn::And(hn::IsFinite(x), hn::IsFinite(y)), hn::IsFinite(depth));
  const V w = k.parallel ? one : depth;
  const V gx = k.guardX * w, gy = k.guardY * w;
  const V planes =
      bitWhere(d, hn::Or(depth - k.near < zero, hn::Not(w > zero)), kBeyondNear) +
      bitWhere(d, k.far - depth < zero, kBeyondFar) + bitWhere(d, gx + x < zero, kBeyondLeft) +
      bitWhere(d, gx - x < zero, kBeyondRight) + bitWhere(d, gy + y < zero, kBeyondBottom) +
      bitWhere(d, gy - y < zero, kBeyondTop);
  const V code = hn::IfThenElse(finite, planes, hn::Set(d, static_cast<double>(kNonFinite)));
  const M inside = code == zero;

  // toWindow; lanes not inside get project()'s outside vertex: zeros, the background key.
  const V inverseW = one / w;
  const Snapped sx = snap(d, x, inverseW, k.guardX, k.halfWidth);
  const Snapped sy = snap(d, y, inverseW, k.guardY, k.halfHeight);
  const V key = k.parallel ? (k.near - depth) * inverseW : k.near * inverseW;
  const V largest = hn::Set(d, std::numeric_limits<float>::max());
  const V clamped = hn::IfThenElse(
      key < largest, hn::IfThenElse(key > hn::Neg(largest), key, hn::Neg(largest)), largest);

  // Lanes not inside are zeroed before they narrow (a conversion out of range saturates on
  // some targets, is undefined in C++); their key is set as bits (Highway's SCALAR target
  // narrows −∞ to −FLT_MAX).
  const DI di;
  const DU du;
  const auto narrow = [&](V v) {
    return hn::BitCast(du, hn::DemoteTo(di, hn::IfThenElseZero(inside, v)));
  };
  const auto byte = [&](V v) { return hn::And(narrow(v), hn::Set(du, 0xFF)); };
  const hn::Vec<DI> codes = hn::DemoteTo(di, code);
  const hn::Vec<DU> last =
      hn::Or(hn::BitCast(du, codes),
             hn::Or(hn::ShiftLeft<16>(byte(sx.residue)), hn::ShiftLeft<24>(byte(sy.residue))));
  const hn::Vec<DU> keyBits =
      hn::IfThenElse(hn::BitCast(du, codes) == hn::Zero(du),
                     hn::BitCast(du, hn::DemoteTo(DF(), hn::IfThenElseZero(inside, clamped))),
                     hn::Set(du, std::bit_cast<std::uint32_t>(kBackgroundDepthKey)));
  hn::StoreInterleaved4(narrow(sx.fixed), narrow(sy.fixed), keyBits, last, du,
                        reinterpret_cast<std::uint32_t*>(vertices));
  return codes;
}

template <class Scalar>
std::uint32_t projectTyped(const FrameTransform& transform, const Scalar* xyz, std::size_t count,
                           WindowVertex* vertices) {
  const D d;
  const std::size_t lanes = hn::Lanes(d);
  const Constants k(d, transform.constants());
  const V large = hn::Set(d, kLargeCoordinate);
  hn::Vec<DI> codes = hn::Zero(DI());
  std::uint32_t any = 0;
  const auto projectOne = [&](std::size_t i) {
    const glm::dvec3 point(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    vertices[i] = transform.project(point);
    any |= vertices[i].outcode;
  };
  // The points and vertices kPrefetchBytes ahead, asked for a lane group at a time (one line
  // of each at least every 64 bytes read or written): a run of needed points starts cold after
  // a frame that evicted them, before the hardware's stream prefetcher has seen it. Addresses
  // as integers: they may lie past the arrays' ends, where a prefetch does not fault.
  constexpr std::uintptr_t kPrefetchBytes = 1024;
  const std::uintptr_t pointBytes = 3 * sizeof(Scalar) * lanes;
  const std::uintptr_t vertexBytes = sizeof(WindowVertex) * lanes;
  std::uintptr_t pointAhead = reinterpret_cast<std::uintptr_t>(xyz) + kPrefetchBytes;
  std::uintptr_t vertexAhead = reinterpret_cast<std::uintptr_t>(vertices) + kPrefetchBytes;
  std::size_t i = 0;
  for (; i + lanes <= count; i += lanes) {
    for (std::uintptr_t b = 0; b < pointBytes; b += 64)
      __builtin_prefetch(reinterpret_cast<const void*>(pointAhead + b));
    for (std::uintptr_t b = 0; b < vertexBytes; b += 64)
      __builtin_prefetch(reinterpret_cast<const void*>(vertexAhead + b), 1);
    pointAhead += pointBytes, vertexAhead += vertexBytes;
    V relative[3];
    loadPoints(d, xyz, i, relative);
    for (int c = 0; c < 3; ++c)
      relative[c] = relative[c] - k.eye[c];
    const V largest =
        hn::Max(hn::Max(hn::Abs(relative[0]), hn::Abs(relative[1])), hn::Abs(relative[2]));
    if (hn::AllTrue(d, largest <= large)) [[likely]] {
      codes = hn::Or(codes, projectLanes(d, k, relative, vertices + i));
    } else {
      for (std::size_t j = i; j < i + lanes; ++j)
        projectOne(j);
    }
  }
  for (; i < count; ++i)
    projectOne(i);
  HWY_ALIGN std::int32_t laneCodes[hn::MaxLanes(DI())];
  hn::Store(codes, DI(), laneCodes);
  for (std::size_t lane = 0; lane < lanes; ++lane)
    any |= static_cast<std::uint32_t>(laneCodes[lane]);
  return any;
}

std::uint32_t ProjectFloatPoints(const FrameTransform& transform, const float* xyz,
                                 std::size_t count, WindowVertex* vertices) {
  return projectTyped(transform, xyz, count, vertices);
}
std::uint32_t ProjectDoublePoints(const FrameTransform& transform, const double* xyz,
                                  std::size_t count, WindowVertex* vertices) {
  return projectTyped(transform, xyz, count, vertices);
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {

HWY_EXPORT(ProjectFloatPoints);
HWY_EXPORT(ProjectDoublePoints);

std::uint32_t projectPoints(const FrameTransform& transform, const float* xyz, std::size_t count,
                            WindowVertex* vertices) {
  return HWY_DYNAMIC_DISPATCH(ProjectFloatPoints)(transform, xyz, count, vertices);
}
std::uint32_t projectPoints(const FrameTransform& transform, const double* xyz, std::size_t count,
                            WindowVertex* vertices) {
  return HWY_DYNAMIC_DISPATCH(ProjectDoublePoints)(transform, xyz, count, vertices);
}

WindowVertex projectPoint(const FrameTransform& transform, const glm::dvec3& world) {
  return transform.project(world);
}

}  // namespace facet::detail
#endif  // HWY_ONCE
