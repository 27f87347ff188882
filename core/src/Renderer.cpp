// The render, phase by phase. Each phase lives in a file of its own and takes its inputs as
// arguments; this file only wires them together:
//
//   0. plan      History.cpp    which path: full, re-shade or resolve (incremental rendering)
//                MeshCache.cpp  validation, and per mesh version its bounding boxes
//                LightCulling   lights that reach nothing          } the rules
//                Plan.cpp       what runs, and which routines run it
//   1. transform ViewCulling    blocks outside the view            }
//                Transform.cpp  points to window coordinates; back faces; painter's sort
//   2. set-up    Setup.cpp      polygons to triangles (facing, triangulation, clipping),
//      binning   Binning.cpp    triangles to the bins of the tiles they touch
//   3. raster    Raster.cpp     per tile: depth keys and polygon ids (coarse depth, a rule)
//   4. shade     Shade.cpp      the color of every polygon that won a pixel
//   5. resolve   Resolve.cpp    pixel colors and window depths

#include "facet/Renderer.h"

#include <algorithm>
#include <optional>
#include <string_view>
#include <thread>

#include "Frame.h"
#include "History.h"
#include "LightCulling.h"
#include "MeshCache.h"
#include "PhaseRunner.h"
#include "Plan.h"
#include "Raster.h"
#include "RendererInputs.h"
#include "Resolve.h"
#include "Setup.h"
#include "Shade.h"
#include "ThreadPool.h"
#include "TileGrid.h"
#include "Transform.h"
#include "Validate.h"
#include "ViewCulling.h"
#include "facet/Error.h"

namespace facet {
namespace {

using detail::Phase;

int hardwareThreads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

detail::PhaseSet phasesOf(RenderPath path) {
  switch (path) {
    case RenderPath::Full:
      return {Phase::Validate, Phase::Measure, Phase::Transform, Phase::Sort,
              Phase::Setup,    Phase::Raster,  Phase::Shade,     Phase::Resolve};
    case RenderPath::Reshade:
      return {Phase::Shade, Phase::Resolve};
    case RenderPath::Resolve:
      break;
  }
  return {Phase::Resolve};
}

detail::PlanInputs planInputs(const detail::FrameInputs& in, int threads) {
  return {in.scene,      in.camera,           in.target.width, in.target.height, threads,
          in.visibility, in.twoSidedLighting, in.depthOutput,  in.rules};
}

}  // namespace

// The renderer's state between renders: the plan, every phase's buffers, and what the
// previous frame was.
struct Renderer::Workspace {
  std::unique_ptr<detail::ThreadPool> pool;
  RenderPlan plan;
  detail::ShadingChoice shading;
  std::optional<detail::FrameTransform> transform;
  detail::TileGrid grid;
  detail::MeshCache cache;
  std::vector<detail::Box> bounds;  // per mesh, for the lights
  std::vector<detail::FrameMesh> meshes;
  detail::ViewCulling viewCulling;
  detail::PointRanges pointRanges;
  HugePageVector<detail::WindowVertex> vertices;
  std::vector<detail::MeshRange> sortRanges;
  detail::DrawOrder order;
  detail::SetupBuffers setup;
  detail::PolygonBuffers polygons;
  std::vector<detail::PaintCounts> tiles;
  detail::ShadeBuffers shadeBuffers;
  HugePageVector<float> ownDepth;  // the depth plane of a caller without one
  detail::FrameHistory history;

