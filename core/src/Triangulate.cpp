#include "Triangulate.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/common.hpp>

namespace facet::detail {
namespace {

double cross(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// p inside or on triangle abc (counter-clockwise).
bool inTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b,
                const glm::dvec2& c) {
  return cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0;
}

bool isEar(std::span<const glm::dvec2> projected, const std::vector<std::uint32_t>& remaining,
           std::size_t i) {
  const std::size_t n = remaining.size();
  const std::uint32_t prev = remaining[(i + n - 1) % n];
  const std::uint32_t curr = remaining[i];
  const std::uint32_t next = remaining[(i + 1) % n];
  const glm::dvec2 &a = projected[prev], &b = projected[curr], &c = projected[next];
  if (!(cross(a, b, c) > 0.0)) return false;  // reflex or flat corner
  for (std::uint32_t other : remaining) {
    if (other == prev || other == curr || other == next) continue;
    const glm::dvec2& p = projected[other];
    if (p == a || p == b || p == c) continue;  // a repeated point does not block
    if (inTriangle(p, a, b, c)) return false;
  }
  return true;
}

// Segments ab and cd cross at a point interior to both.
bool properlyCross(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                   const glm::dvec2& d) {
  const auto opposite = [](double s, double t) {
    return (s > 0.0 && t < 0.0) || (s < 0.0 && t > 0.0);
  };
  return opposite(cross(a, b, c), cross(a, b, d)) && opposite(cross(c, d, a), cross(c, d, b));
}

}  // namespace

void projectToPolygonPlane(std::span<const glm::dvec3> vertices, const glm::dvec3& normal,
                           std::vector<glm::dvec2>& projected) {
  const glm::dvec3 n = glm::abs(normal);
  const int axis = (n.x >= n.y && n.x >= n.z) ? 0 : (n.y >= n.z ? 1 : 2);
  const bool positive = normal[axis] > 0.0;
  // (u, v) axes such that u × v points along +axis; swapped when the normal points along −axis.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  projected.clear();
  for (const glm::dvec3& vertex : vertices) {
    const glm::dvec3 d = vertex - vertices[0];
    projected.push_back(positive ? glm::dvec2(d[u], d[v]) : glm::dvec2(d[v], d[u]));
  }
}

bool isConvex(std::span<const glm::dvec2> projected) {
  const std::size_t n = projected.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (cross(projected[i], projected[(i + 1) % n], projected[(i + 2) % n]) < 0.0) return false;
  }
  return true;
}

bool selfIntersects(std::span<const glm::dvec2> projected, TriangulationScratch& scratch) {
  const std::size_t n = projected.size();
  const auto start = [&](std::uint32_t e) { return projected[e]; };
  const auto end = [&](std::uint32_t e) { return projected[(e + 1) % n]; };
  const auto left = [&](std::uint32_t e) { return std::min(start(e).x, end(e).x); };
  const auto right = [&](std::uint32_t e) { return std::max(start(e).x, end(e).x); };
  std::vector<std::uint32_t>& order = scratch.edgeOrder;
  order.resize(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](auto e, auto f) { return left(e) < left(f); });
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t e = order[i];
    for (std::size_t j = i + 1; j < n && left(order[j]) <= right(e); ++j) {
      const std::uint32_t f = order[j];
      const bool adjacent = (e + 1) % n == f || (f + 1) % n == e;
      if (!adjacent && properlyCross(start(e), end(e), start(f), end(f))) return true;
    }
  }
  return false;
}

void earClip(std::span<const glm::dvec2> projected, TriangulationScratch& scratch,
             std::vector<LocalTriangle>& triangles) {
  std::vector<std::uint32_t>& remaining = scratch.remaining;
  remaining.clear();
  for (std::uint32_t i = 0; i < projected.size(); ++i)
    remaining.push_back(i);
  std::size_t candidate = 0;
  std::size_t misses = 0;
  while (remaining.size() > 3) {
    const std::size_t n = remaining.size();
    candidate %= n;
    // With no ear left (a self-intersecting or numerically flat polygon), cut the corner
    // anyway so the loop always ends.
    if (misses >= n || isEar(projected, remaining, candidate)) {
      triangles.push_back({remaining[(candidate + n - 1) % n], remaining[candidate],
                           remaining[(candidate + 1) % n]});
      remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(candidate));
      misses = 0;
    } else {
      ++candidate;
      ++misses;
    }
  }
  if (remaining.size() == 3) triangles.push_back({remaining[0], remaining[1], remaining[2]});
}

}  // namespace facet::detail
