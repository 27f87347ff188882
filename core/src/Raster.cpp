#include "Raster.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string_view>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "Assert.h"
#include "MarkShown.h"
#include "Resolve.h"
#include "StreamRows.h"
#include "facet/Framebuffer.h"

namespace facet::detail {
namespace {

// A tile's depth keys (window depths once painted) and polygon ids, kTileSize pixels a row: 32 KiB
// that stay in cache from tile to tile. Cleared and painted here, they reach the image's
// planes once, by streaming stores (writeOut): cleared there, every line of the planes was
// read from memory before its first write (a third of the raster's time at 500k triangles).
struct TilePlanes {
  static constexpr int kSide = TileGrid::kTileSize;
  alignas(64) float depth[kSide * kSide];
  alignas(64) std::int32_t polygonId[kSide * kSide];

  // Planes whose index y·kSide + x (image coordinates, inside `tile`) lands here: the
  // painters index every plane as y·width + x − origin.
  Planes planesFor(const PixelBounds& tile) {
    const std::size_t origin = static_cast<std::size_t>(tile.y0) * kSide + tile.x0;
    return {depth, polygonId, kSide, origin};
  }

  void clear(const PixelBounds& tile) {
    const int columns = tile.x1 - tile.x0 + 1;
    for (int y = 0; y <= tile.y1 - tile.y0; ++y) {
      std::fill_n(depth + y * kSide, columns, kBackgroundDepthKey);
      std::fill_n(polygonId + y * kSide, columns, Framebuffer::kBackgroundId);
    }
  }

  // Four values a store.
  void fillDepth(const PixelBounds& tile, float value) {
    const int columns = tile.x1 - tile.x0 + 1;
    for (int y = 0; y <= tile.y1 - tile.y0; ++y) {
      float* row = depth + y * kSide;  // 64-byte aligned
      int x = 0;
#if defined(__SSE2__)
      for (; x + 4 <= columns; x += 4)
        _mm_store_ps(row + x, _mm_set1_ps(value));
#endif
      for (; x < columns; ++x)
        row[x] = value;
    }
  }

  // The image's planes' rows of the tile (a two-pass frame's front pass left them there).
  void readIn(const RasterContext& context, const PixelBounds& tile) {
    const int columns = tile.x1 - tile.x0 + 1;
    for (int y = 0; y <= tile.y1 - tile.y0; ++y) {
      const std::size_t row = static_cast<std::size_t>(tile.y0 + y) * context.width + tile.x0;
      std::copy_n(context.depth + row, columns, depth + y * kSide);
      std::copy_n(context.polygonId + row, columns, polygonId + y * kSide);
    }
  }

