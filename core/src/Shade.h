#pragma once

// Phase 4: shade. Flat shading is a function of the polygon alone, so only the polygons that
// won a pixel while painting are lit — in id order, as sequential reads of the mesh arrays
// (screen order would scatter them). Polygons hidden all along — behind others, or the back
// faces of a closed surface — are never lit; one overdrawn later is lit once for nothing.
//
// Each mesh is shaded by a routine chosen once per render from what its shading needs
// (direct light or not, polygon centers, specular, per-polygon colors), as llvmpipe picks
// its triangle routine: no per-polygon tests of the plan.

#include <cstdint>
#include <span>
#include <vector>

#include "Frame.h"
#include "PhaseRunner.h"
#include "ShownPolygons.h"

namespace facet::detail {

struct EstimateHook;  // EstimateHook.h

struct ShadeContext {
  const FrameTransform& transform;
  const Shader& shader;
  bool twoSidedLighting;
  const std::uint8_t* shown;       // per polygon id (Raster.h)
  const std::uint8_t* backFacing;  // per polygon id (Setup.h)
  Rgba8* colors;                   // out, per shown polygon id
  // The error estimate's bounds, taken as the polygons are lit (EstimateHook.h); null: none.
  EstimateHook* estimate = nullptr;
};

// Shades the shown polygons among one mesh's polygons [begin, end); returns how many.
using ShadeRoutine = std::size_t (*)(const ShadeContext& context, const FrameMesh& mesh,
                                     std::size_t begin, std::size_t end);
struct ShadeRoutineChoice {
  ShadeRoutine shade = nullptr;
  const char* name = "";
  bool ambientOnly = false;  // Rule::AmbientOnly: no normal, no light loop
  bool oneColor = false;     // Rule::OneColor: no color fetched per polygon
};

// What one mesh's shading computes, and which rules may leave work out of it.
struct ShadeNeeds {
  bool directLighting = false;  // else the color does not depend on the normal
  bool centers = false;         // positional lights, or a perspective viewer for specular
  bool specular = false;        // the material's Ks > 0 under a direct light
  bool polygonColors = false;   // the mesh has its own color per polygon
  std::size_t polygons = 0;
  bool ambientOnlyRule = true;  // RenderRules::ambientOnly
  bool oneColorRule = true;     // RenderRules::oneColor
};
ShadeRoutineChoice chooseShadeRoutine(const ShadeNeeds& needs);

struct ShadeBuffers {
  std::vector<MeshRange> ranges;
  std::vector<std::size_t> counts;  // polygons shaded per range
};

// Shades every mesh with its routine (`routines[mesh]`).
bool shadePolygons(PhaseRunner& runner, std::span<const FrameMesh> meshes,
                   std::span<const ShadeRoutineChoice> routines, const ShadeContext& context,
                   ShadeBuffers& buffers);

}  // namespace facet::detail
