// Resolve.h, in SIMD lanes: compiled once per instruction set by Highway's foreach_target
// (this file includes itself) and dispatched at run time, as SetupBatch.cpp. A group of
// pixels all showing the background (most of a frame's, around a small object) is one
// store; any other group gathers its polygons' colors (streamed to a large image's plane),
// or converts its depth keys with
// FrameTransform::windowDepth's operations on the same doubles in the same order (the file
// is compiled without contraction into fused multiply-adds, core/CMakeLists.txt), so every
// target gives the scalar conversion's bytes.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "Resolve.cpp"
#include <hwy/cache_control.h>
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "EstimateHook.h"
#include "RasterTriangle.h"
#include "Resolve.h"
#include "StoreRow-inl.h"
#include "facet/IdPlane.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A group of depths: as many as doubles fit in a vector (the conversion's width); their ids
// and keys in half vectors of the same lane count.
using D = hn::ScalableTag<double>;
using DI = hn::Rebind<std::int32_t, D>;
using DF = hn::Rebind<float, D>;

HWY_INLINE std::uint32_t wordOf(Rgba8 color) {
  std::uint32_t word;
  std::memcpy(&word, &color, sizeof word);
  return word;
}

// The color groups are whole vectors of 32-bit words (the depth groups' lane count of
// doubles would be half of one): a whole vector can be streamed (hn::Stream rounds a partial
// one up to 16 bytes).
using DC = hn::ScalableTag<std::int32_t>;
using DCU = hn::RebindToUnsigned<DC>;

// What depthGroup keeps in registers: windowDepth's offset and scale.
struct DepthConstants {
  hn::Vec<D> offset, scale;
};

// What colorRow tells its caller of the groups it colors: nothing (NoSpan), or where the
// groups not all background lie (CoveredGroups), from the test for the background that the
// colors take anyway.
struct NoSpan {
  void seen(const std::int32_t*, const std::int32_t*) {}
};
// The ids [first, last) from the first to the last group (or single pixel) not all
// background a row's colorRow calls saw, null when none; colorRowFindingSpan narrows them to
// the covered pixels.
struct CoveredGroups {
  const std::int32_t* first = nullptr;
  const std::int32_t* last = nullptr;
  void seen(const std::int32_t* begin, const std::int32_t* end) {
    if (!first) first = begin;
    last = end;  // the groups come in the row's order
  }
};

// The colors of pixels [x, x + lanes) of a row, lanes of DC.
template <class Span>
HWY_INLINE hn::Vec<DCU> colorGroup(const std::uint32_t* colors, hn::Vec<DCU> backgroundColor,
                                   const std::int32_t* ids, Span& span) {
  const DC di;
  const DCU du;
  const hn::Vec<DC> id = hn::LoadU(di, ids);
  const hn::Mask<DC> background = id < hn::Zero(di);
  if (hn::AllTrue(di, background)) return backgroundColor;
  span.seen(ids, ids + hn::Lanes(di));
  const hn::Vec<DCU> shown = hn::GatherIndex(du, colors, hn::IfThenZeroElse(background, id));
  return hn::IfThenElse(hn::RebindMask(du, background), backgroundColor, shown);
}

// The window depths of pixels [x, x + lanes) of a row from their keys; 1 for the background.
HWY_INLINE void depthGroup(const DepthConstants& k, const std::int32_t* ids, float* depth) {
  const D d;
  const DI di;
  const DF df;
  const hn::Mask<DI> background = hn::LoadU(di, ids) < hn::Zero(di);
  if (hn::AllTrue(di, background)) {
    hn::StoreU(hn::Set(df, kBackgroundWindowDepth), df, depth);
    return;
  }
  // windowDepth: offset + scale · key, then 0 below (NaN too), 1 above.
  const hn::Vec<D> window = k.offset + k.scale * hn::PromoteTo(d, hn::LoadU(df, depth));
  const hn::Vec<D> zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const hn::Vec<D> clamped =
      hn::IfThenElse(window > zero, hn::IfThenElse(window < one, window, one), zero);
  const hn::Vec<DF> narrowed = hn::DemoteTo(df, clamped);
  hn::StoreU(
      hn::IfThenElse(hn::RebindMask(df, background), hn::Set(df, kBackgroundWindowDepth), narrowed),
      df, depth);
}

