#include "RendererInputs.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "MeshAccess.h"
#include "Validate.h"
#include "facet/Conventions.h"
#include "facet/Error.h"

namespace facet::detail {
namespace {

void validateMaterials(const Scene& scene) {
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    try {
      validate(scene.meshes[i].material);
    } catch (const Error& e) {
      throw Error("Scene.meshes[" + std::to_string(i) + "]." + e.what());
    }
  }
}

// Polygon ids and point indices are 32-bit in the framebuffer and the triangle records.
void validateCounts(const Scene& scene) {
  std::size_t polygons = 0, points = 0;
  for (const SceneMesh& mesh : scene.meshes) {
    polygons += mesh.mesh.polygons.count;
    points += mesh.mesh.points.count;
  }
  constexpr std::size_t kMaxIds = std::numeric_limits<std::int32_t>::max();
  if (polygons > kMaxIds || points > kMaxIds) {
    throw Error("Scene has " + std::to_string(polygons) + " polygons and " +
                std::to_string(points) + " points; at most 2^31 - 1 of each render at once");
  }
}

}  // namespace

void validateSceneInputs(const Scene& scene, const Camera& camera, int width, int height) {
  validate(camera);
  requireInRange(width, 1, kMaxImageSide, "image width");
  requireInRange(height, 1, kMaxImageSide, "image height");
  validateMaterials(scene);
  validate(scene.lights);
}

void validateRenderInputs(const Scene& scene, const Camera& camera, const FramebufferView& target,
                          bool depthOutput) {
  validateSceneInputs(scene, camera, target.width, target.height);
  if (!target.color || (!target.depth && depthOutput) || !target.polygonId) {
    throw Error("FramebufferView has a null plane");
  }
  validateMeshHeaders(scene);
}

void validateMeshHeaders(const Scene& scene) {
  validateCounts(scene);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    validateMeshHeader(scene.meshes[m].mesh, m);
}

void clearTarget(const FramebufferView& target, Rgba8 background) {
  const std::size_t pixels = static_cast<std::size_t>(target.width) * target.height;
  std::fill(target.color, target.color + pixels, background);
  if (target.depth)
    std::fill(target.depth, target.depth + pixels, 1.0f);  // none without depth output
  std::fill(target.polygonId, target.polygonId + pixels, Framebuffer::kBackgroundId);
}

}  // namespace facet::detail
