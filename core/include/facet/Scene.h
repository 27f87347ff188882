#pragma once

/// @file Scene.h
/// What a render draws: meshes with their materials, and the lights.

#include <vector>

#include "facet/Light.h"
#include "facet/Material.h"
#include "facet/Mesh.h"

namespace facet {

/// One mesh and the material of all its polygons.
struct SceneMesh {
  MeshView mesh;
  Material material;
};

struct Scene {
  /// Polygon ids in the framebuffer count through these in order: the polygons of meshes[0]
  /// are 0 .. n0−1, those of meshes[1] follow, and so on.
  std::vector<SceneMesh> meshes;
  LightSet lights;  ///< (default: Sixth 3D's dim ambient, no direct lights)
};

/// How visibility between polygons is resolved.
enum class Visibility {
  /// A depth buffer: correct for every opaque scene, including intersecting polygons.
  ZBuffer,
  /// Painter's algorithm (Sixth 3D): polygons drawn far to near by the view depth of their
  /// centroid, ties by polygon id. Cannot be right for intersecting polygons or cyclic
  /// overlap (each polygon is drawn whole); kept for comparison and, later, translucency.
  PainterSort,
};

}  // namespace facet
