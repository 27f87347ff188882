#include "Plan.h"

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

}  // namespace

RenderPlan makePlan(const PlanInputs& in) {
  RenderPlan plan;
  plan.visibility = in.visibility;
  plan.depthTest = in.visibility == Visibility::ZBuffer;
  plan.sortByDepth = in.visibility == Visibility::PainterSort;
  plan.directLighting = in.shader.lightCount() > 0;
  plan.positionalLights = in.shader.hasPositionalLights();
  plan.twoSidedLighting = in.twoSidedLighting;
  plan.parallelProjection = in.camera.parallelProjection;
  plan.depthOutput = in.depthOutput;
  for (const SceneMesh& mesh : in.scene.meshes) {
    plan.specular |= plan.directLighting && mesh.material.specular > 0.0;
    plan.backfaceCulling |= mesh.material.backfaceCulling;
    plan.closedSurfaces |= mesh.mesh.closedSurface && in.rules.closedSurfaces;
    plan.points += mesh.mesh.points.count;
    plan.polygons += mesh.mesh.polygons.count;
  }
  plan.viewerDirection = plan.specular;
  plan.polygonCenters =
      plan.positionalLights || (plan.viewerDirection && !in.camera.parallelProjection);
  plan.threads = in.threads;
  plan.meshes = in.scene.meshes.size();
  sizeOf(plan, in.width, in.height);
  allowRules(plan, in.rules);
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

void carryGeometryReport(RenderPlan& plan, const RenderPlan& previous) {
  for (Rule rule : {Rule::GeometryOutsideView, Rule::HiddenGeometry, Rule::ClosedSurfaces})
    plan.rule(rule) = previous.rule(rule);
  plan.blocksTested = previous.blocksTested;
  plan.blocksOutside = previous.blocksOutside;
  plan.depthComplexity = previous.depthComplexity;
  plan.meanTriangleBox = previous.meanTriangleBox;
  plan.rasterRoutine = previous.rasterRoutine;
  plan.setupRoutine = previous.setupRoutine;
}

}  // namespace facet::detail
