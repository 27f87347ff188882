// Depth that resolves what double precision can (issue 7): two parallel surfaces a small
// fraction of their eye distance apart resolve at every far/near ratio, whichever is drawn
// first; a tiny near plane still draws; exact ties keep the polygon drawn first; the Depth
// output keeps VTK's window-depth convention.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../support/RandomCorners.h"
#include "../support/Sanitizers.h"
#include "../support/SquarePlanes.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "RasterTriangle.h"

namespace facet::testing {
namespace {

constexpr double kEyeDistance = 3.0;
constexpr int kWidth = 320, kHeight = 240;

// A square of side 40 in the plane through `center` with unit normal `normal` (counter-
// clockwise about it), shifted by `shift` within the plane, appended to `mesh` as one
// polygon.
void addSquare(Mesh& mesh, const glm::dvec3& center, const glm::dvec3& normal,
               glm::dvec2 shift = {0.0, 0.0}) {
  const glm::dvec3 u = glm::normalize(glm::cross(normal, glm::dvec3(1, 0, 0)));
  const glm::dvec3 v = glm::cross(normal, u);
  const std::int64_t base = static_cast<std::int64_t>(mesh.points.size());
  for (const auto& [s, t] : {std::pair{-20.0, -20.0}, {20.0, -20.0}, {20.0, 20.0}, {-20.0, 20.0}})
    mesh.addPoint(center + (s + shift.x) * u + (t + shift.y) * v);
  mesh.addPolygon({base, base + 1, base + 2, base + 3});
}

// Camera at the origin looking down −z; the clipping range has far/near = `ratio` and either
// a tiny near plane (far = 10·D) or a huge far plane (near = D/10).
Camera cameraWithRatio(double ratio, bool tinyNear, bool parallel) {
  Camera camera;
  camera.position = {0, 0, 0};
  camera.focalPoint = {0, 0, -1};
  camera.parallelProjection = parallel;
  camera.parallelScale = 1.0;
  camera.farClip = tinyNear ? 10.0 * kEyeDistance : 0.1 * kEyeDistance * ratio;
  camera.nearClip = camera.farClip / ratio;
  return camera;
}

std::string describe(double separation, double ratio, bool tinyNear, bool parallel) {
  return "separation " + std::to_string(separation) + " of the eye distance, far/near " +
         std::to_string(ratio) + (tinyNear ? ", tiny near" : ", huge far") +
         (parallel ? ", parallel" : ", perspective");
}

// Renders the scene of two meshes (0 drawn first; closed: marked MeshView::closedSurface)
// and counts the covered pixels that do not show the polygons of mesh `nearer`.
std::size_t pixelsNotShowing(const Mesh& first, const Mesh& second, int nearer,
                             const Camera& camera, std::size_t& covered, bool closed = false) {
  Scene scene;
  for (const Mesh* mesh : {&first, &second}) {
    MeshView view = mesh->view();
    view.closedSurface = closed;
    scene.meshes.push_back({view, Material{}});
  }
  const Rendered r = renderScene(scene, camera, kWidth, kHeight);
  const std::int32_t firstOfSecond = static_cast<std::int32_t>(first.polygonCount());
  std::size_t wrong = 0;
  covered = r.stats.pixelsCovered;
  for (std::int32_t id : r.framebuffer.polygonId()) {
    if (id == Framebuffer::kBackgroundId) continue;
    wrong += (id >= firstOfSecond) != (nearer == 1);
  }
  return wrong;
}

// Two planes tilted 30° and 75° about x, the nearer `separation`·D closer along their normal
// and shifted within it (so their vertices snap differently); each drawn first in turn. At
// 75° snapping a vertex to 1/256 pixel (as coverage must) moves its key by more than 1e-6 of
// itself, so the depth plane is set up from the unsnapped positions.
TEST(DepthPrecision, NearerOfTwoTiltedPlanesWinsAtEveryFarNearRatio) {
  const glm::dvec3 center(0.0, 0.0, -kEyeDistance);
  for (double tiltDegrees : {30.0, 75.0}) {
    const double tilt = tiltDegrees * M_PI / 180.0;
    const glm::dvec3 normal(0.0, std::sin(tilt), std::cos(tilt));
    for (double separation : {1e-4, 1e-5, 1e-6}) {
      Mesh far, near;
      addSquare(far, center, normal);
      addSquare(near, center + separation * kEyeDistance * normal, normal, {0.1234, 0.0567});
      for (double ratio : {1e4, 1e6, 1e8, 1e10, 1e12}) {
        for (bool tinyNear : {true, false}) {
          for (bool parallel : {false, true}) {
            SCOPED_TRACE(describe(separation, ratio, tinyNear, parallel) + ", tilt " +
                         std::to_string(tiltDegrees));
            const Camera camera = cameraWithRatio(ratio, tinyNear, parallel);
            std::size_t covered = 0;
            EXPECT_EQ(pixelsNotShowing(far, near, 1, camera, covered), 0u) << "farther drawn first";
            EXPECT_GT(covered, std::size_t(kWidth * kHeight) / 2);
            EXPECT_EQ(pixelsNotShowing(near, far, 0, camera, covered), 0u) << "nearer drawn first";
          }
        }
      }
    }
  }
}

// Concentric spheres (radius 1 at distance D, and 1 + separation·D): the outer one's facets
// are parallel to the inner one's and snap to other sub-pixel positions. Marked closed, their
// back faces are skipped and keys come from the unsnapped planes everywhere. Drawn with their
// back faces, samples only snapping covers (within 1/512 pixel beyond a triangle's edge) take
// the snapped plane's key, so that silhouettes fold as culling would: there a gap of 1e-6
// can be below the snapping error on steep facets, and a handful of such samples may go to
// the inner sphere.
TEST(DepthPrecision, OuterOfTwoConcentricSpheresWinsAtEveryFarNearRatio) {
  const glm::dvec3 center(0.0, 0.0, -kEyeDistance);
  for (bool closed : {true, false}) {
    for (double separation : {1e-4, 1e-5, 1e-6}) {
      Mesh inner = makeUvSphere(48, 32, 1.0, center);
      Mesh outer = makeUvSphere(48, 32, 1.0 + separation * kEyeDistance, center);
      const std::size_t allowed = closed || separation > 1e-6 ? 0 : kWidth * kHeight / 5000;
      for (double ratio : {1e4, 1e6, 1e8, 1e10, 1e12}) {
        for (bool tinyNear : {true, false}) {
          SCOPED_TRACE(describe(separation, ratio, tinyNear, false) +
                       (closed ? ", closed" : ", back faces drawn"));
          const Camera camera = cameraWithRatio(ratio, tinyNear, false);
          std::size_t covered = 0;
          EXPECT_LE(pixelsNotShowing(inner, outer, 1, camera, covered, closed), allowed)
              << "inner drawn first";
          EXPECT_GT(covered, 2000u);
          EXPECT_LE(pixelsNotShowing(outer, inner, 0, camera, covered, closed), allowed)
              << "outer drawn first";
        }
      }
    }
  }
}

// Issue 7, defect 5: with clipping range (1e-8, 10) a sphere 3 units away used to round to
// window depth 1, the background's, and vanish. VTK draws it; so do we, like with a usual
// near plane — and at every far/near ratio up to 1e12, by a tiny near or a huge far plane.
TEST(DepthPrecision, TinyNearPlaneStillDrawsTheSphere) {
  const Mesh sphere = makeUvSphere(40, 30, 1.0);
  Camera usual;
  usual.position = {0, 0, 3};
  usual.nearClip = 1.0;
  usual.farClip = 10.0;
  const Rendered reference = renderScene(oneMeshScene(sphere.view()), usual, 200, 200);
  EXPECT_GT(reference.stats.pixelsCovered, 5000u);
  for (int exponent = 2; exponent <= 12; ++exponent) {
    for (bool tinyNear : {true, false}) {
      Camera camera = usual;
      if (tinyNear)
        camera.nearClip = camera.farClip / std::pow(10.0, exponent);
      else
        camera.farClip = camera.nearClip * std::pow(10.0, exponent);
      SCOPED_TRACE("far/near 1e" + std::to_string(exponent) +
                   (tinyNear ? ", tiny near" : ", huge far"));
      const Rendered r = renderScene(oneMeshScene(sphere.view()), camera, 200, 200);
      std::size_t differentIds = 0;
      for (std::size_t i = 0; i < r.framebuffer.pixelCount(); ++i)
        differentIds += r.framebuffer.polygonId()[i] != reference.framebuffer.polygonId()[i];
      EXPECT_EQ(differentIds, 0u);
      for (float depth : r.framebuffer.depth())
        ASSERT_TRUE(depth >= 0.0f && depth <= 1.0f) << depth;
    }
  }
}

// Exact ties (the same polygon twice) keep the polygon drawn first in the z-buffer: the test
// is strictly "nearer". Painter's order paints equal depths in id order, so the last wins.
TEST(DepthPrecision, ExactTiesKeepThePolygonDrawnFirst) {
  Mesh twice;
  for (int copy = 0; copy < 2; ++copy)
    addSquare(twice, {0.0, 0.0, -kEyeDistance}, glm::normalize(glm::dvec3(0.2, 0.3, 1.0)));
  const Camera camera = cameraWithRatio(1e3, false, false);
  const Rendered z = renderScene(oneMeshScene(twice.view()), camera, kWidth, kHeight);
  RenderOptions painter;
  painter.visibility = Visibility::PainterSort;
  const Rendered p = renderScene(oneMeshScene(twice.view()), camera, kWidth, kHeight, painter);
  for (std::size_t i = 0; i < z.framebuffer.pixelCount(); ++i) {
    ASSERT_EQ(z.framebuffer.polygonId()[i], 0) << "pixel " << i;
    ASSERT_EQ(p.framebuffer.polygonId()[i], 1) << "pixel " << i;
    ASSERT_EQ(z.framebuffer.depth()[i], p.framebuffer.depth()[i]) << "pixel " << i;
  }
}

// The Depth plane holds VTK's window depth: perspective f(d − n)/(d(f − n)), parallel
// (d − n)/(f − n), computed in double and rounded to the nearest float. A square facing the
// camera at distance d has one depth everywhere: the rounding of that closed form, within
// the key's own rounding (a float of n/d, resp. of d − n).
TEST(DepthPrecision, DepthOutputIsTheWindowDepthOfTheClosedForm) {
  for (bool parallel : {false, true}) {
    for (double distance : {0.5, 1.0, 2.9, 7.0, 99.0}) {
      Camera camera = cameraWithRatio(1000.0, false, parallel);  // near 0.3, far 300
      camera.nearClip = 0.3;
      Mesh square;
      addSquare(square, {0.0, 0.0, -distance}, {0.0, 0.0, 1.0});
      const Rendered r = renderScene(oneMeshScene(square.view()), camera, 8, 6);
      const double n = camera.nearClip, f = camera.farClip, d = distance;
      const double expected = parallel ? (d - n) / (f - n) : f * (d - n) / (d * (f - n));
      // The key's rounding: 2^-24 relative in n/d (perspective) or in d − n (parallel).
      const double tolerance = 1e-7 * (parallel ? expected : n / d / (1.0 - n / f)) + 6e-8;
      SCOPED_TRACE((parallel ? "parallel, d = " : "perspective, d = ") + std::to_string(d));
      ASSERT_EQ(r.framebuffer.polygonIdAt(4, 3), 0);
      for (std::size_t i = 0; i < r.framebuffer.pixelCount(); ++i) {
        const bool covered = r.framebuffer.polygonId()[i] == 0;
        ASSERT_NEAR(r.framebuffer.depth()[i], covered ? expected : 1.0, tolerance);
      }
    }
  }
}

}  // namespace
}  // namespace facet::testing

