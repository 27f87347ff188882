#include "Plan.h"

#include <algorithm>
#include <cstdint>

#include "LightCulling.h"
#include "MeshCache.h"
#include "TileGrid.h"

namespace facet::detail {
namespace {

void allowRules(RenderPlan& plan, const RenderRules& rules) {
  for (int r = 0; r < kRuleCount; ++r)
    plan.rules[r].allowed = rules.allows(static_cast<Rule>(r));
}

void sizeOf(RenderPlan& plan, int width, int height) {
  const TileGrid grid(width, height);
  plan.tileSize = TileGrid::kTileSize;
  plan.tilesX = grid.tilesX();
  plan.tilesY = grid.tilesY();
  plan.width = width;
  plan.height = height;
}

// Rule::LightsThatReachNothing: the lights kept, prepared into the shader.
void cullLights(const PlanInputs& in, std::span<const Box> bounds, ShadingChoice& shading,
                RenderPlan& plan) {
  RenderPlan::LightCulling& report = plan.lightCulling;
  if (in.rules.lightsThatReachNothing) {
    detail::cullLights(in.scene.lights, {in.scene.meshes, bounds}, in.rules.lightTolerance,
                       shading.keptLights, report);
  } else {
    shading.keptLights = in.scene.lights;
    report = {};
    report.lights = in.scene.lights.lights.size();
  }
  shading.shader.reset(shading.keptLights);
  reportRule(plan, Rule::LightsThatReachNothing,
             report.dark + report.outsideCone + report.belowTolerance);
}

void planLighting(RenderPlan& plan, const PlanInputs& in, const Shader& shader) {
  plan.directLighting = shader.lightCount() > 0;
  plan.positionalLights = shader.hasPositionalLights();
  plan.twoSidedLighting = in.twoSidedLighting;
  for (const SceneMesh& mesh : in.scene.meshes)
    plan.specular |= plan.directLighting && mesh.material.specular > 0.0;
  plan.viewerDirection = plan.specular;
  plan.polygonCenters =
      plan.positionalLights || (plan.viewerDirection && !in.camera.parallelProjection);
}

// The shading routine of every mesh, and what rules 4 and 5 do with them.
void chooseShading(RenderPlan& plan, const PlanInputs& in,
                   std::vector<ShadeRoutineChoice>& routines) {
  routines.clear();
  for (const SceneMesh& mesh : in.scene.meshes)
    routines.push_back(chooseShadeRoutine(shadeNeedsOf(plan, mesh, in.rules)));
  plan.shadeRoutine = commonName(routines, [](const auto& r) { return r.name; });
  RuleOutcome& oneColor = plan.rule(Rule::OneColor);
  for (const ShadeRoutineChoice& routine : routines) {
    plan.rule(Rule::AmbientOnly).fired |= routine.ambientOnly;
    oneColor.skipped += routine.oneColor && in.rules.oneColor;
  }
  oneColor.fired = oneColor.skipped > 0;
}

}  // namespace

RenderPlan makePlan(const PlanInputs& in, std::span<const Box> bounds, ShadingChoice& shading) {
  RenderPlan plan;
  allowRules(plan, in.rules);
  cullLights(in, bounds, shading, plan);
  plan.visibility = in.visibility;
  plan.depthTest = in.visibility == Visibility::ZBuffer;
  plan.sortByDepth = in.visibility == Visibility::PainterSort;
  plan.parallelProjection = in.camera.parallelProjection;
  plan.depthOutput = in.depthOutput;
  planLighting(plan, in, shading.shader);
  for (const SceneMesh& mesh : in.scene.meshes) {
    plan.backfaceCulling |= mesh.material.backfaceCulling;
    plan.closedSurfaces |= mesh.mesh.closedSurface && in.rules.closedSurfaces;
    plan.points += mesh.mesh.points.count;
    plan.polygons += mesh.mesh.polygons.count;
  }
  plan.threads = in.threads;
  plan.meshes = in.scene.meshes.size();
  sizeOf(plan, in.width, in.height);
  chooseShading(plan, in, shading.routines);
  return plan;
}

RenderPlan planAhead(const PlanInputs& in) {
  std::vector<Box> bounds;
  for (const SceneMesh& mesh : in.scene.meshes)
    bounds.push_back(boundsOf(mesh.mesh));
  ShadingChoice shading;
  RenderPlan plan = makePlan(in, bounds, shading);
  plan.pathReason = "planned ahead (Renderer::plan)";
  plan.rasterRoutine =
      plan.depthTest ? "depth test (hierarchical z decided by the render)" : "painter's overwrite";
  return plan;
}

ShadeNeeds shadeNeedsOf(const RenderPlan& plan, const SceneMesh& mesh, const RenderRules& rules) {
  ShadeNeeds needs;
  needs.directLighting = plan.directLighting;
  needs.specular = plan.directLighting && mesh.material.specular > 0.0;
  needs.centers = plan.positionalLights || (needs.specular && !plan.parallelProjection);
  needs.polygonColors = !mesh.mesh.polygonColors.empty();
  needs.polygons = mesh.mesh.polygons.count;
  needs.ambientOnlyRule = rules.ambientOnly;
  needs.oneColorRule = rules.oneColor;
  return needs;
}

bool useCoarseDepth(const RenderPlan& plan, HierarchicalZ mode) {
  if (!plan.depthTest || mode == HierarchicalZ::Off) return false;
  return mode == HierarchicalZ::On || (plan.depthComplexity >= kCoarseDepthMinComplexity &&
                                       plan.meanTriangleBox >= kCoarseDepthMinTriangleBox);
}

TileRoutine chooseRasterRoutine(RenderPlan& plan, std::span<const Chunk> chunks,
                                HierarchicalZ mode) {
  std::size_t samples = 0, triangles = 0;
  for (const Chunk& chunk : chunks) {
    samples += chunk.counts.boxSamples;
    triangles += chunk.counts.trianglesBinned;
  }
  plan.depthComplexity = double(samples) / (double(plan.width) * plan.height);
  plan.meanTriangleBox = triangles == 0 ? 0.0 : double(samples) / double(triangles);
  const TileRoutineChoice choice = chooseTileRoutine(plan.depthTest, useCoarseDepth(plan, mode));
  plan.rasterRoutine = choice.name;
  return choice.paint;
}

void reportRule(RenderPlan& plan, Rule rule, std::size_t skipped) {
  plan.rule(rule).skipped = skipped;
  plan.rule(rule).fired = skipped > 0;
}

void carryGeometryReport(RenderPlan& plan, const RenderPlan& previous) {
  for (Rule rule : {Rule::GeometryOutsideView, Rule::HiddenGeometry, Rule::ClosedSurfaces})
    plan.rule(rule) = previous.rule(rule);
  plan.blocksTested = previous.blocksTested;
  plan.blocksOutside = previous.blocksOutside;
  plan.blocksBackFacing = previous.blocksBackFacing;
  plan.polygonsBackFacing = previous.polygonsBackFacing;
  plan.depthComplexity = previous.depthComplexity;
  plan.meanTriangleBox = previous.meanTriangleBox;
  plan.rasterRoutine = previous.rasterRoutine;
  plan.setupRoutine = previous.setupRoutine;
  plan.twoPassFrame = previous.twoPassFrame;
  plan.everyFacePolygonsPerCoveredPixel = previous.everyFacePolygonsPerCoveredPixel;
  plan.blocksHiddenBehindFront = previous.blocksHiddenBehindFront;
  plan.polygonsHiddenBehindFront = previous.polygonsHiddenBehindFront;
}

bool chooseTwoPassFrame(RenderPlan& plan, std::span<const FrameMesh> meshes,
                        std::size_t coveredPixels) {
  std::size_t everyFace = 0;
  for (const FrameMesh& mesh : meshes)
    everyFace += mesh.skipBackFaces ? 0 : mesh.endPolygon() - mesh.firstPolygon;
  const std::size_t covered =
      coveredPixels > 0 ? coveredPixels : static_cast<std::size_t>(plan.width) * plan.height;
  plan.everyFacePolygonsPerCoveredPixel =
      static_cast<double>(everyFace) / static_cast<double>(std::max<std::size_t>(covered, 1));
  switch (twoPassFrames()) {
    case TwoPassFrames::On:
      plan.twoPassFrame = everyFace > 0;
      break;
    case TwoPassFrames::Off:
      plan.twoPassFrame = false;
      break;
    case TwoPassFrames::ByPlan:
      plan.twoPassFrame = everyFace > 0 && plan.everyFacePolygonsPerCoveredPixel >=
                                               kTwoPassMinPolygonsPerCoveredPixel;
      break;
  }
  return plan.twoPassFrame;
}

namespace {

// Marks the cells the window box of `box`'s corners touches; false when the box is not wholly
// in front of the near plane (its image is then unbounded).
bool markCellsOf(const Box& box, const FrameTransform& transform, const PixelBounds& viewport,
                 int cellsX, std::vector<std::uint8_t>& cells) {
  if (box.empty()) return true;
  if (!transform.boxInFrontOfNear(box)) return false;
  std::int64_t x0 = INT64_MAX, y0 = INT64_MAX, x1 = INT64_MIN, y1 = INT64_MIN;
  for (int i = 0; i < 8; ++i) {
    const WindowVertex v = transform.toWindow(transform.toClip(box.corner(i)));
    x0 = std::min<std::int64_t>(x0, v.x), x1 = std::max<std::int64_t>(x1, v.x);
    y0 = std::min<std::int64_t>(y0, v.y), y1 = std::max<std::int64_t>(y1, v.y);
  }
  const auto pixel = [](std::int64_t fixed) { return fixed >> kSubpixelBits; };  // floor
  const std::int64_t px0 = std::max<std::int64_t>(pixel(x0), viewport.x0);
  const std::int64_t px1 = std::min<std::int64_t>(pixel(x1), viewport.x1);
  const std::int64_t py0 = std::max<std::int64_t>(pixel(y0), viewport.y0);
  const std::int64_t py1 = std::min<std::int64_t>(pixel(y1), viewport.y1);
  if (px0 > px1 || py0 > py1) return true;  // outside the image
  // A ring of a UV sphere's blocks spans the sphere's width: rows of cells, not cell by cell.
  const std::int64_t cx0 = px0 >> kCoveredCellBits, cx1 = px1 >> kCoveredCellBits;
  for (std::int64_t cy = py0 >> kCoveredCellBits; cy <= py1 >> kCoveredCellBits; ++cy) {
    const auto row = cells.begin() + cy * cellsX;
    std::fill(row + cx0, row + cx1 + 1, std::uint8_t{1});
  }
  return true;
}

}  // namespace

std::size_t estimateCoveredPixels(std::span<const FrameMesh> meshes, const MeshCache& cache,
                                  const FrameTransform& transform, const TileGrid& grid,
                                  std::vector<std::uint8_t>& cells) {
  const PixelBounds viewport = grid.viewport();
  constexpr int kCell = 1 << kCoveredCellBits;
  const int cellsX = (viewport.x1 + kCell) >> kCoveredCellBits;
  const int cellsY = (viewport.y1 + kCell) >> kCoveredCellBits;
  cells.assign(static_cast<std::size_t>(cellsX) * cellsY, 0);
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const MeshFacts& facts = cache[m];
    if (!facts.measured || facts.blocks.empty()) {
      if (!facts.bounded || !markCellsOf(facts.bounds, transform, viewport, cellsX, cells))
        return 0;
      continue;
    }
    const std::uint8_t* visible = meshes[m].visibleBlocks;
    for (std::size_t b = 0; b < facts.blocks.size(); ++b) {
      if (visible && !visible[b]) continue;
      if (!markCellsOf(facts.blocks[b], transform, viewport, cellsX, cells)) return 0;
    }
  }
  const std::size_t pixels = static_cast<std::size_t>(viewport.x1 + 1) * (viewport.y1 + 1);
  const auto marked = static_cast<std::size_t>(std::count(cells.begin(), cells.end(), 1));
  return std::min(pixels, marked << (2 * kCoveredCellBits));
}

}  // namespace facet::detail