// The colors of the polygons a group of pixels shows (lanes of DC from `ids`), fetched toward
// the caches. Shown polygons' colors lie scattered through a plane of one per polygon (2 MB
// at 500k, beyond L2), and a row's neighbouring pixels mostly show polygons far apart in it:
// the lookups were ~60 % of the 500k resolve on AVX3 (bench/core-frame-issue11.md section 40).
HWY_INLINE void prefetchColors(const std::uint32_t* colors, const std::int32_t* ids) {
  const DC di;
  const hn::Vec<DC> id = hn::LoadU(di, ids);
  const hn::Mask<DC> none = id < hn::Zero(di);
  if (hn::AllTrue(di, none)) return;
  HWY_ALIGN std::int32_t lane[hn::MaxLanes(DC())];
  hn::Store(hn::IfThenZeroElse(none, id), di, lane);
  for (std::size_t i = 0; i < hn::Lanes(di); ++i)
    hwy::Prefetch(colors + lane[i]);
}

// The rows of a resolve task below the one colorRow colors, from its first pixel (null: none,
// past the task). While a row is colored, the colors of the polygons the next row shows are
// fetched (its ids, fetched the row before, in cache), and the ids of the row after it: a
// whole row ahead of their use. 128 pixels ahead in the row (section 40) took ~16 % off the
// 500k resolve; a row ahead in its place took ~30 % off that (bench/core-frame-issue11.md
// section 45; both together no better). Within the task: its rows lie in one row of tiles, so the
// next row's ids are read only where its own colors read them.
struct RowsBelow {
  const std::int32_t* next = nullptr;       // ids: the colors they show are prefetched
  const std::int32_t* afterNext = nullptr;  // ids, prefetched
  RowsBelow from(std::size_t x) const {
    return {next ? next + x : nullptr, afterNext ? afterNext + x : nullptr};
  }
};

// One row's colors, `count` pixels from `ids` to `color` (kStream: storeRow's), the groups
// not all background told to `span`.
template <bool kStream, class Span = NoSpan>
HWY_INLINE void colorRow(const std::uint32_t* colors, std::uint32_t background,
                         const std::int32_t* ids, std::uint32_t* color, std::size_t count,
                         const RowsBelow& below, Span&& span = NoSpan{}) {
  const DCU du;
  const hn::Vec<DCU> backgroundColor = hn::Set(du, background);
  storeRow<kStream>(
      du, color, count,
      [&](std::size_t x) {
        if (ids[x] < 0) {
          color[x] = background;
        } else {
          color[x] = colors[ids[x]];
          span.seen(ids + x, ids + x + 1);
        }
      },
      [&](std::size_t x) {
        if (below.next) prefetchColors(colors, below.next + x);
        if (below.afterNext) hwy::Prefetch(below.afterNext + x);
        return colorGroup(colors, backgroundColor, ids + x, span);
      });
}

// `count` pixels of a row given the background's color, ids unread (kStream: storeRow's).
template <bool kStream>
HWY_INLINE void backgroundRow(std::uint32_t background, std::uint32_t* color, std::size_t count) {
  const DCU du;
  const hn::Vec<DCU> backgroundColor = hn::Set(du, background);
  storeRow<kStream>(
      du, color, count, [&](std::size_t x) { color[x] = background; },
      [&](std::size_t) { return backgroundColor; });
}

// Whether the raster found that column x's tile of a tile row shows only the background.
HWY_INLINE bool backgroundTile(const PaintCounts* tileRow, std::size_t x) {
  return tileRow[x / TileGrid::kTileSize].covered == 0;
}

// colorRow, pixels [x0, x0 + count) of a row (ids and color from x0) in runs of whole tiles of
// `tileRow`: a run of tiles showing only the background is written by backgroundRow, its ids
// not read (they stream through the caches for nothing, most of a frame around a small
// object); every other run by colorRow, telling `span` its groups.
template <bool kStream, class Span = NoSpan>
HWY_INLINE void colorRowByTiles(const std::uint32_t* colors, std::uint32_t background,
                                const std::int32_t* ids, std::uint32_t* color, std::size_t x0,
                                std::size_t count, const PaintCounts* tileRow,
                                const RowsBelow& below, Span&& span = NoSpan{}) {
  constexpr auto kTile = static_cast<std::size_t>(TileGrid::kTileSize);
  const std::size_t end = x0 + count;
  for (std::size_t x = x0; x < end;) {
    const bool runIsBackground = backgroundTile(tileRow, x);
    std::size_t runEnd = x;
    do {
      runEnd = std::min(end, (runEnd / kTile + 1) * kTile);
    } while (runEnd < end && backgroundTile(tileRow, runEnd) == runIsBackground);
    if (runIsBackground) {
      backgroundRow<kStream>(background, color + (x - x0), runEnd - x);
    } else {
      colorRow<kStream>(colors, background, ids + (x - x0), color + (x - x0), runEnd - x,
                        below.from(x - x0), span);
    }
    x = runEnd;
  }
}

