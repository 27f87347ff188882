#pragma once

// Meshes for the core tests and benchmarks (test-only: the core itself reads no files).

#include <filesystem>
#include <string>

#include <glm/vec3.hpp>

#include "facet/Camera.h"
#include "facet/Mesh.h"

namespace facet::testing {

// The shared data folder (FACET_SHARED_DATA_DIR, set by CMake).
std::filesystem::path sharedMeshPath(const std::string& fileName);

// A tiny Wavefront OBJ reader: `v x y z` and `f a b c ...` lines (a, b, c may be `i`,
// `i/t`, `i//n` or `i/t/n`, 1-based or negative). Throws std::runtime_error on a missing
// file or a malformed line.
Mesh readObj(const std::filesystem::path& path);

// The order a UV sphere lists its points and triangles in (the same surface either way).
enum class UvSphereOrder {
  // Points ring-major (north pole, south pole, then ring by ring from the north); triangles
  // ring by ring: the north cap, the bands between rings, the south cap.
  ringByRing,
  // Exactly vtkSphereSource's output (VTK 9, LatLongTessellation off): points theta-major
  // (the poles, then meridian by meridian from the north), triangles the north cap, the
  // south cap, then meridian by meridian pole to pole; the point values as it computes them.
  vtkSphereSource,
};

// A UV sphere with vtkSphereSource's topology: two poles, phiResolution − 2 rings of
// thetaResolution points, 2·theta·(phi − 2) counter-clockwise (outward) triangles.
Mesh makeUvSphere(int thetaResolution, int phiResolution, double radius = 1.0,
                  const glm::dvec3& center = glm::dvec3(0.0),
                  UvSphereOrder order = UvSphereOrder::ringByRing);

// makeUvSphere(theta, theta + 2) without the polygons whose first corner lies in the band
// |y − 0.2| < 0.15: the back faces show through the band, and most others hide behind the
// front faces (a two-pass frame's hidden blocks).
Mesh sphereWithBand(int theta);

// An axis-aligned box as 6 outward quads.
Mesh makeBox(const glm::dvec3& low, const glm::dvec3& high);

// The square [−extent, extent]² in the plane z = 0, cells × cells quads each split into two
// triangles.
Mesh makeFloorGrid(int cells, double extent);

// A low camera looking down at makeFloorGrid's floor from just above it: the near plane cuts
// through the visible floor, so the front triangles are clipped in homogeneous space.
Camera nearClippedFloorCamera();

// Deep occlusion: `layers` squares [−1, 1]² stacked along −z, 0.1 apart, each a grid of
// cells × cells quads, listed nearest first (front to back) or farthest first.
Mesh makeStackedSquares(int layers, int cells, bool frontToBack);

// A perspective camera looking at the mesh's bounding box from `direction` (toward the
// box), fitting the bounding sphere in the view like vtkRenderer::ResetCamera.
Camera fitCamera(const Mesh& mesh, const glm::dvec3& direction = {0.0, 0.0, -1.0},
                 double viewAngleDegrees = 30.0);

// A parallel camera looking down −Z for which world x, y equal window x, y in pixels
// (window = width × height), with the z = 0 plane between near and far.
Camera pixelCamera(int width, int height);

}  // namespace facet::testing
