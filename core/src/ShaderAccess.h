#pragma once

// The renderer's way into Shader: the shading routine for a material, picked once per mesh
// rather than per polygon.

#include "facet/Lighting.h"

namespace facet::detail {

struct ShaderAccess {
  using Routine = Color (*)(const Shader& shader, const SurfaceSample& sample,
                            const PreparedMaterial& material);
  static Routine routine(const Shader& shader, bool specular) { return shader.routine(specular); }
};

}  // namespace facet::detail
