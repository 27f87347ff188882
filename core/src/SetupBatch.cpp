// The batch test of SetupBatch.h, compiled once per instruction set by Highway's
// foreach_target (this file includes itself) and dispatched at run time.
//
// 32-bit arithmetic, exact. A lane is tested only when its triangle's bounding box is less
// than kMaxExtent = 2^14 grid steps (64 pixels) on each side, and coordinates are taken
// relative to its vertex a: every vertex coordinate then is below 2^14 in magnitude, and so
// is every edge's (dx, dy). The samples tested lie in the bounding box, or one pixel (2^8)
// beyond it when the box holds fewer than two pixel centers across; so each product of an
// edge function, (q − p)·(s − p), is below 2^14 · (2^14 + 2^8) < 2^28.1, an edge function
// below 2^29.1 and twice the area below 2^29: far from int32's 2^31. Lanes beyond the bound
// (rare: a dense mesh's triangles are pixels across) have their coordinates zeroed before
// any product and go to the per-triangle path, whose 64-bit arithmetic holds any triangle
// in the guard band.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "SetupBatch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "SetupBatch.h"
#include "facet/Conventions.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<std::int32_t>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

constexpr std::int32_t kMaxExtent = 1 << 14;
constexpr std::int32_t kHalfPixel = kSubpixelScale / 2;

// One directed edge p → q of a counter-clockwise triangle: its function at the first sample,
// biased by −1 unless the edge is a top or left edge (RasterTriangle.h, top-left rule), so
// that a sample is covered when every biased value is ≥ 0; and its steps to the next pixel.
struct EdgeLanes {
  V value, stepX, stepY;
  EdgeLanes(D d, V px, V py, V qx, V qy, V sx, V sy) {
    const V dx = qx - px, dy = qy - py;
    const M topLeft = hn::Or(dy < hn::Zero(d), hn::And(dy == hn::Zero(d), dx < hn::Zero(d)));
    const V bias = hn::IfThenZeroElse(topLeft, hn::Set(d, 1));
    value = dx * (sy - py) - dy * (sx - px) - bias;
    stepX = hn::Zero(d) - hn::ShiftLeft<kSubpixelBits>(dy);
    stepY = hn::ShiftLeft<kSubpixelBits>(dx);
  }
};

// Whether one of the samples (0, 0), (1, 0), (0, 1), (1, 1) pixels from the first is inside
// all three edges, the second column only where `twoColumns`, the second row where `twoRows`.
M coversSample(D d, const EdgeLanes (&e)[3], M twoColumns, M twoRows) {
  const V minusOne = hn::Set(d, -1);  // Highway 1.0 has no integer >=
  const auto inside = [&](V w0, V w1, V w2) { return (w0 | w1 | w2) > minusOne; };
  const M s00 = inside(e[0].value, e[1].value, e[2].value);
  const M s10 = inside(e[0].value + e[0].stepX, e[1].value + e[1].stepX, e[2].value + e[2].stepX);
  const M s01 = inside(e[0].value + e[0].stepY, e[1].value + e[1].stepY, e[2].value + e[2].stepY);
  const M s11 = inside(e[0].value + e[0].stepX + e[0].stepY, e[1].value + e[1].stepX + e[1].stepY,
                       e[2].value + e[2].stepX + e[2].stepY);
  return hn::Or(hn::Or(s00, hn::And(twoColumns, s10)),
                hn::Or(hn::And(twoRows, s01), hn::And(hn::And(twoColumns, twoRows), s11)));
}

// ceil(v / 256) and floor(v / 256): arithmetic shifts (RasterTriangle.cpp, floorToPixel).
V ceilToPixel(D d, V v) {
  return hn::Zero(d) - hn::ShiftRight<kSubpixelBits>(hn::Zero(d) - v);
}
V floorToPixel(V v) {
  return hn::ShiftRight<kSubpixelBits>(v);
}

// Bit l of the result: lane l of the mask.
std::uint32_t laneBits(D d, M mask) {
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, mask, bytes);
  return bytes[0] | std::uint32_t{bytes[1]} << 8;
}

