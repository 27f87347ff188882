#include "HiddenBlocks.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "HiddenBlockCorners.h"
#include "facet/Conventions.h"

namespace facet::detail {

// The steps refer to HiddenBlocks.h's proof.
bool HiddenBlockTest::hidden(const Box& box) const {
  if (box.empty()) return false;
  // Step 2: every point of the box inside the clip volume, so no triangle is clipped, and
  // every distance d > 0 (FrameTransform::boxInsideClipVolume); the corners' window bounds
  // and distances, all eight in SIMD lanes (HiddenBlockCorners.h: the bits of
  // FrameTransform's corner by corner, on every instruction set).
  BlockCorners corners;
  if (!corners_(constants_, box, corners)) return false;
  std::int64_t x0 = corners.x0, y0 = corners.y0, x1 = corners.x1, y1 = corners.y1;
  // The corners' largest |coordinate − eye|: each is one of the box's six differences.
  const glm::dvec3 low = glm::abs(box.low - constants_.eye);
  const glm::dvec3 high = glm::abs(box.high - constants_.eye);
  const double largestOffset = std::max({0.0, low.x, low.y, low.z, high.x, high.y, high.z});
  // Step 4: outward by two grid steps (each snapped vertex lies within 1/2 step and the
  // rounding of the corners' images).
  constexpr std::int64_t kMargin = 2;
  constexpr std::int64_t kHalf = kSubpixelScale / 2;
  x0 -= kMargin, y0 -= kMargin, x1 += kMargin, y1 += kMargin;
  // Pixel centers at p·scale + half inside [x0, x1].
  const auto firstCenter = [](std::int64_t g) {
    const std::int64_t t = g - kHalf;
    return t >= 0 ? (t + kSubpixelScale - 1) / kSubpixelScale : -((-t) / kSubpixelScale);
  };
  const auto lastCenter = [](std::int64_t g) {
    const std::int64_t t = g - kHalf;
    return t >= 0 ? t / kSubpixelScale : -((-t + kSubpixelScale - 1) / kSubpixelScale);
  };
  const std::int64_t px0 = std::max<std::int64_t>(firstCenter(x0), viewport_.x0);
  const std::int64_t px1 = std::min<std::int64_t>(lastCenter(x1), viewport_.x1);
  const std::int64_t py0 = std::max<std::int64_t>(firstCenter(y0), viewport_.y0);
  const std::int64_t py1 = std::min<std::int64_t>(lastCenter(y1), viewport_.y1);
  if (px0 > px1 || py0 > py1) return false;
  const double bound = nearestVertexKeyBound(corners.nearest, corners.farthest, largestOffset);
  // Step 5: the float the vertex key rounds to is at most the blocks' least key F_min
  // (rounding is monotone) when F_min >= bound; a tie keeps the front face.
  return front_.noneNearerThan(
      {static_cast<int>(px0), static_cast<int>(py0), static_cast<int>(px1), static_cast<int>(py1)},
      bound);
}

// Step 3: a bound on the key FrameTransform::toWindow gives any point of the box, from its
// corners' computed distances. A distance d = −back·(p − eye) is computed with an error of at
// most (γ₃ + u(1 + γ₃))·Σ|back_i|·|p_i − eye_i| ≤ 9u·`largestOffset` (u = 2^-53, |back| = 1,
// |p_i − eye_i| at most the corners' largest for p in the box: it is convex in p): η =
// 1e-14·largestOffset bounds it with room. The exact distance is affine in p, so its least
// over the box is at a corner: every vertex's computed distance is at least the corners'
// least computed one less 2η.
double HiddenBlockTest::nearestVertexKeyBound(double nearestDistance, double farthestDistance,
                                              double largestOffset) const {
  const double eta = 1e-14 * largestOffset;
  const double least = nearestDistance - 2.0 * eta;
  if (!(least > 0.0)) return std::numeric_limits<double>::infinity();
  if (!constants_.parallel) {
    // key = near·(1·(1/d)): two roundings up at most (1 + u)² over near/least; this
    // division and product round by less than the 1e-14 added.
    return constants_.near / least * (1.0 + 1e-14);
  }
  // key = (near·1 − d)·1: one rounding, at most u·(|near| + |d|) with d ≤ the corners'
  // largest computed distance + 2η.
  const double most = farthestDistance + 2.0 * eta;
  return (constants_.near - least) +
         1e-14 * (std::abs(constants_.near) + std::abs(least) + std::abs(most));
}

namespace {
bool hiddenBlocksSetTo(const char* setting) {
  const char* value = std::getenv("FACET_HIDDEN_BLOCKS");
  return value != nullptr && std::strcmp(value, setting) == 0;
}
const bool coneOnly = hiddenBlocksSetTo("cone");
std::atomic<bool> blocksOn{!hiddenBlocksSetTo("0")};

struct DebugCounts {
  std::atomic<std::size_t> blocks{0}, hidden{0}, polygons{0}, hiddenPolygons{0};
  std::atomic<std::size_t> coneCertain{0}, coneCertainHidden{0}, coneCertainHiddenPolygons{0};
  std::atomic<std::size_t> deferredWhole{0}, deferredWholePolygons{0};
  std::atomic<std::size_t> runs{0}, hiddenRuns{0}, runPolygons{0}, hiddenRunPolygons{0};
  std::atomic<std::size_t> waitingBlocks{0}, waitingBlocksKept{0};
  std::atomic<std::size_t> wholeTested{0}, wholeKept{0};
  std::atomic<bool> on{std::getenv("FACET_HIDDEN_BLOCKS_DEBUG") != nullptr};
  bool print = on;
  ~DebugCounts() {
    if (print)
      std::fprintf(stderr,
                   "hidden blocks %zu of %zu, polygons %zu of %zu; cone-certain blocks %zu, "
                   "hidden %zu (polygons %zu)\n",
                   hidden.load(), blocks.load(), hiddenPolygons.load(), polygons.load(),
                   coneCertain.load(), coneCertainHidden.load(), coneCertainHiddenPolygons.load());
    if (print)
      std::fprintf(stderr,
                   "hidden runs %zu of %zu, polygons %zu of %zu; blocks whose points waited %zu, "
                   "kept %zu\n",
                   hiddenRuns.load(), runs.load(), hiddenRunPolygons.load(), runPolygons.load(),
                   waitingBlocks.load(), waitingBlocksKept.load());
    if (print)
      std::fprintf(
          stderr, "blocks deferred whole %zu (polygons %zu); tested as one entry %zu, kept %zu\n",
          deferredWhole.load(), deferredWholePolygons.load(), wholeTested.load(), wholeKept.load());
  }
} debugCounts;
}  // namespace

void enableHiddenBlocks(bool on) {
  blocksOn = on;
}

bool hiddenBlocksEnabled() {
  return blocksOn;
}

bool hiddenBlocksConeOnly() {
  return coneOnly;
}

void countHiddenBlocks(bool on) {
  debugCounts.blocks = debugCounts.hidden = debugCounts.polygons = 0;
  debugCounts.hiddenPolygons = 0;
  debugCounts.coneCertain = debugCounts.coneCertainHidden = 0;
  debugCounts.coneCertainHiddenPolygons = 0;
  debugCounts.deferredWhole = debugCounts.deferredWholePolygons = 0;
  debugCounts.runs = debugCounts.hiddenRuns = debugCounts.runPolygons = 0;
  debugCounts.hiddenRunPolygons = 0;
  debugCounts.waitingBlocks = debugCounts.waitingBlocksKept = 0;
  debugCounts.wholeTested = debugCounts.wholeKept = 0;
  debugCounts.on = on;
}

bool countingHiddenBlocks() {
  return debugCounts.on;
}

HiddenBlockCounts hiddenBlockCounts() {
  return {debugCounts.blocks,
          debugCounts.hidden,
          debugCounts.polygons,
          debugCounts.hiddenPolygons,
          debugCounts.coneCertain,
          debugCounts.coneCertainHidden,
          debugCounts.coneCertainHiddenPolygons,
          debugCounts.deferredWhole,
          debugCounts.deferredWholePolygons,
          debugCounts.runs,
          debugCounts.hiddenRuns,
          debugCounts.runPolygons,
          debugCounts.hiddenRunPolygons,
          debugCounts.waitingBlocks,
          debugCounts.waitingBlocksKept,
          debugCounts.wholeTested,
          debugCounts.wholeKept};
}

void hiddenRunDebug(std::size_t runs, std::size_t hiddenRuns, std::size_t polygons,
                    std::size_t hiddenPolygons) {
  if (!debugCounts.on) return;
  debugCounts.runs += runs;
  debugCounts.hiddenRuns += hiddenRuns;
  debugCounts.runPolygons += polygons;
  debugCounts.hiddenRunPolygons += hiddenPolygons;
}

void waitingBlocksDebug(std::size_t waiting, std::size_t kept) {
  if (!debugCounts.on) return;
  debugCounts.waitingBlocks += waiting;
  debugCounts.waitingBlocksKept += kept;
}

void deferredWholeDebug(std::size_t polygons) {
  if (!debugCounts.on) return;
  ++debugCounts.deferredWhole;
  debugCounts.deferredWholePolygons += polygons;
}

void hiddenBlockDebug(bool hidden, bool coneCertain, std::size_t polygons, bool whole) {
  if (!debugCounts.on) return;
  ++debugCounts.blocks;
  if (whole) {
    ++debugCounts.wholeTested;
    if (!hidden) ++debugCounts.wholeKept;
  }
  debugCounts.polygons += polygons;
  if (hidden) {
    ++debugCounts.hidden;
    debugCounts.hiddenPolygons += polygons;
  }
  if (coneCertain) {
    ++debugCounts.coneCertain;
    if (hidden) {
      ++debugCounts.coneCertainHidden;
      debugCounts.coneCertainHiddenPolygons += polygons;
    }
  }
}

}  // namespace facet::detail
