#include "facet/Renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include "Frame.h"
#include "ThreadPool.h"
#include "Validate.h"
#include "facet/Conventions.h"
#include "facet/Error.h"

namespace facet {
namespace {

using detail::Chunk;
using detail::FrameMesh;
using detail::FrameState;
using detail::kTileSize;
using detail::PixelBounds;
using Clock = std::chrono::steady_clock;

// Points per transform task and the bounds of polygons per setup chunk. Chunks aim at four
// per thread for load balance, and stay under 2^20 polygons.
constexpr std::size_t kPointsPerTask = 1 << 14;
constexpr std::size_t kMinPolygonsPerChunk = 1 << 10;
constexpr std::size_t kMaxPolygonsPerChunk = 1 << 20;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

int hardwareThreads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

// A range of one mesh's points or polygons: the unit of the validation, transform and sort
// tasks, which never straddle meshes.
struct MeshRange {
  std::size_t mesh, begin, end;
};

// Reports one phase's finished tasks as the overall fraction the user's callback sees,
// between the phase's start and end (exactly the end when all are done, so fractions never
// step back at the next phase's start).
class PhaseProgress {
 public:
  PhaseProgress(const Renderer::ProgressCallback& callback, double start, double end,
                std::size_t tasks)
      : callback_(callback), start_(start), end_(end), tasks_(tasks) {}
  bool operator()(std::size_t done) const {
    if (!callback_) return true;
    return callback_(
        done >= tasks_ ? end_ : start_ + (end_ - start_) * static_cast<double>(done) / tasks_);
  }

 private:
  const Renderer::ProgressCallback& callback_;
  double start_, end_;
  std::size_t tasks_;
};

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

RenderPlan makePlan(const Scene& scene, const Camera& camera, int width, int height,
                    const Shader& shader, int threads, Visibility visibility, bool twoSided) {
  RenderPlan plan;
  plan.visibility = visibility;
  plan.depthTest = visibility == Visibility::ZBuffer;
  plan.sortByDepth = visibility == Visibility::PainterSort;
  plan.directLighting = shader.lightCount() > 0;
  plan.positionalLights = shader.hasPositionalLights();
  plan.twoSidedLighting = twoSided;
  plan.parallelProjection = camera.parallelProjection;
  for (const SceneMesh& mesh : scene.meshes) {
    plan.specular |= plan.directLighting && mesh.material.specular > 0.0;
    plan.backfaceCulling |= mesh.material.backfaceCulling;
    plan.closedSurfaces |= mesh.mesh.closedSurface;
    plan.points += mesh.mesh.points.count;
    plan.polygons += mesh.mesh.polygons.count;
  }
  plan.viewerDirection = plan.specular;
  plan.polygonCenters =
      plan.positionalLights || (plan.viewerDirection && !camera.parallelProjection);
  plan.threads = threads;
  plan.tileSize = kTileSize;
  plan.tilesX = (width + kTileSize - 1) / kTileSize;
  plan.tilesY = (height + kTileSize - 1) / kTileSize;
  plan.width = width;
  plan.height = height;
  plan.meshes = scene.meshes.size();
  return plan;
}

// Splits every mesh's [0, count(mesh)) into ranges of at most `perRange`.
template <class Count>
void splitPerMesh(const Scene& scene, std::size_t perRange, const Count& count,
                  std::vector<MeshRange>& ranges) {
  ranges.clear();
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const std::size_t n = count(scene.meshes[m].mesh);
    for (std::size_t begin = 0; begin < n; begin += perRange) {
      ranges.push_back({m, begin, std::min(n, begin + perRange)});
    }
  }
}

}  // namespace

// One render's work, phase by phase, on the renderer's reusable state. Each phase returns
// false when the progress callback asked to stop.
struct Renderer::Workspace {
  std::unique_ptr<detail::ThreadPool> pool;
  FrameState frame;
  std::vector<MeshRange> pointRanges;
  std::vector<std::uint32_t> rangeOutcodes;  // OR of the outcodes of each point range
  std::vector<MeshRange> polygonRanges;
  std::vector<std::optional<detail::MeshProblem>> problems;
  std::vector<detail::PaintCounts> tiles;
  std::vector<std::size_t> shadedCounts;

