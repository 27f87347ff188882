#pragma once

// The polygons that won a pixel (Renderer::shownPolygons, Raster.h's `shown` plane), which
// every walker of the visible polygons after the raster goes through: the shade routines and
// the error estimate (QualityRenderer).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace facet::detail {

// Calls visit(i) for each i in [begin, end) whose flags[i] is set, in order. Eight flags at a
// time: most polygons of a dense mesh won no pixel (behind others, back faces, or covering no
// pixel center), and a branch per flag would be a coin toss at each shown one. A flag is 0
// or 1 (bit 8k of a little-endian word is flag k), as the raster stores them.
template <class Visit>
void forEachShownPolygon(const std::uint8_t* flags, std::size_t begin, std::size_t end,
                         Visit&& visit) {
  static_assert(std::endian::native == std::endian::little);
  std::size_t polygon = begin;
  for (; polygon + 8 <= end; polygon += 8) {
    std::uint64_t word;
    std::memcpy(&word, flags + polygon, sizeof word);
    while (word != 0) {
      const int bit = std::countr_zero(word);
      visit(polygon + bit / 8);
      word &= word - 1;
    }
  }
  for (; polygon < end; ++polygon) {
    if (flags[polygon]) visit(polygon);
  }
}

// Whether any of flags [begin, end) is set, eight at a time, from the first (a block of
// polygon ids is shown iff one of its polygons is: most shown blocks answer at their first
// eight, a block that shows none reads them all).
inline bool anyShown(const std::uint8_t* flags, std::size_t begin, std::size_t end) {
  std::size_t polygon = begin;
  for (; polygon + 8 <= end; polygon += 8) {
    std::uint64_t word;
    std::memcpy(&word, flags + polygon, sizeof word);
    if (word != 0) return true;
  }
  for (; polygon < end; ++polygon)
    if (flags[polygon]) return true;
  return false;
}

}  // namespace facet::detail
