#include "HiddenBlocks.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "facet/Conventions.h"

namespace facet::detail {

bool HiddenBlockTest::hidden(const Box& box) const {
  if (box.empty()) return false;
  ClipPoint corners[8];
  if (!transform_.boxInsideClipVolume(box, corners)) return false;
  std::int64_t x0 = std::numeric_limits<std::int64_t>::max(), y0 = x0;
  std::int64_t x1 = std::numeric_limits<std::int64_t>::min(), y1 = x1;
  double nearest = -std::numeric_limits<double>::infinity();
  for (const ClipPoint& corner : corners) {
    const WindowVertex v = transform_.toWindow(corner);
    x0 = std::min<std::int64_t>(x0, v.x);
    x1 = std::max<std::int64_t>(x1, v.x);
    y0 = std::min<std::int64_t>(y0, v.y);
    y1 = std::max<std::int64_t>(y1, v.y);
    nearest = std::max(nearest, static_cast<double>(v.depth));
  }
  // Outward by two grid steps (snapping and the corners' own rounding).
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
  const float farthest = front_.over(
      {static_cast<int>(px0), static_cast<int>(py0), static_cast<int>(px1), static_cast<int>(py1)});
  // A relative 1e-6 above the nearest corner's key (NOT a bound: the header).
  return static_cast<double>(farthest) >= nearest + 1e-6 * std::abs(nearest);
}

namespace {
bool hiddenBlocksSetTo(const char* setting) {
  const char* value = std::getenv("FACET_HIDDEN_BLOCKS");
  return value != nullptr && std::strcmp(value, setting) == 0;
}
const bool coneOnly = hiddenBlocksSetTo("cone");
std::atomic<bool> blocksOn{hiddenBlocksSetTo("1") || coneOnly};

struct DebugCounts {
  std::atomic<std::size_t> blocks{0}, hidden{0}, polygons{0}, hiddenPolygons{0};
  std::atomic<std::size_t> coneCertain{0}, coneCertainHidden{0}, coneCertainHiddenPolygons{0};
  std::atomic<bool> on{std::getenv("FACET_HIDDEN_BLOCKS_DEBUG") != nullptr};
  bool print = on;
  ~DebugCounts() {
    if (print)
      std::fprintf(stderr,
                   "hidden blocks %zu of %zu, polygons %zu of %zu; cone-certain blocks %zu, "
                   "hidden %zu (polygons %zu)\n",
                   hidden.load(), blocks.load(), hiddenPolygons.load(), polygons.load(),
                   coneCertain.load(), coneCertainHidden.load(), coneCertainHiddenPolygons.load());
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
          debugCounts.coneCertainHiddenPolygons};
}

void hiddenBlockDebug(bool hidden, bool coneCertain, std::size_t polygons) {
  if (!debugCounts.on) return;
  ++debugCounts.blocks;
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
