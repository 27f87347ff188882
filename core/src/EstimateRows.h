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

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "facet/Color.h"

namespace facet::detail {

// Fixed point of the estimate: this many steps per 8-bit unit (a power of two: the scaling
// of a float bound is exact).
inline constexpr std::uint32_t kEstimateUnit = 128;
// The largest estimate of a sample or pixel: 255 units.
inline constexpr std::uint32_t kEstimateCap = 255 * kEstimateUnit;
// Fields per sample: red, green, blue, each as c and as 255 − c.
inline constexpr int kEstimateFields = 6;
// Fields of a grey sample row (every covered sample's color has r = g = b): the green and
// blue fields are the red ones, so the pass keeps only the red pair, planes 0 and 1 (a white
// material under white light is grey: a third of the planes, the same bytes).
inline constexpr int kGreyFields = 2;
// A field: at most kEstimateCap + ⌈255·kEstimateUnit⌉ + 1 = 65281, 16 bits (half the memory
// and twice the lanes of 32: the pass reads six planes of three rows per sample).
using EstimateField = std::uint16_t;
static_assert(2 * kEstimateCap + 1 < (1u << 16), "a field fits 16 bits");

// A polygon's bound b as the fields add it: q = ⌈min(b, 255)·kEstimateUnit⌉ + 1 (≥ 1: a
// covered sample's fields are never 0; NaN as 255), below 2^16. Kept per polygon id in 16
// bits, not per sample from the float: the pass reads one per sample by its id, scattered,
// and half the bytes is half the cache lines (most of the pass's time at 500k triangles,
// where nearly every sample's polygon differs from its neighbour's).
using EstimateBound = std::uint16_t;
inline EstimateBound fixedBoundOf(float bound) {
  const float capped = bound < 255.0f ? (bound > 0.0f ? bound : 0.0f) : 255.0f;
  const float scaled = capped * static_cast<float>(kEstimateUnit);  // exact: a power of two
  const auto whole = static_cast<std::uint32_t>(scaled);            // below 2^24: exact
  return static_cast<EstimateBound>(whole + (static_cast<float>(whole) < scaled) + 1);
}
static_assert(kEstimateCap + 1 < (1u << 16), "a fixed bound fits 16 bits");

// For x in [begin, end): fields k < planes (kEstimateFields or kGreyFields) of sample x
// (plane k at fields + k·stride), from its color and its polygon's fixed bound q (ids[x]
// indexes fixedBounds, whose count is even: the lanes read them as 32-bit pairs; < 0: the
// background, whose fields are 0): field 2j is c_j·kEstimateUnit + q and field 2j+1 is
// (255 − c_j)·kEstimateUnit + q. With `shift`, q is fixedBounds[id >> shift]: one bound per
// block of 2^shift polygon ids (the summary-only estimate's, FlatErrorBoundOfMesh.h). Returns
// whether every covered sample there is grey.
bool neighbourFields(const Rgba8* colors, const std::int32_t* ids, const EstimateBound* fixedBounds,
                     int begin, int end, EstimateField* fields, std::size_t stride,
                     int planes = kEstimateFields, int shift = 0);

// For x in [begin, end) and planes k < planes: out[x] = max(in[x − 1], in[x], in[x + 1]) (the
// caller keeps in[begin − 1] and in[end] readable).
void rowMaxima(const EstimateField* in, int begin, int end, EstimateField* out, std::size_t stride,
               int planes = kEstimateFields);

// For x in [begin, end): the sample's estimate plus its rounding (0.5), in kEstimateUnit
// steps and capped at kEstimateCap, from the row maxima of the rows above, of its own and
// below; 0 for the background (a covered sample's is at least 0.5 unit). With kGreyFields
// planes, the three rows' covered samples are grey.
void sampleEstimates(const EstimateField* above, const EstimateField* row,
                     const EstimateField* below, std::size_t stride, const Rgba8* colors,
                     const std::int32_t* ids, int begin, int end, std::uint32_t* out,
                     int planes = kEstimateFields);

// Over [begin, end) of a row of estimates: the sum of their squares, the largest, and how
// many are not 0 (covered).
struct EstimateSums {
  std::uint64_t squares = 0;
  std::uint32_t largest = 0, covered = 0;
};
EstimateSums estimateSums(const std::uint32_t* estimates, int begin, int end);

// neighbourFields with each sample's color its polygon's, polygonColors[ids[x]] (the resolve's
// gather), in place of a row of colors.
bool neighbourFieldsById(const Rgba8* polygonColors, const std::int32_t* ids,
                         const EstimateBound* fixedBounds, int begin, int end,
                         EstimateField* fields, std::size_t stride, int planes = kEstimateFields,
                         int shift = 0);

// The span [first, last) of a row's covered samples (ids ≥ 0).
std::array<int, 2> coveredSpan(const std::int32_t* ids, int width);

// Where a pass over the sample grid reads its samples: the planes of ids and colors (width ×
// height), and the fixed bounds per polygon id (fixedBoundOf; an even count). With `polygonColors`,
// the rows outside [ownFirst, ownLast] take each sample's color from its polygon's there (rows
// whose colors another task may be writing, EstimateHook.h); the others read `colors`.
struct EstimateGrid {
  const std::int32_t* ids;
  const Rgba8* colors;
  const EstimateBound* fixedBounds;
  const Rgba8* polygonColors = nullptr;
  int width = 0, height = 0;
  int ownFirst = 0, ownLast = -1;
  int boundShift = 0;  // fixedBounds per block of 2^boundShift ids (neighbourFields)
};

// One task's space for the estimate's pass (QualityRenderer.cpp, EstimateHook.h), kept from
// frame to frame. Every row of fields holds kEstimateFields planes of `stride` words, a zero
// either side of a sample row's `width`.
struct EstimateSpace {
  int width = 0, side = 0;  // sample row width, samples per pixel side
  std::size_t stride = 0;
  std::vector<EstimateField> fields;  // one sample row's fields
  // The row maxima of three consecutive sample rows (row r in maxima[r % 3]): its planes below
  // planes[r % 3] 0 outside the samples `written` says, the others 0 (a grey row keeps
  // kGreyFields until a neighbour that is not grey needs them all); and a row of zeros, for
  // the rows outside the grid.
  std::array<std::vector<EstimateField>, 3> maxima;
  std::array<std::array<int, 2>, 3> written{};
  std::array<int, 3> planes{};
  bool lastGrey = true;  // the last row's fields were grey: the next is tried grey first
  std::array<std::array<int, 2>, 3> spans{};  // the covered samples of each of those rows
  std::vector<EstimateField> zeros;
  std::vector<std::uint32_t> samples;  // the estimates of a pixel row's sample rows
  std::vector<std::uint32_t> pixels;   // a pixel row's, with more than one sample

  void resize(int sampleWidth, int gridSide);
  // Sample row r's row maxima into maxima[r % 3]: the fields of its covered span and of two
  // samples either side (the neighbours' fields that maxima read), the maxima over one sample
  // either side; zero elsewhere.
  void findMaxima(const EstimateGrid& grid, int r);
  // The estimates of sample row r (its maxima and its neighbours' found) into samples' row
  // r % side; 0 outside its covered span where `whole` (else left as they were).
  void estimateSamples(const EstimateGrid& grid, int r, bool whole);
  // Pixel row y's estimates (samples holds its sample rows): the mean of its samples',
  // rounded up, plus 0.5 for rounding that mean, capped; 0 where no sample is covered.
  const std::uint32_t* pixelEstimates();

 private:
  static EstimateField* at(std::vector<EstimateField>& row) { return row.data() + 1; }
  const EstimateField* maximaOf(int r, int height) {
    return r < 0 || r >= height ? at(zeros) : at(maxima[r % 3]);
  }
  // Row r's maxima with all kEstimateFields planes (a grey row's red pair copied).
  void expand(int r);
};

}  // namespace facet::detail
