// StreamRows.h on every SIMD target: every word of the rows written, at every alignment of
// the destination and every row length, and nothing outside them.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "SetupBatch.h"
#include "StreamRows.h"

namespace facet::testing {
namespace {

class StreamRows : public EveryTargetTest {};

constexpr std::uint32_t kUntouched = 0xdeadbeef;
constexpr int kRows = 3;

// Whether `to` holds expected(y, x) in the rows' words (`stride` apart) and kUntouched
// everywhere else.
template <class Expected>
std::size_t wrongWords(const std::vector<std::uint32_t>& to, std::size_t offset, std::size_t stride,
                       int columns, const Expected& expected) {
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < to.size(); ++i) {
    const bool before = i < offset;
    const std::size_t y = before ? 0 : (i - offset) / stride,
                      x = before ? 0 : (i - offset) % stride;
    const bool inside = !before && y < kRows && x < static_cast<std::size_t>(columns);
    wrong += to[i] != (inside ? expected(y, x) : kUntouched);
  }
  return wrong;
}

// Words between rows of the destination: 101 leaves each row at another alignment; 128 keeps
// every row at the first one's, and with 64 columns at an aligned offset streamValueRows takes
// its whole-tile path (an image whose width is a multiple of a vector).
constexpr std::size_t kStrides[] = {101, 128};

TEST_F(StreamRows, EveryWordOfTheRowsAndNoOtherOnEveryTarget) {
  std::vector<std::uint32_t> from(kRows * 64);
  for (std::size_t i = 0; i < from.size(); ++i)
    from[i] = static_cast<std::uint32_t>(i * 2654435761u);
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    for (const std::size_t stride : kStrides) {
      for (std::size_t offset = 0; offset < 17; ++offset) {
        for (const int columns : {0, 1, 3, 4, 15, 16, 17, 31, 33, 63, 64}) {
          std::vector<std::uint32_t> to(offset + kRows * stride + 8, kUntouched);
          detail::streamRows(from.data(), 64, to.data() + offset, stride, kRows, columns);
          EXPECT_EQ(wrongWords(to, offset, stride, columns,
                               [&](std::size_t y, std::size_t x) { return from[y * 64 + x]; }),
                    0u)
              << "copied, stride " << stride << ", offset " << offset << ", columns " << columns;
          to.assign(to.size(), kUntouched);
          detail::streamValueRows(0x3f800000u, to.data() + offset, stride, kRows, columns);
          EXPECT_EQ(wrongWords(to, offset, stride, columns,
                               [](std::size_t, std::size_t) { return 0x3f800000u; }),
                    0u)
              << "filled, stride " << stride << ", offset " << offset << ", columns " << columns;
        }
      }
    }
  }
}

}  // namespace
}  // namespace facet::testing
