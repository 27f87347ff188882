#pragma once

// A two-pass frame's (Raster.h) back pass drops every deferred back face of a back-face block
// (MeshCache.h, kPolygonsPerBackBlock polygons) whose 3D box (the compact record's, which
// holds every point its polygons use: BackBlockTest) projects behind the front faces'
// 4 × 4 pixel blocks (FrontDepthBlocks), before any per-polygon work: its polygons are counted
// hidden (RenderStats::polygonsHidden), nothing is loaded, classified or painted. On by default
// in two-pass frames (the plan decides those, Plan.h); FACET_HIDDEN_BLOCKS=0 turns it off
// (measurements).
//
// Why no dropped back face could have changed anything (every24; sections 18b–18c and 21 of
// bench/core-frame-issue11.md say how the earlier attempts fell short). Keys are larger
// nearer. A back face is painted after every front face of its tile (both passes), and
// writeFragment writes only a strictly nearer key: a back face whose written key is at most
// the front key at each of its covered samples writes nothing. Nothing else of the frame is
// read from its triangles: shading and the shown flags come from the final ids, the
// covered count from the final ids. So, with W a key any of its triangles writes and F the
// front key at that sample after the front pass (it only grows nearer afterwards):
// 1. W ≤ its triangle's nearest vertex key, by construction: the block is dropped only when
//    all its polygons are triangles (MeshFacts::backSkippable), and every back face of an
//    every-face mesh that a depth-tested frame paints (its back bins, Chunk::binsFor: one
//    pass or the back pass of two alike) is set up clamped when it is a triangle polygon's
//    unclipped triangle (kClampedEdges: its three edges polygon-boundary edges plus the clamp
//    bit; Setup.cpp's triangleEdges; SetupBatch's keyLanes and the records'
//    Chunk::smallNearestKeys with clampBackFaces), so every paint path clamps the key it
//    writes to the nearest vertex key (nearestWrittenKey, RasterTriangle.h:
//    TriangleDepth::keyAt and refine<true>, paintSmallTriangle with a nearest key). The frame
//    with and the frame without the reject, and the one-pass frame, paint those triangles
//    alike, so it is the clamped keys a dropped triangle would have written, and one pass and
//    two give the same bytes by construction whatever the last frame made the plan choose.
//    No rounding argument: the clamp is a min of two floats' worth of doubles before the one
//    rounding to float, and rounding is monotone. (Front faces and closed meshes are not
//    clamped: nothing of theirs is dropped, and they are painted alike in both kinds of
//    frame.)
// 2. No triangle of the block is clipped and every point of it has d > 0: its box is inside
//    the clip volume with a margin (FrameTransform::boxInsideClipVolume; its eight corners
//    taken in SIMD lanes, HiddenBlockCorners.h, with the same bits), so every vertex's
//    outcode is kInside and its window position and key are toWindow's of its own point.
// 3. Every vertex key is at most nearestVertexKeyBound (HiddenBlocks.cpp): the view distance
//    d is affine in the point, so its least over the box is at a corner; each computed
//    distance (the corners' and the vertices', the same operations) is within
//    η = 1e-14 · (the corners' largest |coordinate − eye|) of the exact one (it rounds at
//    under 9u of that); the key, n/d in perspective and n − d in parallel projection, is
//    monotone in d, and its own roundings (below 3u of it) are covered by the bound's
//    1e-14. The vertex's float key is the rounding of that double: at most any float
//    at least the bound (monotone rounding).
// 4. Every covered sample lies within the window box of the corners' images widened by two
//    grid steps: the projection (w = d > 0 on the box) maps the box into the convex hull of
//    its corners' images, a vertex is snapped by at most half a grid step and the
//    corners' and vertices' images round by far less than one, and a covered sample lies
//    inside the snapped triangle, hence in its vertices' bounding box. Its pixel is in the
//    pixel box tested, whose 4 × 4 blocks' least front keys (FrontDepthBlocks::over) are
//    at most every front key there.
// 5. So when the blocks' least key F_min ≥ the bound: W ≤ nearest vertex float key ≤ F_min ≤
//    F: an exact tie keeps the front face, no fragment is written.
// What it changes in the frame's report: the dropped polygons are counted hidden
// (RenderStats::polygonsHidden, the filters' PolygonsHidden), neither drawn nor binned: one
// pass counts some of them drawn and binned, others outside (covering no pixel center) or
// degenerate, which only setting them up tells apart, so drawn + outside + degenerate +
// hidden is one pass's drawn + outside + degenerate, and trianglesBinned is lower. The
// fragments written are the same (none); their boxes' samples are not added to the plan's
// depth complexity nor their triangles to its mean box (RenderPlan::depthComplexity and
// meanTriangleBox differ from one pass's), and RenderPlan reports the blocks and polygons
// dropped.
// The margin test is DepthPrecision.TriangleKeysNeverPassTheirNearestVertexKey (step 1) and
// HiddenBlocks.ApexThroughTheFrontFaceIsNeverDropped (steps 3–5).
//
// Runs (silhouette25). A block that straddles the silhouette reaches the background (its
// 4 × 4 blocks' least front key is the background's), so the block test cannot hold there,
// though most of its back faces lie behind front faces. The back pass then splits the
// block's deferred ids into runs, the deferred ids of one aligned window of kHiddenRunIds
// polygon ids, and drops a run whole before any of its polygons is loaded or classified when
// HiddenRunTest::hidden holds for the window bounds of its own vertices (RunBounds: the
// transform's WindowVertex of each corner, no box and no distance bound; taken in SIMD lanes,
// HiddenRuns.h):
// R1. Every polygon of the run is a triangle and every vertex's outcode is kInside
//     (RunBounds::outcodes): no triangle is clipped, each vertex's window position and key are
//     the ones the set-up paints with. Such a deferred triangle has a negative snapped area
//     (the front pass defers only those: runTriangle's area < 0, the batch's clockwise culled
//     lanes, and the cone-certain blocks, BackFacingBlocks.h), computed again from the same
//     vertices in the back pass, so it is painted as a back face of a triangle polygon:
//     clamped (step 1): W ≤ its nearest vertex key ≤ RunBounds::nearest, the largest float
//     key of the run's vertices. No rounding here: the floats are compared as they are.
// R2. A covered sample (pixel center p·scale + half, in the grid's fixed point) lies inside
//     the snapped triangle, hence within the closed box of its snapped vertices, hence of
//     the run's [x0, x1] × [y0, y1]; its pixel is in the pixel box of the centers there,
//     clipped to the viewport (nothing outside is written), found exactly in integers.
// R3. FrontDepthBlocks::over(that box) F_min is at most every front key there (step 4):
//     F_min ≥ nearest gives W ≤ nearest ≤ F_min ≤ F; a tie keeps the front face.
// Counted as a dropped block's polygons (hidden alone: drawn + outside + degenerate + hidden
// is one pass's). The windows are aligned in mesh polygon ids and kHiddenRunIds divides the
// block (and so every chunk: planChunks cuts at 1,024-polygon blocks), so a run is the same
// set of ids whatever the threads, and so are the counts. The margin test is
// HiddenBlocks.RunPokingThroughTheFrontFaceIsNeverDropped (R1–R3: fails with the comparison
// loosened by 1e-6 of the key).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "Box.h"
#include "FrameTransform.h"
#include "HiddenBlockCorners.h"
#include "RasterTriangle.h"
#include "TileGrid.h"
#include "facet/Conventions.h"

