// MarkShown.h on every SIMD target: the flags of exactly the ids shown and their count, for
// rows of every length, wholly painted, wholly background or mixed.

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "MarkShown.h"
#include "SetupBatch.h"
#include "facet/Framebuffer.h"

namespace facet::testing {
namespace {

class MarkShown : public EveryTargetTest {};

constexpr std::size_t kStride = 64;
constexpr int kRows = 5;
constexpr std::int32_t kPolygons = 300;

TEST_F(MarkShown, FlagsAndCountOfTheShownIdsOnEveryTarget) {
  // Row 0 all background, row 1 all painted, rows 2-4 mixed (runs of background and of one id).
  std::mt19937 random(7);
  std::vector<std::int32_t> ids(kRows * kStride, Framebuffer::kBackgroundId);
  for (std::size_t x = 0; x < kStride; ++x)
    ids[kStride + x] = static_cast<std::int32_t>(random() % kPolygons);
  for (std::size_t i = 2 * kStride; i < ids.size(); ++i) {
    const unsigned pick = random() % 4;
    ids[i] = pick == 0   ? Framebuffer::kBackgroundId
             : pick == 1 ? ids[i - 1]
                         : static_cast<std::int32_t>(random() % kPolygons);
  }
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    for (const int columns : {0, 1, 3, 4, 7, 8, 9, 15, 16, 17, 31, 33, 63, 64}) {
      std::vector<std::uint8_t> expected(kPolygons, 0), shown(kPolygons, 0);
      std::size_t covered = 0;
      for (int y = 0; y < kRows; ++y) {
        for (int x = 0; x < columns; ++x) {
          const std::int32_t id = ids[y * kStride + x];
          if (id == Framebuffer::kBackgroundId) continue;
          ++covered;
          expected[id] = 1;
        }
      }
      EXPECT_EQ(detail::markShownIds(ids.data(), kStride, kRows, columns, shown.data()), covered)
          << columns << " columns";
      EXPECT_EQ(shown, expected) << columns << " columns";
    }
  }
}

}  // namespace
}  // namespace facet::testing
