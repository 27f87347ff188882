#include "RasterTriangle.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iterator>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

#include "Assert.h"
#include "facet/Conventions.h"

namespace facet::detail {
namespace {

constexpr std::int64_t kHalfPixel = kSubpixelScale / 2;

// One edge's function, stepped exactly in integers.
struct Edge {
  std::int64_t stepX;  // change per pixel to the right
  std::int64_t stepY;  // change per pixel up
  std::int64_t value;  // biased value at the first sample
  bool biased;         // value is the edge function − 1 (not a top-left edge)

  [[gnu::always_inline]] Edge(const WindowVertex& p, const WindowVertex& q, std::int64_t sampleX,
                              std::int64_t sampleY) {
    const std::int64_t dx = q.x - p.x;
    const std::int64_t dy = q.y - p.y;
    stepX = -dy * kSubpixelScale;
    stepY = dx * kSubpixelScale;
    // Samples exactly on a non-top-left edge are outside: bias them to −1.
    biased = !(dy < 0 || (dy == 0 && dx < 0));
    value = dx * (sampleY - p.y) - dy * (sampleX - p.x) - (biased ? 1 : 0);
  }
  std::int64_t unbiased(std::int64_t biasedValue) const { return biasedValue + (biased ? 1 : 0); }
};

// Window positions in fine units: 1/kResidueScale of a grid step.
struct FinePoint {
  double x, y;
};
FinePoint finePoint(const WindowVertex& v, bool unsnapped) {
  // Exact integers below 2^32: one conversion each.
  return {static_cast<double>(std::int64_t{v.x} * kResidueScale + (unsnapped ? v.residueX : 0)),
          static_cast<double>(std::int64_t{v.y} * kResidueScale + (unsnapped ? v.residueY : 0))};
}
FinePoint finePoint(std::int64_t gridX, std::int64_t gridY) {
  return {static_cast<double>(gridX) * kResidueScale, static_cast<double>(gridY) * kResidueScale};
}
double edgeFunction(const FinePoint& p, const FinePoint& q, const FinePoint& s) {
  return (q.x - p.x) * (s.y - p.y) - (q.y - p.y) * (s.x - p.x);
}

// refine()'s bounds for the polygon-boundary edges of a triangle, grid units², by edge (opposite
// corner i; `never` for a diagonal). Out of line, and returned by value: a member function
// there, or inlined, cost the closed path (which never calls it) 55 instructions a triangle
// at 20k (the depth plane's object kept in memory, or registers spilled).
struct InsideBounds {
  std::int64_t edge[3];
};
[[gnu::noinline]] InsideBounds surelyInsideBounds(const WindowVertex& a, const WindowVertex& b,
                                                  const WindowVertex& c, EdgeMask boundary,
                                                  std::int64_t never) {
  const GridBox extent = gridBoxOf(a, b, c);
  const std::int64_t box = std::int64_t{extent.x1} - extent.x0 + extent.y1 - extent.y0;
  const WindowVertex* ends[3][2] = {{&b, &c}, {&c, &a}, {&a, &b}};
  InsideBounds bounds;
  for (int i = 0; i < 3; ++i) {
    const std::int64_t dx = ends[i][1]->x - ends[i][0]->x, dy = ends[i][1]->y - ends[i][0]->y;
    bounds.edge[i] =
        ((boundary >> i) & 1u) ? (std::abs(dx) + std::abs(dy) + 1) / 2 + box + 2 : never;
  }
  return bounds;
}

// The depth keys of one triangle. Coverage is decided on the snapped vertices (exact, VTK's
// 1/256 pixel); keys come from the plane through the unsnapped ones (snapped + residue):
// snapping moves a vertex by up to 1/512 pixel, which on a steep surface moves its key by
// more than the gap between two surfaces 1e-6 of their distance apart. A sample that only
// the snapped triangle covers, beyond one of its polygon-boundary edges (within 1/512 pixel
// of it), takes the snapped plane's key instead: there, the unsnapped planes of a front and
// a back face meeting at a silhouette have already crossed, while the snapped ones keep the
// front face in front, as culling would. Beyond a diagonal the unsnapped plane goes on: the
// triangle on the other side is in the same plane; so it does everywhere for a mesh whose
// back faces are skipped (Setup.cpp passes no boundary edges then): no fold can form.
//
// Keys are barycentric interpolations, key = a + (dk1·λb + dk2·λc)/area, with the λ the
// edge functions at the sample (snapped or unsnapped), in double.
class TriangleDepth {
 public:
  [[gnu::always_inline]] TriangleDepth(const WindowVertex& a, const WindowVertex& b,
                                       const WindowVertex& c, std::int64_t snappedArea,
                                       EdgeMask boundary)
      : key0_(a.depth),
        dk1_(static_cast<double>(b.depth) - a.depth),
        dk2_(static_cast<double>(c.depth) - a.depth),
        nearest_(nearestWrittenKey(a, b, c, boundary)),
        snappedArea_(static_cast<double>(snappedArea)),
        boundary_(boundary),
        fa_(finePoint(a, true)),
        fb_(finePoint(b, true)),
        fc_(finePoint(c, true)) {
    // Turned over by snapping (a sliver): the snapped plane everywhere.
    const double fineArea = edgeFunction(fa_, fb_, fc_);
    unsnapped_ = fineArea > 0.0;
    inverseFineArea_ = unsnapped_ ? 1.0 / fineArea : 0.0;
  }
  // The key of one covered sample, given its snapped edge values (unbiased); never nearer
  // than nearestWrittenKey (+∞ for a triangle not clamped: the min changes nothing, and it
  // is only asked near boundary edges and for single samples, beside a division).
  double keyAt(std::int64_t sampleX, std::int64_t sampleY, const std::int64_t (&snapped)[3]) const {
    if (unsnapped_) {
      const FinePoint s = finePoint(sampleX, sampleY);
      const double fine[3] = {edgeFunction(fb_, fc_, s), edgeFunction(fc_, fa_, s),
                              edgeFunction(fa_, fb_, s)};
      if (!beyondBoundary(fine))
        return std::min(interpolate(fine[1], fine[2], inverseFineArea_), nearest_);
    }
    return std::min(interpolate(static_cast<double>(snapped[1]), static_cast<double>(snapped[2]),
                                1.0 / snappedArea_),
                    nearest_);
  }

