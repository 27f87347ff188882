// The batches of SetupBatch.h, compiled once per instruction set by Highway's foreach_target
// (this file includes itself) and dispatched at run time.
//
// Coverage in 32-bit arithmetic, exact. A lane is tested only when its triangle's bounding box
// is less than kMaxExtent = 2^14 grid steps (64 pixels) on each side, and coordinates are
// taken relative to its vertex a: every vertex coordinate then is below 2^14 in magnitude, and
// so is every edge's (dx, dy). The samples tested lie in the bounding box, or at most three
// pixels (3 · 2^8) beyond it (the pixel-center test's steps); so each product of an
// edge function, (q − p)·(s − p), is below 2^14 · (2^14 + 3 · 2^8) < 2^28.3, an edge function
// below 2^29.3 and twice the area below 2^29: far from int32's 2^31. Lanes beyond the bound
// (rare: a dense mesh's triangles are pixels across) have their coordinates zeroed before
// any product and go to the per-triangle path, whose 64-bit arithmetic holds any triangle
// in the guard band.
//
// Depth keys in double lanes, as RasterTriangle.cpp's TriangleDepth computes them: positions
// in fine units (1/kResidueScale of a grid step) relative to vertex a are below 2^22.1, so the
// fine area and edge functions are exact integers below 2^46 whatever the order of their
// operations; the interpolation, which rounds, runs the scalar path's operations in its order.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "SetupBatch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <iterator>
#include <limits>

#include "SetupBatch.h"
#include "facet/Conventions.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<std::int32_t>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

constexpr std::int32_t kMaxExtent = 1 << 14;
constexpr int kTileBits = std::countr_zero(unsigned{TileGrid::kTileSize});
static_assert(TileGrid::kTileSize == 1 << kTileBits);
constexpr std::int32_t kHalfPixel = kSubpixelScale / 2;

// One directed edge p → q of a counter-clockwise triangle: its function at the first sample
// (`exact`) and that biased by −1 unless the edge is a top or left edge (RasterTriangle.h,
// top-left rule), so that a sample is covered when every biased value is ≥ 0; and its steps
// to the next pixel.
struct EdgeLanes {
  V exact, value, stepX, stepY;
  EdgeLanes(D d, V px, V py, V qx, V qy, V sx, V sy) {
    const V dx = qx - px, dy = qy - py;
    const M topLeft = hn::Or(dy < hn::Zero(d), hn::And(dy == hn::Zero(d), dx < hn::Zero(d)));
    exact = dx * (sy - py) - dy * (sx - px);
    value = exact - hn::IfThenZeroElse(topLeft, hn::Set(d, 1));
    stepX = hn::Zero(d) - hn::ShiftLeft<kSubpixelBits>(dy);
    stepY = hn::ShiftLeft<kSubpixelBits>(dx);
  }
};

// The pixel centers of a box of at most 4, from its first: (0, 0), then across a 2 × 2 box
// (1, 0), (0, 1), (1, 1), or along a row or column of up to 4.
struct FewSamples {
  M valid[4];                           // which of the four the box holds
  FewSamples(D d, V width, V height) {  // in centers, less one
    const V one = hn::Set(d, 1), three = hn::Set(d, 3);
    square = hn::And(width == one, height == one);
    wide = width > hn::Zero(d);
    valid[0] = hn::FirstN(d, hn::Lanes(d));
    valid[1] = hn::Or(wide, height > hn::Zero(d));
    valid[2] = hn::Or(square, hn::Or(width > one, height > one));
    valid[3] = hn::Or(square, hn::Or(width == three, height == three));
  }
  // Whether one of them is inside all three edges.
  M covered(D d, const EdgeLanes (&e)[3]) const {
    const V minusOne = hn::Set(d, -1);  // Highway 1.0 has no integer >=
    V at[4][3];
    for (int i = 0; i < 3; ++i) {
      const V along = hn::IfThenElse(wide, e[i].stepX, e[i].stepY);
      at[0][i] = e[i].value;
      at[1][i] = e[i].value + along;
      at[2][i] = hn::IfThenElse(square, e[i].value + e[i].stepY, at[1][i] + along);
      at[3][i] = hn::IfThenElse(square, at[2][i] + e[i].stepX, at[2][i] + along);
    }
    M any = hn::FirstN(d, 0);
    for (int k = 0; k < 4; ++k)
      any = hn::Or(any, hn::And(valid[k], (at[k][0] | at[k][1] | at[k][2]) > minusOne));
    return any;
  }
  M square, wide;
};

