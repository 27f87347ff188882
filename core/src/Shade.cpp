#include "Shade.h"

#include <array>

#include "ShadeLit.h"

namespace facet::detail {
namespace {

// Polygons per shading task. Small enough to balance 2 threads on a closed mesh, whose shown
// polygons fill only the tasks of its front half: with 2^16 a 500k sphere's were four tasks of
// 0.60, 0.73, 0.65 and 0.26 ms, split 1.25 / 0.99 ms between the threads.
constexpr std::size_t kPolygonsPerTask = 1 << 14;

// Calls color(id, polygon) for every shown polygon among the mesh's [begin, end) and
// stores the result; returns how many.
template <class ColorOf>
std::size_t forEachShown(const ShadeContext& context, const FrameMesh& mesh, std::size_t begin,
                         std::size_t end, const ColorOf& colorOf) {
  std::size_t shaded = 0;
  forEachShownPolygon(context.shown + mesh.firstPolygon, begin, end, [&](std::size_t polygon) {
    const std::size_t id = mesh.firstPolygon + polygon;
    ++shaded;
    context.colors[id] = colorOf(id, polygon);
  });
  return shaded;
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
    sample.color = shading::polygonColor(mesh, polygon);
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
  using shading::ColorSource, shading::litRoutine;
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
