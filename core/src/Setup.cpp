#include "Setup.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <numeric>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>

#include "Assert.h"
#include "BackFacingBlocks.h"
#include "Binning.h"
#include "Clipper.h"
#include "HiddenBlocks.h"
#include "HiddenRuns.h"
#include "MeshAccess.h"
#include "MeshCache.h"
#include "SetupBatch.h"
#include "facet/PolygonNormal.h"

namespace facet::detail {
namespace {

// Polygons per set-up chunk (planChunks: about four chunks per thread of equal work, for
// load balance): at least 2^10 (a chunk's bins cost a vector per tile) and at most 2^20.
constexpr std::size_t kMinPolygonsPerChunk = 1 << 10;
constexpr std::size_t kMaxPolygonsPerChunk = 1 << 20;

// What became of a polygon's triangles: how many were binned, and why the others were
// dropped, to count the polygon once under one reason.
struct Tally {
  int binned = 0, zeroArea = 0, outside = 0;
};

// The boundary edges of triangle (c0, c1, c2) of an n-corner polygon, by corner index: an
// edge is on the boundary when its corners are neighbours in the polygon.
EdgeMask boundaryEdges(std::uint32_t c0, std::uint32_t c1, std::uint32_t c2, std::size_t n) {
  const auto neighbours = [n](std::uint32_t i, std::uint32_t j) {
    return (i + 1) % n == j || (j + 1) % n == i;
  };
  return static_cast<EdgeMask>(neighbours(c1, c2) | neighbours(c2, c0) << 1 |
                               neighbours(c0, c1) << 2);
}

// Whether side j (vertex j to j + 1) of a clipped triangle lies on its polygon's boundary:
// on an input edge that is, or on a clip plane (no input edge).
bool clippedSideOnBoundary(const ClipVertex* clipped, int count, int j, EdgeMask boundary) {
  const unsigned onEdges = clipped[j].onEdges & clipped[(j + 1) % count].onEdges;
  return onEdges == 0 || (onEdges & boundary) != 0;
}

// The boundary edges of fan triangle (0, i, i + 1) of a clipped triangle with `count`
// vertices: side i always is a side of the clipped polygon, sides (0, i) and (i + 1, 0)
// only for the first and last triangles.
EdgeMask clippedFanEdges(const ClipVertex* clipped, int count, int i, EdgeMask boundary) {
  const bool opposite0 = clippedSideOnBoundary(clipped, count, i, boundary);
  const bool opposite1 = i + 2 == count && clippedSideOnBoundary(clipped, count, i + 1, boundary);
  const bool opposite2 = i == 1 && clippedSideOnBoundary(clipped, count, 0, boundary);
  return static_cast<EdgeMask>(opposite0 | opposite1 << 1 | opposite2 << 2);
}

// The mean of the corners, each divided first so that no sum overflows.
glm::dvec3 centerOf(std::span<const glm::dvec3> corners) {
  const double weight = 1.0 / static_cast<double>(corners.size());
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& corner : corners)
    sum += corner * weight;
  return sum;
}

// Facing. A polygon is seen from one side as a whole: its normal (polygonNormal) against the
// direction to the viewer, never the snapped window area of one of its triangles, which a
// sliver can flip. It is lit from that side and, when back faces are skipped, dropped as a
// whole. A triangle the clipper leaves alone is decided by its exact integer window area
// instead, as OpenGL's gl_FrontFacing (VTK agreement); one the clipper cuts by its plane.
// The triangles of a kept polygon are painted whatever their own winding.
//
// kSkipBackFaces is the mesh's back-face handling this frame (FrameMesh::skipBackFaces),
// chosen once per mesh rather than tested per polygon. kDeferBackFaces: a mesh that draws its
// back faces, set up by a two-pass frame's front pass (SetupPass::Front), which defers them
// (the back pass sets them up): it keeps front faces alone, so its code never asks whether a
// kept polygon is seen from the back, as a mesh that skips them. The batch drops the back faces
// as it would cull them, and settle() defers them.
template <class PointsT, class PolygonsT, bool kSkipBackFaces, bool kDeferBackFaces = false>
class PolygonSetup {
  static_assert(!(kSkipBackFaces && kDeferBackFaces));
  // Whether a polygon the set-up keeps may be seen from the back.
  static constexpr bool kKeepsBackFaces = !kSkipBackFaces && !kDeferBackFaces;

 public:
  PolygonSetup(const SetupContext& context, Chunk& chunk, const FrameMesh& mesh, PointsT points,
               PolygonsT polygons)
      : context_(context),
        chunk_(chunk),
        mesh_(mesh),
        points_(points),
        polygons_(polygons),
        meshVertices_(context.vertices + mesh.firstVertex),
        clampBack_(kKeepsBackFaces && context.backFacesLast) {
    FACET_ASSERT(kDeferBackFaces == (!kSkipBackFaces && context.pass == SetupPass::Front));
  }

  // Whether the back faces the batch keeps have their keys clamped (triangleEdges).
  bool clampsBackFaces() const { return clampBack_; }

  // Puts polygon `polygon` in lane `lane` of a batch (the back pass's scattered polygons).
  // `gathered`: the polygon is a triangle whose corners the back pass's run test read already
  // (HiddenRuns.h), loadOne's bytes; null: read here.
  void loadOne(std::size_t polygon, TriangleBatch& batch, int lane,
               const WindowVertex* gathered) const {
    if (gathered != nullptr) {
      batch.triangle[lane] = true;
      for (int j = 0; j < 3; ++j)
        batch.v[j][lane] = gathered[j];
      return;
    }
    const bool triangle = polygons_.size(polygon) == 3;
    batch.triangle[lane] = triangle;
    if (triangle) {
      for (int j = 0; j < 3; ++j)
        batch.v[j][lane] = meshVertices_[polygons_.pointId(polygon, static_cast<std::size_t>(j))];
    }
  }

  // Puts `count` consecutive polygons from `first` in a batch's lanes from `lane`, each to be
  // set up there when it is a triangle with every vertex inside (SetupBatch.h); each offset
  // is read once.
  void load(std::size_t first, int count, TriangleBatch& batch, int lane) const {
    const auto* offsets = polygons_.offsets + first;
    prefetchAhead<1>(offsets);
    prefetchAhead<3>(polygons_.connectivity + static_cast<std::size_t>(offsets[0]));
    auto begin = static_cast<std::size_t>(offsets[0]);
    for (int k = 0; k < count; ++k) {
      const auto end = static_cast<std::size_t>(offsets[k + 1]);
      const bool triangle = end - begin == 3;
      batch.triangle[lane + k] = triangle;
      if (triangle) {
        for (int j = 0; j < 3; ++j)
          batch.v[j][lane + k] = meshVertices_[polygons_.connectivity[begin + j]];
      }
      begin = end;
    }
  }

  // The entries of a batch's polygons (kPerPolygon each) kPrefetchPolygons polygons past
  // `at`, asked for now: the loader reads the offsets and connectivity in order, from memory
  // after a frame that evicted them (section 52). A fixed count of lines, unrolled: a load of
  // fewer polygons asks for lines the next one would (harmless). Addresses as integers: they
  // may lie past the array's end, where a prefetch does not fault. Inlined by force: a
  // function of prefetches alone is "pure" to GCC, whose calls it drops (section 66).
  template <int kPerPolygon, class Index>
  [[gnu::always_inline]] static void prefetchAhead(const Index* at) {
    constexpr std::size_t kPrefetchPolygons = 64;
    constexpr std::size_t kBytes = kBatchSize * kPerPolygon * sizeof(Index);
    const std::uintptr_t from =
        reinterpret_cast<std::uintptr_t>(at) + kPrefetchPolygons * kPerPolygon * sizeof(Index);
    for (std::size_t line = 0; line < kBytes; line += 64)
      __builtin_prefetch(reinterpret_cast<const void*>(from + line));
  }

