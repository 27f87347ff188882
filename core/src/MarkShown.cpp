// MarkShown.h, in SIMD lanes: compiled once per instruction set by Highway's foreach_target
// (this file includes itself) and dispatched at run time, as StreamRows.cpp.

#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "MarkShown.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "MarkShown.h"
#include "facet/Framebuffer.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DI = hn::ScalableTag<std::int32_t>;

inline void markShown(std::uint8_t* shown, std::int32_t id) {
  std::atomic_ref<std::uint8_t>(shown[static_cast<std::size_t>(id)])
      .store(1, std::memory_order_relaxed);
}

// The lanes of `marks` (a mask's bits, lane k at bit k) marked from row + x.
inline void markLanes(std::uint64_t marks, const std::int32_t* row, std::size_t x,
                      std::uint8_t* shown) {
  while (marks != 0) {
    markShown(shown, row[x + static_cast<std::size_t>(__builtin_ctzll(marks))]);
    marks &= marks - 1;
  }
}

std::size_t MarkShownIds(const std::int32_t* ids, std::size_t stride, int rows, int columns,
                         std::uint8_t* shown) {
  const DI d;
  const std::size_t lanes = hn::Lanes(d);
  const auto background = hn::Set(d, Framebuffer::kBackgroundId);
  const auto count = static_cast<std::size_t>(columns);
  std::size_t covered = 0;
  for (int y = 0; y < rows; ++y) {
    const std::int32_t* row = ids + static_cast<std::size_t>(y) * stride;
    std::size_t x = 0;
    for (; x + lanes <= count; x += lanes) {
      const auto painted = hn::Ne(hn::LoadU(d, row + x), background);
      const std::size_t paintedLanes = hn::CountTrue(d, painted);
      if (paintedLanes == 0) continue;  // a run of background (most of a tile's edge)
      covered += paintedLanes;
      if (paintedLanes == lanes) {  // inside the object: a load and a store a pixel
        HWY_UNROLL(16)
        for (std::size_t k = 0; k < lanes; ++k)
          markShown(shown, row[x + k]);
        continue;
      }
      static_assert(std::endian::native == std::endian::little);
      std::uint64_t bits = 0;  // lane k at bit k
      hn::StoreMaskBits(d, painted, reinterpret_cast<std::uint8_t*>(&bits));
      markLanes(bits, row, x, shown);
    }
    for (; x < count; ++x) {
      if (row[x] == Framebuffer::kBackgroundId) continue;
      ++covered;
      markShown(shown, row[x]);
    }
  }
  return covered;
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {
namespace {
HWY_EXPORT(MarkShownIds);
}  // namespace

std::size_t markShownIds(const std::int32_t* ids, std::size_t stride, int rows, int columns,
                         std::uint8_t* shown) {
  return HWY_DYNAMIC_DISPATCH(MarkShownIds)(ids, stride, rows, columns, shown);
}

}  // namespace facet::detail
#endif  // HWY_ONCE