// colorRow<false> (colorRowByTiles<false> given a tile row: the background's tiles' ids
// unread, as without the estimate), also finding the span [first, last) of the row's covered
// pixels (coveredSpan's, EstimateRows.h; {count, count} when none) from the groups colorRow
// saw not all background (CoveredGroups): the estimate's pass does not read the row's ids
// again for it. The same read-ahead as colorRow's (RowsBelow).
HWY_INLINE std::array<int, 2> colorRowFindingSpan(const std::uint32_t* colors,
                                                  std::uint32_t background, const std::int32_t* ids,
                                                  std::uint32_t* color, std::size_t x0,
                                                  std::size_t count, const PaintCounts* tileRow,
                                                  const RowsBelow& below) {
  CoveredGroups groups;
  if (tileRow) {
    colorRowByTiles<false>(colors, background, ids, color, x0, count, tileRow, below, groups);
  } else {
    colorRow<false>(colors, background, ids, color, count, below, groups);
  }
  const int end = static_cast<int>(count);
  if (!groups.first) return {end, end};
  // Narrowed within the first and the last group to their first and last covered pixel.
  const std::int32_t* first = groups.first;
  const std::int32_t* last = groups.last;
  while (*first < 0)
    ++first;
  while (last[-1] < 0)
    --last;
  return {static_cast<int>(first - ids), static_cast<int>(last - ids)};
}

// The colors of a band of rows within one row of tiles, `tileRow` its tiles' counts (null:
// every id read); rows through `lastRowAhead` (the task's, in the same row of tiles; with the
// estimate also the row below the task, which it reads) are read ahead (RowsBelow).
void ResolveColors(const ResolveContext& context, const PixelBounds& pixels, bool stream,
                   std::array<int, 2>* spans, const PaintCounts* tileRow, int lastRowAhead) {
  const auto* colors = reinterpret_cast<const std::uint32_t*>(context.colors);
  const std::uint32_t background = wordOf(context.background);
  const std::size_t width = static_cast<std::size_t>(pixels.x1 - pixels.x0 + 1);
  for (int y = pixels.y0; y <= pixels.y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * context.width + pixels.x0;
    auto* color = reinterpret_cast<std::uint32_t*>(context.color + row);
    const std::int32_t* ids = context.polygonId + row;
    const auto x0 = static_cast<std::size_t>(pixels.x0);
    const std::size_t rowStep = static_cast<std::size_t>(context.width);
    const RowsBelow below{y < lastRowAhead ? ids + rowStep : nullptr,
                          y + 1 < lastRowAhead ? ids + 2 * rowStep : nullptr};
    if (spans) {  // the estimate's rows: stored plainly, to be read back from the caches
      spans[y - pixels.y0] =
          colorRowFindingSpan(colors, background, ids, color, x0, width, tileRow, below);
    } else if (tileRow && stream) {
      colorRowByTiles<true>(colors, background, ids, color, x0, width, tileRow, below);
    } else if (tileRow) {
      colorRowByTiles<false>(colors, background, ids, color, x0, width, tileRow, below);
    } else if (stream) {
      colorRow<true>(colors, background, ids, color, width, below);
    } else {
      colorRow<false>(colors, background, ids, color, width, below);
    }
  }
  if (stream) hwy::FlushStream();  // weakly ordered: done before the band is handed back
}

void ResolveDepths(const std::int32_t* polygonId, float* depth, int planeWidth,
                   const PixelBounds& pixels, const FrameTransform& transform) {
  const D d;
  const std::size_t lanes = hn::Lanes(d);
  const DepthConstants k{hn::Set(d, transform.depthFromKeyOffset()),
                         hn::Set(d, transform.depthFromKeyScale())};
  const std::size_t width = static_cast<std::size_t>(pixels.x1 - pixels.x0 + 1);
  for (int y = pixels.y0; y <= pixels.y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * planeWidth + pixels.x0;
    const std::int32_t* ids = polygonId + row;
    float* depths = depth + row;
    std::size_t x = 0;
    for (; x + lanes <= width; x += lanes)
      depthGroup(k, ids + x, depths + x);
    for (; x < width; ++x)  // a width that is no multiple of a group
      depths[x] = ids[x] < 0 ? kBackgroundWindowDepth : resolvedDepth(transform, depths[x]);
  }
}

