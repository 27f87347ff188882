// Back-face blocks skipped whole (BackFacingBlocks.h): renders with skipping on are the same
// bytes and counts as with it off, on meshes of tiny triangles and slivers seen from many
// views, perspective and parallel, near and far from the origin; and without the snapping
// margin they are not.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "BackFacingBlocks.h"
#include "MeshCache.h"
#include "PhaseRunner.h"
#include "SetupBatch.h"
#include "ThreadPool.h"
#include "Transform.h"
#include "ViewCulling.h"

namespace facet::testing {
namespace {

// Leaves the default SIMD target, whatever a test did.
class BackFacingBlocks : public ::testing::Test {
 protected:
  void TearDown() override { detail::useSimdTarget(0); }
};

using Settings = detail::ScopedBackBlockSettings::Settings;

// The back-face blocks' margin off while it lives.
detail::ScopedBackBlockSettings withoutMargin() {
  return detail::ScopedBackBlockSettings(Settings{.skipping = true, .margin = false});
}

// Patches of kPolygonsPerBackBlock triangles each, every patch a small disc of random
// orientation on a sphere of radius 1 about `center`, its triangles facing out: pixel-sized
// ones, tiny ones (1e-4 of a pixel) and slivers (a corner within 1e-3 of the opposite edge),
// mixed per patch as `mix` says (0: ordinary, 1: a few tiny, 2: a few slivers, 3: all tiny).
Mesh patches(int count, unsigned seed, const glm::dvec3& center) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.0, 1.0);
  std::uniform_int_distribution<int> mixOf(0, 3);
  Mesh mesh;
  for (int patch = 0; patch < count; ++patch) {
    glm::dvec3 normal(unit(random), unit(random), unit(random));
    normal = glm::normalize(normal + glm::dvec3(1e-3));
    const glm::dvec3 side = glm::normalize(glm::cross(normal, glm::dvec3(0.3, 0.5, 0.8)));
    const glm::dvec3 up = glm::cross(normal, side);
    const int mix = mixOf(random);
    for (int t = 0; t < static_cast<int>(detail::kPolygonsPerBackBlock); ++t) {
      // Points on the disc, bent slightly toward the sphere.
      const double s = 0.15 * unit(random), u = 0.15 * unit(random);
      const double size = (mix == 3 || (mix == 1 && t % 17 == 0)) ? 3e-7 : 0.004;
      const glm::dvec3 a = center + normal + s * side + u * up - 0.5 * (s * s + u * u) * normal;
      glm::dvec3 b = a + size * side;
      glm::dvec3 c = a + size * up;
      if (mix == 2 && t % 7 == 0) c = 0.5 * (a + b) + 1e-3 * size * up;  // a sliver
      const std::int64_t first = mesh.addPoint(a);
      mesh.addPoint(b);
      mesh.addPoint(c);
      mesh.addPolygon({first, first + 1, first + 2});  // counter-clockwise seen from outside
    }
  }
  return mesh;
}

// A camera looking at `center` from `distance` in a random direction.
Camera randomCamera(std::mt19937& random, const glm::dvec3& center, bool parallel) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), distance(2.5, 6.0);
  const glm::dvec3 direction = glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)));
  Camera camera;
  camera.position = center + distance(random) * direction;
  camera.focalPoint = center;
  camera.viewUp = std::abs(direction.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  camera.viewAngleDegrees = 30.0 + 20.0 * unit(random);
  camera.parallelProjection = parallel;
  camera.parallelScale = 1.3;
  camera.nearClip = 0.1;
  camera.farClip = 20.0;
  return camera;
}

// A closed mesh's view, versioned: its back-face blocks measured.
MeshView closedView(const Mesh& mesh) {
  MeshView view = mesh.view();
  view.closedSurface = true;
  view.version = 1;
  return view;
}

// Renders with skipping as given (and the margin as the test left it).
Rendered renderWith(const Scene& scene, const Camera& camera, bool skipping) {
  Settings settings = detail::ScopedBackBlockSettings::current();
  settings.skipping = skipping;
  const detail::ScopedBackBlockSettings scoped(settings);
  return renderScene(scene, camera, 320, 240);
}

// Whether two renders are the same bytes with the same counts.
bool sameRender(const Rendered& a, const Rendered& b) {
  const RenderStats &s = a.stats, &t = b.stats;
  return differingPixels(a.framebuffer, b.framebuffer) == 0 && s.polygonsDrawn == t.polygonsDrawn &&
         s.polygonsCulled == t.polygonsCulled && s.polygonsOutside == t.polygonsOutside &&
         s.polygonsDegenerate == t.polygonsDegenerate &&
         s.polygonsNonFinite == t.polygonsNonFinite && s.trianglesBinned == t.trianglesBinned;
}

