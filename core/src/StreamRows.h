#pragma once

// Rows of 32-bit values written to an image's plane by streaming stores (the raster's tiles
// to the depth and id planes), a whole SIMD vector a store where the destination is aligned
// to one: the plane's lines are not read before they are written, and a 64-byte store on
// AVX-512 fills a line at once. Run-time dispatched (Highway); every target writes the same
// values, and each call ends with the stores ordered (hwy::FlushStream).

#include <cstddef>
#include <cstdint>

namespace facet::detail {

// Copies `rows` rows of `columns` 32-bit words: row y from from + y·fromStride to
// to + y·toStride (strides in words).
void streamRows(const std::uint32_t* from, std::size_t fromStride, std::uint32_t* to,
                std::size_t toStride, int rows, int columns);

// Writes `value` to `rows` rows of `columns` words, row y at to + y·toStride.
void streamValueRows(std::uint32_t value, std::uint32_t* to, std::size_t toStride, int rows,
                     int columns);

}  // namespace facet::detail
