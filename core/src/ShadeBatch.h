#pragma once

// Phase 4's lighting in SIMD lanes (Google Highway, the instruction set chosen at run time, as
// SetupBatch.h): the colors of a batch of shown polygons at once, for the lighting of nearly
// every scene, directional lights or point lights without attenuation (a VTK headlight, VTK's
// point lights) on a material without specular term. The shade routines (ShadeLit.h) gather
// each polygon's sample (center, normal, color: the memory-bound part, now a short loop whose
// iterations overlap) into columns; the lanes then run Shader::shade's operations
// (Lighting.cpp) on the same doubles in the same order — the square root and the three
// divisions per light that made the polygon-by-polygon loop wait — compiled without fused
// multiply-adds (core/CMakeLists.txt), so every target gives the scalar colors' bytes. A lane
// that would take one of shade()'s rare branches (a light at the sample, or beyond double's
// range from it) has its group shaded by Shader::shade itself.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>

#include "facet/Color.h"
#include "facet/Lighting.h"

namespace facet::detail {

inline constexpr std::size_t kShadeBatchSize = 64;

// Up to kShadeBatchSize samples in columns: SurfaceSample's normal and color, and its position
// as the sum of the polygon's corners and their count (the lanes divide: three divisions per
// polygon were a quarter of the gathering loop's time).
struct ShadeBatch {
  // The lanes past `count` compute on what the columns hold: zeros over one corner, or an
  // earlier batch's samples; never a 0/0.
  ShadeBatch() { std::fill(std::begin(corners), std::end(corners), 1.0); }

  alignas(64) double cornerSum[3][kShadeBatchSize] = {};
  alignas(64) double corners[kShadeBatchSize];
  alignas(64) double normal[3][kShadeBatchSize] = {};
  alignas(64) float color[3][kShadeBatchSize] = {};
  std::size_t count = 0;

  // Every lane's color, for samples added without theirs (polygons of one color: the store
  // per sample was a tenth of the gathering's instructions outside the lanes).
  void setEveryColor(const Color& surface) {
    for (int c = 0; c < 3; ++c)
      std::fill(std::begin(color[c]), std::end(color[c]), surface[c]);
  }

  // `gathered.position` is the sum of `cornerCount` corners. kColor false: its color is the
  // one setEveryColor set.
  template <bool kColor = true>
  void add(const SurfaceSample& gathered, double cornerCount) {
    for (int c = 0; c < 3; ++c) {
      cornerSum[c][count] = gathered.position[c];
      normal[c][count] = gathered.normal[c];
      if constexpr (kColor) color[c][count] = gathered.color[c];
    }
    corners[count] = cornerCount;
    ++count;
  }
  bool full() const { return count == kShadeBatchSize; }
  // Sample i, its position divided out.
  SurfaceSample sample(std::size_t i) const;
};

// Whether shadeBatch takes these lights (their loop: directional, or point lights without
// attenuation). The material's diffuse model and ambient color do not matter; its specular
// term is left out (the routines without specular call shadeBatch).
bool shadesInBatches(const Shader& shader);

// Room for a batch's colors in whole groups of lanes (written past batch.count).
using ShadeBatchColors = std::array<Rgba8, kShadeBatchSize>;

// colors[i] = toRgba8(shader.shade(batch.sample(i), material)) for i < batch.count, with
// shade()'s routine without specular term, for a shader shadesInBatches takes; and the
// samples' positions into `centers` when not null.
// The lanes' centers (positions with the corners divided out), for the error estimate's bound
// of the same polygons (EstimateHook.h).
struct ShadeBatchCenters {
  alignas(64) double xyz[3][kShadeBatchSize] = {};
};

void shadeBatch(const Shader& shader, const PreparedMaterial& material, const ShadeBatch& batch,
                ShadeBatchColors& colors, ShadeBatchCenters* centers = nullptr);

// Up to kShadeBatchSize shown triangles of one color in columns, as the scan of the shown flags
// copies them: each one's corners (as double, with centers), its face normal (as the mesh
// version keeps it), the sign bit that turns that normal to the side seen (two-sided lighting
// of a back face) or 0, and its polygon index. Plain copies: the conversions, sums and tests
// that gatherSample made per polygon (~110 instructions) are the lanes' (shadeTriangleBatch).
struct ShownTriangleBatch {
  // The lanes past `count` compute on what the columns hold: zeros, or an earlier batch's.
  alignas(64) double corner[3][3][kShadeBatchSize] = {};  // [corner][axis]
  alignas(64) float normal[3][kShadeBatchSize] = {};
  alignas(64) std::uint64_t flip[kShadeBatchSize] = {};
  std::int32_t polygon[kShadeBatchSize] = {};
  std::size_t count = 0;
};

// shadeBatch's colors of the batch's triangles from the columns: the center (with `centers`:
// the corners' sum, from 0, over 3; else the origin), the face normal flipped by its sign bit,
// the one `surface` color; the same operations as gatherSample's and shadeBatch's. Returns the
// lanes whose face normal is zero (bit i: triangle i), whose colors the caller takes from
// gatherSample's fallback normal instead.
std::uint64_t shadeTriangleBatch(const Shader& shader, const PreparedMaterial& material,
                                 const ShownTriangleBatch& batch, const Color& surface,
                                 bool centers, ShadeBatchColors& colors);

}  // namespace facet::detail
