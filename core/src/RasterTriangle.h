#pragma once

// Painting one triangle into one tile with integer edge functions.
//
// Window vertices are on a fixed-point grid (kSubpixelBits = 8), so every coverage decision
// below is exact integer arithmetic:
// - pixel (px, py) is sampled at its center, (px·256 + 128, py·256 + 128);
// - edge function of the directed edge p→q: E(X, Y) = (q.x − p.x)(Y − p.y) − (q.y − p.y)(X − p.x),
//   positive on the left, i.e. inside a counter-clockwise triangle (y up);
// - top-left fill rule: a sample exactly on an edge belongs to the triangle only if the edge
//   is a left edge (dy < 0 for counter-clockwise, y up) or a top edge (dy = 0, dx < 0). The
//   two triangles sharing an edge traverse it in opposite directions, so exactly one of
//   them owns the samples on it (D3D10 / OpenGL rasterization rules, llvmpipe's approach).

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "FrameTransform.h"
#include "TileGrid.h"
#include "facet/Color.h"
#include "facet/Conventions.h"
#include "facet/Framebuffer.h"

namespace facet::detail {

// Which edges of a triangle lie on its polygon's boundary: bit i for the edge opposite
// corner i (a, b, c). The others are diagonals the triangulation or the clipper added.
using EdgeMask = std::uint8_t;
inline constexpr EdgeMask kAllEdges = 0b111;

// Bit 3 beside the edges: the triangle's written keys are clamped to its nearest vertex key
// (nearestWrittenKey). The set-up sets it (with all three edges, on a triangle polygon's
// triangle: kClampedEdges) on every back face a depth-tested frame paints after its front
// faces (the back bins, one pass or two alike: the whole-block reject drops back faces,
// HiddenBlocks.h, and whether a frame takes two passes depends on the last frame); front
// faces and closed meshes pay nothing.
inline constexpr EdgeMask kClampToNearestVertex = 0b1000;
inline constexpr EdgeMask kClampedEdges = kAllEdges | kClampToNearestVertex;

// The nearest (largest) depth key a triangle may write: its nearest vertex key when it is
// clamped (kClampedEdges: a triangle polygon's back face, depth test on), else none (+∞;
// without all three boundary edges a triangle beside a diagonal continues its polygon's plane
// past the diagonal legitimately). The clamping paint paths (TriangleDepth::keyAt and
// refine<true>, paintSmallTriangle with a nearest key, SetupBatch's keyLanes with `front`)
// clamp the key they write to it: exactly the keys are convex combinations of the vertex keys
// there, so only the rounding of the interpolation and of the stepping could pass it, and the
// clamp makes "no written key is nearer than the nearest vertex key" hold by construction,
// with no rounding argument (HiddenBlocks.h's proof rests on it).
inline float nearestWrittenKey(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                               EdgeMask boundary) {
  return boundary == kClampedEdges ? std::max(std::max(a.depth, b.depth), c.depth)
                                   : std::numeric_limits<float>::infinity();
}

// Twice the signed area in fixed-point units²: > 0 counter-clockwise (front-facing).
inline std::int64_t doubleSignedArea(const WindowVertex& a, const WindowVertex& b,
                                     const WindowVertex& c) {
  return static_cast<std::int64_t>(b.x - a.x) * (c.y - a.y) -
         static_cast<std::int64_t>(c.x - a.x) * (b.y - a.y);
}

// A triangle's bounding box in grid units (fixed point), inclusive.
struct GridBox {
  std::int32_t x0, y0, x1, y1;
};
inline GridBox gridBoxOf(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c) {
  return {std::min(std::min(a.x, b.x), c.x), std::min(std::min(a.y, b.y), c.y),
          std::max(std::max(a.x, b.x), c.x), std::max(std::max(a.y, b.y), c.y)};
}

// The pixels whose centers lie in a grid box, clipped to `clip`.
inline PixelBounds samplesInGridBox(const GridBox& grid, const PixelBounds& clip) {
  // Smallest px with px·256 + 128 ≥ min, largest with px·256 + 128 ≤ max: ceil and floor of
  // (v − 128)/256 by arithmetic shifts (C++20 >> is arithmetic). Window coordinates are below
  // 2^23 in magnitude (FrameTransform.h): no overflow in 32 bits.
  constexpr std::int32_t kHalf = kSubpixelScale / 2;
  const auto ceilPixel = [](std::int32_t v) { return -((kHalf - v) >> kSubpixelBits); };
  const auto floorPixel = [](std::int32_t v) { return (v - kHalf) >> kSubpixelBits; };
  return {std::max(ceilPixel(grid.x0), clip.x0), std::max(ceilPixel(grid.y0), clip.y0),
          std::min(floorPixel(grid.x1), clip.x1), std::min(floorPixel(grid.y1), clip.y1)};
}

// The pixels whose centers lie in the triangle's bounding box, clipped to `clip`. Inline:
// set-up and raster call it once per triangle (per tile), and out of line its call and
// std::min's initializer lists cost ~60 instructions a call (callgrind, 500k triangles).
inline PixelBounds samplesInBoundingBox(const WindowVertex& a, const WindowVertex& b,
                                        const WindowVertex& c, const PixelBounds& clip) {
  return samplesInGridBox(gridBoxOf(a, b, c), clip);
}

// coversAnySample for bounds of 2 to 4 samples.
bool coversAnyOfFewSamples(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                           const PixelBounds& bounds);

// False only when the triangle (counter-clockwise) certainly covers no sample in `bounds`
// (not empty): decided exactly for bounds of at most 4 samples (most triangles of a dense
// mesh), assumed true for larger ones. Lets set-up drop sub-pixel triangles before lighting
// and binning.
inline bool coversAnySample(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                            const PixelBounds& bounds) {
  return bounds.area() > 4 || coversAnyOfFewSamples(a, b, c, bounds);
}

// The one sample (x, y) a counter-clockwise triangle's box holds: its depth key if the
// triangle covers it, as paintTriangle would write it; nothing if it does not. Set-up decides
// the fragment of such a triangle (most of a dense mesh's) when it bins it (Binning.cpp).
std::optional<float> keyOfOnlySample(const WindowVertex& a, const WindowVertex& b,
                                     const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                                     int x, int y);

// Where a tile writes its depth keys and polygon ids: a tile's own planes (Raster.cpp), or a
// test's. The painters index pixel (x, y) as
// y·width + x − origin: a tile's planes start at its first pixel's index, an offset rather
// than pointers moved before the buffer (which the language leaves undefined).
struct Planes {
  float* depth;
  std::int32_t* polygonId;
  int width;
  std::size_t origin = 0;  // the index y·width + x of depth[0] and polygonId[0]
};

enum class DepthMode { Test, Overwrite };

struct PaintCounts {
  std::size_t written = 0;  // pixel writes, counting overdraw
  std::size_t covered = 0;  // pixels the tile shows a polygon at (counted from its final ids)
  std::size_t hidden = 0;   // triangles (per tile) the coarse depth proved hidden
};

// A tile's coarse depth (hierarchical z): per 8 × 8 pixel block, a depth key no nearer than
// any of the block's pixels — the farthest the block may show. It starts at the
// background's and rises as triangles cover the block: a triangle covering all of it
// raises it to the triangle's farthest key; triangles covering parts (the two halves of a
// quad) gather in a layer (Hasselgren et al., "Masked Software Occlusion Culling", 2016):
// the union of their pixels holds at least the farthest of their keys, and once the union
// is the whole block that key becomes the block's. A triangle whose keys are all at most
// the farthest of every block it overlaps cannot pass the depth test anywhere.
class CoarseDepth {
 public:
  static constexpr int kBlockSize = 8;
  static constexpr int kBlocksPerSide = TileGrid::kTileSize / kBlockSize;

