#include "Triangulate.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

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

// The polygon ear clipping cuts down: a doubly linked ring of the corners left, and which
// of them are reflex (or flat), the only ones that can lie inside an ear of a simple polygon
// (Eberly, "Triangulation by Ear Clipping", 2008).
class EarRing {
 public:
  EarRing(std::span<const glm::dvec2> projected, TriangulationScratch& scratch)
      : p_(projected),
        next_(scratch.next),
        previous_(scratch.previous),
        reflex_(scratch.reflex),
        reflexCorners_(scratch.reflexCorners) {
    const auto n = static_cast<std::uint32_t>(projected.size());
    next_.resize(n);
    previous_.resize(n);
    reflex_.assign(n, 0);
    reflexCorners_.clear();
    for (std::uint32_t i = 0; i < n; ++i) {
      next_[i] = (i + 1) % n;
      previous_[i] = (i + n - 1) % n;
    }
    for (std::uint32_t i = 0; i < n; ++i)
      update(i);
  }
  std::uint32_t next(std::uint32_t i) const { return next_[i]; }
  std::uint32_t previous(std::uint32_t i) const { return previous_[i]; }

  // A corner whose triangle has no area (a repeated or collinear point, or a spike back):
  // cutting it changes no covered point.
  bool isFlat(std::uint32_t i) const { return cross(p_[previous_[i]], p_[i], p_[next_[i]]) == 0.0; }
  bool isEar(std::uint32_t i) const {
    const std::uint32_t a = previous_[i], c = next_[i];
    if (isReflex(i)) return false;
    const glm::dvec2 &pa = p_[a], &pb = p_[i], &pc = p_[c];
    for (std::uint32_t other : reflexCorners_) {
      if (!isReflex(other) || other == a || other == c) continue;
      const glm::dvec2& q = p_[other];
      if (q == pa || q == pb || q == pc) continue;  // a repeated point does not block
      if (inTriangle(q, pa, pb, pc)) return false;
    }
    return true;
  }
  // Cuts corner i off; its neighbours' corners change, so their reflexness too. (In a simple
  // polygon they only turn convex; repeated points can make one turn reflex.)
  void cut(std::uint32_t i) {
    const std::uint32_t a = previous_[i], c = next_[i];
    next_[a] = c;
    previous_[c] = a;
    reflex_[i] &= 2u;
    update(a);
    update(c);
  }

 private:
  // reflex_: bit 0 reflex now, bit 1 in reflexCorners_ already.
  void update(std::uint32_t i) {
    const bool reflex = !isConvexCorner(i);
    if (reflex && !(reflex_[i] & 2u)) reflexCorners_.push_back(i);
    reflex_[i] = static_cast<std::uint8_t>((reflex_[i] & 2u) | (reflex ? 3u : 0u));
  }
  bool isReflex(std::uint32_t i) const { return reflex_[i] & 1u; }
  bool isConvexCorner(std::uint32_t i) const {
    return cross(p_[previous_[i]], p_[i], p_[next_[i]]) > 0.0;
  }

  std::span<const glm::dvec2> p_;
  std::vector<std::uint32_t>& next_;
  std::vector<std::uint32_t>& previous_;
  std::vector<std::uint8_t>& reflex_;
  std::vector<std::uint32_t>& reflexCorners_;
};

// Segments ab and cd cross at a point interior to both.
bool properlyCross(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                   const glm::dvec2& d) {
  const auto opposite = [](double s, double t) {
    return (s > 0.0 && t < 0.0) || (s < 0.0 && t > 0.0);
  };
  return opposite(cross(a, b, c), cross(a, b, d)) && opposite(cross(c, d, a), cross(c, d, b));
}

// Calls turn(in, out) for each pair of successive edges of nonzero length around the ring:
// repeated points make zero-length edges, which have no direction (and would hide the turn
// at a repeated corner).
template <class Turn>
void forEachTurn(std::span<const glm::dvec2> projected, const Turn& turn) {
  const std::size_t n = projected.size();
  const auto edge = [&](std::size_t i) { return projected[(i + 1) % n] - projected[i]; };
  std::size_t last = n;
  while (last > 0 && edge(last - 1) == glm::dvec2(0.0))
    --last;
  if (last == 0) return;
  glm::dvec2 in = edge(last - 1);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec2 out = edge(i);
    if (out == glm::dvec2(0.0)) continue;
    turn(in, out);
    in = out;
  }
}

