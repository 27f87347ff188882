#include "HeapCounter.h"

#include <malloc.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <mutex>
#include <new>
#include <utility>

namespace {
std::atomic<std::size_t> inUse{0};
std::atomic<std::size_t> peak{0};

void count(std::size_t bytes) {
  const std::size_t now = inUse.fetch_add(bytes) + bytes;
  std::size_t previous = peak.load();
  while (now > previous && !peak.compare_exchange_weak(previous, now)) {
  }
}

// An aligned allocation counts the bytes asked for (rounded up to its alignment), not
// malloc_usable_size: glibc serves a 2 MiB-aligned request (HugePageAllocator) from an mmap of
// the size plus the alignment and reports the unused tail as usable — up to 2 MiB a buffer of
// address space that is never touched, so never resident. The asked-for sizes wait here for
// the free: aligned allocations are few (the renderer's large buffers), and the table is a
// fixed array so that it allocates nothing itself.
struct AlignedBlock {
  void* pointer = nullptr;
  std::size_t bytes = 0;
};
std::mutex alignedMutex;
std::array<AlignedBlock, 4096> alignedBlocks;
std::size_t alignedSlotsUsed = 0;  // every live block lies below: frees scan no further

void rememberAligned(void* p, std::size_t bytes) {
  const std::lock_guard lock(alignedMutex);
  for (std::size_t i = 0; i < alignedBlocks.size(); ++i) {
    if (alignedBlocks[i].pointer == nullptr) {
      alignedBlocks[i] = {p, bytes};
      alignedSlotsUsed = std::max(alignedSlotsUsed, i + 1);
      return;
    }
  }
  std::abort();  // more live aligned buffers than the table holds: enlarge it
}

// The bytes an aligned block was counted with, forgetting it; 0 for an unaligned one.
std::size_t forgetAligned(void* p) {
  const std::lock_guard lock(alignedMutex);
  for (std::size_t i = 0; i < alignedSlotsUsed; ++i) {
    if (alignedBlocks[i].pointer == p) return std::exchange(alignedBlocks[i], {}).bytes;
  }
  return 0;
}

void* allocate(std::size_t size, std::size_t alignment = 0) {
  if (alignment == 0) {
    void* p = std::malloc(size == 0 ? 1 : size);
    if (!p) throw std::bad_alloc();
    count(malloc_usable_size(p));
    return p;
  }
  const std::size_t bytes = (size + alignment - 1) / alignment * alignment;
  void* p = std::aligned_alloc(alignment, bytes == 0 ? alignment : bytes);
  if (!p) throw std::bad_alloc();
  rememberAligned(p, bytes);
  count(bytes);
  return p;
}

void release(void* p) {
  if (!p) return;
  const std::size_t aligned = forgetAligned(p);
  inUse.fetch_sub(aligned != 0 ? aligned : malloc_usable_size(p));
  std::free(p);
}

}  // namespace

void* operator new(std::size_t size) {
  return allocate(size);
}
void* operator new[](std::size_t size) {
  return allocate(size);
}
void operator delete(void* p) noexcept {
  release(p);
}
void operator delete[](void* p) noexcept {
  release(p);
}
void operator delete(void* p, std::size_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  release(p);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  return allocate(size, static_cast<std::size_t>(alignment));
}
void operator delete(void* p, std::align_val_t) noexcept {
  release(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  release(p);
}

namespace facet::bench {
std::size_t heapBytesInUse() {
  return inUse.load();
}
std::size_t heapPeakBytes() {
  return peak.load();
}
void resetHeapPeak() {
  peak.store(inUse.load());
}
}  // namespace facet::bench