struct Outcome {
  int views = 0, differing = 0;
  std::size_t blocksSkipped = 0;
};

// Renders the patches from many views with skipping on and off; closed surfaces, and a
// material that culls back faces on an open one.
Outcome compareViews(int views, unsigned seed, const glm::dvec3& center) {
  const Mesh mesh = patches(48, seed, center);
  MeshView closed = mesh.view();
  closed.closedSurface = true;  // a promise the test keeps for the eye outside the sphere
  closed.version = 1;
  MeshView open = mesh.view();
  open.version = 1;
  Material culled;
  culled.backfaceCulling = true;
  LightSet lights;
  lights.lights.push_back(
      PointLight{center + glm::dvec3(0, 0, 9), Color(1.0f), 1.0, NoAttenuation{}});
  const Scene scenes[2] = {oneMeshScene(closed, {}, lights), oneMeshScene(open, culled, lights)};
  std::mt19937 random(seed);
  Outcome outcome;
  for (int v = 0; v < views; ++v) {
    const Camera camera = randomCamera(random, center, v % 2 == 1);
    const Scene& scene = scenes[v % 4 / 2];
    const Rendered on = renderWith(scene, camera, true);
    const Rendered off = renderWith(scene, camera, false);
    EXPECT_EQ(off.stats.plan.blocksBackFacing, 0u);
    outcome.blocksSkipped += on.stats.plan.blocksBackFacing;
    outcome.differing += !sameRender(on, off);
    ++outcome.views;
  }
  return outcome;
}

TEST_F(BackFacingBlocks, SkippedBlocksRenderTheSameBytesAndCountsFromManyViews) {
  for (const glm::dvec3 center :
       {glm::dvec3(0.0), glm::dvec3(1e6, -2e6, 3e5), glm::dvec3(-1e9, 1e9, 2e9)}) {
    const Outcome outcome = compareViews(24, 11, center);
    EXPECT_EQ(outcome.differing, 0) << "center " << center.x;
    EXPECT_GT(outcome.blocksSkipped, 24u) << "center " << center.x;  // the test tests
  }
}

// The same views with the snapping margin taken out (a block skipped whenever its cone faces
// away): tiny triangles that snap to no area, or slivers that snap to the other winding, then
// count (and draw) otherwise than the set-up would.
TEST_F(BackFacingBlocks, WithoutTheMarginSomeViewDiffers) {
  const auto noMargin = withoutMargin();
  int differing = 0;
  for (const glm::dvec3 center : {glm::dvec3(0.0), glm::dvec3(1e6, -2e6, 3e5)})
    differing += compareViews(24, 11, center).differing;
  EXPECT_GT(differing, 0);
}

// A plane seen from its back almost edge-on (4e-4 below it at 2 to 4 away), its image a band
// a few grid steps high through a row of pixel centers: its triangles' true windows areas are
// negative by less than their snapping moves them, so some snap counter-clockwise and are drawn.
// The margin keeps their blocks; without it they are skipped and those pixels lost.
TEST_F(BackFacingBlocks, WithoutTheMarginAnEdgeOnPlaneLosesPixels) {
  constexpr double kHeight = 1e-3;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> along(2.9, 3.1), across(-0.5, 0.5), depth(-0.09, 0.09),
      side(-0.3, 0.3);
  Mesh plane;
  for (int t = 0; t < 4 * static_cast<int>(detail::kPolygonsPerBackBlock); ++t) {
    const glm::dvec3 a(along(random), across(random), kHeight);
    const glm::dvec3 b = a + glm::dvec3(depth(random), side(random), 0.0);
    const glm::dvec3 c = a + glm::dvec3(depth(random), side(random), 0.0);
    const std::int64_t first = plane.addPoint(a);
    plane.addPoint(b);
    plane.addPoint(c);
    if (glm::cross(b - a, c - a).z > 0.0) {  // counter-clockwise from above: facing up
      plane.addPolygon({first, first + 1, first + 2});
    } else {
      plane.addPolygon({first, first + 2, first + 1});
    }
  }
  MeshView view = plane.view();
  view.version = 1;
  Material culled;
  culled.backfaceCulling = true;
  const Scene scene = oneMeshScene(view, culled);
  Camera camera;  // below the plane, pitched down by its image's height to half a pixel
  camera.position = {0.0, 0.0, 0.0};
  camera.focalPoint = {1.0, 0.0, -7.84e-4};
  camera.viewUp = {0.0, 0.0, 1.0};
  camera.viewAngleDegrees = 30.0;
  camera.nearClip = 0.5;
  camera.farClip = 10.0;
  const Rendered off = renderWith(scene, camera, false);
  ASSERT_GT(off.stats.polygonsDrawn, 0u);  // some snapped counter-clockwise (70)
  const Rendered on = renderWith(scene, camera, true);
  EXPECT_EQ(on.stats.plan.blocksBackFacing, 0u);
  EXPECT_TRUE(sameRender(on, off));
  const auto noMargin = withoutMargin();
  const Rendered unsafe = renderWith(scene, camera, true);
  EXPECT_GT(unsafe.stats.plan.blocksBackFacing, 0u);
  EXPECT_GT(differingPixels(unsafe.framebuffer, off.framebuffer), 0u);
}

