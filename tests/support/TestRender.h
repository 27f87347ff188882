#pragma once

// Rendering helpers shared by the core tests.

#include <cstdint>
#include <vector>

#include "facet/Framebuffer.h"
#include "facet/Renderer.h"

namespace facet::testing {

struct RenderOptions {
  int threads = 2;
  Visibility visibility = Visibility::ZBuffer;
  bool twoSidedLighting = true;
  RenderRules rules = {};
};

struct Rendered {
  Framebuffer framebuffer;
  RenderStats stats;
};

Rendered renderScene(const Scene& scene, const Camera& camera, int width, int height,
                     const RenderOptions& options = {});

// How many pixels differ in color, depth or polygon id (0: the same bytes).
std::size_t differingPixels(const Framebuffer& a, const Framebuffer& b);
// The largest difference of a color channel between two images of one size, in 8-bit steps.
int largestChannelDifference(const Framebuffer& a, const Framebuffer& b);

// A scene of one mesh, with the given material and lights (default: ambient only).
Scene oneMeshScene(const MeshView& mesh, const Material& material = {},
                   const LightSet& lights = {});

// Snaps a pixel coordinate to the rasterizer's 1/256 grid (as a double, in pixels).
double snapToSubpixel(double pixels);

// Fixed-point coordinates (1/256 pixel) of a point on the grid.
struct FixedPoint {
  std::int64_t x, y;
};
FixedPoint toFixed(double x, double y);

// Exact winding number of the pixel center (px + 0.5, py + 0.5) around a closed polyline of
// fixed-point vertices; `onBoundary` is set when the center lies exactly on it.
int windingNumber(const std::vector<FixedPoint>& polygon, int px, int py, bool& onBoundary);

}  // namespace facet::testing