// The verdicts of the lanes from `lane` on (SetupBatch.h), decided as Setup.cpp and
// Binning.cpp decide: culled before zero area, zero area before the pixel-center test, which
// is exact for boxes of at most 2 × 2 pixel centers (samplesInBoundingBox, coversAnySample)
// and left to the per-triangle path for larger ones.
void classifyLanes(D d, const TriangleBatch& batch, std::size_t lane, const PixelBounds& viewport,
                   bool skipBackFaces, BatchVerdicts& verdicts) {
  const V zero = hn::Zero(d);
  const V ax = hn::Load(d, batch.x[0] + lane), ay = hn::Load(d, batch.y[0] + lane);
  const V bx = hn::Load(d, batch.x[1] + lane), by = hn::Load(d, batch.y[1] + lane);
  const V cx = hn::Load(d, batch.x[2] + lane), cy = hn::Load(d, batch.y[2] + lane);
  const V minX = hn::Min(hn::Min(ax, bx), cx), maxX = hn::Max(hn::Max(ax, bx), cx);
  const V minY = hn::Min(hn::Min(ay, by), cy), maxY = hn::Max(hn::Max(ay, by), cy);
  const V limit = hn::Set(d, kMaxExtent);
  const M tested = hn::And(hn::Load(d, batch.tested + lane) != zero,
                           hn::And(maxX - minX < limit, maxY - minY < limit));

  // b and c relative to a; zero in untested lanes, so that no product below can overflow.
  V ux = hn::IfThenElseZero(tested, bx - ax), uy = hn::IfThenElseZero(tested, by - ay);
  V vx = hn::IfThenElseZero(tested, cx - ax), vy = hn::IfThenElseZero(tested, cy - ay);
  const V area = ux * vy - vx * uy;  // doubleSignedArea
  const M clockwise = area < zero;
  const M culled = skipBackFaces ? hn::And(tested, clockwise) : hn::FirstN(d, 0);
  const M zeroArea = hn::And(tested, area == zero);
  // Counter-clockwise, as binning keeps it: b and c trade places.
  const V swappedX = hn::IfThenElse(clockwise, vx, ux),
          swappedY = hn::IfThenElse(clockwise, vy, uy);
  vx = hn::IfThenElse(clockwise, ux, vx), vy = hn::IfThenElse(clockwise, uy, vy);
  ux = swappedX, uy = swappedY;

  // The pixel centers in the box, clipped to the viewport (samplesInBoundingBox).
  const V half = hn::Set(d, kHalfPixel);
  const V x0 = hn::Max(ceilToPixel(d, minX - half), hn::Set(d, viewport.x0));
  const V y0 = hn::Max(ceilToPixel(d, minY - half), hn::Set(d, viewport.y0));
  const V x1 = hn::Min(floorToPixel(maxX - half), hn::Set(d, viewport.x1));
  const V y1 = hn::Min(floorToPixel(maxY - half), hn::Set(d, viewport.y1));
  const M empty = hn::Or(x0 > x1, y0 > y1);
  const V two = hn::Set(d, 2);
  const M small = hn::And(x1 - x0 < two, y1 - y0 < two);  // at most 2 × 2 centers
  const M sampled = hn::AndNot(empty, hn::And(tested, small));

  // The first center, relative to a; zero in lanes not sampled (it may lie far outside
  // their box).
  const V sx = hn::IfThenElseZero(sampled, hn::ShiftLeft<kSubpixelBits>(x0) + half - ax);
  const V sy = hn::IfThenElseZero(sampled, hn::ShiftLeft<kSubpixelBits>(y0) + half - ay);
  const EdgeLanes edges[3] = {EdgeLanes(d, ux, uy, vx, vy, sx, sy),
                              EdgeLanes(d, vx, vy, zero, zero, sx, sy),
                              EdgeLanes(d, zero, zero, ux, uy, sx, sy)};
  const M covers = coversSample(d, edges, x1 > x0, y1 > y0);

  const M live = hn::AndNot(hn::Or(culled, zeroArea), tested);
  const M noSample = hn::And(live, hn::Or(empty, hn::AndNot(covers, sampled)));
  verdicts.culled |= laneBits(d, culled) << lane;
  verdicts.zeroArea |= laneBits(d, zeroArea) << lane;  // never culled: area == 0, not < 0
  verdicts.coversNoSample |= laneBits(d, noSample) << lane;
  verdicts.coversSample |= laneBits(d, hn::And(live, hn::And(sampled, covers))) << lane;
}

BatchVerdicts ClassifyBatch(const TriangleBatch& batch, const PixelBounds& viewport,
                            bool skipBackFaces) {
  const D d;
  BatchVerdicts verdicts;
  for (std::size_t lane = 0; lane < kBatchSize; lane += hn::Lanes(d))
    classifyLanes(d, batch, lane, viewport, skipBackFaces, verdicts);
  verdicts.culledCount = static_cast<int>(hwy::PopCount(verdicts.culled));
  verdicts.zeroAreaCount = static_cast<int>(hwy::PopCount(verdicts.zeroArea));
  verdicts.coversNoSampleCount = static_cast<int>(hwy::PopCount(verdicts.coversNoSample));
  return verdicts;
}

const char* BatchTargetName() {
  return hwy::TargetName(HWY_TARGET);
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <atomic>

namespace facet::detail {

HWY_EXPORT(ClassifyBatch);
HWY_EXPORT(BatchTargetName);

namespace {
std::atomic<bool> batchesOn{true};
}

BatchVerdicts classifyBatch(const TriangleBatch& batch, const PixelBounds& viewport,
                            bool skipBackFaces) {
  return HWY_DYNAMIC_DISPATCH(ClassifyBatch)(batch, viewport, skipBackFaces);
}

std::vector<SimdTarget> simdTargets() {
  std::vector<SimdTarget> targets;
  for (std::int64_t bits : hwy::SupportedAndGeneratedTargets())
    targets.push_back({bits, hwy::TargetName(bits)});
  return targets;
}

void useSimdTarget(std::int64_t target) {
  hwy::SetSupportedTargetsForTest(target);
  hwy::GetChosenTarget().Update(hwy::SupportedTargets());
}

const char* simdTargetInUse() {
  return HWY_DYNAMIC_DISPATCH(BatchTargetName)();
}

void enableSetupBatches(bool on) {
  batchesOn = on;
}

bool setupBatchesEnabled() {
  return batchesOn;
}

}  // namespace facet::detail
#endif  // HWY_ONCE
