#pragma once

// Blocks of back faces skipped whole. A mesh whose back faces are skipped this frame
// (FrameMesh::skipBackFaces) culls about half its polygons one by one in the set-up, each
// after its points were transformed: a triangle with every corner inside the clip volume is
// culled when its *snapped* doubled window area (doubleSignedArea) is negative, and snapping
// can flip a sliver's or a tiny triangle's sign against its true normal. A back-face block
// (MeshCache.h, BackBlock: kPolygonsPerBackBlock polygons) is skipped, its polygons counted
// as culled and its points not transformed unless a drawn block uses them too, only when
// every triangle in it is certain to be culled by that rule. The proof, for one triangle
// P0 P1 P2 of the block (exact double points, what the transform reads):
//
// 1. Every corner is inside the clip volume: the block's box is, each corner by
//    FrameTransform::boxInsideClipVolume's margin 1e-9·(w + |x|) (the volume is convex, so
//    every point of the box is; the transform's own rounding of clip x and y, ~2^-53 of
//    |row|·reach, is checked per block to be a tenth of that margin at most, so it cannot
//    move a point across). So the triangle is not clipped, nor outside, nor non-finite: facing
//    decides it (runTriangle and the batch alike), culled iff 2A' < 0, 2A' its snapped area.
// 2. Exact window area. View coordinates V = R(P − E) (R the camera rotation, E the eye);
//    window = S·(clip/w + 1) with S = (halfWidth, halfHeight)·kSubpixelScale. Perspective
//    (clip x, clip y, d) = M·V for a 3×3 M (the projection's translation column is zero, else
//    nothing is skipped), so 2A = det[clip_i, 1]·SxSy = det(M)det(R)SxSy·n·(P0 − E)/(d0d1d2)
//    with n = (P1 − P0) × (P2 − P0), |n| = 2a (a the world area). Parallel (w = 1):
//    2A = SxSy·det(R)·(Rᵀ(cx × cy))·n = q·n, cx and cy the rows of clip x and y.
// 3. Facing margin from the cone. Every unit normal n̂ of the block is within α of the axis c
//    (α widened by the normals' rounding, measureBackBlock). For a direction u and
//    β = angle(n̂, c) ≤ α: n̂·u ≥ cos β (c·u) − sin β |u⊥| ≥ cos α (c·u) − sin α |u⊥| when
//    c·u ≥ 0 (u⊥ the part of u normal to c). c·u is linear and |u⊥| convex in u, so over the
//    box their bounds are at its corners: D = cos α · min(c'·u) − sin α · max|u⊥|, u = corner
//    − E, c' = −sign(k)·c (perspective), and n̂·(−sign(k))(P0 − E) ≥ D. If D > 0:
//    2A ≤ −|k|·2a·D/d_max³ (d ≤ d_max over the box, d affine). Parallel, with u = −q/|q| the
//    same D: 2A ≤ −|q|·2a·D.
// 4. Snapping. Each coordinate is rounded to the grid (≤ 1/2) from a value within δ ≤ 2^-11
//    of the exact one (checked per block: the transform's ~10 roundings of 2^-53 against the
//    magnitudes it multiplies, bounded at the box's corners — including the rounding of d,
//    which enters window x = clip x / d multiplied by |x/d|). With e1 = p1 − p0, e2 = p2 − p0
//    in window units and perturbations d1, d2 of max-norm Δ = 1 + 2δ:
//    |2A' − 2A| ≤ Δ(|e1|₁ + |e2|₁) + 2Δ². A window edge is at most G·|P1 − P0|/d_min, with
//    G = Sx(|cx| + Nx) + Sy(|cy| + Ny) (perspective: Δ(x/d) = cx·ΔV/d1 − (x0/d0)Δd/d1, |Δd| ≤
//    |ΔP|; Nx, Ny bounds of |clip/w| over the box: the largest |clip x| and |clip y| at its
//    corners over the smallest w there, both affine over the box, w > 0 (step 1)), G =
//    Sx|cx| + Sy|cy| and d_min = 1 in parallel. So
//    |2A' − 2A| ≤ Δ·G·perimeter/d_min + 2Δ² ≤ 2a·ΔGρ/d_min + 2Δ², ρ the block's largest
//    perimeter/2a (measured from
//    the bound perimeter² ≤ 3(|e1|² + |e2|² + |e2 − e1|²), which only widens the margin).
// 5. Hence 2A' ≤ −2a(X − ΔρY) + 2Δ² with X = |k|D/d_max³ (|q|D) and Y = G/d_min (G): negative
//    for every triangle when X > ΔρY and minDoubleArea·(X − ΔρY) > 2Δ², each side given a
//    1e-6 relative slack for this test's own rounding.
//
// Steps 1 and 4, and the factors of X and Y, hold for every box inside the box they were
// checked on (convexity; d_max, the |clip/w| bounds and the rounding bounds only grow and
// d_min only shrinks over a wider box): the frame's cull checks them once per view-culling
// block (ParentClipBounds), steps 3 and 5 per back-face block.
//
// A polygon that is not a triangle (facing by its normal in double), a degenerate triangle or
// one with a non-finite point makes its block not skippable at measurement.
//
// The compact record. A mesh version keeps not the measured BackBlock but a BackBlockTest
// (MeshCache.h), and the frame runs the steps above on what it decodes from it (BackBlockCone).
// Each decoded fact is a weaker one of the same kind, so the proof holds for it as it stands:
// - the box: low corners rounded down and high ones up to the view-culling block's grid, each
//   checked at measurement with the very expression the frame decodes by (boxOf); a wider box
//   holds every point the triangles use, which is all steps 1, 3 and 4 ask of it;
// - the cone: the axis rounded to float, a, and the half-angle widened by the angle between
//   the exact axis c and â = a/|a| (bounded above by |c − â|, plus 1e-15): every normal within
//   α of c is within α + angle(c, â) of â, a cone around â. The test reads the axis as a,
//   not â: along = a·u = |a|(â·u), and across = |u − (a·u)a| ≥ |u⊥| (its square is
//   (1 − |a|²)²(â·u)² + |u⊥|²), so with the stored cosine rounded down from cos(α')/|a| and
//   the sine up from sin(α'), cos'·along − sin'·across ≤ cos α'(â·u) − sin α'|u⊥| whenever
//   â·u ≥ 0; when some corner has â·u < 0, both D are negative. So D' ≤ D of a true cone;
// - the smallest doubled area rounded down and the largest perimeter / doubled area up (to
//   float; 0 and infinity where float cannot hold them), which only shrink X − ΔρY and the
//   left side of step 5.
// So a block the compact test culls is culled by the exact test's proof, and the compact test
// is the exact one on a wider box and cone (a test checks, on random blocks and boxes at the
// ends of the 16-bit range and far from the origin, that it culls none the exact one keeps).