  // Counts the polygons the batch dropped as run() would, bins the ones it kept, and runs the
  // others of the first `lanes` lanes (the lanes beyond were not tested), in lane order.
  void settle(const BatchVerdicts& verdicts, const std::size_t* lanePolygon, int lanes) {
    if constexpr (kDeferBackFaces) {
      if (verdicts.culled != 0) deferCulled(verdicts, lanePolygon, lanes);
    } else {
      chunk_.counts.culled += static_cast<std::size_t>(verdicts.culledCount);
    }
    chunk_.counts.degenerate += static_cast<std::size_t>(verdicts.zeroAreaCount);
    chunk_.counts.outside += static_cast<std::size_t>(verdicts.coversNoSampleCount);
    chunk_.counts.boxSamples += static_cast<std::size_t>(verdicts.keptSamples);
    const std::uint32_t used = (1u << lanes) - 1;
    const std::uint32_t kept = verdicts.kept() & used;
    std::size_t binned = 0;
    for (std::uint32_t rest = ~verdicts.dropped() & used; rest != 0; rest &= rest - 1) {
      const int lane = std::countr_zero(rest);
      if ((kept >> lane) & 1u) {
        bin(verdicts, lane, lanePolygon[lane]);
        ++binned;
      } else {
        run(lanePolygon[lane]);
      }
    }
    // The kept polygons' facing, after every append: a byte store may alias anything, and
    // between appends it made the compiler reload the chunk's vectors (and, in this loop, the
    // base pointer: taken once). A mesh that skips or defers back faces keeps no clockwise
    // lane.
    std::uint8_t* const facing = context_.backFacing + mesh_.firstPolygon;
    if (!kKeepsBackFaces && kept != 0 && wholeRun(lanePolygon, lanes)) {
      // Every lane's byte at once: 0 is also right for the lanes not kept, which are dropped
      // (never shown, so never read), were drawn front-facing by run() (back faces culled or
      // deferred), or are deferred: the back pass, a later phase, writes the byte of each one
      // it draws (never shown otherwise).
      static constexpr std::uint8_t kFront[kBatchSize] = {};
      std::memcpy(facing + lanePolygon[0], kFront, kBatchSize);
    } else {
      for (std::uint32_t rest = kept; rest != 0; rest &= rest - 1) {
        const int lane = std::countr_zero(rest);
        facing[lanePolygon[lane]] = kKeepsBackFaces ? (verdicts.clockwise >> lane) & 1u : 0;
      }
    }
    chunk_.counts.trianglesBinned += binned;
    chunk_.counts.drawn += binned;
  }

  // Whether a batch's lanes hold kBatchSize consecutive polygons: in z-buffer order a batch's
  // polygons ascend, so they do unless it spans a block the set-up skipped whole.
  bool wholeRun(const std::size_t* lanePolygon, int lanes) const {
    return lanes == kBatchSize && context_.order.ids.empty() &&
           lanePolygon[kBatchSize - 1] - lanePolygon[0] == kBatchSize - 1;
  }

  void run(std::size_t polygon) {
    polygon_ = polygon;
    polygonId_ = static_cast<std::int32_t>(mesh_.firstPolygon + polygon);
    const std::size_t n = polygons_.size(polygon);
    if (n == 3) {
      runTriangle();
    } else if (n < 3) {
      ++chunk_.counts.degenerate;
    } else if (const std::uint32_t code = polygonOutcode(n); code != kInside) {
      ++((code & kNonFinite) ? chunk_.counts.nonFinite : chunk_.counts.outside);
    } else {
      runPolygon(n);
    }
  }

 private:
  // kNonFinite when a corner is not finite, another bit when every corner is beyond one
  // plane, else kInside.
  std::uint32_t polygonOutcode(std::size_t n) const {
    std::uint32_t any = 0, all = ~0u;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t code = meshVertices_[pointId(k)].outcode;
      any |= code;
      all &= code;
    }
    return (any & kNonFinite) ? kNonFinite : all;
  }

  // The common case, kept short: a triangle, with the vertex records loaded once.
  void runTriangle() {
    const std::size_t ids[3] = {pointId(0), pointId(1), pointId(2)};
    const WindowVertex& a = meshVertices_[ids[0]];
    const WindowVertex& b = meshVertices_[ids[1]];
    const WindowVertex& c = meshVertices_[ids[2]];
    const std::uint32_t any = a.outcode | b.outcode | c.outcode;
    if (any & kNonFinite) {
      ++chunk_.counts.nonFinite;
      return;
    }
    if ((a.outcode & b.outcode & c.outcode) != kInside) {
      ++chunk_.counts.outside;
      return;
    }
    if (any != kInside) {
      runClippedTriangle(ids, any);
      return;
    }
    const std::int64_t area = doubleSignedArea(a, b, c);
    if (kSkipBackFaces && area < 0) {
      ++chunk_.counts.culled;
      return;
    }
    if (kDeferBackFaces && area < 0) {
      defer(polygon_);
      return;
    }
    emit(area < 0, [&](Tally& tally) {
      keep(frameIndex(ids[0]), frameIndex(ids[1]), frameIndex(ids[2]), a, b, c, area,
           triangleEdges(area < 0), tally);
    });
  }

  void runClippedTriangle(const std::size_t (&ids)[3], std::uint32_t planes) {
    const glm::dvec3 corners[3] = {points_[ids[0]], points_[ids[1]], points_[ids[2]]};
    const std::optional<bool> back =
        sideSeen(triangleNormal(corners[0], corners[1], corners[2]), corners);
    if (back) emit(*back, [&](Tally& tally) { clip(ids, planes, kAllEdges, tally); });
  }

  void runPolygon(std::size_t n) {
    chunk_.corners.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      chunk_.corners[k] = points_[pointId(k)];
    const std::optional<glm::dvec3> normal =
        polygonNormal(std::span<const glm::dvec3>(chunk_.corners));
    const std::optional<bool> back = sideSeen(normal, chunk_.corners);
    if (back) emit(*back, [&](Tally& tally) { triangulate(*normal, tally); });
  }

  // Whether the viewer sees the back of a polygon with this normal; nothing (counted) when
  // it has no normal, or is a back face the mesh skips.
  std::optional<bool> sideSeen(const std::optional<glm::dvec3>& normal,
                               std::span<const glm::dvec3> corners) {
    if (!normal) {
      ++chunk_.counts.degenerate;
      return std::nullopt;
    }
    const bool back = !context_.transform.facesViewer(*normal, centerOf(corners));
    if (kSkipBackFaces && back) {
      ++chunk_.counts.culled;
      return std::nullopt;
    }
    if (kDeferBackFaces && back) {
      defer(polygon_);
      return std::nullopt;
    }
    return back;
  }

