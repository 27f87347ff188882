#pragma once

// The planes the raster's internals paint into (RasterTriangle.h), for tests that call them
// directly: a kSide × kSide image of depth keys and polygon ids, background everywhere.

#include <cstdint>
#include <vector>

#include "RasterTriangle.h"

namespace facet::testing {

template <int kSideValue>
struct SquarePlanes {
  static constexpr int kSide = kSideValue;
  std::vector<float> depth = std::vector<float>(kSide * kSide, detail::kBackgroundDepthKey);
  std::vector<std::int32_t> ids = std::vector<std::int32_t>(kSide * kSide, -1);
  detail::Planes planes() { return {depth.data(), ids.data(), kSide}; }
};

}  // namespace facet::testing
