#pragma once

// Phase 0: what is checked about every mesh before a render reads it.

#include <optional>
#include <vector>

#include "Frame.h"
#include "MeshAccess.h"
#include "PhaseRunner.h"
#include "facet/Scene.h"

namespace facet::detail {

struct ValidationScratch {
  std::vector<MeshRange> ranges;
  std::vector<std::optional<MeshProblem>> problems;
};

// Offsets and point ids of every mesh, in parallel. Throws facet::Error for the first
// problem in polygon order, whatever the thread count; false when the progress callback
// asked to stop.
bool validateMeshes(PhaseRunner& runner, const Scene& scene, ValidationScratch& scratch);

}  // namespace facet::detail
