// Corner normals with vtkPolyDataNormals' meaning (see VertexNormals.h). Per point, the
// corners around it are grouped by a union-find over the edges they share; the union-find
// also tracks each corner's winding relative to its group, which is how polygons of
// opposite winding join one smooth group.

#include "facet/VertexNormals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "MeshAccess.h"
#include "Validate.h"
#include "facet/MeshTriangles.h"
#include "facet/PolygonNormal.h"

namespace facet {
namespace {

constexpr std::uint32_t kNoEntry = std::numeric_limits<std::uint32_t>::max();

std::size_t cornerCount(const MeshView& mesh) {
  if (mesh.polygons.count == 0) return 0;
  return detail::withTypedMesh(
      mesh, [&](auto, auto polygons) { return polygons.begin(mesh.polygons.count); });
}

// Validates the mesh and checks that every corner and normal can be numbered in 32 bits.
std::size_t validatedCornerCount(const MeshView& mesh) {
  validate(mesh);
  const std::size_t corners = cornerCount(mesh);
  if (corners >= kNoEntry || mesh.points.count >= kNoEntry) {
    detail::fail("VertexNormals", "got " + std::to_string(corners) + " corners and " +
                                      std::to_string(mesh.points.count) +
                                      " points; at most 2^32 − 2 of each are supported");
  }
  return corners;
}

// Newell's unit normal per polygon; zero for a degenerate one.
template <class PointsT, class PolygonsT>
std::vector<glm::dvec3> polygonNormals(PointsT points, PolygonsT polygons, std::size_t count,
                                       std::size_t& degenerate) {
  std::vector<glm::dvec3> normals(count, glm::dvec3(0.0));
  for (std::size_t p = 0; p < count; ++p) {
    const auto corner = [&](std::size_t k) { return points[polygons.pointId(p, k)]; };
    const std::size_t n = polygons.size(p);
    const std::optional<glm::dvec3> normal =
        n == 3 ? triangleNormal(corner(0), corner(1), corner(2)) : newellNormal(n, corner);
    if (normal) {
      normals[p] = *normal;
    } else {
      ++degenerate;
    }
  }
  return normals;
}

// Union-find over a point's corners, with each corner's winding relative to its parent
// (parity 1 = opposite), so a group knows how its polygons are oriented to each other.
class OrientedUnionFind {
 public:
  void reset(std::size_t size) {
    parent_.resize(size);
    std::iota(parent_.begin(), parent_.end(), 0u);
    parity_.assign(size, 0);
  }
  // The root of i and i's parity relative to it.
  std::pair<std::uint32_t, std::uint8_t> find(std::uint32_t i) {
    std::uint8_t parity = 0;
    std::uint32_t root = i;
    while (parent_[root] != root) {
      parity ^= parity_[root];
      root = parent_[root];
    }
    return {root, parity};
  }
  // Joins i and j with relative parity `opposite`; false when they are already joined with
  // the other parity (a contradiction: the caller treats that edge as sharp).
  bool unite(std::uint32_t i, std::uint32_t j, std::uint8_t opposite) {
    const auto [rootI, parityI] = find(i);
    const auto [rootJ, parityJ] = find(j);
    if (rootI == rootJ) return (parityI ^ parityJ) == opposite;
    // Attach the later root under the earlier so the result does not depend on edge order.
    const auto [low, high] = std::minmax(rootI, rootJ);
    parent_[high] = low;
    parity_[high] = parityI ^ parityJ ^ opposite;
    return true;
  }

 private:
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint8_t> parity_;
};

// One end of an edge at the current point: the corner, the point at the other end, and
// whether the corner's polygon runs along the edge away from the current point.
struct EdgeEnd {
  std::uint32_t otherPoint;
  std::uint32_t localCorner;
  bool outgoing;
  friend bool operator<(const EdgeEnd& a, const EdgeEnd& b) {
    return a.otherPoint != b.otherPoint ? a.otherPoint < b.otherPoint
                                        : a.localCorner < b.localCorner;
  }
};

template <class PointsT, class PolygonsT>
class NormalBuilder {
 public:
  NormalBuilder(PointsT points, PolygonsT polygons, const MeshView& mesh, std::size_t corners,
                double featureAngleDegrees)
      : polygons_(polygons),
        pointCount_(mesh.points.count),
        polygonCount_(mesh.polygons.count),
        cosFeatureAngle_(std::cos(glm::radians(featureAngleDegrees))) {
    result_.cornerNormal.assign(corners, 0);
    faceNormals_ = polygonNormals(points, polygons, polygonCount_, result_.degeneratePolygons);
    buildPointCorners(corners);
  }

