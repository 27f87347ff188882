#pragma once

// FlatErrorBound::bound for many polygons at once, in SIMD lanes (Google Highway, the
// instruction set chosen at run time), for the common case a frame of the flat render with
// the estimate meets: directional and point lights (no spot cone), a material without
// specular, one color per polygon. It is the same double-precision arithmetic in the same
// order as FlatErrorBound.cpp (no fused multiply-add: the file is compiled with
// -ffp-contract=off), so every lane gives the bytes the scalar bound gives, on any
// instruction set (tested). Lanes the scalar bound treats apart (an eye or light at or near
// the polygon's center, or astronomically far) come out NaN, for the caller to bound one by
// one.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Camera.h"
#include "facet/Light.h"
#include "facet/Lighting.h"

namespace facet::detail {

// Lanes per batch: two AVX-512 vectors of doubles, four of AVX2, eight of SSE4.
inline constexpr std::size_t kBoundBatchSize = 16;

// What the bound of one frame needs: the camera and the lights, prepared once per frame.
struct BatchLighting {
  struct Source {
    bool directional = false;
    glm::dvec3 position{0.0};  // point light; a directional light's unit direction toward it
    glm::dvec3 radiance{0.0};  // color × intensity, capped as FlatErrorBound.cpp's
    // Constant: a QuadraticAttenuation of constant term only (vtkLight's default), its factor
    // the same at every distance.
    enum class Falloff { None, Constant, Quadratic, Distance } falloff = Falloff::None;
    double factor = 1.0;                                   // Constant
    double constant = 0.0, linear = 0.0, quadratic = 0.0;  // Quadratic
    double distance = 0.0;                                 // Distance
  };
  std::vector<Source> lights;
  glm::dvec3 eye{0.0}, viewer{0.0, 0.0, 1.0};  // viewer: toward it under parallel projection
  bool parallel = false, twoSided = true;
};

// What the bound needs of one material: its diffuse terms.
struct BatchMaterial {
  double diffuse = 1.0;  // Kd
  bool lerp = false;     // DiffuseModel::Lerp, with its two ends
  double lerpAmbient = 0.0, lerpFull = 1.0;
};

// The lighting of the batch, or nothing when the frame is one the batch leaves to the scalar
// bound (a spot light).
std::optional<BatchLighting> batchLighting(const LightSet& lights, const Camera& camera,
                                           bool twoSidedLighting);
// The material's terms, or nothing for one the batch leaves to the scalar bound (specular).
std::optional<BatchMaterial> batchMaterial(const PreparedMaterial& material);

// Polygons in lanes (the fields of PolygonShape that the batch reads), and their bounds.
struct BoundBatch {
  alignas(64) double center[3][kBoundBatchSize];
  alignas(64) double normal[3][kBoundBatchSize];  // unit; zero gives a NaN bound
  alignas(64) double radius[kBoundBatchSize];
  alignas(64) double sinNormalSpread[kBoundBatchSize];  // ≥ 1: 90° or more
  alignas(64) double surface[3][kBoundBatchSize];       // Cd, capped at kMaxRadiance
  alignas(64) double bound[kBoundBatchSize];            // out: 8-bit units; NaN: not bounded
};

// Fills `bound` of lanes [0, count) (the others are left to any value). A lane of zero
// normal (a degenerate polygon) is NaN too.
void boundBatch(const BatchLighting& lighting, const BatchMaterial& material, BoundBatch& batch,
                std::size_t count);

// A polygon's part of the estimate that does not depend on the camera (QualityRenderer.cpp):
// its center (in double, for data far from the origin) so a frame reads no corners; its
// normal, flat shading's rounded to float as the Renderer's; its radius and the sine of its
// corner normals' spread about that normal, both rounded up, so the bound stays a bound.
struct BoundExtent {
  glm::dvec3 center{0.0};
  glm::vec3 normal{0.0f};  // zero: degenerate
  float radius = 0.0f;
  float sinNormalSpread = 0.0f;  // 2: 90° or more
};

// The most polygons gatherExtents takes: their fields' offsets fit 32-bit lanes.
inline constexpr std::size_t kMaxGatheredPolygons = (std::size_t{1} << 31) / sizeof(BoundExtent);

// The center, normal, radius and spread of lanes [0, kBoundBatchSize) from
// extents[polygons[lane]], gathered in SIMD lanes; the lanes from `count` on repeat lane 0.
// Every polygon index is below kMaxGatheredPolygons.
void gatherExtents(const BoundExtent* extents, const std::uint32_t* polygons, std::size_t count,
                   BoundBatch& batch);

}  // namespace facet::detail