  // Set by begin() for the render under way.
  const Scene* scene = nullptr;
  const Renderer::ProgressCallback* progress = nullptr;
  RenderStats* stats = nullptr;
  Clock::time_point phaseStart;

  // Runs a phase on the pool. The phase's start is always reported: workers may take every
  // task, leaving the caller none to report after.
  template <class Task>
  bool runPhase(std::size_t tasks, Task&& task, double progressBegin, double progressEnd) {
    const PhaseProgress progressOf(*progress, progressBegin, progressEnd,
                                   std::max<std::size_t>(tasks, 1));
    if (!progressOf(0)) return false;
    detail::FunctionRef<void(std::size_t)> taskRef(task);
    auto report = [&](std::size_t done) { return progressOf(done); };
    return pool->run(tasks, taskRef, detail::FunctionRef<bool(std::size_t)>(report));
  }

  // Seconds since the last call (or begin), for the phase timings.
  double lap() {
    const Clock::time_point now = Clock::now();
    return std::chrono::duration<double>(now - std::exchange(phaseStart, now)).count();
  }

  void begin(const Scene& s, const Renderer::ProgressCallback& callback, RenderStats& out) {
    scene = &s;
    progress = &callback;
    stats = &out;
    stats->plan = frame.plan;
    phaseStart = Clock::now();
  }

  bool validateMeshes();
  void prepareFrame(const Camera& camera, const FramebufferView& target, bool twoSided);
  bool transformPoints();
  void decideBackFaces();
  bool sortForPainter();
  bool setUpPolygons();
  bool paintTiles(const detail::Planes& planes);
  bool shadeAndColor(const detail::Planes& planes, Rgba8 background);
  void collectStatistics(bool completed);

  PixelBounds tileBounds(std::size_t t) const {
    const RenderPlan& plan = frame.plan;
    const int tx = static_cast<int>(t % plan.tilesX), ty = static_cast<int>(t / plan.tilesX);
    return {tx * kTileSize, ty * kTileSize, std::min(plan.width, (tx + 1) * kTileSize) - 1,
            std::min(plan.height, (ty + 1) * kTileSize) - 1};
  }
  std::size_t tileCount() const {
    return static_cast<std::size_t>(frame.plan.tilesX) * frame.plan.tilesY;
  }
};

// Offsets and point ids of every mesh, in parallel; throws for the first problem in id
// order, whatever the thread count.
bool Renderer::Workspace::validateMeshes() {
  splitPerMesh(
      *scene, kMaxPolygonsPerChunk / 4, [](const MeshView& m) { return m.polygons.count; },
      polygonRanges);
  problems.assign(polygonRanges.size(), std::nullopt);
  const bool completed = runPhase(
      polygonRanges.size(),
      [&](std::size_t i) {
        const MeshRange& r = polygonRanges[i];
        problems[i] = detail::findMeshProblem(scene->meshes[r.mesh].mesh, r.begin, r.end);
      },
      0.0, 0.05);
  for (std::size_t i = 0; i < problems.size(); ++i) {
    if (problems[i]) detail::throwMeshProblem(*problems[i], polygonRanges[i].mesh);
  }
  stats->validateSeconds = lap();
  return completed;
}

void Renderer::Workspace::prepareFrame(const Camera& camera, const FramebufferView& target,
                                       bool twoSided) {
  frame.transform.emplace(camera, target.width, target.height);
  frame.twoSidedLighting = twoSided;
  frame.viewport = {0, 0, target.width - 1, target.height - 1};
  frame.meshes.clear();
  std::size_t firstVertex = 0, firstPolygon = 0;
  for (const SceneMesh& mesh : scene->meshes) {
    FrameMesh frameMesh{&mesh, PreparedMaterial(mesh.material), firstVertex, firstPolygon,
                        std::nullopt};
    if (!frame.plan.directLighting && mesh.mesh.polygonColors.empty()) {
      frameMesh.uniformColor = toRgba8(frame.shader.shade(SurfaceSample{}, frameMesh.material));
    }
    frame.meshes.push_back(frameMesh);
    firstVertex += mesh.mesh.points.count;
    firstPolygon += mesh.mesh.polygons.count;
  }
}