// SmallBox::coverage (RasterTriangle.cpp) of boxes of (width + 1) × (height + 1) centers, at
// most 4 × 4: bit y·4 + x where center (x, y) of the box is inside all three edges (their
// biased values, ≥ 0 by the fill rule). The same integers: a sample's edge function is the
// same whatever the origin of the coordinates, and the centers tested lie in the box, where
// the range above holds (the last steps go at most 4 · 2^8 beyond it, into 2^29.3 still).
// `unsure` (kSure): the covered centers where a biased edge value is below sureFrom (a
// center there may not be surely inside a boundary edge: smallTriangleOf). Only the rows and
// columns some lane of `small` has are visited; a center beyond a lane's box is not covered.
template <bool kSure>
struct BoxCoverage {
  V covered, unsure;
  BoxCoverage(D d, M small, const EdgeLanes (&e)[3], V width, V height, const V (&sureFrom)[3]) {
    const int columns = hn::GetLane(hn::MaxOfLanes(d, hn::IfThenElseZero(small, width))) + 1;
    const int rows = hn::GetLane(hn::MaxOfLanes(d, hn::IfThenElseZero(small, height))) + 1;
    V outside = hn::Zero(d), notSure = hn::Zero(d);
    V row[3] = {e[0].value, e[1].value, e[2].value};
    // A bit per center, 1 << (4y + x): doubled a step along the row, not set from the
    // scalar (a shift and a broadcast a center).
    V rowBit = hn::Set(d, 1);
    for (int y = 0; y < rows; ++y) {
      V at[3] = {row[0], row[1], row[2]};
      V bit = rowBit;
      for (int x = 0; x < columns; ++x) {
        // The sign of a value (all ones when negative, by the shift).
        outside = outside | hn::And(hn::ShiftRight<31>(at[0] | at[1] | at[2]), bit);
        if constexpr (kSure) {
          const V margin = (at[0] - sureFrom[0]) | (at[1] - sureFrom[1]) | (at[2] - sureFrom[2]);
          notSure = notSure | hn::And(hn::ShiftRight<31>(margin), bit);
        }
        for (int k = 0; k < 3; ++k)
          at[k] = at[k] + e[k].stepX;
        bit = bit + bit;
      }
      for (int k = 0; k < 3; ++k)
        row[k] = row[k] + e[k].stepY;
      rowBit = hn::ShiftLeft<4>(rowBit);
    }
    // The box's centers: (width + 1) bits in each of (height + 1) rows of 4 (the shift in
    // range in every lane: other lanes' widths may be anything).
    const V zero = hn::Zero(d);
    const V rowBits = (hn::Set(d, 2) << hn::IfThenElseZero(small, width)) - hn::Set(d, 1);
    const V box = rowBits | hn::IfThenElseZero(height > zero, hn::ShiftLeft<4>(rowBits)) |
                  hn::IfThenElseZero(height > hn::Set(d, 1), hn::ShiftLeft<8>(rowBits)) |
                  hn::IfThenElseZero(height > hn::Set(d, 2), hn::ShiftLeft<12>(rowBits));
    covered = hn::AndNot(outside, box);
    unsure = hn::And(notSure, covered);
  }
};

