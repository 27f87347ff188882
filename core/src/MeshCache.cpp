#include "MeshCache.h"

namespace facet::detail {
namespace {

// Polygons per validation task: large, the work per polygon is a few loads.
constexpr std::size_t kPolygonsPerTask = 1 << 18;

}  // namespace

bool validateMeshes(PhaseRunner& runner, const Scene& scene, ValidationScratch& scratch) {
  splitPerMesh(
      scene.meshes.size(), kPolygonsPerTask,
      [&](std::size_t m) { return scene.meshes[m].mesh.polygons.count; }, scratch.ranges);
  scratch.problems.assign(scratch.ranges.size(), std::nullopt);
  const bool completed = runner.run(Phase::Validate, scratch.ranges.size(), [&](std::size_t i) {
    const MeshRange& r = scratch.ranges[i];
    scratch.problems[i] = findMeshProblem(scene.meshes[r.mesh].mesh, r.begin, r.end);
  });
  for (std::size_t i = 0; i < scratch.problems.size(); ++i) {
    if (scratch.problems[i]) throwMeshProblem(*scratch.problems[i], scratch.ranges[i].mesh);
  }
  return completed;
}

}  // namespace facet::detail
