// The set-up's batch test (SetupBatch.h) on every instruction set this CPU has: its verdicts
// against the exact per-triangle decisions, and whole renders byte for byte against the
// set-up without batches.

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "../support/SameRender.h"
#include "../support/Sanitizers.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "Binning.h"
#include "Raster.h"
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
    detail::planTwoPassFrames();
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

enum Verdict { kUntested, kCulled, kZeroArea, kCoversNoSample, kFragment, kTriangle };

// What the per-triangle path (Setup.cpp, Binning.cpp) makes of a triangle with every vertex
// inside: the verdict, and for a kept one the pixel centers of its box, its winding and, for a
// fragment, its depth key.
struct TriangleSetUp {
  int verdict = kUntested;
  PixelBounds samples{};
  bool clockwise = false;
  float key = 0.0f;
};

TriangleSetUp exactSetUp(WindowVertex a, WindowVertex b, WindowVertex c,
                         const PixelBounds& viewport, bool skipBackFaces) {
  TriangleSetUp result;
  const std::int64_t area = detail::doubleSignedArea(a, b, c);
  if (skipBackFaces && area < 0) return {kCulled};
  if (area == 0) return {kZeroArea};
  result.clockwise = area < 0;
  if (area < 0) std::swap(b, c);
  result.samples = detail::samplesInBoundingBox(a, b, c, viewport);
  const PixelBounds& box = result.samples;
  if (box.x0 == box.x1 && box.y0 == box.y1) {
    const detail::EdgeMask boundary = skipBackFaces ? 0 : detail::kAllEdges;
    const std::optional<float> key =
        detail::keyOfOnlySample(a, b, c, std::abs(area), boundary, box.x0, box.y0);
    if (!key) return {kCoversNoSample};
    result.verdict = kFragment;
    result.key = *key;
    return result;
  }
  if (box.empty() || !detail::coversAnySample(a, b, c, box)) return {kCoversNoSample};
  result.verdict = kTriangle;
  return result;
}

// Whether the batch takes this triangle: flagged a triangle, every vertex inside, its box below
// 2^14 grid steps across.
bool batchTakes(const WindowVertex (&v)[3], bool triangle) {
  const auto [minX, maxX] = std::minmax({v[0].x, v[1].x, v[2].x});
  const auto [minY, maxY] = std::minmax({v[0].y, v[1].y, v[2].y});
  const bool inside = (v[0].outcode | v[1].outcode | v[2].outcode) == detail::kInside;
  return triangle && inside && maxX - minX < (1 << 14) && maxY - minY < (1 << 14);
}

// Random triangles of every kind the batch meets: pixel-sized ones with corners on pixel
// centers and half-pixel lines (so that samples fall exactly on edges, where the top-left
// rule decides), slivers and collinear ones, ones partly or wholly off the viewport, ones
// near and beyond the 2^14 bound, sub-pixel ones, and some with a vertex outside (to clip);
// with random residues and depth keys of every magnitude.
std::vector<WindowVertex> randomTriangles(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> kind(0, 6), pixel(-3, 105), fine(-600, 600), any(0, 255);
  std::uniform_int_distribution<int> residue(-128, 127), exponent(-30, 30);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<WindowVertex> corners;
  for (std::size_t t = 0; t < count; ++t) {
    const int k = kind(random);
    const std::int32_t x0 = pixel(random) * 256 + any(random),
                       y0 = pixel(random) * 256 + any(random);
    const float scale = std::ldexp(1.0f, exponent(random));
    WindowVertex v[3];
    for (WindowVertex& corner : v) {
      corner.x = x0 + fine(random), corner.y = y0 + fine(random);
      if (k >= 5) {  // sub-pixel: many are fragments
        corner.x = x0 + fine(random) / (k - 3), corner.y = y0 + fine(random) / (k - 3);
      }
      if (k == 0) corner.x -= corner.x % 128, corner.y -= corner.y % 128;  // on half pixels
      if (k == 1) corner.x *= 24, corner.y *= 24;                          // near the bound
      corner.residueX = static_cast<std::int8_t>(residue(random));
      corner.residueY = static_cast<std::int8_t>(residue(random));
      corner.depth = scale * (1.0f + 0.001f * unit(random));
    }
    if (k == 2) v[2].x = 2 * v[1].x - v[0].x, v[2].y = 2 * v[1].y - v[0].y;  // collinear
    if (k == 3) v[2] = v[1];
    if (k == 4) v[1].outcode = detail::kNonFinite;
    corners.insert(corners.end(), std::begin(v), std::end(v));
  }
  return corners;
}