// For a boundary edge p → q: the biased value from which a sample is surely inside it,
// TriangleDepth::refine's bound (surelyInsideBound, RasterTriangle.cpp: the unbiased value
// must reach ⌊(|dx| + |dy| + 1)/2⌋ + extent + 2, extent the width plus the height of the
// bounding box; below 2^16) less the edge's bias. A biased value less this is below 2^30.
V sureFrom(D d, V dx, V dy, V extent, const EdgeLanes& edge) {
  const V bound =
      hn::ShiftRight<1>(hn::Abs(dx) + hn::Abs(dy) + hn::Set(d, 1)) + extent + hn::Set(d, 2);
  return bound - (edge.exact - edge.value);
}

// The coverage of the small lanes (SetupBatch.h; `boxEdges` at their first center, as the
// pixel-center test computed them; b and c relative to a, the box in centers less one,
// `extent` the bounding box's width plus height), stored to `coverage`; with boundary edges
// (a triangle polygon's three) the covered centers not surely inside them stored to `unsure`
// (without, every center is sure): returns the lanes with none, which stay small (the others
// are nearEdge lanes, BatchVerdicts). Out of
// line: most batches of a dense mesh have none, and inlined it cost their lanes 4 % more
// instructions (8M triangles).
HWY_NOINLINE M smallLanes(D d, M small, const EdgeLanes (&boxEdges)[3], V ux, V uy, V vx, V vy,
                          V width, V height, V extent, bool boundaryEdges, std::int32_t* coverage,
                          std::int32_t* unsure) {
  const V zero = hn::Zero(d);
  if (boundaryEdges) {
    const V sure[3] = {sureFrom(d, vx - ux, vy - uy, extent, boxEdges[0]),
                       sureFrom(d, zero - vx, zero - vy, extent, boxEdges[1]),
                       sureFrom(d, ux, uy, extent, boxEdges[2])};
    const BoxCoverage<true> box(d, small, boxEdges, width, height, sure);
    hn::Store(box.covered, d, coverage);
    hn::Store(box.unsure, d, unsure);
    return hn::And(small, box.unsure == zero);
  }
  hn::Store(BoxCoverage<false>(d, small, boxEdges, width, height, {zero, zero, zero}).covered, d,
            coverage);
  return small;
}

// ceil(v / 256) and floor(v / 256): arithmetic shifts (RasterTriangle.cpp, floorToPixel).
HWY_INLINE V ceilToPixel(D d, V v) {
  return hn::Zero(d) - hn::ShiftRight<kSubpixelBits>(hn::Zero(d) - v);
}
HWY_INLINE V floorToPixel(V v) {
  return hn::ShiftRight<kSubpixelBits>(v);
}

// Bit l of the result: lane l of the mask.
HWY_INLINE std::uint32_t laneBits(D d, M mask) {
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, mask, bytes);
  return bytes[0] | std::uint32_t{bytes[1]} << 8;
}

// One vertex per lane: its four 32-bit words (FrameTransform.h's WindowVertex layout).
struct VertexLanes {
  V x, y, depth, word;
  VertexLanes(D d, const WindowVertex* v) {
    hn::LoadInterleaved4(d, reinterpret_cast<const std::int32_t*>(v), x, y, depth, word);
  }
  V outcode(D d) const { return hn::And(word, hn::Set(d, 0xFFFF)); }
  V residueX() const { return hn::ShiftRight<24>(hn::ShiftLeft<8>(word)); }  // signed byte 2
  V residueY() const { return hn::ShiftRight<24>(word); }                    // signed byte 3
};