  // For many samples: the key stepped along a row, keyAt() near boundary edges only.
  [[gnu::always_inline]] void prepareRows(const WindowVertex& a, const WindowVertex& b,
                                          const WindowVertex& c) {
    const FinePoint pa = unsnapped_ ? fa_ : finePoint(a, false);
    const FinePoint pb = unsnapped_ ? fb_ : finePoint(b, false);
    const FinePoint pc = unsnapped_ ? fc_ : finePoint(c, false);
    const double inverse = unsnapped_ ? inverseFineArea_ : 1.0 / (snappedArea_ * kFinePerGrid2);
    x0_ = pa.x, y0_ = pa.y;
    perX_ = (dk1_ * (pc.y - pa.y) - dk2_ * (pb.y - pa.y)) * inverse;
    perY_ = (dk2_ * (pb.x - pa.x) - dk1_ * (pc.x - pa.x)) * inverse;
    // Without boundary edges refine() is never asked (paint() steps the keys alone).
    if (unsnapped_ && boundary_ != 0) {
      const InsideBounds bounds = surelyInsideBounds(a, b, c, boundary_, kNever);
      std::copy(std::begin(bounds.edge), std::end(bounds.edge), sureInside_);
    }
  }
  double at(std::int64_t sampleX, std::int64_t sampleY) const {
    const FinePoint s = finePoint(sampleX, sampleY);
    return key0_ + perX_ * (s.x - x0_) + perY_ * (s.y - y0_);
  }
  double perPixelX() const { return perX_ * kSubpixelScale * kResidueScale; }
  // After prepareRows: the plane as a SmallTriangle steps it from sample (sampleX, sampleY).
  void stepsFrom(std::int64_t sampleX, std::int64_t sampleY, SmallTriangle& small) const {
    const FinePoint s = finePoint(sampleX, sampleY);
    small.firstKey = key0_ + perX_ * (s.x - x0_);
    small.keyPerFine = perY_;
    small.keyPerPixel = perPixelX();
    small.firstRowFine = static_cast<std::int32_t>(s.y - y0_);  // exact (SmallTriangle)
  }
  // After prepareRows: bounds on every key at(), refine() and keyAt() give for a sample of
  // the snapped triangle in a box `extent` pixels across. The vertices' keys, widened by the
  // plane's change over one grid step (a sample of the snapped triangle is within half a
  // step of the unsnapped one in each axis, and the unsnapped plane goes on that far beyond
  // it; the snapped plane only interpolates), and by 1e-9 of the magnitudes involved for the
  // rounding of the interpolation and the stepping in double (below 1e-14 of them).
  void keyRange(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, int extent,
                double& lowest, double& highest) const {
    const double slope = std::abs(perX_) + std::abs(perY_);
    const double largest = std::max({std::abs(a.depth), std::abs(b.depth), std::abs(c.depth)});
    const double rounding = 1e-9 * (largest + slope * extent * kSubpixelScale * kResidueScale);
    const double slack = slope * kResidueScale + rounding;
    lowest = std::min({a.depth, b.depth, c.depth}) - slack;
    highest = std::max({a.depth, b.depth, c.depth}) + slack;
  }
  // keyAt(sample), given at(sample) and the sample's unbiased snapped edge values (kClamp: the
  // stepped key clamped as keyAt clamps, for a clamped triangle, kClampedEdges; painters with
  // boundary edges write only refine()'s keys). A
  // snapped edge value of at least sureInside_ (grid units²) means the sample is inside the
  // unsnapped edge too: residues below 1/2 change (q − p) × (s − p) by at most
  // ½(|dx| + |dy|) + |s − p|₁ + 1, and s stays in the triangle's bounding box. Far from the
  // edges (the common case) three comparisons decide.
  template <bool kClamp>
  double refine(double key, std::int64_t sampleX, std::int64_t sampleY,
                const std::int64_t (&snapped)[3]) const {
    if (takesSteppedKey(snapped)) {
      return kClamp ? std::min(key, nearest_) : key;
    }
    return keyAt(sampleX, sampleY, snapped);
  }
  // refine()'s test: the sample (its unbiased snapped edge values) is surely inside every
  // boundary edge, and takes the stepped key (clamped, kClamp).
  bool takesSteppedKey(const std::int64_t (&snapped)[3]) const {
    return snapped[0] >= sureInside_[0] && snapped[1] >= sureInside_[1] &&
           snapped[2] >= sureInside_[2];
  }
  // Whether the keys come from the unsnapped plane (not turned over by snapping): refine()
  // bounds the samples near the boundary edges then, and only then.
  bool unsnapped() const { return unsnapped_; }
  // refine()'s test in the walker's terms: the least biased value (Edge::value, `biased` as
  // Edge's) of edge k's function at which a sample is surely inside it (kNever: always).
  std::int64_t sureInsideBiased(int k, bool biased) const {
    return sureInside_[k] == kNever ? kNever : sureInside_[k] - (biased ? 1 : 0);
  }
  // refine()'s key for a sample surely inside every edge.
  template <bool kClamp>
  double keyInside(double key) const {
    return kClamp ? std::min(key, nearest_) : key;
  }

 private:
  static constexpr double kFinePerGrid2 = double{kResidueScale} * kResidueScale;
  static constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::min();

