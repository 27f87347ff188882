#pragma once

// Axis-aligned boxes in world space: the bounds the rules test lights and the view against.

#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace facet::detail {

struct Box {
  glm::dvec3 low{std::numeric_limits<double>::infinity()};
  glm::dvec3 high{-std::numeric_limits<double>::infinity()};

  bool empty() const { return !(low.x <= high.x && low.y <= high.y && low.z <= high.z); }
  void add(const glm::dvec3& p) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  void add(const Box& other) {
    low = glm::min(low, other.low);
    high = glm::max(high, other.high);
  }
  // Corner i: bit 0 picks x, bit 1 y, bit 2 z from high instead of low.
  glm::dvec3 corner(int i) const {
    return {(i & 1) ? high.x : low.x, (i & 2) ? high.y : low.y, (i & 4) ? high.z : low.z};
  }
  bool contains(const glm::dvec3& p) const {
    return p.x >= low.x && p.x <= high.x && p.y >= low.y && p.y <= high.y && p.z >= low.z &&
           p.z <= high.z;
  }
  glm::dvec3 closestPoint(const glm::dvec3& p) const { return glm::clamp(p, low, high); }
};

}  // namespace facet::detail