// Every face drawn (no culling material, not closed): nothing skipped.
TEST_F(BackFacingBlocks, EveryFaceMeshesSkipNothing) {
  const Mesh sphere = makeUvSphere(64, 66);
  MeshView view = sphere.view();
  view.version = 1;
  const Rendered r = renderScene(oneMeshScene(view), fitCamera(sphere), 320, 240);
  EXPECT_EQ(r.stats.plan.blocksBackFacing, 0u);
  EXPECT_GT(r.stats.polygonsDrawn, 0u);
}

// A closed sphere edited in place (its winding reversed, a new version): its blocks are
// measured again, and the render is the one without skipping.
TEST_F(BackFacingBlocks, ANewVersionMeasuresItsBlocksAgain) {
  Mesh sphere = makeUvSphere(128, 130);
  const Camera camera = fitCamera(sphere);
  MeshView view = sphere.view();
  view.closedSurface = true;
  view.version = 1;
  Renderer renderer;
  renderer.setThreadCount(2);
  Framebuffer first(320, 240), again(320, 240);
  const RenderStats before = renderer.render(oneMeshScene(view), camera, first.view());
  EXPECT_GT(before.plan.blocksBackFacing, 0u);
  for (std::size_t p = 0; p + 1 < sphere.offsets.size(); ++p) {  // every triangle reversed
    const auto at = static_cast<std::size_t>(sphere.offsets[p]);
    std::swap(sphere.connectivity[at + 1], sphere.connectivity[at + 2]);
  }
  view.version = 2;
  const RenderStats after = renderer.render(oneMeshScene(view), camera, again.view());
  EXPECT_GT(after.plan.blocksBackFacing, 0u);
  const Rendered off = renderWith(oneMeshScene(view), camera, false);
  EXPECT_EQ(differingPixels(again, off.framebuffer), 0u);
  EXPECT_EQ(after.polygonsCulled, off.stats.polygonsCulled);
  EXPECT_EQ(after.polygonsDrawn, off.stats.polygonsDrawn);
}

// A versioned closed sphere turning: skipping on gives the bytes and counts of skipping off on
// 1, 2 and 8 threads and on every SIMD target (the set-up's batches are what it skips).
TEST_F(BackFacingBlocks, SkippingIsTheSameBytesOnEveryThreadCountAndTarget) {
  const Mesh sphere = makeUvSphere(128, 130);
  const Scene scene = oneMeshScene(closedView(sphere));
  Camera camera = fitCamera(sphere);
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  for (int turn = 0; turn < 3; ++turn) {
    camera.position = glm::dvec3(glm::rotate(glm::dmat4(1.0), 0.4 * turn, glm::dvec3(0, 1, 0)) *
                                 glm::dvec4(camera.position - camera.focalPoint, 0.0)) +
                      camera.focalPoint;
    const Rendered off = renderWith(scene, camera, false);
    for (const detail::SimdTarget& target : targets) {
      detail::useSimdTarget(target.bits);
      for (int threads : {1, 2, 8}) {
        RenderOptions options;
        options.threads = threads;
        const Rendered on = renderScene(scene, camera, 320, 240, options);
        EXPECT_GT(on.stats.plan.blocksBackFacing, 0u) << target.name << ", " << threads;
        EXPECT_TRUE(sameRender(on, off)) << target.name << ", " << threads << " threads";
      }
    }
    detail::useSimdTarget(0);
  }
}

// A NaN point makes its block not skippable (and the mesh's back faces drawn, as a closed
// surface with a non-finite point); with a culling material the others still are.
TEST_F(BackFacingBlocks, NonFinitePointsKeepTheirBlocks) {
  Mesh sphere = makeUvSphere(128, 130);
  const Camera camera = fitCamera(sphere);
  sphere.points[static_cast<std::size_t>(sphere.connectivity[5])].x =
      std::numeric_limits<double>::quiet_NaN();
  MeshView view = sphere.view();
  view.version = 1;
  Material culled;
  culled.backfaceCulling = true;
  const Rendered on = renderWith(oneMeshScene(view, culled), camera, true);
  const Rendered off = renderWith(oneMeshScene(view, culled), camera, false);
  EXPECT_TRUE(sameRender(on, off));
  EXPECT_EQ(on.stats.polygonsNonFinite, off.stats.polygonsNonFinite);
  EXPECT_GT(on.stats.polygonsNonFinite, 0u);
  EXPECT_GT(on.stats.plan.blocksBackFacing, 0u);
  view.closedSurface = true;
  EXPECT_EQ(renderWith(oneMeshScene(view), camera, true).stats.plan.blocksBackFacing, 0u);
}