  double interpolate(double weightB, double weightC, double inverseArea) const {
    return key0_ + (dk1_ * weightB + dk2_ * weightC) * inverseArea;
  }
  bool isBoundary(int edge) const { return (boundary_ >> edge) & 1u; }
  bool beyondBoundary(const double (&fine)[3]) const {
    return (isBoundary(0) && fine[0] < 0.0) || (isBoundary(1) && fine[1] < 0.0) ||
           (isBoundary(2) && fine[2] < 0.0);
  }
  double key0_, dk1_, dk2_;
  double nearest_;  // nearestWrittenKey
  double snappedArea_, inverseFineArea_ = 0.0;
  EdgeMask boundary_;
  bool unsnapped_ = false;
  FinePoint fa_, fb_, fc_;
  double x0_ = 0.0, y0_ = 0.0, perX_ = 0.0, perY_ = 0.0;
  std::int64_t sureInside_[3] = {kNever, kNever, kNever};  // diagonals: always
};

// TriangleDepth::refine()'s key for a sample near a boundary edge (one refine() does not give
// the stepped key), given its snapped edge values (unbiased): keyAt of the triangle's depth,
// set up again. Out of line and from the vertices, so that the walker's loop over the samples
// far from the edges keeps its registers and its TriangleDepth stays out of memory (a member
// function called there costs every triangle the object's stores, the closed path's too).
[[gnu::noinline]] double keyNearEdge(const WindowVertex& a, const WindowVertex& b,
                                     const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                                     std::int64_t sampleX, std::int64_t sampleY,
                                     std::int64_t snapped0, std::int64_t snapped1,
                                     std::int64_t snapped2) {
  const std::int64_t snapped[3] = {snapped0, snapped1, snapped2};
  return TriangleDepth(a, b, c, area, boundary).keyAt(sampleX, sampleY, snapped);
}

// Most triangles of a dense mesh have a single sample in their bounding box: test it
// exactly, skipping the edge walker's set-up. Same coverage decision (the same biased edge
// functions) and the same depth plane.
template <DepthMode kMode>
void paintSingleSample(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                       std::int64_t area, EdgeMask boundary, int x, int y, std::int32_t polygonId,
                       const Planes& planes, PaintCounts& counts) {
  if (const std::optional<float> key = keyOfOnlySample(a, b, c, area, boundary, x, y)) {
    writeFragment<kMode>(static_cast<std::size_t>(y) * planes.width + x, *key, polygonId, planes,
                         counts);
  }
}

// One triangle over one box of samples: its edge functions at the box's first sample and
// its depth plane, then the painting of its rows. Always inlined: with two callers (the
// plain and the coarse-depth paths) GCC 12 left the constructor out of line, a call per
// triangle on the hottest path that cost the raster phase 8 % more instructions on a
// 500k-triangle sphere (bench/full_render_speed.md).
struct BoxRaster {
  [[gnu::always_inline]] BoxRaster(const WindowVertex& a, const WindowVertex& b,
                                   const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                                   const PixelBounds& samples)
      : box(samples),
        sampleX(std::int64_t{samples.x0} * kSubpixelScale + kHalfPixel),
        sampleY(std::int64_t{samples.y0} * kSubpixelScale + kHalfPixel),
        e0(b, c, sampleX, sampleY),  // opposite a
        e1(c, a, sampleX, sampleY),  // opposite b
        e2(a, b, sampleX, sampleY),  // opposite c
        depth(a, b, c, area, boundary) {
    depth.prepareRows(a, b, c);
  }

  // An edge's (biased) function at pixel (x, y): ≥ 0 inside, by the fill rule.
  static std::int64_t at(const Edge& e, std::int64_t dx, std::int64_t dy) {
    return e.value + dx * e.stepX + dy * e.stepY;
  }
  bool covers(int x, int y) const {
    const std::int64_t dx = x - box.x0, dy = y - box.y0;
    return (at(e0, dx, dy) | at(e1, dx, dy) | at(e2, dx, dy)) >= 0;
  }
  // Whether all four corners of the pixels are outside one edge (then all are: the edge's
  // function is affine).
  bool outsideOneEdge(const PixelBounds& p) const {
    for (const Edge* e : {&e0, &e1, &e2}) {
      const std::int64_t x0 = p.x0 - box.x0, x1 = p.x1 - box.x0;
      const std::int64_t y0 = p.y0 - box.y0, y1 = p.y1 - box.y0;
      if ((at(*e, x0, y0) & at(*e, x1, y0) & at(*e, x0, y1) & at(*e, x1, y1)) < 0) return true;
    }
    return false;
  }
  // The pixels inside the triangle among a block's, bit (y − p.y0)·8 + (x − p.x0). The four
  // corners decide a block wholly inside (the triangle is convex) or wholly outside one edge.
  std::uint64_t coverage(const PixelBounds& p) const {
    if (outsideOneEdge(p)) return 0;
    if (covers(p.x0, p.y0) && covers(p.x1, p.y0) && covers(p.x0, p.y1) && covers(p.x1, p.y1)) {
      return ~std::uint64_t{0};
    }
    std::uint64_t mask = 0;
    for (int y = p.y0; y <= p.y1; ++y) {
      for (int x = p.x0; x <= p.x1; ++x) {
        if (covers(x, y)) mask |= std::uint64_t{1} << ((y - p.y0) * 8 + (x - p.x0));
      }
    }
    return mask;
  }

