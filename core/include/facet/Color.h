#pragma once

/// @file Color.h
/// Linear RGB colors and the one place where they saturate (see Conventions.h, "Colors").

#include <cstdint>

#include <glm/vec3.hpp>

namespace facet {

/// Linear RGB, nominally in [0, 1] per channel.
using Color = glm::vec3;

/// An 8-bit RGBA pixel, the framebuffer's color format.
struct Rgba8 {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  friend bool operator==(const Rgba8&, const Rgba8&) = default;
};

/// Clamps to [0, 1]. NaN maps to 0, so no NaN can leave the shading stage.
constexpr float saturate(float x) {
  return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
}

/// Clamps each channel to [0, 1] (NaN → 0).
inline Color saturate(const Color& c) {
  return {saturate(c.r), saturate(c.g), saturate(c.b)};
}

/// Converts a channel to 8 bits, rounding to nearest after saturating (0.5/255 → 1).
constexpr std::uint8_t toByte(float x) {
  return static_cast<std::uint8_t>(saturate(x) * 255.0f + 0.5f);
}

/// Converts a color to an opaque 8-bit pixel (rounding to nearest, see `toByte`).
inline Rgba8 toRgba8(const Color& c, float alpha = 1.0f) {
  return {toByte(c.r), toByte(c.g), toByte(c.b), toByte(alpha)};
}

}  // namespace facet