  VertexNormals build() {
    for (std::size_t v = 0; v < pointCount_; ++v)
      buildPoint(static_cast<std::uint32_t>(v));
    return std::move(result_);
  }

 private:
  // Corner c of polygon p, by connectivity index.
  struct Corner {
    std::uint32_t polygon, index;
  };

  // Point → the corners using it (CSR), in connectivity order.
  void buildPointCorners(std::size_t corners) {
    pointStart_.assign(pointCount_ + 1, 0);
    for (std::size_t p = 0; p < polygonCount_; ++p) {
      for (std::size_t k = 0; k < polygons_.size(p); ++k)
        ++pointStart_[polygons_.pointId(p, k) + 1];
    }
    std::partial_sum(pointStart_.begin(), pointStart_.end(), pointStart_.begin());
    pointCorners_.resize(corners);
    std::vector<std::uint32_t> fill(pointStart_.begin(), pointStart_.end() - 1);
    for (std::size_t p = 0; p < polygonCount_; ++p) {
      for (std::size_t k = 0; k < polygons_.size(p); ++k) {
        const std::size_t c = polygons_.begin(p) + k;
        pointCorners_[fill[polygons_.pointId(p, k)]++] = {static_cast<std::uint32_t>(p),
                                                          static_cast<std::uint32_t>(c)};
      }
    }
  }

  // The point after (or before) a corner in its polygon. No modulo: it is this loop's cost.
  std::uint32_t neighbourPoint(const Corner& corner, bool next) const {
    const std::size_t k = corner.index - polygons_.begin(corner.polygon);
    const std::size_t last = polygons_.size(corner.polygon) - 1;
    const std::size_t neighbour = next ? (k == last ? 0 : k + 1) : (k == 0 ? last : k - 1);
    return static_cast<std::uint32_t>(polygons_.pointId(corner.polygon, neighbour));
  }

  void buildPoint(std::uint32_t v) {
    const std::span<const Corner> corners(pointCorners_.data() + pointStart_[v],
                                          pointStart_[v + 1] - pointStart_[v]);
    groups_.reset(corners.size());
    collectEdgeEnds(v, corners);
    joinAcrossSmoothEdges(v, corners);
    emitNormals(v, corners);
  }

  void collectEdgeEnds(std::uint32_t v, std::span<const Corner> corners) {
    ends_.clear();
    for (std::uint32_t i = 0; i < corners.size(); ++i) {
      for (const bool next : {true, false}) {
        const std::uint32_t w = neighbourPoint(corners[i], next);
        if (w != v) ends_.push_back({w, i, next});
      }
    }
    std::sort(ends_.begin(), ends_.end());
  }

  // An edge is smooth when exactly two corners use it (a manifold edge) and their normals,
  // the second reversed if the windings disagree, are within the feature angle.
  void joinAcrossSmoothEdges(std::uint32_t v, std::span<const Corner> corners) {
    for (std::size_t first = 0; first < ends_.size();) {
      std::size_t last = first + 1;
      while (last < ends_.size() && ends_[last].otherPoint == ends_[first].otherPoint)
        ++last;
      if (last - first == 2) joinPair(v, corners, ends_[first], ends_[first + 1]);
      first = last;
    }
  }

  void joinPair(std::uint32_t v, std::span<const Corner> corners, const EdgeEnd& a,
                const EdgeEnd& b) {
    if (a.localCorner == b.localCorner) return;  // a polygon folded back along the edge
    const bool consistent = a.outgoing != b.outgoing;
    if (!consistent && v < a.otherPoint) ++result_.inconsistentEdges;  // count each edge once
    const glm::dvec3& na = faceNormals_[corners[a.localCorner].polygon];
    const glm::dvec3& nb = faceNormals_[corners[b.localCorner].polygon];
    const double cosine = glm::dot(na, nb) * (consistent ? 1.0 : -1.0);
    // A degenerate polygon joins nothing (in VTK its zero normal fails the test too, up to
    // a feature angle of 90°).
    if (na == glm::dvec3(0.0) || nb == glm::dvec3(0.0) || !(cosine > cosFeatureAngle_)) return;
    groups_.unite(a.localCorner, b.localCorner, consistent ? 0 : 1);
  }