// 64-bit ids, a whole vector of them, from as many 32-bit ids (half a vector).
using DW = hn::ScalableTag<std::int64_t>;
using DWI = hn::Rebind<std::int32_t, DW>;

// ids [0, count) widened (facet/IdPlane.h; kStream: storeRow's).
template <bool kStream>
HWY_INLINE void widenIds(const std::int32_t* ids, std::int64_t* out, std::size_t count,
                         std::int64_t first) {
  const DW dw;
  const DWI di;
  const hn::Vec<DW> shift = hn::Set(dw, first);
  storeRow<kStream>(
      dw, out, count,
      [&](std::size_t i) {
        // By memcpy, as the vectors store: never as an int64_t lvalue (IdPlane.h says why).
        const std::int64_t id = ids[i] < 0 ? -1 : first + ids[i];
        std::memcpy(out + i, &id, sizeof id);
      },
      [&](std::size_t i) {
        // Bitwise, from the 32-bit sign: -1 lanes where negative, else 0 (Highway 1.0's
        // 64-bit IfNegativeThenElse took INT32_MIN's widened lane for not negative on SSSE3).
        const hn::Vec<DWI> id = hn::LoadU(di, ids + i);
        const hn::Vec<DW> negative = hn::PromoteTo(dw, hn::ShiftRight<31>(id));
        return hn::Or(hn::AndNot(negative, hn::Add(hn::PromoteTo(dw, id), shift)), negative);
      });
}