// The cone of a measured block: a flat patch's is narrow; a sliver, a tiny triangle under the
// representable area or a quad makes a block not skippable.
TEST_F(BackFacingBlocks, MeasurementRefusesWhatItCannotTrust) {
  Mesh flat;
  for (int t = 0; t < 4; ++t) {
    const std::int64_t first = flat.addPoint({t, 0, 0});
    flat.addPoint({t + 1, 0, 0});
    flat.addPoint({t, 1, 0});
    flat.addPolygon({first, first + 1, first + 2});
  }
  detail::BackBlock block = detail::measureBackBlock(flat.view(), 0, 4);
  EXPECT_TRUE(block.skippable);
  EXPECT_NEAR(block.axis.z, 1.0, 1e-12);
  EXPECT_GT(block.cosAngle, 0.999999);
  EXPECT_NEAR(block.minDoubleArea, 1.0, 1e-6);

  Mesh sliver = flat;
  sliver.points[static_cast<std::size_t>(sliver.connectivity[2])] = {0.5, 1e-9, 0.0};
  EXPECT_FALSE(detail::measureBackBlock(sliver.view(), 0, 4).skippable);
  Mesh quad = flat;
  quad.addPoint({9, 9, 0});
  quad.addPolygon({0, 1, 12, 2});
  EXPECT_FALSE(detail::measureBackBlock(quad.view(), 0, 5).skippable);
  Mesh folded = flat;
  std::swap(folded.connectivity[4], folded.connectivity[5]);  // one facing the other way
  EXPECT_FALSE(detail::measureBackBlock(folded.view(), 0, 4).skippable);
}

// A block of a ring-ordered sphere uses two runs of point ids, a quarter of two rings: its two
// spans hold every id it uses and leave the rest of the ring between them out (what lets the
// transform skip the points only back-facing blocks use, ViewCulling.cpp).
TEST_F(BackFacingBlocks, ABlockOfTwoRingsKeepsTwoPointSpans) {
  const Mesh sphere = makeUvSphere(600, 40);
  const MeshView view = sphere.view();
  const std::size_t blocks = view.polygons.count / detail::kPolygonsPerBackBlock;
  std::size_t apart = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t begin = b * detail::kPolygonsPerBackBlock;
    const detail::BackBlock block =
        detail::measureBackBlock(view, begin, begin + detail::kPolygonsPerBackBlock);
    const detail::PointSpan &low = block.lowPoints, &high = block.highPoints;
    ASSERT_LE(low.first, low.last);
    EXPECT_TRUE(high.first > high.last || high.first > low.last);
    for (std::size_t p = begin; p < begin + detail::kPolygonsPerBackBlock; ++p) {
      for (std::int64_t c = sphere.offsets[p]; c < sphere.offsets[p + 1]; ++c) {
        const auto id = static_cast<std::size_t>(sphere.connectivity[static_cast<std::size_t>(c)]);
        EXPECT_TRUE((id >= low.first && id <= low.last) || (id >= high.first && id <= high.last))
            << "block " << b << ", point " << id;
      }
    }
    apart += high.first <= high.last && high.first > low.last + 300;
  }
  EXPECT_GT(apart, blocks / 2);  // most blocks leave most of a ring out
}

// The settings are the thread's and the object's: a render on another thread skips while
// this one's are off, and they return to the defaults when the object goes.
TEST_F(BackFacingBlocks, SettingsAreScopedToTheirThreadAndObject) {
  const Mesh sphere = makeUvSphere(128, 130);
  const Scene scene = oneMeshScene(closedView(sphere));
  const Camera camera = fitCamera(sphere);
  {
    const detail::ScopedBackBlockSettings off(Settings{.skipping = false, .margin = true});
    EXPECT_EQ(renderScene(scene, camera, 320, 240).stats.plan.blocksBackFacing, 0u);
    std::size_t elsewhere = 0;
    std::thread other(
        [&] { elsewhere = renderScene(scene, camera, 320, 240).stats.plan.blocksBackFacing; });
    other.join();
    EXPECT_GT(elsewhere, 0u);
  }
  EXPECT_TRUE(detail::ScopedBackBlockSettings::current().skipping);
  EXPECT_GT(renderScene(scene, camera, 320, 240).stats.plan.blocksBackFacing, 0u);
}