// The batch of the triangles from `first` on (three corners each), lane l a polygon (left to
// the per-triangle path) when l % 7 == 3.
TriangleBatch batchAt(const std::vector<WindowVertex>& corners, std::size_t first) {
  TriangleBatch batch{};
  for (int lane = 0; lane < kBatchSize; ++lane) {
    for (int j = 0; j < 3; ++j)
      batch.v[j][lane] = corners[3 * (first + static_cast<std::size_t>(lane)) + j];
    batch.triangle[lane] = lane % 7 != 3;  // some lanes hold polygons
  }
  return batch;
}

// One lane's verdict, and that its bits are at most one of the kinds.
int verdictOf(const detail::BatchVerdicts& verdicts, int lane) {
  const std::uint32_t bits[5] = {verdicts.culled, verdicts.zeroArea, verdicts.coversNoSample,
                                 verdicts.fragment, verdicts.triangle};
  int verdict = kUntested, kinds = 0;
  for (int k = 0; k < 5; ++k) {
    if ((bits[k] >> lane) & 1u) verdict = k + 1, ++kinds;
  }
  EXPECT_LE(kinds, 1) << "lane " << lane;
  return verdict;
}

// Whether two SmallTriangle records are the same, every value to the bit.
bool sameRecord(const detail::SmallTriangle& a, const detail::SmallTriangle& b) {
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  return bits(a.firstKey) == bits(b.firstKey) && bits(a.keyPerFine) == bits(b.keyPerFine) &&
         bits(a.keyPerPixel) == bits(b.keyPerPixel) && a.firstRowFine == b.firstRowFine &&
         a.polygon == b.polygon && a.x0 == b.x0 && a.y0 == b.y0 && a.coverage == b.coverage;
}

// A kept triangle lane's SmallTriangle: made exactly when smallTriangleOf makes one from the
// triangle (counter-clockwise, with its three boundary edges unless back faces are skipped)
// and the tile of its box, when that is its only tile; then the same, bit for bit.
bool smallRecordRight(const detail::BatchVerdicts& verdicts, int lane, const WindowVertex (&v)[3],
                      const detail::TileGrid& grid, bool skipBackFaces, std::size_t& records) {
  const bool clockwise = (verdicts.clockwise >> lane) & 1u;
  const bool oneTile = (verdicts.oneTile >> lane) & 1u;
  const std::optional<detail::SmallTriangle> expected =
      oneTile
          ? detail::smallTriangleOf(v[0], v[clockwise ? 2 : 1], v[clockwise ? 1 : 2],
                                    skipBackFaces ? detail::EdgeMask{0} : detail::kAllEdges,
                                    grid.bounds(static_cast<std::size_t>(verdicts.tile[lane])), 7)
          : std::nullopt;
  const bool made = (verdicts.small >> lane) & 1u;
  if (made != expected.has_value()) return false;
  records += made;
  return !made || sameRecord(detail::smallTriangleOfLane(verdicts, lane, 7), *expected);
}