void WidenPolygonIds(const std::int32_t* ids, std::int64_t* out, std::size_t count,
                     std::int64_t first, bool stream) {
  if (stream) {
    widenIds<true>(ids, out, count, first);
    hwy::FlushStream();  // weakly ordered: done before the caller hands the plane on
  } else {
    widenIds<false>(ids, out, count, first);
  }
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {
namespace {

// Rows per resolve step (colored, then handed on: the estimate, ResolvedRowsCallback) and per
// task but for the two below: whole rows, not tiles. The pass is bound by memory, and a tile's
// rows are 256 bytes of each plane, each in a page of its own (a 1080p row of ids is 7.5
// KiB), which the hardware prefetchers do not follow; a band of whole rows streams.
constexpr int kRowsPerTask = 8;
// Without the estimate, tasks of two steps: the rows a task colors are read a row ahead
// (RowsBelow), the first row of a task not (its colors not prefetched, nor the first two rows'
// ids). 16 rows: the 500k resolve -2 % on-CPU at 1 thread (noise), -9 % at 2 (section 45).
constexpr int kRowsPerColoringTask = 16;
// With the estimate, taller bands, resolved kRowsPerTask rows at a time and each step's rows
// estimated right after (ResolvedBandEstimate). A band also finds the fields of the row either
// side of it, with the colors gathered again by polygon id (another task's rows): 2 rows a
// band, 3.5 times a band row's cost each at 500k; a sixteenth of the rows at 32, a quarter at
// 8. 64 was no faster (bench/estimate-cost.md). Its rows are read a row ahead as without the
// estimate, and the row below it too (its colors prefetched while the band's last is
// colored: NeighbourFieldsById ~-65 % on-CPU at 500k); the row above it prefetched while its
// first is colored paid nothing (bench/core-frame-issue11.md section 54).
constexpr int kRowsPerEstimatingTask = 32;
// A band lies in one row of tiles (ResolveContext::tiles).
static_assert(TileGrid::kTileSize % kRowsPerTask == 0 &&
              TileGrid::kTileSize % kRowsPerColoringTask == 0 &&
              kRowsPerColoringTask % kRowsPerTask == 0 &&
              TileGrid::kTileSize % kRowsPerEstimatingTask == 0);

HWY_EXPORT(ResolveColors);
HWY_EXPORT(ResolveDepths);
HWY_EXPORT(WidenPolygonIds);

// The columns [x0, x1) outside which a row of tiles shows only the background: from its first
// to its last covered tile ({0, 0}: none covered). The resolve reads only covered tiles' ids,
// so a ResolvedRowsCallback given these need not read the rest (from memory).
std::array<int, 2> coveredColumns(const PaintCounts* tileRow, int tilesX, int width) {
  int first = -1, last = -1;
  for (int t = 0; t < tilesX; ++t) {
    if (tileRow[t].covered == 0) continue;
    if (first < 0) first = t;
    last = t;
  }
  if (last < 0) return {0, 0};
  return {first * TileGrid::kTileSize, std::min(width, (last + 1) * TileGrid::kTileSize)};
}

}  // namespace

void resolveDepths(const std::int32_t* polygonId, float* depth, int width,
                   const PixelBounds& pixels, const FrameTransform& transform) {
  HWY_DYNAMIC_DISPATCH(ResolveDepths)(polygonId, depth, width, pixels, transform);
}

float resolvedDepth(const FrameTransform& transform, float key) {
  // windowDepth's operations written out, so that this file's flags compile them (an inline
  // windowDepth may be instantiated, and fused, in another file).
  const double depth = transform.depthFromKeyOffset() + transform.depthFromKeyScale() * key;
  return depth > 0.0 ? (depth < 1.0 ? static_cast<float>(depth) : 1.0f) : 0.0f;
}

bool resolveTiles(PhaseRunner& runner, const TileGrid& grid, const ResolveContext& context) {
  const PixelBounds viewport = grid.viewport();
  // The estimate reads the band's colors right after it is resolved: from the caches.
  const bool estimatesRows = context.estimate && context.estimate->rows;
  if (context.estimate && context.estimate->beforeResolve) context.estimate->beforeResolve();
  const int rowsPerTask = estimatesRows ? kRowsPerEstimatingTask : kRowsPerColoringTask;
  const int bands = (viewport.y1 - viewport.y0 + rowsPerTask) / rowsPerTask;
  const std::size_t colorBytes = static_cast<std::size_t>(viewport.x1 - viewport.x0 + 1) *
                                 static_cast<std::size_t>(viewport.y1 - viewport.y0 + 1) *
                                 sizeof(Rgba8);
  const bool stream = !estimatesRows && colorBytes >= kStreamedColorBytes;
  const bool wholeRows = viewport.x0 == 0 && viewport.x1 + 1 == context.width;
  return runner.run(Phase::Resolve, static_cast<std::size_t>(bands), [&](std::size_t b) {
    const int y0 = viewport.y0 + static_cast<int>(b) * rowsPerTask;
    const int y1 = std::min(viewport.y1, y0 + rowsPerTask - 1);
    // The rows read ahead: the task's; with the estimate also the row below it, which the
    // estimate reads next (by id: its colors gathered again, its ids from memory), within the
    // viewport.
    const int lastRowAhead = estimatesRows ? std::min(y1 + 1, viewport.y1) : y1;
    std::optional<ResolvedBandEstimate> estimate;
    if (estimatesRows) {
      estimate.emplace(*context.estimate, context.colors, context.color, context.polygonId,
                       context.width, y0, y1);
    }
    for (int s0 = y0; s0 <= y1; s0 += kRowsPerTask) {  // a step's rows still in cache after it
      const int s1 = std::min(y1, s0 + kRowsPerTask - 1);
      // The rows' covered spans, found as they resolve, for the estimate (whole rows only).
      std::array<int, 2>* spans =
          estimate && wholeRows ? estimate->resolvedSpans() + (s0 - y0) : nullptr;
      const PaintCounts* tileRow =
          context.tiles ? context.tiles + static_cast<std::size_t>(s0 / TileGrid::kTileSize) *
                                              static_cast<std::size_t>(grid.tilesX())
                        : nullptr;
      HWY_DYNAMIC_DISPATCH(ResolveColors)
      (context, {viewport.x0, s0, viewport.x1, s1}, stream, spans, tileRow, lastRowAhead);
      if (estimate) estimate->resolvedThrough(s1);
      if (context.resolvedRows) {
        const auto [shownX0, shownX1] = tileRow && wholeRows
                                            ? coveredColumns(tileRow, grid.tilesX(), context.width)
                                            : std::array<int, 2>{0, context.width};
        (*context.resolvedRows)(*context.target, s0, s1, shownX0, shownX1);
      }
    }
  });
}

}  // namespace facet::detail

namespace facet {

void widenPolygonIds(const std::int32_t* ids, std::int64_t* out, std::size_t count,
                     std::int64_t first, bool stream) {
  using namespace detail;  // the dispatch table, in the anonymous namespace above
  HWY_DYNAMIC_DISPATCH(WidenPolygonIds)(ids, out, count, first, stream);
}

}  // namespace facet
#endif  // HWY_ONCE