// What the keys of a batch's fragments are computed from, per lane (counter-clockwise,
// relative to vertex a): b, c and the sample in fine units, the sample's snapped edge
// functions of edges c → a and a → b, twice the snapped area, and the vertices' keys.
struct KeyInputs {
  alignas(64) std::int32_t bx[kBatchSize], by[kBatchSize], cx[kBatchSize], cy[kBatchSize];
  alignas(64) std::int32_t sx[kBatchSize], sy[kBatchSize];
  // The same in grid steps, without residues (the snapped plane's).
  alignas(64) std::int32_t gridBx[kBatchSize], gridBy[kBatchSize], gridCx[kBatchSize],
      gridCy[kBatchSize], gridSx[kBatchSize], gridSy[kBatchSize];
  alignas(64) std::int32_t edge1[kBatchSize], edge2[kBatchSize], area[kBatchSize];
  alignas(64) float keyA[kBatchSize], keyB[kBatchSize], keyC[kBatchSize];
  // With clampBackFaces: nearestWrittenKey, a clockwise lane's nearest vertex key, else +∞.
  alignas(64) float nearest[kBatchSize];
};

// In fine units: grid steps · kResidueScale + the residue.
HWY_INLINE V toFine(V grid, V residue) {
  return hn::ShiftLeft<kResidueBits>(grid) + residue;
}