#include <cstddef>

#include <glm/geometric.hpp>

#include "FrameTransform.h"
#include "MeshAccess.h"
#include "MeshCache.h"

namespace facet::detail {

// The back-face block of polygons [begin, end) of a mesh. With `faceNormals`, also each
// polygon p's face normal (FaceNormal.h) into faceNormals[p], from the same cross product:
// MeshCache reads every polygon once.
BackBlock measureBackBlock(const MeshView& mesh, std::size_t begin, std::size_t end,
                           glm::vec3* faceNormals = nullptr);

// The grid of a view-culling block's back-face blocks' boxes (MeshCache.h), from its box.
BackBlockFrame backFrameOf(const Box& viewBlock);

// The compact record of a block (MeshCache.h) on its view-culling block's grid: cosAngle 0
// when the block is not skippable or its box does not fit the grid.
BackBlockTest testOf(const BackBlock& block, const BackBlockFrame& frame);

// The box a compact record keeps: it holds the measured block's.
Box boxOf(const BackBlockTest& block, const BackBlockFrame& frame);

// What the test computes with, in double: a compact record decoded, or a measured block's own
// facts (coneOf(BackBlock), the exact test, for the tests).
struct BackBlockCone {
  glm::dvec3 ballCenter{0.0};
  double ballRadius = 0.0;
  glm::dvec3 axis{0.0};
  double cosAngle = 0.0, sinAngle = 1.0;
  Box box;
  double minDoubleArea = 0.0, maxPerimeterPerDoubleArea = 0.0;
};
BackBlockCone coneOf(const BackBlockTest& block, const BackBlockFrame& frame);
BackBlockCone coneOf(const BackBlock& block);

// The compact form of the block's point spans (MeshCache.h) for a mesh of `pointCount` points.
BackPointFlags pointFlagsOf(const BackBlock& block, std::size_t pointCount);

// What steps 1 and 4 find for a box, which hold for every box inside it too: every point of
// it is inside the clip volume, the transform's rounding is small enough, and the factors
// of X and Y in step 5 (their bounds over the box are bounds over any box inside it: d_max
// and the |clip/w| bounds only grow, d_min only shrinks).
struct ClipBounds {
  bool inside = false;
  double areaPerFacing = 0.0;  // X / D: |k|/d_max³ (parallel |q|)
  double edgePerLength = 0.0;  // Y: G/d_min (parallel G)
};

// A view-culling block's ClipBounds (MeshCache.h: its box holds its back-face blocks'),
// measured for the first of its back-face blocks that faces away and shared by the others:
// the clip-space corners and their checks are most of a block's test, and a back-face block
// is small against the view, so its parent's bounds are nearly as tight.
struct ParentClipBounds {
  const Box* box = nullptr;
  bool measured = false;
  ClipBounds bounds;
};

// One frame's test of back-face blocks.
class BackFaceTest {
 public:
  explicit BackFaceTest(const FrameTransform& transform);
  // Whether every triangle of the block is culled by a mesh that skips back faces (above),
  // from its compact record (what a frame tests), or from the measured block's own facts (the
  // exact test, for the tests).
  bool certainlyCulled(const BackBlockTest& block, const BackBlockFrame& frame) const;
  bool certainlyCulled(const BackBlock& block) const;
  // A necessary condition of certainlyCulled from the block's cone and ball alone: false for a
  // block that is not skippable and for most that face the viewer (half of them).
  bool mayFaceAway(const BackBlockTest& block, const BackBlockFrame& frame) const;
  // certainlyCulled for a block that passed mayFaceAway, steps 1 and 4 on `parent`'s box,
  // which holds the block's (measured on first use): skips fewer blocks only where the
  // parent's box is much wider than the block's.
  bool culledPastPreTest(const BackBlockTest& block, const BackBlockFrame& frame,
                         ParentClipBounds& parent) const;

