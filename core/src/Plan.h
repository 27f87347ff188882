#pragma once

// Phase 0: the plan. Decided once per render from the scene, before any polygon is touched:
// which work runs and which routines do it.

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
  const Shader& shader;  // the scene's lights, prepared
  int threads;
  Visibility visibility;
  bool twoSidedLighting;
};

RenderPlan makePlan(const PlanInputs& inputs);

// What shading one mesh computes under this plan.
ShadeNeeds shadeNeedsOf(const RenderPlan& plan, const SceneMesh& mesh);

}  // namespace facet::detail