// The verdicts of the lanes from `lane` on (SetupBatch.h), decided as Setup.cpp and
// Binning.cpp decide: culled before zero area, zero area before the pixel-center test, which
// is exact for boxes of at most 4 pixel centers (samplesInBoundingBox, coversAnySample)
// and assumed true for larger ones; a kept triangle whose box holds one center is a fragment.
void classifyLanes(D d, const TriangleBatch& batch, std::size_t lane, const TileGrid& grid,
                   bool skipBackFaces, bool boundaryEdges, bool clamp, BatchVerdicts& verdicts,
                   KeyInputs& keys) {
  const PixelBounds viewport = grid.viewport();
  const V zero = hn::Zero(d);
  const VertexLanes a(d, batch.v[0] + lane), b0(d, batch.v[1] + lane), c0(d, batch.v[2] + lane);
  const V minX = hn::Min(hn::Min(a.x, b0.x), c0.x), maxX = hn::Max(hn::Max(a.x, b0.x), c0.x);
  const V minY = hn::Min(hn::Min(a.y, b0.y), c0.y), maxY = hn::Max(hn::Max(a.y, b0.y), c0.y);
  const V limit = hn::Set(d, kMaxExtent);
  const M inside = hn::Or(hn::Or(a.outcode(d), b0.outcode(d)), c0.outcode(d)) == zero;
  const M tested = hn::And(hn::And(hn::Load(d, batch.triangle + lane) != zero, inside),
                           hn::And(maxX - minX < limit, maxY - minY < limit));

  // b and c relative to a; zero in untested lanes, so that no product below can overflow.
  V ux = hn::IfThenElseZero(tested, b0.x - a.x), uy = hn::IfThenElseZero(tested, b0.y - a.y);
  V vx = hn::IfThenElseZero(tested, c0.x - a.x), vy = hn::IfThenElseZero(tested, c0.y - a.y);
  const V signedArea = ux * vy - vx * uy;  // doubleSignedArea
  const M clockwise = signedArea < zero;
  const M culled = skipBackFaces ? hn::And(tested, clockwise) : hn::FirstN(d, 0);
  const M zeroArea = hn::And(tested, signedArea == zero);
  verdicts.culled |= laneBits(d, culled) << lane;
  verdicts.zeroArea |= laneBits(d, zeroArea) << lane;  // never culled: area == 0, not < 0
  const M live = hn::AndNot(hn::Or(culled, zeroArea), tested);
  // Nothing more to decide (often: the back faces of a closed mesh come in runs).
  if (hn::AllFalse(d, live)) return;
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
  const V width = x1 - x0, height = y1 - y0;  // in centers, less one
  const V one = hn::Set(d, 1), four = hn::Set(d, 4);
  const M few = hn::Or(hn::Or(hn::And(width == zero, height < four),  // at most 4 centers
                              hn::And(height == zero, width < four)),
                       hn::And(width == one, height == one));
  const M boxed = hn::AndNot(empty, tested);
  const M sampled = hn::And(boxed, few);

  // The first center of the box, relative to a: in the bounding box, so below 2^14 in
  // magnitude (the edges' 32-bit range above holds); zero in lanes untested or with no center
  // in their box (it may lie far outside it). The pixel-center test, the small lanes'
  // coverage and the keys all start from it.
  const V sx = hn::IfThenElseZero(boxed, hn::ShiftLeft<kSubpixelBits>(x0) + half - a.x);
  const V sy = hn::IfThenElseZero(boxed, hn::ShiftLeft<kSubpixelBits>(y0) + half - a.y);
  const EdgeLanes edges[3] = {EdgeLanes(d, ux, uy, vx, vy, sx, sy),
                              EdgeLanes(d, vx, vy, zero, zero, sx, sy),
                              EdgeLanes(d, zero, zero, ux, uy, sx, sy)};
  const M covers = FewSamples(d, width, height).covered(d, edges);

  const M noSample = hn::And(live, hn::Or(empty, hn::AndNot(covers, sampled)));
  verdicts.coversNoSample |= laneBits(d, noSample) << lane;
  const M kept = hn::AndNot(noSample, live);
  if (hn::AllFalse(d, kept)) return;
  verdicts.keptSamples +=
      hn::GetLane(hn::SumOfLanes(d, hn::IfThenElseZero(kept, (width + one) * (height + one))));
  const M single = hn::And(kept, hn::And(width == zero, height == zero));
  const std::uint32_t fragments = laneBits(d, single) << lane;
  verdicts.fragment |= fragments;
  verdicts.triangle |= laneBits(d, hn::AndNot(single, kept)) << lane;
  verdicts.clockwise |= laneBits(d, clockwise) << lane;
  hn::Store(x0, d, verdicts.samples.x0 + lane);
  hn::Store(y0, d, verdicts.samples.y0 + lane);
  hn::Store(x1, d, verdicts.samples.x1 + lane);
  hn::Store(y1, d, verdicts.samples.y1 + lane);
  // The tile of the first center, and whether it is the only one the box overlaps (centers
  // of a kept lane are in the viewport: not negative).
  const V tileX = hn::ShiftRight<kTileBits>(x0), tileY = hn::ShiftRight<kTileBits>(y0);
  hn::Store(tileY * hn::Set(d, grid.tilesX()) + tileX, d, verdicts.tile + lane);
  const M oneTile =
      hn::And(tileX == hn::ShiftRight<kTileBits>(x1), tileY == hn::ShiftRight<kTileBits>(y1));
  verdicts.oneTile |= laneBits(d, oneTile) << lane;
  // SmallTriangle records (SetupBatch.h): boxes of 2 to 15 centers, at most 4 on a side.
  const V three = hn::Set(d, 3);
  const M smallBox =
      hn::AndNot(hn::And(width == three, height == three), hn::And(width < four, height < four));
  M small = hn::And(hn::AndNot(single, kept), hn::And(oneTile, smallBox));
  const bool anySmall = !hn::AllFalse(d, small);
  if (fragments == 0 && !anySmall) return;

  std::uint32_t smalls = 0;
  if (anySmall) {
    const M sure = smallLanes(
        d, small, edges, ux, uy, vx, vy, width, height, (maxX - minX) + (maxY - minY),
        boundaryEdges, verdicts.smallPlane.coverage + lane, verdicts.smallPlane.unsure + lane);
    smalls = laneBits(d, sure) << lane;
    verdicts.small |= smalls;
    if (boundaryEdges) {  // the others near a boundary edge; both kinds' planes made
      const std::uint32_t near = (laneBits(d, small) << lane) & ~smalls;
      verdicts.nearEdge |= near;
      smalls |= near;
    }
  }
  if ((fragments | smalls) == 0) return;

  // The keys' and planes' inputs, b and c (and their residues and keys) swapped as above.
  const V bResidueX = hn::IfThenElse(clockwise, c0.residueX(), b0.residueX());
  const V bResidueY = hn::IfThenElse(clockwise, c0.residueY(), b0.residueY());
  const V cResidueX = hn::IfThenElse(clockwise, b0.residueX(), c0.residueX());
  const V cResidueY = hn::IfThenElse(clockwise, b0.residueY(), c0.residueY());
  const V aResidueX = a.residueX(), aResidueY = a.residueY();
  hn::Store(toFine(ux, bResidueX - aResidueX), d, keys.bx + lane);
  hn::Store(toFine(uy, bResidueY - aResidueY), d, keys.by + lane);
  hn::Store(toFine(vx, cResidueX - aResidueX), d, keys.cx + lane);
  hn::Store(toFine(vy, cResidueY - aResidueY), d, keys.cy + lane);
  hn::Store(toFine(sx, zero - aResidueX), d, keys.sx + lane);  // sx in fragment lanes
  hn::Store(toFine(sy, zero - aResidueY), d, keys.sy + lane);
  if (smalls != 0) {
    hn::Store(ux, d, keys.gridBx + lane);
    hn::Store(uy, d, keys.gridBy + lane);
    hn::Store(vx, d, keys.gridCx + lane);
    hn::Store(vy, d, keys.gridCy + lane);
    hn::Store(sx, d, keys.gridSx + lane);
    hn::Store(sy, d, keys.gridSy + lane);
  }
  hn::Store(edges[1].exact, d, keys.edge1 + lane);
  hn::Store(edges[2].exact, d, keys.edge2 + lane);
  hn::Store(hn::Abs(signedArea), d, keys.area + lane);
  const hn::Repartition<float, D> df;
  hn::Store(hn::BitCast(df, a.depth), df, keys.keyA + lane);
  hn::Store(hn::BitCast(df, hn::IfThenElse(clockwise, c0.depth, b0.depth)), df, keys.keyB + lane);
  hn::Store(hn::BitCast(df, hn::IfThenElse(clockwise, b0.depth, c0.depth)), df, keys.keyC + lane);
  if (clamp) {
    const auto nearest = hn::Max(hn::Max(hn::BitCast(df, a.depth), hn::BitCast(df, b0.depth)),
                                 hn::BitCast(df, c0.depth));
    hn::Store(hn::IfThenElse(hn::RebindMask(df, clockwise), nearest,
                             hn::Set(df, std::numeric_limits<float>::infinity())),
              df, keys.nearest + lane);
  }
}

