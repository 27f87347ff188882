// The render, phase by phase. Each phase lives in a file of its own and takes its inputs as
// arguments; this file only wires them together:
//
//   0. plan      Plan.cpp       what runs, and which routines run it
//      validate  MeshCache.cpp  every mesh's offsets and point ids
//   1. transform Transform.cpp  points to window coordinates; back-face decision; painter's sort
//   2. set-up    Setup.cpp      polygons to triangles (facing, triangulation, clipping),
//      binning   Binning.cpp    triangles to the bins of the tiles they touch
//   3. raster    Raster.cpp     per tile: depth keys and polygon ids
//   4. shade     Shade.cpp      the color of every polygon that won a pixel
//   5. resolve   Resolve.cpp    pixel colors and window depths

#include "facet/Renderer.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

#include "Frame.h"
#include "MeshCache.h"
#include "PhaseRunner.h"
#include "Plan.h"
#include "Raster.h"
#include "Resolve.h"
#include "Setup.h"
#include "Shade.h"
#include "ThreadPool.h"
#include "TileGrid.h"
#include "Transform.h"
#include "Validate.h"
#include "facet/Conventions.h"
#include "facet/Error.h"

namespace facet {
namespace {

using detail::Phase;

int hardwareThreads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

void validateMaterials(const Scene& scene) {
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    try {
      validate(scene.meshes[i].material);
    } catch (const Error& e) {
      throw Error("Scene.meshes[" + std::to_string(i) + "]." + e.what());
    }
  }
}

void validateImageSize(int width, int height) {
  detail::requireInRange(width, 1, kMaxImageSide, "image width");
  detail::requireInRange(height, 1, kMaxImageSide, "image height");
}

// Polygon ids and point indices are 32-bit in the framebuffer and the triangle records.
void validateCounts(const RenderPlan& plan) {
  constexpr std::size_t kMaxIds = std::numeric_limits<std::int32_t>::max();
  if (plan.polygons > kMaxIds || plan.points > kMaxIds) {
    throw Error("Scene has " + std::to_string(plan.polygons) + " polygons and " +
                std::to_string(plan.points) + " points; at most 2^31 - 1 of each render at once");
  }
}

// The name every mesh's routine shares, or "per mesh".
template <class Items, class NameOf>
const char* commonName(const Items& items, const NameOf& nameOf) {
  if (items.empty()) return "none (no mesh)";
  for (const auto& item : items) {
    if (std::string_view(nameOf(item)) != nameOf(items.front())) return "per mesh";
  }
  return nameOf(items.front());
}

// A stopped render leaves a valid image (background) rather than a half-painted one.
void clearTarget(const FramebufferView& target, Rgba8 background) {
  const std::size_t pixels = static_cast<std::size_t>(target.width) * target.height;
  std::fill(target.color, target.color + pixels, background);
  std::fill(target.depth, target.depth + pixels, 1.0f);
  std::fill(target.polygonId, target.polygonId + pixels, Framebuffer::kBackgroundId);
}

}  // namespace

// The renderer's state between renders: the plan and every phase's buffers.
struct Renderer::Workspace {
  std::unique_ptr<detail::ThreadPool> pool;
  RenderPlan plan;
  Shader shader;
  std::optional<detail::FrameTransform> transform;
  detail::TileGrid grid;
  std::vector<detail::FrameMesh> meshes;
  std::vector<detail::ShadeRoutineChoice> shadeRoutines;  // per mesh
  detail::ValidationScratch validation;
  detail::PointRanges pointRanges;
  HugePageVector<detail::WindowVertex> vertices;
  std::vector<detail::MeshRange> sortRanges;
  detail::DrawOrder order;
  detail::SetupBuffers setup;
  detail::PolygonBuffers polygons;
  std::vector<detail::PaintCounts> tiles;
  detail::ShadeBuffers shading;

  void prepareMeshes(const Scene& scene);
  bool renderFull(const Scene& scene, const FramebufferView& target, Rgba8 background,
                  detail::PhaseRunner& runner, RenderStats& stats);
  void collectStatistics(RenderStats& stats) const;
};

// Each mesh's place in the frame's vertex and polygon numbering, and its shading routine.
void Renderer::Workspace::prepareMeshes(const Scene& scene) {
  meshes.clear();
  shadeRoutines.clear();
  std::size_t firstVertex = 0, firstPolygon = 0;
  for (const SceneMesh& mesh : scene.meshes) {
    meshes.push_back({&mesh, PreparedMaterial(mesh.material), firstVertex, firstPolygon});
    shadeRoutines.push_back(detail::chooseShadeRoutine(detail::shadeNeedsOf(plan, mesh)));
    firstVertex += mesh.mesh.points.count;
    firstPolygon += mesh.mesh.polygons.count;
  }
  polygons.resize(plan.polygons);
  plan.shadeRoutine = commonName(shadeRoutines, [](const auto& r) { return r.name; });
}

