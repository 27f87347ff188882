// Corner normals with vtkPolyDataNormals' meaning (see VertexNormals.h). Per point, the
// corners around it are grouped by a union-find over the edges they share; the union-find
// also tracks each corner's winding relative to its group, which is how polygons of
// opposite winding join one smooth group.

#include "facet/VertexNormals.h"

#include <algorithm>
#include <atomic>
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

// Blocks of work: polygons or points per task. Fixed, so the blocks (and the order their
// results are joined in) are the same for any thread count.
constexpr std::size_t kBlock = 1 << 12;

// Runs work(begin, end) over [0, count) in blocks of kBlock, through `parallel` when given.
void forBlocks(const ParallelFor& parallel, std::size_t count,
               const std::function<void(std::size_t, std::size_t)>& work) {
  if (parallel) {
    parallel(count, kBlock, work);
    return;
  }
  for (std::size_t begin = 0; begin < count; begin += kBlock)
    work(begin, std::min(count, begin + kBlock));
}

// Newell's unit normal per polygon; zero for a degenerate one (counted in `degenerate`).
template <class PointsT, class PolygonsT>
std::vector<glm::dvec3> polygonNormals(PointsT points, PolygonsT polygons, std::size_t count,
                                       std::size_t& degenerate, const ParallelFor& parallel) {
  std::vector<glm::dvec3> normals(count, glm::dvec3(0.0));
  std::atomic<std::size_t> degenerates{0};
  forBlocks(parallel, count, [&](std::size_t begin, std::size_t end) {
    std::size_t found = 0;
    for (std::size_t p = begin; p < end; ++p) {
      const auto corner = [&](std::size_t k) { return points[polygons.pointId(p, k)]; };
      const std::size_t n = polygons.size(p);
      const std::optional<glm::dvec3> normal =
          n == 3 ? triangleNormal(corner(0), corner(1), corner(2)) : newellNormal(n, corner);
      if (normal) {
        normals[p] = *normal;
      } else {
        ++found;
      }
    }
    degenerates += found;
  });
  degenerate += degenerates;
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

// The normals of a block of points, in point order, before they are joined: `cornerNormal`
// of their corners then holds indices into this block's `normals`.
struct PointBlock {
  std::vector<glm::dvec3> normals;
  std::vector<std::uint32_t> point;
  std::size_t splitPoints = 0, inconsistentEdges = 0;
};

// One task's space for a point at a time, reused.
struct PointScratch {
  OrientedUnionFind groups;
  std::vector<EdgeEnd> ends;
  std::vector<glm::dvec3> sums;
  std::vector<std::uint32_t> entries;
};

template <class PointsT, class PolygonsT>
class NormalBuilder {
 public:
  NormalBuilder(PointsT points, PolygonsT polygons, const MeshView& mesh, std::size_t corners,
                double featureAngleDegrees, const ParallelFor& parallel)
      : polygons_(polygons),
        pointCount_(mesh.points.count),
        polygonCount_(mesh.polygons.count),
        cosFeatureAngle_(std::cos(glm::radians(featureAngleDegrees))),
        parallel_(parallel) {
    result_.cornerNormal.assign(corners, 0);
    faceNormals_ =
        polygonNormals(points, polygons, polygonCount_, result_.degeneratePolygons, parallel);
    buildPointCorners(corners);
  }

  // Blocks of points in parallel, each numbering its normals from 0; then the blocks joined
  // in point order, their corners' indices moved by the normals of the blocks before: the
  // normals of one point after another, whatever the threads.
  VertexNormals build() {
    std::vector<PointBlock> blocks((pointCount_ + kBlock - 1) / kBlock);
    forBlocks(parallel_, pointCount_, [&](std::size_t begin, std::size_t end) {
      PointScratch scratch;
      PointBlock& block = blocks[begin / kBlock];
      for (std::size_t v = begin; v < end; ++v)
        buildPoint(static_cast<std::uint32_t>(v), scratch, block);
    });
    std::vector<std::uint32_t> firstNormal(blocks.size() + 1, 0);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      firstNormal[b + 1] = firstNormal[b] + static_cast<std::uint32_t>(blocks[b].normals.size());
      result_.splitPoints += blocks[b].splitPoints;
      result_.inconsistentEdges += blocks[b].inconsistentEdges;
    }
    result_.normals.resize(firstNormal.back());
    result_.point.resize(firstNormal.back());
    forBlocks(parallel_, pointCount_, [&](std::size_t begin, std::size_t end) {
      const std::size_t b = begin / kBlock;
      PointBlock& block = blocks[b];
      std::copy(block.normals.begin(), block.normals.end(),
                result_.normals.begin() + firstNormal[b]);
      std::copy(block.point.begin(), block.point.end(), result_.point.begin() + firstNormal[b]);
      for (std::uint32_t i = pointStart_[begin]; i < pointStart_[end]; ++i)
        result_.cornerNormal[pointCorners_[i].index] += firstNormal[b];
      block = {};
    });
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

  void buildPoint(std::uint32_t v, PointScratch& scratch, PointBlock& block) {
    const std::span<const Corner> corners(pointCorners_.data() + pointStart_[v],
                                          pointStart_[v + 1] - pointStart_[v]);
    scratch.groups.reset(corners.size());
    collectEdgeEnds(v, corners, scratch.ends);
    joinAcrossSmoothEdges(v, corners, scratch, block);
    emitNormals(v, corners, scratch, block);
  }

  void collectEdgeEnds(std::uint32_t v, std::span<const Corner> corners,
                       std::vector<EdgeEnd>& ends) const {
    ends.clear();
    for (std::uint32_t i = 0; i < corners.size(); ++i) {
      for (const bool next : {true, false}) {
        const std::uint32_t w = neighbourPoint(corners[i], next);
        if (w != v) ends.push_back({w, i, next});
      }
    }
    std::sort(ends.begin(), ends.end());
  }

  // An edge is smooth when exactly two corners use it (a manifold edge) and their normals,
  // the second reversed if the windings disagree, are within the feature angle.
  void joinAcrossSmoothEdges(std::uint32_t v, std::span<const Corner> corners,
                             PointScratch& scratch, PointBlock& block) const {
    const std::vector<EdgeEnd>& ends = scratch.ends;
    for (std::size_t first = 0; first < ends.size();) {
      std::size_t last = first + 1;
      while (last < ends.size() && ends[last].otherPoint == ends[first].otherPoint)
        ++last;
      if (last - first == 2) joinPair(v, corners, ends[first], ends[first + 1], scratch, block);
      first = last;
    }
  }

  void joinPair(std::uint32_t v, std::span<const Corner> corners, const EdgeEnd& a,
                const EdgeEnd& b, PointScratch& scratch, PointBlock& block) const {
    if (a.localCorner == b.localCorner) return;  // a polygon folded back along the edge
    const bool consistent = a.outgoing != b.outgoing;
    if (!consistent && v < a.otherPoint) ++block.inconsistentEdges;  // count each edge once
    const glm::dvec3& na = faceNormals_[corners[a.localCorner].polygon];
    const glm::dvec3& nb = faceNormals_[corners[b.localCorner].polygon];
    const double cosine = glm::dot(na, nb) * (consistent ? 1.0 : -1.0);
    // A degenerate polygon joins nothing (in VTK its zero normal fails the test too, up to
    // a feature angle of 90°).
    if (na == glm::dvec3(0.0) || nb == glm::dvec3(0.0) || !(cosine > cosFeatureAngle_)) return;
    scratch.groups.unite(a.localCorner, b.localCorner, consistent ? 0 : 1);
  }

  // One normal per (group, winding) pair, in order of first use.
  void emitNormals(std::uint32_t v, std::span<const Corner> corners, PointScratch& scratch,
                   PointBlock& block) {
    scratch.sums.assign(corners.size(), glm::dvec3(0.0));
    for (std::uint32_t i = 0; i < corners.size(); ++i) {
      const auto [root, parity] = scratch.groups.find(i);
      scratch.sums[root] += (parity ? -1.0 : 1.0) * faceNormals_[corners[i].polygon];
    }
    scratch.entries.assign(2 * corners.size(), kNoEntry);
    std::size_t groupCount = 0;
    for (std::uint32_t i = 0; i < corners.size(); ++i) {
      const auto [root, parity] = scratch.groups.find(i);
      groupCount += root == i;
      std::uint32_t& entry = scratch.entries[2 * root + parity];
      if (entry == kNoEntry) entry = addNormal(v, scratch.sums[root], parity, block);
      result_.cornerNormal[corners[i].index] = entry;
    }
    block.splitPoints += groupCount > 1;
  }

  static std::uint32_t addNormal(std::uint32_t v, const glm::dvec3& sum, std::uint8_t parity,
                                 PointBlock& block) {
    const double length = glm::length(sum);
    // Zero: only degenerate polygons, or normals that cancel exactly (impossible within the
    // feature angle below 90°); never divide by it.
    const glm::dvec3 unit = length > 0.0 ? sum / length : glm::dvec3(0.0);
    block.normals.push_back(parity ? -unit : unit);
    block.point.push_back(v);
    return static_cast<std::uint32_t>(block.normals.size() - 1);
  }

  PolygonsT polygons_;
  std::size_t pointCount_, polygonCount_;
  double cosFeatureAngle_;
  const ParallelFor& parallel_;
  VertexNormals result_;
  std::vector<glm::dvec3> faceNormals_;
  std::vector<std::uint32_t> pointStart_;
  std::vector<Corner> pointCorners_;
};

// Unit, or nothing for a zero or non-finite input normal.
std::optional<glm::dvec3> usableNormal(const glm::dvec3& n) {
  const double length = glm::length(n);
  if (!std::isfinite(length) || !(length > 0.0)) return std::nullopt;
  return n / length;
}

}  // namespace

VertexNormals computeVertexNormals(const MeshView& mesh, const VertexNormalOptions& options,
                                   const ParallelFor& parallel) {
  detail::requireInRange(options.featureAngleDegrees, 0.0, 180.0,
                         "VertexNormalOptions.featureAngleDegrees");
  const std::size_t corners = validatedCornerCount(mesh);
  return detail::withTypedMesh(mesh, [&](auto points, auto polygons) {
    return NormalBuilder(points, polygons, mesh, corners, options.featureAngleDegrees, parallel)
        .build();
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
        polygonNormals(points, polygons, mesh.polygons.count, result.degeneratePolygons, {});
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