  // The tile's rows to the image's planes.
  void writeOut(const RasterContext& context, const PixelBounds& tile) const {
    const std::size_t first = static_cast<std::size_t>(tile.y0) * context.width + tile.x0;
    const int rows = tile.y1 - tile.y0 + 1, columns = tile.x1 - tile.x0 + 1;
    streamRows(reinterpret_cast<const std::uint32_t*>(depth), kSide,
               reinterpret_cast<std::uint32_t*>(context.depth + first),
               static_cast<std::size_t>(context.width), rows, columns);
    streamRows(reinterpret_cast<const std::uint32_t*>(polygonId), kSide,
               reinterpret_cast<std::uint32_t*>(context.polygonId + first),
               static_cast<std::size_t>(context.width), rows, columns);
  }
};

// What a tile with nothing binned leaves in the image's planes, written there directly (no
// tile buffer cleared, painted and copied): the background's id and the depth a painted
// tile's background pixels get (the window depth, or the cleared key).
void writeBackground(const RasterContext& context, const PixelBounds& tile) {
  const std::size_t first = static_cast<std::size_t>(tile.y0) * context.width + tile.x0;
  const int rows = tile.y1 - tile.y0 + 1, columns = tile.x1 - tile.x0 + 1;
  const float depth = context.windowDepths ? kBackgroundWindowDepth : kBackgroundDepthKey;
  streamValueRows(std::bit_cast<std::uint32_t>(depth),
                  reinterpret_cast<std::uint32_t*>(context.depth + first),
                  static_cast<std::size_t>(context.width), rows, columns);
  streamValueRows(std::bit_cast<std::uint32_t>(Framebuffer::kBackgroundId),
                  reinterpret_cast<std::uint32_t*>(context.polygonId + first),
                  static_cast<std::size_t>(context.width), rows, columns);
}

// Whether no chunk binned anything to tile t: front or back, or (`backToo` false: a two-pass
// frame's front pass, before the back faces are binned) front only.
bool nothingBinned(const RasterContext& context, std::size_t t, bool backToo = true) {
  for (const Chunk& chunk : context.chunks) {
    if (!chunk.bins[t].empty() || (backToo && !chunk.backBins[t].empty())) return false;
  }
  return true;
}

// The polygons the tile's final image shows, read from its id plane while it is in cache:
// only they need a color. Flagging winners as they were painted also shaded every polygon that
// won a pixel and lost it again to a nearer one, and cost a load, a test and a store per
// fragment. Returns how many of the tile's pixels show a polygon (PaintCounts::covered):
// counted here rather than per fragment written.
std::size_t markShownPolygons(const RasterContext& context, const TilePlanes& planes,
                              const PixelBounds& tile) {
  return markShownIds(planes.polygonId, TilePlanes::kSide, tile.y1 - tile.y0 + 1,
                      tile.x1 - tile.x0 + 1, context.shown.data());
}

// A bin's triangles lie scattered through their chunk's array (a tile meets many rows of a
// mesh), and their vertices through the frame's: read in bin order, nearly every triangle
// waited for memory twice (perf annotate: half of paintTile's cycles on the load of its first
// vertex reference). So the entry kPrefetchTriangle places ahead is fetched, and the
// vertices of the one kPrefetchVertices ahead, whose record arrived meanwhile (a fragment or
// a small triangle has none).
constexpr std::size_t kPrefetchTriangle = 8;
constexpr std::size_t kPrefetchVertices = 4;

[[gnu::always_inline]] inline void prefetchAhead(const WindowVertex* vertices, const Chunk& chunk,
                                                 std::span<const std::uint32_t> bin,
                                                 std::size_t k) {
  if (k + kPrefetchTriangle < bin.size()) {
    const std::uint32_t entry = bin[k + kPrefetchTriangle];
    if (entry & kFragmentBit) {
      __builtin_prefetch(&chunk.fragments[entry & kBinIndexMask]);
    } else if (entry & kSmallTriangleBit) {
      // 40 bytes: sometimes across two cache lines.
      const auto* record =
          reinterpret_cast<const char*>(&chunk.smallTriangles[entry & kBinIndexMask]);
      __builtin_prefetch(record);
      __builtin_prefetch(record + sizeof(SmallTriangle) - 1);
    } else {
      __builtin_prefetch(&chunk.triangles[entry]);
    }
  }
  if (k + kPrefetchVertices < bin.size()) {
    const std::uint32_t entry = bin[k + kPrefetchVertices];
    if (entry & (kFragmentBit | kSmallTriangleBit)) return;
    for (const std::uint32_t reference : chunk.triangles[entry].vertex)
      __builtin_prefetch(&vertexOf(vertices, chunk, reference));
  }
}

// Paints one bin's entries in order. kCoarse: with the tile's coarse depth
// (Rule::HiddenGeometry, depth test only). kBackBins: a back bin (Chunk::backBins, one pass or
// two), whose records are clamped to their nearest keys (Chunk::smallNearestKeys; its
// triangles and fragments carry their clamp: kClampedEdges, clamped keys). `front`: the
// tile's front faces are painted (back bins, every face drawn).
template <DepthMode kMode, bool kCoarse, bool kBackBins>
[[gnu::always_inline]] inline void paintBin(const RasterContext& context, const Chunk& chunk,
                                            std::span<const std::uint32_t> bin,
                                            const PixelBounds& tile, const Planes& planes,
                                            PaintCounts& counts, CoarseDepth& coarse,
                                            FarthestBlocks* front) {
  for (std::size_t k = 0; k < bin.size(); ++k) {
    prefetchAhead(context.vertices, chunk, bin, k);
    const std::uint32_t index = bin[k];
    if (index & kFragmentBit) {
      const BinnedFragment& f = chunk.fragments[index & kBinIndexMask];
      writeFragment<kMode>(static_cast<std::size_t>(f.y) * planes.width + f.x, f.key, f.polygon,
                           planes, counts);
      continue;
    }
    if (index & kSmallTriangleBit) {  // at most 15 samples: as paintTriangleBehindCoarseDepth
      const std::size_t record = index & kBinIndexMask;
      if constexpr (kBackBins) {
        // Every record of the chunk's back pass (or one pass) has its key (Setup.cpp's setUpRun).
        FACET_ASSERT(record >= chunk.firstKeyedSmall &&
                     record - chunk.firstKeyedSmall < chunk.smallNearestKeys.size());
        paintSmallTriangle<kMode>(chunk.smallTriangles[record],
                                  chunk.smallNearestKeys[record - chunk.firstKeyedSmall], planes,
                                  counts);
      } else {
        paintSmallTriangle<kMode>(chunk.smallTriangles[record], planes, counts);
      }
      continue;
    }
    const BinnedTriangle& tri = chunk.triangles[index];
    const WindowVertex& a = vertexOf(context.vertices, chunk, tri.vertex[0]);
    const WindowVertex& b = vertexOf(context.vertices, chunk, tri.vertex[1]);
    const WindowVertex& c = vertexOf(context.vertices, chunk, tri.vertex[2]);
    const EdgeMask boundary = chunk.boundaryEdges[index];
    if constexpr (kCoarse) {
      paintTriangleBehindCoarseDepth(a, b, c, boundary, tri.polygon, tile, planes, counts, coarse);
    } else if (kMode == DepthMode::Test && kBackBins && boundary != 0) {
      // Only a mesh whose back faces are drawn passes boundary edges (Setup.cpp): the
      // hidden triangles losesEverywhere rejects are its back faces, all in the back bins; a
      // closed mesh's triangles and the front bins' front faces (painted first, over little
      // but background) would only pay for the test.
      if (front != nullptr) {
        paintBackTriangle(a, b, c, boundary, tri.polygon, tile, planes, counts, *front);
      } else {
        paintTriangle<DepthMode::Test, true>(a, b, c, boundary, tri.polygon, tile, planes, counts);
      }
    } else {
      paintTriangle<kMode>(a, b, c, boundary, tri.polygon, tile, planes, counts);
    }
  }
}

// The painted tile's shown polygons marked, its keys made window depths (if asked), and its
// planes written to the image's.
[[gnu::always_inline]] inline void finishTile(const RasterContext& context, TilePlanes& local,
                                              const PixelBounds& tile, PaintCounts& counts) {
  // A tile nothing was written to shows only the background (most tiles around a small
  // object): no id to scan for, and the background's window depth everywhere. This holds
  // because every painter writes ids through writeFragment, which counts them: a painter that
  // wrote planes another way would have to count its writes too.
  const bool painted = counts.written != 0;
  if (painted) counts.covered = markShownPolygons(context, local, tile);
  if (context.windowDepths) {  // the keys become window depths before they leave the cache
    if (painted) {
      const PixelBounds here{0, 0, tile.x1 - tile.x0, tile.y1 - tile.y0};
      resolveDepths(local.polygonId, local.depth, TilePlanes::kSide, here, *context.windowDepths);
    } else {
      local.fillDepth(tile, kBackgroundWindowDepth);
    }
  }
  local.writeOut(context, tile);
}

// Every chunk's front bins, then (the depth test) every chunk's back bins: chunks in draw
// order each time, so that within either facing the polygon drawn first keeps an exact tie.
template <DepthMode kMode, bool kCoarse>
PaintCounts paintTile(const RasterContext& context, std::size_t t, const PixelBounds& tile) {
  if (nothingBinned(context, t)) {  // most tiles around a small object
    writeBackground(context, tile);
    return {};
  }
  TilePlanes local;  // uninitialized: clear() writes what the tile uses
  local.clear(tile);
  const Planes planes = local.planesFor(tile);
  PaintCounts counts;
  CoarseDepth coarse(tile);
  for (const Chunk& chunk : context.chunks)
    paintBin<kMode, kCoarse, false>(context, chunk, chunk.bins[t], tile, planes, counts, coarse,
                                    nullptr);
  FarthestBlocks frontPainted(tile, planes);  // read when a back face first asks
  for (const Chunk& chunk : context.chunks)
    paintBin<kMode, kCoarse, true>(context, chunk, chunk.backBins[t], tile, planes, counts, coarse,
                                   &frontPainted);
  finishTile(context, local, tile, counts);
  return counts;
}

// A two-pass frame's front pass over one tile (paintFrontTiles).
PaintCounts paintFrontOfTile(const RasterContext& context, std::size_t t, const PixelBounds& tile) {
  if (nothingBinned(context, t, /*backToo=*/false)) {
    // Nothing written (counts.written == 0): the back pass starts from cleared planes and
    // writes them all, so only the blocks are kept, every one the cleared key.
    float cleared[FrontDepthBlocks::kPerTile];
    std::fill_n(cleared, FrontDepthBlocks::kPerTile, kBackgroundDepthKey);
    context.frontBlocks->store(t, cleared);
    return {};
  }
  TilePlanes local;
  local.clear(tile);
  const Planes planes = local.planesFor(tile);
  PaintCounts counts;
  CoarseDepth unused(tile);
  for (const Chunk& chunk : context.chunks)
    paintBin<DepthMode::Test, false, false>(context, chunk, chunk.bins[t], tile, planes, counts,
                                            unused, nullptr);
  FarthestBlocks blocks(tile, planes);
  context.frontBlocks->store(t, blocks.measuredBlocks());
  local.writeOut(context, tile);
  return counts;
}

// Its back pass, after the front pass's `counts`.
void paintBackOfTile(const RasterContext& context, std::size_t t, const PixelBounds& tile,
                     PaintCounts& counts) {
  if (counts.written == 0 && nothingBinned(context, t)) {
    writeBackground(context, tile);
    return;
  }
  TilePlanes local;
  if (counts.written != 0) {
    local.readIn(context, tile);
  } else {
    local.clear(tile);  // the planes the front pass wrote: nothing read back
  }
  const Planes planes = local.planesFor(tile);
  CoarseDepth unused(tile);
  float measured[FrontDepthBlocks::kPerTile];
  context.frontBlocks->load(t, measured);
  FarthestBlocks front(tile, planes, measured);
  for (const Chunk& chunk : context.chunks)
    paintBin<DepthMode::Test, false, true>(context, chunk, chunk.backBins[t], tile, planes, counts,
                                           unused, &front);
  finishTile(context, local, tile, counts);
}

}  // namespace

TileRoutineChoice chooseTileRoutine(bool depthTest, bool coarseDepth) {
  if (!depthTest) return {paintTile<DepthMode::Overwrite, false>, "painter's overwrite"};
  if (coarseDepth) return {paintTile<DepthMode::Test, true>, "depth test, hierarchical z"};
  return {paintTile<DepthMode::Test, false>, "depth test"};
}

namespace {
// The shown flags cleared in parts of this many, by every thread, as the raster's first stage
// (FirstStage): on the calling thread alone, 2 MB at 2M polygons were a serial gap of
// 0.10 ms before the painting.
constexpr std::size_t kShownFlagsClearedATask = std::size_t{1} << 18;

std::size_t shownClearTasks(const RasterContext& context) {
  return (context.shown.size() + kShownFlagsClearedATask - 1) / kShownFlagsClearedATask;
}

void clearShownFlags(const RasterContext& context, std::size_t task) {
  const std::size_t begin = task * kShownFlagsClearedATask;
  const std::size_t end = std::min(begin + kShownFlagsClearedATask, context.shown.size());
  std::fill(context.shown.begin() + begin, context.shown.begin() + end, std::uint8_t{0});
}
}  // namespace

bool paintTiles(PhaseRunner& runner, const TileGrid& grid, const RasterContext& context,
                TileRoutine routine, std::vector<PaintCounts>& counts) {
  counts.assign(grid.count(), {});
  auto clear = [&](std::size_t task) { clearShownFlags(context, task); };
  return runner.run(Phase::Raster, grid.count(),
                    [&](std::size_t t) { counts[t] = routine(context, t, grid.bounds(t)); },
                    {shownClearTasks(context), clear});
}

bool paintFrontTiles(PhaseRunner& runner, const TileGrid& grid, const RasterContext& context,
                     std::vector<PaintCounts>& counts) {
  counts.assign(grid.count(), {});
  context.frontBlocks->resize(grid);
  auto clear = [&](std::size_t task) { clearShownFlags(context, task); };
  runner.runUnreported(
      grid.count(),
      [&](std::size_t t) { counts[t] = paintFrontOfTile(context, t, grid.bounds(t)); },
      {shownClearTasks(context), clear});
  return true;
}

bool paintBackTiles(PhaseRunner& runner, const TileGrid& grid, const RasterContext& context,
                    std::vector<PaintCounts>& counts) {
  return runner.run(Phase::Raster, grid.count(),
                    [&](std::size_t t) { paintBackOfTile(context, t, grid.bounds(t), counts[t]); });
}

namespace {
// FACET_TWO_PASS_FRAMES=1 or 0 forces two passes on or off (measurements); else the plan.
std::atomic<TwoPassFrames> twoPasses{[] {
  const char* value = std::getenv("FACET_TWO_PASS_FRAMES");
  if (value == nullptr) return TwoPassFrames::ByPlan;
  if (std::string_view(value) == "1") return TwoPassFrames::On;
  return std::string_view(value) == "0" ? TwoPassFrames::Off : TwoPassFrames::ByPlan;
}()};
}  // namespace

void enableTwoPassFrames(bool on) {
  twoPasses = on ? TwoPassFrames::On : TwoPassFrames::Off;
}

void planTwoPassFrames() {
  twoPasses = TwoPassFrames::ByPlan;
}

TwoPassFrames twoPassFrames() {
  return twoPasses;
}

void addPaintCounts(std::span<const PaintCounts> tiles, RenderStats& stats) {
  for (const PaintCounts& tile : tiles) {
    stats.fragmentsWritten += tile.written;
    stats.pixelsCovered += tile.covered;
    stats.trianglesHidden += tile.hidden;
  }
}

}  // namespace facet::detail
