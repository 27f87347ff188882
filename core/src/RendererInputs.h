#pragma once

// What the Renderer checks before a render touches a pixel, and the image a stopped render
// leaves.

#include "facet/Camera.h"
#include "facet/Color.h"
#include "facet/Framebuffer.h"
#include "facet/Scene.h"

namespace facet::detail {

// Throws facet::Error naming the first invalid value: camera, image size, a material, a
// light, a mesh's array sizes, or more than 2^31 − 1 polygons or points.
void validateSceneInputs(const Scene& scene, const Camera& camera, int width, int height);

// The same, and a null plane (the depth plane may be null without depth output).
void validateRenderInputs(const Scene& scene, const Camera& camera, const FramebufferView& target,
                          bool depthOutput);
// The meshes' counts and arrays (non-null where counts say there is data), not their contents.
void validateMeshHeaders(const Scene& scene);

// The background everywhere: a valid image rather than a half-painted one.
void clearTarget(const FramebufferView& target, Rgba8 background);

}  // namespace facet::detail
