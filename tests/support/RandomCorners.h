#pragma once

// The raster tests' random triangles (RasterTest, DepthPrecisionTest): three corners around a
// point, drawn in one fixed order from the test's generator (the tests' streams depend on it).

#include <cstdint>
#include <random>

#include "FrameTransform.h"

namespace facet::testing {

// Corners each within `size` (window units, 256 a pixel) of (cx, cy) in x and in y, with
// random residues, their depths `base` plus up to ±0.05 each (a steep plane), or 1e-4 of that
// when `flat`.
inline void randomCornersAround(std::mt19937& random, int cx, int cy, int size, float base,
                                bool flat, detail::WindowVertex (&corners)[3]) {
  std::uniform_int_distribution<int> offset(-size, size), residue(-127, 127);
  std::uniform_real_distribution<float> steep(-0.05f, 0.05f);
  for (detail::WindowVertex& c : corners) {
    c.x = cx + offset(random);
    c.y = cy + offset(random);
    c.residueX = static_cast<std::int8_t>(residue(random));
    c.residueY = static_cast<std::int8_t>(residue(random));
    c.depth = base + (flat ? steep(random) * 1e-4f : steep(random));
  }
}

}  // namespace facet::testing