using DD = hn::ScalableTag<double>;
using VD = hn::Vec<DD>;

// keyOfOnlySample's key (RasterTriangle.cpp: TriangleDepth's keyAt, then toDepthKey) of the
// lanes from `lane` on: from the unsnapped plane where the fine area is positive and the
// sample is not beyond a polygon-boundary edge of the unsnapped triangle, else from the
// snapped one.
void keyLanes(DD dd, const KeyInputs& in, std::size_t lane, bool boundaryEdges, bool clamp,
              float* keys) {
  const hn::Rebind<std::int32_t, DD> di;
  const hn::Rebind<float, DD> df;
  const auto load = [&](const std::int32_t* p) {
    return hn::PromoteTo(dd, hn::Load(di, p + lane));
  };
  const VD bx = load(in.bx), by = load(in.by), cx = load(in.cx), cy = load(in.cy);
  const VD sx = load(in.sx), sy = load(in.sy);
  const VD zero = hn::Zero(dd);
  // edgeFunction(p, q, s) = (q.x − p.x)(s.y − p.y) − (q.y − p.y)(s.x − p.x), a at 0: exact.
  const VD fineArea = bx * cy - by * cx;
  const VD fine1 = (zero - cx) * (sy - cy) - (zero - cy) * (sx - cx);  // c → a
  const VD fine2 = bx * sy - by * sx;                                  // a → b
  const auto unsnapped = fineArea > zero;
  auto plane = unsnapped;
  if (boundaryEdges) {
    const VD fine0 = (cx - bx) * (sy - by) - (cy - by) * (sx - bx);  // b → c
    plane = hn::AndNot(hn::Or(hn::Or(fine0 < zero, fine1 < zero), fine2 < zero), unsnapped);
  }
  const VD keyA = hn::PromoteTo(dd, hn::Load(df, in.keyA + lane));
  const VD dk1 = hn::PromoteTo(dd, hn::Load(df, in.keyB + lane)) - keyA;
  const VD dk2 = hn::PromoteTo(dd, hn::Load(df, in.keyC + lane)) - keyA;
  const VD one = hn::Set(dd, 1.0);
  // The unsnapped key keyA + (dk1 · fine1 + dk2 · fine2) · (1 / fineArea) or the snapped one
  // from the snapped edge functions and area: the same operations on the plane's operands,
  // one division for both.
  const VD edge1 = hn::IfThenElse(plane, fine1, load(in.edge1));
  const VD edge2 = hn::IfThenElse(plane, fine2, load(in.edge2));
  const VD area = hn::IfThenElse(plane, fineArea, load(in.area));
  const VD largest = hn::Set(dd, std::numeric_limits<float>::max());
  VD key = keyA + (dk1 * edge1 + dk2 * edge2) * (one / area);
  if (clamp) {  // clamped to nearestWrittenKey (+∞: unchanged), as TriangleDepth::keyAt clamps
    key = hn::Min(key, hn::PromoteTo(dd, hn::Load(df, in.nearest + lane)));
  }
  hn::Store(hn::DemoteTo(df, hn::Min(hn::Max(key, hn::Neg(largest)), largest)), df, keys + lane);
}