  // The depth key is affine in window x, y. It is stepped in double and rounded to float
  // once per fragment: stepping in float would add a rounding per pixel, enough to tie
  // surfaces 1e-6 apart.
  // (a, b, c and area: the triangle's, as given to the constructor, for keyNearEdge.)
  // kRefineEverySample: refine() asked for every covered sample, as before the unrolled test
  // (paintTriangleRefiningEverySample, the tests' reference for it).
  template <DepthMode kMode, bool kRefineEverySample = false>
  [[gnu::always_inline]] void paint(const WindowVertex& a, const WindowVertex& b,
                                    const WindowVertex& c, std::int64_t area,
                                    std::int32_t polygonId, const Planes& planes,
                                    PaintCounts& counts, EdgeMask boundary) {
    // No polygon-boundary edge (every triangle of a mesh whose back faces are skipped): the
    // stepped key is every sample's (refine() would return it), so no refining per pixel.
    // A clamped triangle (kClampedEdges, a back face with the depth test) clamps each refined
    // key; the others pay nothing for it.
    if (boundary == 0) {
      paintRows<kMode, false, false, kRefineEverySample>(a, b, c, area, boundary, polygonId, planes,
                                                         counts);
    } else if (boundary == kClampedEdges) {
      paintRows<kMode, true, true, kRefineEverySample>(a, b, c, area, boundary, polygonId, planes,
                                                       counts);
    } else {
      paintRows<kMode, true, false, kRefineEverySample>(a, b, c, area, boundary, polygonId, planes,
                                                        counts);
    }
  }
  template <DepthMode kMode, bool kRefine, bool kClamp, bool kRefineEverySample>
  [[gnu::always_inline]] void paintRows(const WindowVertex& a, const WindowVertex& b,
                                        const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                                        std::int32_t polygonId, const Planes& planes,
                                        PaintCounts& counts) {
    const double keyPerPixel = depth.perPixelX();
    // refine()'s test on the biased values themselves (refine() unrolled: the samples surely
    // inside every edge, nearly all, take keyInside; the others keyNearEdge, out of line): the
    // same keys as refine(). At 20k triangles, every face drawn, refine() inlined here cost the
    // front faces ~26 instructions a covered sample (and every triangle the TriangleDepth's
    // stores, the closed path's too, when keyNearEdge was a member function).
    const std::int64_t sure0 = kRefine ? depth.sureInsideBiased(0, e0.biased) : 0;
    const std::int64_t sure1 = kRefine ? depth.sureInsideBiased(1, e1.biased) : 0;
    const std::int64_t sure2 = kRefine ? depth.sureInsideBiased(2, e2.biased) : 0;
    for (int y = box.y0; y <= box.y1; ++y) {
      std::int64_t w0 = e0.value, w1 = e1.value, w2 = e2.value;
      const std::int64_t rowY = sampleY + std::int64_t{y - box.y0} * kSubpixelScale;
      double key = depth.at(sampleX, rowY);
      const std::size_t row = static_cast<std::size_t>(y) * planes.width;
      for (int x = box.x0; x <= box.x1; ++x) {
        if ((w0 | w1 | w2) >= 0) {
          double refined = key;
          if constexpr (kRefine && kRefineEverySample) {
            const std::int64_t columnX = sampleX + std::int64_t{x - box.x0} * kSubpixelScale;
            const std::int64_t snapped[3] = {e0.unbiased(w0), e1.unbiased(w1), e2.unbiased(w2)};
            refined = depth.refine<kClamp>(key, columnX, rowY, snapped);
          } else if constexpr (kRefine) {
            if (w0 >= sure0 && w1 >= sure1 && w2 >= sure2) [[likely]] {
              refined = depth.keyInside<kClamp>(key);
            } else {
              const std::int64_t columnX = sampleX + std::int64_t{x - box.x0} * kSubpixelScale;
              refined = keyNearEdge(a, b, c, area, boundary, columnX, rowY, e0.unbiased(w0),
                                    e1.unbiased(w1), e2.unbiased(w2));
            }
          }
          writeFragment<kMode>(row + x, toDepthKey(refined), polygonId, planes, counts);
        }
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

  PixelBounds box;
  std::int64_t sampleX, sampleY;
  Edge e0, e1, e2;
  TriangleDepth depth;
};

// The small-box path: a box of at most kSmallSide × kSmallSide samples (every triangle of a
// dense mesh the set-up did not bin as a fragment; ~200k a frame of a 500k-triangle sphere,
// 1.5 covered samples each) costs BoxRaster's walk ~550 instructions, nearly all per triangle:
// 64-bit edges stepped sample by sample, the depth plane set up whether or not a sample is
// covered. Here a row of four samples' edge functions is tested at once in 32-bit lanes,
// giving the box's coverage as a mask, bit (y − y0)·kSmallSide + (x − x0); the depth plane is
// set up only when a sample is covered, and only covered samples are visited. The same edge
// functions and fill rule as BoxRaster's Edge, and the same keys: a row's key is stepped from
// its first sample by the same additions as BoxRaster::paintRows, and refined near a polygon
// boundary from the same snapped edge values.
//
// 32-bit lanes are exact when the triangle's bounding box is below kMaxLaneExtent = 2^14 grid
// steps (64 pixels) across in each axis: the lanes' samples lie in the box's rows, and at most
// three pixels (768 steps) right of its first column, so |s − p| < 2^14 + 2^10 in each axis for
// a vertex p, and an edge function |dx·(s.y − p.y) − dy·(s.x − p.x)| + 1 < 2^29.1, with room for
// the step past the last row; int32's bound is 2^31. Wider triangles (clipped by the tile to a
// small box: rare) are walked.
constexpr std::int32_t kMaxLaneExtent = 1 << 14;

// `extent`: the triangle's bounding box; `box`: its samples in the tile.
bool fitsSmallPath(const GridBox& extent, const PixelBounds& box) {
  // Window coordinates are below 2^23 in magnitude (FrameTransform.h): no overflow.
  return box.x1 - box.x0 < kSmallSide && box.y1 - box.y0 < kSmallSide &&
         extent.x1 - extent.x0 < kMaxLaneExtent && extent.y1 - extent.y0 < kMaxLaneExtent;
}

// Four samples of a row, one per lane (GCC and Clang vector extensions: SSE2, on every x86-64).
using RowLanes = std::int32_t __attribute__((vector_size(4 * sizeof(std::int32_t))));

// Bit i set where lane i is negative.
unsigned negativeLanes(RowLanes lanes) {
#if defined(__SSE2__)
  return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(reinterpret_cast<__m128i>(lanes))));
#else
  return (lanes[0] < 0 ? 1u : 0u) | (lanes[1] < 0 ? 2u : 0u) | (lanes[2] < 0 ? 4u : 0u) |
         (lanes[3] < 0 ? 8u : 0u);
#endif
}

// The covered samples of a box of (lastColumn + 1) × (lastRow + 1) samples, at most
// kSmallSide × kSmallSide, bit y·kSmallSide + x, from its three biased edge functions at its
// first sample and their steps (SmallBox; SetupBatch.cpp's BoxCoverage decides the same in
// the set-up's lanes).
[[gnu::always_inline]] inline std::uint32_t smallBoxCoverage(const std::int32_t (&value)[3],
                                                             const std::int32_t (&stepX)[3],
                                                             const std::int32_t (&stepY)[3],
                                                             int lastColumn, int lastRow) {
  RowLanes w[3];
  for (int k = 0; k < 3; ++k)
    w[k] =
        RowLanes{value[k], value[k] + stepX[k], value[k] + 2 * stepX[k], value[k] + 3 * stepX[k]};
  const unsigned columns = (2u << lastColumn) - 1;
  std::uint32_t mask = 0;
  for (int y = 0; y <= lastRow; ++y) {
    // Covered where every biased edge function is ≥ 0: the sign bit of their OR is clear.
    mask |= (~negativeLanes(w[0] | w[1] | w[2]) & columns) << (y * kSmallSide);
    for (int k = 0; k < 3; ++k)
      w[k] += stepY[k];
  }
  return mask;
}

// A triangle over a box of at most kSmallSide × kSmallSide samples that fitsSmallPath: its
// edge functions as BoxRaster's Edge has them, in 32 bits, from vertices taken relative to
// the box's first sample (within the bounding box, so below 2^14 in magnitude).
struct SmallBox {
  [[gnu::always_inline]] SmallBox(const WindowVertex& a, const WindowVertex& b,
                                  const WindowVertex& c, const PixelBounds& samples)
      : box(samples),
        sampleX(samples.x0 * kSubpixelScale + kHalfPixel),
        sampleY(samples.y0 * kSubpixelScale + kHalfPixel) {
    const std::int32_t x[3] = {a.x - sampleX, b.x - sampleX, c.x - sampleX};
    const std::int32_t y[3] = {a.y - sampleY, b.y - sampleY, c.y - sampleY};
    constexpr int kFrom[3] = {1, 2, 0}, kTo[3] = {2, 0, 1};
    for (int k = 0; k < 3; ++k) {  // the edge opposite corner k: b → c, c → a, a → b
      const int p = kFrom[k], q = kTo[k];
      const std::int32_t dx = x[q] - x[p], dy = y[q] - y[p];
      bias[k] = (dy < 0 || (dy == 0 && dx < 0)) ? 0 : 1;
      value[k] = dy * x[p] - dx * y[p] - bias[k];
      stepX[k] = -dy * kSubpixelScale;
      stepY[k] = dx * kSubpixelScale;
    }
  }