  FramebufferView planesFor(const FramebufferView& target);
  void planShading(const detail::FrameInputs& in, const detail::PathChoice& path, int threads);
  void prepareMeshes(const Scene& scene);
  bool renderFull(const detail::FrameInputs& in, const detail::PathChoice& path, int threads,
                  const FramebufferView& planes, detail::PhaseRunner& runner, RenderStats& stats);
  bool renderAgain(const detail::FrameInputs& in, const detail::PathChoice& path, int threads,
                   const FramebufferView& planes, detail::PhaseRunner& runner, RenderStats& stats);
  bool renderGeometry(const detail::FrameInputs& in, const FramebufferView& planes,
                      detail::PhaseRunner& runner, RenderStats& stats);
  bool shadeAndResolve(const detail::FrameInputs& in, const FramebufferView& planes, bool depths,
                       detail::PhaseRunner& runner, RenderStats& stats);
  bool resolve(const detail::FrameInputs& in, const FramebufferView& planes, bool depths,
               detail::PhaseRunner& runner);
  void countShaded(RenderStats& stats);
};

FramebufferView Renderer::Workspace::planesFor(const FramebufferView& target) {
  FramebufferView planes = target;
  if (!planes.depth) {
    ownDepth.resize(static_cast<std::size_t>(target.width) * target.height);
    planes.depth = ownDepth.data();
  }
  return planes;
}

// The lights kept, the plan and the shading routines (every path).
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

// Each mesh's place in the frame's vertex and polygon numbering.
void Renderer::Workspace::prepareMeshes(const Scene& scene) {
  meshes.clear();
  std::size_t firstVertex = 0, firstPolygon = 0;
  for (const SceneMesh& mesh : scene.meshes) {
    meshes.push_back({&mesh, PreparedMaterial(mesh.material), firstVertex, firstPolygon});
    if (cache[meshes.size() - 1].measured)
      meshes.back().faceNormals = cache[meshes.size() - 1].faceNormals.data();
    firstVertex += mesh.mesh.points.count;
    firstPolygon += mesh.mesh.polygons.count;
  }
  polygons.resize(plan.polygons);
}

bool Renderer::Workspace::renderFull(const detail::FrameInputs& in, const detail::PathChoice& path,
                                     int threads, const FramebufferView& planes,
                                     detail::PhaseRunner& runner, RenderStats& stats) {
  const bool bounded = in.rules.lightsThatReachNothing &&
                       detail::lightCullingNeedsBounds(in.scene.lights, in.rules.lightTolerance);
  bool completed = cache.update(runner, in.scene, bounded);
  stats.validateSeconds = runner.lap();
  planShading(in, path, threads);
  completed = completed && renderGeometry(in, planes, runner, stats);
  completed = completed && shadeAndResolve(in, planes, in.depthOutput, runner, stats);
  detail::addSetupCounts(setup.chunks, stats);
  detail::addPaintCounts(tiles, stats);
  detail::reportRule(plan, Rule::HiddenGeometry, stats.trianglesHidden);
  return completed;
}

// An incremental render: the previous frame re-shaded, or only recolored. `stats` holds the
// previous frame's.
bool Renderer::Workspace::renderAgain(const detail::FrameInputs& in, const detail::PathChoice& path,
                                      int threads, const FramebufferView& planes,
                                      detail::PhaseRunner& runner, RenderStats& stats) {
  const RenderPlan previous = stats.plan;
  stats.validateSeconds = stats.transformSeconds = stats.setupSeconds = stats.rasterSeconds = 0;
  if (path.path == RenderPath::Reshade) {
    planShading(in, path, threads);
    detail::carryGeometryReport(plan, previous);
    return shadeAndResolve(in, planes, false, runner, stats);
  }
  plan = previous;
  plan.path = path.path;
  plan.pathReason = path.reason;
  plan.threads = threads;
  const bool completed = resolve(in, planes, false, runner);
  stats.shadeSeconds = runner.lap();
  return completed;
}

// Phases 1 to 3.
bool Renderer::Workspace::renderGeometry(const detail::FrameInputs& in,
                                         const FramebufferView& planes, detail::PhaseRunner& runner,
                                         RenderStats& stats) {
  if (in.rules.geometryOutsideView) {
    detail::cullBlocksOutsideView(meshes, cache, *transform, viewCulling);
    plan.blocksTested = viewCulling.blocksTested;
    plan.blocksOutside = viewCulling.blocksOutside;
    detail::reportRule(plan, Rule::GeometryOutsideView, viewCulling.polygonsOutside);
  }
  bool completed = detail::transformPoints(runner, meshes, *transform, pointRanges, vertices);
  stats.closedMeshesSkippingBackFaces =
      detail::decideBackFaces(meshes, pointRanges, in.rules.closedSurfaces);
  detail::reportRule(plan, Rule::ClosedSurfaces, stats.closedMeshesSkippingBackFaces);
  plan.setupRoutine =
      commonName(meshes, [](const auto& m) { return detail::setupRoutineName(m.skipBackFaces); });
  order.ids.clear();
  if (plan.sortByDepth) {
    completed = completed && detail::sortForPainter(runner, meshes, *transform, sortRanges, order);
  }
  stats.transformSeconds = runner.lap();

  const detail::SetupContext setupContext{meshes, *transform, vertices.data(),
                                          order,  grid,       polygons.backFacing.data()};
  completed = completed && detail::setUpPolygons(runner, setupContext, plan.threads, setup);
  stats.setupSeconds = runner.lap();

  const detail::TileRoutine tileRoutine =
      detail::chooseRasterRoutine(plan, setup.chunks, in.rules.hiddenGeometry);
  const detail::RasterContext rasterContext{setup.chunks,  vertices.data(),  planes.color,
                                            planes.depth,  planes.polygonId, planes.width,
                                            polygons.shown};
  completed = completed && detail::paintTiles(runner, grid, rasterContext, tileRoutine, tiles);
  stats.rasterSeconds = runner.lap();
  return completed;
}

// Phases 4 and 5; `depths`: convert the depth keys too.
bool Renderer::Workspace::shadeAndResolve(const detail::FrameInputs& in,
                                          const FramebufferView& planes, bool depths,
                                          detail::PhaseRunner& runner, RenderStats& stats) {
  const detail::ShadeContext shadeContext{*transform,
                                          shading.shader,
                                          plan.twoSidedLighting,
                                          polygons.shown.data(),
                                          polygons.backFacing.data(),
                                          polygons.colors.data()};
  bool completed =
      detail::shadePolygons(runner, meshes, shading.routines, shadeContext, shadeBuffers);
  countShaded(stats);
  completed = completed && resolve(in, planes, depths, runner);
  stats.shadeSeconds = runner.lap();
  return completed;
}

// Phase 5: the pixels' colors from their polygons'; `depths`: window depths from the keys.
bool Renderer::Workspace::resolve(const detail::FrameInputs& in, const FramebufferView& planes,
                                  bool depths, detail::PhaseRunner& runner) {
  const detail::ResolveContext context{polygons.colors.data(), in.background,    planes.color,
                                       planes.depth,           planes.polygonId, planes.width};
  const detail::ResolveRoutine routine = detail::chooseResolveRoutine(depths).resolve;
  return detail::resolveTiles(runner, grid, context, routine, *transform);
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

Renderer::Renderer() : workspace_(std::make_unique<Workspace>()) {
  setThreadCount(0);
}
Renderer::~Renderer() = default;

void Renderer::setThreadCount(int threads) {
  if (threads < 0)
    throw Error("Renderer thread count is " + std::to_string(threads) + ", must be >= 0");
  const int count = threads == 0 ? hardwareThreads() : threads;
  if (!workspace_->pool || workspace_->pool->threadCount() != count) {
    workspace_->pool = std::make_unique<detail::ThreadPool>(count);
  }
}

int Renderer::threadCount() const {
  return workspace_->pool->threadCount();
}

void Renderer::setRules(const RenderRules& rules) {
  detail::requireNonNegative(rules.lightTolerance, "RenderRules.lightTolerance");
  rules_ = rules;
}

void Renderer::forgetPreviousFrame() {
  workspace_->history.forget();
}

void Renderer::parallelFor(std::size_t count, std::size_t grain,
                           const std::function<void(std::size_t, std::size_t)>& work) {
  grain = std::max<std::size_t>(grain, 1);
  auto block = [&](std::size_t i) { work(i * grain, std::min(count, (i + 1) * grain)); };
  workspace_->pool->run((count + grain - 1) / grain, detail::FunctionRef<void(std::size_t)>(block));
}

RenderPlan Renderer::plan(const Scene& scene, const Camera& camera, int width, int height) const {
  detail::validateSceneInputs(scene, camera, width, height);
  detail::validateMeshHeaders(scene);  // the bounds read the points
  std::vector<detail::Box> bounds;
  for (const SceneMesh& mesh : scene.meshes)
    bounds.push_back(detail::boundsOf(mesh.mesh));
  detail::ShadingChoice shading;
  RenderPlan plan = detail::makePlan({scene, camera, width, height, threadCount(), visibility_,
                                      twoSidedLighting_, depthOutput_, rules_},
                                     bounds, shading);
  plan.pathReason = "planned ahead (Renderer::plan)";
  plan.rasterRoutine =
      plan.depthTest ? "depth test (hierarchical z decided by the render)" : "painter's overwrite";
  return plan;
}

RenderStats Renderer::render(const Scene& scene, const Camera& camera,
                             const FramebufferView& target) {
  detail::validateRenderInputs(scene, camera, target, depthOutput_);  // before a pixel changes
  Workspace& ws = *workspace_;
  const detail::FrameInputs in{scene,
                               camera,
                               target,
                               visibility_,
                               twoSidedLighting_,
                               toRgba8(background_, backgroundAlpha_),
                               depthOutput_,
                               rules_};
  const detail::PathChoice path = ws.history.choosePath(in);
  const FramebufferView planes = ws.planesFor(target);
  detail::PhaseRunner runner(*ws.pool, progress_, phasesOf(path.path));
  ws.transform.emplace(camera, target.width, target.height);
  ws.grid = detail::TileGrid(target.width, target.height);

  RenderStats stats = path.path == RenderPath::Full ? RenderStats{} : ws.history.stats();
  const bool completed = path.path == RenderPath::Full
                             ? ws.renderFull(in, path, threadCount(), planes, runner, stats)
                             : ws.renderAgain(in, path, threadCount(), planes, runner, stats);
  stats.plan = ws.plan;
  stats.aborted = !completed;
  if (completed) {
    ws.history.remember(in, stats);
  } else {
    detail::clearTarget(planes, in.background);  // a valid image rather than half a one
    ws.history.forget();
    stats.pixelsCovered = 0;
  }
  stats.totalSeconds = runner.secondsSinceStart();
  if (completed) runner.finish();
  return stats;
}

}  // namespace facet