TEST_F(SetupBatches, VerdictsAreThePerTriangleSetUpOnEveryTarget) {
  const detail::TileGrid grid(100, 70);  // 2 × 2 tiles, the last ones partial
  const PixelBounds viewport = grid.viewport();
  const std::vector<WindowVertex> corners = randomTriangles(20000, 11);
  const std::size_t triangles = corners.size() / 3;
  for (const SimdTarget& target : targets()) {
    SCOPED_TRACE(target.name);
    use(target);
    for (bool skipBackFaces : {false, true}) {
      std::size_t mismatches = 0, counts[6] = {}, records = 0, recordsBeyondFew = 0;
      for (std::size_t first = 0; first + kBatchSize <= triangles; first += kBatchSize) {
        const TriangleBatch batch = batchAt(corners, first);
        detail::BatchVerdicts verdicts;
        detail::classifyBatch(batch, grid, skipBackFaces, !skipBackFaces, verdicts);
        EXPECT_EQ(verdicts.culledCount, std::popcount(verdicts.culled));
        EXPECT_EQ(verdicts.zeroAreaCount, std::popcount(verdicts.zeroArea));
        EXPECT_EQ(verdicts.coversNoSampleCount, std::popcount(verdicts.coversNoSample));
        for (int lane = 0; lane < kBatchSize; ++lane) {
          const std::size_t at = 3 * (first + lane);
          const WindowVertex v[3] = {corners[at], corners[at + 1], corners[at + 2]};
          const int verdict = verdictOf(verdicts, lane);
          const TriangleSetUp exact = batchTakes(v, batch.triangle[lane])
                                          ? exactSetUp(v[0], v[1], v[2], viewport, skipBackFaces)
                                          : TriangleSetUp{};
          ++counts[verdict];
          const PixelBounds samples{verdicts.samples.x0[lane], verdicts.samples.y0[lane],
                                    verdicts.samples.x1[lane], verdicts.samples.y1[lane]};
          const bool kept = verdict == kFragment || verdict == kTriangle;
          bool right = verdict == exact.verdict;
          if (right && kept) {
            right = samples.x0 == exact.samples.x0 && samples.y0 == exact.samples.y0 &&
                    samples.x1 == exact.samples.x1 && samples.y1 == exact.samples.y1 &&
                    ((verdicts.clockwise >> lane) & 1u) == exact.clockwise;
            // Its first center's tile, and whether its box overlaps no other.
            const int tileSize = detail::TileGrid::kTileSize;
            const bool oneTile = samples.x0 / tileSize == samples.x1 / tileSize &&
                                 samples.y0 / tileSize == samples.y1 / tileSize;
            right = right &&
                    verdicts.tile[lane] ==
                        static_cast<std::int32_t>(detail::tileOf(grid, samples.x0, samples.y0)) &&
                    ((verdicts.oneTile >> lane) & 1u) == oneTile;
          }
          // The same key to the bit.
          if (right && verdict == kFragment)
            right = std::bit_cast<std::uint32_t>(verdicts.key[lane]) ==
                    std::bit_cast<std::uint32_t>(exact.key);
          // A small box's record, made from the same triangle.
          if (right && verdict == kTriangle)
            right = smallRecordRight(verdicts, lane, v, grid, skipBackFaces, records);
          // Records of boxes of more than 4 centers or 2 × 3: the pixel-center test did not
          // sample them, yet its edge values at their first center are the coverage's start.
          const int width = samples.x1 - samples.x0, height = samples.y1 - samples.y0;
          if (right && ((verdicts.small >> lane) & 1u) && width > 0 && height > 0 &&
              width + height > 2)
            ++recordsBeyondFew;
          right = right && (verdict == kTriangle || ((verdicts.small >> lane) & 1u) == 0);
          if (!right && ++mismatches <= 5) {
            ADD_FAILURE() << "triangle (" << v[0].x << "," << v[0].y << ") (" << v[1].x << ","
                          << v[1].y << ") (" << v[2].x << "," << v[2].y << "), triangle "
                          << batch.triangle[lane] << ", skip back faces " << skipBackFaces
                          << ": batch " << verdict << " samples " << samples.x0 << "," << samples.y0
                          << ".." << samples.x1 << "," << samples.y1 << " key "
                          << verdicts.key[lane] << "; exact " << exact.verdict << " samples "
                          << exact.samples.x0 << "," << exact.samples.y0 << ".." << exact.samples.x1
                          << "," << exact.samples.y1 << " key " << exact.key;
          }
        }
      }
      EXPECT_EQ(mismatches, 0u);
      EXPECT_GT(records, triangles / 200) << "small records met too seldom";
      EXPECT_GT(recordsBeyondFew, triangles / 1000) << "boxes beyond 4 centers met too seldom";
      // Every kind is met (culled only when back faces are skipped).
      for (int k = kUntested; k <= kTriangle; ++k) {
        if (k == kCulled && !skipBackFaces) {
          EXPECT_EQ(counts[k], 0u);
        } else {
          EXPECT_GT(counts[k], triangles / 200) << "verdict " << k << " met too seldom";
        }
      }
    }
  }
}

