#include "MeshCache.h"

#include <algorithm>

#include "BackFacingBlocks.h"
#include "FaceNormal.h"
#include "Transform.h"

namespace facet::detail {
namespace {

// Polygons per validation task: large, the work per polygon is a few loads.
constexpr std::size_t kPolygonsPerTask = 1 << 18;
// Points per bounds task, and blocks per block task.
constexpr std::size_t kPointsPerBoundsTask = 1 << 16;
constexpr std::size_t kBlocksPerTask = 64;

// The box of the finite points among [begin, end); false when some point is not finite.
bool boundPoints(const MeshView& mesh, std::size_t begin, std::size_t end, Box& box) {
  return withTypedMesh(mesh, [&](auto points, auto) {
    bool finite = true;
    for (std::size_t i = begin; i < end; ++i) {
      const glm::dvec3 p = points[i];
      // Qualified: in the unity build LightCulling.cpp's isFinite(const Box&), in the same
      // anonymous namespace, would hide detail::isFinite from unqualified lookup here.
      if (detail::isFinite(p)) {
        box.add(p);
      } else {
        finite = false;
      }
    }
    return finite;
  });
}

// Whether a mesh's back-face blocks' point flags or its scattered blocks' flags could reach
// past 32 bits (BackPointFlags): its blocks keep their spans instead (MeshFacts::wideBackSpans).
bool wideBackFlags(const MeshView& mesh) {
  const std::size_t flags = (mesh.points.count + kPointsPerNeededFlag - 1) >> kNeededPointBits;
  return flags >= kReadWholeBackBlock || mesh.polygons.connectivitySize >= kReadWholeBackBlock;
}

// Block b's box and finiteness, from the points its polygons use, its
// back-face blocks, and its polygons' normals: each polygon read once (measureBackBlock).
// The blocks' compact records need the view-culling block's box: they are measured first. A
// scattered block's flags go to the end of `scattered` (the task's), its BackPointFlags
// pointing there until collectScatteredFlags moves them to the mesh's.
void measureBlock(const MeshView& mesh, std::size_t b, MeshFacts& facts,
                  std::vector<std::uint32_t>& scattered) {
  constexpr std::size_t kBackBlocksPerBlock = kPolygonsPerBlock / kPolygonsPerBackBlock;
  const std::size_t begin = b * kPolygonsPerBlock;
  const std::size_t end = std::min(mesh.polygons.count, begin + kPolygonsPerBlock);
  BackBlock backs[kBackBlocksPerBlock];
  Box box;
  bool finite = true;
  std::size_t count = 0;
  for (std::size_t first = begin; first < end; first += kPolygonsPerBackBlock) {
    BackBlock& back = backs[count++] = measureBackBlock(
        mesh, first, std::min(end, first + kPolygonsPerBackBlock), facts.faceNormals.data());
    box.add(back.box);
    finite = finite && back.allFinite;
  }
  facts.blocks[b] = box;
  facts.blockFinite[b] = finite;
  const BackBlockFrame frame = facts.backFrames[b] = backFrameOf(box);
  const bool wide = !facts.wideBackSpans.empty();
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t index = (begin >> kBackBlockBits) + i;
    const BackBlock& back = backs[i];
    facts.backTests[index] = testOf(back, frame);
    BackPointFlags flags = pointFlagsOf(back, mesh.points.count);
    if (wide) {
      flags = BackPointFlags{kReadWholeBackBlock, 0, 0, 0};
      facts.wideBackSpans[2 * index] = back.lowPoints;
      facts.wideBackSpans[2 * index + 1] = back.highPoints;
    } else if (flags.lowFirst == kReadWholeBackBlock) {
      flags.highFirst = static_cast<std::uint32_t>(scattered.size());
      scattered.insert(scattered.end(), back.scatteredPointFlags.begin(),
                       back.scatteredPointFlags.end());
      flags.highEnd = static_cast<std::uint32_t>(scattered.size());
    }
    facts.backPointFlags[index] = flags;
  }
}

// Whether polygons [begin, end) are triangles stored in order: offsets[p] = 3p.
bool areTriangles(const MeshView& mesh, std::size_t begin, std::size_t end) {
  return withTypedMesh(mesh, [&](auto, auto polygons) {
    for (std::size_t p = begin; p <= end; ++p) {
      if (polygons.begin(p) != 3 * p) return false;
    }
    return true;
  });
}

void sizeBlocks(MeshFacts& facts, std::size_t polygons, bool wide) {
  const std::size_t blocks = (polygons + kPolygonsPerBlock - 1) / kPolygonsPerBlock;
  facts.blocks.resize(blocks);
  facts.blockFinite.resize(blocks);
  facts.faceNormals.resize(polygons);
  const std::size_t backBlocks = (polygons + kPolygonsPerBackBlock - 1) / kPolygonsPerBackBlock;
  facts.backTests.resize(backBlocks);
  facts.backTests.shrink_to_fit();
  facts.backPointFlags.resize(backBlocks);
  facts.backPointFlags.shrink_to_fit();
  facts.backFrames.resize(blocks);
  facts.backFrames.shrink_to_fit();
  facts.scatteredPointFlags.clear();
  facts.wideBackSpans.clear();
  if (wide) facts.wideBackSpans.resize(2 * backBlocks);
  facts.wideBackSpans.shrink_to_fit();
}

}  // namespace

