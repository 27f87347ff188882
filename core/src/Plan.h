#pragma once

// Phase 0: the plan. Decided once per render from the scene and from what changed since the
// previous render: which path runs (History.h), which rules may leave work out, and which
// routines do the work. Decisions that need the frame's geometry (closed surfaces, the
// coarse depth) are completed by the phases that learn it.

#include <span>
#include <string_view>
#include <vector>

#include "Box.h"
#include "FrameTransform.h"
#include "MeshCache.h"
#include "Raster.h"
#include "Shade.h"
#include "TileGrid.h"
#include "facet/Camera.h"
#include "facet/Lighting.h"
#include "facet/RenderPlan.h"
#include "facet/Scene.h"

namespace facet::detail {

struct PlanInputs {
  const Scene& scene;
  const Camera& camera;
  int width, height;
  int threads;
  Visibility visibility;
  bool twoSidedLighting;
  bool depthOutput;
  const RenderRules& rules;
};

// What the plan decides about shading: the lights kept by Rule::LightsThatReachNothing,
// prepared, and each mesh's shading routine.
struct ShadingChoice {
  LightSet keptLights;
  Shader shader;
  std::vector<ShadeRoutineChoice> routines;  // per mesh
};

// The plan of a render, and its shading. `bounds`: each mesh's bounding box, or empty when
// they are not known (the lights are then judged as reaching everything).
RenderPlan makePlan(const PlanInputs& inputs, std::span<const Box> bounds, ShadingChoice& shading);

// The plan a full render would start with (Renderer::plan): the meshes' bounds measured
// here, the decisions the geometry settles left to the render.
RenderPlan planAhead(const PlanInputs& inputs);

// The name every item's routine shares, or "per mesh".
template <class Items, class NameOf>
const char* commonName(const Items& items, const NameOf& nameOf) {
  if (items.empty()) return "none (no mesh)";
  for (const auto& item : items) {
    if (std::string_view(nameOf(item)) != nameOf(items.front())) return "per mesh";
  }
  return nameOf(items.front());
}

// What shading one mesh computes under this plan.
ShadeNeeds shadeNeedsOf(const RenderPlan& plan, const SceneMesh& mesh, const RenderRules& rules);

// Rule::HiddenGeometry under HierarchicalZ::Auto: the coarse depth pays where triangles
// overlap many times (depth complexity, the pixels of their boxes over the image's) and
// are large enough to cover its 8 × 8 blocks; on a dense mesh's one-pixel triangles it only
// adds a test. Thresholds measured in bench/ (README, "Leaving out work").
inline constexpr double kCoarseDepthMinComplexity = 4.0;
inline constexpr double kCoarseDepthMinTriangleBox = 64.0;
bool useCoarseDepth(const RenderPlan& plan, HierarchicalZ mode);

// The tile routine (Raster.h), once the set-up is known: Rule::HiddenGeometry's estimate
// from the chunks (depth complexity, the mean triangle's box) decides the coarse depth.
TileRoutine chooseRasterRoutine(RenderPlan& plan, std::span<const Chunk> chunks,
                                HierarchicalZ mode);

// A frame drawing every face of some mesh (the depth test, z-buffer order, the coarse depth
// not forced) runs in two passes (Raster.h: the back faces set up after the front faces are
// painted, whole blocks of them hidden behind the front faces dropped, HiddenBlocks.h) when
// those meshes have at least this many polygons per pixel the previous frame covered (the
// image's pixels before a first frame): measured, two passes took 0.78x the frame time at
// 500k triangles (1.7 a covered pixel), 0.88x at 2M (6.9), but 1.2x at 20k (0.07), where the
// planes' round trip outweighs the little set-up saved (bench/core-frame-issue11.md, 18b, 21).
inline constexpr double kTwoPassMinPolygonsPerCoveredPixel = 1.0;
// Decides plan.twoPassFrame (and reports its figures in `plan`) for a frame that may take two
// passes; TwoPassFrames::On or Off (Raster.h) overrides the rule. `coveredPixels`: the
// previous frame's, or estimateCoveredPixels' before a first frame (0: the image's pixels).
bool chooseTwoPassFrame(RenderPlan& plan, std::span<const FrameMesh> meshes,
                        std::size_t coveredPixels);

// Cells of 8 × 8 pixels (kCoveredCellBits) for estimateCoveredPixels.
inline constexpr int kCoveredCellBits = 3;
// Before a first frame (no covered pixels to go by): the pixels of the 8 × 8 cells that the
// window boxes of the meshes' blocks in view (MeshCache.h; a mesh's bounds when it has no
// blocks) touch, at most the image's. Never below the pixels the frame covers (each lies in
// a triangle, inside its block's box's image), above them by the cells along the silhouette
// and the boxes' corners: 1.52x for a sphere 300 pixels across. 0 (unknown) when a box is not
// wholly in front of the near plane or a mesh is not bounded. `cells`: scratch.
std::size_t estimateCoveredPixels(std::span<const FrameMesh> meshes, const MeshCache& cache,
                                  const FrameTransform& transform, const TileGrid& grid,
                                  std::vector<std::uint8_t>& cells);

// Records that `rule` left out `skipped` items (fired when some).
void reportRule(RenderPlan& plan, Rule rule, std::size_t skipped);

// Copies into `plan` what `previous` found out about the geometry of the frame it drew (an
// incremental render reuses that frame).
void carryGeometryReport(RenderPlan& plan, const RenderPlan& previous);

}  // namespace facet::detail