// A run's classifier (batchClassifier, taken once per run of batches) is the batch of the
// target in use: the same verdicts, samples, keys and records as classifyBatch, every
// target; a target of its own each.
TEST_F(SetupBatches, ARunsClassifierIsTheBatchOfTheTargetInUse) {
  const detail::TileGrid grid(100, 70);
  const std::vector<WindowVertex> corners = randomTriangles(4000, 19);
  const std::size_t triangles = corners.size() / 3;
  std::vector<detail::BatchClassifier> seen;
  for (const SimdTarget& target : targets()) {
    SCOPED_TRACE(target.name);
    use(target);
    const detail::BatchClassifier classify = detail::batchClassifier();
    ASSERT_NE(classify, nullptr);
    EXPECT_EQ(detail::batchClassifier(), classify);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), classify), 0);
    seen.push_back(classify);
    for (bool skipBackFaces : {false, true}) {
      for (bool clamp : {false, true}) {
        for (std::size_t first = 0; first + kBatchSize <= triangles; first += kBatchSize) {
          const TriangleBatch batch = batchAt(corners, first);
          detail::BatchVerdicts run, each;
          classify(batch, grid, skipBackFaces, !skipBackFaces, run, clamp);
          detail::classifyBatch(batch, grid, skipBackFaces, !skipBackFaces, each, clamp);
          ASSERT_EQ(run.culled, each.culled);
          ASSERT_EQ(run.zeroArea, each.zeroArea);
          ASSERT_EQ(run.coversNoSample, each.coversNoSample);
          ASSERT_EQ(run.fragment, each.fragment);
          ASSERT_EQ(run.triangle, each.triangle);
          ASSERT_EQ(run.clockwise & run.kept(), each.clockwise & each.kept());
          ASSERT_EQ(run.small, each.small);
          ASSERT_EQ(run.keptSamples, each.keptSamples);
          for (std::uint32_t rest = run.kept(); rest != 0; rest &= rest - 1) {
            const int lane = std::countr_zero(rest);
            EXPECT_EQ(run.samples.x0[lane], each.samples.x0[lane]);
            EXPECT_EQ(run.samples.y1[lane], each.samples.y1[lane]);
            EXPECT_EQ(run.tile[lane], each.tile[lane]);
            if ((run.fragment >> lane) & 1u) {
              EXPECT_EQ(std::bit_cast<std::uint32_t>(run.key[lane]),
                        std::bit_cast<std::uint32_t>(each.key[lane]));
            }
            if ((run.small >> lane) & 1u) {
              EXPECT_TRUE(sameRecord(detail::smallTriangleOfLane(run, lane, 3),
                                     detail::smallTriangleOfLane(each, lane, 3)));
            }
          }
        }
      }
    }
  }
}

// batchClassifier before any dispatch (a process's first render): Highway's table then holds
// its first-call initializer, which batchClassifier must not hand out (each batch would update
// the chosen target again); it chooses the target first. Two runs starting at once on two
// threads (two renders) get the best target's batch, as one run does. Checked to fail without
// the choice (batchClassifier returned the initializer).
TEST_F(SetupBatches, ARunsClassifierBeforeAnyDispatchIsTheBestTargets) {
  const SimdTarget best = targets().front();
  use(best);
  const detail::BatchClassifier bestClassifier = detail::batchClassifier();
  expectFirstDispatchOnTwoThreadsGives(detail::batchClassifier, bestClassifier);
  EXPECT_STREQ(detail::simdTargetInUse(), best.name);
}