  explicit CoarseDepth(const PixelBounds& tile);
  // Whether no key up to `nearest` can win a pixel of the box (inside the tile).
  bool hides(const PixelBounds& box, float nearest) const;
  // Notes that the pixels of the blocks the box overlaps that coverage(block pixels) marks
  // (bit (y − y0)·8 + (x − x0)) now hold `key` or nearer.
  template <class Coverage>
  void raise(const PixelBounds& box, float key, const Coverage& coverage);

 private:
  struct Block {
    float farthest;
    float layerKey;
    std::uint64_t layerMask;
  };
  PixelBounds blockPixels(int bx, int by) const;
  static std::uint64_t allPixels(const PixelBounds& pixels);
  void cover(Block& block, std::uint64_t all, std::uint64_t mask, float key);
  PixelBounds tile_;
  Block blocks_[kBlocksPerSide * kBlocksPerSide];
};

// Writes one fragment of `polygonId` at pixel i if it passes the depth test: strictly nearer
// (a larger key), so an exact tie keeps the polygon painted first. A tile paints every front
// face before any back face (Raster.cpp, Chunk::backBins), each facing in draw order: an
// exact tie keeps the front face; among polygons facing the same way, the one drawn first.
// counts.covered is left to the tile, from its final ids (one pass with the shown flags
// rather than a load and compare per fragment).
template <DepthMode kMode>
void writeFragment(std::size_t i, float depth, std::int32_t polygonId, const Planes& planes,
                   PaintCounts& counts) {
  i -= planes.origin;
  if (kMode == DepthMode::Overwrite || depth > planes.depth[i]) {
    planes.depth[i] = depth;
    planes.polygonId[i] = polygonId;
    ++counts.written;
  }
}

// Whether a counter-clockwise triangle certainly loses the depth test at every pixel of `box`
// (its samples in one tile), decided before its edges and depth plane are set up: the nearest
// key it can give (TriangleDepth::keyRange's bound, RasterTriangle.cpp) is no nearer than the
// farthest key written in the box. Never for a triangle that snapping turned over. Back faces
// drawn after the front faces over them (every face drawn) are most of what it rejects.
bool losesEverywhere(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                     const PixelBounds& box, const Planes& planes);

// The farthest depth key of each 4 × 4 pixel block of a tile, read from its depth plane once
// the tile's front faces are painted (every face drawn, Raster.cpp): under the depth test a
// pixel's key only grows nearer, so each stays no nearer than any of its block's keys while the
// back faces paint. losesEverywhere then bounds a back face's box from a few blocks instead of
// reading each of its keys (a back face of a 20k sphere has dozens). Read on first use: a
// tile without a back face that reaches the reject pays nothing.
class FarthestBlocks {
 public:
  // 4, not 8 (big40, bench section 67): at 8M triangles every face a 4 × 4 block follows the
  // silhouette closer, so the back pass drops more blocks and runs whole (2.5 % fewer
  // instructions a frame, −1.7 % CPU); at 2M and 500k even in time, 1–2 % fewer instructions.
  static constexpr int kBlockSize = 4;
  static constexpr int kBlocksPerSide = TileGrid::kTileSize / kBlockSize;

