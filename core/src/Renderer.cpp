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
//   3. raster    Raster.cpp     per tile: depth keys and polygon ids (coarse depth, a rule),
//                               then window depths
//   4. shade     Shade.cpp      the color of every polygon that won a pixel
//   5. resolve   Resolve.cpp    pixel colors
//
// What the renderer keeps between renders (the plan, every phase's buffers, the previous
// frame) is Workspace.h; the bookkeeping around the phases is Workspace.cpp.

#include "facet/Renderer.h"

#include <algorithm>

#include "Assert.h"
#include "BackFacingBlocks.h"
#include "Binning.h"
#include "DeferredBackPoints.h"
#include "Raster.h"
#include "RendererInputs.h"
#include "Resolve.h"
#include "Validate.h"
#include "Workspace.h"
#include "facet/Error.h"
#include "facet/ParallelFor.h"

namespace facet {

// The phases a render runs: all of them, or the last ones of an incremental render.
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
                               rules_,
                               estimateHook_,
                               &resolvedRows_};
  const detail::PathChoice path = ws.history.choosePath(in);
  const FramebufferView planes = ws.startFrame(in);
  detail::PhaseRunner runner(*ws.pool, progress_, detail::phasesOf(path.path));
  RenderStats stats = ws.statsToStartFrom(path);
  // Until this render completes the planes hold no frame the history describes: an exception
  // (from a callback) must leave the next render to draw in full.
  ws.history.forget();
  const bool completed = path.path == RenderPath::Full
                             ? ws.renderFull(in, path, threadCount(), planes, runner, stats)
                             : ws.renderAgain(in, path, threadCount(), planes, runner, stats);
  ws.finishFrame(in, planes, completed, stats);
  stats.totalSeconds = runner.secondsSinceStart();
  if (completed) runner.finish();
  return stats;
}

// Phase 0 (validation, plan), then the geometry phases, then shade and resolve.
bool Renderer::Workspace::renderFull(const detail::FrameInputs& in, const detail::PathChoice& path,
                                     int threads, const FramebufferView& planes,
                                     detail::PhaseRunner& runner, RenderStats& stats) {
  bool completed = cache.update(runner, in.scene, lightsNeedBounds(in));
  stats.validateSeconds = runner.lap();
  planShading(in, path, threads);
  completed = completed && renderGeometry(in, planes, runner, stats);
  // The records painted, their storage sized for the next frame: a frame like this one then
  // takes none (an aborted frame's partial records size nothing).
  if (completed) detail::settleRecords(setup.chunks);
  completed = completed && shadeAndResolve(in, planes, runner, stats);
  countGeometry(stats);
  return completed;
}

// An incremental render: the previous frame re-shaded, or only recolored. `stats` holds the
// previous frame's counts.
bool Renderer::Workspace::renderAgain(const detail::FrameInputs& in, const detail::PathChoice& path,
                                      int threads, const FramebufferView& planes,
                                      detail::PhaseRunner& runner, RenderStats& stats) {
  if (path.path == RenderPath::Reshade) {
    planShading(in, path, threads);
    detail::carryGeometryReport(plan, stats.plan);
    return shadeAndResolve(in, planes, runner, stats);
  }
  keepPreviousPlan(path, threads);
  // Only recolored: no shade phase bounded anything, so the resolve estimates nothing (the
  // QualityRenderer keeps or redoes its estimate itself).
  detail::FrameInputs recolor = in;
  recolor.estimate = nullptr;
  const bool completed = resolve(recolor, planes, runner);
  stats.shadeSeconds = runner.lap();
  return completed;
}