// Phase 1: every point to window coordinates.
bool Renderer::Workspace::transformPoints() {
  frame.vertices.resize(frame.plan.points);
  splitPerMesh(
      *scene, kPointsPerTask, [](const MeshView& m) { return m.points.count; }, pointRanges);
  rangeOutcodes.assign(pointRanges.size(), 0);
  return runPhase(
      pointRanges.size(),
      [&](std::size_t i) {
        const MeshRange& r = pointRanges[i];
        const FrameMesh& mesh = frame.meshes[r.mesh];
        detail::withTypedMesh(mesh.source->mesh, [&](auto points, auto) {
          std::uint32_t any = 0;
          for (std::size_t p = r.begin; p < r.end; ++p) {
            const detail::WindowVertex v = frame.transform->project(points[p]);
            frame.vertices[mesh.firstVertex + p] = v;
            any |= v.outcode;
          }
          rangeOutcodes[i] = any;
        });
      },
      0.05, 0.2);
}

// Back faces of a closed surface are hidden while no point of it is beyond the near plane
// (none behind the eye: the eye is outside) and none is non-finite (no polygon dropped).
void Renderer::Workspace::decideBackFaces() {
  for (std::size_t m = 0; m < frame.meshes.size(); ++m) {
    std::uint32_t any = 0;
    for (std::size_t i = 0; i < pointRanges.size(); ++i) {
      if (pointRanges[i].mesh == m) any |= rangeOutcodes[i];
    }
    FrameMesh& mesh = frame.meshes[m];
    const bool culled = mesh.source->material.backfaceCulling;
    const bool hidden =
        mesh.source->mesh.closedSurface && (any & (detail::kBeyondNear | detail::kNonFinite)) == 0;
    mesh.skipBackFaces = culled || hidden;
    stats->closedMeshesSkippingBackFaces += hidden && !culled;
  }
}

