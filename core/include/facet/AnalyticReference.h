#pragma once

/// @file AnalyticReference.h
/// The exact image of spheres and planes: every sample's ray is intersected with the true
/// surface in double precision, and the true point and normal are lit by the renderer's own
/// formula (Shader::shade, Lighting.h). A tessellated sphere or plane rendered by the
/// rasterizer is compared against it (ImageMetrics.h) to measure the error of tessellation
/// and of the shading mode. See Reference.h for what a reference image is.

#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "facet/Lighting.h"
#include "facet/Material.h"
#include "facet/Reference.h"

namespace facet {

struct AnalyticSphere {
  glm::dvec3 center{0.0};
  double radius = 1.0;  ///< > 0 (default: 1)
  Material material;    ///< its color is the surface color
};

/// A flat parallelogram: the points origin + s·edgeU + t·edgeV for s, t in [0, 1] (a plane
/// bounded so that a quad with the same corners is its exact tessellation). Its front faces
/// normalize(edgeU × edgeV), as a counter-clockwise quad's does.
struct AnalyticPlane {
  glm::dvec3 origin{0.0};
  glm::dvec3 edgeU{1.0, 0.0, 0.0};  ///< not parallel to edgeV (default: +X)
  glm::dvec3 edgeV{0.0, 1.0, 0.0};  ///< (default: +Y)
  Material material;
};

struct AnalyticScene {
  std::vector<AnalyticSphere> spheres;
  std::vector<AnalyticPlane> planes;
  LightSet lights;  ///< as Scene::lights (default: Sixth 3D's dim ambient, no direct lights)
};

/// What one ray sees of the scene: the nearest surface point in [tNear, tFar] (back faces
/// skipped where the material culls them), shaded, or nothing. Throws facet::Error for an
/// invalid scene (checked once, then shared by every sample).
class AnalyticTracer {
 public:
  AnalyticTracer(const AnalyticScene& scene, bool twoSidedLighting);
  std::optional<Color> operator()(const Ray& ray) const;

 private:
  struct Hit;
  std::optional<Hit> nearestHit(const Ray& ray) const;

  AnalyticScene scene_;
  std::vector<PreparedMaterial> sphereMaterials_, planeMaterials_;
  Shader shader_;
  bool twoSidedLighting_;
};

/// The converged image of an analytic scene through the camera (Reference.h's
/// renderReference with an AnalyticTracer). Throws facet::Error for an invalid scene
/// (radius ≤ 0, parallel plane edges, non-finite numbers, bad materials or lights), camera,
/// options or size.
ReferenceRender renderAnalyticReference(const AnalyticScene& scene, const Camera& camera, int width,
                                        int height, const ReferenceOptions& options = {});

}  // namespace facet
