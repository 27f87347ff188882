#pragma once

// FlatErrorBound::bound for many polygons at once, in SIMD lanes (Google Highway, the
// instruction set chosen at run time), for the common case a frame of the flat render with
// the estimate meets: directional and point lights (no spot cone), a material without
// specular, one color per polygon. boundBatch is the same double-precision arithmetic in the
// same order as FlatErrorBound.cpp (no fused multiply-add: the file is compiled with
// -ffp-contract=off), so every lane gives the bytes the scalar bound gives (tested).
// boundShadeColumns, the one the shade phase takes, is that arithmetic in float, with a
// proven margin that keeps it at least the double bound (FlatErrorBoundBatch.cpp); its bytes
// are the same on every instruction set, and the separate passes take it too
// (boundOneColumn). Lanes the scalar bound treats apart (an eye or light at or near the
// polygon's center, or astronomically far) come out NaN, for the caller to bound one by one
// with the double bound.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Camera.h"
#include "facet/Light.h"
#include "facet/Lighting.h"

#include "EstimateHook.h"
#include "ShadeBatch.h"

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
    // The same in float, for the float lanes of boundShadeColumns (nearest: their rounding
    // is in the margin, FlatErrorBoundBatch.cpp).
    float directionF[3] = {};  // a directional light's position
    float radianceF[3] = {};
    float factorF = 1.0f, constantF = 0.0f, linearF = 0.0f, quadraticF = 0.0f, distanceF = 0.0f;
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
  // For the float lanes (FlatErrorBoundBatch.cpp): Kd rounded up with the final products'
  // rounding folded in, the Lerp ends, and the margin per unit of light (kappa).
  float diffuseUp = 1.0f, lerpAmbientF = 0.0f, lerpSpanF = 1.0f, kappa = 0.0f;
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

// std::nextafter(f, INFINITY) for a float below +∞, without the library call (a call per
// visible polygon was a tenth of the bounds' time).
inline float nextUp(float f) {
  if (f == 0.0f) return std::numeric_limits<float>::denorm_min();
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits + 1 : bits - 1);
}

// A bound kept as a float: rounded up, so it stays a bound.
inline float roundedUp(double value) {
  const float f = static_cast<float>(value);
  return f < value ? nextUp(f) : f;
}

// The bounds of a shade batch's polygons (ShadeBatch.h: normals as lit, surface colors; their
// centers as the shade's lanes divided them out), each with its terms (radius and sine, per
// lane): bounds[lane] for lanes [0, batch.count), NaN where the batch leaves it to the scalar
// bound. Taken in float lanes with a proven margin (FlatErrorBoundBatch.cpp): at least
// roundedUp(boundBatch), the double bound, and above it by about 2^-16 of the light's reach
// (tested); the same bytes on every instruction set. And each as the per-pixel estimate reads
// it, fixed[lane] = fixedBoundOf(bounds[lane]) (EstimateRows.h).
void boundShadeColumns(const BatchLighting& lighting, const BatchMaterial& material,
                       const ShadeBatch& batch, const ShadeBatchCenters& centers,
                       const float* radius, const float* sine, float* bounds, EstimateBound* fixed);

// boundShadeColumns for one polygon (the separate passes' bound of a polygon the batches
// take, so that they give the fused estimate's bytes): NaN where the batch leaves it.
float boundOneColumn(const BatchLighting& lighting, const BatchMaterial& material,
                     const glm::dvec3& center, const glm::dvec3& normal, const Color& surface,
                     float radius, float sine);

// The bounds of one shade task's polygons of one mesh (the fused estimate, EstimateHook.h),
// taken batch by batch as the shade phase lights them, into hook.bounds. Polygons the batch
// does not take (a mesh whose material it leaves out, a frame whose lights it leaves out,
// lanes it leaves NaN) go to hook.boundOne.
class ShadeBoundCollector {
 public:
  // Inactive without a hook, or for a mesh that is not one of the hook's. `centers`: the
  // shade phase gathers the polygons' centers (else the bound takes the normal as lit, facing
  // the viewer, and needs no center: the lights are directional).
  ShadeBoundCollector(EstimateHook* hook, const SceneMesh* mesh, std::size_t firstPolygon,
                      bool centers);
  ShadeBoundCollector(const ShadeBoundCollector&) = delete;
  ShadeBoundCollector& operator=(const ShadeBoundCollector&) = delete;

  bool active() const { return hook_ != nullptr; }
  // Polygon `polygon` of the mesh is lane `lane` of the shade batch to come.
  void note(std::size_t lane, std::size_t polygon) {
    const BoundTerms& t = terms_[polygon];
    radius_[lane] = t.radius;
    sine_[lane] = t.sinNormalSpread;
    polygons_[lane] = polygon;
  }
  // Where the shade batch's lanes leave their centers (shadeBatch).
  ShadeBatchCenters* centers() { return &centers_; }
  // The bounds of the batch's polygons, noted lane by lane, their centers left in centers().
  void bound(const ShadeBatch& batch);

  // For the routines that light polygon by polygon: the polygon, lit at `sample` (its
  // position the center), batched here.
  void add(std::size_t polygon, const SurfaceSample& sample) {
    note(own_.count, polygon);
    for (int k = 0; k < 3; ++k)
      centers_.xyz[k][own_.count] = sample.position[k];
    own_.add(sample, 1.0);
    if (own_.full()) flush();
  }
  void flush() {
    if (own_.count > 0) bound(own_);
    own_.count = 0;
  }

 private:
  EstimateHook* hook_ = nullptr;
  std::size_t mesh_ = 0, first_ = 0;
  bool hasCenters_ = true;
  const BoundTerms* terms_ = nullptr;
  const BatchLighting* lighting_ = nullptr;
  const BatchMaterial* material_ = nullptr;  // null: every polygon to boundOne
  // Per lane; past a batch's count, zeros or an earlier batch's (computed, not read).
  alignas(64) float radius_[kShadeBatchSize] = {};
  alignas(64) float sine_[kShadeBatchSize] = {};
  alignas(64) float lanes_[kShadeBatchSize] = {};
  alignas(64) EstimateBound fixed_[kShadeBatchSize] = {};
  std::size_t polygons_[kShadeBatchSize] = {};
  ShadeBatchCenters centers_;
  ShadeBatch own_;  // add()'s

  bool allFromLanes(std::size_t count) const;
  void storeLanes(std::size_t count);
};

}  // namespace facet::detail
