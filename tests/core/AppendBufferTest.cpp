// The set-up's bins and binned records (AppendBuffer.h): appends through growth keep every
// record in order, growth follows std::vector's (so peak memory is unchanged), and clear()
// keeps the storage for the next frame.

#include "AppendBuffer.h"

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "facet/HugePageAllocator.h"

namespace facet::detail {
namespace {

TEST(AppendBuffer, AppendsThroughGrowthInOrderWithStdVectorsCapacities) {
  AppendBuffer<std::uint32_t> buffer;
  std::vector<std::uint32_t> expected;
  EXPECT_TRUE(buffer.empty());
  for (std::uint32_t k = 0; k < 5000; ++k) {
    buffer.push_back(k * 7u + 1u);
    expected.push_back(k * 7u + 1u);
    ASSERT_EQ(buffer.capacity(), expected.capacity()) << "after " << k + 1 << " appends";
  }
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
  for (int growths = 0; growths < 12; ++growths) {
    while (buffer.size() < buffer.capacity())
      buffer.push_back(buffer[buffer.size() - 1]);
    const std::size_t full = buffer.capacity();
    buffer.push_back(buffer[buffer.size() - 1]);  // full: it grows holding its own record
    ASSERT_GT(buffer.capacity(), full);
  }
  EXPECT_EQ(buffer.size(), 2049u);
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
