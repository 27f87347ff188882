#pragma once

// Small robust vector helpers shared by the lighting and the geometry code.

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace facet::detail {

struct UnitAndLength {
  glm::dvec3 unit;
  double length;
};

// Normalizes without overflow or NaN: the vector is divided by its largest component first,
// so components near DBL_MAX still give a unit vector (the length may then be +inf, which
// callers treat as "infinitely far"). Nothing for a zero or non-finite vector.
inline std::optional<UnitAndLength> normalizeRobust(const glm::dvec3& v) {
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(largest > 0.0) || !std::isfinite(largest)) return std::nullopt;
  const glm::dvec3 scaled = v / largest;
  const double scaledLength = glm::length(scaled);
  return UnitAndLength{scaled / scaledLength, largest * scaledLength};
}

}  // namespace facet::detail