// Phases 1 to 3.
bool Renderer::Workspace::renderGeometry(const detail::FrameInputs& in,
                                         const FramebufferView& planes, detail::PhaseRunner& runner,
                                         RenderStats& stats) {
  if (in.rules.geometryOutsideView) {
    detail::cullBlocksOutsideView(runner, meshes, cache, *transform, in.rules.closedSurfaces,
                                  backPointsMayWait(in), viewCulling);
    reportViewCulling();
  }
  bool completed = detail::transformPoints(runner, meshes, *transform, pointRanges, vertices);
  stats.closedMeshesSkippingBackFaces =
      detail::decideBackFaces(meshes, pointRanges, in.rules.closedSurfaces);
  detail::reportRule(plan, Rule::ClosedSurfaces, stats.closedMeshesSkippingBackFaces);
  for ([[maybe_unused]] const detail::FrameMesh& mesh : meshes) {
    FACET_ASSERT(!mesh.backBlocks || mesh.skipBackFaces);  // willSkipBackFaces, ViewCulling
    FACET_ASSERT(!mesh.deferredBackBlocks || !mesh.skipBackFaces);
  }
  plan.setupRoutine =
      commonName(meshes, [](const auto& m) { return detail::setupRoutineName(m.skipBackFaces); });
  order.ids.clear();
  if (plan.sortByDepth) {
    completed = completed && detail::sortForPainter(runner, meshes, *transform, sortRanges, order);
  }
  stats.transformSeconds = runner.lap();

  detail::SetupContext setupContext{
      meshes, *transform, vertices.data(), order, grid, polygons.backFacing.data(), plan.depthTest};
  const bool twoPasses = twoPassesMayPay(in);
  setupContext.deferCertainBackBlocks = twoPasses && frontPassDefersCertainBlocks();
  // The cone-certain blocks' points left out for a front pass that would defer them (the
  // guess before the transform was wrong): every face may read them now.
  if (!setupContext.deferCertainBackBlocks) transformWaitingPoints(runner, nullptr);
  if (twoPasses) {
    setupContext.pass = detail::SetupPass::Front;
    completed = completed && detail::setUpPolygons(runner, setupContext, plan.threads, setup);
    return completed && rasterInTwoPasses(in, planes, setupContext, runner, stats);
  }
  completed = completed && detail::setUpPolygons(runner, setupContext, plan.threads, setup);
  stats.setupSeconds = runner.lap();
  return completed && rasterInOnePass(in, planes, runner, stats);
}

// Whether the front pass of a two-pass frame defers whole the back-face blocks BackFaceTest
// proves all back faces (SetupContext::deferCertainBackBlocks).
bool Renderer::Workspace::frontPassDefersCertainBlocks() const {
  const detail::ScopedBackBlockSettings::Settings blocks =
      detail::ScopedBackBlockSettings::current();  // this thread's (tests)
  return detail::frontPassConeSkipEnabled() && blocks.skipping && blocks.margin;
}

// Before the transform: whether the frame will likely take two passes whose front pass
// defers cone-certain blocks, so that those blocks' points may wait for the back pass's
// reject (DeferredBackPoints.h). By the previous frame's covered pixels and every mesh
// counted as drawing its back faces (decideBackFaces has not run); a first frame (no covered
// pixels yet) transforms every point. A wrong guess costs a second transform run
// (transformWaitingPoints before the set-up), not a byte.
bool Renderer::Workspace::backPointsMayWait(const detail::FrameInputs& in) {
  if (!plan.depthTest || plan.sortByDepth || in.rules.hiddenGeometry == HierarchicalZ::On ||
      !frontPassDefersCertainBlocks())
    return false;
  const std::size_t covered = history.stats().pixelsCovered;
  // Sets the plan's two-pass figures, which twoPassesMayPay sets again after the transform.
  return covered > 0 && detail::chooseTwoPassFrame(plan, meshes, covered);
}

// The points of the deferred blocks that `front` keeps (null: all of them), transformed.
void Renderer::Workspace::transformWaitingPoints(detail::PhaseRunner& runner,
                                                 const detail::FrontDepthBlocks* front) {
  detail::transformKeptBackBlocks(runner, meshes, cache, *transform, grid, front, viewCulling,
                                  deferredBlockRanges, latePointRanges, vertices);
}

// Every face drawn with the depth test, in z-buffer order, where the coarse depth is not
// forced: the back faces may be set up after the front faces are painted (Raster.h). The rule
// goes by the previous frame's covered pixels, or before a first frame (or after one that
// covered none) by the blocks' projected boxes.
bool Renderer::Workspace::twoPassesMayPay(const detail::FrameInputs& in) {
  plan.twoPassFrame = false;
  plan.everyFacePolygonsPerCoveredPixel = 0.0;
  plan.blocksHiddenBehindFront = plan.polygonsHiddenBehindFront = 0;
  if (!plan.depthTest || plan.sortByDepth || in.rules.hiddenGeometry == HierarchicalZ::On)
    return false;
  std::size_t covered = history.stats().pixelsCovered;
  const bool everyFace = std::any_of(meshes.begin(), meshes.end(),
                                     [](const detail::FrameMesh& m) { return !m.skipBackFaces; });
  if (covered == 0 && everyFace)
    covered = detail::estimateCoveredPixels(meshes, cache, *transform, grid, coveredCells);
  return detail::chooseTwoPassFrame(plan, meshes, covered);
}

detail::RasterContext Renderer::Workspace::rasterContext(const detail::FrameInputs& in,
                                                         const FramebufferView& planes) {
  return {setup.chunks,
          vertices.data(),
          planes.depth,
          planes.polygonId,
          planes.width,
          polygons.shown,
          in.depthOutput ? &*transform : nullptr,
          &frontBlocks};
}

bool Renderer::Workspace::rasterInOnePass(const detail::FrameInputs& in,
                                          const FramebufferView& planes,
                                          detail::PhaseRunner& runner, RenderStats& stats) {
  const detail::TileRoutine tileRoutine =
      detail::chooseRasterRoutine(plan, setup.chunks, in.rules.hiddenGeometry);
  const bool completed =
      detail::paintTiles(runner, grid, rasterContext(in, planes), tileRoutine, tiles);
  stats.rasterSeconds = runner.lap();
  return completed;
}