// Painter's order: far to near by centroid view depth, ties by polygon id.
bool Renderer::Workspace::sortForPainter() {
  frame.drawOrder.clear();
  if (!frame.plan.sortByDepth) return true;
  frame.sortKeys.resize(frame.plan.polygons);
  const bool completed = runPhase(
      polygonRanges.size(),
      [&](std::size_t i) {
        const MeshRange& r = polygonRanges[i];
        const FrameMesh& mesh = frame.meshes[r.mesh];
        detail::withTypedMesh(mesh.source->mesh, [&](auto points, auto polygons) {
          for (std::size_t p = r.begin; p < r.end; ++p) {
            glm::dvec3 sum(0.0);
            const std::size_t n = polygons.size(p);
            for (std::size_t k = 0; k < n; ++k)
              sum += points[polygons.pointId(p, k)];
            double distance = frame.transform->viewDistance(sum / static_cast<double>(n));
            if (!std::isfinite(distance)) distance = std::numeric_limits<double>::infinity();
            const std::size_t id = mesh.firstPolygon + p;
            frame.sortKeys[id] = {distance, static_cast<std::uint32_t>(id)};
          }
        });
      },
      0.2, 0.25);
  std::sort(frame.sortKeys.begin(), frame.sortKeys.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  frame.drawOrder.resize(frame.plan.polygons);
  for (std::size_t i = 0; i < frame.plan.polygons; ++i)
    frame.drawOrder[i] = frame.sortKeys[i].second;
  return completed;
}

// Phase 2: per polygon geometry, in chunks of draw positions (aligned with meshes unless
// painter's order interleaves them).
bool Renderer::Workspace::setUpPolygons() {
  const RenderPlan& plan = frame.plan;
  const std::size_t perChunk =
      std::clamp<std::size_t>(plan.polygons / (4 * static_cast<std::size_t>(plan.threads)) + 1,
                              kMinPolygonsPerChunk, kMaxPolygonsPerChunk);
  if (plan.sortByDepth) {
    polygonRanges.clear();
    for (std::size_t begin = 0; begin < plan.polygons; begin += perChunk) {
      polygonRanges.push_back({0, begin, std::min(plan.polygons, begin + perChunk)});
    }
  } else {
    splitPerMesh(
        *scene, perChunk, [](const MeshView& m) { return m.polygons.count; }, polygonRanges);
    for (MeshRange& r : polygonRanges) {  // to draw positions (= global polygon ids)
      r.begin += frame.meshes[r.mesh].firstPolygon;
      r.end += frame.meshes[r.mesh].firstPolygon;
    }
  }
  frame.polygonColors.resize(plan.polygons);
  frame.shown.resize(plan.polygons);
  frame.chunks.resize(polygonRanges.size());
  for (std::size_t i = 0; i < frame.chunks.size(); ++i) {
    frame.chunks[i].counts = {};  // an aborted render leaves chunks unvisited
    frame.chunks[i].begin = polygonRanges[i].begin;
    frame.chunks[i].end = polygonRanges[i].end;
    frame.chunks[i].bins.resize(tileCount());
  }
  return runPhase(
      frame.chunks.size(), [&](std::size_t i) { detail::setUpChunk(frame, frame.chunks[i]); }, 0.25,
      0.65);
}

// Phase 3: per tile, clear, then paint depth and ids (marking the polygons shown).
bool Renderer::Workspace::paintTiles(const detail::Planes& planes) {
  tiles.assign(tileCount(), {});
  return runPhase(
      tileCount(),
      [&](std::size_t t) {
        const PixelBounds tile = tileBounds(t);
        for (int y = tile.y0; y <= tile.y1; ++y) {
          const std::size_t row = static_cast<std::size_t>(y) * planes.width;
          std::fill(planes.depth + row + tile.x0, planes.depth + row + tile.x1 + 1,
                    detail::kBackgroundDepthKey);
          std::fill(planes.polygonId + row + tile.x0, planes.polygonId + row + tile.x1 + 1,
                    Framebuffer::kBackgroundId);
        }
        detail::PaintCounts counts;
        for (const Chunk& chunk : frame.chunks) {
          for (const std::uint32_t index : chunk.bins[t]) {
            const detail::BinnedTriangle& tri = chunk.triangles[index];
            const auto& a = frame.vertex(chunk, tri.vertex[0]);
            const auto& b = frame.vertex(chunk, tri.vertex[1]);
            const auto& c = frame.vertex(chunk, tri.vertex[2]);
            const detail::EdgeMask boundary = chunk.boundaryEdges[index];
            if (frame.plan.depthTest) {
              detail::paintTriangle<detail::DepthMode::Test>(a, b, c, boundary, tri.polygon, tile,
                                                             planes, counts);
            } else {
              detail::paintTriangle<detail::DepthMode::Overwrite>(a, b, c, boundary, tri.polygon,
                                                                  tile, planes, counts);
            }
          }
        }
        tiles[t] = counts;
      },
      0.65, 0.85);
}

// Phase 4: light the shown polygons (in id order), then color every tile and write its
// window depths.
bool Renderer::Workspace::shadeAndColor(const detail::Planes& planes, Rgba8 background) {
  splitPerMesh(
      *scene, kMaxPolygonsPerChunk / 16, [](const MeshView& m) { return m.polygons.count; },
      polygonRanges);
  shadedCounts.assign(polygonRanges.size(), 0);
  const bool shaded = runPhase(
      polygonRanges.size(),
      [&](std::size_t i) {
        const MeshRange& r = polygonRanges[i];
        shadedCounts[i] = detail::shadeVisiblePolygons(frame, r.mesh, r.begin, r.end);
      },
      0.85, 0.95);
  return shaded &&
         runPhase(
             tileCount(),
             [&](std::size_t t) { detail::resolveTile(frame, tileBounds(t), planes, background); },
             0.95, 1.0);
}

void Renderer::Workspace::collectStatistics(bool completed) {
  stats->aborted = !completed;
  for (const Chunk& chunk : frame.chunks) {
    stats->polygonsDrawn += chunk.counts.drawn;
    stats->polygonsCulled += chunk.counts.culled;
    stats->polygonsOutside += chunk.counts.outside;
    stats->polygonsDegenerate += chunk.counts.degenerate;
    stats->polygonsNonFinite += chunk.counts.nonFinite;
    stats->trianglesBinned += chunk.counts.trianglesBinned;
    stats->trianglesClipped += chunk.counts.trianglesClipped;
  }
  for (const detail::PaintCounts& tile : tiles) {
    stats->fragmentsWritten += tile.written;
    stats->pixelsCovered += tile.covered;
  }
  for (std::size_t count : shadedCounts)
    stats->polygonsShaded += count;
  if (stats->aborted) stats->pixelsCovered = 0;  // the image left is the background
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
  return makePlan(scene, camera, width, height, shader, threadCount(), visibility_,
                  twoSidedLighting_);
}

RenderStats Renderer::render(const Scene& scene, const Camera& camera,
                             const FramebufferView& target) {
  const Clock::time_point start = Clock::now();
  Workspace& ws = *workspace_;

  // Everything that can throw does so before a pixel changes.
  validate(camera);
  validateImageSize(target.width, target.height);
  if (!target.color || !target.depth || !target.polygonId) {
    throw Error("FramebufferView has a null plane");
  }
  validateMaterials(scene);
  ws.frame.shader.reset(scene.lights);
  ws.frame.plan = makePlan(scene, camera, target.width, target.height, ws.frame.shader,
                           threadCount(), visibility_, twoSidedLighting_);
  constexpr std::size_t kMaxIds = std::numeric_limits<std::int32_t>::max();
  if (ws.frame.plan.polygons > kMaxIds || ws.frame.plan.points > kMaxIds) {
    throw Error("Scene has " + std::to_string(ws.frame.plan.polygons) + " polygons and " +
                std::to_string(ws.frame.plan.points) +
                " points; at most 2^31 - 1 of each render at once");
  }
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    detail::validateMeshHeader(scene.meshes[m].mesh, m);
  }
  RenderStats stats;
  ws.begin(scene, progress_, stats);
  bool completed = ws.validateMeshes();

  ws.prepareFrame(camera, target, twoSidedLighting_);
  completed = completed && ws.transformPoints();
  ws.decideBackFaces();
  completed = completed && ws.sortForPainter();
  stats.transformSeconds = ws.lap();
  completed = completed && ws.setUpPolygons();
  stats.setupSeconds = ws.lap();

  const Rgba8 background = toRgba8(background_, backgroundAlpha_);
  const detail::Planes planes{target.color, target.depth, target.polygonId, target.width,
                              ws.frame.shown.data()};
  completed = completed && ws.paintTiles(planes);
  stats.rasterSeconds = ws.lap();
  completed = completed && ws.shadeAndColor(planes, background);
  if (!completed) {
    // Stopped early: leave a valid image (background) rather than a half-painted one.
    const std::size_t pixels = static_cast<std::size_t>(target.width) * target.height;
    std::fill(target.color, target.color + pixels, background);
    std::fill(target.depth, target.depth + pixels, 1.0f);
    std::fill(target.polygonId, target.polygonId + pixels, Framebuffer::kBackgroundId);
  }
  stats.shadeSeconds = ws.lap();

  ws.collectStatistics(completed);
  stats.totalSeconds = secondsSince(start);
  if (completed && progress_) progress_(1.0);
  return stats;
}

}  // namespace facet
