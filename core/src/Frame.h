#pragma once

// The state the render phases share. It lives in the Renderer between renders, so that
// re-rendering the same scene at the same size reuses every buffer and allocates nothing.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "FrameTransform.h"
#include "MeshAccess.h"
#include "Rasterizer.h"
#include "Triangulate.h"
#include "facet/HugePageAllocator.h"
#include "facet/Lighting.h"
#include "facet/RenderPlan.h"
#include "facet/Scene.h"

namespace facet::detail {

// Square screen tiles, each painted by one thread: 64 × 64 pixels keep a tile's color,
// depth and id planes (48 KiB) in L2 while giving hundreds of tiles to balance at 1080p.
inline constexpr int kTileSize = 64;

// A triangle vertex reference: an index into FrameState::vertices, or, with this bit set,
// into the chunk's own clippedVertices.
inline constexpr std::uint32_t kClippedVertexBit = 0x80000000u;

// A triangle ready to paint: counter-clockwise, covering at least one sample's box. Corners
// are references (16 bytes a triangle): storing the corners themselves (40 bytes) saved
// ~4% of a frame at 500k triangles for ~40% more peak memory.
struct BinnedTriangle {
  std::uint32_t vertex[3];
  std::int32_t polygon;
};

// Flat shading is deferred to the polygons that end up visible (Resolve.cpp): after set-up,
// a drawn polygon's slot in FrameState::polygonColors says which side the viewer sees;
// after shading, it holds the polygon's RGBA8 color.
inline constexpr std::uint32_t kUnshadedFront = 0;
inline constexpr std::uint32_t kUnshadedBack = 1;

struct PolygonCounts {
  std::size_t drawn = 0, culled = 0, outside = 0, degenerate = 0, nonFinite = 0;
  std::size_t trianglesBinned = 0, trianglesClipped = 0;
};

// A run of consecutive draw positions set up by one task. Its bins list, per tile, indices
// into `triangles`; tiles read the chunks in order, so every tile sees its triangles in draw
// order whatever the chunking (which depends on the thread count) was.
struct Chunk {
  std::size_t begin = 0, end = 0;
  HugePageVector<BinnedTriangle> triangles;
  HugePageVector<EdgeMask> boundaryEdges;  // per triangle: which edges are its polygon's
  std::vector<WindowVertex> clippedVertices;
  std::vector<std::vector<std::uint32_t>> bins;
  PolygonCounts counts;
  // Scratch, reused polygon to polygon.
  std::vector<glm::dvec3> corners;
  std::vector<LocalTriangle> localTriangles;
  TriangulationScratch triangulation;
};

// Per-frame facts about one scene mesh.
struct FrameMesh {
  const SceneMesh* source = nullptr;
  PreparedMaterial material;
  std::size_t firstVertex = 0;   // into FrameState::vertices
  std::size_t firstPolygon = 0;  // global polygon id of its polygon 0
  // Without direct light and per-polygon colors, every polygon of the mesh has one color.
  std::optional<Rgba8> uniformColor;
  // Back faces cannot be seen this frame: a closed surface wholly in front of the near
  // plane (see MeshView::closedSurface), or culled by the material.
  bool skipBackFaces = false;
};

struct FrameState {
  // Set at the start of each render.
  RenderPlan plan;
  std::optional<FrameTransform> transform;
  Shader shader;
  bool twoSidedLighting = true;
  PixelBounds viewport{0, 0, -1, -1};

  // Buffers reused from render to render.
  std::vector<FrameMesh> meshes;
  HugePageVector<WindowVertex> vertices;  // every mesh's points, projected
  std::vector<std::uint32_t> drawOrder;   // painter's order; empty means polygon id order
  std::vector<std::pair<double, std::uint32_t>> sortKeys;
  std::vector<Chunk> chunks;
  HugePageVector<std::uint32_t> polygonColors;  // per polygon id; see kUnshadedFront
  HugePageVector<std::uint8_t> shown;           // per polygon id: won a pixel (Planes::shown)

  std::size_t meshOfPolygon(std::size_t polygonId) const;
  const WindowVertex& vertex(const Chunk& chunk, std::uint32_t reference) const {
    return (reference & kClippedVertexBit) ? chunk.clippedVertices[reference & ~kClippedVertexBit]
                                           : vertices[reference];
  }
  std::size_t polygonAt(std::size_t drawPosition) const {
    return drawOrder.empty() ? drawPosition : drawOrder[drawPosition];
  }
};

// Phase 2 for one chunk: clip, cull, triangulate and bin its polygons.
void setUpChunk(FrameState& frame, Chunk& chunk);

// Phase 4, colors (Resolve.cpp): shade the shown polygons of one mesh's id range
// [begin, end), returning how many; then write a tile's colors from its ids and turn its
// depth keys into window depths.
std::size_t shadeVisiblePolygons(FrameState& frame, std::size_t meshIndex, std::size_t begin,
                                 std::size_t end);
void resolveTile(const FrameState& frame, const PixelBounds& tile, const Planes& planes,
                 Rgba8 background);

}  // namespace facet::detail
