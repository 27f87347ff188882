#pragma once

// The error estimate's pass over the sample grid (QualityRenderer.cpp, estimate()) in SIMD
// lanes (Google Highway, the instruction set chosen at run time), in integers: the same bytes
// on every instruction set (tested) and for any thread count.
//
// A sample p's estimate is, over the polygons q its 3 × 3 neighbourhood shows (p's own
// included), the largest |c_p − c_q| + b_q: D(c_p, c_q), the largest channel difference of
// the two flat colors, plus q's bound (FlatErrorBound.h, QualityStats::predicted*) — the
// sample may show any of them where the Phong image has them: |c_p − Phong_q(x)| ≤
// |c_p − c_q| + 0.5 + b_q (c_q is q's flat color rounded to 8 bits, within 0.5 of the exact
// one, which is within b_q of Phong_q anywhere on q; the caller's 0.5 is added here). As
// |a − b| = max(a − b, b − a),
//   max_q (D(c_p, c_q) + b_q) = max over channel k and sign s of
//                               [ max_q (s·c_q,k + b_q) ] − s·c_p,k,
// and the bracket is a 3 × 3 maximum filter of one field per (k, s), which separates into a
// maximum along the row and one across rows: 6 fields, 4 maxima per sample, in place of the
// 9 neighbour differences. The fields are fixed point, in 1/kEstimateUnit of an 8-bit unit,
// with each bound rounded up (so the estimate stays a bound: at most 1/128 above its exact
// value) and capped at 255 (no sample can be off by more); the − fields take 255 − c, so
// every field is an unsigned integer below 2^16, and a field of the background is 0, below
// any polygon's.

#include <cstddef>
#include <cstdint>

#include "facet/Color.h"

namespace facet::detail {

// Fixed point of the estimate: this many steps per 8-bit unit (a power of two: the scaling
// of a float bound is exact).
inline constexpr std::uint32_t kEstimateUnit = 128;
// The largest estimate of a sample or pixel: 255 units.
inline constexpr std::uint32_t kEstimateCap = 255 * kEstimateUnit;
// Fields per sample: red, green, blue, each as c and as 255 − c.
inline constexpr int kEstimateFields = 6;

// For x in [begin, end): field k of sample x (plane k at fields + k·stride), from its color
// and its polygon's bound (ids[x] indexes polygonBounds; < 0: the background, whose fields
// are 0). With q = ⌈min(b, 255)·kEstimateUnit⌉ + 1 (≥ 1: a covered sample is never 0):
// field 2j is c_j·kEstimateUnit + q and field 2j+1 is (255 − c_j)·kEstimateUnit + q.
void neighbourFields(const Rgba8* colors, const std::int32_t* ids, const float* polygonBounds,
                     int begin, int end, std::uint32_t* fields, std::size_t stride);

// For x in [begin, end) and every plane: out[x] = max(in[x − 1], in[x], in[x + 1]) (the
// caller keeps in[begin − 1] and in[end] readable).
void rowMaxima(const std::uint32_t* in, int begin, int end, std::uint32_t* out, std::size_t stride);

// For x in [begin, end): the sample's estimate plus its rounding (0.5), in kEstimateUnit
// steps and capped at kEstimateCap, from the row maxima of the rows above, of its own and
// below; 0 for the background (a covered sample's is at least 0.5 unit).
void sampleEstimates(const std::uint32_t* above, const std::uint32_t* row,
                     const std::uint32_t* below, std::size_t stride, const Rgba8* colors,
                     const std::int32_t* ids, int begin, int end, std::uint32_t* out);

// Over [begin, end) of a row of estimates: the sum of their squares, the largest, and how
// many are not 0 (covered).
struct EstimateSums {
  std::uint64_t squares = 0;
  std::uint32_t largest = 0, covered = 0;
};
EstimateSums estimateSums(const std::uint32_t* estimates, int begin, int end);

}  // namespace facet::detail