// The plan reports the skipped blocks on a line of their own, with their polygons (counted
// culled: the same count as without skipping), not on the view culling's line; off with that rule.
TEST_F(BackFacingBlocks, ThePlanReportsSkippedBlocksOnALineOfTheirOwn) {
  const Mesh sphere = makeUvSphere(100, 131);  // 25,800 triangles: the last block is short
  const Scene scene = oneMeshScene(closedView(sphere));
  Camera camera = fitCamera(sphere);
  camera.position = camera.focalPoint +
                    glm::dvec3(0.0, 0.0, 1.0) * glm::length(camera.position - camera.focalPoint);
  camera.viewUp = {0.0, 1.0, 0.0};  // looking down the axis: the last block faces away
  const Rendered on = renderWith(scene, camera, true);
  const Rendered off = renderWith(scene, camera, false);
  const RenderPlan& plan = on.stats.plan;
  ASSERT_GT(plan.blocksBackFacing, 0u);
  EXPECT_TRUE(sameRender(on, off));
  EXPECT_LE(plan.polygonsBackFacing, plan.blocksBackFacing * detail::kPolygonsPerBackBlock);
  EXPECT_GT(plan.polygonsBackFacing, (plan.blocksBackFacing - 1) * detail::kPolygonsPerBackBlock);
  EXPECT_LE(plan.polygonsBackFacing, on.stats.polygonsCulled);
  EXPECT_EQ(off.stats.plan.polygonsBackFacing, 0u);
  const std::string report = on.stats.describe();
  const std::string line = "fired back-facing blocks (with geometry outside the view): " +
                           std::to_string(plan.polygonsBackFacing) +
                           " polygons counted culled, not set up (" +
                           std::to_string(plan.blocksBackFacing) + " blocks)";
  EXPECT_NE(report.find(line), std::string::npos) << report;
  EXPECT_EQ(report.find("back-facing blocks skipped whole"), std::string::npos) << report;
  RenderOptions noViewCulling;
  noViewCulling.rules.geometryOutsideView = false;
  const Rendered ruleOff = renderScene(scene, camera, 320, 240, noViewCulling);
  EXPECT_EQ(ruleOff.stats.plan.blocksBackFacing, 0u);
  EXPECT_NE(ruleOff.stats.describe().find("off   back-facing blocks"), std::string::npos);
}

// vtkSphereSource's order lists a sphere meridian by meridian, so a back-face block is a
// sliver of a meridian: kPolygonsPerBackBlock small enough (64: 12° of latitude here, where
// 256 was 46° and skipped under half) and the test per block on its view-culling block's clip
// bounds (ParentClipBounds) skip most back faces whole, the same render as without skipping.
TEST_F(BackFacingBlocks, MostBackFacesOfAMeridianOrderedSphereAreSkippedWhole) {
  const Mesh sphere = makeUvSphere(100, 500, 1.0, glm::dvec3(0.0), UvSphereOrder::vtkSphereSource);
  const Scene scene = oneMeshScene(closedView(sphere));
  const Camera camera = fitCamera(sphere);
  const Rendered on = renderWith(scene, camera, true);
  const Rendered off = renderWith(scene, camera, false);
  EXPECT_TRUE(sameRender(on, off));
  EXPECT_EQ(on.stats.polygonsCulled, off.stats.polygonsCulled);
  EXPECT_GT(on.stats.plan.polygonsBackFacing, on.stats.polygonsCulled * 3 / 4);
}

// `mesh` with its point ids permuted at random: each back-face block then uses ids all over
// the mesh (its two spans cover nearly all of them), not two runs of a ring.
Mesh shuffledPoints(const Mesh& mesh, unsigned seed) {
  std::vector<std::int64_t> newId(mesh.points.size());
  for (std::size_t i = 0; i < newId.size(); ++i)
    newId[i] = static_cast<std::int64_t>(i);
  std::mt19937 random(seed);
  std::shuffle(newId.begin(), newId.end(), random);
  Mesh shuffled = mesh;
  for (std::size_t i = 0; i < newId.size(); ++i)
    shuffled.points[static_cast<std::size_t>(newId[i])] = mesh.points[i];
  for (std::int64_t& id : shuffled.connectivity)
    id = newId[static_cast<std::size_t>(id)];
  return shuffled;
}

