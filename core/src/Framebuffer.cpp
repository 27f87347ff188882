#include "facet/Framebuffer.h"

#include <new>
#include <string>

#include "Validate.h"
#include "facet/Conventions.h"
#include "facet/Error.h"

namespace facet {

Framebuffer::Framebuffer(int width, int height) {
  resize(width, height);
}

std::size_t Framebuffer::byteSize() const {
  return pixelCount() * kBytesPerPixel;
}

void Framebuffer::resize(int width, int height) {
  detail::requireInRange(width, 1, kMaxImageSide, "Framebuffer width");
  detail::requireInRange(height, 1, kMaxImageSide, "Framebuffer height");
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  try {
    color_.resize(pixels);
    depth_.resize(pixels, 1.0f);
    polygonId_.resize(pixels, kBackgroundId);
  } catch (const std::bad_alloc&) {
    width_ = height_ = 0;
    color_ = {};
    depth_ = {};
    polygonId_ = {};
    throw Error("Framebuffer " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                std::to_string(pixels * kBytesPerPixel) + " bytes: allocation failed");
  }
  width_ = width;
  height_ = height;
}

}  // namespace facet
