// HiddenBlockCorners.h's corners in lanes, compiled once per instruction set by Highway's
// foreach_target (this file includes itself) and dispatched at run time: HiddenBlockTest takes the
// chosen target's function once (blockCornersFunction) and calls it per block.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "HiddenBlockCorners.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <cmath>
#include <cstddef>
#include <limits>

#include "HiddenBlockCorners.h"
#include "SetupBatch.h"
#include "facet/Conventions.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Corner i of the box is Box::corner(i): bit 0 picks x, bit 1 y, bit 2 z from high. Lane
// for lane the operations of FrameTransform::toClip (glm's dot products: (a + b) + c for
// three terms, (a + b) + (c + d) for four; h = 1, so the clip rows' last term is their
// fourth entry times 1), boxInsideClipVolume's test and toWindow's x and y.
bool BlockCornersLanes(const ProjectionConstants& k, const Box& box, BlockCorners& out) {
  // Eye-relative coordinates, each exactly the difference toClip takes for a corner that has
  // it; a box beyond kLargeCoordinate (or NaN) would be scaled there: clipCorners refuses it.
  const double rx0 = box.low.x - k.eye.x, rx1 = box.high.x - k.eye.x;
  const double ry0 = box.low.y - k.eye.y, ry1 = box.high.y - k.eye.y;
  const double rz0 = box.low.z - k.eye.z, rz1 = box.high.z - k.eye.z;
  for (const double r : {rx0, rx1, ry0, ry1, rz0, rz1}) {
    if (!(std::abs(r) <= kLargeCoordinate)) return false;
  }
  const hn::CappedTag<double, 8> d;
  const hn::RebindToSigned<decltype(d)> di;
  using V = hn::Vec<decltype(d)>;
  const std::size_t n = hn::Lanes(d);
  const V one = hn::Set(d, 1.0), margin = hn::Set(d, 1e-9),
          largest = hn::Set(d, std::numeric_limits<double>::max());
  const V nearV = hn::Set(d, k.near), farV = hn::Set(d, k.far);
  const V absNear = hn::Set(d, std::abs(k.near)), absFar = hn::Set(d, std::abs(k.far));
  const V guardX = hn::Set(d, k.guardX), guardY = hn::Set(d, k.guardY);
  const V negGuardX = hn::Set(d, -k.guardX), negGuardY = hn::Set(d, -k.guardY);
  const V halfWidth = hn::Set(d, k.halfWidth), halfHeight = hn::Set(d, k.halfHeight);
  const V scale = hn::Set(d, static_cast<double>(kSubpixelScale));
  const V shift = hn::Set(d, 6755399441055744.0);  // roundToNearest's 1.5 · 2^52
  V least = hn::Set(d, std::numeric_limits<double>::infinity());
  V most = hn::Neg(least);
  V x0 = least, y0 = least, x1 = most, y1 = most;
  bool inside = true;
  for (std::size_t first = 0; first < 8; first += n) {
    const auto corner = hn::Iota(di, static_cast<std::int64_t>(first));
    const auto picks = [&](std::int64_t bit) {
      return hn::RebindMask(d, hn::Ne(hn::And(corner, hn::Set(di, bit)), hn::Zero(di)));
    };
    const V rx = hn::IfThenElse(picks(1), hn::Set(d, rx1), hn::Set(d, rx0));
    const V ry = hn::IfThenElse(picks(2), hn::Set(d, ry1), hn::Set(d, ry0));
    const V rz = hn::IfThenElse(picks(4), hn::Set(d, rz1), hn::Set(d, rz0));
    const auto dot3 = [&](const glm::dvec3& row) {
      return hn::Add(hn::Add(hn::Mul(hn::Set(d, row.x), rx), hn::Mul(hn::Set(d, row.y), ry)),
                     hn::Mul(hn::Set(d, row.z), rz));
    };
    const V vx = dot3(k.right), vy = dot3(k.up), vz = dot3(k.back);
    const auto dot4 = [&](const glm::dvec4& row) {
      return hn::Add(hn::Add(hn::Mul(hn::Set(d, row.x), vx), hn::Mul(hn::Set(d, row.y), vy)),
                     hn::Add(hn::Mul(hn::Set(d, row.z), vz), hn::Mul(hn::Set(d, row.w), one)));
    };
    const V cx = dot4(k.clipX), cy = dot4(k.clipY), cd = hn::Neg(vz);
    // clipCorners: finite (NaN fails every comparison).
    auto ok = hn::And(hn::And(hn::Le(hn::Abs(cx), largest), hn::Le(hn::Abs(cy), largest)),
                      hn::Le(hn::Abs(cd), largest));
    // boxInsideClipVolume's test, w = clipW (h = 1).
    const V w = k.parallel ? one : cd;
    const V sideX = hn::Mul(margin, hn::Add(w, hn::Abs(cx)));
    const V sideY = hn::Mul(margin, hn::Add(w, hn::Abs(cy)));
    const V gx = hn::Mul(guardX, w), gy = hn::Mul(guardY, w);
    ok = hn::And(ok, hn::Gt(w, hn::Zero(d)));
    ok = hn::And(ok, hn::Gt(hn::Sub(cd, nearV), hn::Mul(margin, hn::Add(hn::Abs(cd), absNear))));
    ok = hn::And(ok, hn::Gt(hn::Sub(farV, cd), hn::Mul(margin, hn::Add(hn::Abs(cd), absFar))));
    ok = hn::And(ok, hn::Gt(hn::Add(gx, cx), sideX));
    ok = hn::And(ok, hn::Gt(hn::Sub(gx, cx), sideX));
    ok = hn::And(ok, hn::Gt(hn::Add(gy, cy), sideY));
    ok = hn::And(ok, hn::Gt(hn::Sub(gy, cy), sideY));
    inside = inside && hn::AllTrue(d, ok);
    // toWindow's snapped x and y (clampToGuard of a finite value is its min and max).
    const V inverseW = hn::Div(one, w);
    const auto snapped = [&](V clip, V guard, V negGuard, V half) {
      const V ndc = hn::Min(hn::Max(hn::Mul(clip, inverseW), negGuard), guard);
      const V fixed = hn::Mul(hn::Mul(hn::Add(ndc, one), half), scale);
      return hn::Sub(hn::Add(fixed, shift), shift);
    };
    const V sx = snapped(cx, guardX, negGuardX, halfWidth);
    const V sy = snapped(cy, guardY, negGuardY, halfHeight);
    x0 = hn::Min(x0, sx), x1 = hn::Max(x1, sx);
    y0 = hn::Min(y0, sy), y1 = hn::Max(y1, sy);
    least = hn::Min(least, cd), most = hn::Max(most, cd);
  }
  if (!inside) return false;
  out.x0 = static_cast<std::int32_t>(hn::GetLane(hn::MinOfLanes(d, x0)));
  out.x1 = static_cast<std::int32_t>(hn::GetLane(hn::MaxOfLanes(d, x1)));
  out.y0 = static_cast<std::int32_t>(hn::GetLane(hn::MinOfLanes(d, y0)));
  out.y1 = static_cast<std::int32_t>(hn::GetLane(hn::MaxOfLanes(d, y1)));
  out.nearest = hn::GetLane(hn::MinOfLanes(d, least));
  out.farthest = hn::GetLane(hn::MaxOfLanes(d, most));
  return true;
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {

HWY_EXPORT(BlockCornersLanes);

bool blockCorners(const ProjectionConstants& constants, const Box& box, BlockCorners& corners) {
  return HWY_DYNAMIC_DISPATCH(BlockCornersLanes)(constants, box, corners);
}

BlockCornersFunction blockCornersFunction() {
  chooseSimdTarget();
  return &HWY_DYNAMIC_DISPATCH(BlockCornersLanes);
}

}  // namespace facet::detail
#endif  // HWY_ONCE
