#include "vtkFacetBackgroundSpans.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace {
// Ids tested at a time: a block of background is found with one AND over it (the scan reads
// 4 B a pixel in cache; the write it saves is 8 B a pixel to memory), two ids to a 64-bit
// word: half the instructions of one id a time, and a loop GCC turns into SIMD lanes
// (bench/filter_overhead.md, filter25).
constexpr int kBlock = 32;
// Background ids are negative: a pair of them keeps both sign bits through the AND.
constexpr std::uint64_t kPairSigns = 0x8000000080000000ull;

bool AllBackground(const std::int32_t* ids)
{
  std::uint64_t all = ~std::uint64_t{ 0 };
  for (int i = 0; i < kBlock; i += 2)
  {
    std::uint64_t pair;
    std::memcpy(&pair, ids + i, sizeof pair);
    all &= pair;
  }
  return (all & kPairSigns) == kPairSigns;
}
}

//------------------------------------------------------------------------------
void vtkFacetBackgroundSpans::Forget(int width, int height)
{
  this->Width = width;
  this->Spans.assign(static_cast<std::size_t>(height), Span{ 0, width });
}

//------------------------------------------------------------------------------
vtkFacetBackgroundSpans::Span vtkFacetBackgroundSpans::ShownSpan(const std::int32_t* ids, int width)
{
  int first = 0;
  while (first + kBlock <= width && AllBackground(ids + first))
  {
    first += kBlock;
  }
  while (first < width && ids[first] < 0)
  {
    ++first;
  }
  if (first == width)
  {
    return Span{ 0, 0 };
  }
  int last = width;
  while (last - kBlock > first && AllBackground(ids + last - kBlock))
  {
    last -= kBlock;
  }
  while (ids[last - 1] < 0)
  {
    --last;
  }
  return Span{ first, last };
}
