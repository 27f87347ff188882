#include "facet/FloatImage.h"

#include <string>

#include "Validate.h"
#include "facet/Conventions.h"

namespace facet {

FloatImage::FloatImage(int w, int h) : width(w), height(h) {
  detail::requireInRange(w, 1, kMaxImageSide, "FloatImage width");
  detail::requireInRange(h, 1, kMaxImageSide, "FloatImage height");
  color.assign(pixelCount(), Color(0.0f));
  coverage.assign(pixelCount(), 0.0f);
}

FloatImage toFloatImage(std::span<const Rgba8> color, std::span<const std::int32_t> polygonId,
                        int width, int height) {
  FloatImage image(width, height);
  if (color.size() != image.pixelCount() || polygonId.size() != image.pixelCount()) {
    detail::fail("toFloatImage", "has " + std::to_string(color.size()) + " colors and " +
                                     std::to_string(polygonId.size()) + " ids for " +
                                     std::to_string(width) + "x" + std::to_string(height) +
                                     " pixels");
  }
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    image.color[i] = Color(color[i].r, color[i].g, color[i].b) / 255.0f;
    image.coverage[i] = polygonId[i] >= 0 ? 1.0f : 0.0f;
  }
  return image;
}

std::vector<Rgba8> toRgba8(const FloatImage& image) {
  std::vector<Rgba8> pixels(image.pixelCount());
  for (std::size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = facet::toRgba8(image.color[i], image.coverage[i]);
  return pixels;
}

}  // namespace facet