// A SmallTriangle's depth plane (RasterTriangle.cpp: TriangleDepth's constructor,
// prepareRows and stepsFrom; the boundary edges change only refine(), which a record's
// samples do not need) for the lanes from `lane` on: the unsnapped plane where the fine area
// is positive, else the snapped one. Every difference of positions is an exact integer in
// double (below 2^23), so only the operations that round follow the scalar order.
void planeLanes(DD dd, const KeyInputs& in, std::size_t lane, bool clamp, BatchVerdicts& verdicts) {
  const hn::Rebind<std::int32_t, DD> di;
  const hn::Rebind<float, DD> df;
  const auto load = [&](const std::int32_t* p) {
    return hn::PromoteTo(dd, hn::Load(di, p + lane));
  };
  const VD toFine = hn::Set(dd, kResidueScale);
  const auto fineOr = [&](auto unsnapped, const std::int32_t* fine, const std::int32_t* grid) {
    return hn::IfThenElse(unsnapped, load(fine), load(grid) * toFine);  // exact integers
  };
  const VD fineArea = load(in.bx) * load(in.cy) - load(in.by) * load(in.cx);
  const auto unsnapped = fineArea > hn::Zero(dd);
  const VD bx = fineOr(unsnapped, in.bx, in.gridBx), by = fineOr(unsnapped, in.by, in.gridBy);
  const VD cx = fineOr(unsnapped, in.cx, in.gridCx), cy = fineOr(unsnapped, in.cy, in.gridCy);
  const VD sx = fineOr(unsnapped, in.sx, in.gridSx), sy = fineOr(unsnapped, in.sy, in.gridSy);
  const VD one = hn::Set(dd, 1.0);
  const VD finePerGrid2 = hn::Set(dd, double{kResidueScale} * kResidueScale);
  // One division: the plane's area chosen first.
  const VD inverse = one / hn::IfThenElse(unsnapped, fineArea, load(in.area) * finePerGrid2);
  const VD keyA = hn::PromoteTo(dd, hn::Load(df, in.keyA + lane));
  const VD dk1 = hn::PromoteTo(dd, hn::Load(df, in.keyB + lane)) - keyA;
  const VD dk2 = hn::PromoteTo(dd, hn::Load(df, in.keyC + lane)) - keyA;
  const VD perX = (dk1 * cy - dk2 * by) * inverse;
  const VD perY = (dk2 * bx - dk1 * cx) * inverse;
  auto& out = verdicts.smallPlane;
  hn::Store(keyA + perX * sx, dd, out.firstKey + lane);
  hn::Store(perY, dd, out.keyPerFine + lane);
  hn::Store(perX * hn::Set(dd, kSubpixelScale) * toFine, dd, out.keyPerPixel + lane);
  hn::Store(hn::DemoteTo(di, sy), di, out.firstRowFine + lane);
  // nearestWrittenKey: a clockwise lane's nearest vertex key, else +∞.
  if (clamp) {
    const hn::Rebind<float, DD> dfl;
    hn::Store(hn::Load(dfl, in.nearest + lane), dfl, out.nearestKey + lane);
  }
}

