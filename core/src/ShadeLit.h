#pragma once

// Shade.cpp's routines under direct light: by [centers][specular] and color source, each for
// the four typed meshes (float or double points, 32- or 64-bit ids), 48 instantiations, and
// the 24 diffuse ones' batches again for meshes of triangles (shadeTrianglesInBatches).
// Defined here and instantiated in four translation units, one per [centers][specular]
// (ShadeLit*.cpp): in one file they were the core's longest compile, which a build's other
// cores waited for.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

#include "FaceNormal.h"
#include "FlatErrorBoundBatch.h"
#include "MeshAccess.h"
#include "Shade.h"
#include "ShadeBatch.h"
#include "ShaderAccess.h"

namespace facet::detail {
namespace shading {

// Where a polygon's surface color comes from: the material, the mesh's per-polygon
// colors, or either, tested per polygon (the routine when Rule::OneColor is off).
enum class ColorSource { Material, PerPolygon, Either };

inline Color polygonColor(const FrameMesh& mesh, std::size_t polygon) {
  const Rgba8 c = mesh.mesh().polygonColors[polygon];
  return Color(c.r, c.g, c.b) / 255.0f;
}

template <ColorSource kSource>
Color surfaceColor(const FrameMesh& mesh, std::size_t polygon) {
  if constexpr (kSource == ColorSource::PerPolygon) {
    return polygonColor(mesh, polygon);
  } else if constexpr (kSource == ColorSource::Either) {
    if (!mesh.mesh().polygonColors.empty()) return polygonColor(mesh, polygon);
  }
  return mesh.source->material.color;
}

// One polygon's sample under direct light before its center is divided out: `sample.position`
// holds the sum of its `corners` corners (kCenters; else the origin over 1), its normal faces
// the side seen, its color is the surface color.
struct GatheredSample {
  SurfaceSample sample;
  double corners = 1.0;
};

template <bool kCenters, ColorSource kColors, class PointsT, class PolygonsT>
GatheredSample gatherSample(const ShadeContext& context, const FrameMesh& mesh, PointsT points,
                            PolygonsT polygons, std::size_t polygon, bool seenFromBack) {
  GatheredSample gathered;
  SurfaceSample& sample = gathered.sample;
  sample.color = surfaceColor<kColors>(mesh, polygon);
  const std::size_t n = polygons.size(polygon);
  const auto corner = [&](std::size_t k) { return points[polygons.pointId(polygon, k)]; };
  const glm::vec3 normal = mesh.faceNormals ? mesh.faceNormals[polygon] : faceNormalOf(n, corner);
  if constexpr (kCenters) {
    glm::dvec3 sum(0.0);
    for (std::size_t k = 0; k < n; ++k)
      sum += corner(k);
    sample.position = sum;
    gathered.corners = static_cast<double>(n);
  }
  // A polygon with area on screen but none in 3D (pathological input only) faces the viewer.
  sample.normal =
      normal != glm::vec3(0.0f) ? glm::dvec3(normal) : context.transform.toViewer(corner(0));
  if (seenFromBack && context.twoSidedLighting) sample.normal = -sample.normal;
  return gathered;
}

// The sample one polygon is lit at under direct light, at its center.
template <bool kCenters, bool kSpecular, ColorSource kColors, class PointsT, class PolygonsT>
SurfaceSample litSample(const ShadeContext& context, const FrameMesh& mesh, PointsT points,
                        PolygonsT polygons, std::size_t polygon, bool seenFromBack) {
  GatheredSample gathered =
      gatherSample<kCenters, kColors>(context, mesh, points, polygons, polygon, seenFromBack);
  SurfaceSample& sample = gathered.sample;
  if constexpr (kCenters) sample.position /= gathered.corners;
  if constexpr (kSpecular) sample.toViewer = context.transform.toViewer(sample.position);
  return sample;
}

// The shown polygons among [begin, end) without specular term, under lights ShadeBatch.h
// takes: their samples gathered into columns, lit in SIMD lanes (the same bytes).
template <bool kCenters, ColorSource kColors, class PointsT, class PolygonsT>
std::size_t shadeLitInBatches(const ShadeContext& context, const FrameMesh& mesh, PointsT points,
                              PolygonsT polygons, std::size_t begin, std::size_t end) {
  ShadeBatch batch;
  ShadeBatchColors colors;
  std::size_t ids[kShadeBatchSize];
  std::size_t shaded = 0;
  ShadeBoundCollector bounds(context.estimate, mesh.source, mesh.firstPolygon, kCenters);
  constexpr bool kOneColor = kColors == ColorSource::Material;
  if constexpr (kOneColor) batch.setEveryColor(mesh.source->material.color);
  const auto flush = [&] {
    shadeBatch(context.shader, mesh.material, batch, colors,
               bounds.active() ? bounds.centers() : nullptr);
    if (bounds.active()) bounds.bound(batch);
    for (std::size_t i = 0; i < batch.count; ++i)
      context.colors[ids[i]] = colors[i];
    shaded += batch.count;
    batch.count = 0;
  };
  forEachShownPolygon(context.shown + mesh.firstPolygon, begin, end, [&](std::size_t polygon) {
    const std::size_t id = mesh.firstPolygon + polygon;
    ids[batch.count] = id;
    const GatheredSample gathered = gatherSample<kCenters, kColors>(
        context, mesh, points, polygons, polygon, context.backFacing[id]);
    if (bounds.active()) bounds.note(batch.count, polygon);
    batch.add<!kOneColor>(gathered.sample, gathered.corners);
    if (batch.full()) flush();
  });
  flush();
  return shaded;
}

// A versioned triangle mesh of one color without the error estimate: the scan of the shown
// flags copies each shown triangle's corners and face normal into columns, and the lanes do
// the rest of gatherSample's work (ShadeBatch.h, shadeTriangleBatch): the per-polygon gathering
// was ~110 instructions, most of the phase. A zero face normal (no area in 3D) takes
// gatherSample's fallback here, as the lanes cannot.
template <bool kCenters, class PointsT, class IndexT>
std::size_t shadeTrianglesCopied(const ShadeContext& context, const FrameMesh& mesh, PointsT points,
                                 Triangles<IndexT> triangles, std::size_t begin, std::size_t end) {
  const Color surface = mesh.source->material.color;
  const std::uint64_t flipBit = context.twoSidedLighting ? std::uint64_t{1} << 63 : 0;
  const std::uint8_t* backFacing = context.backFacing + mesh.firstPolygon;
  Rgba8* out = context.colors + mesh.firstPolygon;
  ShownTriangleBatch batch;
  ShadeBatchColors colors;
  std::size_t shaded = 0;
  // The face normals and corner ids of the polygons kPrefetchPolygons ahead, asked for early:
  // at 2M the shown polygons' runs (half a meridian each in vtkSphereSource's order) are too
  // short for the hardware prefetcher, and the copies waited on these loads (section 36).
  constexpr std::size_t kPrefetchPolygons = 256;
  const std::size_t lastPolygon = mesh.mesh().polygons.count - 1;
  const auto flush = [&] {
    std::uint64_t zeroNormals =
        shadeTriangleBatch(context.shader, mesh.material, batch, surface, kCenters, colors);
    for (; zeroNormals != 0; zeroNormals &= zeroNormals - 1) {
      const auto lane = static_cast<std::size_t>(std::countr_zero(zeroNormals));
      const auto polygon = static_cast<std::size_t>(batch.polygon[lane]);
      const SurfaceSample sample = litSample<kCenters, false, ColorSource::Material>(
          context, mesh, points, triangles, polygon, backFacing[polygon] != 0);
      colors[lane] = toRgba8(
          ShaderAccess::routine(context.shader, false)(context.shader, sample, mesh.material));
    }
    for (std::size_t i = 0; i < batch.count; ++i)
      out[batch.polygon[i]] = colors[i];
    shaded += batch.count;
    batch.count = 0;
  };
  forEachShownPolygon(context.shown + mesh.firstPolygon, begin, end, [&](std::size_t polygon) {
    const std::size_t lane = batch.count;
    const std::size_t ahead = std::min(polygon + kPrefetchPolygons, lastPolygon);
    __builtin_prefetch(mesh.faceNormals + ahead);
    __builtin_prefetch(triangles.connectivity + 3 * ahead);
    batch.polygon[lane] = static_cast<std::int32_t>(polygon);
    batch.flip[lane] = -static_cast<std::uint64_t>(backFacing[polygon] != 0) & flipBit;
    const glm::vec3& normal = mesh.faceNormals[polygon];
    for (int c = 0; c < 3; ++c)
      batch.normal[c][lane] = normal[c];
    if constexpr (kCenters) {
      for (std::size_t k = 0; k < 3; ++k) {
        const glm::dvec3 corner = points[triangles.pointId(polygon, k)];
        for (int c = 0; c < 3; ++c)
          batch.corner[k][c][lane] = corner[c];
      }
    }
    if (++batch.count == kShadeBatchSize) flush();
  });
  if (batch.count != 0) flush();
  return shaded;
}

// Flattened: with these many instantiations, GCC's unit-growth limit would otherwise
// leave the per-polygon helpers (normal, corners, toRgba8) as calls, ~25 % of the phase.
// Not under AddressSanitizer: flattening 48 instrumented instantiations takes GCC 12 more
// than half an hour, and a sanitizer build measures no speed.
#if defined(__SANITIZE_ADDRESS__)
#define FACET_FLATTEN
#else
#define FACET_FLATTEN [[gnu::flatten]]
#endif
template <bool kCenters, bool kSpecular, ColorSource kColors, class PointsT, class PolygonsT>
FACET_FLATTEN std::size_t shadeLitTyped(const ShadeContext& context, const FrameMesh& mesh,
                                        PointsT points, PolygonsT polygons, std::size_t begin,
                                        std::size_t end) {
  if constexpr (!kSpecular) {
    if (shadesInBatches(context.shader)) {
      return shadeLitInBatches<kCenters, kColors>(context, mesh, points, polygons, begin, end);
    }
  }
  const ShaderAccess::Routine shade = ShaderAccess::routine(context.shader, kSpecular);
  std::size_t shaded = 0;
  ShadeBoundCollector bounds(context.estimate, mesh.source, mesh.firstPolygon, kCenters);
  forEachShownPolygon(context.shown + mesh.firstPolygon, begin, end, [&](std::size_t polygon) {
    const std::size_t id = mesh.firstPolygon + polygon;
    ++shaded;
    const SurfaceSample sample = litSample<kCenters, kSpecular, kColors>(
        context, mesh, points, polygons, polygon, context.backFacing[id]);
    context.colors[id] = toRgba8(shade(context.shader, sample, mesh.material));
    if (bounds.active()) bounds.add(polygon, sample);
  });
  if (bounds.active()) bounds.flush();
  return shaded;
}

// A triangle mesh's corners read without its offsets (MeshAccess.h, Triangles): 8 bytes fewer
// a polygon shaded. Only in batches, the routine of the lights most scenes have: the others'
// per-polygon cost is far larger than the offset's load, and instantiating all of them for
// triangles too doubled these files' compile time (44 -> 88 s for ShadeLitCentersDiffuse.cpp).
template <bool kCenters, ColorSource kColors, class PointsT, class IndexT>
FACET_FLATTEN std::size_t shadeTrianglesInBatches(const ShadeContext& context,
                                                  const FrameMesh& mesh, PointsT points,
                                                  Triangles<IndexT> triangles, std::size_t begin,
                                                  std::size_t end) {
  if constexpr (kColors == ColorSource::Material) {
    constexpr std::size_t kInt32Max = std::numeric_limits<std::int32_t>::max();
    if (mesh.faceNormals && !context.estimate && mesh.mesh().polygons.count <= kInt32Max) {
      return shadeTrianglesCopied<kCenters>(context, mesh, points, triangles, begin, end);
    }
  }
  return shadeLitInBatches<kCenters, kColors>(context, mesh, points, triangles, begin, end);
}

template <bool kCenters, bool kSpecular, ColorSource kColors>
std::size_t shadeLit(const ShadeContext& context, const FrameMesh& mesh, std::size_t begin,
                     std::size_t end) {
  return withTypedMesh(mesh.mesh(), [&](auto points, auto polygons) {
    if constexpr (!kSpecular) {
      if (mesh.allTriangles && shadesInBatches(context.shader)) {
        return shadeTrianglesInBatches<kCenters, kColors>(context, mesh, points,
                                                          asTriangles(polygons), begin, end);
      }
    }
    return shadeLitTyped<kCenters, kSpecular, kColors>(context, mesh, points, polygons, begin, end);
  });
}

// The routines under direct light (or without Rule::AmbientOnly), by [centers][specular]
// and color source.
template <bool kCenters, bool kSpecular>
ShadeRoutineChoice litRoutine(ColorSource colors) {
  static constexpr const char* kNames[2][2][3] = {
      {{"lit by directions, diffuse, one color", "lit by directions, diffuse, per-polygon colors",
        "lit by directions, diffuse, colors tested per polygon"},
       {"lit by directions, specular, one color", "lit by directions, specular, per-polygon colors",
        "lit by directions, specular, colors tested per polygon"}},
      {{"lit at centers, diffuse, one color", "lit at centers, diffuse, per-polygon colors",
        "lit at centers, diffuse, colors tested per polygon"},
       {"lit at centers, specular, one color", "lit at centers, specular, per-polygon colors",
        "lit at centers, specular, colors tested per polygon"}}};
  const char* name = kNames[kCenters][kSpecular][static_cast<int>(colors)];
  switch (colors) {
    case ColorSource::Material:
      return {shadeLit<kCenters, kSpecular, ColorSource::Material>, name, false, true};
    case ColorSource::PerPolygon:
      return {shadeLit<kCenters, kSpecular, ColorSource::PerPolygon>, name};
    case ColorSource::Either:
      break;
  }
  return {shadeLit<kCenters, kSpecular, ColorSource::Either>, name};
}

#undef FACET_FLATTEN

}  // namespace shading

extern template ShadeRoutineChoice shading::litRoutine<false, false>(shading::ColorSource);
extern template ShadeRoutineChoice shading::litRoutine<false, true>(shading::ColorSource);
extern template ShadeRoutineChoice shading::litRoutine<true, false>(shading::ColorSource);
extern template ShadeRoutineChoice shading::litRoutine<true, true>(shading::ColorSource);

}  // namespace facet::detail