double crossOf(const glm::dvec2& in, const glm::dvec2& out) {
  return in.x * out.y - in.y * out.x;
}

// True when no corner turns clockwise or back (collinear corners allowed): the polygon is
// convex, or it winds around more than once (a pentagram) and self-intersects.
bool isConvex(std::span<const glm::dvec2> projected) {
  bool convex = true;
  forEachTurn(projected, [&](const glm::dvec2& in, const glm::dvec2& out) {
    const double turn = crossOf(in, out);
    convex = convex && (turn > 0.0 || (turn == 0.0 && glm::dot(in, out) > 0.0));
  });
  return convex;
}

// Whether the edge directions turn through more than one full turn: a polygon that only
// turns left and does is a star (a pentagram winds twice).
bool windsMoreThanOnce(std::span<const glm::dvec2> projected) {
  double turning = 0.0;
  forEachTurn(projected, [&](const glm::dvec2& in, const glm::dvec2& out) {
    turning += std::atan2(crossOf(in, out), glm::dot(in, out));
  });
  return std::abs(turning) > 3.0 * M_PI;
}

// True when two edges of the closed outline cross, each strictly across the other's line.
// Touching is not crossing (a repeated point, a vertex on another edge, collinear overlaps):
// ear clipping handles those. A sweep over x: O(n log n) plus the pairs of edges whose
// x-extents overlap.
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

// Ear clipping (O(n·r), r reflex corners): triangles covering a simple polygon, counter-
// clockwise in the projected plane; flat corners (repeated or collinear points) are cut
// without one. It terminates for any input (when no ear is left, from rounding, it cuts a
// corner anyway).
void earClip(std::span<const glm::dvec2> projected, TriangulationScratch& scratch,
             std::vector<LocalTriangle>& triangles) {
  EarRing ring(projected, scratch);
  std::size_t left = projected.size();
  std::uint32_t corner = 0;
  std::size_t misses = 0;
  while (left > 3) {
    // With no ear left (rounding), cut the corner anyway so the loop always ends.
    const bool flat = ring.isFlat(corner);
    if (flat || misses >= left || ring.isEar(corner)) {
      if (!flat) triangles.push_back({ring.previous(corner), corner, ring.next(corner)});
      const std::uint32_t after = ring.next(corner);
      ring.cut(corner);
      corner = after;
      --left;
      misses = 0;
    } else {
      corner = ring.next(corner);
      ++misses;
    }
  }
  if (left == 3 && !ring.isFlat(corner)) {
    triangles.push_back({ring.previous(corner), corner, ring.next(corner)});
  }
}

void fanFromCornerZero(std::size_t count, std::vector<LocalTriangle>& triangles) {
  for (std::uint32_t k = 1; k + 1 < count; ++k)
    triangles.push_back({0, k, k + 1});
}

// Halves the chain first..last (closed by last → first) at its middle corner, recursively.
void halveConvex(std::size_t count, std::vector<LocalTriangle>& triangles) {
  const auto split = [&](auto& self, std::uint32_t first, std::uint32_t last) -> void {
    if (last - first < 2) return;
    const std::uint32_t middle = first + (last - first) / 2;
    triangles.push_back({first, middle, last});
    self(self, first, middle);
    self(self, middle, last);
  };
  split(split, 0, static_cast<std::uint32_t>(count - 1));
}

}  // namespace

void triangulate(std::span<const glm::dvec2> projected, TriangulationScratch& scratch,
                 std::vector<LocalTriangle>& triangles) {
  const std::size_t n = projected.size();
  const bool convex = isConvex(projected);
  if (convex && n > kLargestFan && !windsMoreThanOnce(projected)) {
    halveConvex(n, triangles);
  } else if (convex || selfIntersects(projected, scratch)) {
    fanFromCornerZero(n, triangles);
  } else {
    earClip(projected, scratch, triangles);
  }
}

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

void triangulatePolygon(std::span<const glm::dvec3> corners, const glm::dvec3& normal,
                        TriangulationScratch& scratch, std::vector<LocalTriangle>& triangles) {
  projectToPolygonPlane(corners, normal, scratch.projected);
  triangulate(scratch.projected, scratch, triangles);
}

}  // namespace facet::detail