  // One normal per (group, winding) pair, in order of first use.
  void emitNormals(std::uint32_t v, std::span<const Corner> corners) {
    sums_.assign(corners.size(), glm::dvec3(0.0));
    for (std::uint32_t i = 0; i < corners.size(); ++i) {
      const auto [root, parity] = groups_.find(i);
      sums_[root] += (parity ? -1.0 : 1.0) * faceNormals_[corners[i].polygon];
    }
    entries_.assign(2 * corners.size(), kNoEntry);
    std::size_t groupCount = 0;
    for (std::uint32_t i = 0; i < corners.size(); ++i) {
      const auto [root, parity] = groups_.find(i);
      groupCount += root == i;
      std::uint32_t& entry = entries_[2 * root + parity];
      if (entry == kNoEntry) entry = addNormal(v, sums_[root], parity);
      result_.cornerNormal[corners[i].index] = entry;
    }
    result_.splitPoints += groupCount > 1;
  }

  std::uint32_t addNormal(std::uint32_t v, const glm::dvec3& sum, std::uint8_t parity) {
    const double length = glm::length(sum);
    // Zero: only degenerate polygons, or normals that cancel exactly (impossible within the
    // feature angle below 90°); never divide by it.
    const glm::dvec3 unit = length > 0.0 ? sum / length : glm::dvec3(0.0);
    result_.normals.push_back(parity ? -unit : unit);
    result_.point.push_back(v);
    return static_cast<std::uint32_t>(result_.normals.size() - 1);
  }

  PolygonsT polygons_;
  std::size_t pointCount_, polygonCount_;
  double cosFeatureAngle_;
  VertexNormals result_;
  std::vector<glm::dvec3> faceNormals_;
  std::vector<std::uint32_t> pointStart_;
  std::vector<Corner> pointCorners_;
  // Per-point scratch, reused.
  OrientedUnionFind groups_;
  std::vector<EdgeEnd> ends_;
  std::vector<glm::dvec3> sums_;
  std::vector<std::uint32_t> entries_;
};

// Unit, or nothing for a zero or non-finite input normal.
std::optional<glm::dvec3> usableNormal(const glm::dvec3& n) {
  const double length = glm::length(n);
  if (!std::isfinite(length) || !(length > 0.0)) return std::nullopt;
  return n / length;
}

}  // namespace

VertexNormals computeVertexNormals(const MeshView& mesh, const VertexNormalOptions& options) {
  detail::requireInRange(options.featureAngleDegrees, 0.0, 180.0,
                         "VertexNormalOptions.featureAngleDegrees");
  const std::size_t corners = validatedCornerCount(mesh);
  return detail::withTypedMesh(mesh, [&](auto points, auto polygons) {
    return NormalBuilder(points, polygons, mesh, corners, options.featureAngleDegrees).build();
  });
}

VertexNormals fromPointNormals(const MeshView& mesh, const PointArray& pointNormals) {
  const std::size_t corners = validatedCornerCount(mesh);
  if (pointNormals.count != mesh.points.count || (pointNormals.count > 0 && !pointNormals.data)) {
    detail::fail("fromPointNormals", "got " + std::to_string(pointNormals.count) + " normals for " +
                                         std::to_string(mesh.points.count) + " points");
  }
  VertexNormals result;
  result.cornerNormal.assign(corners, 0);
  std::vector<std::uint32_t> entryOfPoint(mesh.points.count, kNoEntry);
  const auto add = [&](const glm::dvec3& normal, std::size_t point) {
    result.normals.push_back(normal);
    result.point.push_back(static_cast<std::uint32_t>(point));
    return static_cast<std::uint32_t>(result.normals.size() - 1);
  };
  detail::withTypedMesh(mesh, [&](auto points, auto polygons) {
    const std::vector<glm::dvec3> faces =
        polygonNormals(points, polygons, mesh.polygons.count, result.degeneratePolygons);
    for (std::size_t p = 0; p < mesh.polygons.count; ++p) {
      for (std::size_t k = 0; k < polygons.size(p); ++k) {
        const std::size_t v = polygons.pointId(p, k);
        std::uint32_t& slot = result.cornerNormal[polygons.begin(p) + k];
        if (const auto n = usableNormal(pointAt(pointNormals, v))) {
          if (entryOfPoint[v] == kNoEntry) entryOfPoint[v] = add(*n, v);
          slot = entryOfPoint[v];
        } else {
          slot = add(faces[p], v);
          ++result.replacedNormals;
        }
      }
    }
  });
  return result;
}

}  // namespace facet