Box boundsOf(const MeshView& mesh) {
  Box box;
  boundPoints(mesh, 0, mesh.points.count, box);
  return box;
}

MeshIdentity MeshIdentity::of(const MeshView& mesh) {
  return {mesh.points.data,
          mesh.polygons.offsets,
          mesh.polygons.connectivity,
          mesh.points.type,
          mesh.polygons.type,
          mesh.points.count,
          mesh.polygons.count,
          mesh.polygons.connectivitySize,
          mesh.version};
}

bool MeshCache::update(PhaseRunner& runner, const Scene& scene, bool bounds) {
  const std::size_t n = scene.meshes.size();
  facts_.resize(n);
  checking_.assign(n, 0);
  measuring_.assign(n, 0);
  bounding_.assign(n, 0);
  for (std::size_t m = 0; m < n; ++m) {
    MeshFacts& facts = facts_[m];
    const MeshIdentity identity = MeshIdentity::of(scene.meshes[m].mesh);
    const bool versioned = identity.version != 0;
    if (versioned && facts.measured && facts.identity == identity) continue;
    facts.identity = identity;
    facts.measured = facts.bounded = facts.allTriangles = false;
    checking_[m] = 1;
    measuring_[m] = versioned;
    bounding_[m] = versioned || bounds;
  }
  return validate(runner, scene) && measure(runner, scene);
}

// Offsets and point ids of the meshes not known already, in parallel.
bool MeshCache::validate(PhaseRunner& runner, const Scene& scene) {
  splitPerMesh(
      scene.meshes.size(), kPolygonsPerTask,
      [&](std::size_t m) { return checking_[m] ? scene.meshes[m].mesh.polygons.count : 0; },
      ranges_);
  problems_.assign(ranges_.size(), std::nullopt);
  const bool completed = runner.run(Phase::Validate, ranges_.size(), [&](std::size_t i) {
    const MeshRange& r = ranges_[i];
    problems_[i] = findMeshProblem(scene.meshes[r.mesh].mesh, r.begin, r.end);
  });
  for (std::size_t i = 0; i < problems_.size(); ++i) {
    if (problems_[i]) throwMeshProblem(*problems_[i], ranges_[i].mesh);
  }
  return completed;
}

// Tasks over points for the bounds of the meshes that want them (the first `pointTasks` of
// ranges_), then tasks over the blocks of the new versions.
std::size_t MeshCache::planMeasurement(const Scene& scene) {
  const auto& meshes = scene.meshes;
  splitPerMesh(
      meshes.size(), kPointsPerBoundsTask,
      [&](std::size_t m) { return bounding_[m] ? meshes[m].mesh.points.count : 0; }, ranges_);
  const std::size_t pointTasks = ranges_.size();
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (!measuring_[m]) continue;
    sizeBlocks(facts_[m], meshes[m].mesh.polygons.count, wideBackFlags(meshes[m].mesh));
    for (std::size_t b = 0; b < facts_[m].blocks.size(); b += kBlocksPerTask)
      ranges_.push_back({m, b, std::min(facts_[m].blocks.size(), b + kBlocksPerTask)});
  }
  rangeBounds_.assign(pointTasks, Box{});
  rangeFinite_.assign(pointTasks, 1);
  rangeTriangles_.assign(ranges_.size() - pointTasks, 0);
  rangeScattered_.resize(ranges_.size() - pointTasks);
  for (std::vector<std::uint32_t>& flags : rangeScattered_)
    flags.clear();
  return pointTasks;
}

