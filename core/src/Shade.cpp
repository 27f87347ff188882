#include "Shade.h"

#include "MeshAccess.h"
#include "ShaderAccess.h"
#include "facet/PolygonNormal.h"

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

template <bool kPolygonColors>
Color surfaceColor(const FrameMesh& mesh, std::size_t polygon) {
  if constexpr (kPolygonColors) {
    const Rgba8 c = mesh.mesh().polygonColors[polygon];
    return Color(c.r, c.g, c.b) / 255.0f;
  } else {
    return mesh.source->material.color;
  }
}

// The flat-shaded color of one polygon under direct light, at its center.
template <bool kCenters, bool kSpecular, bool kPolygonColors, class PointsT, class PolygonsT>
Rgba8 litColor(const ShadeContext& context, const FrameMesh& mesh, ShaderAccess::Routine shade,
               PointsT points, PolygonsT polygons, std::size_t polygon, bool seenFromBack) {
  SurfaceSample sample;
  sample.color = surfaceColor<kPolygonColors>(mesh, polygon);
  const std::size_t n = polygons.size(polygon);
  const auto corner = [&](std::size_t k) { return points[polygons.pointId(polygon, k)]; };
  const std::optional<glm::dvec3> normal =
      n == 3 ? triangleNormal(corner(0), corner(1), corner(2)) : polygonNormal(n, corner);
  if constexpr (kCenters) {
    glm::dvec3 sum(0.0);
    for (std::size_t k = 0; k < n; ++k)
      sum += corner(k);
    sample.position = sum / static_cast<double>(n);
  }
  if constexpr (kSpecular) sample.toViewer = context.transform.toViewer(sample.position);
  // A polygon with area on screen but none in 3D (pathological input only) faces the viewer.
  sample.normal = normal ? *normal : context.transform.toViewer(corner(0));
  if (seenFromBack && context.twoSidedLighting) sample.normal = -sample.normal;
  return toRgba8(shade(context.shader, sample, mesh.material));
}

// Flattened: with this file's many instantiations, GCC's unit-growth limit would otherwise
// leave the per-polygon helpers (normal, corners, toRgba8) as calls, ~25 % of the phase.
template <bool kCenters, bool kSpecular, bool kPolygonColors, class PointsT, class PolygonsT>
[[gnu::flatten]] std::size_t shadeLitTyped(const ShadeContext& context, const FrameMesh& mesh,
                                           PointsT points, PolygonsT polygons, std::size_t begin,
                                           std::size_t end) {
  const ShaderAccess::Routine shade = ShaderAccess::routine(context.shader, kSpecular);
  std::size_t shaded = 0;
  for (std::size_t polygon = begin; polygon < end; ++polygon) {
    const std::size_t id = mesh.firstPolygon + polygon;
    if (!context.shown[id]) continue;
    ++shaded;
    context.colors[id] = litColor<kCenters, kSpecular, kPolygonColors>(
        context, mesh, shade, points, polygons, polygon, context.backFacing[id]);
  }
  return shaded;
}

template <bool kCenters, bool kSpecular, bool kPolygonColors>
std::size_t shadeLit(const ShadeContext& context, const FrameMesh& mesh, std::size_t begin,
                     std::size_t end) {
  return withTypedMesh(mesh.mesh(), [&](auto points, auto polygons) {
    return shadeLitTyped<kCenters, kSpecular, kPolygonColors>(context, mesh, points, polygons,
                                                              begin, end);
  });
}

// Without direct light a polygon's color does not depend on its orientation, and a mesh
// without its own colors has one color for all its polygons: shaded once.
std::size_t shadeAmbientOneColor(const ShadeContext& context, const FrameMesh& mesh,
                                 std::size_t begin, std::size_t end) {
  const Rgba8 color = toRgba8(context.shader.shade(SurfaceSample{}, mesh.material));
  return forEachShown(context, mesh, begin, end, [&](std::size_t, std::size_t) { return color; });
}

std::size_t shadeAmbientPolygonColors(const ShadeContext& context, const FrameMesh& mesh,
                                      std::size_t begin, std::size_t end) {
  return forEachShown(context, mesh, begin, end, [&](std::size_t, std::size_t polygon) {
    SurfaceSample sample;
    sample.color = surfaceColor<true>(mesh, polygon);
    return toRgba8(context.shader.shade(sample, mesh.material));
  });
}

// The routines under direct light, by [centers][specular][polygon colors].
constexpr ShadeRoutineChoice kLitRoutines[2][2][2] = {
    {{{shadeLit<false, false, false>, "lit by directions, diffuse, one color"},
      {shadeLit<false, false, true>, "lit by directions, diffuse, per-polygon colors"}},
     {{shadeLit<false, true, false>, "lit by directions, specular, one color"},
      {shadeLit<false, true, true>, "lit by directions, specular, per-polygon colors"}}},
    {{{shadeLit<true, false, false>, "lit at centers, diffuse, one color"},
      {shadeLit<true, false, true>, "lit at centers, diffuse, per-polygon colors"}},
     {{shadeLit<true, true, false>, "lit at centers, specular, one color"},
      {shadeLit<true, true, true>, "lit at centers, specular, per-polygon colors"}}}};

}  // namespace

ShadeRoutineChoice chooseShadeRoutine(const ShadeNeeds& needs) {
  if (!needs.directLighting) {
    return needs.polygonColors
               ? ShadeRoutineChoice{shadeAmbientPolygonColors, "ambient, per-polygon colors"}
               : ShadeRoutineChoice{shadeAmbientOneColor, "ambient, one color"};
  }
  return kLitRoutines[needs.centers][needs.specular][needs.polygonColors];
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