  // Runs addTriangles(tally), then counts the polygon and notes for its shading which side
  // the viewer sees.
  template <class AddTriangles>
  void emit(bool back, const AddTriangles& addTriangles) {
    last_ = back && context_.backFacesLast;
    Tally tally;
    addTriangles(tally);
    if (tally.binned == 0) {
      countDropped(tally);
      return;
    }
    countDrawn(polygonId_, back, tally.binned);
  }

  void countDrawn(std::int32_t polygonId, bool back, int trianglesBinned) {
    context_.backFacing[static_cast<std::size_t>(polygonId)] = back;
    chunk_.counts.trianglesBinned += static_cast<std::size_t>(trianglesBinned);
    ++chunk_.counts.drawn;
  }

  // A triangle polygon a batch kept, binned as it decided (as keep() would bin it); settle()
  // counts it drawn.
  [[gnu::always_inline]] void bin(const BatchVerdicts& verdicts, int lane, std::size_t polygon) {
    const auto polygonId = static_cast<std::int32_t>(mesh_.firstPolygon + polygon);
    // A mesh that skips or defers back faces keeps no clockwise lane (the batch culled them).
    const bool back = kKeepsBackFaces && ((verdicts.clockwise >> lane) & 1u);
    const bool last = back && context_.backFacesLast;
    const auto& samples = verdicts.samples;
    const std::size_t tile = static_cast<std::size_t>(verdicts.tile[lane]);
    if ((verdicts.fragment >> lane) & 1u) {
      binFragment(chunk_, tile, samples.x0[lane], samples.y0[lane], verdicts.key[lane], polygonId,
                  last);
    } else if ((verdicts.small >> lane) & 1u) {
      binSmallOfLane(verdicts, lane, tile, smallTriangleOfLane(verdicts, lane, polygonId), last);
    } else if ((verdicts.nearEdge >> lane) & 1u) {
      binNearEdge(verdicts, lane, polygon, polygonId, back, last);
    } else {
      // Its vertex references, read again here (most kept triangles are fragments).
      const auto reference = [&](std::size_t corner) {
        return frameIndex(polygons_.pointId(polygon, corner));
      };
      binCovering(chunk_, context_.grid, reference(0), reference(back ? 2 : 1),
                  reference(back ? 1 : 2),
                  {samples.x0[lane], samples.y0[lane], samples.x1[lane], samples.y1[lane]},
                  triangleEdges(back), polygonId, last,
                  (verdicts.oneTile >> lane) & 1u ? static_cast<std::int64_t>(tile) : -1);
    }
  }

  // A small or nearEdge lane's record, with its nearest key when the back faces are clamped
  // (Chunk::smallNearestKeys: one a record from firstKeyedSmall on).
  [[gnu::always_inline]] void binSmallOfLane(const BatchVerdicts& verdicts, int lane,
                                             std::size_t tile, const SmallTriangle& record,
                                             bool last) {
    if (kKeepsBackFaces && clampBack_)
      chunk_.smallNearestKeys.push_back(verdicts.smallPlane.nearestKey[lane]);
    binSmall(chunk_, tile, record, last);
  }

  // A nearEdge lane (BatchVerdicts): its record without the centers near a boundary edge at
  // which paintTriangle takes keyAt's key, and those as fragments (keysNearBoundary): the
  // pixels and keys paintTriangle would give, the tile painting no triangle of its own. Out of
  // line: a few lanes in a hundred (every face drawn).
  [[gnu::noinline]] void binNearEdge(const BatchVerdicts& verdicts, int lane, std::size_t polygon,
                                     std::int32_t polygonId, bool back, bool last) {
    const WindowVertex& a = meshVertices_[polygons_.pointId(polygon, 0)];
    const WindowVertex& b = meshVertices_[polygons_.pointId(polygon, back ? 2 : 1)];
    const WindowVertex& c = meshVertices_[polygons_.pointId(polygon, back ? 1 : 2)];
    const int x0 = verdicts.samples.x0[lane], y0 = verdicts.samples.y0[lane];
    const std::size_t tile = static_cast<std::size_t>(verdicts.tile[lane]);
    float keys[kSmallSide * kSmallSide];
    const std::uint32_t near =
        keysNearBoundary(a, b, c, triangleEdges(back), x0, y0,
                         static_cast<std::uint32_t>(verdicts.smallPlane.unsure[lane]), keys);
    SmallTriangle record = smallTriangleOfLane(verdicts, lane, polygonId);
    record.coverage = static_cast<std::uint16_t>(record.coverage & ~near);
    if (record.coverage != 0) binSmallOfLane(verdicts, lane, tile, record, last);
    for (std::uint32_t rest = near; rest != 0; rest &= rest - 1) {
      const int bit = std::countr_zero(rest);
      binFragment(chunk_, tile, x0 + bit % kSmallSide, y0 + bit / kSmallSide, keys[bit], polygonId,
                  last);
    }
  }

  // The front pass's back lanes (the batch culled them), put off to the back pass.
  [[gnu::noinline]] void deferCulled(const BatchVerdicts& verdicts, const std::size_t* lanePolygon,
                                     int lanes) {
    // Appended one by one: a resize() for the batch's count zeroes the new ids first (a call
    // to memset) and std::popcount is a call into libgcc on the baseline build; most calls
    // append a few ids.
    const std::uint32_t used = (1u << lanes) - 1;
    std::vector<std::uint32_t>& list = chunk_.deferredBack;
    const auto first = static_cast<std::uint32_t>(mesh_.firstPolygon);
    for (std::uint32_t rest = verdicts.culled & used; rest != 0; rest &= rest - 1)
      list.push_back(first + static_cast<std::uint32_t>(lanePolygon[std::countr_zero(rest)]));
  }

  // A polygon run() defers: in a batch's settle() after the culled lanes deferCulled appended,
  // which may come after it, so put in its place (at most a batch's lanes from the end): the
  // back pass finds blocks' ids by binary search and sets them up in polygon order.
  [[gnu::noinline]] void defer(std::size_t polygon) {
    std::vector<std::uint32_t>& list = chunk_.deferredBack;
    const auto id = static_cast<std::uint32_t>(mesh_.firstPolygon + polygon);
    list.insert(std::upper_bound(list.begin(), list.end(), id,
                                 [](std::uint32_t a, std::uint32_t b) {
                                   return deferredIdOf(a) < deferredIdOf(b);
                                 }),
                id);
  }

  std::size_t pointId(std::size_t corner) const { return polygons_.pointId(polygon_, corner); }

  // The boundary edges keep() gives the triangle of a triangle polygon seen from the back or
  // not: all three, and the clamp to its nearest vertex key (kClampedEdges) on every back face
  // a depth-tested frame paints after the front faces (its back bins, Chunk::binsFor), one pass
  // or two alike (HiddenBlocks.h, step 1); none when back faces are skipped.
  EdgeMask triangleEdges(bool back) const {
    if (kSkipBackFaces) return EdgeMask{0};
    return kKeepsBackFaces && back && clampBack_ ? kClampedEdges : kAllEdges;
  }

  // In the polygon's plane, by Triangulate.h's rules.
  void triangulate(const glm::dvec3& normal, Tally& tally) {
    chunk_.localTriangles.clear();
    triangulatePolygon(chunk_.corners, normal, chunk_.triangulation, chunk_.localTriangles);
    for (const LocalTriangle& t : chunk_.localTriangles)
      addTriangle(t[0], t[1], t[2], tally);
  }

