#ifndef vtkFacetBackgroundSpans_h
#define vtkFacetBackgroundSpans_h

#include "vtkType.h"

#include <algorithm>
#include <cstdint>
#include <vector>

/**
 * Which pixels of a kept id plane (the output's CellId) the next frame must write.
 *
 * Per row, the columns [First, Last) outside which the last frame's polygon ids were all
 * background (negative), so that the id plane, which the front end maps every background
 * pixel to the same value (-1), already holds the right value there. A turning view of one
 * object covers a small part of each row: the rest of the 64-bit plane (16.6 MB at 1080p,
 * written at the machine's write bandwidth) need not be written again
 * (bench/filter_overhead.md, id24). A row's write covers the union of the last frame's span
 * and this frame's, so that a pixel that showed a polygon and is background now is written.
 *
 * It relies on the plane being the one the last frame wrote, untouched since (the same
 * assumption as the renderer's kept depth plane): Forget() whenever that is not known.
 */
class vtkFacetBackgroundSpans
{
public:
  /// Nothing known about the plane of a width × height image: every pixel is written.
  void Forget(int width, int height);

  /**
   * Calls write(begin, end) over the pixels of rows [firstRow, endRow) whose id may differ
   * from the plane's, given this frame's polygon ids (width × height, row after row), and
   * records this frame's spans of those rows. Every id of those rows outside columns
   * [shownX0, shownX1) is background (the renderer says so: Renderer::ResolvedRowsCallback),
   * and is not read: the resolve leaves such ids unread, so they are not in cache. Distinct
   * rows may be written from distinct threads at once.
   */
  template<class Write>
  void WriteChanged(const std::int32_t* polygonIds,
    vtkIdType firstRow,
    vtkIdType endRow,
    int shownX0,
    int shownX1,
    Write&& write)
  {
    const vtkIdType width = this->Width;
    shownX0 = std::max(shownX0, 0);
    shownX1 = std::min(shownX1, static_cast<int>(width));
    for (vtkIdType row = firstRow; row < endRow; ++row)
    {
      const vtkIdType start = row * width;
      Span shown{ 0, 0 };
      if (shownX0 < shownX1)
      {
        shown = ShownSpan(polygonIds + start + shownX0, shownX1 - shownX0);
        if (shown.First < shown.Last)
        {
          shown.First += shownX0;
          shown.Last += shownX0;
        }
      }
      Span& last = this->Spans[static_cast<std::size_t>(row)];
      const Span both = Union(last, shown);
      if (both.First < both.Last)
      {
        write(start + both.First, start + both.Last);
      }
      last = shown;
    }
  }

private:
  struct Span
  {
    int First = 0; ///< the first column that may show a polygon
    int Last = 0;  ///< one past the last; First == Last: all background
  };
  /// The columns of one row between its first and last polygon (empty: none).
  static Span ShownSpan(const std::int32_t* ids, int width);
  /// The smallest span holding both (an empty one adds nothing).
  static Span Union(const Span& a, const Span& b)
  {
    if (a.First == a.Last)
    {
      return b;
    }
    if (b.First == b.Last)
    {
      return a;
    }
    return Span{ std::min(a.First, b.First), std::max(a.Last, b.Last) };
  }

  std::vector<Span> Spans;
  int Width = 0;
};

#endif