  FarthestBlocks(const PixelBounds& tile, const Planes& planes) : tile_(tile), planes_(planes) {}
  // The blocks measured already (FrontDepthBlocks, a two-pass frame's back pass).
  FarthestBlocks(const PixelBounds& tile, const Planes& planes, const float* measured)
      : tile_(tile), planes_(planes), measured_(true) {
    std::copy_n(measured, kBlocksPerSide * kBlocksPerSide, farthest_);
  }
  // Each block's least key, row of blocks by row (blocks beyond the image's pixels undefined).
  const float* measuredBlocks() {
    if (!measured_) measure();
    return farthest_;
  }
  // A key no nearer than any the box's pixels (inside the tile) hold, now or later.
  float over(const PixelBounds& box) {
    if (!measured_) measure();
    float farthest = std::numeric_limits<float>::infinity();
    for (int by = (box.y0 - tile_.y0) / kBlockSize; by <= (box.y1 - tile_.y0) / kBlockSize; ++by) {
      for (int bx = (box.x0 - tile_.x0) / kBlockSize; bx <= (box.x1 - tile_.x0) / kBlockSize; ++bx)
        farthest = std::min(farthest, farthest_[by * kBlocksPerSide + bx]);
    }
    return farthest;
  }

 private:
  void measure();
  PixelBounds tile_;
  Planes planes_;
  bool measured_ = false;
  float farthest_[kBlocksPerSide * kBlocksPerSide];
};

// A two-pass frame's (every face drawn, Raster.h) least depth key of each 4 × 4 pixel block of
// the image once the front faces are painted: FarthestBlocks kept per tile between the raster's
// two passes, so that the back faces' set-up can drop, before it loads them, the blocks and
// runs of them that lose everywhere (HiddenBlocks.h). 4 bytes per 16 pixels: 520 KB at 1080p,
// 2.1 MB at 4K.
class FrontDepthBlocks {
 public:
  static constexpr int kBlockSize = FarthestBlocks::kBlockSize;
  static constexpr int kPerTile = FarthestBlocks::kBlocksPerSide * FarthestBlocks::kBlocksPerSide;