  // One triangle of the polygon, by corner index: kept whole, clipped, or dropped.
  void addTriangle(std::uint32_t c0, std::uint32_t c1, std::uint32_t c2, Tally& tally) {
    const std::size_t ids[3] = {pointId(c0), pointId(c1), pointId(c2)};
    const std::uint32_t codes[3] = {meshVertices_[ids[0]].outcode, meshVertices_[ids[1]].outcode,
                                    meshVertices_[ids[2]].outcode};
    const std::uint32_t any = codes[0] | codes[1] | codes[2];
    const EdgeMask boundary = boundaryEdges(c0, c1, c2, chunk_.corners.size());
    if (any == kInside) {
      keep(frameIndex(ids[0]), frameIndex(ids[1]), frameIndex(ids[2]), boundary, tally);
    } else if ((codes[0] & codes[1] & codes[2]) != kInside) {
      ++tally.outside;
    } else {
      clip(ids, any, boundary, tally);
    }
  }

  std::uint32_t frameIndex(std::size_t pointId) const {
    return static_cast<std::uint32_t>(mesh_.firstVertex + pointId);
  }

  void clip(const std::size_t (&ids)[3], std::uint32_t planes, EdgeMask boundary, Tally& tally) {
    ++chunk_.counts.trianglesClipped;
    ClipVertex triangle[3];
    for (int i = 0; i < 3; ++i) {
      const auto onEdges = static_cast<std::uint8_t>(kAllEdges & ~(1u << i));  // not opposite
      triangle[i] = {context_.transform.toClip(points_[ids[i]]), frameIndex(ids[i]), onEdges};
    }
    ClipVertex clipped[kMaxClippedVertices];
    const int count = clipTriangle(context_.transform, triangle, planes, clipped);
    if (count == 0) {
      ++tally.outside;
      return;
    }
    std::uint32_t references[kMaxClippedVertices];
    for (int i = 0; i < count; ++i)
      references[i] = referenceOf(clipped[i]);
    for (int i = 1; i + 1 < count; ++i) {
      keep(references[0], references[i], references[i + 1],
           clippedFanEdges(clipped, count, i, boundary), tally);
    }
  }

  // An input corner keeps its snapped coordinates; a new vertex joins the chunk's own.
  std::uint32_t referenceOf(const ClipVertex& vertex) {
    if (vertex.source != ClipVertex::kNewVertex) return vertex.source;
    const auto index = static_cast<std::uint32_t>(chunk_.clippedVertices.size());
    chunk_.clippedVertices.push_back(context_.transform.toWindow(vertex.clip));
    return index | kClippedVertexBit;
  }

  void keep(std::uint32_t r0, std::uint32_t r1, std::uint32_t r2, EdgeMask boundary, Tally& tally) {
    const WindowVertex& a = vertexOf(context_.vertices, chunk_, r0);
    const WindowVertex& b = vertexOf(context_.vertices, chunk_, r1);
    const WindowVertex& c = vertexOf(context_.vertices, chunk_, r2);
    keep(r0, r1, r2, a, b, c, doubleSignedArea(a, b, c), boundary, tally);
  }

  // Hands a triangle to binning. Without back faces no silhouette fold can form: no edge is
  // marked as a polygon boundary, so the unsnapped depth plane holds everywhere
  // (RasterTriangle.cpp, TriangleDepth).
  void keep(std::uint32_t r0, std::uint32_t r1, std::uint32_t r2, const WindowVertex& a,
            const WindowVertex& b, const WindowVertex& c, std::int64_t area, EdgeMask boundary,
            Tally& tally) {
    const EdgeMask edges = kSkipBackFaces ? EdgeMask{0} : boundary;
    switch (
        binTriangle(chunk_, context_.grid, r0, r1, r2, a, b, c, area, edges, polygonId_, last_)) {
      case BinOutcome::ZeroArea:
        ++tally.zeroArea;
        break;
      case BinOutcome::CoversNoSample:
        ++tally.outside;
        break;
      case BinOutcome::Binned:
        ++tally.binned;
        break;
    }
  }

  void countDropped(const Tally& tally) {
    if (tally.zeroArea > 0 && tally.outside == 0) {
      ++chunk_.counts.degenerate;
    } else {
      ++chunk_.counts.outside;
    }
  }

  const SetupContext& context_;
  Chunk& chunk_;
  const FrameMesh& mesh_;
  PointsT points_;
  PolygonsT polygons_;
  const WindowVertex* meshVertices_;
  // The back faces are painted after the front faces (the depth test, context.backFacesLast)
  // and clamped (triangleEdges); the records carry their keys (Chunk::smallNearestKeys). Not
  // in a two-pass frame's front pass, which keeps no back face.
  bool clampBack_;
  std::size_t polygon_ = 0;
  std::int32_t polygonId_ = 0;
  bool last_ = false;  // the polygon's triangles join the back bins (Chunk::binsFor)
};

// The mesh a global polygon id belongs to.
std::size_t meshOfPolygon(std::span<const FrameMesh> meshes, std::size_t polygonId) {
  if (meshes.size() == 1) return 0;
  // The last mesh starting at or before the id.
  const auto after = std::upper_bound(
      meshes.begin(), meshes.end(), polygonId,
      [](std::size_t id, const FrameMesh& mesh) { return id < mesh.firstPolygon; });
  return static_cast<std::size_t>(after - meshes.begin()) - 1;
}

// The end (a global id) of the polygons of a Chunk::deferredBack entry with kWholeBackBlockBit
// whose first is `first`: its back-face block's end, or the mesh's or the chunk's when nearer
// (the front pass's block loop stops there: z-buffer order, draw positions are ids).
std::size_t wholeBlockEnd(std::uint32_t first, const FrameMesh& mesh, const Chunk& chunk) {
  const std::size_t blockEnd =
      mesh.firstPolygon + (((first - mesh.firstPolygon) | (kPolygonsPerBackBlock - 1)) + 1);
  return std::min({blockEnd, mesh.endPolygon(), chunk.end});
}

