#include "facet/AnalyticReference.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "Validate.h"

namespace facet {

struct AnalyticTracer::Hit {
  double t = 0.0;
  glm::dvec3 normal{0.0};  // unit, the side the surface's front faces
  const PreparedMaterial* material = nullptr;
};

namespace {

void validate(const AnalyticSphere& sphere, std::size_t i) {
  const auto name = [&](const char* field) {
    return "AnalyticScene.spheres[" + std::to_string(i) + "]." + field;
  };
  detail::requireFinite(sphere.center, [&] { return name("center"); });
  detail::requirePositive(sphere.radius, [&] { return name("radius"); });
  facet::validate(sphere.material);
}

void validate(const AnalyticPlane& plane, std::size_t i) {
  const auto name = [&](const char* field) {
    return "AnalyticScene.planes[" + std::to_string(i) + "]." + field;
  };
  detail::requireFinite(plane.origin, [&] { return name("origin"); });
  detail::requireNonZeroDirection(plane.edgeU, [&] { return name("edgeU"); });
  detail::requireNonZeroDirection(plane.edgeV, [&] { return name("edgeV"); });
  const glm::dvec3 unitU = glm::normalize(plane.edgeU), unitV = glm::normalize(plane.edgeV);
  if (!(glm::length(glm::cross(unitU, unitV)) > 1e-12)) {
    detail::fail(name("edgeV"), "is " + detail::formatVector(plane.edgeV) +
                                    ", parallel to edgeU: the plane has no area");
  }
  facet::validate(plane.material);
}

// The roots of |offset + t·direction| = radius (offset = origin − center, direction unit),
// ascending, by Haines et al., "Precision Improvements for Ray/Sphere Intersection" (Ray
// Tracing Gems, ch. 7): the discriminant from the closest approach, not b² − c, and the
// smaller root from c/q, so neither cancels for spheres small or far from the ray origin.
std::optional<std::pair<double, double>> sphereRoots(const glm::dvec3& offset,
                                                     const glm::dvec3& direction, double radius) {
  const double b = -glm::dot(offset, direction);
  const glm::dvec3 closest = offset + b * direction;
  const double discriminant = radius * radius - glm::dot(closest, closest);
  if (discriminant < 0.0) return std::nullopt;
  const double q = b + std::copysign(std::sqrt(discriminant), b);
  const double c = glm::dot(offset, offset) - radius * radius;
  const double t0 = q == 0.0 ? 0.0 : c / q, t1 = q;
  return t0 < t1 ? std::pair(t0, t1) : std::pair(t1, t0);
}

bool acceptable(const Ray& ray, double t, const glm::dvec3& normal, const Material& material) {
  if (!(t >= ray.tNear && t <= ray.tFar)) return false;
  return !(material.backfaceCulling && glm::dot(normal, ray.direction) > 0.0);
}

}  // namespace

AnalyticTracer::AnalyticTracer(const AnalyticScene& scene, bool twoSidedLighting)
    : scene_(scene), shader_(scene.lights), twoSidedLighting_(twoSidedLighting) {
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    validate(scene.spheres[i], i);
    sphereMaterials_.emplace_back(scene.spheres[i].material);
  }
  for (std::size_t i = 0; i < scene.planes.size(); ++i) {
    validate(scene.planes[i], i);
    planeMaterials_.emplace_back(scene.planes[i].material);
  }
}

auto AnalyticTracer::nearestHit(const Ray& ray) const -> std::optional<Hit> {
  std::optional<Hit> nearest;
  const auto consider = [&](double t, const glm::dvec3& normal, const PreparedMaterial& m) {
    if (acceptable(ray, t, normal, m.material) && (!nearest || t < nearest->t)) {
      nearest = Hit{t, normal, &m};
    }
  };
  for (std::size_t i = 0; i < scene_.spheres.size(); ++i) {
    const AnalyticSphere& sphere = scene_.spheres[i];
    const glm::dvec3 offset = ray.origin - sphere.center;
    const auto roots = sphereRoots(offset, ray.direction, sphere.radius);
    if (!roots) continue;
    for (const double t : {roots->first, roots->second}) {
      // Relative to the center, so the normal keeps its digits far from the origin.
      consider(t, glm::normalize(offset + t * ray.direction), sphereMaterials_[i]);
    }
  }
  for (std::size_t i = 0; i < scene_.planes.size(); ++i) {
    const AnalyticPlane& plane = scene_.planes[i];
    const glm::dvec3 n = glm::cross(plane.edgeU, plane.edgeV);
    const double facing = glm::dot(n, ray.direction);
    if (facing == 0.0) continue;  // the ray runs along the plane: it sees no area
    const glm::dvec3 offset = ray.origin - plane.origin;
    const double t = -glm::dot(n, offset) / facing;
    // Coordinates in the (edgeU, edgeV) basis, by the dual basis (cross products with n).
    const glm::dvec3 w = offset + t * ray.direction;
    const double nn = glm::dot(n, n);
    const double s = glm::dot(glm::cross(w, plane.edgeV), n) / nn;
    const double r = glm::dot(glm::cross(plane.edgeU, w), n) / nn;
    if (s >= 0.0 && s <= 1.0 && r >= 0.0 && r <= 1.0) {
      consider(t, n / std::sqrt(nn), planeMaterials_[i]);
    }
  }
  return nearest;
}

std::optional<Color> AnalyticTracer::operator()(const Ray& ray) const {
  const std::optional<Hit> hit = nearestHit(ray);
  if (!hit) return std::nullopt;
  SurfaceSample sample;
  sample.position = ray.origin + hit->t * ray.direction;
  sample.toViewer = CameraRays::toViewer(ray);
  const bool seenFromBack = glm::dot(hit->normal, ray.direction) > 0.0;
  sample.normal = seenFromBack && twoSidedLighting_ ? -hit->normal : hit->normal;
  sample.color = hit->material->material.color;
  return shader_.shade(sample, *hit->material);
}

ReferenceRender renderAnalyticReference(const AnalyticScene& scene, const Camera& camera, int width,
                                        int height, const ReferenceOptions& options) {
  const AnalyticTracer tracer(scene, options.twoSidedLighting);
  return renderReference(camera, width, height, options,
                         [&](const Ray& ray) { return tracer(ray); });
}

}  // namespace facet
