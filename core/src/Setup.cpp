// Phase 2 of a render: everything that happens once per polygon.

#include <algorithm>
#include <span>
#include <utility>

#include <glm/geometric.hpp>

#include "Clipper.h"
#include "Frame.h"
#include "facet/PolygonNormal.h"

namespace facet::detail {
namespace {

// Why a polygon's triangles were dropped, to count the polygon once under one reason.
struct Tally {
  int zeroArea = 0, culled = 0, outside = 0;
};

template <class PointsT, class PolygonsT>
class PolygonSetup {
 public:
  PolygonSetup(FrameState& frame, Chunk& chunk, const FrameMesh& mesh, PointsT points,
               PolygonsT polygons)
      : frame_(frame),
        chunk_(chunk),
        mesh_(mesh),
        material_(mesh.source->material),
        points_(points),
        polygons_(polygons),
        meshVertices_(frame.vertices.data() + mesh.firstVertex) {}

  void run(std::size_t polygon) {
    polygon_ = polygon;
    polygonId_ = static_cast<std::int32_t>(mesh_.firstPolygon + polygon);
    const std::size_t n = polygons_.size(polygon);
    if (n < 3) {
      ++chunk_.counts.degenerate;
      return;
    }
    std::uint32_t any = 0, all = ~0u;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t code = meshVertices_[polygons_.pointId(polygon, k)].outcode;
      any |= code;
      all &= code;
    }
    if (any & kNonFinite) {
      ++chunk_.counts.nonFinite;
      return;
    }
    if (all != kInside) {
      ++chunk_.counts.outside;
      return;
    }

    std::optional<glm::dvec3> normal;
    if (n > 3 || frame_.plan.directLighting) {
      gatherCorners(n);
      normal = newellNormal(std::span<const glm::dvec3>(chunk_.corners));
      if (!normal) {
        ++chunk_.counts.degenerate;
        return;
      }
    }

    const std::size_t first = chunk_.triangles.size();
    Tally tally;
    if (n == 3) {
      addTriangle(0, 1, 2, tally);
    } else {
      triangulate(*normal, tally);
    }
    if (chunk_.triangles.size() == first) {
      countDropped(tally);
      return;
    }
    finishPolygon(first, shade(normal));
  }

 private:
  std::size_t pointId(std::size_t corner) const { return polygons_.pointId(polygon_, corner); }

  void gatherCorners(std::size_t n) {
    chunk_.corners.clear();
    for (std::size_t k = 0; k < n; ++k) chunk_.corners.push_back(points_[pointId(k)]);
  }

  void triangulate(const glm::dvec3& normal, Tally& tally) {
    std::vector<glm::dvec2>& projected = chunk_.triangulation.projected;
    projectToPolygonPlane(chunk_.corners, normal, projected);
    if (isConvex(projected)) {
      for (std::uint32_t k = 1; k + 1 < projected.size(); ++k) addTriangle(0, k, k + 1, tally);
      return;
    }
    chunk_.localTriangles.clear();
    earClip(projected, chunk_.triangulation, chunk_.localTriangles);
    for (const LocalTriangle& t : chunk_.localTriangles) addTriangle(t[0], t[1], t[2], tally);
  }

  // One triangle of the polygon, by corner index: kept whole, clipped, or dropped.
  void addTriangle(std::uint32_t c0, std::uint32_t c1, std::uint32_t c2, Tally& tally) {
    const std::size_t ids[3] = {pointId(c0), pointId(c1), pointId(c2)};
    const std::uint32_t codes[3] = {meshVertices_[ids[0]].outcode, meshVertices_[ids[1]].outcode,
                                    meshVertices_[ids[2]].outcode};
    const std::uint32_t any = codes[0] | codes[1] | codes[2];
    if (any == kInside) {
      keep(frameIndex(ids[0]), frameIndex(ids[1]), frameIndex(ids[2]), tally);
    } else if ((codes[0] & codes[1] & codes[2]) != kInside) {
      ++tally.outside;
    } else {
      clip(ids, any, tally);
    }
  }

  std::uint32_t frameIndex(std::size_t pointId) const {
    return static_cast<std::uint32_t>(mesh_.firstVertex + pointId);
  }

  void clip(const std::size_t (&ids)[3], std::uint32_t planes, Tally& tally) {
    ++chunk_.counts.trianglesClipped;
    const FrameTransform& transform = *frame_.transform;
    ClipVertex triangle[3];
    for (int i = 0; i < 3; ++i) {
      triangle[i] = {transform.toClip(points_[ids[i]]), frameIndex(ids[i])};
    }
    ClipVertex clipped[kMaxClippedVertices];
    const int count = clipTriangle(transform, triangle, planes, clipped);
    if (count == 0) {
      ++tally.outside;
      return;
    }
    std::uint32_t references[kMaxClippedVertices];
    for (int i = 0; i < count; ++i) {
      if (clipped[i].source != ClipVertex::kNewVertex) {
        references[i] = clipped[i].source;  // an input corner: keep its snapped coordinates
      } else {
        references[i] =
            static_cast<std::uint32_t>(chunk_.clippedVertices.size()) | kClippedVertexBit;
        chunk_.clippedVertices.push_back(transform.toWindow(clipped[i].clip));
      }
    }
    for (int i = 1; i + 1 < count; ++i) keep(references[0], references[i], references[i + 1], tally);
  }

