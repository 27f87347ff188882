#include "vtkFacetBackgroundSpans.h"

#include <algorithm>

namespace {
// Ids tested at a time: a block of background is found with one AND over it, which the
// compiler turns into SIMD lanes (the scan reads 4 B a pixel in cache; the write it saves is
// 8 B a pixel to memory).
constexpr int kBlock = 16;

bool AllBackground(const std::int32_t* ids, int count)
{
  std::int32_t all = -1;
  for (int i = 0; i < count; ++i)
  {
    all &= ids[i];
  }
  return all < 0; // every id negative
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
  while (first + kBlock <= width && AllBackground(ids + first, kBlock))
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
  while (last - kBlock > first && AllBackground(ids + last - kBlock, kBlock))
  {
    last -= kBlock;
  }
  while (ids[last - 1] < 0)
  {
    --last;
  }
  return Span{ first, last };
}
