#pragma once

// EXPERIMENT (every22, not proven, off unless FACET_HIDDEN_BLOCKS=1): a two-pass frame's back
// pass drops every deferred back face of a back-face block (MeshCache.h, 256 polygons) whose
// 3D box projects behind the front faces' 8 × 8 blocks (FrontDepthBlocks), before any
// per-polygon work. The box gives a window box (its corners projected, rounded outward) and a
// nearest key (its nearest corner's). What this does NOT bound: a triangle's fragment keys may
// exceed its largest vertex key by its key plane's slope times a grid step plus a rounding term
// proportional to that slope (TriangleDepth::keyRange), and a sliver's slope is unbounded by
// anything the block's box says; see bench/core-frame-issue11.md §18b. Used only to measure
// what a whole-block reject would save.

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

// FACET_HIDDEN_BLOCKS=1 in the environment, or enableHiddenBlocks(true) (tests), turns it on.
void enableHiddenBlocks(bool on);
bool hiddenBlocksEnabled();
// The blocks tested and hidden and their deferred polygons, counted only while counting is on
// (tests; FACET_HIDDEN_BLOCKS_DEBUG=1 prints them at exit).
struct HiddenBlockCounts {
  std::size_t blocks = 0, hidden = 0, polygons = 0, hiddenPolygons = 0;
};
void countHiddenBlocks(bool on);
HiddenBlockCounts hiddenBlockCounts();
void hiddenBlockDebug(bool hidden, std::size_t polygons);

}  // namespace facet::detail
