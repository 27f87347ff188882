#include "Binning.h"

#include <optional>
#include <string>
#include <utility>

#include "facet/Error.h"

namespace facet::detail {
namespace {

// Corners 1 and 2 trade places: so do the edges opposite them (bits 1 and 2); the clamp bit
// stays.
EdgeMask swapEdges12(EdgeMask boundary) {
  return static_cast<EdgeMask>((boundary & (1u | kClampToNearestVertex)) | (boundary & 2u) << 1 |
                               (boundary & 4u) >> 1);
}

}  // namespace

BinOutcome binTriangle(Chunk& chunk, const TileGrid& grid, std::uint32_t r0, std::uint32_t r1,
                       std::uint32_t r2, const WindowVertex& a, const WindowVertex& b,
                       const WindowVertex& c, std::int64_t area, EdgeMask boundary,
                       std::int32_t polygon, bool last) {
  if (area == 0) return BinOutcome::ZeroArea;
  const WindowVertex* second = &b;
  const WindowVertex* third = &c;
  if (area < 0) {
    std::swap(r1, r2);
    std::swap(second, third);
    boundary = swapEdges12(boundary);
  }
  const PixelBounds bounds = samplesInBoundingBox(a, *second, *third, grid.viewport());
  if (bounds.x0 == bounds.x1 && bounds.y0 == bounds.y1) {
    const std::optional<float> key = keyOfOnlySample(a, *second, *third, area < 0 ? -area : area,
                                                     boundary, bounds.x0, bounds.y0);
    if (!key) return BinOutcome::CoversNoSample;
    ++chunk.counts.boxSamples;
    binFragment(chunk, tileOf(grid, bounds.x0, bounds.y0), bounds.x0, bounds.y0, *key, polygon,
                last);
    return BinOutcome::Binned;
  }
  if (bounds.empty() || !coversAnySample(a, *second, *third, bounds)) {
    return BinOutcome::CoversNoSample;
  }
  chunk.counts.boxSamples += bounds.area();
  binCovering(chunk, grid, r0, r1, r2, bounds, boundary, polygon, last);
  return BinOutcome::Binned;
}

void requireIndexable(std::size_t triangles, std::size_t fragments, std::size_t smallTriangles,
                      std::size_t clippedVertices) {
  static_assert(kMaxBinnedPerChunk == kSmallTriangleBit && kMaxBinnedPerChunk < kClippedVertexBit);
  const auto check = [](std::size_t count, const char* what) {
    if (count >= kMaxBinnedPerChunk) {
      throw Error("a set-up chunk holds " + std::to_string(count) + " " + what +
                  "; a 32-bit bin entry indexes at most " + std::to_string(kMaxBinnedPerChunk - 1) +
                  " (draw fewer or smaller polygons)");
    }
  };
  check(triangles, "binned triangles");
  check(fragments, "binned fragments");
  check(smallTriangles, "binned small triangles");
  check(clippedVertices, "clipped vertices");
}

namespace {
// Calls `visit` on each of a chunk's record buffers and each of its bins: the one list that
// clearBins and settleRecords both walk.
template <class Visit>
void forEachAppendBuffer(Chunk& chunk, const Visit& visit) {
  visit(chunk.triangles);
  visit(chunk.boundaryEdges);
  visit(chunk.fragments);
  visit(chunk.smallTriangles);
  visit(chunk.smallNearestKeys);
  for (auto* bins : {&chunk.bins, &chunk.backBins}) {
    for (auto& bin : *bins)
      visit(bin);
  }
}
}  // namespace

void clearBins(Chunk& chunk, const TileGrid& grid) {
  chunk.bins.resize(grid.count());
  chunk.backBins.resize(grid.count());
  forEachAppendBuffer(chunk, [](auto& buffer) { buffer.clear(); });
  chunk.firstKeyedSmall = 0;
}

void settleRecords(std::span<Chunk> chunks) {
  for (Chunk& chunk : chunks) {
    forEachAppendBuffer(chunk, [](auto& buffer) { buffer.settle(); });
    chunk.firstKeyedSmall = 0;
    settleVector(chunk.clippedVertices);
    settleVector(chunk.deferredBack);
  }
}

}  // namespace facet::detail
