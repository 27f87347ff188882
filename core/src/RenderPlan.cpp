#include "facet/RenderPlan.h"

#include <sstream>

namespace facet {
namespace {

const char* onOff(bool value) {
  return value ? "on" : "off";
}
const char* doneOrSkipped(bool value) {
  return value ? "computed" : "skipped";
}

}  // namespace

std::string RenderPlan::describe() const {
  std::ostringstream out;
  out << "Facet render plan: " << width << "x" << height << " pixels, " << threads
      << (threads == 1 ? " thread, " : " threads, ") << tilesX << "x" << tilesY << " tiles of "
      << tileSize << " px\n";
  out << "  scene: " << meshes << (meshes == 1 ? " mesh, " : " meshes, ") << polygons
      << " polygons, " << points << " points; " << (parallelProjection ? "parallel" : "perspective")
      << " projection\n";
  out << "  visibility: "
      << (visibility == Visibility::ZBuffer ? "z-buffer (depth test on, no sort)"
                                            : "painter's order (centroid sort, no depth test)")
      << "\n";
  out << "  lighting: flat, once per polygon that wins a pixel; "
      << (directLighting
              ? (positionalLights ? "direct lights incl. point/spot" : "directional lights only")
              : "ambient only")
      << "; specular " << (specular ? "on" : "off (skipped)") << "\n";
  out << "  per polygon: normals " << doneOrSkipped(directLighting) << ", centers "
      << doneOrSkipped(polygonCenters) << ", viewer direction " << doneOrSkipped(viewerDirection)
      << "\n";
  out << "  two-sided lighting " << onOff(twoSidedLighting) << ", back-face culling "
      << onOff(backfaceCulling) << ", back faces of closed surfaces "
      << (closedSurfaces ? "skipped unless the near plane cuts them" : "drawn (none marked closed)")
      << "\n";
  out << "  routines: raster " << rasterRoutine << "; set-up " << setupRoutine << "; shade "
      << shadeRoutine << "\n";
  return out.str();
}

}  // namespace facet