// A block whose two spans hold far more points than its corners name lists the needed-point
// flags of its points instead (MeshCache.h, BackBlock::scatteredPointFlags): a cap of the
// sphere vtkSphereSource lists meridian by meridian (one point per meridian) does, exactly
// its points' flags; the blocks of a ring-ordered sphere's bands do not.
TEST_F(BackFacingBlocks, ScatteredBlocksListTheFlagsOfTheirPoints) {
  const Mesh meridians =
      makeUvSphere(600, 300, 1.0, glm::dvec3(0.0), UvSphereOrder::vtkSphereSource);
  const MeshView view = closedView(meridians);
  const detail::BackBlock cap = detail::measureBackBlock(view, 0, detail::kPolygonsPerBackBlock);
  std::vector<std::uint32_t> expected;
  for (std::size_t c = 0; c < 3 * detail::kPolygonsPerBackBlock; ++c)
    expected.push_back(
        static_cast<std::uint32_t>(meridians.connectivity[c] >> detail::kNeededPointBits));
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  EXPECT_EQ(cap.scatteredPointFlags, expected);
  EXPECT_LT(expected.size(), detail::kPolygonsPerBackBlock + 2);
  const Mesh rings = makeUvSphere(600, 300);
  const MeshView ringView = closedView(rings);
  for (std::size_t b = 0; b < 8; ++b) {
    const std::size_t begin = 5000 + b * detail::kPolygonsPerBackBlock;
    EXPECT_TRUE(detail::measureBackBlock(ringView, begin, begin + detail::kPolygonsPerBackBlock)
                    .scatteredPointFlags.empty());
  }
}

// The compact records the frame's cull reads (MeshCache.h) say what the whole blocks say: the
// flag ranges mark exactly the flags markPointsOfBlock marks, a scattered block sends the
// reader to its whole record, and a block that is not skippable fails the pre-test.
TEST_F(BackFacingBlocks, CompactRecordsAgreeWithTheWholeBlocks) {
  const Mesh rings = makeUvSphere(600, 300);
  const MeshView view = closedView(rings);
  const std::size_t flagCount =
      (view.points.count + detail::kPointsPerNeededFlag - 1) >> detail::kNeededPointBits;
  for (std::size_t b = 0; b < 40; ++b) {
    const std::size_t begin = 3000 + b * detail::kPolygonsPerBackBlock;
    const detail::BackBlock block =
        detail::measureBackBlock(view, begin, begin + detail::kPolygonsPerBackBlock);
    const detail::BackPointFlags ranges = detail::pointFlagsOf(block, view.points.count);
    ASSERT_NE(ranges.lowFirst, detail::kReadWholeBackBlock);
    std::vector<std::uint8_t> whole(flagCount, 0), compact(flagCount, 0);
    for (const detail::PointSpan& span : {block.lowPoints, block.highPoints}) {
      if (span.first > span.last) continue;
      std::fill(
          whole.begin() + static_cast<std::ptrdiff_t>(span.first >> detail::kNeededPointBits),
          whole.begin() + static_cast<std::ptrdiff_t>(span.last >> detail::kNeededPointBits) + 1,
          1);
    }
    std::fill(compact.begin() + ranges.lowFirst, compact.begin() + ranges.lowEnd, 1);
    std::fill(compact.begin() + ranges.highFirst, compact.begin() + ranges.highEnd, 1);
    EXPECT_EQ(compact, whole) << "block " << b;
    // On the grid of its own box: the stepped box is the box, the cone a little wider.
    const detail::BackBlockTest test = detail::testOf(block, detail::backFrameOf(block.box));
    const detail::Box box = detail::boxOf(test, detail::backFrameOf(block.box));
    EXPECT_EQ(box.low, block.box.low);
    for (int k = 0; k < 3; ++k)
      EXPECT_GE(box.high[k], block.box.high[k]);
    ASSERT_EQ(test.cosAngle > 0.0F, block.skippable);
    if (block.skippable) {
      // The test reads the rounded axis a, not â: the cosine is over |a| (BackFacingBlocks.h).
      const double length = glm::length(glm::dvec3(test.axis[0], test.axis[1], test.axis[2]));
      EXPECT_LE(test.cosAngle * length, block.cosAngle);
      EXPECT_GT(test.cosAngle * length, block.cosAngle - 1e-5);
    }
  }
  const Mesh meridians =
      makeUvSphere(600, 300, 1.0, glm::dvec3(0.0), UvSphereOrder::vtkSphereSource);
  const MeshView capView = closedView(meridians);
  const detail::BackBlock cap = detail::measureBackBlock(capView, 0, detail::kPolygonsPerBackBlock);
  ASSERT_FALSE(cap.scatteredPointFlags.empty());
  EXPECT_EQ(detail::pointFlagsOf(cap, capView.points.count).lowFirst, detail::kReadWholeBackBlock);

  Mesh quads;  // not skippable: cosAngle 0, whatever the view
  quads.addPoint({0, 0, 0});
  quads.addPoint({1, 0, 0});
  quads.addPoint({1, 1, 0});
  quads.addPoint({0, 1, 0});
  quads.addPolygon({0, 1, 2, 3});
  const detail::BackBlock quad = detail::measureBackBlock(quads.view(), 0, 1);
  ASSERT_FALSE(quad.skippable);
  EXPECT_EQ(detail::testOf(quad, detail::backFrameOf(quad.box)).cosAngle, 0.0F);
}

