#pragma once

// The error estimate's pass over a row of samples (QualityRenderer.cpp, rowEstimates) in SIMD
// lanes (Google Highway, the instruction set chosen at run time). Integer differences, an
// exact conversion to float, one addition and a maximum: the same bytes on every
// instruction set (tested).

#include "facet/Color.h"

namespace facet::detail {

// For x in [begin, end): out[x] = max(out[x], d + bounds[x]), d the largest channel
// difference |neighbours[x] − center[x]| over red, green and blue. A bound of −∞ (the
// background) leaves out[x] as it was.
void neighbourMaxima(const Rgba8* center, const Rgba8* neighbours, const float* bounds, int begin,
                     int end, float* out);

}  // namespace facet::detail