// After the front pass's set-up: the front faces painted, the back faces set up against them
// and painted, each tile finished. When the front faces alone call for the coarse depth
// (large triangles, where little set-up is to be saved), the back faces are set up at once and
// the frame painted in one pass.
bool Renderer::Workspace::rasterInTwoPasses(const detail::FrameInputs& in,
                                            const FramebufferView& planes,
                                            detail::SetupContext setupContext,
                                            detail::PhaseRunner& runner, RenderStats& stats) {
  detail::chooseRasterRoutine(plan, setup.chunks, in.rules.hiddenGeometry);
  setupContext.pass = detail::SetupPass::Back;
  if (detail::useCoarseDepth(plan, in.rules.hiddenGeometry)) {
    transformWaitingPoints(runner, nullptr);
    detail::setUpBackFaces(runner, setupContext, setup);
    stats.setupSeconds = runner.lap();
    plan.twoPassFrame = false;
    return rasterInOnePass(in, planes, runner, stats);
  }
  stats.setupSeconds = runner.lap();
  const detail::RasterContext context = rasterContext(in, planes);
  detail::paintFrontTiles(runner, grid, context, tiles);
  stats.rasterSeconds = runner.lap();
  setupContext.front = &frontBlocks;
  transformWaitingPoints(runner, &frontBlocks);
  detail::setUpBackFaces(runner, setupContext, setup);
  stats.setupSeconds += runner.lap();
  detail::reportHiddenBlocks(setup.chunks, plan);
  const bool completed = detail::paintBackTiles(runner, grid, context, tiles);
  stats.rasterSeconds += runner.lap();
  // The plan's figures from every face set up (the lanes hidden behind the front blocks
  // counted as binned, as in one pass; the blocks dropped whole not: RenderStats::
  // polygonsHidden); the routine is the depth test's.
  detail::chooseRasterRoutine(plan, setup.chunks, HierarchicalZ::Off);
  return completed;
}

// Phases 4 and 5.
bool Renderer::Workspace::shadeAndResolve(const detail::FrameInputs& in,
                                          const FramebufferView& planes,
                                          detail::PhaseRunner& runner, RenderStats& stats) {
  const detail::ShadeContext shadeContext{*transform,
                                          shading.shader,
                                          plan.twoSidedLighting,
                                          polygons.shown.data(),
                                          polygons.backFacing.data(),
                                          polygons.colors.data(),
                                          in.estimate};
  bool completed =
      detail::shadePolygons(runner, meshes, shading.routines, shadeContext, shadeBuffers);
  countShaded(stats);
  completed = completed && resolve(in, planes, runner);
  stats.shadeSeconds = runner.lap();
  return completed;
}

// Phase 5: the pixels' colors from their polygons' (the raster left window depths).
bool Renderer::Workspace::resolve(const detail::FrameInputs& in, const FramebufferView& planes,
                                  detail::PhaseRunner& runner) {
  const detail::ResolveContext context{
      polygons.colors.data(), in.background, planes.color, planes.polygonId, planes.width,
      in.estimate, in.resolvedRows && *in.resolvedRows ? in.resolvedRows : nullptr, &in.target,
      // The frame's (or, resolving again, the previous frame's: the same id plane) tiles.
      tiles.size() == grid.count() ? tiles.data() : nullptr};
  return detail::resolveTiles(runner, grid, context);
}

Renderer::Renderer() : workspace_(std::make_unique<Workspace>()) {
  setThreadCount(0);
}
Renderer::~Renderer() = default;

void Renderer::setThreadCount(int threads) {
  if (threads < 0)
    throw Error("Renderer thread count is " + std::to_string(threads) + ", must be >= 0");
  const int count = threads == 0 ? detail::ThreadPool::hardwareThreads() : threads;
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

ParallelFor parallelOn(Renderer& renderer) {
  return [&renderer](std::size_t count, std::size_t grain,
                     const std::function<void(std::size_t, std::size_t)>& work) {
    renderer.parallelFor(count, grain, work);
  };
}

std::span<const std::uint8_t> Renderer::shownPolygons() const {
  return {workspace_->polygons.shown.data(), workspace_->polygons.shown.size()};
}

RenderPlan Renderer::plan(const Scene& scene, const Camera& camera, int width, int height) const {
  detail::validateSceneInputs(scene, camera, width, height);
  detail::validateMeshHeaders(scene);  // the bounds read the points
  return detail::planAhead({scene, camera, width, height, threadCount(), visibility_,
                            twoSidedLighting_, depthOutput_, rules_});
}

}  // namespace facet
