#pragma once

// The summary-only estimate's bound (QualityRenderer.cpp): one number per mesh and frame that
// is at least FlatErrorBound::bound (and its float lanes, boundShadeColumns) of every ordinary
// polygon of the mesh, found from what the polygons share — the largest radius and normal
// spread, kept per mesh version, and the box the mesh lies in — with no work per polygon per
// frame. The derivation is in FlatErrorBoundOfMesh.cpp.

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Color.h"
#include "facet/Light.h"
#include "facet/Lighting.h"

namespace facet::detail {

// What a mesh's polygons share for the bound, per mesh version. The ordinary polygons are
// those with a normal and a spread below 90°; the others are listed by index, for the frame
// to check whether it shows any.
struct MeshBoundExtent {
  float radius = 0.0f;           // the largest radius of an ordinary polygon (rounded up)
  float sinNormalSpread = 0.0f;  // the largest sine of an ordinary polygon's spread
  // The box every finite point lies in (low > high: no point).
  glm::dvec3 low{std::numeric_limits<double>::infinity()};
  glm::dvec3 high{-std::numeric_limits<double>::infinity()};
  std::vector<std::size_t> degenerate;  // no normal: their bound is 255
  std::vector<std::size_t> wide;        // a spread of 90° or more
};

// The largest bound, in 8-bit units, of a polygon of a mesh within `extent`'s radius and box
// and of a spread of sine at most `sinNormalSpread` (extent.sinNormalSpread, or 2 for a frame
// that shows a wide polygon), of material `material` and surface colors at most `surface` per
// channel, under `lights`; nothing where this bound does not apply (a spot light, a specular
// material: the caller takes the per-polygon estimate). Never NaN; at most 255.
std::optional<double> largestFlatBound(const LightSet& lights, const PreparedMaterial& material,
                                       const glm::dvec3& surface, const MeshBoundExtent& extent,
                                       float sinNormalSpread);

}  // namespace facet::detail