// Sets up draw positions from `position` on while they belong to `mesh`, in batches
// (SetupBatch.h) unless they are off; returns where it stopped. The batch only drops
// polygons: the others are set up in draw order, as without batches.
template <bool kSkipBackFaces, bool kDeferBackFaces, class PointsT, class PolygonsT>
std::size_t setUpRun(const SetupContext& context, Chunk& chunk, const FrameMesh& mesh,
                     PointsT points, PolygonsT polygons, std::size_t position) {
  PolygonSetup<PointsT, PolygonsT, kSkipBackFaces, kDeferBackFaces> setup(context, chunk, mesh,
                                                                          points, polygons);
  // A record's nearest key is read at chunk.smallNearestKeys[record - firstKeyedSmall] (the
  // tiles' back bins): right only while every record of the chunk from there on pushed one,
  // i.e. the chunk holds this mesh's polygons alone (planChunks splits per mesh in z-buffer
  // order, which the depth test that clamps implies).
  FACET_ASSERT(!setup.clampsBackFaces() ||
               (context.order.ids.empty() && chunk.begin >= mesh.firstPolygon &&
                chunk.end <= mesh.endPolygon()));
  const bool batched = setupBatchesEnabled();
  const BatchClassifier classify = batched ? batchClassifier() : nullptr;
  TriangleBatch batch{};
  BatchVerdicts verdicts;
  std::size_t lanePolygon[kBatchSize];
  int lanes = 0;
  const auto settleBatch = [&] {
    classify(batch, context.grid, kSkipBackFaces || kDeferBackFaces, !kSkipBackFaces, verdicts,
             setup.clampsBackFaces());
    setup.settle(verdicts, lanePolygon, lanes);
    lanes = 0;
  };
  // `count` polygons from `polygon` on, all in view.
  const auto setUp = [&](std::size_t polygon, std::size_t count) {
    if (!batched) {
      for (std::size_t k = 0; k < count; ++k)
        setup.run(polygon + k);
      return;
    }
    while (count > 0) {
      const int take = static_cast<int>(
          std::min<std::size_t>(static_cast<std::size_t>(kBatchSize - lanes), count));
      setup.load(polygon, take, batch, lanes);
      for (int k = 0; k < take; ++k)
        lanePolygon[lanes + k] = polygon + static_cast<std::size_t>(k);
      polygon += static_cast<std::size_t>(take);
      count -= static_cast<std::size_t>(take);
      lanes += take;
      if (lanes == kBatchSize) settleBatch();
    }
  };
  const auto inView = [&](std::size_t polygon) {
    return !mesh.visibleBlocks || mesh.visibleBlocks[polygon >> kBlockBits];
  };
  // Every triangle of its back-face block would be culled (BackFacingBlocks.h).
  const auto culledWhole = [&](std::size_t polygon) {
    return mesh.backBlocks && mesh.backBlocks[polygon >> kBackBlockBits];
  };
  // A two-pass frame's front pass defers every polygon of a block BackFaceTest proves all back
  // faces without loading or classifying them: each would be a triangle inside the clip volume
  // with a negative snapped area (BackFacingBlocks.h, steps 1-5), which the front pass defers
  // (the batch's culled lanes, runTriangle) and counts nowhere, so the deferred ids are the
  // same, in the same order. Their points are transformed as the mesh's others: only meshes
  // that skip back faces leave blocks' points out (ViewCulling.h).
  std::optional<BackFaceTest> certainBack;
  if (context.deferCertainBackBlocks && kDeferBackFaces && context.order.ids.empty() &&
      mesh.backBlockFacts != nullptr)
    certainBack.emplace(context.transform);
  // Defers the block's polygons when it is certain to be all back faces, as one entry
  // (kWholeBackBlockBit: the back pass finds their end, wholeBlockEnd); flushes the batch
  // first, whose lanes' deferred ids come earlier (the back pass's ids ascend).
  const auto deferredWhole = [&](std::size_t polygon, std::size_t count) {
    if (!certainBack) return false;
    // The transform phase's verdict when it left the block's points out (ViewCulling.h).
    const std::size_t block = polygon >> kBackBlockBits;
    if (mesh.deferredBackBlocks
            ? !mesh.deferredBackBlocks[block]
            : !certainBack->certainlyCulled(mesh.backBlockFacts->backTests[block],
                                            mesh.backBlockFacts->backFrameOf(block)))
      return false;
    if (lanes > 0) {
      std::fill(batch.triangle + lanes, batch.triangle + kBatchSize, 0);
      settleBatch();
    }
    const auto first = static_cast<std::uint32_t>(mesh.firstPolygon + polygon);
    FACET_ASSERT(wholeBlockEnd(first, mesh, chunk) == first + count);
    chunk.deferredBack.push_back(kWholeBackBlockBit | first);
    deferredWholeDebug(count);
    return true;
  };
  // Whether the block of `polygon` is left out whole, none of its polygons loaded: outside the
  // view, culled whole, or (the front pass) deferred whole by the transform phase's verdict
  // (without it, the first frames', the prefetch below sees no gap there).
  const auto leftOutWhole = [&](std::size_t polygon) __attribute__((always_inline)) {
    if constexpr (kDeferBackFaces) {
      if (certainBack && mesh.deferredBackBlocks &&
          mesh.deferredBackBlocks[polygon >> kBackBlockBits])
        return true;
    }
    return !inView(polygon) || culledWhole(polygon);
  };
  // `count` polygons from `polygon` on, in one back-face block.
  // A frame that skips back faces leaves out whole blocks, in runs (a meridian's far side),
  // and so does a two-pass frame's front pass (the blocks it defers whole): the offsets and
  // connectivity of the next block it sets up after such a gap are asked for while this one is
  // set up. The hardware prefetchers follow the arrays only within a run of blocks, and after
  // another program's frame (VTK's in bench/peers.py's paired frames) the mesh is not in cache
  // (core-frame-issue11.md, sections 51 and 63); at 2M polygons it is not in cache after the
  // previous frame either.
  // Inlined by force: a function of prefetches alone is "pure" to GCC, and its calls dropped.
  const auto prefetchAfterGap = [&](std::size_t from, std::size_t end)
      __attribute__((always_inline)) {
    std::size_t next = from;
    while (next < end && leftOutWhole(next))
      next = std::min(end, (next | (kPolygonsPerBackBlock - 1)) + 1);
    if (next == from || next >= end) return;  // no gap: the streams go on; or none left
    const std::size_t count = std::min(end - next, kPolygonsPerBackBlock);
    constexpr std::size_t kLine = 64;
    using Index = std::remove_cvref_t<decltype(*polygons.offsets)>;
    const auto* offsets = reinterpret_cast<const char*>(polygons.offsets + next);
    for (std::size_t at = 0; at < (count + 1) * sizeof(Index); at += kLine)
      __builtin_prefetch(offsets + at);
    if (!mesh.allTriangles) return;  // the connectivity's place is offsets[next]'s, not read here
    const auto* connectivity = reinterpret_cast<const char*>(polygons.connectivity + 3 * next);
    for (std::size_t at = 0; at < 3 * count * sizeof(Index); at += kLine)
      __builtin_prefetch(connectivity + at);
  };
  const auto setUpBlock = [&](std::size_t polygon, std::size_t count) {
    if (!inView(polygon))
      chunk.counts.outside += count;  // outside the view (ViewCulling.h)
    else if (culledWhole(polygon))
      chunk.counts.culled += count;
    else if (!deferredWhole(polygon, count))
      setUp(polygon, count);
  };
  if (context.order.ids.empty()) {
    // Draw positions are polygon ids: the run ends where the chunk or the mesh does, and
    // visibility changes only from block to block (a third of the loop's instructions were
    // per-polygon tests at 2M triangles); a visible block's polygons go to the batch's lanes
    // in order, each offset read once.
    const std::size_t end = std::min(chunk.end, mesh.endPolygon()) - mesh.firstPolygon;
    std::size_t polygon = position - mesh.firstPolygon;
    while (polygon < end) {
      const std::size_t blockEnd = std::min(end, (polygon | (kPolygonsPerBackBlock - 1)) + 1);
      if constexpr (kSkipBackFaces || kDeferBackFaces) {
        if (!leftOutWhole(polygon)) prefetchAfterGap(blockEnd, end);
      }
      setUpBlock(polygon, blockEnd - polygon);
      polygon = blockEnd;
    }
    position = polygon + mesh.firstPolygon;
  } else {
    for (; position < chunk.end; ++position) {
      const std::size_t id = context.order.ids[position];
      if (id < mesh.firstPolygon || id >= mesh.endPolygon()) break;
      setUpBlock(id - mesh.firstPolygon, 1);
    }
  }
  if (lanes > 0) {
    std::fill(batch.triangle + lanes, batch.triangle + kBatchSize, 0);  // earlier triangles
    settleBatch();
  }
  return position;
}

