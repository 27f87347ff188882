#pragma once

/// @file HugePageAllocator.h
/// A std::allocator for the renderer's large buffers (framebuffer planes, per-frame vertex
/// and triangle arrays) that asks Linux for transparent huge pages.
///
/// Why: tiles walk a row-major framebuffer 64 rows at a time, and set-up gathers vertices
/// by index, so a 1080p frame touches thousands of 4 KiB pages in scattered order. Under
/// virtualization every TLB miss costs a two-level page walk; with 2 MiB pages the whole
/// frame fits in a few TLB entries (measured: 1080p, 500k triangles, 2 threads, 39 → 30 ms).
/// Buffers of 2 MiB and more are aligned to 2 MiB and their whole huge pages
/// madvise(MADV_HUGEPAGE)'d before first touch; smaller ones are ordinary allocations. A buffer's
/// tail past its last whole huge page is rounded up to one more when it fills at least half of it
/// (at most 1 MiB unused; e.g. a 1080p plane, 3.96 huge pages), and otherwise left to ordinary
/// pages: rounding every tail up cost a 2.1 MiB buffer 4 MiB (bench/core-frame-issue11.md, the
/// peak-memory section). Elsewhere than Linux it is std::allocator.

#include <cstddef>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace facet {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;
  // Records aligned beyond plain operator new's guarantee (alignas(32), alignas(64)) take the
  // aligned form in the small buffers too, as std::allocator does.
  static constexpr bool kOverAligned = alignof(T) > __STDCPP_DEFAULT_NEW_ALIGNMENT__;
  static constexpr std::align_val_t kAlignment{alignof(T)};

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}  // NOLINT: rebinding, as std::allocator

  // The bytes a buffer of `bytes` (at least kHugePage) is given, and the leading part of them
  // that huge pages back: its whole huge pages, and its tail rounded up to one more when the
  // tail fills at least half of it.
  struct Layout {
    std::size_t allocated, advised;
  };
  static constexpr Layout layoutOf(std::size_t bytes) {
    const std::size_t whole = bytes / kHugePage * kHugePage;
    if (bytes - whole >= kHugePage / 2) return {whole + kHugePage, whole + kHugePage};
    return {bytes, whole};
  }

  T* allocate(std::size_t count) {
    const std::size_t bytes = count * sizeof(T);
    if (bytes < kHugePage) {
      if constexpr (kOverAligned) return static_cast<T*>(::operator new(bytes, kAlignment));
      return static_cast<T*>(::operator new(bytes));
    }
    const Layout layout = layoutOf(bytes);
    void* p = ::operator new (layout.allocated, std::align_val_t{kHugePage});
#if defined(__linux__)
    madvise(p, layout.advised, MADV_HUGEPAGE);  // advice only: failure changes nothing but speed
#endif
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t count) noexcept {
    const std::size_t bytes = count * sizeof(T);
    if (bytes < kHugePage) {
      if constexpr (kOverAligned) {
        ::operator delete(p, kAlignment);
      } else {
        ::operator delete(p);
      }
    } else {
      ::operator delete (p, std::align_val_t{kHugePage});
    }
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const {
    return true;
  }
};

/// A vector whose large allocations use huge pages.
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace facet