namespace facet::detail {

class HiddenBlockTest {
 public:
  HiddenBlockTest(const FrameTransform& transform, const TileGrid& grid,
                  const FrontDepthBlocks& front)
      : constants_(transform.constants()),
        viewport_(grid.viewport()),
        front_(front),
        corners_(blockCornersFunction()) {}
  // Whether every triangle of a triangle polygon with points in `box` loses the depth test
  // everywhere to the front faces (the header's proof).
  bool hidden(const Box& box) const;

 private:
  double nearestVertexKeyBound(double nearestDistance, double farthestDistance,
                               double largestOffset) const;

  ProjectionConstants constants_;
  PixelBounds viewport_;
  const FrontDepthBlocks& front_;
  BlockCornersFunction corners_;  // blockCorners on the target chosen when the test was made
};

// The index of the first of ids[k, stop) at least `value` (stop when none is), for ascending
// distinct ids with ids[k] < value and k < stop (the back pass's deferred ids, Setup.cpp: the
// end of a block's, `value` the next block's first id): found directly when the ids from k on
// leave no gap below `value` (a block deferred whole: its ids are consecutive), else by a
// binary search over at most value − ids[k] ids, not over the rest of the chunk. Distinct
// ids: at most value − ids[k] of them lie in [ids[k], value). An entry of a later block
// deferred whole (kWholeBackBlockBit, Frame.h) reads as at least `value` (its id is, and the
// bit only adds), so it ends the block as an id would. Whatever the ids, only
// ids[k, stop) are read. A repeated id (never: the back pass asserts strictly ascending ids;
// the front pass appends each polygon once, in id order) may end it early, at an id still
// below `value`, never past it: the back pass then takes the rest of the block as another
// block of the same verdict (its blocks counted twice, nothing drawn differently).
inline std::size_t firstIdFrom(const std::vector<std::uint32_t>& ids, std::size_t k,
                               std::size_t stop, std::uint32_t value) {
  const std::size_t most = std::min<std::size_t>(stop, k + (value - ids[k]));
  if (ids[most - 1] < value) return most;
  return static_cast<std::size_t>(std::lower_bound(ids.begin() + static_cast<std::ptrdiff_t>(k),
                                                   ids.begin() + static_cast<std::ptrdiff_t>(most),
                                                   value) -
                                  ids.begin());
}

// Polygon ids per run (the header's runs): 8 measured best at 500k (section 30 of
// bench/core-frame-issue11.md: 4 the same, 16 and up fewer dropped).
inline constexpr std::size_t kHiddenRunIds = 8;
static_assert((kHiddenRunIds & (kHiddenRunIds - 1)) == 0);

// The window bounds of a run of deferred back faces, from their vertices as the transform
// left them (HiddenRunTest). add() is the one-lane target's and the tests' reference for
// HiddenRuns.h's lanes.
struct RunBounds {
  std::int32_t x0 = std::numeric_limits<std::int32_t>::max(), y0 = x0;
  std::int32_t x1 = std::numeric_limits<std::int32_t>::min(), y1 = x1;
  float nearest = -std::numeric_limits<float>::infinity();
  // The vertices' outcodes, and kNotTriangle when a polygon of the run is not a triangle.
  std::uint32_t outcodes = kInside;
  static constexpr std::uint32_t kNotTriangle = 1u << 16;  // beyond WindowVertex::outcode

