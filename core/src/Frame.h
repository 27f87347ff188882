#pragma once

// What the render phases hand each other. The buffers live in the Renderer between renders,
// so that re-rendering the same scene at the same size reuses every one and allocates
// nothing. One meaning per buffer.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "AppendBuffer.h"
#include "FrameTransform.h"
#include "RasterTriangle.h"
#include "Triangulate.h"
#include "facet/HugePageAllocator.h"
#include "facet/Lighting.h"
#include "facet/Scene.h"

namespace facet::detail {

struct MeshFacts;  // MeshCache.h

// A range of one mesh's points or polygons: the unit of the validation, transform and
// shading tasks, which never straddle meshes.
struct MeshRange {
  std::size_t mesh, begin, end;
};

// Splits every mesh's [0, countOf(mesh)) into ranges of at most `perRange`.
template <class CountOf>
void splitPerMesh(std::size_t meshCount, std::size_t perRange, const CountOf& countOf,
                  std::vector<MeshRange>& ranges) {
  ranges.clear();
  for (std::size_t m = 0; m < meshCount; ++m) {
    const std::size_t n = countOf(m);
    for (std::size_t begin = 0; begin < n; begin += perRange) {
      ranges.push_back({m, begin, std::min(n, begin + perRange)});
    }
  }
}

// FrameMesh::backBlockVerdicts: the back pass's block reject (DeferredBackPoints.h).
inline constexpr std::uint8_t kBlockKept = 1, kBlockHidden = 2;

// Per-frame facts about one scene mesh.
struct FrameMesh {
  const SceneMesh* source = nullptr;
  PreparedMaterial material;
  std::size_t firstVertex = 0;   // into the frame's vertices
  std::size_t firstPolygon = 0;  // global polygon id of its polygon 0
  // Back faces cannot be seen this frame: a closed surface wholly in front of the near
  // plane (see MeshView::closedSurface), or culled by the material. Decided by the
  // transform phase.
  bool skipBackFaces = false;
  // Rule::GeometryOutsideView (ViewCulling.h): per block of polygons, whether it may be
  // seen, and per kPointsPerNeededFlag points (Transform.h), whether a block that is set up
  // uses them. Null: all.
  const std::uint8_t* visibleBlocks = nullptr;
  const std::uint8_t* neededPoints = nullptr;
  // Per back-face block (MeshCache.h, BackFacingBlocks.h): every triangle in it would be
  // culled, so none is set up. Null: none.
  const std::uint8_t* backBlocks = nullptr;
  // Per polygon, its unit normal kept per mesh version (MeshCache.h); null: computed by the
  // shade phase from the points (an unversioned mesh).
  const glm::vec3* faceNormals = nullptr;
  // What the mesh version's measurement knows, its back-face blocks' compact records among it
  // (MeshCache.h); null: an unversioned mesh. A two-pass frame's back pass may drop blocks
  // whole (HiddenBlocks.h).
  const MeshFacts* backBlockFacts = nullptr;
  // A two-pass frame's every-face mesh (DeferredBackPoints.h): per back-face block, whether
  // BackFaceTest proves it all back faces, so that the front pass defers it whole and its
  // points wait for the back pass's block reject (not in neededPoints); then per
  // kPointsPerNeededFlag points, those the kept blocks use that neededPoints did not hold
  // (transformed after the front pass); and per back-face block the reject's verdict
  // (kBlockKept, kBlockHidden; 0: not tested). Null: none.
  const std::uint8_t* deferredBackBlocks = nullptr;
  const std::uint8_t* latePoints = nullptr;
  const std::uint8_t* backBlockVerdicts = nullptr;
  // Every polygon is a triangle, offsets[p] = 3p (MeshFacts::allTriangles, measured meshes).
  bool allTriangles = false;

