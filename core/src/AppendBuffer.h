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
// Its storage is sized frame by frame (settle(), called once a frame's records are painted):
// kept while it leaves the frame's records between 1/16 and 1/4 of headroom, else taken anew
// (nothing to copy) for them plus 1/8 (RecordSizing). So a turning camera's frames reuse it, a
// frame like the previous one takes no storage, and the storage kept stays close to what a
// frame holds (bench/core-frame-issue11.md section 69: with std::vector's doubling, kept from
// the largest frame, the 500k frame's ~9 MiB of records kept 12-17 MiB). A frame that outgrows
// it grows it by half (the first frame, from nothing: kSlack records, then by half).
#include <atomic>
#include <cstddef>
#include <cstring>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>

namespace facet::detail {

// Tests and measurements: how many times any AppendBuffer took new storage (its growth and
// settle()'s resizing), counted off the appends' path.
inline std::atomic<std::size_t> appendBufferReallocations{0};

// The storage a frame's buffer of records keeps for the next frame, from what it held: see the
// header comment. `slack` records (32 bytes' worth) on top keep a buffer of a few records, a
// tile's bin, from being taken anew for one or two records more or less.
struct RecordSizing {
  template <class T>
  static constexpr std::size_t kSlack = sizeof(T) >= 32 ? 1 : 32 / sizeof(T);

  // Whether `capacity` is kept for a frame after one that held `held` records.
  static constexpr bool keeps(std::size_t capacity, std::size_t held, std::size_t slack) {
    return capacity >= held + held / 16 && capacity <= held + held / 4 + 2 * slack;
  }
  // The capacity taken when it is not (none after a frame that held nothing).
  static constexpr std::size_t target(std::size_t held, std::size_t slack) {
    return held == 0 ? 0 : held + held / 8 + slack;
  }
  // A buffer found full mid-frame: grown by half, rounded up (std::vector doubles), from
  // `slack`.
  static constexpr std::size_t grown(std::size_t count, std::size_t slack) {
    return count == 0 ? slack : count + (count + 1) / 2;
  }
};

// AppendBuffer::settle for a std::vector: cleared, and its storage taken anew (empty: nothing
// copied) unless RecordSizing keeps it.
template <class Vector>
void settleVector(Vector& vector) {
  using T = typename Vector::value_type;
  constexpr std::size_t slack = RecordSizing::kSlack<T>;
  const std::size_t held = vector.size();
  vector.clear();
  if (RecordSizing::keeps(vector.capacity(), held, slack)) return;
  appendBufferReallocations.fetch_add(1, std::memory_order_relaxed);
  Vector().swap(vector);
  vector.reserve(RecordSizing::target(held, slack));
}

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
  // Ends a frame: cleared, and its storage sized from the records it held for the next
  // frame: kept, or taken anew with nothing to copy (RecordSizing).
  void settle() {
    const std::size_t held = size();
    end_ = begin_;
    if (!RecordSizing::keeps(capacity(), held, kSlack))
      reallocate(RecordSizing::target(held, kSlack));
  }
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
    const std::size_t grown = RecordSizing::grown(count, kSlack);
    appendBufferReallocations.fetch_add(1, std::memory_order_relaxed);
    Allocator allocator;
    T* const storage = Traits::allocate(allocator, grown);
    if (count != 0) std::memcpy(storage, begin_, count * sizeof(T));
    release();
    begin_ = storage;
    end_ = storage + count;
    capacityEnd_ = storage + grown;
  }

  // Empty: the old storage goes first, then the new is taken (none for 0).
  [[gnu::noinline]] void reallocate(std::size_t capacity) {
    appendBufferReallocations.fetch_add(1, std::memory_order_relaxed);
    release();
    begin_ = end_ = capacityEnd_ = nullptr;
    if (capacity == 0) return;
    Allocator allocator;
    begin_ = end_ = Traits::allocate(allocator, capacity);
    capacityEnd_ = begin_ + capacity;
  }

  void release() {
    if (begin_ == nullptr) return;
    Allocator allocator;
    Traits::deallocate(allocator, begin_, capacity());
  }

  static constexpr std::size_t kSlack = RecordSizing::kSlack<T>;

  T* begin_ = nullptr;
  T* end_ = nullptr;
  T* capacityEnd_ = nullptr;
};

}  // namespace facet::detail
