// The set-up's bins and binned records (AppendBuffer.h): appends through growth keep every
// record in order, growth is by half (RecordSizing::grown), clear() keeps the storage, and
// settle() sizes it frame by frame from what the frame held (RecordSizing).

#include "AppendBuffer.h"

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "facet/HugePageAllocator.h"

namespace facet::detail {
namespace {

TEST(AppendBuffer, AppendsThroughGrowthInOrderGrowingByHalf) {
  AppendBuffer<std::uint32_t> buffer;
  std::vector<std::uint32_t> expected;
  EXPECT_TRUE(buffer.empty());
  constexpr std::size_t slack = RecordSizing::kSlack<std::uint32_t>;
  std::size_t capacity = 0;
  for (std::uint32_t k = 0; k < 5000; ++k) {
    if (k == capacity) capacity = RecordSizing::grown(capacity, slack);
    buffer.push_back(k * 7u + 1u);
    expected.push_back(k * 7u + 1u);
    ASSERT_EQ(buffer.capacity(), capacity) << "after " << k + 1 << " appends";
  }
  EXPECT_EQ(RecordSizing::grown(0, slack), 8u);  // 32 bytes of 4-byte entries
  EXPECT_EQ(RecordSizing::grown(1, 1), 2u);      // a 40-byte record's buffer grows too
  EXPECT_EQ(RecordSizing::grown(100, 8), 150u);
  const std::span<const std::uint32_t> read = buffer;
  EXPECT_EQ(std::vector<std::uint32_t>(read.begin(), read.end()), expected);
}

TEST(AppendBuffer, ClearKeepsTheStorage) {
  AppendBuffer<std::uint32_t> buffer;
  for (std::uint32_t k = 0; k < 100; ++k)
    buffer.push_back(k);
  const std::uint32_t* storage = buffer.data();
  const std::size_t capacity = buffer.capacity();
  buffer.clear();
  EXPECT_TRUE(buffer.empty());
  for (std::uint32_t k = 0; k < 100; ++k)
    buffer.push_back(k + 1000);
  EXPECT_EQ(buffer.data(), storage);
  EXPECT_EQ(buffer.capacity(), capacity);
  EXPECT_EQ(buffer[99], 1099u);
}

// Appending one of its own records when full: the value is copied before the storage moves.
TEST(AppendBuffer, AppendsItsOwnRecordWhileGrowing) {
  struct Record {
    std::uint64_t a, b, c;
  };
  AppendBuffer<Record, HugePageAllocator<Record>> buffer;
  buffer.push_back({1, 2, 3});
  std::size_t full = 0;
  for (int growths = 0; growths < 12; ++growths) {
    while (buffer.size() < buffer.capacity())
      buffer.push_back(buffer[buffer.size() - 1]);
    full = buffer.capacity();
    buffer.push_back(buffer[buffer.size() - 1]);  // full: it grows holding its own record
    ASSERT_GT(buffer.capacity(), full);
  }
  EXPECT_EQ(buffer.size(), full + 1);
  for (const Record& r : buffer) {
    ASSERT_EQ(r.a, 1u);
    ASSERT_EQ(r.c, 3u);
  }
}

// Records aligned beyond what operator new guarantees (16 bytes): every growth's storage, small
// (an ordinary allocation) or of huge pages, keeps their alignment.
TEST(AppendBuffer, KeepsTheRecordsAlignmentInHugePages) {
  struct alignas(64) Line {
    std::uint32_t word;
  };
  AppendBuffer<Line, HugePageAllocator<Line>> buffer;
  for (std::uint32_t k = 0; k < (1u << 16); ++k) {  // 4 MiB: both kinds of storage
    buffer.push_back({k});
    ASSERT_EQ(reinterpret_cast<std::uintptr_t>(buffer.data()) % alignof(Line), 0u)
        << "capacity " << buffer.capacity();
  }
  EXPECT_EQ(buffer[12345].word, 12345u);
}

// A frame's records held, then settle(): what the next frame finds.
template <class T>
void holdAndSettle(AppendBuffer<T>& buffer, std::size_t records) {
  buffer.clear();
  for (std::size_t k = 0; k < records; ++k)
    buffer.push_back(static_cast<T>(k));
  buffer.settle();
}

// The sizing policy frame by frame: after a frame that held n records the storage leaves
// between n/16 and n/4 (+ 2 x 32 bytes) of headroom; a frame like the previous one, or one
// that drifts by a few percent, takes no storage; a frame of nothing leaves none.
TEST(AppendBuffer, SettleSizesTheStorageFromTheFrameHeld) {
  AppendBuffer<std::uint32_t> buffer;
  constexpr std::size_t slack = RecordSizing::kSlack<std::uint32_t>;
  const auto reallocations = [] { return appendBufferReallocations.load(); };
  const auto inBand = [&](std::size_t held) {
    return buffer.capacity() >= held + held / 16 &&
           buffer.capacity() <= held + held / 4 + 2 * slack;
  };
  holdAndSettle(buffer, 100000);  // a first frame: grown by half from nothing, then sized
  EXPECT_TRUE(buffer.empty());
  EXPECT_EQ(buffer.capacity(), RecordSizing::target(100000, slack));
  EXPECT_TRUE(inBand(100000));

  // The same frame again: no storage taken, none while growing either.
  std::size_t before = reallocations();
  holdAndSettle(buffer, 100000);
  EXPECT_EQ(reallocations() - before, 0u);

  // A turning camera: the count drifts by up to 3 % a frame, up then down. The storage is
  // taken anew only when the drift leaves the band (1/16 to 1/4): a few times in 200 frames,
  // never twice in a row, and never mid-frame (the headroom covers a frame's drift).
  before = reallocations();
  std::size_t held = 100000, renewed = 0;
  bool previousRenewed = false;
  for (int frame = 0; frame < 200; ++frame) {
    held = frame % 100 < 50 ? held + held * (frame % 4) / 100 : held - held * (frame % 4) / 100;
    const std::size_t capacity = buffer.capacity(), count = reallocations();
    holdAndSettle(buffer, held);
    const bool renewedNow = reallocations() != count;
    EXPECT_LE(reallocations() - count, 1u) << "frame " << frame << ": grew mid-frame";
    EXPECT_TRUE(inBand(held)) << "frame " << frame;
    if (renewedNow) {
      EXPECT_FALSE(previousRenewed) << "frame " << frame;
      EXPECT_NE(buffer.capacity(), capacity);
      ++renewed;
    }
    previousRenewed = renewedNow;
  }
  EXPECT_EQ(reallocations() - before, renewed);
  EXPECT_LE(renewed, 200u / 4);

  // A frame twice as large grows mid-frame, and the next frame's storage is sized for it.
  holdAndSettle(buffer, 2 * held);
  EXPECT_TRUE(inBand(2 * held));
  // A frame of nothing (a chunk that binned nothing) leaves no storage; an empty bin keeps none.
  holdAndSettle(buffer, 0);
  EXPECT_EQ(buffer.capacity(), 0u);
  EXPECT_EQ(buffer.data(), nullptr);
  before = reallocations();
  holdAndSettle(buffer, 0);
  EXPECT_EQ(reallocations() - before, 0u);
  // A few entries (a tile's bin at a silhouette) come and go within the first storage (the
  // slack's 8 entries).
  holdAndSettle(buffer, 3);
  before = reallocations();
  for (std::size_t records : {5u, 0u, 8u, 2u, 3u})
    holdAndSettle(buffer, records);
  EXPECT_EQ(reallocations() - before, 0u);
}

// std::vector's lists in a chunk (deferredBack, clippedVertices): the same policy.
TEST(AppendBuffer, SettleVectorSizesLikeTheBuffers) {
  std::vector<std::uint32_t> list;
  for (std::uint32_t k = 0; k < 1000; ++k)
    list.push_back(k);
  EXPECT_EQ(list.capacity(), 1024u);  // doubled: 1/40 headroom is below the band
  settleVector(list);
  EXPECT_TRUE(list.empty());
  EXPECT_EQ(list.capacity(), RecordSizing::target(1000, RecordSizing::kSlack<std::uint32_t>));
  const std::uint32_t* storage = list.data();
  for (std::uint32_t k = 0; k < 1040; ++k)
    list.push_back(k);
  settleVector(list);
  EXPECT_EQ(list.data(), storage);  // kept: 1040 + 1040 / 16 <= 1133
  settleVector(list);
  EXPECT_EQ(list.capacity(), 0u);
}

// A large buffer is given its whole huge pages and its tail rounded up to one more only when the
// tail fills half of it: never more than half a huge page unused, and huge pages for all of a
// buffer but a tail of less than half of one.
TEST(HugePageAllocator, RoundsUpOnlyATailOfHalfAHugePage) {
  using Allocator = HugePageAllocator<char>;
  constexpr std::size_t huge = Allocator::kHugePage;
  for (std::size_t bytes : {huge, huge + 1, huge + huge / 2 - 1, huge + huge / 2, 2 * huge - 1,
                            std::size_t{8294400}, 5 * huge + 4096}) {
    const Allocator::Layout layout = Allocator::layoutOf(bytes);
    EXPECT_GE(layout.allocated, bytes) << bytes;
    EXPECT_LE(layout.allocated - bytes, huge / 2) << bytes;
    EXPECT_EQ(layout.advised % huge, 0u) << bytes;
    EXPECT_LE(layout.advised, layout.allocated) << bytes;
    EXPECT_LT(bytes - std::min(bytes, layout.advised), huge / 2) << bytes;
  }
  EXPECT_EQ(Allocator::layoutOf(huge + 1).allocated, huge + 1);  // not 4 MiB
  EXPECT_EQ(Allocator::layoutOf(8294400).allocated, 4 * huge);   // a 1080p plane: whole pages
  std::vector<char, Allocator> buffer(huge + huge / 4, 'x');     // usable to its last byte
  EXPECT_EQ(buffer.back(), 'x');
}

TEST(AppendBuffer, MovesHandOverTheStorage) {
  std::vector<AppendBuffer<std::uint32_t>> bins(3);
  bins[1].push_back(42);
  const std::uint32_t* storage = bins[1].data();
  bins.resize(1000);  // the bins move to new storage; their records stay where they were
  EXPECT_EQ(bins[1].data(), storage);
  EXPECT_EQ(bins[1].size(), 1u);
  EXPECT_EQ(bins[1][0], 42u);
  AppendBuffer<std::uint32_t> taken = std::move(bins[1]);
  EXPECT_EQ(taken.data(), storage);
}

}  // namespace
}  // namespace facet::detail
