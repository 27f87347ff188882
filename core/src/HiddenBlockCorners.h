#pragma once

// HiddenBlockTest's corner step (HiddenBlocks.h, steps 2 and 4) in SIMD lanes: a box's eight
// corners projected at once, one corner a lane (HiddenBlockCorners.cpp: Highway, the
// instruction set chosen at run time). Every lane computes what FrameTransform computes for one
// corner (toClip, boxInsideClipVolume's test, toWindow's snapped x and y) with the same IEEE
// operations in the same order, no multiply-add fused (the file is compiled
// -ffp-contract=off): every instruction set gives the bits of the corner-by-corner path, so
// every target drops the same blocks (the test is HiddenBlockCorners' every-target test).

#include <cstdint>

#include "Box.h"
#include "FrameTransform.h"

namespace facet::detail {

// The snapped window positions' bounds of a box's corners (toWindow's x and y, in the grid's
// fixed point) and the least and largest computed view distance d of its corners.
struct BlockCorners {
  std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double nearest = 0.0, farthest = 0.0;
};

// False when a corner is not finite, is beyond kLargeCoordinate from the eye (toClip would
// scale it), or is not inside the clip volume by boxInsideClipVolume's margin; else
// true and `corners` set. `box` is not empty.
bool blockCorners(const ProjectionConstants& constants, const Box& box, BlockCorners& corners);

// blockCorners on the instruction set chosen now: HiddenBlockTest takes it once and calls it
// per block, without Highway's dispatch (the chosen target's index and its table) in every
// block. The same function blockCorners calls.
using BlockCornersFunction = bool (*)(const ProjectionConstants& constants, const Box& box,
                                      BlockCorners& corners);
BlockCornersFunction blockCornersFunction();

}  // namespace facet::detail
