#include "Rasterizer.h"

#include <algorithm>
#include <atomic>
#include <limits>

#include "Assert.h"
#include "facet/Conventions.h"
#include "facet/Framebuffer.h"

namespace facet::detail {
namespace {

constexpr std::int64_t kHalfPixel = kSubpixelScale / 2;
constexpr std::int32_t kBackgroundPolygon = Framebuffer::kBackgroundId;

// floor(value / 256) and ceil(value / 256) for any sign (C++20 >> is arithmetic).
std::int64_t floorToPixel(std::int64_t value) {
  return value >> kSubpixelBits;
}
std::int64_t ceilToPixel(std::int64_t value) {
  return -((-value) >> kSubpixelBits);
}

// One edge's function, stepped exactly in integers.
struct Edge {
  std::int64_t stepX;  // change per pixel to the right
  std::int64_t stepY;  // change per pixel up
  std::int64_t value;  // biased value at the first sample
  bool biased;         // value is the edge function − 1 (not a top-left edge)

  Edge(const WindowVertex& p, const WindowVertex& q, std::int64_t sampleX, std::int64_t sampleY) {
    const std::int64_t dx = q.x - p.x;
    const std::int64_t dy = q.y - p.y;
    stepX = -dy * kSubpixelScale;
    stepY = dx * kSubpixelScale;
    // Samples exactly on a non-top-left edge are outside: bias them to −1.
    biased = !(dy < 0 || (dy == 0 && dx < 0));
    value = dx * (sampleY - p.y) - dy * (sampleX - p.x) - (biased ? 1 : 0);
  }
};

// The depth key's plane over the window, in double: key = key0 + perX·(X − x0) + perY·(Y − y0),
// with X, Y in fine units (1/kResidueScale of a grid step). It goes through the vertices'
// unsnapped positions (snapped + residue): snapping moves a vertex by up to 1/512 pixel, and
// on a steep surface that moves its key by more than the gap between two surfaces 1e-6 of
// their distance apart. A triangle that snapping made much larger than it is (a sliver, whose
// unsnapped plane is ill-conditioned) keeps the snapped positions.
class DepthPlane {
 public:
  DepthPlane(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
             std::int64_t snappedArea) {
    Fine pa = fine(a, true), pb = fine(b, true), pc = fine(c, true);
    double area = doubleArea(pa, pb, pc);
    if (!(area >= 0.5 * static_cast<double>(snappedArea) * kResidueScale * kResidueScale)) {
      pa = fine(a, false), pb = fine(b, false), pc = fine(c, false);
      area = doubleArea(pa, pb, pc);
    }
    const double dk1 = static_cast<double>(b.depth) - a.depth;
    const double dk2 = static_cast<double>(c.depth) - a.depth;
    key0_ = a.depth;
    x0_ = pa.x, y0_ = pa.y;
    perX_ = (dk1 * (pc.y - pa.y) - dk2 * (pb.y - pa.y)) / area;
    perY_ = (dk2 * (pb.x - pa.x) - dk1 * (pc.x - pa.x)) / area;
  }
  // At a sample given in grid units (kSubpixelBits).
  double at(std::int64_t sampleX, std::int64_t sampleY) const {
    return key0_ + perX_ * (static_cast<double>(sampleX) * kResidueScale - x0_) +
           perY_ * (static_cast<double>(sampleY) * kResidueScale - y0_);
  }
  double perPixelX() const { return perX_ * kSubpixelScale * kResidueScale; }