  [[gnu::always_inline]] void add(const WindowVertex& v) {
    x0 = std::min(x0, v.x), x1 = std::max(x1, v.x);
    y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
    nearest = std::max(nearest, v.depth);
    outcodes |= v.outcode;
  }
};

class HiddenRunTest {
 public:
  HiddenRunTest(const TileGrid& grid, const FrontDepthBlocks& front)
      : viewport_(grid.viewport()), front_(front) {}
  // Whether every triangle of a run of triangle polygons with these bounds loses the depth
  // test everywhere to the front faces (the header's runs, steps R1-R3).
  bool hidden(const RunBounds& run) const {
    if (run.outcodes != kInside) return false;  // step R1
    // Step R2: pixel centers p·scale + half inside [x0, x1] (an arithmetic shift floors).
    constexpr std::int32_t kHalf = kSubpixelScale / 2;
    const int px0 = std::max((run.x0 - kHalf + kSubpixelScale - 1) >> kSubpixelBits, viewport_.x0);
    const int px1 = std::min((run.x1 - kHalf) >> kSubpixelBits, viewport_.x1);
    const int py0 = std::max((run.y0 - kHalf + kSubpixelScale - 1) >> kSubpixelBits, viewport_.y0);
    const int py1 = std::min((run.y1 - kHalf) >> kSubpixelBits, viewport_.y1);
    if (px0 > px1 || py0 > py1) return false;
    // Step R3: a tie keeps the front face.
    return front_.over({px0, py0, px1, py1}) >= run.nearest;
  }

 private:
  PixelBounds viewport_;
  const FrontDepthBlocks& front_;
};

// On unless FACET_HIDDEN_BLOCKS=0 in the environment or enableHiddenBlocks(false) (tests);
// FACET_HIDDEN_BLOCKS=cone restricts it to the blocks BackFaceTest proves back-facing
// (measured in section 18c).
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
  // The blocks (parts of blocks a chunk holds) the front pass deferred whole, unclassified
  // (SetupContext::deferCertainBackBlocks), and their polygons.
  std::size_t deferredWhole = 0, deferredWholePolygons = 0;
  // The runs (HiddenRunTest) of the blocks not dropped whole, the runs dropped, and their
  // deferred polygons.
  std::size_t runs = 0, hiddenRuns = 0, runPolygons = 0, hiddenRunPolygons = 0;
  // The blocks whose points waited for the reject (DeferredBackPoints.h), and those kept.
  std::size_t waitingBlocks = 0, waitingBlocksKept = 0;
  // Of the blocks tested, those the back pass took as one entry (deferred whole,
  // kWholeBackBlockBit), and those of them kept (their ids made for the runs).
  std::size_t wholeTested = 0, wholeKept = 0;
};
void countHiddenBlocks(bool on);
bool countingHiddenBlocks();
HiddenBlockCounts hiddenBlockCounts();
void hiddenBlockDebug(bool hidden, bool coneCertain, std::size_t polygons, bool whole);
void deferredWholeDebug(std::size_t polygons);
void hiddenRunDebug(std::size_t runs, std::size_t hiddenRuns, std::size_t polygons,
                    std::size_t hiddenPolygons);
void waitingBlocksDebug(std::size_t waiting, std::size_t kept);

}  // namespace facet::detail
