// The resolve (Resolve.h, SIMD lanes) against its definition pixel by pixel, on every
// instruction set this CPU has: the polygon's color or the background's (resolveTiles), and
// FrameTransform::windowDepth of the key (resolveDepths tile by tile, as the raster calls it: 1
// for the background; detail::resolvedDepth, the library's scalar path, compiled as the lanes
// are), for perspective and parallel cameras, keys of every magnitude, images whose width is
// no multiple of a group, colors stored plainly and streamed.

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <new>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "EstimateHook.h"
#include "EstimateRows.h"
#include "FrameTransform.h"
#include "PhaseRunner.h"
#include "RasterTriangle.h"
#include "Resolve.h"
#include "SetupBatch.h"
#include "ThreadPool.h"
#include "facet/Camera.h"
#include "facet/IdPlane.h"

namespace facet::testing {
namespace {

struct Planes {
  std::vector<Rgba8> color;
  std::vector<float> depth;
  std::vector<std::int32_t> ids;
};

// Every fourth pixel shows a polygon, in runs, so that groups are all background, all shown
// or mixed; keys from the near plane's 1 to far beyond the far plane, and the stiff ones.
Planes randomPlanes(int width, int height, int polygons, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> id(0, polygons - 1), run(1, 40);
  std::uniform_real_distribution<float> exponent(-30.0f, 2.0f);
  const float stiff[] = {0.0f,
                         -0.0f,
                         1.0f,
                         std::numeric_limits<float>::max(),
                         -std::numeric_limits<float>::max(),
                         std::numeric_limits<float>::denorm_min()};
  Planes p;
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  p.color.assign(pixels, Rgba8{1, 2, 3, 4});  // overwritten everywhere
  for (std::size_t i = 0; i < pixels;) {
    const bool shown = random() % 4 == 0;
    for (int k = run(random); k > 0 && i < pixels; --k, ++i) {
      p.ids.push_back(shown ? id(random) : -1);
      p.depth.push_back(random() % 16 == 0 ? stiff[random() % std::size(stiff)]
                                           : std::exp2(exponent(random)));
    }
  }
  return p;
}

class Resolve : public EveryTargetTest {};

TEST_F(Resolve, EveryPixelIsItsDefinitionOnEveryTarget) {
  static_assert(1031 * 1030 * sizeof(Rgba8) >= detail::kStreamedColorBytes);
  static_assert(200 * 70 * sizeof(Rgba8) < detail::kStreamedColorBytes);
  Camera perspective;
  perspective.nearClip = 0.01, perspective.farClip = 1e4;
  Camera parallel = perspective;
  parallel.parallelProjection = true;
  std::vector<Rgba8> colors(500);
  for (std::size_t i = 0; i < colors.size(); ++i)
    colors[i] = Rgba8{std::uint8_t(i), std::uint8_t(i * 7), std::uint8_t(i * 13), 255};
  const Rgba8 background{9, 8, 7, 0};
  detail::ThreadPool pool(2);
  const detail::PhaseRunner::ProgressCallback noProgress;
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    for (const Camera& camera : {perspective, parallel}) {
      // The last streams its colors (kStreamedColorBytes), its rows at every alignment.
      for (const auto& [width, height] :
           {std::pair{200, 70}, std::pair{131, 67}, std::pair{1031, 1030}}) {
        const detail::FrameTransform transform(camera, width, height);
        const Planes before = randomPlanes(width, height, 500, 7);
        Planes after = before;
        const detail::TileGrid grid(width, height);
        const detail::ResolveContext context{colors.data(), background, after.color.data(),
                                             after.ids.data(), width};
        detail::PhaseRunner runner(pool, noProgress, {detail::Phase::Resolve});
        ASSERT_TRUE(detail::resolveTiles(runner, grid, context));
        for (std::size_t t = 0; t < grid.count(); ++t)
          detail::resolveDepths(after.ids.data(), after.depth.data(), width, grid.bounds(t),
                                transform);
        std::size_t differing = 0;
        for (std::size_t i = 0; i < before.ids.size(); ++i) {
          const std::int32_t id = before.ids[i];
          const Rgba8 color = id < 0 ? background : colors[id];
          // The library's scalar path (compiled without fused multiply-adds, as the lanes).
          const float key = before.depth[i];
          const float depth = id < 0 ? 1.0f : detail::resolvedDepth(transform, key);
          const bool same =
              after.color[i] == color && std::memcmp(&after.depth[i], &depth, sizeof depth) == 0;
          if (!same && ++differing <= 5) {
            ADD_FAILURE() << "pixel " << i << ", id " << id << ", key " << key << ": depth "
                          << after.depth[i] << ", expected " << depth;
          }
        }
        EXPECT_EQ(differing, 0u) << width << " x " << height;
      }
    }
  }
}

// The raster's per-tile fact handed to the resolve (ResolveContext::tiles): a tile it counted
// no covered pixel in takes the background's color everywhere, its ids unread (here they
// hold polygons, which a resolve reading them would show), and every other tile its
// polygons' colors, pixel by pixel; on every instruction set, 1, 2 and 8 threads, colors
// stored plainly and streamed, tiles cut by the image's edge, runs of either kind of tile.
TEST_F(Resolve, BackgroundOnlyTilesTakeTheBackgroundAndNoOtherTileDoes) {
  std::vector<Rgba8> colors(500);
  for (std::size_t i = 0; i < colors.size(); ++i)
    colors[i] = Rgba8{std::uint8_t(i), std::uint8_t(i * 7), std::uint8_t(i * 13), 255};
  const Rgba8 background{9, 8, 7, 0};
  const detail::PhaseRunner::ProgressCallback noProgress;
  for (const auto& [width, height] : {std::pair{200, 70}, std::pair{1031, 1030}}) {
    const detail::TileGrid grid(width, height);
    const Planes planes = randomPlanes(width, height, 500, 5);
    std::vector<detail::PaintCounts> tiles(grid.count());
    for (std::size_t t = 0; t < grid.count(); ++t) {
      const detail::PixelBounds bounds = grid.bounds(t);
      for (int y = bounds.y0; y <= bounds.y1; ++y) {
        for (int x = bounds.x0; x <= bounds.x1; ++x)
          tiles[t].covered += planes.ids[static_cast<std::size_t>(y) * width + x] >= 0;
      }
      if (t % 3 != 1) tiles[t].covered = 0;  // said to show the background: ids not read
    }
    for (const detail::SimdTarget& target : detail::simdTargets()) {
      SCOPED_TRACE(target.name);
      detail::useSimdTarget(target.bits);
      for (const int threads : {1, 2, 8}) {
        detail::ThreadPool pool(threads);
        std::vector<Rgba8> color(planes.ids.size(), Rgba8{1, 2, 3, 4});
        detail::ResolveContext context{colors.data(), background, color.data(), planes.ids.data(),
                                       width};
        context.tiles = tiles.data();
        detail::PhaseRunner runner(pool, noProgress, {detail::Phase::Resolve});
        ASSERT_TRUE(detail::resolveTiles(runner, grid, context));
        std::size_t differing = 0, backgroundPixels = 0;
        for (std::size_t t = 0; t < grid.count(); ++t) {
          const detail::PixelBounds bounds = grid.bounds(t);
          for (int y = bounds.y0; y <= bounds.y1; ++y) {
            for (int x = bounds.x0; x <= bounds.x1; ++x) {
              const std::size_t i = static_cast<std::size_t>(y) * width + x;
              const std::int32_t id = planes.ids[i];
              const bool backgroundOnly = tiles[t].covered == 0;
              backgroundPixels += backgroundOnly && id >= 0;
              const Rgba8 expected = backgroundOnly || id < 0 ? background : colors[id];
              if (!(color[i] == expected) && ++differing <= 5)
                ADD_FAILURE() << "pixel (" << x << ", " << y << ") of tile " << t << ", id " << id;
            }
          }
        }
        EXPECT_EQ(differing, 0u) << width << " x " << height << ", " << threads << " threads";
        EXPECT_GT(backgroundPixels, 0u);  // the tiles said to show the background hold polygons
      }
    }
  }
}

// An id plane whose last byte ends a page and the page after it unreadable: a read past its
// last row faults. With `before`, its first byte begins a page and the page before it is
// unreadable: a read before its first row faults.
class GuardedIds {
 public:
  explicit GuardedIds(const std::vector<std::int32_t>& ids, bool before = false) {
    const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    const std::size_t bytes = ids.size() * sizeof(std::int32_t);
    mapped_ = (bytes + page - 1) / page * page + page;
    base_ = mmap(nullptr, mapped_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (base_ == MAP_FAILED) throw std::bad_alloc();
    char* guard = static_cast<char*>(base_) + (before ? 0 : mapped_ - page);
    mprotect(guard, page, PROT_NONE);
    ids_ = reinterpret_cast<std::int32_t*>(before ? guard + page : guard - bytes);
    std::memcpy(ids_, ids.data(), bytes);
  }
  GuardedIds(const GuardedIds&) = delete;
  GuardedIds& operator=(const GuardedIds&) = delete;
  ~GuardedIds() { munmap(base_, mapped_); }
  const std::int32_t* data() const { return ids_; }

 private:
  void* base_ = nullptr;
  std::size_t mapped_ = 0;
  std::int32_t* ids_ = nullptr;
};

// The estimate's sums per row (EstimateRows.h) as the pass over the finished image finds them
// (QualityRenderer's at one sample per pixel): what the resolve's fused estimate must give.
std::vector<detail::EstimateSums> estimateOfImage(const std::vector<Rgba8>& color,
                                                  const std::int32_t* ids,
                                                  const detail::EstimateBound* fixedBounds,
                                                  int width, int height) {
  detail::EstimateSpace space;
  space.resize(width, 1);
  const detail::EstimateGrid grid{ids, color.data(), fixedBounds, nullptr, width, height};
  std::vector<detail::EstimateSums> rows(static_cast<std::size_t>(height));
  for (int r = 0; r <= height; ++r) {
    if (r < height) space.findMaxima(grid, r);
    if (r >= 1) rows[static_cast<std::size_t>(r - 1)] = space.sampleSums(grid, r - 1);
  }
  return rows;
}

// The estimate tests' palette: 500 polygons' colors and fixed bounds (an even count).
struct Palette {
  std::vector<Rgba8> colors = std::vector<Rgba8>(500);
  std::vector<detail::EstimateBound> fixedBounds = std::vector<detail::EstimateBound>(500);
  Palette() {
    for (std::size_t i = 0; i < colors.size(); ++i) {
      colors[i] = Rgba8{std::uint8_t(i), std::uint8_t(i * 7), std::uint8_t(i * 13), 255};
      fixedBounds[i] = detail::fixedBoundOf(0.37f * static_cast<float>(i % 11));
    }
  }
};

// Each tile's covered count, as the raster leaves it, from the ids plane.
std::vector<detail::PaintCounts> tileCounts(const detail::TileGrid& grid,
                                            const std::vector<std::int32_t>& ids, int width) {
  std::vector<detail::PaintCounts> tiles(grid.count());
  for (std::size_t t = 0; t < grid.count(); ++t) {
    const detail::PixelBounds bounds = grid.bounds(t);
    for (int y = bounds.y0; y <= bounds.y1; ++y) {
      for (int x = bounds.x0; x <= bounds.x1; ++x)
        tiles[t].covered += ids[static_cast<std::size_t>(y) * width + x] >= 0;
    }
  }
  return tiles;
}

// Each pixel's color as the resolve must give it: its polygon's, or the background's.
std::vector<Rgba8> colorsOfIds(const std::vector<std::int32_t>& ids,
                               const std::vector<Rgba8>& colors, Rgba8 background) {
  std::vector<Rgba8> expected(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
    expected[i] = ids[i] < 0 ? background : colors[static_cast<std::size_t>(ids[i])];
  return expected;
}

// The pixels whose color is not the expected one, the first five reported.
std::size_t differingColors(const std::vector<Rgba8>& color, const std::vector<Rgba8>& expected,
                            const std::vector<std::int32_t>& ids) {
  std::size_t differing = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (!(color[i] == expected[i]) && ++differing <= 5)
      ADD_FAILURE() << "pixel " << i << ", id " << ids[i];
  }
  return differing;
}

// The rows whose estimate sums are not the expected ones, the first five reported.
std::size_t differingEstimateRows(const std::vector<detail::EstimateSums>& estimate,
                                  const std::vector<detail::EstimateSums>& expectedRows) {
  std::size_t differing = 0;
  for (std::size_t y = 0; y < estimate.size(); ++y) {
    const detail::EstimateSums &found = estimate[y], &expected = expectedRows[y];
    if ((found.squares != expected.squares || found.largest != expected.largest ||
         found.covered != expected.covered) &&
        ++differing <= 5) {
      ADD_FAILURE() << "row " << y << ": " << found.squares << " " << found.largest << " "
                    << found.covered << ", expected " << expected.squares << " " << expected.largest
                    << " " << expected.covered;
    }
  }
  return differing;
}

// While coloring a row the resolve reads the next row's ids (their colors fetched a row
// ahead) and fetches the row after it, within its task (with the estimate, also the row
// below the task, which the estimate reads): at the image's last rows it reads nothing past
// the plane (a page no one may read follows it), nor before its first row (a page no one may
// read before it), for last tasks of 1, 3 and 10 rows (8 + 2: read ahead across its steps),
// an image of one row, widths no multiple of a vector, with the tiles and without, colors
// stored plainly and streamed (1031 x 1025), the estimate off and on (its bands of 32 rows,
// each row's covered span found as it is colored), on every instruction set, 1 and 2
// threads; and every pixel is its polygon's color or the background's, and every row's
// estimate the pass over the finished image's.
TEST_F(Resolve, ReadsNoIdPastTheLastRowOfThePlane) {
  static_assert(1031 * 1025 * sizeof(Rgba8) >= detail::kStreamedColorBytes);
  Palette palette;  // the estimate hook takes its bounds unconst
  const std::vector<Rgba8>& colors = palette.colors;
  std::vector<detail::EstimateBound>& fixedBounds = palette.fixedBounds;
  const Rgba8 background{9, 8, 7, 0};
  const detail::PhaseRunner::ProgressCallback noProgress;
  for (const auto& [width, height] : {std::pair{131, 65}, std::pair{200, 74}, std::pair{67, 3},
                                      std::pair{29, 1}, std::pair{1031, 1025}}) {
    const detail::TileGrid grid(width, height);
    std::vector<std::int32_t> plainIds = randomPlanes(width, height, 500, 3).ids;
    // The first and last rows show polygons everywhere: their tiles are covered, their ids
    // all read.
    std::fill(plainIds.begin(), plainIds.begin() + width, 23);
    std::fill(plainIds.end() - width, plainIds.end(), 17);
    for (const bool guardBefore : {false, true}) {
      const GuardedIds ids(plainIds, guardBefore);
      const std::vector<detail::PaintCounts> tiles = tileCounts(grid, plainIds, width);
      const std::vector<Rgba8> expectedColor = colorsOfIds(plainIds, colors, background);
      const std::vector<detail::EstimateSums> expectedEstimate =
          estimateOfImage(expectedColor, ids.data(), fixedBounds.data(), width, height);
      for (const detail::SimdTarget& target : detail::simdTargets()) {
        SCOPED_TRACE(target.name);
        detail::useSimdTarget(target.bits);
        for (const int threads : {1, 2}) {
          for (const bool withTiles : {false, true}) {
            for (const bool estimating : {false, true}) {
              detail::ThreadPool pool(threads);
              std::vector<Rgba8> color(plainIds.size(), Rgba8{1, 2, 3, 4});
              detail::ResolveContext context{colors.data(), background, color.data(), ids.data(),
                                             width};
              if (withTiles) context.tiles = tiles.data();
              detail::EstimateHook hook;
              std::vector<detail::EstimateSums> estimate(static_cast<std::size_t>(height));
              if (estimating) {
                hook.fixedBounds = fixedBounds.data();
                hook.height = height;
                hook.rows = estimate.data();
                context.estimate = &hook;
              }
              detail::PhaseRunner runner(pool, noProgress, {detail::Phase::Resolve});
              ASSERT_TRUE(detail::resolveTiles(runner, grid, context));
              const std::size_t differing = differingColors(color, expectedColor, plainIds);
              const std::size_t differingRows =
                  estimating ? differingEstimateRows(estimate, expectedEstimate) : 0;
              EXPECT_EQ(differing + differingRows, 0u)
                  << width << " x " << height << ", " << threads << " threads, tiles " << withTiles
                  << ", estimate " << estimating << ", guard before " << guardBefore;
            }
          }
        }
      }
    }
  }
}

// The estimating resolve with the raster's tiles (the filter's default path): each row's
// covered span is found from the groups colorRow colors, the background-only tiles' ids
// unread (CoveredGroups), so a row's span must come out the same whatever tiles lie between
// its covered pixels. Tiles of the background only in runs (two in three), rows of the
// background only inside covered tiles (the span none, however many groups were skipped),
// rows whose only covered pixel is the first or the last column of a covered tile (the span
// narrowed within one group to one pixel), the image's last row a partial band's and tile's:
// the colors and every row's estimate are the pass over the finished image's, on every
// instruction set, 1 and 2 threads.
TEST_F(Resolve, EstimatingBandsFindTheirSpansAcrossBackgroundTiles) {
  Palette palette;  // the estimate hook takes its bounds unconst
  const std::vector<Rgba8>& colors = palette.colors;
  std::vector<detail::EstimateBound>& fixedBounds = palette.fixedBounds;
  const Rgba8 background{9, 8, 7, 0};
  const detail::PhaseRunner::ProgressCallback noProgress;
  constexpr int kTile = detail::TileGrid::kTileSize;
  for (const auto& size : {std::pair{300, 130}, std::pair{131, 71}}) {
    const int width = size.first, height = size.second;  // plain locals: the lambdas take them
    const detail::TileGrid grid(width, height);
    std::vector<std::int32_t> ids = randomPlanes(width, height, 500, 13).ids;
    const auto at = [&](int x, int y) -> std::int32_t& {
      return ids[static_cast<std::size_t>(y) * width + x];
    };
    const int tilesX = (width + kTile - 1) / kTile;
    const auto shown = [&](int tx, int ty) { return (ty * tilesX + tx) % 3 == 1; };
    std::size_t edgeRows = 0;
    for (int y = 0; y < height; ++y) {
      const int ty = y / kTile;
      for (int x = 0; x < width; ++x) {
        if (!shown(x / kTile, ty)) at(x, y) = -1;
      }
      if (y % 7 == 3 || y % 7 == 5 || y % 7 == 6) {
        // The row's covered tiles: only the background (3), or a single pixel at a covered
        // tile's first (5) or last (6) column.
        for (int x = 0; x < width; ++x)
          at(x, y) = -1;
        for (int tx = 0; tx < tilesX && y % 7 != 3; ++tx) {
          if (!shown(tx, ty)) continue;
          at(y % 7 == 5 ? tx * kTile : std::min(width, (tx + 1) * kTile) - 1, y) = 42;
          ++edgeRows;
          break;
        }
      }
    }
    EXPECT_GT(edgeRows, 0u);
    const std::vector<detail::PaintCounts> tiles = tileCounts(grid, ids, width);
    const auto backgroundTiles = std::count_if(tiles.begin(), tiles.end(),
                                               [](const auto& tile) { return tile.covered == 0; });
    EXPECT_GT(backgroundTiles, 1);
    const std::vector<Rgba8> expectedColor = colorsOfIds(ids, colors, background);
    const std::vector<detail::EstimateSums> expectedEstimate =
        estimateOfImage(expectedColor, ids.data(), fixedBounds.data(), width, height);
    for (const detail::SimdTarget& target : detail::simdTargets()) {
      SCOPED_TRACE(target.name);
      detail::useSimdTarget(target.bits);
      for (const int threads : {1, 2}) {
        detail::ThreadPool pool(threads);
        std::vector<Rgba8> color(ids.size(), Rgba8{1, 2, 3, 4});
        detail::ResolveContext context{colors.data(), background, color.data(), ids.data(), width};
        context.tiles = tiles.data();
        detail::EstimateHook hook;
        std::vector<detail::EstimateSums> estimate(static_cast<std::size_t>(height));
        hook.fixedBounds = fixedBounds.data();
        hook.height = height;
        hook.rows = estimate.data();
        context.estimate = &hook;
        detail::PhaseRunner runner(pool, noProgress, {detail::Phase::Resolve});
        ASSERT_TRUE(detail::resolveTiles(runner, grid, context));
        const std::size_t differing = differingColors(color, expectedColor, ids) +
                                      differingEstimateRows(estimate, expectedEstimate);
        EXPECT_EQ(differing, 0u) << width << " x " << height << ", " << threads << " threads";
      }
    }
  }
}

// widenPolygonIds (facet/IdPlane.h) against its definition on every instruction set: stored
// plainly and streamed, from every alignment of the 64-bit plane (the streamed path's scalar
// head) and for counts that are no multiple of a vector (its tail), ids of every sign.
TEST_F(Resolve, WidenedIdsAreTheShiftedIdsOnEveryTarget) {
  const Planes planes = randomPlanes(301, 37, 1 << 30, 11);
  std::vector<std::int32_t> ids = planes.ids;
  ids[0] = std::numeric_limits<std::int32_t>::max();
  ids[1] = std::numeric_limits<std::int32_t>::min();
  ids[2] = 0;
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    for (const bool stream : {false, true}) {
      for (const std::int64_t first : {std::int64_t{0}, std::int64_t{17}, std::int64_t{1} << 40}) {
        for (std::size_t offset = 0; offset < 9; ++offset) {
          const std::size_t count = ids.size() - 2 * offset;
          std::vector<std::int64_t> out(ids.size() + 8, 5);  // 5: not written
          widenPolygonIds(ids.data() + offset, out.data() + offset, count, first, stream);
          std::size_t differing = 0;
          for (std::size_t i = 0; i < out.size(); ++i) {
            const bool inside = i >= offset && i < offset + count;
            const std::int64_t expected = !inside ? 5 : ids[i] < 0 ? -1 : first + ids[i];
            if (out[i] != expected && ++differing <= 5)
              ADD_FAILURE() << "value " << i << " of " << out.size() << ": " << out[i]
                            << ", expected " << expected;
          }
          EXPECT_EQ(differing, 0u)
              << "stream " << stream << ", first " << first << ", offset " << offset;
        }
      }
    }
  }
}

}  // namespace
}  // namespace facet::testing
