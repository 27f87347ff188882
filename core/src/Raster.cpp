#include "Raster.h"

#include <algorithm>
#include <atomic>

#include "Resolve.h"
#include "facet/Framebuffer.h"

namespace facet::detail {
namespace {

void clearTile(const RasterContext& context, const PixelBounds& tile) {
  for (int y = tile.y0; y <= tile.y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * context.width;
    std::fill(context.depth + row + tile.x0, context.depth + row + tile.x1 + 1,
              kBackgroundDepthKey);
    std::fill(context.polygonId + row + tile.x0, context.polygonId + row + tile.x1 + 1,
              Framebuffer::kBackgroundId);
  }
}

// The polygons the tile's final image shows, read from its id plane while it is in cache:
// only they need a color. Flagging winners as they were painted also shaded every polygon that
// won a pixel and lost it again to a nearer one, and cost a load, a test and a store per
// fragment. Tiles sharing a polygon may store the same 1 at once: relaxed atomics make that
// benign. Four pixels at a time: a run of background (−1, all bits set) is skipped whole.
void markShownPolygons(const RasterContext& context, const PixelBounds& tile) {
  static_assert(Framebuffer::kBackgroundId == -1);
  std::uint8_t* const shown = context.shown.data();
  const auto mark = [shown](std::int32_t id) {
    if (id != Framebuffer::kBackgroundId) {
      std::atomic_ref<std::uint8_t>(shown[static_cast<std::size_t>(id)])
          .store(1, std::memory_order_relaxed);
    }
  };
  const int columns = tile.x1 - tile.x0 + 1;
  for (int y = tile.y0; y <= tile.y1; ++y) {
    const std::int32_t* ids =
        context.polygonId + static_cast<std::size_t>(y) * context.width + tile.x0;
    int x = 0;
    for (; x + 4 <= columns; x += 4) {
      if ((ids[x] & ids[x + 1] & ids[x + 2] & ids[x + 3]) == Framebuffer::kBackgroundId) continue;
      mark(ids[x]), mark(ids[x + 1]), mark(ids[x + 2]), mark(ids[x + 3]);
    }
    for (; x < columns; ++x)
      mark(ids[x]);
  }
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
                                                 const std::vector<std::uint32_t>& bin,
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
// (Rule::HiddenGeometry, depth test only).
template <DepthMode kMode, bool kCoarse>
[[gnu::always_inline]] inline void paintBin(const RasterContext& context, const Chunk& chunk,
                                            const std::vector<std::uint32_t>& bin,
                                            const PixelBounds& tile, const Planes& planes,
                                            PaintCounts& counts, CoarseDepth& coarse) {
  for (std::size_t k = 0; k < bin.size(); ++k) {
    prefetchAhead(context.vertices, chunk, bin, k);
    const std::uint32_t index = bin[k];
    if (index & kFragmentBit) {
      const BinnedFragment& f = chunk.fragments[index & kBinIndexMask];
      writeFragment<kMode>(static_cast<std::size_t>(f.y) * context.width + f.x, f.key, f.polygon,
                           planes, counts);
      continue;
    }
    if (index & kSmallTriangleBit) {  // at most 15 samples: as paintTriangleBehindCoarseDepth
      paintSmallTriangle<kMode>(chunk.smallTriangles[index & kBinIndexMask], planes, counts);
      continue;
    }
    const BinnedTriangle& tri = chunk.triangles[index];
    const WindowVertex& a = vertexOf(context.vertices, chunk, tri.vertex[0]);
    const WindowVertex& b = vertexOf(context.vertices, chunk, tri.vertex[1]);
    const WindowVertex& c = vertexOf(context.vertices, chunk, tri.vertex[2]);
    const EdgeMask boundary = chunk.boundaryEdges[index];
    if constexpr (kCoarse) {
      paintTriangleBehindCoarseDepth(a, b, c, boundary, tri.polygon, tile, planes, counts, coarse);
    } else if (kMode == DepthMode::Test && boundary != 0) {
      // Only a mesh whose back faces are drawn passes boundary edges (Setup.cpp): the
      // hidden triangles losesEverywhere rejects are its back faces; a closed mesh's
      // triangles would only pay for the test.
      paintTriangle<DepthMode::Test, true>(a, b, c, boundary, tri.polygon, tile, planes, counts);
    } else {
      paintTriangle<kMode>(a, b, c, boundary, tri.polygon, tile, planes, counts);
    }
  }
}

// Every chunk's front bins, then (the depth test) every chunk's back bins: chunks in draw
// order each time, so that within either facing the polygon drawn first keeps an exact tie.
template <DepthMode kMode, bool kCoarse>
PaintCounts paintTile(const RasterContext& context, std::size_t t, const PixelBounds& tile) {
  clearTile(context, tile);
  const Planes planes{context.color, context.depth, context.polygonId, context.width};
  PaintCounts counts;
  CoarseDepth coarse(tile);
  for (const auto bins : {&Chunk::bins, &Chunk::backBins}) {
    for (const Chunk& chunk : context.chunks)
      paintBin<kMode, kCoarse>(context, chunk, (chunk.*bins)[t], tile, planes, counts, coarse);
  }
  markShownPolygons(context, tile);
  if (context.windowDepths) {
    resolveDepths(context.polygonId, context.depth, context.width, tile, *context.windowDepths);
  }
  return counts;
}

}  // namespace

TileRoutineChoice chooseTileRoutine(bool depthTest, bool coarseDepth) {
  if (!depthTest) return {paintTile<DepthMode::Overwrite, false>, "painter's overwrite"};
  if (coarseDepth) return {paintTile<DepthMode::Test, true>, "depth test, hierarchical z"};
  return {paintTile<DepthMode::Test, false>, "depth test"};
}

bool paintTiles(PhaseRunner& runner, const TileGrid& grid, const RasterContext& context,
                TileRoutine routine, std::vector<PaintCounts>& counts) {
  std::fill(context.shown.begin(), context.shown.end(), std::uint8_t{0});
  counts.assign(grid.count(), {});
  return runner.run(Phase::Raster, grid.count(),
                    [&](std::size_t t) { counts[t] = routine(context, t, grid.bounds(t)); });
}

void addPaintCounts(std::span<const PaintCounts> tiles, RenderStats& stats) {
  for (const PaintCounts& tile : tiles) {
    stats.fragmentsWritten += tile.written;
    stats.pixelsCovered += tile.covered;
    stats.trianglesHidden += tile.hidden;
  }
}

}  // namespace facet::detail
