#pragma once

// The caps the shading puts on its factors (Lighting.h, "Edge cases"), shared by the shading
// and by the rules that bound what a light can contribute.

#include <algorithm>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "facet/Color.h"
#include "facet/Lighting.h"

namespace facet::detail {

// Caps a non-negative factor so that products of a handful of them stay finite in double.
// NaN and negative values map to 0.
inline double capped(double x) {
  return x > 0.0 ? std::min(x, kMaxRadiance) : 0.0;
}
inline glm::dvec3 capped(const Color& c) {
  return {capped(c.r), capped(c.g), capped(c.b)};
}

// A light's color × max(0, intensity), capped.
inline glm::dvec3 radianceOf(const Color& color, double intensity) {
  const double i = std::max(intensity, 0.0);
  return {capped(color.r * i), capped(color.g * i), capped(color.b * i)};
}

// The error bound's radiance (FlatErrorBound.cpp and its SIMD batches, which must agree to the
// bit): color × max(0, intensity), each channel at most kMaxRadiance.
inline glm::dvec3 boundRadianceOf(const Color& color, double intensity) {
  const double i = std::max(intensity, 0.0);
  return glm::min(glm::dvec3(color) * i, glm::dvec3(kMaxRadiance));
}

}  // namespace facet::detail