// A scattered block's flags are kept in its mesh's list (MeshFacts::scatteredPointFlags) and
// marked from there; a band's from its ranges: markPointsOfBlock marks what the measured
// block's spans or list name, on a mesh measured by a render.
TEST_F(BackFacingBlocks, MeasuredMeshesKeepTheFlagsOfTheirScatteredBlocks) {
  const Mesh meridians =
      makeUvSphere(600, 300, 1.0, glm::dvec3(0.0), UvSphereOrder::vtkSphereSource);
  const MeshView view = closedView(meridians);
  detail::MeshCache cache;
  Scene scene = oneMeshScene(view);
  detail::ThreadPool pool(2);
  const detail::PhaseRunner::ProgressCallback noProgress;
  detail::PhaseRunner runner(pool, noProgress, {detail::Phase::Measure});
  ASSERT_TRUE(cache.update(runner, scene, true));
  const detail::MeshFacts& facts = cache[0];
  const std::size_t flagCount =
      (view.points.count + detail::kPointsPerNeededFlag - 1) >> detail::kNeededPointBits;
  std::size_t scattered = 0;
  for (std::size_t b = 0; b < facts.backBlockCount(); ++b) {
    const std::size_t begin = b * detail::kPolygonsPerBackBlock;
    const detail::BackBlock block = detail::measureBackBlock(
        view, begin, std::min(view.polygons.count, begin + detail::kPolygonsPerBackBlock));
    std::vector<std::uint8_t> expected(flagCount, 0), marked(flagCount, 0);
    if (!block.scatteredPointFlags.empty()) {
      ++scattered;
      for (const std::uint32_t f : block.scatteredPointFlags)
        expected[f] = 1;
    } else {
      for (const detail::PointSpan& span : {block.lowPoints, block.highPoints}) {
        for (std::size_t id = span.first; id <= span.last && span.first <= span.last; ++id)
          expected[id >> detail::kNeededPointBits] = 1;
      }
    }
    detail::markPointsOfBlock(facts, b, marked.data());
    ASSERT_EQ(marked, expected) << "block " << b;
    const detail::BackBlockTest compact = detail::testOf(block, facts.backFrameOf(b));
    EXPECT_EQ(std::memcmp(&compact, &facts.backTests[b], sizeof compact), 0) << "block " << b;
  }
  EXPECT_GT(scattered, 4u);  // both caps
}

// The compact record is conservative (BackFacingBlocks.h, "The compact record"): on random
// blocks (patches of tiny triangles and slivers too) seen from random views, perspective and
// parallel, near the origin and far from it, with their boxes anywhere on their grid (the
// grid's box the block's own: its corners at 0 and 65535; or up to 40 times wider around it),
// every block the compact test culls, the exact test culls, the stepped box holds the block's
// and every normal is inside the stored cone; and the compact test culls nearly as many.
TEST_F(BackFacingBlocks, CompactTestCullsOnlyWhatTheExactTestCulls) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t exactCulled = 0, compactCulled = 0, blocks = 0, atEnds = 0;
  unsigned patchSeed = 3;  // one per center (not from the center: -7e7 is no unsigned)
  for (const glm::dvec3 center : {glm::dvec3(0.0), glm::dvec3(3.0, -2.0, 1.0),
                                  glm::dvec3(1e5, 2e5, -3e5), glm::dvec3(-7e7, 1e6, 3e7)}) {
    const Mesh mesh = patches(48, patchSeed++, center);
    const MeshView view = mesh.view();
    std::vector<detail::BackBlock> measured;
    for (std::size_t b = 0; b < 48; ++b) {
      const std::size_t begin = b * detail::kPolygonsPerBackBlock;
      measured.push_back(
          detail::measureBackBlock(view, begin, begin + detail::kPolygonsPerBackBlock));
    }
    for (int v = 0; v < 24; ++v) {
      const Camera camera = randomCamera(random, center, v % 3 == 2);
      const detail::FrameTransform transform(camera, 640, 480);
      const detail::BackFaceTest test(transform);
      for (std::size_t b = 0; b < measured.size(); ++b) {
        const detail::BackBlock& block = measured[b];
        if (!block.skippable) continue;
        detail::Box grid = block.box;
        if ((v + b) % 3 != 0) {  // a wider grid, the block anywhere in it
          const glm::dvec3 size = block.box.high - block.box.low;
          for (int k = 0; k < 3; ++k) {
            grid.low[k] -= 40.0 * size[k] * unit(random);
            grid.high[k] += 40.0 * size[k] * unit(random);
          }
        }
        const detail::BackBlockFrame frame = detail::backFrameOf(grid);
        const detail::BackBlockTest compact = detail::testOf(block, frame);
        ASSERT_GT(compact.cosAngle, 0.0F) << "block " << b;
        const detail::Box box = detail::boxOf(compact, frame);
        for (int k = 0; k < 3; ++k) {
          ASSERT_LE(box.low[k], block.box.low[k]);
          ASSERT_GE(box.high[k], block.box.high[k]);
          atEnds += compact.low[k] == 0 && compact.high[k] == 65535;
        }
        const glm::dvec3 axis(compact.axis[0], compact.axis[1], compact.axis[2]);
        const double length = glm::length(axis);
        for (std::size_t p = b * detail::kPolygonsPerBackBlock;
             p < (b + 1) * detail::kPolygonsPerBackBlock; ++p) {
          const auto corner = [&](int k) {
            return mesh.points[static_cast<std::size_t>(mesh.connectivity[3 * p + k])];
          };
          const glm::dvec3 n =
              glm::normalize(glm::cross(corner(1) - corner(0), corner(2) - corner(0)));
          ASSERT_GE(glm::dot(n, axis) / length, compact.cosAngle * length) << "polygon " << p;
        }
        EXPECT_LE(compact.minDoubleArea, block.minDoubleArea);
        EXPECT_GE(compact.maxPerimeterPerDoubleArea, block.maxPerimeterPerDoubleArea);
        const bool exact = test.certainlyCulled(block);
        const bool stepped = test.certainlyCulled(compact, frame);
        ASSERT_TRUE(exact || !stepped) << "block " << b << ", view " << v;
        ++blocks;
        exactCulled += exact;
        compactCulled += stepped;
      }
    }
  }
  EXPECT_GT(atEnds, blocks / 4);
  EXPECT_GT(exactCulled, blocks / 10);
  EXPECT_GE(compactCulled, exactCulled * 9 / 10) << exactCulled << " of " << blocks;
}

