// storeRow, for the files Highway compiles once per instruction set (Resolve.cpp,
// StreamRows.cpp): included after <hwy/highway.h> on each of foreach_target's passes, so it
// is guarded per target (Highway's -inl.h convention) rather than once.

#if defined(FACET_STORE_ROW_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FACET_STORE_ROW_INL_H_
#undef FACET_STORE_ROW_INL_H_
#else
#define FACET_STORE_ROW_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// out[0, count) a vector at a time: group(i) gives the lanes from i, one(i) a single value (a
// count that is no multiple of a vector, and with kStream the values before the first aligned
// vector). kStream: by streaming stores, so that the plane is not read before it is written
// (the write-allocate read: 8 MB of colors a 1080p frame, 16 MB of 64-bit ids).
template <bool kStream, class D, class T, class One, class Group>
HWY_INLINE void storeRow(D d, T* out, std::size_t count, const One& one, const Group& group) {
  const std::size_t lanes = hn::Lanes(d);
  std::size_t i = 0;
  if constexpr (kStream) {
    for (; i < count && reinterpret_cast<std::uintptr_t>(out + i) % (lanes * sizeof(T)) != 0; ++i)
      one(i);
  }
  for (; i + lanes <= count; i += lanes) {
    if constexpr (kStream) {
      hn::Stream(group(i), d, out + i);
    } else {
      hn::StoreU(group(i), d, out + i);
    }
  }
  for (; i < count; ++i)
    one(i);
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FACET_STORE_ROW_INL_H_