  // The covered samples, bit (y − box.y0)·kSmallSide + (x − box.x0).
  [[gnu::always_inline]] std::uint32_t coverage() const {
    return smallBoxCoverage(value, stepX, stepY, box.x1 - box.x0, box.y1 - box.y0);
  }

  // Paints the samples of `mask` (coverage()) with BoxRaster::paintRows<kMode, kRefine, kClamp>'s
  // keys (kRefine: the triangle has polygon-boundary edges; kClamp: it is clamped).
  template <DepthMode kMode, bool kRefine, bool kClamp>
  [[gnu::always_inline]] void paint(const WindowVertex& a, const WindowVertex& b,
                                    const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                                    std::uint32_t mask, std::int32_t polygonId,
                                    const Planes& planes, PaintCounts& counts) const {
    TriangleDepth depth(a, b, c, area, boundary);
    depth.prepareRows(a, b, c);
    const auto rowKey = [&](int y) {
      return depth.at(sampleX, sampleY + std::int64_t{y} * kSubpixelScale);
    };
    const auto refine = [&](double key, int x, int y) {
      if constexpr (!kRefine) return key;
      std::int64_t snapped[3];
      for (int k = 0; k < 3; ++k)
        snapped[k] = value[k] + x * stepX[k] + y * stepY[k] + bias[k];
      return depth.template refine<kClamp>(key, sampleX + std::int64_t{x} * kSubpixelScale,
                                           sampleY + std::int64_t{y} * kSubpixelScale, snapped);
    };
    paintSmallMask<kMode>(mask, box.x0, box.y0, depth.perPixelX(), rowKey, refine, polygonId,
                          planes, counts);
  }

