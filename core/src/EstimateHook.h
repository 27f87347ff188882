#pragma once

// The error estimate fused into a flat render (QualityRenderer.cpp): what QualityRenderer
// hands the Renderer so that the estimate costs no pass of its own.
//
//  - Shade (Shade.h, ShadeLit.h): the shade phase gathers every shown polygon's center (the
//    sum of its corners), its unit normal facing the side seen, and its surface color to
//    light it; the polygon's bound (FlatErrorBound.h) needs the same, plus two numbers that
//    do not depend on the camera (BoundTerms, kept per mesh version by QualityRenderer). So
//    the bound is taken there, in batches (FlatErrorBoundBatch.h), while those are in cache,
//    in place of a second walk that read a 48-byte extent per polygon, scattered.
//  - Resolve (Resolve.h): the resolve reads every pixel's polygon id to gather its color; the
//    estimate per pixel (EstimateRows.h) reads the ids of its 3 × 3 neighbourhood and their
//    polygons' colors and bounds. Each band of rows estimates its own rows after resolving
//    them, from ids (final since the raster) and the per-polygon colors (final since the
//    shade), never from another band's color rows (written at the same time): the same
//    bytes as the pass over the finished image, in place of a second read of the planes.
//
// The resolve's part at one sample per pixel only; QualityRenderer runs the pass over the
// samples otherwise. Without the ErrorEstimate image (the summary alone), under the lights and
// materials FlatErrorBoundOfMesh.h takes, the shade bounds nothing and the resolve reads one
// bound per block of polygon ids, found before the render (QualityRenderer::blockBounds).

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

#include <glm/vec3.hpp>

#include "EstimateRows.h"
#include "FunctionRef.h"
#include "facet/Color.h"
#include "facet/Scene.h"

namespace facet::detail {

struct BatchLighting;
struct BatchMaterial;

// A polygon's part of its bound that does not depend on the camera: the largest distance of
// a corner from its center, and the sine of its corner normals' spread about its (float)
// face normal (2: 90° or more), both rounded up so the bound stays a bound. A radius below 0:
// no normal (degenerate), whose bound is the largest.
struct BoundTerms {
  float radius = -1.0f;
  float sinNormalSpread = 2.0f;
};

struct EstimateHook {
  // The scene's meshes (FrameMesh::source points into them) and per mesh its terms.
  const SceneMesh* meshes = nullptr;
  std::size_t meshCount = 0;
  const BoundTerms* const* terms = nullptr;
  // The lighting the bound batches take (null: none, every polygon bounded by boundOne), and
  // per mesh its material's terms (nullopt: bounded by boundOne).
  const BatchLighting* lighting = nullptr;
  // The same lights as seen by polygons whose normal already faces the viewer, for the shade
  // routines without centers (directional lights only): parallel, one-sided.
  const BatchLighting* facingLighting = nullptr;
  const std::optional<BatchMaterial>* materials = nullptr;
  // The bound of one polygon of a mesh, lit at `center` (null: not at hand, the callee finds
  // it) with `normal` as flat shading lit it; rounded up to float.
  FunctionRef<float(std::size_t mesh, std::size_t polygon, const glm::dvec3* center,
                    const glm::dvec3& normal)>
      boundOne;
  // Out: per polygon id, the bound of each shown polygon of a mesh marked bounded, and the
  // same in the resolve's fixed point (fixedBoundOf; an even count).
  float* bounds = nullptr;
  EstimateBound* fixedBounds = nullptr;
  // The resolve reads fixedBounds[id >> boundShift]: with the summary-only estimate, one bound
  // per block of polygons (QualityRenderer.cpp, FlatErrorBoundOfMesh.h), the shade none.
  int boundShift = 0;
  std::unique_ptr<std::atomic<bool>[]> bounded;  // per mesh: the shade phase bounded it

  // The resolve's part, at one sample per pixel (null rows: none). Out: per pixel row its
  // sums, and the estimate image when not null.
  int height = 0;
  EstimateSums* rows = nullptr;
  float* image = nullptr;

  // The index of a frame mesh's source among `meshes`, or meshCount when it is not one.
  std::size_t meshOf(const SceneMesh* source) const {
    const auto at = reinterpret_cast<std::uintptr_t>(source),
               first = reinterpret_cast<std::uintptr_t>(meshes);
    const std::size_t m = (at - first) / sizeof(SceneMesh);
    return at >= first && m < meshCount ? m : meshCount;
  }
};

// The resolve's part: the estimate of pixel rows [y0, y1] of a resolved band into hook.rows
// (and hook.image), from the planes of ids and colors (`width` wide) and the colors per
// polygon id (EstimateRows.h: the same bytes as QualityRenderer's pass over the image).
void estimateResolvedRows(const EstimateHook& hook, const Rgba8* polygonColors, const Rgba8* colors,
                          const std::int32_t* ids, int width, int y0, int y1);

}  // namespace facet::detail
