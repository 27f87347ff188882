#pragma once

// The screen's square tiles: the unit of binning, painting and resolving, each painted by
// one thread (so the image is the same for any thread count).

#include <algorithm>
#include <cstddef>

namespace facet::detail {

// Inclusive pixel bounds.
struct PixelBounds {
  int x0, y0, x1, y1;
  bool empty() const { return x0 > x1 || y0 > y1; }
  std::size_t area() const {
    return empty() ? 0
                   : static_cast<std::size_t>(x1 - x0 + 1) * static_cast<std::size_t>(y1 - y0 + 1);
  }
};

class TileGrid {
 public:
  // 64 × 64 pixels keep a tile's color, depth and id planes (48 KiB) in L2 while giving
  // hundreds of tiles to balance at 1080p.
  static constexpr int kTileSize = 64;

  TileGrid() = default;
  TileGrid(int width, int height)
      : width_(width),
        height_(height),
        tilesX_((width + kTileSize - 1) / kTileSize),
        tilesY_((height + kTileSize - 1) / kTileSize) {}

  int tilesX() const { return tilesX_; }
  int tilesY() const { return tilesY_; }
  std::size_t count() const { return static_cast<std::size_t>(tilesX_) * tilesY_; }
  PixelBounds viewport() const { return {0, 0, width_ - 1, height_ - 1}; }

  // The pixels of tile t (tiles count row by row from the bottom left).
  PixelBounds bounds(std::size_t t) const {
    const int tx = static_cast<int>(t % tilesX_), ty = static_cast<int>(t / tilesX_);
    return {tx * kTileSize, ty * kTileSize, std::min(width_, (tx + 1) * kTileSize) - 1,
            std::min(height_, (ty + 1) * kTileSize) - 1};
  }

  // Calls visit(t) for every tile a box of pixels inside the viewport overlaps.
  template <class Visit>
  void forEachTile(const PixelBounds& box, Visit&& visit) const {
    for (int ty = box.y0 / kTileSize; ty <= box.y1 / kTileSize; ++ty) {
      for (int tx = box.x0 / kTileSize; tx <= box.x1 / kTileSize; ++tx) {
        visit(static_cast<std::size_t>(ty) * tilesX_ + tx);
      }
    }
  }

 private:
  int width_ = 0, height_ = 0;
  int tilesX_ = 0, tilesY_ = 0;
};

}  // namespace facet::detail
