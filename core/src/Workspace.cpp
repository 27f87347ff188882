#include "Workspace.h"

#include "LightCulling.h"
#include "Raster.h"
#include "RendererInputs.h"

namespace facet {
namespace {

detail::PlanInputs planInputs(const detail::FrameInputs& in, int threads) {
  return {in.scene,      in.camera,           in.target.width, in.target.height, threads,
          in.visibility, in.twoSidedLighting, in.depthOutput,  in.rules};
}

}  // namespace

// What every path needs before its first phase: the planes it draws into (with a depth plane
// of its own for a caller without one), the camera's transform and the tiles.
FramebufferView Renderer::Workspace::startFrame(const detail::FrameInputs& in) {
  transform.emplace(in.camera, in.target.width, in.target.height);
  grid = detail::TileGrid(in.target.width, in.target.height);
  FramebufferView planes = in.target;
  if (!planes.depth) {
    ownDepth.resize(static_cast<std::size_t>(in.target.width) * in.target.height);
    planes.depth = ownDepth.data();
  }
  return planes;
}

// A full render counts afresh; an incremental one reports the frame it reuses, whose
// geometry phases did not run this time.
RenderStats Renderer::Workspace::statsToStartFrom(const detail::PathChoice& path) const {
  if (path.path == RenderPath::Full) return {};
  RenderStats stats = history.stats();
  stats.validateSeconds = stats.transformSeconds = stats.setupSeconds = stats.rasterSeconds = 0;
  return stats;
}

// Rule::LightsThatReachNothing judges some lights by the meshes' bounds, which the
// validation then measures for unversioned meshes too.
bool Renderer::Workspace::lightsNeedBounds(const detail::FrameInputs& in) const {
  return in.rules.lightsThatReachNothing &&
         detail::lightCullingNeedsBounds(in.scene.lights, in.rules.lightTolerance);
}

// The lights kept, the plan and the shading routines (every path but Resolve).
void Renderer::Workspace::planShading(const detail::FrameInputs& in, const detail::PathChoice& path,
                                      int threads) {
  bounds.clear();
  for (std::size_t m = 0; m < in.scene.meshes.size() && cache[m].bounded; ++m)
    bounds.push_back(cache[m].bounds);
  if (bounds.size() != in.scene.meshes.size()) bounds.clear();  // not known: judged unbounded
  plan = detail::makePlan(planInputs(in, threads), bounds, shading);
  plan.path = path.path;
  plan.pathReason = path.reason;
  prepareMeshes(in.scene);
}

// The Resolve path: the previous frame's plan, with this render's path.
void Renderer::Workspace::keepPreviousPlan(const detail::PathChoice& path, int threads) {
  plan = history.stats().plan;
  plan.path = path.path;
  plan.pathReason = path.reason;
  plan.threads = threads;
}

// Each mesh's place in the frame's vertex and polygon numbering.
void Renderer::Workspace::prepareMeshes(const Scene& scene) {
  meshes.clear();
  std::size_t firstVertex = 0, firstPolygon = 0;
  for (const SceneMesh& mesh : scene.meshes) {
    meshes.push_back({&mesh, PreparedMaterial(mesh.material), firstVertex, firstPolygon});
    const detail::MeshFacts& facts = cache[meshes.size() - 1];
    if (facts.measured) {
      meshes.back().faceNormals = facts.faceNormals.data();
      meshes.back().backBlockFacts = &facts;
      meshes.back().allTriangles = facts.allTriangles;
    }
    firstVertex += mesh.mesh.points.count;
    firstPolygon += mesh.mesh.polygons.count;
  }
  polygons.resize(plan.polygons);
}

void Renderer::Workspace::reportViewCulling() {
  plan.blocksTested = viewCulling.blocksTested;
  plan.blocksOutside = viewCulling.blocksOutside;
  plan.blocksBackFacing = viewCulling.backBlocksSkipped;
  plan.polygonsBackFacing = viewCulling.backPolygonsSkipped;
  detail::reportRule(plan, Rule::GeometryOutsideView, viewCulling.polygonsOutside);
}

// The polygons lit, and those Rule::AmbientOnly lit without normal or light loop.
void Renderer::Workspace::countShaded(RenderStats& stats) {
  stats.polygonsShaded = 0;
  for (std::size_t i = 0; i < shadeBuffers.counts.size(); ++i) {
    stats.polygonsShaded += shadeBuffers.counts[i];
    const bool ambient = shading.routines[shadeBuffers.ranges[i].mesh].ambientOnly;
    plan.rule(Rule::AmbientOnly).skipped += ambient ? shadeBuffers.counts[i] : 0;
  }
}

// What the set-up and the tiles counted, and the triangles the coarse depth left out.
void Renderer::Workspace::countGeometry(RenderStats& stats) {
  detail::addSetupCounts(setup.chunks, stats);
  detail::addPaintCounts(tiles, stats);
  detail::reportRule(plan, Rule::HiddenGeometry, stats.trianglesHidden);
}

// The plan into the stats; a render that completed becomes the previous frame, one that
// stopped early leaves the background (a valid image rather than half a one) and no history.
void Renderer::Workspace::finishFrame(const detail::FrameInputs& in, const FramebufferView& planes,
                                      bool completed, RenderStats& stats) {
  stats.plan = plan;
  stats.aborted = !completed;
  if (completed) {
    history.remember(in, stats);
    return;
  }
  detail::clearTarget(planes, in.background);
  history.forget();
  stats.pixelsCovered = 0;
}

}  // namespace facet
