#pragma once

// Phase 0: the plan. Decided once per render from the scene and from what changed since the
// previous render: which path runs (History.h), which rules may leave work out, and which
// routines do the work. Decisions that need the frame's geometry (closed surfaces, the
// coarse depth) are completed by the phases that learn it.

#include "Shade.h"
#include "facet/Camera.h"
#include "facet/Lighting.h"
#include "facet/RenderPlan.h"
#include "facet/Scene.h"

namespace facet::detail {

struct PlanInputs {
  const Scene& scene;
  const Camera& camera;
  int width, height;
  const Shader& shader;  // the lights that remain after Rule::LightsThatReachNothing
  int threads;
  Visibility visibility;
  bool twoSidedLighting;
  bool depthOutput;
  const RenderRules& rules;
};

RenderPlan makePlan(const PlanInputs& inputs);

// What shading one mesh computes under this plan.
ShadeNeeds shadeNeedsOf(const RenderPlan& plan, const SceneMesh& mesh, const RenderRules& rules);

// Rule::HiddenGeometry under HierarchicalZ::Auto: the coarse depth pays where triangles
// overlap many times (depth complexity, the pixels of their boxes over the image's) and
// are large enough to cover its 8 × 8 blocks; on a dense mesh's one-pixel triangles it only
// adds a test. Thresholds measured in bench/ (README, "Leaving out work").
inline constexpr double kCoarseDepthMinComplexity = 4.0;
inline constexpr double kCoarseDepthMinTriangleBox = 64.0;
bool useCoarseDepth(const RenderPlan& plan, HierarchicalZ mode);

// Copies into `plan` what `previous` found out about the geometry of the frame it drew (an
// incremental render reuses that frame).
void carryGeometryReport(RenderPlan& plan, const RenderPlan& previous);

}  // namespace facet::detail
