#pragma once

// EXPERIMENT (every22, not proven, off unless FACET_HIDDEN_BLOCKS=1): a two-pass frame's back
// pass drops every deferred back face of a back-face block (MeshCache.h, 256 polygons) whose
// 3D box projects behind the front faces' 8 × 8 blocks (FrontDepthBlocks), before any
// per-polygon work. The box gives a window box (its corners projected, rounded outward) and a
// nearest key (its nearest corner's). Used only to measure what a whole-block reject would
// save (bench/core-frame-issue11.md, sections 18b and 18c).
//
// What a proof needs (every23's analysis, section 18c; NOT done, so this stays off). A back
// face is hidden when the float key it writes at every covered sample is at most the front
// key there (writeFragment keeps the nearer key, ties keep the front face: back faces are
// painted last in both passes). Keys are larger nearer.
// 1. The exact key at a covered sample. A polygon that is a triangle has all three edges on its
//    polygon's boundary (Setup.cpp, boundaryEdges), and then every paint path evaluates either
//    the unsnapped plane at a sample surely inside the unsnapped triangle or the snapped plane
//    inside the snapped one (TriangleDepth::keyAt and refine, BoxRaster::paintRows,
//    paintSmallMask, SetupBatch's keyLanes; a small record only when every covered center is
//    surely inside, smallLanes): without rounding, a convex combination of the three vertex
//    keys, so at most the largest. No triangle of a tested block is clipped: its box is inside
//    the clip volume (boxInsideClipVolume). A polygon with a diagonal extrapolates past it by
//    one grid step of the plane: keyRange's slope term.
// 2. The rounding is NOT bounded by the vertex keys and the block alone. BoxRaster and the
//    small path step a row's key by keyPerPixel (n ≤ the row's pixels additions) from the
//    row's first sample of the triangle's box, where the plane is extrapolated: the running
//    key reaches K + |perX|·Lx + |perY|·Ly ≤ K + 4·Δk·E²/F (K the largest vertex key, Δk the
//    vertex keys' range, E the triangle's window extent and F its area, both in the plane's
//    units), so the written key may exceed the convex combination by about
//    (n + c)·u·(K + 4·Δk·E²/F), u = 2^-53, c a few roundings per path (at(), stepsFrom and
//    planeLanes, keyLanes). With only F ≥ 1 fine unit² (an integer), that is ~2·Δk for a
//    100-pixel block: no reject (section 18b's route (b) missed the factor n).
// 3. keyRange's own bound (slope·kResidueScale beyond the vertex keys) with the cone's least
//    area (section 18b's route (a) alone) is ~4·Δk·L/m (L the block's window extent, m its
//    least snapped area, grid units): tens of Δk on the 500k sphere, no reject either.
// 4. Both together: a block BackFaceTest::certainlyCulled passes has only plain triangles
//    (BackBlock::skippable), so step 1 holds, and its step 5 bounds every snapped area below by
//    m = minDoubleArea·(X − ΔρY) − 2Δ² > 0 (grid units²), and every fine (unsnapped) area too
//    (the residues move a point by at most 1/512 + δ < Δ/2). Then step 2's excess is at most
//    (n + c)·u·(K + 4·Δk·L²/m) with n ≤ L/kSubpixelScale + 1: ~4e-7·Δk for a 500-pixel block
//    if m is a tenth of a pixel² (an estimate: m not measured). Still to write and check: c for
//    every path (operation by operation), the vertex keys bounded by the box's corner keys (the key
//    is linear-fractional in the point: its extremes over the box are at corners) plus the
//    transform's rounding, Δk ≤ the corner keys' range, the float rounding (monotone: a double key
//    ≤ a float front key rounds to at most it), the window box widened by the snapping (±1/2 + δ
//    grid steps), and certainlyCulled giving m. The reject would then apply to cone-certain blocks
//    only.

#include "Box.h"
#include "FrameTransform.h"
#include "RasterTriangle.h"
#include "TileGrid.h"

namespace facet::detail {

class HiddenBlockTest {
 public:
  HiddenBlockTest(const FrameTransform& transform, const TileGrid& grid,
                  const FrontDepthBlocks& front)
      : transform_(transform), viewport_(grid.viewport()), front_(front) {}
  // Whether every triangle of points in `box` would lose the depth test everywhere to the
  // front faces (up to what the header says is not bounded).
  bool hidden(const Box& box) const;

 private:
  const FrameTransform& transform_;
  PixelBounds viewport_;
  const FrontDepthBlocks& front_;
};

// FACET_HIDDEN_BLOCKS=1 in the environment, or enableHiddenBlocks(true) (tests), turns it on;
// FACET_HIDDEN_BLOCKS=cone turns it on for the blocks BackFaceTest proves back-facing only
// (what step 4 above would allow; measured in section 18c).
void enableHiddenBlocks(bool on);
bool hiddenBlocksEnabled();
bool hiddenBlocksConeOnly();
// The blocks tested and hidden and their deferred polygons, counted only while counting is on
// (tests; FACET_HIDDEN_BLOCKS_DEBUG=1 prints them at exit).
// `coneCertain`: of those, the blocks BackFaceTest proves back-facing (the blocks a proven
// reject could take, section 18c), and how many of them are hidden.
struct HiddenBlockCounts {
  std::size_t blocks = 0, hidden = 0, polygons = 0, hiddenPolygons = 0;
  std::size_t coneCertain = 0, coneCertainHidden = 0, coneCertainHiddenPolygons = 0;
};
void countHiddenBlocks(bool on);
bool countingHiddenBlocks();
HiddenBlockCounts hiddenBlockCounts();
void hiddenBlockDebug(bool hidden, bool coneCertain, std::size_t polygons);

}  // namespace facet::detail
