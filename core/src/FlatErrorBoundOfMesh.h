#pragma once

// The summary-only estimate's bound (QualityRenderer.cpp): one number per block of
// kBoundBlock consecutive polygons and frame that is at least FlatErrorBound::bound (and its
// float lanes, boundShadeColumns) of every polygon of the block that has a normal, found from
// what they share — the largest radius and normal spread, and the box they lie in, kept per
// mesh version — with no work per polygon per frame. The derivation is in
// FlatErrorBoundOfMesh.cpp.

#include <algorithm>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "facet/Color.h"
#include "facet/Light.h"
#include "facet/Lighting.h"

namespace facet::detail {

// Polygons per block: 2^kBoundBlockShift. A mesh's consecutive polygons are mostly
// neighbours (strips, rings, a scan's order), so a block's bound is near its polygons'; and
// the bounds of a 500k-polygon mesh are 8 kB, which the per-pixel rule reads from L1.
inline constexpr int kBoundBlockShift = 7;
inline constexpr std::size_t kBoundBlock = std::size_t{1} << kBoundBlockShift;

// What a block's polygons with a normal share for the bound (BoundTerms: EstimateHook.h).
struct MeshBoundExtent {
  float radius = 0.0f;           // the largest radius (rounded up)
  float sinNormalSpread = 0.0f;  // the largest sine of a spread (2: 90° or more)
  // The box their corners lie in (low > high: none).
  glm::dvec3 low{std::numeric_limits<double>::infinity()};
  glm::dvec3 high{-std::numeric_limits<double>::infinity()};

  void add(float polygonRadius, float sine, const glm::dvec3& corner) {
    radius = std::max(radius, polygonRadius);
    sinNormalSpread = std::max(sinNormalSpread, sine);
    low = glm::min(low, corner);
    high = glm::max(high, corner);
  }
};

// The largest bound, in 8-bit units, of a polygon within `extent` (its radius, spread and box)
// of material `material` and surface colors at most `surface` per channel, under `lights`;
// nothing where this bound does not apply (a spot light, a specular material: the caller
// takes the per-polygon estimate). Never NaN; at most 255.
std::optional<double> largestFlatBound(const LightSet& lights, const PreparedMaterial& material,
                                       const glm::dvec3& surface, const MeshBoundExtent& extent);

// The same in two steps: what depends on the frame's lights and a mesh's material, once per
// frame and mesh (nothing where the bound does not apply), then each block.
struct BlockBoundSetup {
  struct Source {
    const PointLight* point = nullptr;  // null: a directional light
    glm::dvec3 radiance{0.0};
    double magnitude = 0.0;  // the light position's largest coordinate magnitude
    bool unattenuated = false, constant = false;
    double factor = 1.0;  // the attenuation at distance 0 (all of it when constant)
  };
  std::vector<Source> lights;
  double slope = 1.0, diffuseMax = 1.0, kappa = 0.0;
  glm::dvec3 scale{0.0};  // Kd·|Cd|, Kd with its margin
};
std::optional<BlockBoundSetup> prepareBlockBound(const LightSet& lights,
                                                 const PreparedMaterial& material,
                                                 const glm::dvec3& surface);
double largestFlatBound(const BlockBoundSetup& setup, const MeshBoundExtent& extent);

}  // namespace facet::detail