// Every phase, in order; false as soon as the progress callback asks to stop.
bool Renderer::Workspace::renderFull(const Scene& scene, const FramebufferView& target,
                                     Rgba8 background, detail::PhaseRunner& runner,
                                     RenderStats& stats) {
  bool completed = detail::validateMeshes(runner, scene, validation);
  stats.validateSeconds = runner.lap();

  prepareMeshes(scene);
  completed =
      completed && detail::transformPoints(runner, meshes, *transform, pointRanges, vertices);
  stats.closedMeshesSkippingBackFaces = detail::decideBackFaces(meshes, pointRanges);
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

  const detail::RasterContext rasterContext{setup.chunks,  vertices.data(),  target.color,
                                            target.depth,  target.polygonId, target.width,
                                            polygons.shown};
  const detail::TileRoutine tileRoutine = detail::chooseTileRoutine(plan.depthTest).paint;
  completed = completed && detail::paintTiles(runner, grid, rasterContext, tileRoutine, tiles);
  stats.rasterSeconds = runner.lap();

  const detail::ShadeContext shadeContext{*transform,
                                          shader,
                                          plan.twoSidedLighting,
                                          polygons.shown.data(),
                                          polygons.backFacing.data(),
                                          polygons.colors.data()};
  completed =
      completed && detail::shadePolygons(runner, meshes, shadeRoutines, shadeContext, shading);
  const detail::ResolveContext resolveContext{polygons.colors.data(), background,
                                              target.color,           target.depth,
                                              target.polygonId,       target.width};
  completed = completed && detail::resolveTiles(runner, grid, resolveContext, *transform);
  stats.shadeSeconds = runner.lap();
  return completed;
}

void Renderer::Workspace::collectStatistics(RenderStats& stats) const {
  for (const detail::Chunk& chunk : setup.chunks) {
    stats.polygonsDrawn += chunk.counts.drawn;
    stats.polygonsCulled += chunk.counts.culled;
    stats.polygonsOutside += chunk.counts.outside;
    stats.polygonsDegenerate += chunk.counts.degenerate;
    stats.polygonsNonFinite += chunk.counts.nonFinite;
    stats.trianglesBinned += chunk.counts.trianglesBinned;
    stats.trianglesClipped += chunk.counts.trianglesClipped;
  }
  for (const detail::PaintCounts& tile : tiles) {
    stats.fragmentsWritten += tile.written;
    stats.pixelsCovered += tile.covered;
  }
  for (std::size_t count : shading.counts)
    stats.polygonsShaded += count;
  if (stats.aborted) stats.pixelsCovered = 0;  // the image left is the background
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

void Renderer::parallelFor(std::size_t count, std::size_t grain,
                           const std::function<void(std::size_t, std::size_t)>& work) {
  grain = std::max<std::size_t>(grain, 1);
  auto block = [&](std::size_t i) { work(i * grain, std::min(count, (i + 1) * grain)); };
  workspace_->pool->run((count + grain - 1) / grain, detail::FunctionRef<void(std::size_t)>(block));
}

RenderPlan Renderer::plan(const Scene& scene, const Camera& camera, int width, int height) const {
  validate(camera);
  validateImageSize(width, height);
  validateMaterials(scene);
  const Shader shader(scene.lights);
  return detail::makePlan(
      {scene, camera, width, height, shader, threadCount(), visibility_, twoSidedLighting_});
}

RenderStats Renderer::render(const Scene& scene, const Camera& camera,
                             const FramebufferView& target) {
  Workspace& ws = *workspace_;
  // Everything that can throw does so before a pixel changes.
  validate(camera);
  validateImageSize(target.width, target.height);
  if (!target.color || !target.depth || !target.polygonId) {
    throw Error("FramebufferView has a null plane");
  }
  validateMaterials(scene);
  ws.shader.reset(scene.lights);
  ws.plan = detail::makePlan({scene, camera, target.width, target.height, ws.shader, threadCount(),
                              visibility_, twoSidedLighting_});
  ws.plan.rasterRoutine = detail::chooseTileRoutine(ws.plan.depthTest).name;
  validateCounts(ws.plan);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    detail::validateMeshHeader(scene.meshes[m].mesh, m);

  RenderStats stats;
  ws.transform.emplace(camera, target.width, target.height);
  ws.grid = detail::TileGrid(target.width, target.height);
  const Rgba8 background = toRgba8(background_, backgroundAlpha_);
  const detail::PhaseSet phases{Phase::Validate, Phase::Transform, Phase::Sort,   Phase::Setup,
                                Phase::Raster,   Phase::Shade,     Phase::Resolve};
  detail::PhaseRunner runner(*ws.pool, progress_, phases);
  const bool completed = ws.renderFull(scene, target, background, runner, stats);
  if (!completed) clearTarget(target, background);
  stats.shadeSeconds += runner.lap();
  stats.aborted = !completed;
  stats.plan = ws.plan;
  ws.collectStatistics(stats);
  stats.totalSeconds = runner.secondsSinceStart();
  if (completed) runner.finish();
  return stats;
}

}  // namespace facet
