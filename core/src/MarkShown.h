#pragma once

// The raster's marking of the polygons a painted tile shows (Raster.h's `shown` plane), read
// from the tile's id plane while it is in cache, in SIMD lanes: run-time dispatched (Highway),
// the same flags and count on every target.

#include <cstddef>
#include <cstdint>

namespace facet::detail {

// Sets shown[id] = 1 (a relaxed atomic store: tiles sharing a polygon may store it at once)
// for every id other than the background's (Framebuffer::kBackgroundId) among `rows` rows of
// `columns` ids, row y at ids + y·stride; returns how many of those ids are not the
// background (the tile's covered pixels).
std::size_t markShownIds(const std::int32_t* ids, std::size_t stride, int rows, int columns,
                         std::uint8_t* shown);

}  // namespace facet::detail
