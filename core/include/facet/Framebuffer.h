#pragma once

/// @file Framebuffer.h
/// The renderer's output: color, depth and the id of the polygon behind every pixel.
/// Layout: row-major, row 0 at the bottom (Conventions.h, "Window"); pixel (x, y) is at
/// index y·width + x in every plane.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "facet/Color.h"
#include "facet/HugePageAllocator.h"

namespace facet {

/// The planes a render writes, owned by the caller: color, depth and polygon id for
/// width × height pixels each, with the layout of Framebuffer (row 0 at the bottom). While
/// a render runs, the depth plane holds depth keys; when it returns, window depths (as
/// Framebuffer::depth()). A
/// caller that keeps its image in its own arrays (the VTK filter renders straight into the
/// output's RGBA and Depth arrays) renders into a view of them; nothing is copied.
struct FramebufferView {
  int width = 0;
  int height = 0;
  Rgba8* color = nullptr;
  float* depth = nullptr;
  std::int32_t* polygonId = nullptr;
};

class Framebuffer {
 public:
  /// Polygon id of a pixel no polygon covers.
  static constexpr std::int32_t kBackgroundId = -1;
  /// Bytes a pixel takes in the three planes.
  static constexpr std::size_t kBytesPerPixel =
      sizeof(Rgba8) + sizeof(float) + sizeof(std::int32_t);

  Framebuffer() = default;
  /// Allocates width × height pixels. Throws facet::Error for a side ≤ 0 or above
  /// kMaxImageSide, or when the memory cannot be allocated (the message says how much).
  Framebuffer(int width, int height);

  /// Changes the size; keeps the allocation when the pixel count does not grow.
  void resize(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t pixelCount() const { return static_cast<std::size_t>(width_) * height_; }
  /// Bytes held by the three planes.
  std::size_t byteSize() const;

  /// RGBA8 colors.
  std::span<Rgba8> color() { return {color_.data(), pixelCount()}; }
  std::span<const Rgba8> color() const { return {color_.data(), pixelCount()}; }
  /// Window depth in [0, 1], 1 = background, computed in double and rounded to the nearest
  /// float (Conventions.h, "Depth"). A polygon may show at depth 1.0 exactly: with a tiny
  /// near plane, every depth rounds to 1; polygonId() says what is covered.
  std::span<float> depth() { return {depth_.data(), pixelCount()}; }
  std::span<const float> depth() const { return {depth_.data(), pixelCount()}; }
  /// Index of the polygon that produced the pixel (in scene order: the polygons of mesh 0,
  /// then mesh 1, ...), or kBackgroundId.
  std::span<std::int32_t> polygonId() { return {polygonId_.data(), pixelCount()}; }
  std::span<const std::int32_t> polygonId() const { return {polygonId_.data(), pixelCount()}; }

  /// The planes of this framebuffer, to render into.
  FramebufferView view() {
    return {width_, height_, color_.data(), depth_.data(), polygonId_.data()};
  }

  std::size_t indexOf(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  Rgba8 colorAt(int x, int y) const { return color_[indexOf(x, y)]; }
  float depthAt(int x, int y) const { return depth_[indexOf(x, y)]; }
  std::int32_t polygonIdAt(int x, int y) const { return polygonId_[indexOf(x, y)]; }

 private:
  int width_ = 0;
  int height_ = 0;
  HugePageVector<Rgba8> color_;
  HugePageVector<float> depth_;
  HugePageVector<std::int32_t> polygonId_;
};

}  // namespace facet