// Sets up the chunk's deferred back faces from index `first` on while they belong to `mesh`,
// in batches unless they are off, after the blocks and runs hidden behind the front faces'
// blocks are dropped (HiddenBlocks.h); returns where it stopped. What those leave is set up as
// one pass sets it up: a triangle they keep that loses everywhere all the same is rejected by
// the back bins' paint (paintTriangle's kRejectHidden), as in one pass.
template <class PointsT, class PolygonsT>
std::size_t setUpBackRun(const SetupContext& context, Chunk& chunk, const FrameMesh& mesh,
                         PointsT points, PolygonsT polygons, std::size_t first) {
  PolygonSetup<PointsT, PolygonsT, false> setup(context, chunk, mesh, points, polygons);
  // The entries: ids, and blocks deferred whole (kWholeBackBlockBit).
  const std::vector<std::uint32_t>& ids = chunk.deferredBack;
  const auto endId = static_cast<std::uint32_t>(mesh.endPolygon());
  const std::size_t end = static_cast<std::size_t>(
      std::lower_bound(
          ids.begin() + static_cast<std::ptrdiff_t>(first), ids.end(), endId,
          [](std::uint32_t entry, std::uint32_t id) { return deferredIdOf(entry) < id; }) -
      ids.begin());
  // The deferred back faces of a block of triangle polygons (MeshFacts::backSkippable) whose box
  // is hidden behind the front blocks (HiddenBlocks.h: none would write a pixel), dropped
  // before any per-polygon work (counted hidden, not drawn: one pass would have counted some
  // of them outside or degenerate). The ids ascend (z-buffer order): a block's end is found by
  // firstIdFrom, or it is one entry (a block the front pass deferred whole: no id of it is
  // read, a hidden one costs its verdict alone).
  std::optional<HiddenBlockTest> blocks;
  std::optional<BackFaceTest> cone;
  if (context.front != nullptr && mesh.backBlockFacts != nullptr && hiddenBlocksEnabled()) {
    blocks.emplace(context.transform, context.grid, *context.front);
    if (hiddenBlocksConeOnly() || countingHiddenBlocks()) cone.emplace(context.transform);
  }
  // The block scan's reads a few blocks ahead of ids[k] asked for (section 64): the entries
  // (firstIdFrom reads a block's last id, from memory: the front pass wrote them long
  // before; since a block deferred whole is one entry, section 65, kIdsAhead entries reach
  // further than 16 blocks, and dropping these two hints measured the same) and the compact
  // records. Hints at addresses that may lie past the arrays' ends (as integers: a prefetch
  // does not fault).
  const auto prefetchBlockScan = [&](std::size_t k) __attribute__((always_inline)) {
    constexpr std::size_t kIdsAhead = 16 * kPolygonsPerBackBlock, kBlocksAhead = 8;
    const auto at = reinterpret_cast<std::uintptr_t>(ids.data() + k);
    __builtin_prefetch(reinterpret_cast<const void*>(at + kIdsAhead * sizeof(std::uint32_t)));
    __builtin_prefetch(reinterpret_cast<const void*>(at + (kIdsAhead + kPolygonsPerBackBlock - 1) *
                                                              sizeof(std::uint32_t)));
    const std::size_t block = (deferredIdOf(ids[k]) - mesh.firstPolygon) >> kBackBlockBits;
    const auto test = reinterpret_cast<std::uintptr_t>(mesh.backBlockFacts->backTests.data());
    __builtin_prefetch(
        reinterpret_cast<const void*>(test + (block + kBlocksAhead) * sizeof(BackBlockTest)));
  };
  // The end of the entries of the block of ids[k], whether it is hidden, and its polygons.
  const auto blockOf = [&](std::size_t k, bool& hidden, std::size_t& count) {
    const std::uint32_t entry = ids[k], id = deferredIdOf(entry);
    const std::size_t block = (id - mesh.firstPolygon) >> kBackBlockBits;
    const auto next =
        static_cast<std::uint32_t>(mesh.firstPolygon + ((block + 1) << kBackBlockBits));
    const MeshFacts& facts = *mesh.backBlockFacts;
    // A deferred block's verdict, from the same test (DeferredBackPoints.h).
    const std::uint8_t verdict = mesh.backBlockVerdicts ? mesh.backBlockVerdicts[block] : 0;
    const BackBlockTest& test = facts.backTests[block];
    const BackBlockFrame& frame = facts.backFrameOf(block);
    hidden = verdict != 0 ? verdict == kBlockHidden
                          : facts.backSkippable(block) &&
                                (!hiddenBlocksConeOnly() || cone->certainlyCulled(test, frame)) &&
                                blocks->hidden(boxOf(test, frame));
    if (entry & kWholeBackBlockBit) {
      count = wholeBlockEnd(id, mesh, chunk) - id;
      return k + 1;
    }
    const std::size_t stop = firstIdFrom(ids, k, end, next);
    count = stop - k;
    return stop;
  };
  // The deferred back faces of a block not dropped whole, dropped run by run (HiddenBlocks.h,
  // steps R1-R3) before they are loaded: a run is the deferred ids of one aligned window of
  // kHiddenRunIds polygon ids. Chunks and blocks hold whole windows, so the runs, and what is
  // counted hidden, do not depend on the threads.
  static_assert(kPolygonsPerBackBlock % kHiddenRunIds == 0);
  std::optional<HiddenRunTest> runs;
  if (blocks) runs.emplace(context.grid, *context.front);
  const WindowVertex* const vertices = context.vertices + mesh.firstVertex;
  const auto firstId = static_cast<std::uint32_t>(mesh.firstPolygon);
  // Calls each(polygon, corners) for the deferred polygons of ids [k, stop) (one block's) not
  // in a hidden run (HiddenRuns.h: the runs' bounds in lanes), `corners` its triangle's three
  // window vertices as the runs read them (loadOne's bytes) when every polygon of the block
  // (RunSource::allTriangles: MeshFacts::backSkippable) or of the mesh (offsetsThrice) is a
  // triangle, else null (loadOne reads it again).
  using Source = RunSource<typename PolygonsT::IndexType>;
  const auto sourceOf = [&](std::uint32_t id) {
    return Source{vertices, polygons, firstId,
                  mesh.backBlockFacts->backSkippable((id - firstId) >> kBackBlockBits),
                  mesh.allTriangles};
  };
  // The blocks not dropped whole, taken up to kAhead ahead of the one whose runs are tested,
  // each one's connectivity asked for as it is taken (HiddenRuns.h; section 64): a kept block
  // mostly follows hidden ones, which leave it no lead time else. `ids`: its deferred ids, or
  // null for a block deferred whole (its ids first, first + 1, ...).
  struct Kept {
    const std::uint32_t* ids;
    std::uint32_t first, count;
    Source source;
  };
  std::uint32_t shown[kPolygonsPerBackBlock], wholeIds[kPolygonsPerBackBlock];
  alignas(64) WindowVertex corners[3 * kPolygonsPerBackBlock];
  const auto runsOf = [&](const Kept& kept, const auto& each) {
    FACET_ASSERT(kept.count <= kPolygonsPerBackBlock);
    const std::uint32_t* blockIds = kept.ids;
    if (blockIds == nullptr) {  // a kept block deferred whole: its ids, for the runs
      std::iota(wholeIds, wholeIds + kept.count, kept.first);
      blockIds = wholeIds;
    }
    const Source& source = kept.source;
    prefetchRunsNow(source, kept.first, blockIds[kept.count - 1]);
    RunTally tally;
    const std::size_t count =
        shownOfRuns(*runs, source, std::span(blockIds, kept.count), shown, corners, tally);
    chunk.counts.hiddenBlockPolygons += tally.hiddenPolygons;  // counted hidden alone, as a block's
    hiddenRunDebug(tally.runs, tally.hiddenRuns, tally.polygons, tally.hiddenPolygons);
    for (std::size_t i = 0; i < count; ++i)
      each(blockIds[shown[i]] - firstId,
           source.allTriangles || source.offsetsThrice ? corners + 3 * shown[i] : nullptr);
  };
  constexpr std::size_t kAhead = 3;
  Kept ahead[kAhead];
  std::size_t queued = 0, scan = first;
  // Queues the next block not dropped whole from ids[scan] on, counting the hidden ones before
  // it; false when none is left.
  const auto takeBlock = [&] {
    while (scan < end) {
      prefetchBlockScan(scan);
      bool hidden = false;
      std::size_t count = 0;
      const std::size_t k = scan;
      scan = blockOf(k, hidden, count);
      const std::uint32_t id = deferredIdOf(ids[k]);
      if (cone && countingHiddenBlocks()) {
        const std::size_t block = (id - mesh.firstPolygon) >> kBackBlockBits;
        const bool coneCertain = cone->certainlyCulled(mesh.backBlockFacts->backTests[block],
                                                       mesh.backBlockFacts->backFrameOf(block));
        hiddenBlockDebug(hidden, coneCertain, count, (ids[k] & kWholeBackBlockBit) != 0);
      }
      if (hidden) {  // counted hidden alone (RenderStats::polygonsHidden)
        ++chunk.counts.hiddenBlocks;
        chunk.counts.hiddenBlockPolygons += count;
        continue;
      }
      const bool whole = (ids[k] & kWholeBackBlockBit) != 0;
      ahead[queued] = {whole ? nullptr : ids.data() + k, id, static_cast<std::uint32_t>(count),
                       sourceOf(id)};
      prefetchRunsAhead(ahead[queued].source, id,
                        whole ? id + static_cast<std::uint32_t>(count) - 1 : ids[scan - 1]);
      ++queued;
      return true;
    }
    return false;
  };
  // Calls each(polygon, corners) for every deferred polygon of [first, end) not in a hidden
  // block (corners: runsOf's, or null).
  const auto forEachShown = [&](const auto& each) {
    if (!runs) {  // no reject: every deferred polygon
      for (std::size_t k = first; k < end; ++k) {
        const std::uint32_t id = deferredIdOf(ids[k]);
        const std::size_t stop =
            (ids[k] & kWholeBackBlockBit) ? wholeBlockEnd(id, mesh, chunk) : std::size_t{id} + 1;
        for (std::size_t polygon = id; polygon < stop; ++polygon)
          each(polygon - mesh.firstPolygon, nullptr);
      }
      return;
    }
    while (queued < kAhead && takeBlock()) {
    }
    while (queued > 0) {
      runsOf(ahead[0], each);
      std::copy(ahead + 1, ahead + queued, ahead);
      --queued;
      takeBlock();
    }
  };
  if (!setupBatchesEnabled()) {
    forEachShown([&](std::size_t polygon, const WindowVertex*) { setup.run(polygon); });
    return end;
  }
  const BatchClassifier classify = batchClassifier();
  TriangleBatch batch{};
  BatchVerdicts verdicts;
  std::size_t lanePolygon[kBatchSize];
  int lanes = 0;
  const auto settleBatch = [&] {
    std::fill(batch.triangle + lanes, batch.triangle + kBatchSize, 0);
    classify(batch, context.grid, false, true, verdicts, setup.clampsBackFaces());
    setup.settle(verdicts, lanePolygon, lanes);
    lanes = 0;
  };
  forEachShown([&](std::size_t polygon, const WindowVertex* loaded) {
    lanePolygon[lanes] = polygon;
    setup.loadOne(polygon, batch, lanes, loaded);
    if (++lanes == kBatchSize) settleBatch();
  });
  if (lanes > 0) settleBatch();
  return end;
}

