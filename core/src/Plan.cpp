#include "Plan.h"

#include "TileGrid.h"

namespace facet::detail {

RenderPlan makePlan(const PlanInputs& in) {
  RenderPlan plan;
  plan.visibility = in.visibility;
  plan.depthTest = in.visibility == Visibility::ZBuffer;
  plan.sortByDepth = in.visibility == Visibility::PainterSort;
  plan.directLighting = in.shader.lightCount() > 0;
  plan.positionalLights = in.shader.hasPositionalLights();
  plan.twoSidedLighting = in.twoSidedLighting;
  plan.parallelProjection = in.camera.parallelProjection;
  for (const SceneMesh& mesh : in.scene.meshes) {
    plan.specular |= plan.directLighting && mesh.material.specular > 0.0;
    plan.backfaceCulling |= mesh.material.backfaceCulling;
    plan.closedSurfaces |= mesh.mesh.closedSurface;
    plan.points += mesh.mesh.points.count;
    plan.polygons += mesh.mesh.polygons.count;
  }
  plan.viewerDirection = plan.specular;
  plan.polygonCenters =
      plan.positionalLights || (plan.viewerDirection && !in.camera.parallelProjection);
  const TileGrid grid(in.width, in.height);
  plan.threads = in.threads;
  plan.tileSize = TileGrid::kTileSize;
  plan.tilesX = grid.tilesX();
  plan.tilesY = grid.tilesY();
  plan.width = in.width;
  plan.height = in.height;
  plan.meshes = in.scene.meshes.size();
  return plan;
}

ShadeNeeds shadeNeedsOf(const RenderPlan& plan, const SceneMesh& mesh) {
  ShadeNeeds needs;
  needs.directLighting = plan.directLighting;
  needs.specular = plan.directLighting && mesh.material.specular > 0.0;
  needs.centers = plan.positionalLights || (needs.specular && !plan.parallelProjection);
  needs.polygonColors = !mesh.mesh.polygonColors.empty();
  return needs;
}

}  // namespace facet::detail