  // Keeps a triangle whose corners all have window coordinates, unless it has zero area,
  // is a culled back face, or covers no pixel center's bounding box.
  void keep(std::uint32_t r0, std::uint32_t r1, std::uint32_t r2, Tally& tally) {
    const WindowVertex& a = frame_.vertex(chunk_, r0);
    const WindowVertex* b = &frame_.vertex(chunk_, r1);
    const WindowVertex* c = &frame_.vertex(chunk_, r2);
    const std::int64_t area = doubleSignedArea(a, *b, *c);
    if (area == 0) {
      ++tally.zeroArea;
      return;
    }
    if (area < 0) {
      if (material_.backfaceCulling) {
        ++tally.culled;
        return;
      }
      std::swap(r1, r2);
      std::swap(b, c);
    }
    const PixelBounds bounds = samplesInBoundingBox(a, *b, *c, frame_.viewport);
    if (bounds.empty()) {
      ++tally.outside;
      return;
    }
    chunk_.triangles.push_back({{r0, r1, r2}, polygonId_, Rgba8{}});
    chunk_.pendingBounds.push_back(bounds);
  }

  void countDropped(const Tally& tally) {
    if (tally.culled > 0 && tally.outside == 0) {
      ++chunk_.counts.culled;
    } else if (tally.zeroArea > 0 && tally.outside == 0) {
      ++chunk_.counts.degenerate;
    } else {
      ++chunk_.counts.outside;
    }
  }

  Color surfaceColor() const {
    const auto& colors = mesh_.source->mesh.polygonColors;
    if (colors.empty()) return material_.color;
    const Rgba8 c = colors[polygon_];
    return Color(c.r, c.g, c.b) / 255.0f;
  }

  // Flat shading: once per polygon, at its center (Sixth 3D's shadedColor).
  Rgba8 shade(const std::optional<glm::dvec3>& normal) const {
    if (mesh_.uniformColor) return *mesh_.uniformColor;
    SurfaceSample sample;
    sample.color = surfaceColor();
    if (frame_.plan.directLighting) {
      if (frame_.plan.polygonCenters) {
        glm::dvec3 sum(0.0);
        for (const glm::dvec3& corner : chunk_.corners) sum += corner;
        sample.position = sum / static_cast<double>(chunk_.corners.size());
      }
      sample.normal = *normal;
      if (frame_.plan.viewerDirection) sample.toViewer = frame_.transform->toViewer(sample.position);
      if (frame_.twoSidedLighting && glm::dot(sample.normal, sample.toViewer) < 0.0) {
        sample.normal = -sample.normal;
      }
    }
    return toRgba8(frame_.shader.shade(sample, material_));
  }

  void finishPolygon(std::size_t first, Rgba8 color) {
    const int tilesX = frame_.plan.tilesX;
    for (std::size_t i = first; i < chunk_.triangles.size(); ++i) {
      chunk_.triangles[i].color = color;
      const PixelBounds& b = chunk_.pendingBounds[i - first];
      for (int ty = b.y0 / kTileSize; ty <= b.y1 / kTileSize; ++ty) {
        for (int tx = b.x0 / kTileSize; tx <= b.x1 / kTileSize; ++tx) {
          chunk_.bins[static_cast<std::size_t>(ty) * tilesX + tx].push_back(
              static_cast<std::uint32_t>(i));
        }
      }
    }
    chunk_.counts.trianglesBinned += chunk_.triangles.size() - first;
    chunk_.pendingBounds.clear();
    ++chunk_.counts.drawn;
  }

  FrameState& frame_;
  Chunk& chunk_;
  const FrameMesh& mesh_;
  const Material& material_;
  PointsT points_;
  PolygonsT polygons_;
  const WindowVertex* meshVertices_;
  std::size_t polygon_ = 0;
  std::int32_t polygonId_ = 0;
};

}  // namespace

std::size_t FrameState::meshOfPolygon(std::size_t polygonId) const {
  // upper_bound over firstPolygon: the last mesh starting at or before the id.
  const auto after = std::upper_bound(
      meshes.begin(), meshes.end(), polygonId,
      [](std::size_t id, const FrameMesh& mesh) { return id < mesh.firstPolygon; });
  return static_cast<std::size_t>(after - meshes.begin()) - 1;
}

void setUpChunk(FrameState& frame, Chunk& chunk) {
  chunk.triangles.clear();
  chunk.clippedVertices.clear();
  for (auto& bin : chunk.bins) bin.clear();
  chunk.counts = {};
  // Draw positions come in runs that share a mesh (the whole chunk, in z-buffer mode);
  // each run is set up by code specialized for that mesh's point and index types.
  std::size_t position = chunk.begin;
  while (position < chunk.end) {
    const std::size_t meshIndex = frame.meshOfPolygon(frame.polygonAt(position));
    const FrameMesh& mesh = frame.meshes[meshIndex];
    const std::size_t meshEnd = mesh.firstPolygon + mesh.source->mesh.polygons.count;
    withTypedMesh(mesh.source->mesh, [&](auto points, auto polygons) {
      PolygonSetup setup(frame, chunk, mesh, points, polygons);
      for (; position < chunk.end; ++position) {
        const std::size_t id = frame.polygonAt(position);
        if (id < mesh.firstPolygon || id >= meshEnd) break;
        setup.run(id - mesh.firstPolygon);
      }
    });
  }
}

}  // namespace facet::detail