// The back pass of a chunk: its deferred polygons, run by run of one mesh.
void setUpChunkBack(const SetupContext& context, Chunk& chunk) {
  chunk.firstKeyedSmall = chunk.smallTriangles.size();  // the front pass's records have none
  // setUpBackRun finds a mesh's ids by binary search and a block's by firstIdFrom (which
  // counts on distinct ids: strictly ascending).
  FACET_ASSERT(std::adjacent_find(chunk.deferredBack.begin(), chunk.deferredBack.end(),
                                  [](std::uint32_t a, std::uint32_t b) {
                                    return deferredIdOf(a) >= deferredIdOf(b);
                                  }) == chunk.deferredBack.end());
  std::size_t next = 0;
  while (next < chunk.deferredBack.size()) {
    const FrameMesh& mesh =
        context.meshes[meshOfPolygon(context.meshes, deferredIdOf(chunk.deferredBack[next]))];
    withTypedMesh(mesh.mesh(), [&](auto points, auto polygons) {
      next = setUpBackRun(context, chunk, mesh, points, polygons, next);
    });
  }
}

// Draw positions come in runs that share a mesh (the whole chunk, in z-buffer mode); each
// run is set up by code specialized for that mesh's point and index types and back-face
// handling.
void setUpChunk(const SetupContext& context, Chunk& chunk) {
  clearBins(chunk, context.grid);
  chunk.clippedVertices.clear();
  chunk.deferredBack.clear();
  chunk.counts = {};
  std::size_t position = chunk.begin;
  while (position < chunk.end) {
    const FrameMesh& mesh =
        context.meshes[meshOfPolygon(context.meshes, context.order.polygonAt(position))];
    withTypedMesh(mesh.mesh(), [&](auto points, auto polygons) {
      if (mesh.skipBackFaces)
        position = setUpRun<true, false>(context, chunk, mesh, points, polygons, position);
      else if (context.pass == SetupPass::Front)
        position = setUpRun<false, true>(context, chunk, mesh, points, polygons, position);
      else
        position = setUpRun<false, false>(context, chunk, mesh, points, polygons, position);
    });
  }
}

// Throws when a chunk's bin entries cannot index its records (Binning.h).
void requireChunkIndexable(const Chunk& chunk) {
  requireIndexable(chunk.triangles.size(), chunk.fragments.size(), chunk.smallTriangles.size(),
                   chunk.clippedVertices.size());
}

