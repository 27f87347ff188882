#pragma once

/// @file MeshReference.h
/// The converged image of any scene of meshes (library facet_reference, which adds Embree to
/// the core; the core itself stays free of it). Every sample's ray finds its triangle with
/// Embree 3, and the hit is then recomputed in double precision: the point and the
/// barycentric coordinates (Möller–Trumbore on that triangle), the normal interpolated from
/// the corner normals (VertexNormals.h) — Phong shading — and lit by the renderer's own
/// formula (Shader::shade, Lighting.h) with the color the quality modes give the point
/// (pointColorAt, Mesh.h: point scalars mapped per sample, else point colors interpolated,
/// else the polygon's). See Reference.h for what a reference image is.
///
/// The triangles are the rasterizer's (triangulateMesh), stored for Embree in float relative
/// to the eye, so data far from the origin loses nothing a view of it shows; the double
/// refinement makes the shading independent of Embree's float arithmetic. Which triangle a
/// ray finds can differ from an exact test only within float rounding of an edge (a few
/// 1e-7 of the distance), far below a sample's footprint.

#include <memory>
#include <optional>
#include <span>

#include "facet/Reference.h"
#include "facet/Scene.h"
#include "facet/VertexNormals.h"

namespace facet {

/// What one ray sees of a scene of meshes: built once (Embree's BVH), then called from many
/// threads. Holds views of the scene's arrays: they must outlive it.
class MeshTracer {
 public:
  /// `normals` holds either nothing — every mesh gets computeVertexNormals(mesh,
  /// normalOptions) — or one VertexNormals per scene mesh (computed, or fromPointNormals).
  /// Geometry is stored relative to `eye` (the camera position). Throws facet::Error for an
  /// invalid scene (mesh, material, lights), normals that do not fit their mesh, or an
  /// Embree failure (its message).
  MeshTracer(const Scene& scene, const glm::dvec3& eye, bool twoSidedLighting,
             std::span<const VertexNormals> normals = {},
             const VertexNormalOptions& normalOptions = {});
  ~MeshTracer();
  MeshTracer(const MeshTracer&) = delete;
  MeshTracer& operator=(const MeshTracer&) = delete;

  /// The shaded color of the nearest surface in [tNear, tFar] (back faces skipped where the
  /// material culls them), or nothing.
  std::optional<Color> operator()(const Ray& ray) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The converged Phong-shaded image of a scene through the camera (renderReference with a
/// MeshTracer). Same bytes for any options.threads. Throws facet::Error as MeshTracer and
/// renderReference do.
ReferenceRender renderMeshReference(const Scene& scene, const Camera& camera, int width, int height,
                                    const ReferenceOptions& options = {},
                                    std::span<const VertexNormals> normals = {},
                                    const VertexNormalOptions& normalOptions = {});

}  // namespace facet
