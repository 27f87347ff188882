#include "Transform.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "MeshAccess.h"
#include "TransformBatch.h"

namespace facet::detail {
namespace {

// Polygons per sort task.
constexpr std::size_t kPolygonsPerSortTask = 1 << 18;

// The flags of FrameMesh::neededPoints over a task's points.
std::size_t firstFlag(const MeshRange& r) {
  return r.begin >> kNeededPointBits;
}
std::size_t endFlag(const MeshRange& r) {
  return (r.end + kPointsPerNeededFlag - 1) >> kNeededPointBits;
}

// Whether some of a task's points are flagged (null: all are).
bool needed(const std::uint8_t* flags, const MeshRange& r) {
  if (!flags) return true;
  return std::find(flags + firstFlag(r), flags + endFlag(r), std::uint8_t{1}) != flags + endFlag(r);
}

// Projects the task's points, or only its runs of flagged points (`flags` null: all).
void transformRange(const FrameMesh& mesh, const std::uint8_t* flags,
                    const FrameTransform& transform, const MeshRange& r, WindowVertex* vertices,
                    std::uint32_t& outcodes) {
  withTypedMesh(mesh.mesh(), [&](auto points, auto) {
    const auto project = [&](std::size_t begin, std::size_t end) {
      return projectPoints(transform, points.xyz + 3 * begin, end - begin,
                           vertices + mesh.firstVertex + begin);
    };
    if (!flags) {
      outcodes = project(r.begin, r.end);
      return;
    }
    outcodes = 0;
    // The runs of flagged points, each asked for from memory (its points and the lines of
    // its window vertices) while the run before it is projected: the hardware prefetchers
    // restart at every run, and after another program's frame (VTK's in bench/peers.py's
    // paired frames) nothing of the mesh is in cache (core-frame-issue11.md, section 51).
    const std::size_t endF = endFlag(r);
    const auto nextRun = [&](std::size_t f, std::size_t& runEnd) {
      while (f < endF && !flags[f])
        ++f;
      runEnd = f;
      while (runEnd < endF && flags[runEnd])
        ++runEnd;
      return f;
    };
    // The first kPrefetchPoints of a run: by then the hardware's streams have caught on.
    constexpr std::size_t kPrefetchPoints = 128;
    // Inlined by force: a function of prefetches alone is "pure" to GCC, and its calls dropped.
    const auto prefetchRun = [&](std::size_t f, std::size_t runEnd) __attribute__((always_inline)) {
      if (f >= runEnd) return;
      const std::size_t begin = f << kNeededPointBits,
                        end =
                            std::min({r.end, runEnd << kNeededPointBits, begin + kPrefetchPoints});
      const auto* xyz = reinterpret_cast<const char*>(points.xyz + 3 * begin);
      const auto* xyzEnd = reinterpret_cast<const char*>(points.xyz + 3 * end);
      for (const char* line = xyz; line < xyzEnd; line += 64)
        __builtin_prefetch(line);
      const auto* out = reinterpret_cast<const char*>(vertices + mesh.firstVertex + begin);
      const auto* outEnd = reinterpret_cast<const char*>(vertices + mesh.firstVertex + end);
      for (const char* line = out; line < outEnd; line += 64)
        __builtin_prefetch(line, 1);
    };
    std::size_t runEnd = 0;
    std::size_t f = nextRun(firstFlag(r), runEnd);
    while (f < endF) {
      std::size_t followingEnd = 0;
      const std::size_t following = nextRun(runEnd, followingEnd);
      prefetchRun(following, followingEnd);
      outcodes |= project(f << kNeededPointBits, std::min(r.end, runEnd << kNeededPointBits));
      f = following;
      runEnd = followingEnd;
    }
  });
}

// The view distance of each polygon's centroid (+∞ when not finite), with its id.
void sortKeysOfRange(const FrameMesh& mesh, const FrameTransform& transform, const MeshRange& r,
                     std::pair<double, std::uint32_t>* keys) {
  withTypedMesh(mesh.mesh(), [&](auto points, auto polygons) {
    for (std::size_t p = r.begin; p < r.end; ++p) {
      glm::dvec3 sum(0.0);
      const std::size_t n = polygons.size(p);
      for (std::size_t k = 0; k < n; ++k)
        sum += points[polygons.pointId(p, k)];
      double distance = transform.viewDistance(sum / static_cast<double>(n));
      if (!std::isfinite(distance)) distance = std::numeric_limits<double>::infinity();
      const std::size_t id = mesh.firstPolygon + p;
      keys[id] = {distance, static_cast<std::uint32_t>(id)};
    }
  });
}

}  // namespace

bool transformPoints(PhaseRunner& runner, std::span<const FrameMesh> meshes,
                     const FrameTransform& transform, PointRanges& ranges,
                     HugePageVector<WindowVertex>& vertices) {
  const std::size_t total =
      meshes.empty() ? 0 : meshes.back().firstVertex + meshes.back().mesh().points.count;
  vertices.resize(total);
  splitPerMesh(
      meshes.size(), kPointsPerTransformTask,
      [&](std::size_t m) { return meshes[m].mesh().points.count; }, ranges.ranges);
  std::erase_if(ranges.ranges,
                [&](const MeshRange& r) { return !needed(meshes[r.mesh].neededPoints, r); });
  ranges.outcodes.assign(ranges.ranges.size(), 0);
  return runner.run(Phase::Transform, ranges.ranges.size(), [&](std::size_t i) {
    const MeshRange& r = ranges.ranges[i];
    const FrameMesh& mesh = meshes[r.mesh];
    transformRange(mesh, mesh.neededPoints, transform, r, vertices.data(), ranges.outcodes[i]);
  });
}

void transformLatePoints(PhaseRunner& runner, std::span<const FrameMesh> meshes,
                         const FrameTransform& transform, std::vector<MeshRange>& ranges,
                         HugePageVector<WindowVertex>& vertices) {
  splitPerMesh(
      meshes.size(), kPointsPerTransformTask,
      [&](std::size_t m) { return meshes[m].latePoints ? meshes[m].mesh().points.count : 0; },
      ranges);
  std::erase_if(ranges, [&](const MeshRange& r) { return !needed(meshes[r.mesh].latePoints, r); });
  runner.runUnreported(ranges.size(), [&](std::size_t i) {
    const MeshRange& r = ranges[i];
    const FrameMesh& mesh = meshes[r.mesh];
    std::uint32_t outcodes = 0;  // decideBackFaces has run: meshes with late points draw them
    transformRange(mesh, mesh.latePoints, transform, r, vertices.data(), outcodes);
  });
}

// Back faces of a closed surface are hidden while no point of it is beyond the near plane
// (none behind the eye: the eye is outside) and none is non-finite (no polygon dropped).
std::size_t decideBackFaces(std::span<FrameMesh> meshes, const PointRanges& ranges,
                            bool closedSurfaces) {
  std::size_t closedSkipping = 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    std::uint32_t any = 0;
    for (std::size_t i = 0; i < ranges.ranges.size(); ++i) {
      if (ranges.ranges[i].mesh == m) any |= ranges.outcodes[i];
    }
    FrameMesh& mesh = meshes[m];
    const bool culled = mesh.source->material.backfaceCulling;
    const bool hidden =
        closedSurfaces && mesh.mesh().closedSurface && (any & (kBeyondNear | kNonFinite)) == 0;
    mesh.skipBackFaces = culled || hidden;
    closedSkipping += hidden && !culled;
  }
  return closedSkipping;
}

bool sortForPainter(PhaseRunner& runner, std::span<const FrameMesh> meshes,
                    const FrameTransform& transform, std::vector<MeshRange>& ranges,
                    DrawOrder& order) {
  const std::size_t polygons = meshes.empty() ? 0 : meshes.back().endPolygon();
  splitPerMesh(
      meshes.size(), kPolygonsPerSortTask,
      [&](std::size_t m) { return meshes[m].mesh().polygons.count; }, ranges);
  order.keys.resize(polygons);
  const bool completed = runner.run(Phase::Sort, ranges.size(), [&](std::size_t i) {
    sortKeysOfRange(meshes[ranges[i].mesh], transform, ranges[i], order.keys.data());
  });
  std::sort(order.keys.begin(), order.keys.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  order.ids.resize(polygons);
  for (std::size_t i = 0; i < polygons; ++i)
    order.ids[i] = order.keys[i].second;
  return completed;
}

}  // namespace facet::detail
