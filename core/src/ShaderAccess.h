#pragma once

// The renderer's way into Shader: the shading routine for a material, picked once per mesh
// rather than per polygon.

#include <vector>

#include "facet/Lighting.h"

namespace facet::detail {

struct ShaderAccess {
  using Routine = Color (*)(const Shader& shader, const SurfaceSample& sample,
                            const PreparedMaterial& material);
  static Routine routine(const Shader& shader, bool specular) { return shader.routine(specular); }

  // What the lanes of ShadeBatch.cpp read: the prepared lights, the scene's ambient radiance
  // and the loop the lights run.
  static const std::vector<PreparedLight>& lights(const Shader& shader) { return shader.lights_; }
  static const glm::dvec3& ambient(const Shader& shader) { return shader.ambient_; }
  static LightLoop loop(const Shader& shader) { return shader.loop_; }
};

}  // namespace facet::detail