  const MeshView& mesh() const { return source->mesh; }
  std::size_t endPolygon() const { return firstPolygon + source->mesh.polygons.count; }
};

// Painter's order: the polygon id at each draw position. Empty in z-buffer mode, where
// polygons draw in id order.
struct DrawOrder {
  std::vector<std::uint32_t> ids;
  std::vector<std::pair<double, std::uint32_t>> keys;  // scratch: (view distance, id)
  std::size_t polygonAt(std::size_t position) const {
    return ids.empty() ? position : ids[position];
  }
};

// A triangle vertex reference: an index into the frame's vertices, or, with this bit set,
// into the chunk's own clippedVertices.
inline constexpr std::uint32_t kClippedVertexBit = 0x80000000u;

// A triangle ready to paint: counter-clockwise, covering at least one sample's box. Corners
// are references (16 bytes a triangle): storing the corners themselves (40 bytes) saved
// ~4% of a frame at 500k triangles for ~40% more peak memory.
struct BinnedTriangle {
  std::uint32_t vertex[3];
  std::int32_t polygon;
};

// A triangle whose box holds one sample, binned as the fragment it covers it with
// (keyOfOnlySample, RasterTriangle.h): the tile then reads 12 bytes in place of a triangle
// reference and its three scattered vertices, and sets nothing up. A bin entry with
// kFragmentBit set indexes its chunk's fragments, else its triangles, so a tile still sees
// both in draw order.
struct BinnedFragment {
  std::uint16_t x, y;  // below kMaxImageSide
  float key;
  std::int32_t polygon;
};
inline constexpr std::uint32_t kFragmentBit = 0x80000000u;

// A bin entry with kSmallTriangleBit set (and kFragmentBit clear) indexes its chunk's
// smallTriangles (SmallTriangle, RasterTriangle.h).
inline constexpr std::uint32_t kSmallTriangleBit = 0x40000000u;
inline constexpr std::uint32_t kBinIndexMask = kSmallTriangleBit - 1;

struct PolygonCounts {
  std::size_t drawn = 0, culled = 0, outside = 0, degenerate = 0, nonFinite = 0;
  std::size_t trianglesBinned = 0, trianglesClipped = 0;
  std::size_t boxSamples = 0;  // pixels in the binned triangles' boxes (depth complexity)
  // A two-pass frame's back-face blocks dropped whole behind the front faces (HiddenBlocks.h)
  // and their deferred polygons (counted there alone: RenderStats::polygonsHidden).
  std::size_t hiddenBlocks = 0, hiddenBlockPolygons = 0;
};

template <class T>
using HugePageAppendBuffer = AppendBuffer<T, HugePageAllocator<T>>;

// A tile's entries in one chunk (kFragmentBit, kSmallTriangleBit): appended by the set-up's
// inlined binning helpers (Binning.h) whatever the inliner's budget, read as a span.
using Bin = AppendBuffer<std::uint32_t>;

// A run of consecutive draw positions that one task sets up and bins. Its bins list, per
// tile, indices into `triangles`; tiles read the chunks in order, so every tile sees its
// triangles in draw order whatever the chunking (which depends on the thread count) was.
struct Chunk {
  std::size_t begin = 0, end = 0;
  // The binned records, appended as the bins are (AppendBuffer.h: inlined whatever the
  // inliner's budget, growth out of line), in huge pages when large.
  HugePageAppendBuffer<BinnedTriangle> triangles;
  HugePageAppendBuffer<EdgeMask> boundaryEdges;  // per triangle: which edges are its polygon's
  HugePageAppendBuffer<BinnedFragment> fragments;
  HugePageAppendBuffer<SmallTriangle> smallTriangles;
  // With the depth test and every face drawn, one key per record from firstKeyedSmall on (the
  // set-up's clampsBackFaces; a two-pass frame's front pass, which keeps no back face, makes
  // none): a back bin's record (a back face, one pass or two) is painted clamped to it
  // (nearestWrittenKey), a front bin's reads none. Kept apart so that records stay 40 bytes;
  // one a record, front faces' too in one pass, because a set-up that chose between two record
  // arrays spilled its registers (500k one pass: settle +20 % instructions). A chunk whose
  // meshes skip back faces pushes none: with the depth test (z-buffer order) a chunk holds one
  // mesh's polygons (planChunks splits per mesh), so a keyed chunk's records all have one.
  HugePageAppendBuffer<float> smallNearestKeys;
  std::size_t firstKeyedSmall = 0;
  std::vector<WindowVertex> clippedVertices;
  std::vector<Bin> bins;
  // With the depth test, the back-facing polygons' entries (every face drawn), per tile: a
  // tile paints them after every chunk's `bins`, so that most fail losesEverywhere behind the
  // front faces already painted, and an exact depth tie keeps the front face (writeFragment).
  std::vector<Bin> backBins;
  std::vector<Bin>& binsFor(bool last) { return last ? backBins : bins; }
  // A two-pass frame's back-facing polygons (global ids, in draw order) that the front pass
  // put off to the back pass (SetupPass, Setup.h): an id, or with kWholeBackBlockBit set the
  // first id of a back-face block's polygons deferred whole (Setup.cpp: wholeBlockEnd), one entry
  // in place of their ids. Strictly ascending in the ids (deferredIdOf).
  std::vector<std::uint32_t> deferredBack;
  PolygonCounts counts;
  // Scratch, reused polygon to polygon.
  std::vector<glm::dvec3> corners;
  std::vector<LocalTriangle> localTriangles;
  TriangulationScratch triangulation;
};

// A Chunk::deferredBack entry for the polygons of one back-face block the front pass deferred
// whole, unclassified (Setup.cpp's deferredWhole): global ids below 2^31 (validateCounts)
// leave the bit free. The back pass takes the block's verdict once and drops a hidden one
// with no per-id work (section 65 of bench/core-frame-issue11.md: its 64 ids were written,
// ~4.5 MB a frame at 2M triangles, and read back).
inline constexpr std::uint32_t kWholeBackBlockBit = 0x80000000u;
inline constexpr std::uint32_t deferredIdOf(std::uint32_t entry) {
  return entry & ~kWholeBackBlockBit;
}
inline const WindowVertex& vertexOf(const WindowVertex* vertices, const Chunk& chunk,
                                    std::uint32_t reference) {
  return (reference & kClippedVertexBit) ? chunk.clippedVertices[reference & ~kClippedVertexBit]
                                         : vertices[reference];
}

// What the frame knows per polygon id, one buffer per meaning. Kept after the render: the
// incremental paths re-shade and re-resolve from them.
struct PolygonBuffers {
  HugePageVector<std::uint8_t> backFacing;  // set-up: the viewer sees its back (drawn ones)
  HugePageVector<std::uint8_t> shown;       // raster: it won a pixel, so it needs a color
  HugePageVector<Rgba8> colors;             // shade: its flat-shaded color (shown ones)

  void resize(std::size_t polygons) {
    backFacing.resize(polygons);
    shown.resize(polygons);
    colors.resize(polygons);
  }
};

}  // namespace facet::detail
