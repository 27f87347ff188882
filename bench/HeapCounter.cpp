#include "HeapCounter.h"

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<std::size_t> inUse{0};
std::atomic<std::size_t> peak{0};

void* allocate(std::size_t size, std::size_t alignment = 0) {
  void* p = alignment == 0
                ? std::malloc(size == 0 ? 1 : size)
                : std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
  if (!p) throw std::bad_alloc();
  const std::size_t now = inUse.fetch_add(malloc_usable_size(p)) + malloc_usable_size(p);
  std::size_t previous = peak.load();
  while (now > previous && !peak.compare_exchange_weak(previous, now)) {
  }
  return p;
}

void release(void* p) {
  if (!p) return;
  inUse.fetch_sub(malloc_usable_size(p));
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
