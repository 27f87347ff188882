// The set-up's batch test (SetupBatch.h) on every instruction set this CPU has: its verdicts
// against the exact per-triangle decisions, and whole renders byte for byte against the
// set-up without batches.

#include <bit>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "Binning.h"
#include "RasterTriangle.h"
#include "SetupBatch.h"
#include "facet/Error.h"

namespace facet::testing {
namespace {

using detail::kBatchSize;
using detail::PixelBounds;
using detail::SimdTarget;
using detail::TriangleBatch;
using detail::WindowVertex;

// Leaves batches on and every instruction set allowed, whatever a test did.
class SetupBatches : public EveryTargetTest {
 protected:
  void TearDown() override {
    EveryTargetTest::TearDown();
    detail::enableSetupBatches(true);
  }
  // Every target this CPU has, the best first and the portable one last.
  static std::vector<SimdTarget> targets() {
    std::vector<SimdTarget> all = detail::simdTargets();
    EXPECT_GE(all.size(), 1u);
    return all;
  }
  static void use(const SimdTarget& target) {
    detail::useSimdTarget(target.bits);
    ASSERT_STREQ(detail::simdTargetInUse(), target.name);
  }
};

enum Verdict { kUndecided, kCulled, kZeroArea, kCoversNoSample };

// The per-triangle path's decision (Setup.cpp, Binning.cpp) for a triangle with every vertex
// inside: the verdict a batch must give, or kUndecided for a triangle set up further.
std::int32_t exactVerdict(WindowVertex a, WindowVertex b, WindowVertex c,
                          const PixelBounds& viewport, bool skipBackFaces) {
  const std::int64_t area = detail::doubleSignedArea(a, b, c);
  if (skipBackFaces && area < 0) return kCulled;
  if (area == 0) return kZeroArea;
  if (area < 0) std::swap(b, c);
  const PixelBounds bounds = detail::samplesInBoundingBox(a, b, c, viewport);
  if (bounds.empty() || !detail::coversAnySample(a, b, c, bounds)) return kCoversNoSample;
  return kUndecided;
}

// Whether the batch promises to decide this triangle itself: its box is below 2^14 grid
// steps across and holds at most 2 × 2 pixel centers.
bool batchDecides(const WindowVertex (&v)[3], const PixelBounds& viewport) {
  const auto [minX, maxX] = std::minmax({v[0].x, v[1].x, v[2].x});
  const auto [minY, maxY] = std::minmax({v[0].y, v[1].y, v[2].y});
  if (maxX - minX >= (1 << 14) || maxY - minY >= (1 << 14)) return false;
  const PixelBounds box = detail::samplesInBoundingBox(v[0], v[1], v[2], viewport);
  return box.empty() || (box.x1 - box.x0 < 2 && box.y1 - box.y0 < 2);
}

// Random triangles of every kind the batch meets: pixel-sized ones with corners on pixel
// centers and half-pixel lines (so that samples fall exactly on edges, where the top-left
// rule decides), slivers and collinear ones, ones partly or wholly off the viewport, and
// ones near and beyond the 2^14 bound.
std::vector<WindowVertex> randomTriangles(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> kind(0, 5), pixel(-3, 40), fine(-600, 600), any(0, 255);
  std::vector<WindowVertex> corners;
  for (std::size_t t = 0; t < count; ++t) {
    const int k = kind(random);
    const std::int32_t x0 = pixel(random) * 256 + any(random),
                       y0 = pixel(random) * 256 + any(random);
    WindowVertex v[3];
    for (WindowVertex& corner : v) {
      corner.x = x0 + fine(random), corner.y = y0 + fine(random);
      if (k == 0) corner.x -= corner.x % 128, corner.y -= corner.y % 128;  // on half pixels
      if (k == 1) corner.x *= 24, corner.y *= 24;                          // near the bound
    }
    if (k == 2) v[2].x = 2 * v[1].x - v[0].x, v[2].y = 2 * v[1].y - v[0].y;  // collinear
    if (k == 3) v[2] = v[1];
    corners.insert(corners.end(), std::begin(v), std::end(v));
  }
  return corners;
}

// One lane's verdict, and that its drop bits are at most one.
std::int32_t verdictOf(const detail::BatchVerdicts& verdicts, int lane) {
  const bool culled = (verdicts.culled >> lane) & 1, zeroArea = (verdicts.zeroArea >> lane) & 1,
             none = (verdicts.coversNoSample >> lane) & 1;
  EXPECT_LE(culled + zeroArea + none, 1) << "lane " << lane;
  return culled ? kCulled : zeroArea ? kZeroArea : none ? kCoversNoSample : kUndecided;
}

TEST_F(SetupBatches, VerdictsAreThePerTriangleDecisionsOnEveryTarget) {
  const PixelBounds viewport{0, 0, 31, 23};
  const std::vector<WindowVertex> corners = randomTriangles(20000, 11);
  const std::size_t triangles = corners.size() / 3;
  for (const SimdTarget& target : targets()) {
    SCOPED_TRACE(target.name);
    use(target);
    for (bool skipBackFaces : {false, true}) {
      std::size_t decided = 0, mismatches = 0, covering = 0;
      for (std::size_t first = 0; first + kBatchSize <= triangles; first += kBatchSize) {
        TriangleBatch batch{};
        for (int lane = 0; lane < kBatchSize; ++lane) {
          for (int j = 0; j < 3; ++j) {
            batch.x[j][lane] = corners[3 * (first + lane) + j].x;
            batch.y[j][lane] = corners[3 * (first + lane) + j].y;
          }
          batch.tested[lane] = lane % 7 != 3;  // some lanes are left to the per-triangle path
        }
        const detail::BatchVerdicts verdicts =
            detail::classifyBatch(batch, viewport, skipBackFaces);
        EXPECT_EQ(verdicts.culledCount, std::popcount(verdicts.culled));
        EXPECT_EQ(verdicts.zeroAreaCount, std::popcount(verdicts.zeroArea));
        EXPECT_EQ(verdicts.coversNoSampleCount, std::popcount(verdicts.coversNoSample));
        for (int lane = 0; lane < kBatchSize; ++lane) {
          const std::int32_t verdict = verdictOf(verdicts, lane);
          const std::size_t at = 3 * (first + lane);
          const WindowVertex v[3] = {corners[at], corners[at + 1], corners[at + 2]};
          const std::int32_t exact = exactVerdict(v[0], v[1], v[2], viewport, skipBackFaces);
          // A tested lane may leave a triangle it need not decide to the per-triangle path.
          bool right = batch.tested[lane] && batchDecides(v, viewport)
                           ? verdict == exact
                           : verdict == kUndecided || (batch.tested[lane] && verdict == exact);
          decided += verdict != kUndecided;
          // A lane said to cover a sample is one the per-triangle path keeps.
          if (((verdicts.coversSample >> lane) & 1) &&
              (verdict != kUndecided || exact != kUndecided))
            right = false;
          covering += (verdicts.coversSample >> lane) & 1;
          if (!right && ++mismatches <= 5) {
            ADD_FAILURE() << "triangle (" << v[0].x << "," << v[0].y << ") (" << v[1].x << ","
                          << v[1].y << ") (" << v[2].x << "," << v[2].y << "), tested "
                          << batch.tested[lane] << ", skip back faces " << skipBackFaces
                          << ": batch " << verdict << ", exact " << exact << ", covers a sample "
                          << ((verdicts.coversSample >> lane) & 1);
          }
        }
      }
      EXPECT_EQ(mismatches, 0u);
      EXPECT_GT(decided, triangles / 3) << "the batch should drop most of these";
      EXPECT_GT(covering, triangles / 100) << "the batch should find some covering a sample";
    }
  }
}

struct SceneCase {
  std::string name;
  Scene scene;
  Camera camera;
  int width, height;
  RenderOptions options;
};

// Renders every case without batches, then with them on every target, and compares bytes and
// the set-up's counts.
void expectSameRenders(const std::vector<SceneCase>& cases,
                       const std::vector<SimdTarget>& targets) {
  for (const SceneCase& c : cases) {
    SCOPED_TRACE(c.name);
    detail::enableSetupBatches(false);
    const Rendered before = renderScene(c.scene, c.camera, c.width, c.height, c.options);
    EXPECT_GT(before.stats.pixelsCovered, 0u);
    detail::enableSetupBatches(true);
    for (const SimdTarget& target : targets) {
      SCOPED_TRACE(target.name);
      detail::useSimdTarget(target.bits);
      ASSERT_STREQ(detail::simdTargetInUse(), target.name);
      const Rendered after = renderScene(c.scene, c.camera, c.width, c.height, c.options);
      EXPECT_EQ(differingPixels(before.framebuffer, after.framebuffer), 0u) << "pixels differ";
      const RenderStats &s = before.stats, &t = after.stats;
      EXPECT_EQ(s.polygonsDrawn, t.polygonsDrawn);
      EXPECT_EQ(s.polygonsCulled, t.polygonsCulled);
      EXPECT_EQ(s.polygonsOutside, t.polygonsOutside);
      EXPECT_EQ(s.polygonsDegenerate, t.polygonsDegenerate);
      EXPECT_EQ(s.trianglesBinned, t.trianglesBinned);
      EXPECT_EQ(s.trianglesClipped, t.trianglesClipped);
      EXPECT_EQ(s.fragmentsWritten, t.fragmentsWritten);
    }
  }
}

RenderOptions optionsWith(Visibility visibility, int threads = 2) {
  RenderOptions options;
  options.visibility = visibility;
  options.threads = threads;
  return options;
}

// Pixel-sized triangles in both windings, corners on half pixels: samples on their edges.
Mesh confetti(int triangles, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> center(-4 * 2, 164 * 2), offset(-3, 3);
  Mesh mesh;
  for (int t = 0; t < triangles; ++t) {
    const double x = 0.5 * center(random), y = 0.5 * center(random) * 0.75;
    for (int j = 0; j < 3; ++j)
      mesh.addPoint({x + 0.5 * offset(random), y + 0.5 * offset(random), 0.002 * t});
    mesh.addPolygon({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return mesh;
}

TEST_F(SetupBatches, SmallScenesRenderTheSameBytesOnEveryTarget) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  Camera bunnyCamera = fitCamera(bunny, {0.2, -0.3, -1.0});
  bunnyCamera.nearClip *= 1.3;  // the clipper runs too (DeterminismTest)
  const Mesh dots = confetti(4000, 5);
  const Mesh floor = makeFloorGrid(40, 20.0);  // WatertightTest, ClippedByTheNearPlane
  const Camera floorCamera = nearClippedFloorCamera();
  Material culled;
  culled.backfaceCulling = true;
  std::vector<SceneCase> cases;
  for (Visibility visibility : {Visibility::ZBuffer, Visibility::PainterSort}) {
    const RenderOptions options = optionsWith(visibility);
    cases.push_back({"bunny", oneMeshScene(bunny.view()), bunnyCamera, 640, 480, options});
    cases.push_back({"bunny, back faces culled", oneMeshScene(bunny.view(), culled), bunnyCamera,
                     640, 480, options});
    cases.push_back(
        {"confetti", oneMeshScene(dots.view()), pixelCamera(160, 120), 160, 120, options});
    cases.push_back({"floor cut by the near plane", oneMeshScene(floor.view()), floorCamera, 160,
                     120, options});
  }
  expectSameRenders(cases, targets());
}

// The benchmark's spheres (bench/CoreBench.cpp) at 500k triangles, every face drawn and as a
// closed surface, at 1080p on 1 and 3 threads.
TEST_F(SetupBatches, SphereOf500kTrianglesRendersTheSameBytesOnEveryTarget) {
  const Mesh sphere = makeUvSphere(500, 502);
  const Camera camera = fitCamera(sphere);
  MeshView closed = sphere.view();
  closed.closedSurface = isClosedSurface(closed);
  ASSERT_TRUE(closed.closedSurface);
  LightSet lights;
  lights.lights.push_back(PointLight{camera.position, Color(1.0f), 1.0, NoAttenuation{}});
  std::vector<SceneCase> cases;
  for (int threads : {1, 3}) {
    cases.push_back({"every face, " + std::to_string(threads) + " threads",
                     oneMeshScene(sphere.view(), {}, lights), camera, 1920, 1080,
                     optionsWith(Visibility::ZBuffer, threads)});
    cases.push_back({"closed, " + std::to_string(threads) + " threads",
                     oneMeshScene(closed, {}, lights), camera, 1920, 1080,
                     optionsWith(Visibility::ZBuffer, threads)});
  }
  expectSameRenders(cases, targets());
}

// A bin entry's 31 bits of index (Binning.h): at the limit the set-up throws facet::Error
// naming the count rather than bin an index that wrapped into the fragment bit.
TEST(Binning, ChunksBeyondTheBinIndexThrowNamingTheCount) {
  const std::size_t limit = detail::kMaxBinnedPerChunk;
  EXPECT_NO_THROW(detail::requireIndexable(limit - 1, limit - 1, limit - 1));
  for (int which = 0; which < 3; ++which) {
    const std::size_t counts[3] = {which == 0 ? limit : 0, which == 1 ? limit : 0,
                                   which == 2 ? limit : 0};
    try {
      detail::requireIndexable(counts[0], counts[1], counts[2]);
      ADD_FAILURE() << "no error for " << limit << " of kind " << which;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(std::to_string(limit)), std::string::npos)
          << error.what();
    }
  }
}

}  // namespace
}  // namespace facet::testing
