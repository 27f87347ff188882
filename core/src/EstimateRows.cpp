// EstimateRows.h, compiled once per instruction set by Highway's foreach_target (this file
// includes itself) and dispatched at run time.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "EstimateRows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "EstimateRows.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void NeighbourMaxima(const Rgba8* center, const Rgba8* neighbours, const float* bounds, int begin,
                     int end, float* out) {
  const auto* c = reinterpret_cast<const std::uint8_t*>(neighbours);
  const auto* p = reinterpret_cast<const std::uint8_t*>(center);
  int x = begin;
#if HWY_TARGET != HWY_SCALAR  // a lane of four bytes (HWY_SCALAR has one lane of any type)
  const hn::ScalableTag<std::uint32_t> du;  // one sample (RGBA) per lane
  const hn::Repartition<std::uint8_t, decltype(du)> d8;
  const hn::Repartition<std::int32_t, decltype(du)> di;
  const hn::Repartition<float, decltype(du)> df;
  const int lanes = static_cast<int>(hn::Lanes(du));
  const auto byte = hn::Set(du, 0xFFu);
  for (; x + lanes <= end; x += lanes) {
    const auto a = hn::LoadU(d8, c + 4 * x), b = hn::LoadU(d8, p + 4 * x);
    const auto difference = hn::BitCast(du, hn::Or(hn::SaturatedSub(a, b), hn::SaturatedSub(b, a)));
    const auto largest =
        hn::Max(hn::Max(hn::And(difference, byte), hn::And(hn::ShiftRight<8>(difference), byte)),
                hn::And(hn::ShiftRight<16>(difference), byte));
    const auto v = hn::ConvertTo(df, hn::BitCast(di, largest)) + hn::LoadU(df, bounds + x);
    hn::StoreU(hn::Max(hn::LoadU(df, out + x), v), df, out + x);
  }
#endif
  for (; x < end; ++x) {  // the same, one sample at a time
    const int r = std::abs(c[4 * x] - p[4 * x]), g = std::abs(c[4 * x + 1] - p[4 * x + 1]),
              bl = std::abs(c[4 * x + 2] - p[4 * x + 2]);
    out[x] = std::max(out[x], static_cast<float>(std::max(std::max(r, g), bl)) + bounds[x]);
  }
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {

HWY_EXPORT(NeighbourMaxima);

void neighbourMaxima(const Rgba8* center, const Rgba8* neighbours, const float* bounds, int begin,
                     int end, float* out) {
  HWY_DYNAMIC_DISPATCH(NeighbourMaxima)(center, neighbours, bounds, begin, end, out);
}

}  // namespace facet::detail
#endif  // HWY_ONCE