// Polygons [begin, end) of `mesh`, within one view-culling block (kPolygonsPerBlock), that are
// set up polygon by polygon: in view and in no back-face block culled whole (setUpRun skips
// the others with one test each).
std::size_t polygonsSetUp(const FrameMesh& mesh, std::size_t begin, std::size_t end) {
  if (mesh.visibleBlocks && !mesh.visibleBlocks[begin >> kBlockBits]) return 0;
  if (!mesh.backBlocks) return end - begin;
  if (end - begin == kPolygonsPerBlock) {
    // Whole back-face blocks: their flags (0 or 1, ViewCulling.cpp) counted by words.
    constexpr std::size_t kBackBlocksPerBlock = kPolygonsPerBlock / kPolygonsPerBackBlock;
    static_assert(kBackBlocksPerBlock % sizeof(std::uint32_t) == 0);
    std::size_t skipped = 0;
    for (std::size_t i = 0; i < kBackBlocksPerBlock; i += sizeof(std::uint32_t)) {
      std::uint32_t flags;
      std::memcpy(&flags, mesh.backBlocks + (begin >> kBackBlockBits) + i, sizeof flags);
      skipped += (flags * 0x01010101u) >> 24;
    }
    return kPolygonsPerBlock - kPolygonsPerBackBlock * skipped;
  }
  std::size_t work = 0;
  for (std::size_t b = begin; b < end; b += kPolygonsPerBackBlock) {
    if (!mesh.backBlocks[b >> kBackBlockBits]) work += std::min(kPolygonsPerBackBlock, end - b);
  }
  return work;
}

// All of `mesh`'s polygons set up polygon by polygon.
std::size_t polygonsSetUp(const FrameMesh& mesh) {
  const std::size_t count = mesh.mesh().polygons.count;
  if (!mesh.visibleBlocks && !mesh.backBlocks) return count;
  std::size_t work = 0;
  for (std::size_t begin = 0; begin < count; begin += kPolygonsPerBlock)
    work += polygonsSetUp(mesh, begin, std::min(count, begin + kPolygonsPerBlock));
  return work;
}

// Splits each mesh into chunks of about `workPerChunk` polygons set up (polygonsSetUp: the
// blocks skipped whole cost next to nothing, so a chunk of a closed mesh's far side would
// otherwise finish at once while one of its near side holds up the phase), cut at view-culling
// block boundaries (a serial loop: ~2,000 steps at 2M polygons), each of at least
// kMinPolygonsPerChunk polygons (but a mesh's last) and at most kMaxPolygonsPerChunk; in global
// polygon ids (the draw positions of z-buffer order).
void splitByWork(std::span<const FrameMesh> meshes, std::size_t workPerChunk,
                 std::vector<MeshRange>& ranges) {
  static_assert(kMinPolygonsPerChunk % kPolygonsPerBlock == 0 &&
                kMaxPolygonsPerChunk % kPolygonsPerBlock == 0);
  ranges.clear();
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const FrameMesh& mesh = meshes[m];
    const std::size_t count = mesh.mesh().polygons.count;
    std::size_t begin = 0, work = 0;
    for (std::size_t end = 0; end < count;) {
      const std::size_t blockEnd = std::min(count, end + kPolygonsPerBlock);
      work += polygonsSetUp(mesh, end, blockEnd);
      end = blockEnd;
      const std::size_t polygons = end - begin;
      if (end == count || polygons == kMaxPolygonsPerChunk ||
          (work >= workPerChunk && polygons >= kMinPolygonsPerChunk)) {
        ranges.push_back({m, mesh.firstPolygon + begin, mesh.firstPolygon + end});
        begin = end;
        work = 0;
      }
    }
  }
}

// The chunks' ranges of draw positions: about four chunks per thread of equal work.
void planChunks(const SetupContext& context, int threads, SetupBuffers& buffers) {
  const std::size_t chunksWanted = 4 * static_cast<std::size_t>(threads);
  std::vector<MeshRange>& ranges = buffers.ranges;
  ranges.clear();
  if (!context.order.ids.empty()) {
    const std::size_t polygons = context.meshes.empty() ? 0 : context.meshes.back().endPolygon();
    const std::size_t perChunk = std::clamp<std::size_t>(
        polygons / chunksWanted + 1, kMinPolygonsPerChunk, kMaxPolygonsPerChunk);
    for (std::size_t begin = 0; begin < polygons; begin += perChunk)
      ranges.push_back({0, begin, std::min(polygons, begin + perChunk)});
  } else {
    std::size_t work = 0;
    for (const FrameMesh& mesh : context.meshes)
      work += polygonsSetUp(mesh);
    splitByWork(context.meshes, work / chunksWanted + 1, ranges);
  }
  std::vector<Chunk>& chunks = buffers.chunks;
  chunks.resize(ranges.size());
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    chunks[i].counts = {};  // an aborted render leaves chunks unvisited
    chunks[i].begin = ranges[i].begin;
    chunks[i].end = ranges[i].end;
  }
}

}  // namespace

namespace {
std::atomic<bool> frontPassConeSkip{[] {
  const char* value = std::getenv("FACET_FRONT_PASS_CONE");
  return value == nullptr || std::string_view(value) != "0";
}()};
}  // namespace

void enableFrontPassConeSkip(bool on) {
  frontPassConeSkip = on;
}

bool frontPassConeSkipEnabled() {
  return frontPassConeSkip;
}

const char* setupRoutineName(bool skipBackFaces) {
  return skipBackFaces ? "back faces skipped" : "back faces drawn";
}

namespace {
std::atomic<SetupWatch> setupWatch{nullptr};

void callSetupWatch(std::span<const Chunk> chunks) {
  if (const SetupWatch watch = setupWatch.load(std::memory_order_relaxed)) watch(chunks);
}
}  // namespace

void watchSetup(SetupWatch watch) {
  setupWatch = watch;
}

bool setUpPolygons(PhaseRunner& runner, const SetupContext& context, int threads,
                   SetupBuffers& buffers) {
  planChunks(context, threads, buffers);
  const bool completed = runner.run(Phase::Setup, buffers.chunks.size(),
                                    [&](std::size_t i) { setUpChunk(context, buffers.chunks[i]); });
  // Here, on the caller's thread, before any tile reads a wrapped index.
  for (const Chunk& chunk : buffers.chunks)
    requireChunkIndexable(chunk);
  callSetupWatch(buffers.chunks);
  return completed;
}

bool setUpBackFaces(PhaseRunner& runner, const SetupContext& context, SetupBuffers& buffers) {
  runner.runUnreported(buffers.chunks.size(),
                       [&](std::size_t i) { setUpChunkBack(context, buffers.chunks[i]); });
  for (const Chunk& chunk : buffers.chunks)
    requireChunkIndexable(chunk);
  callSetupWatch(buffers.chunks);
  return true;
}

void reportHiddenBlocks(std::span<const Chunk> chunks, RenderPlan& plan) {
  plan.blocksHiddenBehindFront = plan.polygonsHiddenBehindFront = 0;
  for (const Chunk& chunk : chunks) {
    plan.blocksHiddenBehindFront += chunk.counts.hiddenBlocks;
    plan.polygonsHiddenBehindFront += chunk.counts.hiddenBlockPolygons;
  }
}

void addSetupCounts(std::span<const Chunk> chunks, RenderStats& stats) {
  for (const Chunk& chunk : chunks) {
    stats.polygonsDrawn += chunk.counts.drawn;
    stats.polygonsCulled += chunk.counts.culled;
    stats.polygonsOutside += chunk.counts.outside;
    stats.polygonsDegenerate += chunk.counts.degenerate;
    stats.polygonsNonFinite += chunk.counts.nonFinite;
    stats.polygonsHidden += chunk.counts.hiddenBlockPolygons;
    stats.trianglesBinned += chunk.counts.trianglesBinned;
    stats.trianglesClipped += chunk.counts.trianglesClipped;
  }
}

}  // namespace facet::detail