  // Row by row over the image's blocks (a tile's sixteen rows of sixteen apart), so that a box's
  // blocks are found by shifts alone.
  void resize(const TileGrid& grid) {
    stride_ = static_cast<std::size_t>(grid.tilesX()) * FarthestBlocks::kBlocksPerSide;
    tilesX_ = static_cast<std::size_t>(grid.tilesX());
    blocks_.resize(grid.count() * kPerTile);
  }
  // Keeps tile t's FarthestBlocks (kPerTile keys, row of blocks by row).
  void store(std::size_t t, const float* measured) {
    constexpr std::size_t kSide = FarthestBlocks::kBlocksPerSide;
    float* first = blocks_.data() + (t / tilesX_) * kSide * stride_ + (t % tilesX_) * kSide;
    for (std::size_t row = 0; row < kSide; ++row)
      std::copy_n(measured + row * kSide, kSide, first + row * stride_);
  }
  // Tile t's blocks, as store() took them.
  void load(std::size_t t, float* measured) const {
    constexpr std::size_t kSide = FarthestBlocks::kBlocksPerSide;
    const float* first = blocks_.data() + (t / tilesX_) * kSide * stride_ + (t % tilesX_) * kSide;
    for (std::size_t row = 0; row < kSide; ++row)
      std::copy_n(first + row * stride_, kSide, measured + row * kSide);
  }
  // A key no nearer than any the box's pixels (inside the image) held after the front pass.
  float over(const PixelBounds& box) const {
    constexpr int kBits = std::countr_zero(unsigned{kBlockSize});
    const int bx0 = box.x0 >> kBits, bx1 = box.x1 >> kBits;
    const float* row = blocks_.data() + static_cast<std::size_t>(box.y0 >> kBits) * stride_;
    const float* const last = blocks_.data() + static_cast<std::size_t>(box.y1 >> kBits) * stride_;
    float farthest = std::numeric_limits<float>::infinity();
    for (;; row += stride_) {
      for (int bx = bx0; bx <= bx1; ++bx)
        farthest = std::min(farthest, row[bx]);
      if (row == last) return farthest;
    }
  }
  // Whether over(box) >= bound, row of blocks by row: false at the first row nearer than the
  // bound (a box reaching the background stops there).
  bool noneNearerThan(const PixelBounds& box, double bound) const {
    constexpr int kBits = std::countr_zero(unsigned{kBlockSize});
    const int bx0 = box.x0 >> kBits, bx1 = box.x1 >> kBits;
    const float* row = blocks_.data() + static_cast<std::size_t>(box.y0 >> kBits) * stride_;
    const float* const last = blocks_.data() + static_cast<std::size_t>(box.y1 >> kBits) * stride_;
    for (;; row += stride_) {
      float farthest = std::numeric_limits<float>::infinity();
      for (int bx = bx0; bx <= bx1; ++bx)
        farthest = std::min(farthest, row[bx]);
      if (static_cast<double>(farthest) < bound) return false;
      if (row == last) return true;
    }
  }