// The points a drawn block needs are transformed whatever the layout of their ids and
// whichever of three meshes they belong to (FrameMesh::neededPoints, per kPointsPerNeededFlag
// points, from each back-face block's two spans or its list of flags): renders with back-face
// blocks skipped and blocks outside the view left out, from views that leave part of each
// sphere out, are the same bytes as with neither.
TEST_F(BackFacingBlocks, NeededPointsOfEveryLayoutAndMeshAreTransformed) {
  const Mesh ordered = makeUvSphere(160, 120, 1.0, glm::dvec3(-0.6, 0.0, 0.0));
  const Mesh shuffled = shuffledPoints(makeUvSphere(150, 110, 0.8, glm::dvec3(0.9, 0.2, 0.0)), 7);
  const Mesh meridians =
      makeUvSphere(170, 90, 0.6, glm::dvec3(0.1, -0.9, 0.3), UvSphereOrder::vtkSphereSource);
  Scene scene;
  scene.meshes.push_back({closedView(ordered), {}});
  scene.meshes.push_back({closedView(shuffled), {}});
  scene.meshes.push_back({closedView(meridians), {}});
  scene.lights.lights.push_back(PointLight{glm::dvec3(0, 0, 9), Color(1.0f), 1.0, NoAttenuation{}});
  std::mt19937 random(5);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  std::size_t skipped = 0, outside = 0;
  for (int v = 0; v < 12; ++v) {
    SCOPED_TRACE("view " + std::to_string(v));
    const double a = angle(random), b = angle(random) / 4.0 - 0.4;
    Camera camera;
    camera.focalPoint = glm::dvec3(0.3 * std::cos(a), 0.3 * std::sin(a), 0.0);
    camera.position = camera.focalPoint + 4.0 * glm::dvec3(std::cos(a) * std::cos(b), std::sin(b),
                                                           std::sin(a) * std::cos(b));
    camera.viewUp = {0.0, 1.0, 0.0};
    camera.viewAngleDegrees = 14.0 + 2.0 * v;  // a part of each sphere out of view
    RenderOptions neither;
    neither.rules.geometryOutsideView = false;
    const Rendered reference = renderWith(scene, camera, false);
    const Rendered plain = renderScene(scene, camera, 320, 240, neither);
    ASSERT_EQ(reference.stats.plan.blocksBackFacing, 0u);
    const Rendered both = renderWith(scene, camera, true);
    EXPECT_EQ(differingPixels(both.framebuffer, plain.framebuffer), 0u);
    EXPECT_EQ(differingPixels(reference.framebuffer, plain.framebuffer), 0u);
    EXPECT_EQ(both.stats.polygonsDrawn, plain.stats.polygonsDrawn);
    skipped += both.stats.plan.blocksBackFacing;
    outside += both.stats.plan.blocksOutside;
  }
  EXPECT_GT(skipped, 12u);  // the test tests both
  EXPECT_GT(outside, 12u);
}

}  // namespace
}  // namespace facet::testing
