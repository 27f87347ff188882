// The raster's paths against each other, and the shown flags it hands to the shade phase.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../support/RandomCorners.h"
#include "../support/SquarePlanes.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "RasterTriangle.h"
#include "facet/Renderer.h"

namespace facet::testing {
namespace {

using detail::PixelBounds;
using detail::WindowVertex;

// A 32 × 32 image's depth keys and polygon ids.
using Planes32 = SquarePlanes<32>;

// What a stream of triangles painted through one path.
struct Painted {
  Planes32 planes;
  detail::PaintCounts counts;
};

// The pixels where two images differ (key bits or id); the first few reported.
std::size_t differingKeysOrIds(const Planes32& small, const Planes32& walked) {
  std::size_t differing = 0;
  for (std::size_t i = 0; i < small.depth.size(); ++i) {
    if (small.ids[i] == walked.ids[i] && std::bit_cast<std::uint32_t>(small.depth[i]) ==
                                             std::bit_cast<std::uint32_t>(walked.depth[i])) {
      continue;
    }
    if (++differing <= 5) {
      ADD_FAILURE() << "pixel (" << i % Planes32::kSide << ", " << i / Planes32::kSide
                    << "): small-box path id " << small.ids[i] << " key " << small.depth[i]
                    << ", box walk id " << walked.ids[i] << " key " << walked.depth[i];
    }
  }
  return differing;
}

// paintTriangle (with its small-box path) against the box walk it replaces for boxes of at
// most 4 × 4 samples: a random stream of small triangles (residues, steep and flat depth
// planes, no polygon-boundary edge or random ones, many polygon ids), and slivers whose
// bounding box is wider than the lanes' 64 pixels but whose samples in the tile are few (the
// tile's corner cuts them: they go to the walk), painted into a tile that is not at the
// image's origin, in runs of 200 (the planes compared, then cleared). The same keys, ids and
// counts, with and without the depth test, and with the depth test and the reject of hidden
// triangles (losesEverywhere) too; and through SmallTriangle records (smallTriangleOf,
// paintSmallTriangle: what the set-up's lanes hand the tiles) for the triangles that have one.
template <detail::DepthMode kMode>
void compareSmallBoxPath(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> corner(4 * 256, 28 * 256), spread(1, 5 * 256), polygon(0, 99),
      kind(0, 9), mask(0, 13);
  std::uniform_real_distribution<float> key(0.1f, 0.9f);
  const PixelBounds tile{8, 4, 27, 23};
  Painted small, walked, rejecting, recorded;
  std::size_t painted = 0, slivers = 0, records = 0, differing = 0;
  for (int t = 0; t < 40000; ++t) {
    WindowVertex v[3];
    const bool sliver = kind(random) == 0;
    const int cx = corner(random), cy = corner(random), size = spread(random);
    const float base = key(random);
    randomCornersAround(random, cx, cy, size, base, t % 3 == 0, v);
    if (sliver) {  // one corner 100 pixels away, down and to the left of the tile
      v[0].x = tile.x0 * 256 - 100 * 256 + cx % 256;
      v[0].y = tile.y0 * 256 - 100 * 256 + cy % 256;
    }
    const std::int64_t area = detail::doubleSignedArea(v[0], v[1], v[2]);
    if (area != 0) {
      if (area < 0) std::swap(v[1], v[2]);
      const std::int32_t id = polygon(random);
      const auto boundary = static_cast<detail::EdgeMask>(std::max(0, mask(random) - 6));
      detail::paintTriangle<kMode>(v[0], v[1], v[2], boundary, id, tile, small.planes.planes(),
                                   small.counts);
      detail::paintTriangleWalkingBox<kMode>(v[0], v[1], v[2], boundary, id, tile,
                                             walked.planes.planes(), walked.counts);
      if constexpr (kMode == detail::DepthMode::Test) {
        detail::paintTriangle<kMode, true>(v[0], v[1], v[2], boundary, id, tile,
                                           rejecting.planes.planes(), rejecting.counts);
      }
      const auto record = detail::smallTriangleOf(v[0], v[1], v[2], boundary, tile, id);
      if (record) {
        detail::paintSmallTriangle<kMode>(*record, recorded.planes.planes(), recorded.counts);
      } else {
        detail::paintTriangle<kMode>(v[0], v[1], v[2], boundary, id, tile, recorded.planes.planes(),
                                     recorded.counts);
      }
      ++painted;
      records += record.has_value();
      slivers += sliver;
    }
    if (t % 200 == 199) {
      differing += differingKeysOrIds(small.planes, walked.planes);
      differing += differingKeysOrIds(recorded.planes, walked.planes);
      if (kMode == detail::DepthMode::Test)
        differing += differingKeysOrIds(rejecting.planes, walked.planes);
      small.planes = walked.planes = rejecting.planes = recorded.planes = Planes32{};
    }
  }
  EXPECT_GT(painted, 35000u);
  EXPECT_GT(slivers, 3000u);
  EXPECT_GT(records, 4000u);
  EXPECT_GT(walked.counts.written, 20000u);
  EXPECT_EQ(small.counts.written, walked.counts.written);
  EXPECT_EQ(small.counts.covered, walked.counts.covered);
  EXPECT_EQ(recorded.counts.written, walked.counts.written);
  EXPECT_EQ(recorded.counts.covered, walked.counts.covered);
  if (kMode == detail::DepthMode::Test) {
    EXPECT_EQ(rejecting.counts.written, walked.counts.written);
    EXPECT_EQ(rejecting.counts.covered, walked.counts.covered);
  }
  EXPECT_EQ(differing, 0u);
}

TEST(Raster, SmallBoxPathPaintsWhatTheBoxWalkPaintsWithTheDepthTest) {
  compareSmallBoxPath<detail::DepthMode::Test>(3);
}

TEST(Raster, SmallBoxPathPaintsWhatTheBoxWalkPaintsInPaintersOrder) {
  compareSmallBoxPath<detail::DepthMode::Overwrite>(5);
}

// paintSmallMask, row by row (paintTriangle's small-box path) and by bits (the small records:
// one loop over the mask's bits, each row's four keys made at once), against stepping the key
// sample by sample along each row, as BoxRaster::paintRows does: every coverage mask of a
// 4 × 4 box, keys whose steps round (a key per pixel that is no power of two, rows far apart),
// in both modes: the same key bits, ids and counts.
template <bool kByBits>
void compareSmallMaskWithStepping() {
  using Planes8 = SquarePlanes<8>;
  constexpr int kX0 = 3, kY0 = 2;
  const double keyPerPixel = 0.1 + 1e-9, firstKey = 1234.567;
  const auto rowKey = [&](int y) { return firstKey + 0.3 * static_cast<double>(y * 77 + 5); };
  // The key's low 20 bits as the written key, exact in a float: a step rounded otherwise than
  // stepping rounds it shows (the float key of the double would hide most).
  const auto lowBits = [](double key, int, int) {
    return static_cast<double>(std::bit_cast<std::uint64_t>(key) & 0xfffffu);
  };
  std::size_t differing = 0;
  for (std::uint32_t mask = 0; mask < (1u << 16); ++mask) {
    Planes8 painted, stepped;
    detail::PaintCounts counts;
    if (mask % 2 == 0) {
      detail::paintSmallMask<detail::DepthMode::Overwrite, kByBits>(
          mask, kX0, kY0, keyPerPixel, rowKey, lowBits, 7, painted.planes(), counts);
    } else {
      detail::paintSmallMask<detail::DepthMode::Test, kByBits>(
          mask, kX0, kY0, keyPerPixel, rowKey, lowBits, 7, painted.planes(), counts);
    }
    std::size_t written = 0;
    for (int y = 0; y < detail::kSmallSide; ++y) {
      double key = rowKey(y);
      for (int x = 0; x < detail::kSmallSide; ++x, key += keyPerPixel) {
        if ((mask >> (y * detail::kSmallSide + x) & 1u) == 0) continue;
        const std::size_t i = static_cast<std::size_t>(kY0 + y) * Planes8::kSide + kX0 + x;
        stepped.depth[i] = detail::toDepthKey(lowBits(key, x, y));
        stepped.ids[i] = 7;
        ++written;
      }
    }
    EXPECT_EQ(counts.written, written) << "mask " << mask;
    for (std::size_t i = 0; i < stepped.depth.size(); ++i) {
      if (painted.ids[i] != stepped.ids[i] || std::bit_cast<std::uint32_t>(painted.depth[i]) !=
                                                  std::bit_cast<std::uint32_t>(stepped.depth[i])) {
        if (++differing <= 5) ADD_FAILURE() << "mask " << mask << ", pixel " << i;
      }
    }
  }
  EXPECT_EQ(differing, 0u);
}

TEST(Raster, SmallMaskPaintsTheSteppedKeysOfEveryMaskRowByRow) {
  compareSmallMaskWithStepping<false>();
}

TEST(Raster, SmallMaskPaintsTheSteppedKeysOfEveryMaskByBits) {
  compareSmallMaskWithStepping<true>();
}

// The box walk's own test of the samples surely inside a triangle's polygon-boundary edges
// (BoxRaster::paintRows: the samples' biased edge values against TriangleDepth::refine()'s
// bounds, the samples near an edge keyed out of line) against refine() asked for every
// covered sample (paintTriangleRefiningEverySample): a random stream of triangles up to 20
// pixels across, most boxes walked (residues, steep and flat depth planes, slivers, each
// polygon-boundary mask and the clamped back faces' kClampedEdges), in runs of 100. The same
// keys, ids and counts, with and without the depth test, and with the reject of hidden
// triangles too. Many covered samples lie within refine()'s bound of an edge (the vertices on
// the 1/256-pixel grid, the samples on its half pixels): the out-of-line keys are compared.
template <detail::DepthMode kMode>
void compareWalkRefiningEverySample(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> corner(4 * 256, 28 * 256), spread(1, 10 * 256), polygon(0, 99),
      kind(0, 9), mask(0, 8);
  std::uniform_real_distribution<float> key(0.1f, 0.9f);
  const PixelBounds tile{8, 4, 27, 23};
  Painted walked, reference, rejecting;
  std::size_t painted = 0, slivers = 0, boundaries = 0, differing = 0;
  for (int t = 0; t < 20000; ++t) {
    WindowVertex v[3];
    const bool sliver = kind(random) == 0;
    const int cx = corner(random), cy = corner(random), size = spread(random);
    const float base = key(random);
    randomCornersAround(random, cx, cy, size, base, t % 3 == 0, v);
    if (sliver) {  // one corner far away: a long thin triangle across the tile
      v[0].x = cx + (t % 2 ? 60 : -60) * 256;
      v[0].y = cy + (t % 4 < 2 ? 45 : -45) * 256;
    }
    const std::int64_t area = detail::doubleSignedArea(v[0], v[1], v[2]);
    if (area == 0) continue;
    if (area < 0) std::swap(v[1], v[2]);
    const std::int32_t id = polygon(random);
    const int m = mask(random);
    const auto boundary = static_cast<detail::EdgeMask>(m == 8 ? detail::kClampedEdges : m);
    detail::paintTriangle<kMode>(v[0], v[1], v[2], boundary, id, tile, walked.planes.planes(),
                                 walked.counts);
    detail::paintTriangleRefiningEverySample<kMode>(v[0], v[1], v[2], boundary, id, tile,
                                                    reference.planes.planes(), reference.counts);
    if constexpr (kMode == detail::DepthMode::Test) {
      detail::paintTriangle<kMode, true>(v[0], v[1], v[2], boundary, id, tile,
                                         rejecting.planes.planes(), rejecting.counts);
    }
    ++painted;
    slivers += sliver;
    boundaries += boundary != 0;
    if (t % 100 == 99) {
      differing += differingKeysOrIds(walked.planes, reference.planes);
      if (kMode == detail::DepthMode::Test)
        differing += differingKeysOrIds(rejecting.planes, reference.planes);
      walked.planes = reference.planes = rejecting.planes = Planes32{};
    }
  }
  EXPECT_GT(painted, 15000u);
  EXPECT_GT(slivers, 1500u);
  EXPECT_GT(boundaries, 12000u);
  EXPECT_GT(reference.counts.written, 80000u);
  EXPECT_EQ(walked.counts.written, reference.counts.written);
  EXPECT_EQ(walked.counts.covered, reference.counts.covered);
  if (kMode == detail::DepthMode::Test) {
    EXPECT_EQ(rejecting.counts.written, reference.counts.written);
    EXPECT_EQ(rejecting.counts.covered, reference.counts.covered);
  }
  EXPECT_EQ(differing, 0u);
}

TEST(Raster, BoxWalkKeysTheSamplesNearBoundaryEdgesAsRefineDoesWithTheDepthTest) {
  compareWalkRefiningEverySample<detail::DepthMode::Test>(5);
}

TEST(Raster, BoxWalkKeysTheSamplesNearBoundaryEdgesAsRefineDoesInPaintersOrder) {
  compareWalkRefiningEverySample<detail::DepthMode::Overwrite>(6);
}

// The shown flags are the polygons of the final image: the far squares of a stack listed far
// to near each win every pixel they cover and lose all of them to the next; only the nearest
// is shown, and exactly the ids in the image are flagged, for any thread count.
TEST(Raster, ShownPolygonsAreThoseOfTheFinalImage) {
  const Mesh stack = makeStackedSquares(4, 6, false);
  const Scene scene = oneMeshScene(stack.view());
  const Camera camera = fitCamera(stack);
  for (const int threads : {1, 2, 3}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    Renderer renderer;
    renderer.setThreadCount(threads);
    Framebuffer framebuffer(200, 150);
    const RenderStats stats = renderer.render(scene, camera, framebuffer);
    ASSERT_GT(stats.fragmentsWritten, 2 * stats.pixelsCovered) << "the premise: overdraw";
    std::set<std::int32_t> inImage;
    for (const std::int32_t id : framebuffer.polygonId())
      if (id != Framebuffer::kBackgroundId) inImage.insert(id);
    const std::span<const std::uint8_t> shown = renderer.shownPolygons();
    ASSERT_EQ(shown.size(), stack.polygonCount());
    std::size_t flagged = 0;
    for (std::size_t id = 0; id < shown.size(); ++id) {
      flagged += shown[id] != 0;
      EXPECT_EQ(shown[id] != 0, inImage.count(static_cast<std::int32_t>(id)) == 1)
          << "polygon " << id;
    }
    EXPECT_EQ(flagged, 36u) << "the nearest square's 6 × 6 cells";
  }
}

// Tiles are painted in a tile-sized buffer and streamed to the image's planes 16 bytes at a
// time where the row allows (Raster.cpp, TilePlanes): at widths whose rows are not 16-byte
// multiples and tiles cut by the image's edges, every pixel still reaches the image: covered
// by a square over the whole view, then cleared around a triangle over pixel (0, 0) alone
// (the same framebuffer).
TEST(Raster, EveryPixelReachesTheImageAtAnyWidth) {
  for (const auto& [width, height] : {std::pair{101, 37}, {67, 130}, {3, 1}, {130, 65}}) {
    SCOPED_TRACE(std::to_string(width) + " x " + std::to_string(height));
    const double w = width, h = height;
    Mesh square;
    for (const glm::dvec3& p : {glm::dvec3{-5.0, -5.0, 0.0}, glm::dvec3{w + 5.0, -5.0, 0.0},
                                glm::dvec3{w + 5.0, h + 5.0, 0.0}, glm::dvec3{-5.0, h + 5.0, 0.0}})
      square.addPoint(p);
    square.addPolygon({0, 1, 2, 3});
    Mesh corner;
    for (const glm::dvec3& p :
         {glm::dvec3{0.2, 0.2, 0.0}, glm::dvec3{0.8, 0.2, 0.0}, glm::dvec3{0.5, 0.8, 0.0}})
      corner.addPoint(p);
    corner.addPolygon({0, 1, 2});
    Renderer renderer;
    renderer.setThreadCount(2);
    Framebuffer framebuffer(width, height);
    const auto ids = [&framebuffer](std::int32_t id) {
      return std::count(framebuffer.polygonId().begin(), framebuffer.polygonId().end(), id);
    };
    renderer.render(oneMeshScene(square.view()), pixelCamera(width, height), framebuffer);
    EXPECT_EQ(ids(0), width * height);
    renderer.render(oneMeshScene(corner.view()), pixelCamera(width, height), framebuffer);
    EXPECT_EQ(framebuffer.polygonId()[0], 0);
    EXPECT_EQ(ids(Framebuffer::kBackgroundId), width * height - 1);
  }
}

// Pairs of triangles on the same points (each its own copy: the mesh is open, so every face is
// drawn), one facing the viewer and one its back, in the plane z = 0 that a parallel camera
// sees square on: every key of both is the same, an exact tie at every pixel they cover. Sizes
// from below a pixel (fragments) to 40 pixels (triangles over several tiles); `backFirst`
// lists each pair's back face first. Returns the mesh and, per polygon id, whether it faces
// the viewer.
std::pair<Mesh, std::vector<bool>> tiedPairs(bool backFirst) {
  std::mt19937 random(17);
  std::uniform_real_distribution<double> x(2.0, 190.0), y(2.0, 126.0), size(0.3, 40.0),
      corner(-1.0, 1.0);
  Mesh mesh;
  std::vector<bool> front;
  for (int pair = 0; pair < 300; ++pair) {
    const glm::dvec3 center{x(random), y(random), 0.0};
    const double s = size(random);
    glm::dvec3 corners[3];
    for (glm::dvec3& c : corners)
      c = center + glm::dvec3{s * corner(random), s * corner(random), 0.0};
    const glm::dvec3 normal = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    if (normal.z < 0.0) std::swap(corners[1], corners[2]);  // counter-clockwise: the front
    for (const bool isFront : {!backFirst, backFirst}) {
      const std::int64_t a = mesh.addPoint(corners[0]);
      const std::int64_t b = mesh.addPoint(corners[isFront ? 1 : 2]);
      const std::int64_t c = mesh.addPoint(corners[isFront ? 2 : 1]);
      mesh.addPolygon({a, b, c});
      front.push_back(isFront);
    }
  }
  return {std::move(mesh), std::move(front)};
}

// With the depth test an exact tie keeps the front face, whichever of the two was listed
// first (RasterTriangle.h, writeFragment): the back faces are painted after every front face
// of the tile. The same bytes for 1, 2 and 8 threads.
TEST(Raster, AnExactDepthTieKeepsTheFrontFaceInEitherOrder) {
  const Camera camera = pixelCamera(192, 128);
  for (const bool backFirst : {false, true}) {
    SCOPED_TRACE(backFirst ? "back faces listed first" : "front faces listed first");
    const auto [mesh, front] = tiedPairs(backFirst);
    const Scene scene = oneMeshScene(mesh.view());
    std::optional<Rendered> oneThread;
    for (const int threads : {1, 2, 8}) {
      SCOPED_TRACE(std::to_string(threads) + " threads");
      Rendered r = renderScene(scene, camera, 192, 128, {.threads = threads});
      ASSERT_EQ(r.stats.polygonsCulled, 0u) << "the premise: every face drawn";
      std::size_t covered = 0, backShown = 0;
      for (const std::int32_t id : r.framebuffer.polygonId()) {
        if (id == Framebuffer::kBackgroundId) continue;
        ++covered;
        backShown += !front[static_cast<std::size_t>(id)];
      }
      EXPECT_GT(covered, 5000u);
      EXPECT_EQ(backShown, 0u) << "pixels showing a back face, of " << covered;
      if (oneThread) {
        EXPECT_EQ(differingPixels(r.framebuffer, oneThread->framebuffer), 0u)
            << "not the bytes of one thread";
      } else {
        oneThread = std::move(r);
      }
    }
  }
}

}  // namespace
}  // namespace facet::testing
