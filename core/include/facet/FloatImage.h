#pragma once

/// @file FloatImage.h
/// An image in linear float RGB with a coverage fraction per pixel: what a converged,
/// supersampled reference renders (see Reference.h) and what the error metrics compare
/// (ImageMetrics.h). Layout as Framebuffer: row-major, row 0 at the bottom.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "facet/Color.h"
#include "facet/Framebuffer.h"

namespace facet {

struct FloatImage {
  int width = 0;
  int height = 0;
  /// Linear RGB in [0, 1]: the pixel's area average of what is seen, the surface composited
  /// over the background where it covers only part of the pixel.
  std::vector<Color> color;
  /// The fraction of the pixel's area the surface covers, in [0, 1]; 0 is background.
  std::vector<float> coverage;

  FloatImage() = default;
  /// Black, uncovered. Throws facet::Error for a side outside [1, kMaxImageSide].
  FloatImage(int width, int height);

  std::size_t pixelCount() const { return static_cast<std::size_t>(width) * height; }
  std::size_t indexOf(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
};

/// A rendered frame as a FloatImage: colors divided by 255, coverage 1 where a polygon was
/// drawn (polygonId ≥ 0) and 0 elsewhere. Both spans hold width × height pixels (throws
/// facet::Error otherwise).
FloatImage toFloatImage(std::span<const Rgba8> color, std::span<const std::int32_t> polygonId,
                        int width, int height);
inline FloatImage toFloatImage(const Framebuffer& framebuffer) {
  return toFloatImage(framebuffer.color(), framebuffer.polygonId(), framebuffer.width(),
                      framebuffer.height());
}

/// The image in 8 bits, rounded to nearest (toRgba8), alpha from the coverage.
std::vector<Rgba8> toRgba8(const FloatImage& image);

}  // namespace facet