  PixelBounds box;
  std::int32_t sampleX, sampleY;  // the box's first sample, grid units
  // Per edge (opposite a, b, c): its function at the first sample, biased by −1 (bias 1) off
  // the top-left edges, as Edge; its steps to the next sample right and up.
  std::int32_t value[3], stepX[3], stepY[3], bias[3];
};

// Below this many samples in its box a triangle is cheaper to depth-test pixel by pixel than
// to test against the coarse depth first.
constexpr std::size_t kSamplesForCoarseDepth = 16;

// The float nearest a double, rounded outward (up or down), so that bounds stay bounds.
float floatAbove(double key) {
  const float f = toDepthKey(key);
  return f < key ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}
float floatBelow(double key) {
  const float f = toDepthKey(key);
  return f > key ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

// The farthest key in a box of the depth plane, read row by row; once a row holds a key below
// `nearest` (a front face drawn over the background meets −∞ in its first row) the rest is
// not read: the key returned is then below it too, which is all losesEverywhere asks.
[[gnu::always_inline]] inline float farthestKeyDownTo(const PixelBounds& box, const Planes& planes,
                                                      double nearest) {
  float farthest = std::numeric_limits<float>::infinity();
  for (int y = box.y0; y <= box.y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * planes.width - planes.origin;
    for (int x = box.x0; x <= box.x1; ++x)
      farthest = std::min(farthest, planes.depth[row + x]);
    if (!(farthest >= nearest)) break;
  }
  return farthest;
}

// losesEverywhere's bound in the triangle's fine area F (not positive: snapping turned it over,
// never rejected): a key `farthest` no nearer than its largest vertex key `nearest` rejects it
// when (farthest − nearest)·F >= margin (below).
struct RejectMargin {
  double fineArea, margin;
};
[[gnu::always_inline]] inline RejectMargin rejectMarginOf(const WindowVertex& a,
                                                          const WindowVertex& b,
                                                          const WindowVertex& c,
                                                          const PixelBounds& box) {
  const FinePoint pa = finePoint(a, true), pb = finePoint(b, true), pc = finePoint(c, true);
  const double fineArea = edgeFunction(pa, pb, pc);
  if (!(fineArea > 0.0)) return {fineArea, 0.0};
  const int extent = std::max(box.x1 - box.x0, box.y1 - box.y0) + 1;
  const double dk1 = static_cast<double>(b.depth) - a.depth;
  const double dk2 = static_cast<double>(c.depth) - a.depth;
  const double slopeTimesArea = std::abs(dk1 * (pc.y - pa.y) - dk2 * (pb.y - pa.y)) +
                                std::abs(dk2 * (pb.x - pa.x) - dk1 * (pc.x - pa.x));
  const double largest =
      std::max(std::max(std::abs(a.depth), std::abs(b.depth)), std::abs(c.depth));
  const double rounding =
      2e-9 * (largest * fineArea + slopeTimesArea * extent * kSubpixelScale * kResidueScale);
  return {fineArea, slopeTimesArea * kResidueScale + rounding};
}

// losesEverywhere (RasterTriangle.h): keyRange's bound is max(vertex keys) + s·kResidueScale
// + 1e-9·(largest + s·extent·kSubpixelScale·kResidueScale) with s = (|nx| + |ny|)/F the
// unsnapped plane's slope (numerators nx, ny over the fine area F); multiplied by F > 0 it
// needs no division, and its margin doubled covers this test's own rounding. Inlined into
// paintTriangle: out of line, the call cost the 500k every-face raster 4 % more instructions.
//
// With `front` (a back face after the tile's front faces), the blocks' farthest key is tried
// first: it is no farther than the box's (FarthestBlocks), and the test is monotone in it (the
// subtraction and the product by F > 0 round monotonically), so where it rejects, the box's
// keys would too; where it does not, the box's keys decide. The same decision either way.
[[gnu::always_inline]] inline bool losesEverywhereInline(
    const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, const PixelBounds& box,
    const Planes& planes, FarthestBlocks* front = nullptr) {
  const double nearest = std::max(std::max(a.depth, b.depth), c.depth);
  const float blocks = front != nullptr ? front->over(box) : kBackgroundDepthKey;
  const bool fromBlocks = blocks >= nearest;
  float farthest = fromBlocks ? blocks : farthestKeyDownTo(box, planes, nearest);
  if (!(farthest >= nearest)) return false;  // the background (−∞) anywhere: never
  const RejectMargin bound = rejectMarginOf(a, b, c, box);
  if (!(bound.fineArea > 0.0)) return false;
  if ((static_cast<double>(farthest) - nearest) * bound.fineArea >= bound.margin) return true;
  if (!fromBlocks) return false;
  farthest = farthestKeyDownTo(box, planes, nearest);
  return farthest >= nearest &&
         (static_cast<double>(farthest) - nearest) * bound.fineArea >= bound.margin;
}

// Up to this many samples in its box a triangle that may be a back face is tested by
// losesEverywhere before it is set up: reading its box's keys costs less than the set-up and
// the per-sample depth test it may save (a bound of 16 left the back faces of a 20k sphere,
// boxes of more samples, to the walk: core-frame-issue11.md §14). Larger ones meet the coarse
// depth, when it is on.
constexpr std::size_t kSamplesForLosesEverywhere = 256;

// A box of two or more samples, walked row by row (BoxRaster).
template <DepthMode kMode, bool kRejectHidden>
[[gnu::always_inline]] inline void walkBox(const WindowVertex& a, const WindowVertex& b,
                                           const WindowVertex& c, std::int64_t area,
                                           EdgeMask boundary, const PixelBounds& box,
                                           std::int32_t polygonId, const Planes& planes,
                                           PaintCounts& counts, FarthestBlocks* front) {
  if (kRejectHidden && box.area() <= kSamplesForLosesEverywhere &&
      losesEverywhereInline(a, b, c, box, planes, front)) {
    return;
  }
  BoxRaster raster(a, b, c, area, boundary, box);
  raster.paint<kMode>(a, b, c, area, polygonId, planes, counts, boundary);
}

}  // namespace

std::uint32_t samplesNearBoundary(const WindowVertex& a, const WindowVertex& b,
                                  const WindowVertex& c, EdgeMask boundary, const PixelBounds& box,
                                  std::uint32_t coverage) {
  const SmallBox edges(a, b, c, box);
  const InsideBounds bounds = surelyInsideBounds(a, b, c, boundary, 0);
  std::uint32_t near = 0;
  for (int k = 0; k < 3; ++k) {
    if (!((boundary >> k) & 1u)) continue;
    const std::int64_t bound = bounds.edge[k];
    for (std::uint32_t rest = coverage; rest != 0; rest &= rest - 1) {
      const int x = std::countr_zero(rest) % kSmallSide, y = std::countr_zero(rest) / kSmallSide;
      const std::int64_t snapped =
          std::int64_t{edges.value[k]} + x * edges.stepX[k] + y * edges.stepY[k] + edges.bias[k];
      if (snapped < bound) near |= rest & -rest;
    }
  }
  return near;
}

std::optional<SmallTriangle> smallTriangleOf(const WindowVertex& a, const WindowVertex& b,
                                             const WindowVertex& c, EdgeMask boundary,
                                             const PixelBounds& tile, std::int32_t polygonId) {
  const std::int64_t area = doubleSignedArea(a, b, c);
  const GridBox extent = gridBoxOf(a, b, c);
  const PixelBounds box = samplesInGridBox(extent, tile);
  if (area <= 0 || box.empty() || box.area() < 2 || box.area() >= kSmallSide * kSmallSide ||
      !fitsSmallPath(extent, box)) {
    return std::nullopt;
  }
  const SmallBox edges(a, b, c, box);
  const std::uint32_t coverage = edges.coverage();
  // Every covered sample surely inside the boundary edges.
  if (samplesNearBoundary(a, b, c, boundary, box, coverage) != 0) return std::nullopt;
  SmallTriangle small;
  TriangleDepth depth(a, b, c, area, 0);  // the plane without refine(): the same
  depth.prepareRows(a, b, c);
  depth.stepsFrom(edges.sampleX, edges.sampleY, small);
  small.polygon = polygonId;
  small.x0 = static_cast<std::uint16_t>(box.x0);
  small.y0 = static_cast<std::uint16_t>(box.y0);
  small.coverage = static_cast<std::uint16_t>(coverage);
  return small;
}

std::uint32_t keysNearBoundary(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                               EdgeMask boundary, int x0, int y0, std::uint32_t mask,
                               float (&keys)[kSmallSide * kSmallSide]) {
  const std::int64_t area = doubleSignedArea(a, b, c);
  FACET_ASSERT(area > 0);
  const TriangleDepth depth(a, b, c, area, boundary);
  // Turned over by snapping: refine() has no bounds there, every sample takes the stepped key.
  if (!depth.unsnapped()) return 0;
  for (std::uint32_t rest = mask; rest != 0; rest &= rest - 1) {
    const int bit = std::countr_zero(rest);
    const std::int64_t sampleX = std::int64_t{x0 + bit % kSmallSide} * kSubpixelScale + kHalfPixel;
    const std::int64_t sampleY = std::int64_t{y0 + bit / kSmallSide} * kSubpixelScale + kHalfPixel;
    const Edge e0(b, c, sampleX, sampleY), e1(c, a, sampleX, sampleY), e2(a, b, sampleX, sampleY);
    const std::int64_t snapped[3] = {e0.unbiased(e0.value), e1.unbiased(e1.value),
                                     e2.unbiased(e2.value)};
    keys[bit] = toDepthKey(depth.keyAt(sampleX, sampleY, snapped));
  }
  return mask;
}

bool losesEverywhere(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                     const PixelBounds& box, const Planes& planes) {
  return losesEverywhereInline(a, b, c, box, planes);
}

std::optional<float> keyOfOnlySample(const WindowVertex& a, const WindowVertex& b,
                                     const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                                     int x, int y) {
  const std::int64_t sampleX = std::int64_t{x} * kSubpixelScale + kHalfPixel;
  const std::int64_t sampleY = std::int64_t{y} * kSubpixelScale + kHalfPixel;
  const Edge e0(b, c, sampleX, sampleY), e1(c, a, sampleX, sampleY), e2(a, b, sampleX, sampleY);
  if ((e0.value | e1.value | e2.value) < 0) return std::nullopt;
  const std::int64_t snapped[3] = {e0.unbiased(e0.value), e1.unbiased(e1.value),
                                   e2.unbiased(e2.value)};
  return toDepthKey(TriangleDepth(a, b, c, area, boundary).keyAt(sampleX, sampleY, snapped));
}

bool coversAnyOfFewSamples(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                           const PixelBounds& bounds) {
  const int width = bounds.x1 - bounds.x0 + 1, height = bounds.y1 - bounds.y0 + 1;
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

// paintTriangle, and with kSmallBoxes false its reference, paintTriangleWalkingBox.
template <DepthMode kMode, bool kRejectHidden, bool kSmallBoxes>
[[gnu::always_inline]] inline void paintTriangleThrough(
    const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, EdgeMask boundary,
    std::int32_t polygonId, const PixelBounds& tile, const Planes& planes, PaintCounts& counts,
    FarthestBlocks* front = nullptr) {
  static_assert(kMode == DepthMode::Test || !kRejectHidden);
  const std::int64_t area = doubleSignedArea(a, b, c);
  FACET_ASSERT(area > 0);
  const GridBox extent = gridBoxOf(a, b, c);
  const PixelBounds box = samplesInGridBox(extent, tile);
  if (box.empty()) return;
  if (box.x0 == box.x1 && box.y0 == box.y1) {
    paintSingleSample<kMode>(a, b, c, area, boundary, box.x0, box.y0, polygonId, planes, counts);
    return;
  }
  if (kSmallBoxes && fitsSmallPath(extent, box)) {
    // At most 16 keys: reading them costs less than the blocks (500k sphere: +4 M instructions
    // in 4 frames with them).
    if (kRejectHidden && losesEverywhereInline(a, b, c, box, planes)) return;
    const SmallBox small(a, b, c, box);
    if (const std::uint32_t mask = small.coverage()) {
      if (boundary == 0) {
        small.paint<kMode, false, false>(a, b, c, area, boundary, mask, polygonId, planes, counts);
      } else if (boundary == kClampedEdges) {
        small.paint<kMode, true, true>(a, b, c, area, boundary, mask, polygonId, planes, counts);
      } else {
        small.paint<kMode, true, false>(a, b, c, area, boundary, mask, polygonId, planes, counts);
      }
    }
    return;
  }
  walkBox<kMode, kRejectHidden>(a, b, c, area, boundary, box, polygonId, planes, counts, front);
}

template <DepthMode kMode, bool kRejectHidden>
void paintTriangle(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                   EdgeMask boundary, std::int32_t polygonId, const PixelBounds& tile,
                   const Planes& planes, PaintCounts& counts) {
  paintTriangleThrough<kMode, kRejectHidden, true>(a, b, c, boundary, polygonId, tile, planes,
                                                   counts);
}

void paintBackTriangle(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                       EdgeMask boundary, std::int32_t polygonId, const PixelBounds& tile,
                       const Planes& planes, PaintCounts& counts, FarthestBlocks& front) {
  paintTriangleThrough<DepthMode::Test, true, true>(a, b, c, boundary, polygonId, tile, planes,
                                                    counts, &front);
}

template <DepthMode kMode>
void paintTriangleWalkingBox(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                             EdgeMask boundary, std::int32_t polygonId, const PixelBounds& tile,
                             const Planes& planes, PaintCounts& counts) {
  paintTriangleThrough<kMode, false, false>(a, b, c, boundary, polygonId, tile, planes, counts);
}

template <DepthMode kMode>
void paintTriangleRefiningEverySample(const WindowVertex& a, const WindowVertex& b,
                                      const WindowVertex& c, EdgeMask boundary,
                                      std::int32_t polygonId, const PixelBounds& tile,
                                      const Planes& planes, PaintCounts& counts) {
  const std::int64_t area = doubleSignedArea(a, b, c);
  FACET_ASSERT(area > 0);
  const PixelBounds box = samplesInGridBox(gridBoxOf(a, b, c), tile);
  if (box.empty()) return;
  if (box.x0 == box.x1 && box.y0 == box.y1) {
    paintSingleSample<kMode>(a, b, c, area, boundary, box.x0, box.y0, polygonId, planes, counts);
    return;
  }
  BoxRaster raster(a, b, c, area, boundary, box);
  raster.paint<kMode, true>(a, b, c, area, polygonId, planes, counts, boundary);
}

void paintTriangleBehindCoarseDepth(const WindowVertex& a, const WindowVertex& b,
                                    const WindowVertex& c, EdgeMask boundary,
                                    std::int32_t polygonId, const PixelBounds& tile,
                                    const Planes& planes, PaintCounts& counts,
                                    CoarseDepth& coarse) {
  const PixelBounds box = samplesInBoundingBox(a, b, c, tile);
  if (box.area() < kSamplesForCoarseDepth) {
    paintTriangle<DepthMode::Test>(a, b, c, boundary, polygonId, tile, planes, counts);
    return;
  }
  const std::int64_t area = doubleSignedArea(a, b, c);
  BoxRaster raster(a, b, c, area, boundary, box);
  double lowest, highest;
  raster.depth.keyRange(a, b, c, std::max(box.x1 - box.x0, box.y1 - box.y0) + 1, lowest, highest);
  if (coarse.hides(box, floatAbove(highest))) {
    ++counts.hidden;
    return;
  }
  coarse.raise(box, floatBelow(lowest),
               [&](const PixelBounds& pixels) { return raster.coverage(pixels); });
  raster.paint<DepthMode::Test>(a, b, c, area, polygonId, planes, counts, boundary);
}

// Each block's least key, over the tile's pixels only (the planes beyond an image-edge tile's
// pixels are not cleared); a whole block's four rows a lane each where SSE2 is (the least of
// the same keys: they are never NaN, and the tests only compare it).
void FarthestBlocks::measure() {
  measured_ = true;
  const int columns = tile_.x1 - tile_.x0 + 1, rows = tile_.y1 - tile_.y0 + 1;
  for (int by = 0; by * kBlockSize < rows; ++by) {
    const int y0 = tile_.y0 + by * kBlockSize;
    const int y1 = std::min(tile_.y1, y0 + kBlockSize - 1);
    for (int bx = 0; bx * kBlockSize < columns; ++bx) {
      const int x0 = tile_.x0 + bx * kBlockSize;
      const int x1 = std::min(tile_.x1, x0 + kBlockSize - 1);
      // The block's first pixel in row y (planes are indexed y·width + x − origin).
      const auto rowOf = [&](int y) {
        return planes_.depth + (static_cast<std::size_t>(y) * planes_.width + x0 - planes_.origin);
      };
      float farthest = std::numeric_limits<float>::infinity();
#if defined(__SSE2__)
      static_assert(kBlockSize == 4);
      if (x1 - x0 + 1 == kBlockSize && y1 - y0 + 1 == kBlockSize) {
        const __m128 top = _mm_min_ps(_mm_loadu_ps(rowOf(y0)), _mm_loadu_ps(rowOf(y0 + 1)));
        const __m128 bottom = _mm_min_ps(_mm_loadu_ps(rowOf(y0 + 2)), _mm_loadu_ps(rowOf(y0 + 3)));
        __m128 lanes = _mm_min_ps(top, bottom);
        lanes = _mm_min_ps(lanes, _mm_movehl_ps(lanes, lanes));
        lanes = _mm_min_ss(lanes, _mm_shuffle_ps(lanes, lanes, 1));
        farthest_[by * kBlocksPerSide + bx] = _mm_cvtss_f32(lanes);
        continue;
      }
#endif
      for (int y = y0; y <= y1; ++y) {
        const float* row = rowOf(y);
        for (int x = x0; x <= x1; ++x)
          farthest = std::min(farthest, row[x - x0]);
      }
      farthest_[by * kBlocksPerSide + bx] = farthest;
    }
  }
}

CoarseDepth::CoarseDepth(const PixelBounds& tile) : tile_(tile) {
  std::fill(std::begin(blocks_), std::end(blocks_),
            Block{kBackgroundDepthKey, std::numeric_limits<float>::infinity(), 0});
}

PixelBounds CoarseDepth::blockPixels(int bx, int by) const {
  const int x0 = tile_.x0 + bx * kBlockSize, y0 = tile_.y0 + by * kBlockSize;
  return {x0, y0, std::min(tile_.x1, x0 + kBlockSize - 1), std::min(tile_.y1, y0 + kBlockSize - 1)};
}

// The bits of a block's pixels (fewer than 64 where the image ends inside it).
std::uint64_t CoarseDepth::allPixels(const PixelBounds& pixels) {
  const int width = pixels.x1 - pixels.x0 + 1, height = pixels.y1 - pixels.y0 + 1;
  const std::uint64_t row = width == kBlockSize ? 0xffu : (std::uint64_t{1} << width) - 1;
  std::uint64_t all = 0;
  for (int y = 0; y < height; ++y)
    all |= row << (y * kBlockSize);
  return all;
}

bool CoarseDepth::hides(const PixelBounds& box, float nearest) const {
  for (int by = (box.y0 - tile_.y0) / kBlockSize; by <= (box.y1 - tile_.y0) / kBlockSize; ++by) {
    for (int bx = (box.x0 - tile_.x0) / kBlockSize; bx <= (box.x1 - tile_.x0) / kBlockSize; ++bx) {
      if (!(nearest <= blocks_[by * kBlocksPerSide + bx].farthest)) return false;
    }
  }
  return true;
}

void CoarseDepth::cover(Block& block, std::uint64_t all, std::uint64_t mask, float key) {
  if (mask == all) {
    block.farthest = std::max(block.farthest, key);
    return;
  }
  block.layerMask |= mask;
  block.layerKey = std::min(block.layerKey, key);
  if (block.layerMask == all) {
    block.farthest = std::max(block.farthest, block.layerKey);
    block.layerMask = 0;
    block.layerKey = std::numeric_limits<float>::infinity();
  }
}

template <class Coverage>
void CoarseDepth::raise(const PixelBounds& box, float key, const Coverage& coverage) {
  for (int by = (box.y0 - tile_.y0) / kBlockSize; by <= (box.y1 - tile_.y0) / kBlockSize; ++by) {
    for (int bx = (box.x0 - tile_.x0) / kBlockSize; bx <= (box.x1 - tile_.x0) / kBlockSize; ++bx) {
      const PixelBounds pixels = blockPixels(bx, by);
      const std::uint64_t all = allPixels(pixels);
      const std::uint64_t mask = coverage(pixels) & all;
      if (mask != 0) cover(blocks_[by * kBlocksPerSide + bx], all, mask, key);
    }
  }
}

template void paintTriangle<DepthMode::Test, false>(const WindowVertex&, const WindowVertex&,
                                                    const WindowVertex&, EdgeMask, std::int32_t,
                                                    const PixelBounds&, const Planes&,
                                                    PaintCounts&);
template void paintTriangle<DepthMode::Test, true>(const WindowVertex&, const WindowVertex&,
                                                   const WindowVertex&, EdgeMask, std::int32_t,
                                                   const PixelBounds&, const Planes&, PaintCounts&);
template void paintTriangleRefiningEverySample<DepthMode::Test>(const WindowVertex&,
                                                                const WindowVertex&,
                                                                const WindowVertex&, EdgeMask,
                                                                std::int32_t, const PixelBounds&,
                                                                const Planes&, PaintCounts&);
template void paintTriangleRefiningEverySample<DepthMode::Overwrite>(
    const WindowVertex&, const WindowVertex&, const WindowVertex&, EdgeMask, std::int32_t,
    const PixelBounds&, const Planes&, PaintCounts&);
template void paintTriangleWalkingBox<DepthMode::Test>(const WindowVertex&, const WindowVertex&,
                                                       const WindowVertex&, EdgeMask, std::int32_t,
                                                       const PixelBounds&, const Planes&,
                                                       PaintCounts&);
template void paintTriangleWalkingBox<DepthMode::Overwrite>(const WindowVertex&,
                                                            const WindowVertex&,
                                                            const WindowVertex&, EdgeMask,
                                                            std::int32_t, const PixelBounds&,
                                                            const Planes&, PaintCounts&);
template void paintTriangle<DepthMode::Overwrite, false>(const WindowVertex&, const WindowVertex&,
                                                         const WindowVertex&, EdgeMask,
                                                         std::int32_t, const PixelBounds&,
                                                         const Planes&, PaintCounts&);

}  // namespace facet::detail
