#pragma once

// Set-up in batches: kBatchSize triangles at once, in SIMD lanes (Google Highway, the
// instruction set chosen at run time). Most triangles of a dense mesh are dropped
// (back-facing, zero area, or covering no pixel center); the others cover a few pixel centers
// each, and a batch sets them up to the point where binning is an append: counter-clockwise
// winding, the box of pixel centers, and for a triangle whose box holds one center (most of a
// dense mesh's) the depth key of its fragment there. Triangles a batch does not take (polygons,
// triangles to clip, ones too large for its 32-bit arithmetic) go through the per-triangle
// path (Setup.cpp). A batch decides on the same exact integer facts as that path and computes
// keys with the same double operations in the same order (no fused multiply-add: the
// -ffp-contract=off list in core/CMakeLists.txt), so the image is the same bytes with
// batches or without, on any instruction set.

#include <cstdint>
#include <vector>

#include "FrameTransform.h"
#include "RasterTriangle.h"
#include "TileGrid.h"

namespace facet::detail {

// 16: the int32 lanes of one AVX-512 vector, two of AVX2, four of SSE4, sixteen rounds of
// the portable target's one lane.
inline constexpr int kBatchSize = 16;
static_assert(kBatchSize <= 32, "verdicts hold a bit per lane");

// Triangles in lanes: lane l's vertex j in v[j][l] (16 bytes each, loaded into lanes as four
// 32-bit words). A lane is tested when `triangle` is 1 and every vertex is inside (outcode
// kInside); others (polygons, unused lanes, and so triangles to clip) are left to the
// per-triangle path.
struct TriangleBatch {
  alignas(64) WindowVertex v[3][kBatchSize];
  alignas(64) std::int32_t triangle[kBatchSize];
};

// What a batch decided: per kind, one bit per lane (bit l for lane l). Each drop is counted
// as the per-triangle path would count it. A tested lane is either dropped or kept (binned
// as a fragment or as a triangle); every other lane goes on to the per-triangle path. The
// counts are the bits set in each (counted with the instruction set's POPCNT, which the
// baseline build has not: std::popcount there is a call into libgcc).
struct BatchVerdicts {
  std::uint32_t culled = 0;          // back-facing, and the mesh skips back faces
  std::uint32_t zeroArea = 0;        // degenerate
  std::uint32_t coversNoSample = 0;  // no pixel center inside (or in the viewport): outside
  // Kept, binned as its fragment at (samples.x0[l], samples.y0[l]) with depth key key[l]
  // (keyOfOnlySample, RasterTriangle.h): its box holds that one pixel center, which it covers.
  std::uint32_t fragment = 0;
  // Kept, binned as a triangle over the pixel centers of its box (samplesInBoundingBox): it
  // covers one of them (decided exactly for boxes of at most 4 centers; assumed for larger
  // ones, as coversAnySample).
  std::uint32_t triangle = 0;
  // Clockwise (snapped window area < 0): seen from the back; binned with corners 1 and 2
  // swapped.
  std::uint32_t clockwise = 0;
  // Kept lanes whose box overlaps one tile, tile[l].
  std::uint32_t oneTile = 0;
  // Triangle lanes set up whole, as SmallTriangle (RasterTriangle.h) records: in one tile,
  // 2 to kSmallSide² − 1 centers in a box at most kSmallSide on each side, and with
  // polygon-boundary edges every covered center surely inside them (smallTriangleOf).
  std::uint32_t small = 0;
  // Triangle lanes that would be small but for some covered centers not surely inside a
  // polygon-boundary edge (smallPlane.unsure): binned as a record of their other centers and
  // fragments of these (keysNearBoundary, RasterTriangle.h: those of them at which
  // paintTriangle's key is not the stepped one; the others stay in the record).
  std::uint32_t nearEdge = 0;
  int culledCount = 0, zeroAreaCount = 0, coversNoSampleCount = 0;
  // The pixel centers in the boxes of the lanes kept (fragment or triangle): the
  // chunk's PolygonCounts::boxSamples, summed in lanes (below 2^16 a lane: a tested box is
  // under 2^14 grid steps, 64 pixels, on a side).
  int keptSamples = 0;
  // Per kept lane: the pixel centers of its box, clipped to the viewport (inclusive).
  struct {
    alignas(64) std::int32_t x0[kBatchSize], y0[kBatchSize], x1[kBatchSize], y1[kBatchSize];
  } samples;
  alignas(64) std::int32_t tile[kBatchSize];  // per kept lane: the tile of its first center
  alignas(64) float key[kBatchSize];          // per fragment lane
  // Per small or nearEdge lane: its SmallTriangle's depth plane and coverage (and the
  // covered centers not surely inside a boundary edge: a nearEdge lane's, some).
  struct {
    alignas(64) double firstKey[kBatchSize], keyPerFine[kBatchSize], keyPerPixel[kBatchSize];
    alignas(64) std::int32_t firstRowFine[kBatchSize], coverage[kBatchSize];
    alignas(64) std::int32_t unsure[kBatchSize];
    // nearestWrittenKey, with clampBackFaces (the back faces' clamp,
    // Chunk::smallNearestKeys): a clockwise lane's nearest vertex key, else +∞.
    alignas(64) float nearestKey[kBatchSize];
  } smallPlane;
  std::uint32_t dropped() const { return culled | zeroArea | coversNoSample; }
  std::uint32_t kept() const { return fragment | triangle; }
};

// The SmallTriangle record of a small lane (BatchVerdicts::small) of polygon `polygonId`.
inline SmallTriangle smallTriangleOfLane(const BatchVerdicts& verdicts, int lane,
                                         std::int32_t polygonId) {
  const auto& plane = verdicts.smallPlane;
  const auto& samples = verdicts.samples;
  SmallTriangle t;
  t.firstKey = plane.firstKey[lane];
  t.keyPerFine = plane.keyPerFine[lane];
  t.keyPerPixel = plane.keyPerPixel[lane];
  t.firstRowFine = plane.firstRowFine[lane];
  t.polygon = polygonId;
  t.x0 = static_cast<std::uint16_t>(samples.x0[lane]);
  t.y0 = static_cast<std::uint16_t>(samples.y0[lane]);
  t.coverage = static_cast<std::uint16_t>(plane.coverage[lane]);
  return t;
}

// The verdicts for the tiles' viewport and the mesh's back-face handling (`boundaryEdges`:
// the depth keys' polygon-boundary edges, kAllEdges or none, RasterTriangle.h; a triangle's
// three edges are its polygon's). With `clampBackFaces` (and boundary edges) the clockwise
// lanes' keys are clamped as kClampedEdges clamps them (nearestWrittenKey: the fragments' keys,
// smallPlane.nearestKey for the records): every back face a depth-tested frame paints after
// the front faces (Setup.cpp, triangleEdges).
void classifyBatch(const TriangleBatch& batch, const TileGrid& grid, bool skipBackFaces,
                   bool boundaryEdges, BatchVerdicts& verdicts, bool clampBackFaces = false);

// classifyBatch on the instruction set chosen now: a run of batches (Setup.cpp's setUpRun,
// setUpBackRun) takes it once and calls it per batch, without Highway's dispatch (the chosen
// target's index and its table) in every batch. The same function classifyBatch calls.
using BatchClassifier = void (*)(const TriangleBatch& batch, const TileGrid& grid,
                                 bool skipBackFaces, bool boundaryEdges, BatchVerdicts& verdicts,
                                 bool clampBackFaces);
BatchClassifier batchClassifier();
// Highway's target chosen if no dispatch chose it yet (a process's first render): before that,
// a dispatch table's entry is Highway's first-call initializer, which updates the choice on
// every call. batchClassifier and blockCornersFunction (HiddenBlockCorners.h) call it before
// they take a table's entry once for many calls.
void chooseSimdTarget();

// Tests and benchmarks: which instruction sets the batch runs on. Not for use while a render
// runs.
struct SimdTarget {
  std::int64_t bits;  // Highway's HWY_* target bit
  const char* name;   // "EMU128" (portable C++), "SSE4", "AVX2", "AVX3", ...
};
// The targets compiled in and supported by this CPU, best first; the last is the portable
// fallback. Undoes useSimdTarget's restriction (the best target runs again).
std::vector<SimdTarget> simdTargets();
// Restricts the batch to `target`'s instruction set (0: the best this CPU has again).
void useSimdTarget(std::int64_t target);
// The instruction set the batch runs on now.
const char* simdTargetInUse();
// Tests: Highway's chosen target forgotten, as before a process's first dispatch (the next
// dispatch, or batchClassifier, chooses the best again).
void forgetSimdTarget();
// Off: every polygon through the per-triangle path alone (the set-up before batches).
void enableSetupBatches(bool on);
bool setupBatchesEnabled();

}  // namespace facet::detail
