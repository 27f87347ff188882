// StreamRows.h, in SIMD lanes: compiled once per instruction set by Highway's foreach_target
// (this file includes itself) and dispatched at run time, as Resolve.cpp. The planes hold
// floats or ints: single words are copied with memcpy, whatever their type.

#include <cstddef>
#include <cstdint>
#include <cstring>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "StreamRows.cpp"
#include <hwy/cache_control.h>
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "StoreRow-inl.h"
#include "StreamRows.h"
#include "TileGrid.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DU = hn::ScalableTag<std::uint32_t>;

void StreamRows(const std::uint32_t* from, std::size_t fromStride, std::uint32_t* to,
                std::size_t toStride, int rows, int columns) {
  const DU d;
  const auto count = static_cast<std::size_t>(columns);
  for (int y = 0; y < rows; ++y) {
    const std::uint32_t* source = from + static_cast<std::size_t>(y) * fromStride;
    std::uint32_t* target = to + static_cast<std::size_t>(y) * toStride;
    storeRow<true>(
        d, target, count,
        [&](std::size_t i) { std::memcpy(target + i, source + i, sizeof *target); },
        [&](std::size_t i) { return hn::LoadU(d, source + i); });
  }
  hwy::FlushStream();  // weakly ordered: done before the caller hands the rows on
}

// Whether every row of `columns` words from `to`, `toStride` apart, starts at a vector's
// alignment and holds whole vectors.
bool wholeAlignedVectors(DU d, const std::uint32_t* to, std::size_t toStride, int columns) {
  const std::size_t lanes = hn::Lanes(d);
  return reinterpret_cast<std::uintptr_t>(to) % (lanes * sizeof *to) == 0 &&
         toStride % lanes == 0 && static_cast<std::size_t>(columns) % lanes == 0;
}

void StreamValueRows(std::uint32_t value, std::uint32_t* to, std::size_t toStride, int rows,
                     int columns) {
  const DU d;
  const hn::Vec<DU> values = hn::Set(d, value);
  // A whole tile's rows at aligned addresses (every empty tile of an image whose width is a
  // multiple of a vector's words): the count a constant, unrolled, and no alignment test a
  // row. storeRow's general loop cost 57 instructions a row of 64 words on AVX2 (3.0 M a
  // frame for the 416 empty tiles of the 500k closed sphere).
  constexpr int kTileColumns = TileGrid::kTileSize;
  if (columns == kTileColumns && wholeAlignedVectors(d, to, toStride, columns)) {
    for (int y = 0; y < rows; ++y) {
      std::uint32_t* target = to + static_cast<std::size_t>(y) * toStride;
      HWY_UNROLL(16)
      for (std::size_t i = 0; i < kTileColumns; i += hn::Lanes(d))
        hn::Stream(values, d, target + i);
    }
    hwy::FlushStream();
    return;
  }
  const auto count = static_cast<std::size_t>(columns);
  for (int y = 0; y < rows; ++y) {
    std::uint32_t* target = to + static_cast<std::size_t>(y) * toStride;
    storeRow<true>(
        d, target, count, [&](std::size_t i) { std::memcpy(target + i, &value, sizeof value); },
        [&](std::size_t) { return values; });
  }
  hwy::FlushStream();
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {
namespace {
HWY_EXPORT(StreamRows);
HWY_EXPORT(StreamValueRows);
}  // namespace

void streamRows(const std::uint32_t* from, std::size_t fromStride, std::uint32_t* to,
                std::size_t toStride, int rows, int columns) {
  HWY_DYNAMIC_DISPATCH(StreamRows)(from, fromStride, to, toStride, rows, columns);
}

void streamValueRows(std::uint32_t value, std::uint32_t* to, std::size_t toStride, int rows,
                     int columns) {
  HWY_DYNAMIC_DISPATCH(StreamValueRows)(value, to, toStride, rows, columns);
}

}  // namespace facet::detail
#endif  // HWY_ONCE