 private:
  struct Fine {
    double x, y;
  };
  static Fine fine(const WindowVertex& v, bool unsnapped) {
    return {static_cast<double>(v.x) * kResidueScale + (unsnapped ? v.residueX : 0),
            static_cast<double>(v.y) * kResidueScale + (unsnapped ? v.residueY : 0)};
  }
  static double doubleArea(const Fine& a, const Fine& b, const Fine& c) {
    return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  }
  double key0_, x0_, y0_, perX_, perY_;
};

// Rounds an interpolated depth key to float once; finite, so that no key ties with the
// background (−∞) or becomes NaN.
float toDepthKey(double key) {
  constexpr double kLargest = std::numeric_limits<float>::max();
  return static_cast<float>(std::clamp(key, -kLargest, kLargest));
}

// Writes one fragment if it passes the depth test: strictly nearer (a larger key), so an
// exact tie keeps the polygon drawn first.
template <DepthMode kMode>
void writeFragment(std::size_t i, float depth, std::int32_t polygonId, const Planes& planes,
                   PaintCounts& counts) {
  if (kMode == DepthMode::Overwrite || depth > planes.depth[i]) {
    counts.covered += planes.polygonId[i] == kBackgroundPolygon;
    planes.depth[i] = depth;
    planes.polygonId[i] = polygonId;
    ++counts.written;
    // Tiles sharing a polygon may race to store the same 1: relaxed atomics make it benign.
    std::atomic_ref<std::uint8_t> shown(planes.shown[static_cast<std::size_t>(polygonId)]);
    if (shown.load(std::memory_order_relaxed) == 0) shown.store(1, std::memory_order_relaxed);
  }
}

// Most triangles of a dense mesh have a single sample in their bounding box: test it
// exactly, skipping the edge walker's set-up. Same coverage decision (the same biased edge
// functions) and the same depth plane.
template <DepthMode kMode>
void paintSingleSample(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                       std::int64_t area, int x, int y, std::int32_t polygonId,
                       const Planes& planes, PaintCounts& counts) {
  const std::int64_t sampleX = std::int64_t{x} * kSubpixelScale + kHalfPixel;
  const std::int64_t sampleY = std::int64_t{y} * kSubpixelScale + kHalfPixel;
  const Edge e0(b, c, sampleX, sampleY), e1(c, a, sampleX, sampleY), e2(a, b, sampleX, sampleY);
  if ((e0.value | e1.value | e2.value) < 0) return;
  const double key = DepthPlane(a, b, c, area).at(sampleX, sampleY);
  writeFragment<kMode>(static_cast<std::size_t>(y) * planes.width + x, toDepthKey(key), polygonId,
                       planes, counts);
}

}  // namespace

PixelBounds samplesInBoundingBox(const WindowVertex& a, const WindowVertex& b,
                                 const WindowVertex& c, const PixelBounds& clip) {
  const std::int64_t minX = std::min({a.x, b.x, c.x}), maxX = std::max({a.x, b.x, c.x});
  const std::int64_t minY = std::min({a.y, b.y, c.y}), maxY = std::max({a.y, b.y, c.y});
  // Smallest px with px·256 + 128 ≥ minX, largest with px·256 + 128 ≤ maxX.
  return {static_cast<int>(std::max<std::int64_t>(ceilToPixel(minX - kHalfPixel), clip.x0)),
          static_cast<int>(std::max<std::int64_t>(ceilToPixel(minY - kHalfPixel), clip.y0)),
          static_cast<int>(std::min<std::int64_t>(floorToPixel(maxX - kHalfPixel), clip.x1)),
          static_cast<int>(std::min<std::int64_t>(floorToPixel(maxY - kHalfPixel), clip.y1))};
}

bool coversAnySample(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                     const PixelBounds& bounds) {
  const int width = bounds.x1 - bounds.x0 + 1, height = bounds.y1 - bounds.y0 + 1;
  if (width * height > 4) return true;
  const std::int64_t sampleX = std::int64_t{bounds.x0} * kSubpixelScale + kHalfPixel;
  const std::int64_t sampleY = std::int64_t{bounds.y0} * kSubpixelScale + kHalfPixel;
  const Edge e0(b, c, sampleX, sampleY), e1(c, a, sampleX, sampleY), e2(a, b, sampleX, sampleY);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::int64_t w0 = e0.value + x * e0.stepX + y * e0.stepY;
      const std::int64_t w1 = e1.value + x * e1.stepX + y * e1.stepY;
      const std::int64_t w2 = e2.value + x * e2.stepX + y * e2.stepY;
      if ((w0 | w1 | w2) >= 0) return true;
    }
  }
  return false;
}

template <DepthMode kMode>
void paintTriangle(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                   std::int32_t polygonId, const PixelBounds& tile, const Planes& planes,
                   PaintCounts& counts) {
  const std::int64_t area = doubleSignedArea(a, b, c);
  FACET_ASSERT(area > 0);
  const PixelBounds box = samplesInBoundingBox(a, b, c, tile);
  if (box.empty()) return;
  if (box.x0 == box.x1 && box.y0 == box.y1) {
    paintSingleSample<kMode>(a, b, c, area, box.x0, box.y0, polygonId, planes, counts);
    return;
  }

  const std::int64_t sampleX = std::int64_t{box.x0} * kSubpixelScale + kHalfPixel;
  const std::int64_t sampleY = std::int64_t{box.y0} * kSubpixelScale + kHalfPixel;
  Edge e0(b, c, sampleX, sampleY);  // opposite a
  Edge e1(c, a, sampleX, sampleY);  // opposite b
  Edge e2(a, b, sampleX, sampleY);  // opposite c

  // The depth key is affine in window x, y. It is stepped in double and rounded to float
  // once per fragment: stepping in float would add a rounding per pixel, enough to tie
  // surfaces 1e-6 apart.
  const DepthPlane depth(a, b, c, area);
  const double keyPerPixel = depth.perPixelX();

  for (int y = box.y0; y <= box.y1; ++y) {
    std::int64_t w0 = e0.value, w1 = e1.value, w2 = e2.value;
    double key = depth.at(sampleX, sampleY + std::int64_t{y - box.y0} * kSubpixelScale);
    const std::size_t row = static_cast<std::size_t>(y) * planes.width;
    for (int x = box.x0; x <= box.x1; ++x) {
      if ((w0 | w1 | w2) >= 0)
        writeFragment<kMode>(row + x, toDepthKey(key), polygonId, planes, counts);
      w0 += e0.stepX;
      w1 += e1.stepX;
      w2 += e2.stepX;
      key += keyPerPixel;
    }
    e0.value += e0.stepY;
    e1.value += e1.stepY;
    e2.value += e2.stepY;
  }
}

template void paintTriangle<DepthMode::Test>(const WindowVertex&, const WindowVertex&,
                                             const WindowVertex&, std::int32_t, const PixelBounds&,
                                             const Planes&, PaintCounts&);
template void paintTriangle<DepthMode::Overwrite>(const WindowVertex&, const WindowVertex&,
                                                  const WindowVertex&, std::int32_t,
                                                  const PixelBounds&, const Planes&, PaintCounts&);

}  // namespace facet::detail
