// Phase 4: colors and depth. Flat shading is a function of the polygon alone, so only polygons that
// won a pixel while painting (Planes::shown) are lit — in id order, as sequential reads of
// the mesh arrays (screen order would scatter them) — and tiles then look their pixels'
// colors up. Polygons hidden all along — behind others, or the back faces of a closed
// surface — are never lit; one overdrawn later is lit once for nothing. Each pixel's depth
// key becomes its window depth in the same pass.

#include <bit>

#include "Frame.h"
#include "facet/PolygonNormal.h"

namespace facet::detail {
namespace {

Color surfaceColor(const FrameMesh& mesh, std::size_t polygon) {
  const auto& colors = mesh.source->mesh.polygonColors;
  if (colors.empty()) return mesh.source->material.color;
  const Rgba8 c = colors[polygon];
  return Color(c.r, c.g, c.b) / 255.0f;
}

// The flat-shaded color of one polygon, at its center.
template <class PointsT, class PolygonsT>
Rgba8 shadePolygon(const FrameState& frame, const FrameMesh& mesh, PointsT points,
                   PolygonsT polygons, std::size_t polygon, bool seenFromBack) {
  SurfaceSample sample;
  sample.color = surfaceColor(mesh, polygon);
  if (frame.plan.directLighting) {
    const std::size_t n = polygons.size(polygon);
    const auto corner = [&](std::size_t k) { return points[polygons.pointId(polygon, k)]; };
    const std::optional<glm::dvec3> normal =
        n == 3 ? triangleNormal(corner(0), corner(1), corner(2)) : polygonNormal(n, corner);
    if (frame.plan.polygonCenters) {
      glm::dvec3 sum(0.0);
      for (std::size_t k = 0; k < n; ++k)
        sum += corner(k);
      sample.position = sum / static_cast<double>(n);
    }
    if (frame.plan.viewerDirection) sample.toViewer = frame.transform->toViewer(sample.position);
    // A polygon with area on screen but none in 3D (pathological input only) faces the viewer.
    sample.normal = normal ? *normal : frame.transform->toViewer(corner(0));
    if (seenFromBack && frame.twoSidedLighting) sample.normal = -sample.normal;
  }
  return toRgba8(frame.shader.shade(sample, mesh.material));
}

}  // namespace

std::size_t shadeVisiblePolygons(FrameState& frame, std::size_t meshIndex, std::size_t begin,
                                 std::size_t end) {
  const FrameMesh& mesh = frame.meshes[meshIndex];
  std::size_t shaded = 0;
  withTypedMesh(mesh.source->mesh, [&](auto points, auto polygons) {
    for (std::size_t polygon = begin; polygon < end; ++polygon) {
      const std::size_t id = mesh.firstPolygon + polygon;
      if (!frame.shown[id]) continue;
      ++shaded;
      const Rgba8 color = mesh.uniformColor
                              ? *mesh.uniformColor
                              : shadePolygon(frame, mesh, points, polygons, polygon,
                                             frame.polygonColors[id] == kUnshadedBack);
      frame.polygonColors[id] = std::bit_cast<std::uint32_t>(color);
    }
  });
  return shaded;
}

void resolveTile(const FrameState& frame, const PixelBounds& tile, const Planes& planes,
                 Rgba8 background) {
  // Locals: the color stores (bytes) may alias anything, which would reload these per pixel.
  const std::uint32_t* colors = frame.polygonColors.data();
  const FrameTransform transform = *frame.transform;
  for (int y = tile.y0; y <= tile.y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * planes.width;
    const std::int32_t* ids = planes.polygonId + row;
    Rgba8* color = planes.color + row;
    float* depth = planes.depth + row;
    for (int x = tile.x0; x <= tile.x1; ++x) {
      const std::int32_t id = ids[x];
      color[x] = id < 0 ? background : std::bit_cast<Rgba8>(colors[static_cast<std::size_t>(id)]);
    }
    for (int x = tile.x0; x <= tile.x1; ++x)
      depth[x] = ids[x] < 0 ? 1.0f : transform.windowDepth(depth[x]);
  }
}

}  // namespace facet::detail
