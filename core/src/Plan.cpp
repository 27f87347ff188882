#include "Plan.h"

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
                        std::size_t previousCoveredPixels) {
  std::size_t everyFace = 0;
  for (const FrameMesh& mesh : meshes)
    everyFace += mesh.skipBackFaces ? 0 : mesh.endPolygon() - mesh.firstPolygon;
  const std::size_t covered = previousCoveredPixels > 0
                                  ? previousCoveredPixels
                                  : static_cast<std::size_t>(plan.width) * plan.height;
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

}  // namespace facet::detail