namespace facet::testing {
namespace {

using detail::PixelBounds;
using detail::WindowVertex;

// One tile's planes for the raster's internals: depth keys, polygon ids.
using TilePlanes = SquarePlanes<16>;

// A random window position: grid point from `corner`, residues anywhere (depth key 0).
WindowVertex randomPosition(std::mt19937& random, std::uniform_int_distribution<int>& corner) {
  std::uniform_int_distribution<int> residue(-127, 127);
  WindowVertex v;
  v.x = corner(random), v.y = corner(random);
  v.residueX = static_cast<std::int8_t>(residue(random));
  v.residueY = static_cast<std::int8_t>(residue(random));
  return v;
}

// What a run of random triangles did under losesEverywhere (RasterTriangle.h).
struct RejectTally {
  std::size_t tested = 0, rejected = 0, wronglyRejected = 0;
  std::size_t largerTested = 0;  // boxes of 17–256 samples: no wrong reject, no rate asked
};

// losesEverywhere against the keys the triangle does write: random small triangles (residues,
// steep and flat depth planes), painted first over the background (every edge on the
// polygon's boundary, or random boundary edges) to learn their keys; then with every box
// pixel nearer than those keys it may reject (and should, mostly), and with one covered pixel
// a float farther than the triangle's key there it must not (the triangle would win that
// pixel).
RejectTally rejectRandomTriangles(unsigned seed, bool randomBoundaries) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> corner(2 * 256, 10 * 256), mask(0, 6);
  std::uniform_real_distribution<float> key(0.25f, 0.75f), steep(-0.01f, 0.01f);
  const PixelBounds tile{0, 0, TilePlanes::kSide - 1, TilePlanes::kSide - 1};
  RejectTally tally;
  for (int t = 0; t < 20000; ++t) {
    WindowVertex v[3];
    const float base = key(random);
    for (WindowVertex& c : v) {
      c = randomPosition(random, corner);
      c.depth = base + (t % 2 ? steep(random) : steep(random) * 1e-4f);
    }
    const auto boundary =
        randomBoundaries ? static_cast<detail::EdgeMask>(mask(random)) : detail::kAllEdges;
    const std::int64_t area = detail::doubleSignedArea(v[0], v[1], v[2]);
    if (area == 0) continue;
    if (area < 0) std::swap(v[1], v[2]);
    const PixelBounds box = detail::samplesInBoundingBox(v[0], v[1], v[2], tile);
    // Up to 9 × 9 samples: walkBox tests boxes of up to 256 (kSamplesForLosesEverywhere).
    if (box.area() < 2 || box.area() > 256) continue;
    TilePlanes written;  // the triangle's own keys
    detail::PaintCounts counts;
    detail::paintTriangle<detail::DepthMode::Overwrite>(v[0], v[1], v[2], boundary, 0, tile,
                                                        written.planes(), counts);
    if (counts.written == 0) continue;
    const bool few = box.area() <= 16;  // the rate below is asked of these
    ++(few ? tally.tested : tally.largerTested);

    TilePlanes nearer;
    for (std::size_t i = 0; i < nearer.depth.size(); ++i)
      nearer.depth[i] = written.ids[i] == 0 ? written.depth[i] : 1.0f;
    const bool tie = detail::losesEverywhere(v[0], v[1], v[2], box, nearer.planes());
    for (float& d : nearer.depth)
      d = d < 1.0f ? std::nextafter(d, 2.0f) + 1e-4f : d;
    if (few)
      tally.rejected += detail::losesEverywhere(v[0], v[1], v[2], box, nearer.planes()) || tie;

    // Every pixel the triangle covers, one at a time: the bound is tightest where the
    // triangle's key is largest, which need not be the first pixel in row order.
    TilePlanes oneFarther = nearer;
    for (std::size_t i = 0; i < oneFarther.depth.size(); ++i) {
      if (written.ids[i] != 0) continue;
      oneFarther.depth[i] = std::nextafter(written.depth[i], -1.0f);
      if (detail::losesEverywhere(v[0], v[1], v[2], box, oneFarther.planes()) &&
          ++tally.wronglyRejected <= 5) {
        ADD_FAILURE() << "triangle (" << v[0].x << "," << v[0].y << "," << v[0].depth << ") ("
                      << v[1].x << "," << v[1].y << "," << v[1].depth << ") (" << v[2].x << ","
                      << v[2].y << "," << v[2].depth << "), boundary edges " << int{boundary}
                      << ", rejected, but wins pixel " << i;
      }
      oneFarther.depth[i] = nearer.depth[i];
    }
  }
  return tally;
}

TEST(DepthPrecision, TrianglesRejectedBeforeSetUpLoseEveryPixel) {
  const RejectTally tally = rejectRandomTriangles(7, false);
  EXPECT_EQ(tally.wronglyRejected, 0u);
  EXPECT_GT(tally.tested, 5000u);
  EXPECT_GT(tally.largerTested, 1000u);
  EXPECT_GT(tally.rejected, tally.tested / 2) << "a triangle well behind should mostly be rejected";
}

// The same with random polygon-boundary edges: beyond a diagonal the unsnapped plane goes on
// past the snapped triangle's edge (TriangleDepth, RasterTriangle.cpp).
TEST(DepthPrecision, TrianglesWithDiagonalsRejectedBeforeSetUpLoseEveryPixel) {
  const RejectTally tally = rejectRandomTriangles(13, true);
  EXPECT_EQ(tally.wronglyRejected, 0u);
  EXPECT_GT(tally.tested, 5000u);
  // The margin is wider than 1e-4 on the steepest planes: fewer are rejected than above.
  EXPECT_GT(tally.rejected, tally.tested / 3) << "a triangle well behind should often be rejected";
}

// A back face after its tile's front faces (paintBackTriangle) tries the tile's farthest key
// per 4 × 4 block before its box's keys: random triangles of 17–256 samples over keys just
// nearer than their own (with, every other time, one covered pixel a float farther, where the
// triangle wins), blocks read before any paint: the same planes and counts as
// paintTriangle<Test, true>, and some rejected by the blocks alone (nothing written where
// the box's keys would not have been read).
TEST(DepthPrecision, BackTrianglesRejectedByBlocksPaintAsWithoutThem) {
  std::mt19937 random(29);
  std::uniform_int_distribution<int> corner(2 * 256, 14 * 256);
  std::uniform_real_distribution<float> key(0.25f, 0.75f), steep(-0.01f, 0.01f);
  const PixelBounds tile{0, 0, TilePlanes::kSide - 1, TilePlanes::kSide - 1};
  std::size_t compared = 0, hidden = 0;
  for (int t = 0; t < 4000; ++t) {
    WindowVertex v[3];
    const float base = key(random);
    for (WindowVertex& c : v) {
      c = randomPosition(random, corner);
      c.depth = base + steep(random);
    }
    const std::int64_t area = detail::doubleSignedArea(v[0], v[1], v[2]);
    if (area == 0) continue;
    if (area < 0) std::swap(v[1], v[2]);
    const PixelBounds box = detail::samplesInBoundingBox(v[0], v[1], v[2], tile);
    if (box.area() <= 16 || box.area() > 256) continue;
    TilePlanes written;
    detail::PaintCounts own;
    detail::paintTriangle<detail::DepthMode::Overwrite>(v[0], v[1], v[2], detail::kAllEdges, 0,
                                                        tile, written.planes(), own);
    if (own.written == 0) continue;
    TilePlanes front;  // every pixel nearer than the triangle's key there (a front face's)
    for (std::size_t i = 0; i < front.depth.size(); ++i)
      front.depth[i] = written.ids[i] == 0 ? std::nextafter(written.depth[i], 2.0f) + 1e-4f : 1.0f;
    if (t % 2 == 1) {  // one covered pixel a float farther: the triangle must win it
      for (std::size_t i = 0; i < front.depth.size(); ++i) {
        if (written.ids[i] != 0) continue;
        front.depth[i] = std::nextafter(written.depth[i], -1.0f);
        break;
      }
    }
    TilePlanes withBlocks = front, without = front;
    detail::FarthestBlocks blocks(tile, withBlocks.planes());
    detail::PaintCounts countsWith, countsWithout;
    detail::paintBackTriangle(v[0], v[1], v[2], detail::kAllEdges, 1, tile, withBlocks.planes(),
                              countsWith, blocks);
    detail::paintTriangle<detail::DepthMode::Test, true>(v[0], v[1], v[2], detail::kAllEdges, 1,
                                                         tile, without.planes(), countsWithout);
    ASSERT_EQ(withBlocks.depth, without.depth) << "triangle " << t;
    ASSERT_EQ(withBlocks.ids, without.ids) << "triangle " << t;
    ASSERT_EQ(countsWith.written, countsWithout.written) << "triangle " << t;
    if (t % 2 == 1) {
      EXPECT_GT(countsWith.written, 0u) << "triangle " << t;
    }
    ++compared;
    hidden += countsWith.written == 0 ? 1 : 0;
  }
  EXPECT_GT(compared, 500u);
  EXPECT_GT(hidden, compared / 4) << "a triangle behind every key should often be rejected";
}

// The margin of the whole-block reject (HiddenBlocks.h, step 1): a triangle of a triangle
// polygon (all three edges on its boundary) never writes a key nearer than its nearest vertex
// key, on any paint path. Slivers with steep keys, whose rows start far outside them (the
// stepped key extrapolated by many times the vertex keys' range, so that its rounding passes
// the nearest vertex key without the clamp), painted after front faces exactly at their
// nearest vertex key: a tie keeps the front face, so none may write a pixel. Also the
// set-up's records (smallTriangleOf, paintSmallTriangle). Checked to fail with the clamp of
// TriangleDepth and SmallTriangle::nearestKey removed.
TEST(DepthPrecision, TriangleKeysNeverPassTheirNearestVertexKey) {
  using ImagePlanes = SquarePlanes<128>;
  const detail::TileGrid grid(ImagePlanes::kSide, ImagePlanes::kSide);
  const PixelBounds image = grid.viewport();
  std::mt19937 random(41);
  std::uniform_int_distribution<int> start(4 * 256, 60 * 256), length(256, 60 * 256);
  std::uniform_int_distribution<int> across(-300, 300), residue(-127, 127), path(0, 2);
  std::uniform_real_distribution<float> key(0.25f, 0.75f);
  std::size_t painted = 0, records = 0, fragmentsBehind = 0;
  const int trials = trialsToRun(20000);
  for (int t = 0; t < trials; ++t) {
    WindowVertex v[3];
    const int x = start(random), y = start(random);
    // Long slivers across or down, and short ones (boxes of a few samples: records).
    const int along = t % 3 == 2 ? length(random) % 768 : length(random);
    const int dx = t % 2 ? along : across(random), dy = t % 2 ? across(random) : along;
    v[0].x = x, v[0].y = y;
    v[1].x = x + dx, v[1].y = y + dy;
    v[2].x = x + dx / 2 + across(random), v[2].y = y + dy / 2 + across(random);
    for (WindowVertex& c : v) {
      c.residueX = static_cast<std::int8_t>(residue(random));
      c.residueY = static_cast<std::int8_t>(residue(random));
      c.depth = key(random);
    }
    const std::int64_t area = detail::doubleSignedArea(v[0], v[1], v[2]);
    if (area == 0) continue;
    if (area < 0) std::swap(v[1], v[2]);
    const float nearest = detail::nearestWrittenKey(v[0], v[1], v[2], detail::kClampedEdges);
    ASSERT_EQ(nearest, std::max({v[0].depth, v[1].depth, v[2].depth}));
    ImagePlanes front;
    std::fill(front.depth.begin(), front.depth.end(), nearest);
    std::fill(front.ids.begin(), front.ids.end(), 0);
    detail::PaintCounts counts;
    const int which = path(random);
    const std::size_t tileIndex =
        static_cast<std::size_t>(v[0].y / 256 / detail::TileGrid::kTileSize) *
            static_cast<std::size_t>(grid.tilesX()) +
        static_cast<std::size_t>(v[0].x / 256 / detail::TileGrid::kTileSize);
    const PixelBounds tile = grid.bounds(tileIndex);
    if (which == 0) {
      detail::paintTriangle<detail::DepthMode::Test>(v[0], v[1], v[2], detail::kClampedEdges, 1,
                                                     image, front.planes(), counts);
    } else if (which == 1) {
      detail::paintTriangleWalkingBox<detail::DepthMode::Test>(
          v[0], v[1], v[2], detail::kClampedEdges, 1, image, front.planes(), counts);
    } else if (const auto record =
                   detail::smallTriangleOf(v[0], v[1], v[2], detail::kClampedEdges, tile, 1)) {
      detail::paintSmallTriangle<detail::DepthMode::Test>(*record, nearest, front.planes(), counts);
      ++records;
    }
    ASSERT_EQ(counts.written, 0u) << "triangle " << t << " (path " << which
                                  << ") wrote a key nearer than its nearest vertex key";
    ++painted;
    // Its pixels over the background: every key written at most the nearest vertex key.
    ImagePlanes alone;
    detail::PaintCounts own;
    detail::paintTriangle<detail::DepthMode::Test>(v[0], v[1], v[2], detail::kClampedEdges, 1,
                                                   image, alone.planes(), own);
    fragmentsBehind += own.written;
  }
  EXPECT_GT(painted, static_cast<std::size_t>(trials) * 3 / 4);
  EXPECT_GT(records, static_cast<std::size_t>(trials) / 400);
  EXPECT_GT(fragmentsBehind, static_cast<std::size_t>(trials) * 5);
}

// Each block's key is no nearer than any of its pixels', and stays so as pixels grow nearer.
TEST(DepthPrecision, FarthestBlocksBoundTheirPixelsKeys) {
  std::mt19937 random(31);
  std::uniform_real_distribution<float> key(-1.0f, 1.0f);
  std::uniform_int_distribution<int> at(0, TilePlanes::kSide - 1);
  TilePlanes planes;
  for (float& d : planes.depth)
    d = key(random);
  planes.depth[5 * TilePlanes::kSide + 12] = -std::numeric_limits<float>::infinity();
  const PixelBounds tile{0, 0, TilePlanes::kSide - 1, TilePlanes::kSide - 1};
  detail::FarthestBlocks blocks(tile, planes.planes());
  for (int k = 0; k < 2000; ++k) {
    PixelBounds box{at(random), at(random), at(random), at(random)};
    if (box.x0 > box.x1) std::swap(box.x0, box.x1);
    if (box.y0 > box.y1) std::swap(box.y0, box.y1);
    float least = std::numeric_limits<float>::infinity();
    for (int y = box.y0; y <= box.y1; ++y)
      for (int x = box.x0; x <= box.x1; ++x)
        least = std::min(least, planes.depth[y * TilePlanes::kSide + x]);
    ASSERT_LE(blocks.over(box), least);
    planes.depth[at(random) * TilePlanes::kSide + at(random)] += 0.5f;  // only nearer
  }
  EXPECT_EQ(blocks.over({12, 5, 12, 5}), -std::numeric_limits<float>::infinity());
  EXPECT_GT(blocks.over({8, 8, 15, 15}), -1.0f) << "a block's own least key, not the tile's";
}

// A tile's block bounds are exact (each block's least key, over the tile's own pixels only),
// for tiles anywhere in the image and of every edge size, in a 64 × 64 buffer indexed by the
// tile's origin as the raster's (Raster.cpp, TilePlanes) with near junk past the tile's
// pixels: an off-by-one that stays conservative fails here.
TEST(DepthPrecision, FarthestBlocksAreExactForTilesAnywhereAndOfEverySize) {
  constexpr int kSide = 64, kBlock = detail::FarthestBlocks::kBlockSize;
  std::mt19937 random(5);
  std::uniform_real_distribution<float> key(-1.0f, 1.0f);
  std::vector<float> depth(kSide * kSide);
  std::vector<std::int32_t> ids(kSide * kSide);
  for (int trial = 0; trial < 1000; ++trial) {
    const int tx = kSide * static_cast<int>(random() % 40),
              ty = kSide * static_cast<int>(random() % 40);
    const int w = 1 + static_cast<int>(random() % kSide),
              h = 1 + static_cast<int>(random() % kSide);
    const PixelBounds tile{tx, ty, tx + w - 1, ty + h - 1};
    std::fill(depth.begin(), depth.end(), 1e30f);  // past the tile: never cleared, near
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        depth[y * kSide + x] = key(random);
    const std::size_t origin = static_cast<std::size_t>(ty) * kSide + tx;
    detail::FarthestBlocks blocks(tile, {depth.data(), ids.data(), kSide, origin});
    const auto at = [&](int x, int y) { return depth[(y - ty) * kSide + (x - tx)]; };
    for (int k = 0; k < 20; ++k) {
      int x0 = tx + static_cast<int>(random() % w), x1 = tx + static_cast<int>(random() % w);
      int y0 = ty + static_cast<int>(random() % h), y1 = ty + static_cast<int>(random() % h);
      if (x0 > x1) std::swap(x0, x1);
      if (y0 > y1) std::swap(y0, y1);
      float exact = std::numeric_limits<float>::infinity();
      for (int by = (y0 - ty) / kBlock; by <= (y1 - ty) / kBlock; ++by)
        for (int bx = (x0 - tx) / kBlock; bx <= (x1 - tx) / kBlock; ++bx)
          for (int y = ty + by * kBlock; y <= std::min(tile.y1, ty + by * kBlock + kBlock - 1); ++y)
            for (int x = tx + bx * kBlock; x <= std::min(tile.x1, tx + bx * kBlock + kBlock - 1);
                 ++x)
              exact = std::min(exact, at(x, y));
      ASSERT_EQ(blocks.over({x0, y0, x1, y1}), exact)
          << "tile at " << tx << ", " << ty << " of " << w << " x " << h << ", box " << x0 << ", "
          << y0 << " to " << x1 << ", " << y1;
    }
  }
}

// The reject's margin above the vertex keys, where it is needed: a triangle whose key at a
// sample is nearer than every vertex's, with the tile's keys one float farther than that.
// Vertex a lies on a pixel center where two top-left edges meet (the triangle covers that
// sample); its unsnapped position is half a grid step to the right, across the diagonal a → b,
// so the sample is outside the unsnapped triangle, where the unsnapped plane (keys falling to
// the right, a and b the nearest) goes on to a key nearer than a's. Without the margin the
// tile's keys there, no farther than the vertices', would reject it.
TEST(DepthPrecision, RejectMarginKeepsAKeyNearerThanEveryVertex) {
  constexpr int kCenter = 4 * 256 + 128, kSide = 3 * 256;
  const PixelBounds tile{0, 0, TilePlanes::kSide - 1, TilePlanes::kSide - 1};
  const detail::EdgeMask diagonalAB = 0b011;  // edges b → c and c → a on the boundary
  for (const float nearest : {0.25f, 0.5f, 0.75f}) {
    for (const float drop : {1e-2f, 1e-3f, 1e-4f}) {
      WindowVertex a, b, c;
      a.x = kCenter, a.y = kCenter + kSide, a.residueX = 127, a.depth = nearest;
      b.x = kCenter, b.y = kCenter, b.depth = nearest;
      c.x = kCenter + kSide, c.y = kCenter + kSide, c.depth = nearest - drop;
      SCOPED_TRACE("vertex keys " + std::to_string(nearest) + ", " + std::to_string(drop) +
                   " lower at c");
      const PixelBounds box = detail::samplesInBoundingBox(a, b, c, tile);
      ASSERT_EQ(box.area(), 16u);
      TilePlanes written;
      detail::PaintCounts counts;
      detail::paintTriangle<detail::DepthMode::Overwrite>(a, b, c, diagonalAB, 0, tile,
                                                          written.planes(), counts);
      const std::size_t atA = 7 * TilePlanes::kSide + 4;  // pixel (4, 7), a's sample
      ASSERT_EQ(written.ids[atA], 0);
      ASSERT_GT(written.depth[atA], nearest) << "the premise: a key nearer than every vertex's";

      TilePlanes tied;  // every pixel one float farther than the triangle's key at a
      const float farther = std::nextafter(written.depth[atA], -1.0f);
      std::fill(tied.depth.begin(), tied.depth.end(), farther);
      EXPECT_FALSE(detail::losesEverywhere(a, b, c, box, tied.planes()))
          << "rejected, but wins pixel (4, 7) with key " << written.depth[atA] << " over "
          << farther;
      TilePlanes unrejected = tied;
      detail::PaintCounts tiedCounts, unrejectedCounts;
      detail::paintTriangle<detail::DepthMode::Test, true>(a, b, c, diagonalAB, 1, tile,
                                                           tied.planes(), tiedCounts);
      detail::paintTriangle<detail::DepthMode::Test, false>(a, b, c, diagonalAB, 1, tile,
                                                            unrejected.planes(), unrejectedCounts);
      EXPECT_EQ(tied.ids[atA], 1);
      EXPECT_EQ(tiedCounts.written, unrejectedCounts.written);
      EXPECT_TRUE(tied.depth == unrejected.depth);
    }
  }
}

// The reject end to end: a random stream of small and mid-sized triangles (steep and flat
// depth planes, every boundary-edge mask, many polygon ids) painted with the depth test into
// one tile with the reject and into another without it: the same keys, ids and writes.
TEST(DepthPrecision, RejectingHiddenTrianglesPaintsTheSamePixels) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> corner(0, TilePlanes::kSide * 256), spread(1, 6 * 256),
      mask(0, 7), polygon(0, 63);
  std::uniform_real_distribution<float> key(0.1f, 0.9f);
  const PixelBounds tile{0, 0, TilePlanes::kSide - 1, TilePlanes::kSide - 1};
  TilePlanes with, without;
  detail::PaintCounts withCounts, withoutCounts;
  std::size_t painted = 0;
  for (int t = 0; t < 40000; ++t) {
    WindowVertex v[3];
    const int cx = corner(random), cy = corner(random), size = spread(random);
    const float base = key(random);
    randomCornersAround(random, cx, cy, size, base, t % 3 == 0, v);
    const std::int64_t area = detail::doubleSignedArea(v[0], v[1], v[2]);
    if (area == 0) continue;
    if (area < 0) std::swap(v[1], v[2]);
    const auto boundary = static_cast<detail::EdgeMask>(mask(random));
    const std::int32_t id = polygon(random);
    detail::paintTriangle<detail::DepthMode::Test, true>(v[0], v[1], v[2], boundary, id, tile,
                                                         with.planes(), withCounts);
    detail::paintTriangle<detail::DepthMode::Test, false>(v[0], v[1], v[2], boundary, id, tile,
                                                          without.planes(), withoutCounts);
    ++painted;
  }
  EXPECT_GT(painted, 30000u);
  EXPECT_EQ(withCounts.written, withoutCounts.written);
  EXPECT_GT(withoutCounts.written, 0u);
  EXPECT_TRUE(with.depth == without.depth) << "depth keys differ";
  EXPECT_TRUE(with.ids == without.ids) << "polygon ids differ";
}

}  // namespace
}  // namespace facet::testing