 private:
  // The cone's axis turned to the side step 3 tests (perspective: c' = −sign(k)·c); here, so
  // that it is inlined (out of line it cost a third of the pre-test, perf at 2M).
  glm::dvec3 facingAxis(const glm::dvec3& axis) const {
    return c_.parallel ? axis : facingSign_ * axis;
  }
  // The pre-test on a ball and a cone (mayFaceAway): here, so that it is inlined.
  bool ballMayFaceAway(const glm::dvec3& center, double radius, const glm::dvec3& axis,
                       double cosAngle, double sinAngle) const {
    // The parts of u along the unit vector c and normal to it.
    const glm::dvec3 c = facingAxis(axis);
    const glm::dvec3 u = c_.parallel ? awayFromViewer_ : center - c_.eye;
    const double along = glm::dot(c, u);
    const double across = glm::length(u - along * c);
    if (c_.parallel) return cosAngle * along - sinAngle * across > 0.0;
    return cosAngle * (along + radius) - sinAngle * (across - radius) > 0.0;
  }
  bool mayFaceAway(const BackBlockCone& block) const;
  bool certainlyCulled(const BackBlockCone& block) const;
  double facingMargin(const BackBlockCone& block) const;
  ClipBounds clipBounds(const Box& box) const;
  bool culledWithin(const BackBlockCone& block, double facing, const ClipBounds& bounds) const;
  const FrameTransform& transform_;
  ProjectionConstants c_;
  bool usable_ = false;
  bool margin_ = true;                  // ScopedBackBlockSettings
  double areaScale_ = 0.0;              // perspective |k|; parallel |q|
  glm::dvec3 awayFromViewer_{0.0};      // parallel: −q/|q|
  double facingSign_ = 1.0;             // perspective: −sign(k)
  double rowX_ = 0.0, rowY_ = 0.0;      // |cx|, |cy| (linear parts)
  double scaleX_ = 0.0, scaleY_ = 0.0;  // Sx, Sy
};

// Tests only: how the renders started on this thread treat back-face blocks while an object
// of this class lives (a render reads them once, when it starts, on its calling thread; a
// nested object restores the outer one's). Skipping off: every polygon is set up, as before.
// Margin off: a block is skipped when D > 0 alone (wrong: for the test that shows the margin
// matters).
class ScopedBackBlockSettings {
 public:
  struct Settings {
    bool skipping = true;
    bool margin = true;
  };
  explicit ScopedBackBlockSettings(Settings settings);
  ~ScopedBackBlockSettings();
  ScopedBackBlockSettings(const ScopedBackBlockSettings&) = delete;
  ScopedBackBlockSettings& operator=(const ScopedBackBlockSettings&) = delete;
  // This thread's settings (the defaults outside any object).
  static Settings current();

 private:
  Settings previous_;
};

}  // namespace facet::detail
