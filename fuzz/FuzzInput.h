#pragma once

// What the fuzz targets share: numbers drawn from the fuzzer's bytes (mostly ordinary, often
// the ones renderers break on), the known-defect switches, and the failure report.

#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string_view>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>
#include <glm/vec3.hpp>

#include "facet/Conventions.h"

namespace facet::fuzz {

// Zeros of both signs, the subnormal and normal extremes, magnitudes whose squares or
// products overflow a double (1e155² > DBL_MAX), and the non-finite values.
// clang-format off
inline constexpr std::array<double, 26> kSpecialDoubles = {
    0.0, -0.0, 0.5, 1.0, -1.0,
    std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
    DBL_MIN, -DBL_MIN, 1e-300, 1e-30, -1e-12, 1e-8,
    1e8, -1e12, 1e18, -1e18, 1e30, 1e155, -1e200, 1e300, -1e300, DBL_MAX, -DBL_MAX,
    std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
// clang-format on

// A double for a quantity whose ordinary values lie in [low, high]. The first byte picks the
// kind: 6 % a special value (above, or −Inf), 3 % an arbitrary bit pattern, 22 % one of nine
// evenly spaced values from low to high (exact ties, coincident and collinear points), else
// uniform in [low, high].
inline double anyDouble(FuzzedDataProvider& in, double low, double high) {
  const auto kind = in.ConsumeIntegral<std::uint8_t>();
  if (kind < 15) return in.PickValueInArray(kSpecialDoubles);
  if (kind < 16) return -std::numeric_limits<double>::infinity();
  if (kind < 24) return std::bit_cast<double>(in.ConsumeIntegral<std::uint64_t>());
  if (kind < 80) return low + (high - low) / 8.0 * in.ConsumeIntegralInRange(0, 8);
  return in.ConsumeFloatingPointInRange(low, high);
}

inline glm::dvec3 anyVector(FuzzedDataProvider& in, double low, double high) {
  const double x = anyDouble(in, low, high);
  const double y = anyDouble(in, low, high);
  return {x, y, anyDouble(in, low, high)};
}

// Where a scene lives: points, lights and camera are center + scale · (ordinary values), so
// the same shapes appear tiny, huge and far from the origin.
struct Placement {
  glm::dvec3 center{0.0};
  double scale = 1.0;

  glm::dvec3 place(const glm::dvec3& local) const { return center + scale * local; }
};

// Half the time the unit scene at the origin; else up to 1e12 away, at a scale of 1e-12 to
// 1e12 (or, one time in eight, any scale at all).
inline Placement anyPlacement(FuzzedDataProvider& in) {
  Placement placement;
  if (in.ConsumeBool()) return placement;
  placement.center = anyVector(in, -1e12, 1e12);
  placement.scale = std::pow(10.0, in.ConsumeIntegralInRange(-12, 12));
  if (in.ConsumeIntegralInRange(0, 7) == 0) placement.scale = anyDouble(in, -1.0, 1.0);
  return placement;
}

// A point id for a cell with `pointCount` points: mostly in range, often one the cell already
// has (repeated ids), 1.5 % out of range.
inline std::int64_t anyPointId(FuzzedDataProvider& in, std::int64_t pointCount,
                               const std::vector<std::int64_t>& cell) {
  const auto kind = in.ConsumeIntegral<std::uint8_t>();
  if (kind < 4) {
    const std::int64_t bad[] = {-1, pointCount, pointCount + 1, INT32_MAX, INT32_MIN, INT64_MIN};
    return in.PickValueInArray(bad);
  }
  if (kind < 40 && !cell.empty())
    return cell[in.ConsumeIntegralInRange<std::size_t>(0, cell.size() - 1)];
  return pointCount == 0 ? 0 : in.ConsumeIntegralInRange<std::int64_t>(0, pointCount - 1);
}

// An image side: mostly small (speed), sometimes up to a few hundred pixels, 2 % invalid.
inline int anySide(FuzzedDataProvider& in) {
  const auto kind = in.ConsumeIntegral<std::uint8_t>();
  if (kind < 6) {
    const int bad[] = {0, -1, INT32_MIN, kMaxImageSide + 1, INT32_MAX};
    return in.PickValueInArray(bad);
  }
  if (kind < 40) return in.ConsumeIntegralInRange(1, 400);
  return in.ConsumeIntegralInRange(1, 48);
}

// The float nearest to x, ±Inf beyond FLT_MAX: what IEEE conversion gives, said explicitly
// (C++ leaves converting an out-of-range double undefined, [conv.double]).
inline float toFloat(double x) {
  if (x > FLT_MAX) return std::numeric_limits<float>::infinity();
  if (x < -FLT_MAX) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(x);
}

// A broken invariant: say which, and abort so that libFuzzer saves the input.
#define FUZZ_CHECK(condition, ...)                                                                 \
  do {                                                                                             \
    if (!(condition)) {                                                                            \
      std::fprintf(stderr, "\nFUZZ_CHECK failed: %s (%s:%d)\n  ", #condition, __FILE__, __LINE__); \
      std::fprintf(stderr, __VA_ARGS__);                                                           \
      std::fprintf(stderr, "\n");                                                                  \
      std::abort();                                                                                \
    }                                                                                              \
  } while (false)

}  // namespace facet::fuzz
