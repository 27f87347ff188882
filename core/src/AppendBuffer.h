#pragma once

// A growable array of trivially copyable records whose append is always inlined and whose
// growth never is: the set-up's bins and binned records.
//
// Why not std::vector: its push_back inlines only while GCC's inline-unit-growth budget for
// the translation unit lasts. Setup.cpp shares a unity file whose budget ran out more than
// once (bench/core-frame-issue11.md sections 19 and 20), and the set-up then called
// std::vector::emplace_back out of line for every bin entry (set-up x1.13 at 500k). Here the
// append is a compare, a store and an increment in the caller whatever the budget, and the
// rare reallocation is a call off its path.
//
// Growth is std::vector's (libstdc++: doubling, from one), so peak memory is unchanged; the
// storage is kept by clear() for the next frame.

#include <cstddef>
#include <cstring>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>

namespace facet::detail {

template <class T, class Allocator = std::allocator<T>>
class AppendBuffer {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "records are copied by memcpy when the buffer grows");
  using Traits = std::allocator_traits<Allocator>;
  static_assert(Traits::is_always_equal::value,
                "grow() and release() each make their own allocator: it must have no state");

 public:
  AppendBuffer() = default;
  AppendBuffer(const AppendBuffer&) = delete;
  AppendBuffer& operator=(const AppendBuffer&) = delete;
  AppendBuffer(AppendBuffer&& other) noexcept
      : begin_(std::exchange(other.begin_, nullptr)),
        end_(std::exchange(other.end_, nullptr)),
        capacityEnd_(std::exchange(other.capacityEnd_, nullptr)) {}
  AppendBuffer& operator=(AppendBuffer&& other) noexcept {
    if (this != &other) {
      release();
      begin_ = std::exchange(other.begin_, nullptr);
      end_ = std::exchange(other.end_, nullptr);
      capacityEnd_ = std::exchange(other.capacityEnd_, nullptr);
    }
    return *this;
  }
  ~AppendBuffer() { release(); }

  // `value` by value: it may be a record of this buffer, which grow() moves.
  [[gnu::always_inline]] void push_back(T value) {
    if (end_ == capacityEnd_) [[unlikely]]
      grow();
    *end_++ = value;
  }

  void clear() { end_ = begin_; }
  std::size_t size() const { return static_cast<std::size_t>(end_ - begin_); }
  std::size_t capacity() const { return static_cast<std::size_t>(capacityEnd_ - begin_); }
  bool empty() const { return end_ == begin_; }
  T* data() { return begin_; }
  const T* data() const { return begin_; }
  T* begin() { return begin_; }
  T* end() { return end_; }
  const T* begin() const { return begin_; }
  const T* end() const { return end_; }
  T& operator[](std::size_t k) { return begin_[k]; }
  const T& operator[](std::size_t k) const { return begin_[k]; }
  operator std::span<const T>() const { return {begin_, end_}; }  // NOLINT: read as a span

 private:
  // Not [[gnu::cold]]: GCC then sizes the copy as `rep movsb`, one instruction a byte to
  // callgrind; the call site's [[unlikely]] already keeps it off the appends' path.
  [[gnu::noinline]] void grow() {
    const std::size_t count = size();
    const std::size_t grown = count == 0 ? 1 : 2 * count;
    Allocator allocator;
    T* const storage = Traits::allocate(allocator, grown);
    if (count != 0) std::memcpy(storage, begin_, count * sizeof(T));
    release();
    begin_ = storage;
    end_ = storage + count;
    capacityEnd_ = storage + grown;
  }

  void release() {
    if (begin_ == nullptr) return;
    Allocator allocator;
    Traits::deallocate(allocator, begin_, capacity());
  }

  T* begin_ = nullptr;
  T* end_ = nullptr;
  T* capacityEnd_ = nullptr;
};

}  // namespace facet::detail