 private:
  std::size_t stride_ = 0, tilesX_ = 1;
  std::vector<float> blocks_;
};

// Paints a counter-clockwise triangle (doubleSignedArea > 0) into the depth and polygon-id
// planes of `tile` (colors come later, from the ids); the depth plane holds depth keys
// (FrameTransform.h) until the tile resolves, interpolated as TriangleDepth (Rasterizer.cpp)
// says, which needs the triangle's polygon-boundary edges. DepthMode::Test keeps the nearest
// fragment (strictly greater key: an exact tie keeps the fragment painted first, writeFragment);
// DepthMode::Overwrite is painter's order. kRejectHidden (depth test only): a triangle of a few
// samples that losesEverywhere is skipped before its depth plane is set up; the same pixels.
template <DepthMode kMode, bool kRejectHidden = false>
void paintTriangle(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                   EdgeMask boundary, std::int32_t polygonId, const PixelBounds& tile,
                   const Planes& planes, PaintCounts& counts);

// paintTriangle<Test, true> for a back face painted after its tile's front faces: its reject
// (losesEverywhere) tries the blocks of `front` before the keys of its box; the same decision,
// the same pixels.
void paintBackTriangle(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                       EdgeMask boundary, std::int32_t polygonId, const PixelBounds& tile,
                       const Planes& planes, PaintCounts& counts, FarthestBlocks& front);

// The small-box path (RasterTriangle.cpp): boxes of at most kSmallSide × kSmallSide samples.
inline constexpr int kSmallSide = 4;

// A triangle set up whole by the set-up's lanes (SetupBatch.cpp): one whose box of pixel
// centers lies in one tile and is at most kSmallSide × kSmallSide less one sample, and whose
// covered samples all take the stepped key (with polygon-boundary edges, every face drawn:
// each is surely inside them, smallTriangleOf), so that the tile paints it from this record
// alone, read in sequence, without its three scattered vertices or any set-up of its own
// (paintSmallTriangle: the same pixels and keys as paintTriangle). The full 4 × 4 box is
// left to the tiles: with the coarse depth on, it meets the coarse depth there.
struct SmallTriangle {
  // The depth plane as TriangleDepth (RasterTriangle.cpp) steps it: the key at the box's
  // first sample is firstKey + keyPerFine · (firstRowFine + y · kSubpixelScale · kResidueScale)
  // for row y (in this order of operations: the key TriangleDepth::at gives), stepped by
  // keyPerPixel along the row.
  // firstRowFine is in fine units from the plane's origin (vertex a, unsnapped or snapped):
  // the sample lies in the bounding box, below 2^14 grid steps across, so it is below
  // 2^14 · kResidueScale + 2^7 < 2^22.1, and the fourth row's below 2^22.3.
  double firstKey, keyPerFine, keyPerPixel;
  std::int32_t firstRowFine;
  std::int32_t polygon;
  std::uint16_t x0, y0;  // the box's first pixel
  // The samples the triangle covers, bit y·kSmallSide + x for the pixel (x0 + x, y0 + y): its
  // box's, by the fill rule (SmallBox::coverage).
  std::uint16_t coverage;
};
static_assert(sizeof(SmallTriangle) == 40);

// Rounds an interpolated depth key to float once; finite, so that no key ties with the
// background (−∞) or becomes NaN.
inline float toDepthKey(double key) {
  constexpr double kLargest = std::numeric_limits<float>::max();
  return static_cast<float>(std::clamp(key, -kLargest, kLargest));
}

// Writes the samples of a small box's coverage `mask` whose first pixel is (x0, y0): row y's
// key starts at rowKey(y) and steps by keyPerPixel sample by sample, as BoxRaster::paintRows
// steps it; refine(key, x, y) gives a covered sample's (x, y from the box's first).
// kByBits (the SmallTriangle records, paintSmallTriangle): one loop over the mask's bits, a
// row's four stepped keys made when its first sample comes (the same additions in the same
// order as stepping to each sample). Row by row, the loop per row and the stepping loop per
// sample were branches whose counts the mask decides: their mispredictions were about half of
// the closed 500k frame's paintTile (bench/core-frame-issue11.md, section 57). paintTriangle's
// small-box path keeps the row loop: its triangles are few at 500k, and its 20k frame (boxes
// with refine) ran ~1 % slower by bits.
template <DepthMode kMode, bool kByBits = false, class RowKey, class Refine>
[[gnu::always_inline]] inline void paintSmallMask(std::uint32_t mask, int x0, int y0,
                                                  double keyPerPixel, const RowKey& rowKey,
                                                  const Refine& refine, std::int32_t polygonId,
                                                  const Planes& planes, PaintCounts& counts) {
  constexpr std::uint32_t kRow = (1u << kSmallSide) - 1;
  if constexpr (kByBits) {
    static_assert(kSmallSide == 4);
    double keys[kSmallSide];
    int keysRow = -1;
    std::size_t row = 0;
    for (; mask != 0; mask &= mask - 1) {
      const int bit = std::countr_zero(mask);
      const int y = bit / kSmallSide, x = bit % kSmallSide;
      if (y != keysRow) {
        keysRow = y;
        keys[0] = rowKey(y);
        keys[1] = keys[0] + keyPerPixel;
        keys[2] = keys[1] + keyPerPixel;
        keys[3] = keys[2] + keyPerPixel;
        row = static_cast<std::size_t>(y0 + y) * planes.width + x0;
      }
      writeFragment<kMode>(row + x, toDepthKey(refine(keys[x], x, y)), polygonId, planes, counts);
    }
    return;
  }
  for (int y = 0; mask != 0; ++y, mask >>= kSmallSide) {
    if ((mask & kRow) == 0) continue;
    double key = rowKey(y);
    const std::size_t row = static_cast<std::size_t>(y0 + y) * planes.width + x0;
    int x = 0;
    for (std::uint32_t columns = mask & kRow; columns != 0; columns &= columns - 1) {
      const int next = std::countr_zero(columns);
      for (; x < next; ++x)
        key += keyPerPixel;
      writeFragment<kMode>(row + next, toDepthKey(refine(key, next, y)), polygonId, planes, counts);
    }
  }
}

// A SmallTriangle's first row starts this many fine units after the previous one.
inline constexpr std::int32_t kFinePerRow = kSubpixelScale * kResidueScale;

// Paints a SmallTriangle: paintTriangle<kMode>'s pixels, keys and counts for the triangle the
// set-up made it from. Inline: the tile paints most of a 500k mesh's triangles from records,
// and out of line the call cost a fifth of each (bench/core-frame-issue11.md, section 11).
template <DepthMode kMode>
[[gnu::always_inline]] inline void paintSmallTriangle(const SmallTriangle& t, const Planes& planes,
                                                      PaintCounts& counts) {
  const auto rowKey = [&t](int y) {
    return t.firstKey + t.keyPerFine * static_cast<double>(t.firstRowFine + y * kFinePerRow);
  };
  const auto sameKey = [](double key, int, int) { return key; };
  paintSmallMask<kMode, true>(t.coverage, t.x0, t.y0, t.keyPerPixel, rowKey, sameKey, t.polygon,
                              planes, counts);
}

// The same with every key clamped to `nearestKey` (nearestWrittenKey: a back bin's record keeps
// it beside the record, Chunk::smallNearestKeys).
template <DepthMode kMode>
[[gnu::always_inline]] inline void paintSmallTriangle(const SmallTriangle& t, float nearestKey,
                                                      const Planes& planes, PaintCounts& counts) {
  const auto rowKey = [&t](int y) {
    return t.firstKey + t.keyPerFine * static_cast<double>(t.firstRowFine + y * kFinePerRow);
  };
  const auto clampedKey = [nearest = static_cast<double>(nearestKey)](double key, int, int) {
    return std::min(key, nearest);
  };
  paintSmallMask<kMode, true>(t.coverage, t.x0, t.y0, t.keyPerPixel, rowKey, clampedKey, t.polygon,
                              planes, counts);
}

// The SmallTriangle of a counter-clockwise triangle over its samples in `tile`, as the set-up's
// lanes make it; nothing when its box there is not a small one of 2 to kSmallSide² − 1
// samples, or when a covered sample is not surely inside a polygon-boundary edge (`boundary`)
// by TriangleDepth::refine's bound (there refine may take another key than the stepped one).
// The reference for the set-up's records (tests).
std::optional<SmallTriangle> smallTriangleOf(const WindowVertex& a, const WindowVertex& b,
                                             const WindowVertex& c, EdgeMask boundary,
                                             const PixelBounds& tile, std::int32_t polygonId);

// The samples of `coverage` (bit y·kSmallSide + x for pixel (box.x0 + x, box.y0 + y), of a box
// of at most kSmallSide × kSmallSide samples of a counter-clockwise triangle that fits the small
// path) not surely inside a polygon-boundary edge (`boundary`) by refine()'s bound: where
// paintTriangle's key may not be the stepped one (smallTriangleOf makes no record then). The
// reference for the set-up's lanes (BatchVerdicts::smallPlane.unsure).
std::uint32_t samplesNearBoundary(const WindowVertex& a, const WindowVertex& b,
                                  const WindowVertex& c, EdgeMask boundary, const PixelBounds& box,
                                  std::uint32_t coverage);

// A counter-clockwise triangle with polygon-boundary edges over a small box whose covered
// samples `mask` (bit y·kSmallSide + x for pixel (x0 + x, y0 + y)) are those not surely
// inside a boundary edge by refine()'s test (the set-up's lanes test it, BatchVerdicts::
// nearEdge): the samples of `mask` at which paintTriangle writes refine()'s key rather than
// the stepped one — all of them, or none when snapping turned the triangle over (refine() has
// no bounds then) — and their keys (keyAt's, toDepthKey) in keys[bit]. The set-up bins such a
// triangle as a SmallTriangle record of its other samples and fragments of these:
// paintTriangle's pixels and keys, without the tile's set-up of the triangle.
std::uint32_t keysNearBoundary(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                               EdgeMask boundary, int x0, int y0, std::uint32_t mask,
                               float (&keys)[kSmallSide * kSmallSide]);

// paintTriangle without its small-box path (RasterTriangle.cpp): every box of two or more
// samples walked row by row in 64-bit edge functions. The reference the small-box path is
// tested against: the same pixels, keys and counts.
template <DepthMode kMode>
void paintTriangleWalkingBox(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                             EdgeMask boundary, std::int32_t polygonId, const PixelBounds& tile,
                             const Planes& planes, PaintCounts& counts);

// The box walk (no small-box path) with TriangleDepth::refine() asked for every covered
// sample of a triangle with polygon-boundary edges, as the walk did before it tested the
// samples' edge values against refine()'s bounds itself (core-frame-issue11.md section 53): the
// tests' reference for that test. The same pixels, keys and counts as paintTriangle.
template <DepthMode kMode>
void paintTriangleRefiningEverySample(const WindowVertex& a, const WindowVertex& b,
                                      const WindowVertex& c, EdgeMask boundary,
                                      std::int32_t polygonId, const PixelBounds& tile,
                                      const Planes& planes, PaintCounts& counts);

// The same with the depth test and the tile's coarse depth (Rule::HiddenGeometry): a
// triangle of a few samples is painted as above (its per-pixel test costs no more); a larger
// one is skipped when the coarse depth hides it (counts.hidden), else painted and the coarse
// depth raised where it covers whole blocks. The same pixels as paintTriangle<Test>.
void paintTriangleBehindCoarseDepth(const WindowVertex& a, const WindowVertex& b,
                                    const WindowVertex& c, EdgeMask boundary,
                                    std::int32_t polygonId, const PixelBounds& tile,
                                    const Planes& planes, PaintCounts& counts, CoarseDepth& coarse);

}  // namespace facet::detail
