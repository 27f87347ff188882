#include "TestRender.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace facet::testing {

Rendered renderScene(const Scene& scene, const Camera& camera, int width, int height,
                     const RenderOptions& options) {
  Renderer renderer;
  renderer.setThreadCount(options.threads);
  renderer.setVisibility(options.visibility);
  renderer.setTwoSidedLighting(options.twoSidedLighting);
  renderer.setRules(options.rules);
  Rendered result{Framebuffer(width, height), {}};
  result.stats = renderer.render(scene, camera, result.framebuffer);
  return result;
}

std::size_t differingPixels(const Framebuffer& a, const Framebuffer& b) {
  if (a.pixelCount() != b.pixelCount()) return std::max(a.pixelCount(), b.pixelCount());
  std::size_t count = 0;
  for (std::size_t i = 0; i < a.pixelCount(); ++i) {
    count += !(a.color()[i] == b.color()[i]) || a.polygonId()[i] != b.polygonId()[i] ||
             std::memcmp(&a.depth()[i], &b.depth()[i], sizeof(float)) != 0;
  }
  return count;
}

int largestChannelDifference(const Framebuffer& a, const Framebuffer& b) {
  int largest = 0;
  for (std::size_t i = 0; i < a.pixelCount(); ++i) {
    const Rgba8 p = a.color()[i], q = b.color()[i];
    largest = std::max({largest, std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b),
                        std::abs(p.a - q.a)});
  }
  return largest;
}

Scene oneMeshScene(const MeshView& mesh, const Material& material, const LightSet& lights) {
  Scene scene;
  scene.meshes.push_back({mesh, material});
  scene.lights = lights;
  return scene;
}

double snapToSubpixel(double pixels) {
  return std::nearbyint(pixels * 256.0) / 256.0;
}

FixedPoint toFixed(double x, double y) {
  return {static_cast<std::int64_t>(std::nearbyint(x * 256.0)),
          static_cast<std::int64_t>(std::nearbyint(y * 256.0))};
}

int windingNumber(const std::vector<FixedPoint>& polygon, int px, int py, bool& onBoundary) {
  const std::int64_t sx = std::int64_t{px} * 256 + 128, sy = std::int64_t{py} * 256 + 128;
  int winding = 0;
  onBoundary = false;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const FixedPoint a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const std::int64_t side = (b.x - a.x) * (sy - a.y) - (b.y - a.y) * (sx - a.x);
    if (side == 0 && sx >= std::min(a.x, b.x) && sx <= std::max(a.x, b.x) &&
        sy >= std::min(a.y, b.y) && sy <= std::max(a.y, b.y)) {
      onBoundary = true;
    }
    if (a.y <= sy) {
      if (b.y > sy && side > 0) ++winding;
    } else if (b.y <= sy && side < 0) {
      --winding;
    }
  }
  return winding;
}

}  // namespace facet::testing