// With clampBackFaces (one pass or a two-pass frame's back pass) the kept back faces' keys
// and records are clamped to their nearest vertex key, the front faces' not, on every target.
TEST_F(SetupBatches, BackFaceKeysAreClampedToTheirNearestVertexKeyOnEveryTarget) {
  const detail::TileGrid grid(100, 70);  // 2 × 2 tiles, the last ones partial
  std::vector<WindowVertex> corners = randomTriangles(20000, 13);
  std::mt19937 random(17);
  std::uniform_real_distribution<float> key(0.45f, 0.55f);
  for (WindowVertex& corner : corners)
    corner.depth = key(random);
  const std::size_t triangles = corners.size() / 3;
  for (const SimdTarget& target : targets()) {
    SCOPED_TRACE(target.name);
    use(target);
    std::size_t clampedRecords = 0, clampedFragments = 0, frontRecords = 0, frontFragments = 0;
    for (std::size_t first = 0; first + kBatchSize <= triangles; first += kBatchSize) {
      const TriangleBatch batch = batchAt(corners, first);
      detail::BatchVerdicts unclamped, clamped;
      detail::classifyBatch(batch, grid, false, true, unclamped);
      detail::classifyBatch(batch, grid, false, true, clamped, true);
      ASSERT_EQ(clamped.kept(), unclamped.kept());
      ASSERT_EQ(clamped.small, unclamped.small);
      for (std::uint32_t rest = clamped.kept(); rest != 0; rest &= rest - 1) {
        const int lane = std::countr_zero(rest);
        const bool clockwise = (clamped.clockwise >> lane) & 1u;
        // A back face (clockwise) clamped to its nearest vertex key (nearestWrittenKey), a
        // front face not (+∞).
        const float nearest =
            clockwise
                ? std::max({batch.v[0][lane].depth, batch.v[1][lane].depth, batch.v[2][lane].depth})
                : std::numeric_limits<float>::infinity();
        if ((clamped.small >> lane) & 1u) {
          (clockwise ? clampedRecords : frontRecords) += 1;
          EXPECT_EQ(clamped.smallPlane.nearestKey[lane], nearest) << "lane " << lane;
        }
        if ((clamped.fragment >> lane) & 1u) {
          (clockwise ? clampedFragments : frontFragments) += 1;
          EXPECT_EQ(clamped.key[lane], std::min(unclamped.key[lane], nearest)) << "lane " << lane;
        }
      }
    }
    EXPECT_GT(clampedRecords, 0u);
    EXPECT_GT(clampedFragments, 0u);
    EXPECT_GT(frontRecords, 0u);
    EXPECT_GT(frontFragments, 0u);
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
      expectSameRender(before, after);
      // The binned boxes' samples, which the batch sums in lanes (BatchVerdicts::keptSamples).
      EXPECT_EQ(before.stats.plan.depthComplexity, after.stats.plan.depthComplexity);
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

// Triangles with every third polygon a quad, in a strip three views wide along x in polygon
// order: a batch's lanes mix triangles with polygons for the per-triangle path, and whole
// blocks of polygons (kPolygonsPerBlock) lie left and right of the view
// (Rule::GeometryOutsideView).
Mesh mixedStrip(int polygons, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> jitter(-8, 8), offset(-3, 3);
  Mesh mesh;
  for (int t = 0; t < polygons; ++t) {
    const double x = -160.0 + 480.0 * t / polygons + 0.5 * jitter(random);
    const double y = 0.5 * (std::uniform_int_distribution<int>(-8, 248)(random)) * 0.75;
    const int corners = t % 3 == 2 ? 4 : 3;
    const std::int64_t first = mesh.addPoint({x - 1.5, y - 1.5, 0.002 * t});
    mesh.addPoint({x + 1.5 + 0.5 * offset(random), y - 1.5, 0.002 * t});
    if (corners == 4) mesh.addPoint({x + 1.5, y + 1.5 + 0.5 * offset(random), 0.002 * t});
    mesh.addPoint({x - 1.5 + 0.5 * offset(random), y + 1.5, 0.002 * t});
    if (corners == 4) {
      mesh.addPolygon({first, first + 1, first + 2, first + 3});
    } else {
      mesh.addPolygon({first, first + 1, first + 2});
    }
  }
  return mesh;
}

// A nearEdge lane (BatchVerdicts), binned as Setup.cpp bins it: its record without the samples
// keysNearBoundary takes, and those as fragments; painted, the same keys and ids to the bit as
// paintTriangle paints from its corners (with the back faces' clamp too), on every target. The
// lanes' unsure samples must be exactly those refine() does not step: one it would step,
// taken as a fragment, would get keyAt's key, not the stepped one.
TEST_F(SetupBatches, NearEdgeLanesPaintAsTheirTrianglesOnEveryTarget) {
  const detail::TileGrid grid(100, 70);  // 2 × 2 tiles, the last ones partial
  std::vector<WindowVertex> corners = randomTriangles(40000, 23);
  const std::size_t triangles = corners.size() / 3;
  const int width = 100, height = 70;
  std::vector<float> depth(width * height), expectedDepth(width * height);
  std::vector<std::int32_t> ids(width * height), expectedIds(width * height);
  const detail::Planes planes{depth.data(), ids.data(), width};
  const detail::Planes expected{expectedDepth.data(), expectedIds.data(), width};
  const auto clear = [&] {
    for (auto* plane : {&depth, &expectedDepth})
      std::fill(plane->begin(), plane->end(), detail::kBackgroundDepthKey);
    for (auto* plane : {&ids, &expectedIds})
      std::fill(plane->begin(), plane->end(), -1);
  };
  for (const SimdTarget& target : targets()) {
    SCOPED_TRACE(target.name);
    use(target);
    for (bool clampBackFaces : {false, true}) {
      std::size_t nearEdge = 0, fragments = 0, mismatches = 0;
      for (std::size_t first = 0; first + kBatchSize <= triangles; first += kBatchSize) {
        const TriangleBatch batch = batchAt(corners, first);
        detail::BatchVerdicts verdicts;
        detail::classifyBatch(batch, grid, false, true, verdicts, clampBackFaces);
        EXPECT_EQ(verdicts.nearEdge & verdicts.small, 0u);
        EXPECT_EQ(verdicts.nearEdge & ~verdicts.triangle, 0u);
        for (std::uint32_t rest = verdicts.nearEdge; rest != 0; rest &= rest - 1) {
          const int lane = std::countr_zero(rest);
          ++nearEdge;
          const bool clockwise = (verdicts.clockwise >> lane) & 1u;
          const WindowVertex& a = batch.v[0][lane];
          const WindowVertex& b = batch.v[clockwise ? 2 : 1][lane];
          const WindowVertex& c = batch.v[clockwise ? 1 : 2][lane];
          const detail::EdgeMask boundary =
              clockwise && clampBackFaces ? detail::kClampedEdges : detail::kAllEdges;
          const int x0 = verdicts.samples.x0[lane], y0 = verdicts.samples.y0[lane];
          const auto unsure = static_cast<std::uint32_t>(verdicts.smallPlane.unsure[lane]);
          EXPECT_NE(unsure, 0u);
          // refine()'s own test, sample by sample.
          const PixelBounds box{x0, y0, verdicts.samples.x1[lane], verdicts.samples.y1[lane]};
          EXPECT_EQ(unsure, detail::samplesNearBoundary(
                                a, b, c, boundary, box,
                                static_cast<std::uint32_t>(verdicts.smallPlane.coverage[lane])));
          float keys[detail::kSmallSide * detail::kSmallSide];
          const std::uint32_t near =
              detail::keysNearBoundary(a, b, c, boundary, x0, y0, unsure, keys);
          fragments += static_cast<std::size_t>(std::popcount(near));
          clear();
          detail::PaintCounts counts, expectedCounts;
          detail::SmallTriangle record = detail::smallTriangleOfLane(verdicts, lane, 5);
          record.coverage = static_cast<std::uint16_t>(record.coverage & ~near);
          if (boundary == detail::kClampedEdges) {
            detail::paintSmallTriangle<detail::DepthMode::Test>(
                record, verdicts.smallPlane.nearestKey[lane], planes, counts);
          } else {
            detail::paintSmallTriangle<detail::DepthMode::Test>(record, planes, counts);
          }
          for (std::uint32_t bits = near; bits != 0; bits &= bits - 1) {
            const int bit = std::countr_zero(bits);
            const int x = x0 + bit % detail::kSmallSide, y = y0 + bit / detail::kSmallSide;
            detail::writeFragment<detail::DepthMode::Test>(static_cast<std::size_t>(y) * width + x,
                                                           keys[bit], 5, planes, counts);
          }
          detail::paintTriangle<detail::DepthMode::Test>(
              a, b, c, boundary, 5, grid.bounds(static_cast<std::size_t>(verdicts.tile[lane])),
              expected, expectedCounts);
          const bool same =
              counts.written == expectedCounts.written && ids == expectedIds &&
              std::equal(depth.begin(), depth.end(), expectedDepth.begin(), [](float p, float q) {
                return std::bit_cast<std::uint32_t>(p) == std::bit_cast<std::uint32_t>(q);
              });
          if (!same && ++mismatches <= 5) {
            ADD_FAILURE() << "triangle (" << a.x << "," << a.y << ") (" << b.x << "," << b.y
                          << ") (" << c.x << "," << c.y << "), unsure " << unsure << " near "
                          << near << ", clamped " << (boundary == detail::kClampedEdges);
          }
        }
      }
      EXPECT_EQ(mismatches, 0u);
      EXPECT_GT(nearEdge, triangles / 1000) << "near-edge lanes met too seldom";
      EXPECT_GT(fragments, nearEdge / 2);
    }
  }
}

TEST_F(SetupBatches, SmallScenesRenderTheSameBytesOnEveryTarget) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  Camera bunnyCamera = fitCamera(bunny, {0.2, -0.3, -1.0});
  bunnyCamera.nearClip *= 1.3;  // the clipper runs too (DeterminismTest)
  const Mesh dots = confetti(4000, 5);
  const Mesh strip = mixedStrip(12000, 7);
  MeshView stripView = strip.view();
  stripView.version = 1;  // its blocks measured (Rule::GeometryOutsideView)
  {
    const RenderPlan plan =
        renderScene(oneMeshScene(stripView), pixelCamera(160, 120), 160, 120).stats.plan;
    ASSERT_GE(plan.blocksOutside, 4u) << plan.describe();
    ASSERT_LT(plan.blocksOutside, plan.blocksTested) << plan.describe();
  }
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
    cases.push_back({"triangles and quads, blocks outside the view", oneMeshScene(stripView),
                     pixelCamera(160, 120), 160, 120, options});
    cases.push_back({"triangles and quads, back faces culled", oneMeshScene(stripView, culled),
                     pixelCamera(160, 120), 160, 120, options});
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
  for (int threads : threadCountsToRun({1, 3})) {
    cases.push_back({"every face, " + std::to_string(threads) + " threads",
                     oneMeshScene(sphere.view(), {}, lights), camera, 1920, 1080,
                     optionsWith(Visibility::ZBuffer, threads)});
    cases.push_back({"closed, " + std::to_string(threads) + " threads",
                     oneMeshScene(closed, {}, lights), camera, 1920, 1080,
                     optionsWith(Visibility::ZBuffer, threads)});
  }
  expectSameRenders(cases, targets());
}

// A frame that culls back faces writes the facing (Setup.h: backFacing, which the shade reads)
// of every polygon it draws, also where the renderer's previous frame drew that polygon as a
// back face: the same bytes as a fresh renderer's, on every target.
TEST_F(SetupBatches, CulledFramesWriteTheFacingOfEveryPolygonTheyDraw) {
  const Mesh sphere = makeUvSphere(120, 122);
  const Camera front = fitCamera(sphere, {0.0, 0.0, -1.0});
  const Camera behind = fitCamera(sphere, {0.1, 0.0, 1.0});
  const auto litFrom = [](const Camera& camera) {
    LightSet lights;
    lights.lights.push_back(PointLight{camera.position, Color(1.0f), 1.0, NoAttenuation{}});
    return lights;
  };
  Material culled;
  culled.backfaceCulling = true;
  const Scene everyFace = oneMeshScene(sphere.view(), {}, litFrom(front));
  const Scene closed = oneMeshScene(sphere.view(), culled, litFrom(behind));
  const Rendered fresh = renderScene(closed, behind, 320, 240);
  EXPECT_GT(fresh.stats.pixelsCovered, 0u);
  for (const SimdTarget& target : targets()) {
    SCOPED_TRACE(target.name);
    use(target);
    Renderer renderer;
    Rendered first{Framebuffer(320, 240), {}};
    renderer.render(everyFace, front, first.framebuffer);
    Rendered second{Framebuffer(320, 240), {}};
    second.stats = renderer.render(closed, behind, second.framebuffer);
    EXPECT_GT(second.stats.polygonsCulled, 0u);
    expectSameRender(fresh, second);
  }
}

// A two-pass frame (Raster.h: every face drawn, back faces set up after the front faces are
// painted, the hidden ones dropped) against the same frame in one pass: the same bytes and
// counts, on every target and thread count, with the clipper and polygons of many corners.
TEST_F(SetupBatches, TwoPassFramesRenderAsOnePassOnEveryTarget) {
  const Mesh banded = sphereWithBand(120);
  const Camera bandCamera = fitCamera(banded, {0.3, -0.2, -1.0});
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  Camera bunnyCamera = fitCamera(bunny, {0.2, -0.3, -1.0});
  bunnyCamera.nearClip *= 1.3;  // the clipper runs too
  const Mesh strip = mixedStrip(12000, 7);
  std::vector<SceneCase> cases;
  for (int threads : {1, 2, 8}) {
    const RenderOptions options = optionsWith(Visibility::ZBuffer, threads);
    const std::string suffix = ", " + std::to_string(threads) + " threads";
    cases.push_back({"sphere with a band cut out" + suffix, oneMeshScene(banded.view()), bandCamera,
                     320, 240, options});
    cases.push_back({"bunny" + suffix, oneMeshScene(bunny.view()), bunnyCamera, 640, 480, options});
    cases.push_back({"triangles and quads" + suffix, oneMeshScene(strip.view()),
                     pixelCamera(160, 120), 160, 120, options});
  }
  for (const SceneCase& c : cases) {
    SCOPED_TRACE(c.name);
    detail::enableTwoPassFrames(false);
    const Rendered before = renderScene(c.scene, c.camera, c.width, c.height, c.options);
    detail::enableTwoPassFrames(true);
    EXPECT_GT(before.stats.pixelsCovered, 0u);
    for (const SimdTarget& target : targets()) {
      SCOPED_TRACE(target.name);
      use(target);
      const Rendered after = renderScene(c.scene, c.camera, c.width, c.height, c.options);
      expectSameRender(before, after);
      EXPECT_EQ(before.stats.pixelsCovered, after.stats.pixelsCovered);
      EXPECT_EQ(before.stats.plan.depthComplexity, after.stats.plan.depthComplexity);
    }
  }
}

// A two-pass frame's front pass (Setup.cpp: PolygonSetup's kDeferBackFaces) keeps no back face:
// a batch of consecutive polygons writes all its facing bytes as front-facing, its deferred
// lanes' too, and the back pass rewrites the byte of each back face it draws. One renderer
// turning about the banded sphere, lit from the eye (a polygon changes sides between frames, and
// the silhouette's batches mix front and back faces): each frame the same bytes and counts as
// the set-up without batches (which defers polygon by polygon and writes the facing of the
// polygons it draws alone) and as a fresh renderer's one pass; the hidden blocks and polygons,
// which the back pass finds from the deferred ids, the same too. Every target; 1, 2 and 8
// threads.
TEST_F(SetupBatches, TwoPassFrontPassLeavesEveryDrawnBackFacesFacingToTheBackPass) {
  const Mesh banded = sphereWithBand(120);
  MeshView view = banded.view();
  view.version = 1;  // measured: the back pass's hidden blocks
  const auto frameCamera = [&](int frame) {
    const double angle = 0.9 * frame;  // radians: the far side comes round
    return fitCamera(banded, {std::sin(angle) + 0.3, -0.2, -std::cos(angle)});
  };
  const auto sceneSeenFrom = [&](const Camera& camera) {
    LightSet lights;
    lights.lights.push_back(PointLight{camera.position, Color(1.0f), 1.0, NoAttenuation{}});
    return oneMeshScene(view, {}, lights);
  };
  constexpr int kFrames = 4;
  const auto renderFrames = [&](int threads) {
    Renderer renderer;
    renderer.setThreadCount(threads);
    renderer.setVisibility(Visibility::ZBuffer);
    renderer.setTwoSidedLighting(true);
    std::vector<Rendered> frames;
    for (int frame = 0; frame < kFrames; ++frame) {
      const Camera camera = frameCamera(frame);
      Rendered rendered{Framebuffer(320, 240), {}};
      rendered.stats = renderer.render(sceneSeenFrom(camera), camera, rendered.framebuffer);
      EXPECT_TRUE(rendered.stats.plan.twoPassFrame);
      frames.push_back(std::move(rendered));
    }
    return frames;
  };
  for (int threads : threadCountsToRun({1, 2, 8})) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    detail::enableTwoPassFrames(false);
    std::vector<Rendered> onePass;
    for (int frame = 0; frame < kFrames; ++frame) {
      const Camera camera = frameCamera(frame);
      onePass.push_back(renderScene(sceneSeenFrom(camera), camera, 320, 240,
                                    optionsWith(Visibility::ZBuffer, threads)));
    }
    detail::enableTwoPassFrames(true);
    detail::enableSetupBatches(false);
    const std::vector<Rendered> unbatched = renderFrames(threads);
    detail::enableSetupBatches(true);
    std::size_t hidden = 0;
    for (const Rendered& frame : unbatched)
      hidden += frame.stats.polygonsHidden;
    EXPECT_GT(hidden, 0u);
    for (const SimdTarget& target : targets()) {
      SCOPED_TRACE(target.name);
      use(target);
      const std::vector<Rendered> batched = renderFrames(threads);
      for (int frame = 0; frame < kFrames; ++frame) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        const Rendered &one = onePass[static_cast<std::size_t>(frame)],
                       &before = unbatched[static_cast<std::size_t>(frame)],
                       &after = batched[static_cast<std::size_t>(frame)];
        EXPECT_GT(one.stats.pixelsCovered, 10000u);
        expectSameRender(before, after);
        EXPECT_EQ(before.stats.plan.blocksHiddenBehindFront,
                  after.stats.plan.blocksHiddenBehindFront);
        EXPECT_EQ(before.stats.plan.polygonsHiddenBehindFront,
                  after.stats.plan.polygonsHiddenBehindFront);
        EXPECT_EQ(differingPixels(one.framebuffer, after.framebuffer), 0u);
        EXPECT_EQ(one.stats.fragmentsWritten, after.stats.fragmentsWritten);
        EXPECT_EQ(one.stats.pixelsCovered, after.stats.pixelsCovered);
      }
    }
  }
}

// A bin entry's 30 bits of index (Binning.h): at the limit the set-up throws facet::Error
// naming the count rather than bin an index that wrapped into the kind bits.
TEST(Binning, ChunksBeyondTheBinIndexThrowNamingTheCount) {
  const std::size_t limit = detail::kMaxBinnedPerChunk;
  EXPECT_NO_THROW(detail::requireIndexable(limit - 1, limit - 1, limit - 1, limit - 1));
  for (int which = 0; which < 4; ++which) {
    const std::size_t counts[4] = {which == 0 ? limit : 0, which == 1 ? limit : 0,
                                   which == 2 ? limit : 0, which == 3 ? limit : 0};
    try {
      detail::requireIndexable(counts[0], counts[1], counts[2], counts[3]);
      ADD_FAILURE() << "no error for " << limit << " of kind " << which;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(std::to_string(limit)), std::string::npos)
          << error.what();
    }
  }
}

}  // namespace
}  // namespace facet::testing