bool MeshCache::measure(PhaseRunner& runner, const Scene& scene) {
  const std::size_t pointTasks = planMeasurement(scene);
  const bool completed = runner.run(Phase::Measure, ranges_.size(), [&](std::size_t i) {
    const MeshRange& r = ranges_[i];
    const MeshView& mesh = scene.meshes[r.mesh].mesh;
    if (i < pointTasks) {
      rangeFinite_[i] = boundPoints(mesh, r.begin, r.end, rangeBounds_[i]);
      return;
    }
    for (std::size_t b = r.begin; b < r.end; ++b)
      measureBlock(mesh, b, facts_[r.mesh], rangeScattered_[i - pointTasks]);
    rangeTriangles_[i - pointTasks] =
        areTriangles(mesh, r.begin * kPolygonsPerBlock,
                     std::min(mesh.polygons.count, r.end * kPolygonsPerBlock));
  });
  if (completed) {
    collectBounds(pointTasks);
    collectTriangles(pointTasks);
    collectScatteredFlags(pointTasks);
  }
  return completed;
}

// The block tasks' scattered flags, in order, to their meshes' (MeshFacts::scatteredPointFlags),
// each scattered block's BackPointFlags moved along: the tasks of a mesh are in block order.
void MeshCache::collectScatteredFlags(std::size_t pointTasks) {
  for (std::size_t i = pointTasks; i < ranges_.size(); ++i) {
    const std::vector<std::uint32_t>& flags = rangeScattered_[i - pointTasks];
    if (flags.empty()) continue;
    MeshFacts& facts = facts_[ranges_[i].mesh];
    // Fits: a mesh's scattered flags are at most its corners (wideBackFlags).
    const auto base = static_cast<std::uint32_t>(facts.scatteredPointFlags.size());
    facts.scatteredPointFlags.insert(facts.scatteredPointFlags.end(), flags.begin(), flags.end());
    const std::size_t first = ranges_[i].begin << (kBlockBits - kBackBlockBits);
    const std::size_t end =
        std::min(facts.backBlockCount(), ranges_[i].end << (kBlockBits - kBackBlockBits));
    for (std::size_t b = first; b < end; ++b) {
      BackPointFlags& block = facts.backPointFlags[b];
      if (block.lowFirst != kReadWholeBackBlock) continue;
      block.highFirst += base;
      block.highEnd += base;
    }
  }
  for (std::vector<std::uint32_t>& flags : rangeScattered_) {
    flags.clear();
    flags.shrink_to_fit();
  }
  for (std::size_t m = 0; m < facts_.size(); ++m) {
    if (measuring_[m]) facts_[m].scatteredPointFlags.shrink_to_fit();
  }
}

// A measured mesh is all triangles when each of its block tasks found only triangles.
void MeshCache::collectTriangles(std::size_t pointTasks) {
  for (std::size_t m = 0; m < facts_.size(); ++m) {
    if (measuring_[m]) facts_[m].allTriangles = true;
  }
  for (std::size_t i = pointTasks; i < ranges_.size(); ++i)
    facts_[ranges_[i].mesh].allTriangles &= rangeTriangles_[i - pointTasks] != 0;
}

void MeshCache::collectBounds(std::size_t pointTasks) {
  for (std::size_t m = 0; m < facts_.size(); ++m) {
    if (!bounding_[m]) continue;
    facts_[m].bounds = Box{};
    facts_[m].allFinite = true;
    facts_[m].bounded = true;
    facts_[m].measured = measuring_[m];
  }
  for (std::size_t i = 0; i < pointTasks; ++i) {
    facts_[ranges_[i].mesh].bounds.add(rangeBounds_[i]);
    facts_[ranges_[i].mesh].allFinite &= rangeFinite_[i] != 0;
  }
}

}  // namespace facet::detail