void ClassifyBatch(const TriangleBatch& batch, const TileGrid& grid, bool skipBackFaces,
                   bool boundaryEdges, BatchVerdicts& verdicts, bool clampBackFaces) {
  const D d;
  verdicts.culled = verdicts.zeroArea = verdicts.coversNoSample = 0;
  verdicts.fragment = verdicts.triangle = verdicts.clockwise = verdicts.oneTile = 0;
  verdicts.small = verdicts.nearEdge = 0;
  verdicts.keptSamples = 0;
  KeyInputs keys;
  // The back faces' keys clamped (nearestWrittenKey), one pass or two (Setup.cpp).
  const bool clamp = boundaryEdges && clampBackFaces;
  for (std::size_t lane = 0; lane < kBatchSize; lane += hn::Lanes(d))
    classifyLanes(d, batch, lane, grid, skipBackFaces, boundaryEdges, clamp, verdicts, keys);
  verdicts.culledCount = static_cast<int>(hwy::PopCount(verdicts.culled));
  verdicts.zeroAreaCount = static_cast<int>(hwy::PopCount(verdicts.zeroArea));
  verdicts.coversNoSampleCount = static_cast<int>(hwy::PopCount(verdicts.coversNoSample));
  const DD dd;
  const std::uint32_t laneMask = (1u << hn::Lanes(dd)) - 1;
  const std::uint32_t fragments = verdicts.fragment, planes = verdicts.small | verdicts.nearEdge;
  for (std::size_t lane = 0; lane < kBatchSize; lane += hn::Lanes(dd)) {
    if ((fragments >> lane) & laneMask)
      keyLanes(dd, keys, lane, boundaryEdges, clamp, verdicts.key);
    if ((planes >> lane) & laneMask) planeLanes(dd, keys, lane, clamp, verdicts);
  }
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

void classifyBatch(const TriangleBatch& batch, const TileGrid& grid, bool skipBackFaces,
                   bool boundaryEdges, BatchVerdicts& verdicts, bool clampBackFaces) {
  HWY_DYNAMIC_DISPATCH(ClassifyBatch)
  (batch, grid, skipBackFaces, boundaryEdges, verdicts, clampBackFaces);
}

void chooseSimdTarget() {
  hwy::ChosenTarget& chosen = hwy::GetChosenTarget();
  if (!chosen.IsInitialized()) chosen.Update(hwy::SupportedTargets());
}

BatchClassifier batchClassifier() {
  chooseSimdTarget();
  return &HWY_DYNAMIC_DISPATCH(ClassifyBatch);
}

std::vector<SimdTarget> simdTargets() {
  // Highway lists only the pinned target once useSimdTarget pinned one: unpin first, so that
  // a test looping over the targets more than once covers every one each time.
  useSimdTarget(0);
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

void forgetSimdTarget() {
  hwy::GetChosenTarget().DeInit();
}

void enableSetupBatches(bool on) {
  batchesOn = on;
}

bool setupBatchesEnabled() {
  return batchesOn;
}

}  // namespace facet::detail
#endif  // HWY_ONCE
