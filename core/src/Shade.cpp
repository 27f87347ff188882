#include "Shade.h"

#include <array>

#include "FaceNormal.h"
#include "MeshAccess.h"
#include "ShaderAccess.h"

namespace facet::detail {
namespace {

// Polygons per shading task.
constexpr std::size_t kPolygonsPerTask = 1 << 16;

// Calls color(id, polygon) for every shown polygon among the mesh's [begin, end) and
// stores the result; returns how many.
template <class ColorOf>
std::size_t forEachShown(const ShadeContext& context, const FrameMesh& mesh, std::size_t begin,
                         std::size_t end, const ColorOf& colorOf) {
  std::size_t shaded = 0;
  for (std::size_t polygon = begin; polygon < end; ++polygon) {
    const std::size_t id = mesh.firstPolygon + polygon;
    if (!context.shown[id]) continue;
    ++shaded;
    context.colors[id] = colorOf(id, polygon);
  }
  return shaded;
}

// Where a polygon's surface color comes from: the material, the mesh's per-polygon
// colors, or either, tested per polygon (the routine when Rule::OneColor is off).
enum class ColorSource { Material, PerPolygon, Either };

Color polygonColor(const FrameMesh& mesh, std::size_t polygon) {
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

// The flat-shaded color of one polygon under direct light, at its center.
template <bool kCenters, bool kSpecular, ColorSource kColors, class PointsT, class PolygonsT>
Rgba8 litColor(const ShadeContext& context, const FrameMesh& mesh, ShaderAccess::Routine shade,
               PointsT points, PolygonsT polygons, std::size_t polygon, bool seenFromBack) {
  SurfaceSample sample;
  sample.color = surfaceColor<kColors>(mesh, polygon);
  const std::size_t n = polygons.size(polygon);
  const auto corner = [&](std::size_t k) { return points[polygons.pointId(polygon, k)]; };
  const glm::vec3 normal = mesh.faceNormals ? mesh.faceNormals[polygon] : faceNormalOf(n, corner);
  if constexpr (kCenters) {
    glm::dvec3 sum(0.0);
    for (std::size_t k = 0; k < n; ++k)
      sum += corner(k);
    sample.position = sum / static_cast<double>(n);
  }
  if constexpr (kSpecular) sample.toViewer = context.transform.toViewer(sample.position);
  // A polygon with area on screen but none in 3D (pathological input only) faces the viewer.
  sample.normal =
      normal != glm::vec3(0.0f) ? glm::dvec3(normal) : context.transform.toViewer(corner(0));
  if (seenFromBack && context.twoSidedLighting) sample.normal = -sample.normal;
  return toRgba8(shade(context.shader, sample, mesh.material));
}

// Flattened: with this file's many instantiations, GCC's unit-growth limit would otherwise
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
  const ShaderAccess::Routine shade = ShaderAccess::routine(context.shader, kSpecular);
  std::size_t shaded = 0;
  for (std::size_t polygon = begin; polygon < end; ++polygon) {
    const std::size_t id = mesh.firstPolygon + polygon;
    if (!context.shown[id]) continue;
    ++shaded;
    context.colors[id] = litColor<kCenters, kSpecular, kColors>(
        context, mesh, shade, points, polygons, polygon, context.backFacing[id]);
  }
  return shaded;
}

template <bool kCenters, bool kSpecular, ColorSource kColors>
std::size_t shadeLit(const ShadeContext& context, const FrameMesh& mesh, std::size_t begin,
                     std::size_t end) {
  return withTypedMesh(mesh.mesh(), [&](auto points, auto polygons) {
    return shadeLitTyped<kCenters, kSpecular, kColors>(context, mesh, points, polygons, begin, end);
  });
}

// Without direct light a polygon's color does not depend on its orientation, and a mesh
// without its own colors has one color for all its polygons: shaded once.
std::size_t shadeAmbientOneColor(const ShadeContext& context, const FrameMesh& mesh,
                                 std::size_t begin, std::size_t end) {
  SurfaceSample sample;
  sample.color = mesh.source->material.color;
  const Rgba8 color = toRgba8(context.shader.shade(sample, mesh.material));
  return forEachShown(context, mesh, begin, end, [&](std::size_t, std::size_t) { return color; });
}

// A small mesh: shaded polygon by polygon, still without normal or light loop.
std::size_t shadeAmbientPolygonColors(const ShadeContext& context, const FrameMesh& mesh,
                                      std::size_t begin, std::size_t end) {
  return forEachShown(context, mesh, begin, end, [&](std::size_t, std::size_t polygon) {
    SurfaceSample sample;
    sample.color = polygonColor(mesh, polygon);
    return toRgba8(context.shader.shade(sample, mesh.material));
  });
}

// One shade per color value. Without direct light each channel of the formula (Lighting.h)
// is a function of that channel of the surface color alone, so the shades of the 256 grays
// give every polygon's color, channel by channel: the same bytes as shading each polygon.
std::size_t shadeAmbientTable(const ShadeContext& context, const FrameMesh& mesh, std::size_t begin,
                              std::size_t end) {
  std::array<Rgba8, 256> table;
  for (int v = 0; v < 256; ++v) {
    SurfaceSample sample;
    sample.color = Color(static_cast<float>(v)) / 255.0f;
    table[v] = toRgba8(context.shader.shade(sample, mesh.material));
  }
  const std::span<const Rgba8> colors = mesh.mesh().polygonColors;
  return forEachShown(context, mesh, begin, end, [&](std::size_t, std::size_t polygon) {
    const Rgba8 c = colors[polygon];
    return Rgba8{table[c.r].r, table[c.g].g, table[c.b].b, table[c.r].a};
  });
}

// Below this many polygons a mesh's table would cost more shades than its polygons.
constexpr std::size_t kPolygonsForTable = 1024;

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

ShadeRoutineChoice ambientRoutine(const ShadeNeeds& needs) {
  if (!needs.polygonColors) return {shadeAmbientOneColor, "ambient, one color", true, true};
  if (needs.polygons < kPolygonsForTable) {
    return {shadeAmbientPolygonColors, "ambient, per-polygon colors", true};
  }
  return {shadeAmbientTable, "ambient, per-polygon colors by table", true};
}

}  // namespace

ShadeRoutineChoice chooseShadeRoutine(const ShadeNeeds& needs) {
  if (!needs.directLighting && needs.ambientOnlyRule) return ambientRoutine(needs);
  const ColorSource colors = needs.polygonColors  ? ColorSource::PerPolygon
                             : needs.oneColorRule ? ColorSource::Material
                                                  : ColorSource::Either;
  static constexpr ShadeRoutineChoice (*kTable[2][2])(ColorSource) = {
      {litRoutine<false, false>, litRoutine<false, true>},
      {litRoutine<true, false>, litRoutine<true, true>}};
  return kTable[needs.centers][needs.specular](colors);
}

bool shadePolygons(PhaseRunner& runner, std::span<const FrameMesh> meshes,
                   std::span<const ShadeRoutineChoice> routines, const ShadeContext& context,
                   ShadeBuffers& buffers) {
  splitPerMesh(
      meshes.size(), kPolygonsPerTask,
      [&](std::size_t m) { return meshes[m].mesh().polygons.count; }, buffers.ranges);
  buffers.counts.assign(buffers.ranges.size(), 0);
  return runner.run(Phase::Shade, buffers.ranges.size(), [&](std::size_t i) {
    const MeshRange& r = buffers.ranges[i];
    buffers.counts[i] = routines[r.mesh].shade(context, meshes[r.mesh], r.begin, r.end);
  });
}

}  // namespace facet::detail
