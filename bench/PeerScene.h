#pragma once

// The scene every peer program of `make bench-peers` draws, and the way it reports, so that
// OSMesa, Embree and Facet see the same frames: the vtkSphereSource-topology sphere of the
// requested triangle count, the camera vtkRenderer::ResetCamera would pick (looking down −Z),
// one positional light at the camera, no ambient, a white Lambert surface, 1920 × 1080, one
// sample per pixel, two-sided lighting (VTK's default).
//
// A peer program takes `--triangles N [--frames F] [--threads T] [--image FILE.ppm]` and
// prints one JSON object on stdout (bench/peers.py reads it).

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "facet/Camera.h"

namespace facet::bench {

constexpr int kPeerWidth = 1920, kPeerHeight = 1080;

struct PeerOptions {
  std::int64_t triangles = 500000;
  int frames = 10;
  int threads = 2;
  std::string image;  // where to save the last frame's colors (binary PPM), if anywhere
};

// Parses the command line; prints the usage and exits on a bad argument.
PeerOptions parsePeerOptions(int argc, char** argv);

// The mesh as GPUs and ray tracers take it: float xyz and 32-bit triangle indices.
struct PeerScene {
  std::vector<float> xyz;
  std::vector<std::uint32_t> indices;  // 3 per triangle, counter-clockwise seen from outside
  Camera camera;
  glm::dvec3 light;  // positional light, at the camera

  std::size_t triangleCount() const { return indices.size() / 3; }
  std::size_t pointCount() const { return xyz.size() / 3; }
  // clipFromView · viewFromWorld for the peer image's aspect (OpenGL's NDC).
  glm::mat4 clipFromWorld() const;
};

// The sphere with 2·theta·(phi − 2) triangles, theta = phi − 2 (the benches' spheres: 20k,
// 500k, 2M, 8M triangles). Throws facet::Error when no such sphere has `triangles`.
PeerScene makePeerScene(std::int64_t triangles);

// Pixels whose depth is below the background's 1 (a check that the peers drew the same).
std::size_t coveredPixels(const std::vector<float>& depth);

// Writes kPeerWidth × kPeerHeight RGBA8 pixels, row 0 at the bottom, as a binary PPM (top row
// first). Throws facet::Error when the file cannot be written.
void writePpm(const std::string& path, const std::uint8_t* rgba);

// Runs `frame` once to warm up, then `frames` times; returns the median seconds per frame.
double medianFrameSeconds(int frames, const std::function<void()>& frame);

// One JSON object on stdout: the options, the scene's size, then `fields` (values are
// written verbatim, so strings must carry their quotes: use jsonString).
void printPeerResult(const std::string& peer, const PeerOptions& options, const PeerScene& scene,
                     const std::vector<std::pair<std::string, std::string>>& fields);
std::string jsonString(const std::string& text);

}  // namespace facet::bench
