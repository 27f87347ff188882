// The hidden blocks' corners taken in SIMD lanes (HiddenBlockCorners.h) against
// FrameTransform's corner by corner (boxInsideClipVolume, toWindow), on every instruction set
// this CPU has: the same answer and the same bits.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "Box.h"
#include "FrameTransform.h"
#include "HiddenBlockCorners.h"
#include "SetupBatch.h"

namespace facet::testing {
namespace {

using detail::BlockCorners;
using detail::Box;
using detail::ClipPoint;
using detail::FrameTransform;

// The corners as HiddenBlockTest took them before the lanes: one by one.
bool cornersOneByOne(const FrameTransform& transform, const Box& box, BlockCorners& out) {
  ClipPoint corners[8];
  const bool inside = transform.boxInsideClipVolume(box, corners);
  // FrameTransform's corners (clipCorners: 18 products shared by the corners) are toClip's
  // bits for every box none of whose corners toClip scales or leaves non-finite, inside the
  // clip volume or not (the view cull's boxOutsideView takes the same corners); it refuses
  // the others.
  ClipPoint each[8];
  bool unscaled = !box.empty();
  for (int i = 0; i < 8; ++i) {
    const ClipPoint& c = each[i] = transform.toClip(box.corner(i));
    unscaled =
        unscaled && c.h == 1.0 && std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.d);
  }
  for (int i = 0; i < 8 && unscaled; ++i)
    EXPECT_TRUE(std::memcmp(&each[i], &corners[i], sizeof each[i]) == 0) << "corner " << i;
  EXPECT_TRUE(unscaled || !inside);
  if (!inside) return false;
  out.x0 = out.y0 = std::numeric_limits<std::int64_t>::max();
  out.x1 = out.y1 = std::numeric_limits<std::int64_t>::min();
  out.nearest = std::numeric_limits<double>::infinity();
  out.farthest = -out.nearest;
  for (const ClipPoint& c : corners) {
    const detail::WindowVertex v = transform.toWindow(c);
    out.x0 = std::min<std::int64_t>(out.x0, v.x), out.x1 = std::max<std::int64_t>(out.x1, v.x);
    out.y0 = std::min<std::int64_t>(out.y0, v.y), out.y1 = std::max<std::int64_t>(out.y1, v.y);
    out.nearest = std::min(out.nearest, c.d), out.farthest = std::max(out.farthest, c.d);
  }
  return true;
}

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Boxes of every kind around the view: inside, across the near plane (some corners behind
// the eye), across the guard band's sides and the far plane, flat and point boxes, beyond
// kLargeCoordinate; returns how many were inside.
std::size_t expectTheLanesCorners(const Camera& camera, std::uint32_t seed) {
  const FrameTransform transform(camera, 640, 480);
  const detail::ProjectionConstants constants = transform.constants();
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), signedUnit(-1.0, 1.0);
  const glm::dvec3 eye = camera.position;
  const glm::dvec3 ahead = glm::normalize(camera.focalPoint - camera.position);
  const double near = camera.nearClip, far = camera.farClip;
  std::vector<Box> boxes;
  for (int i = 0; i < 4000; ++i) {
    Box box;
    const int kind = i % 8;
    // A center along the view at a distance from just before the near plane to beyond the
    // far one, spread sideways by up to a few view widths.
    double distance = near + (far - near) * unit(random) * unit(random) * 1.2;
    if (kind == 1) distance = near * (1.0 + 1e-10 * signedUnit(random));  // on the near plane
    if (kind == 2) distance = far * (1.0 + 1e-10 * signedUnit(random));   // on the far plane
    if (kind == 3) distance = near * signedUnit(random);                  // around the eye
    const double side = distance * (kind == 4 ? 40.0 : 0.6);
    glm::dvec3 sideways(signedUnit(random), signedUnit(random), signedUnit(random));
    sideways -= glm::dot(sideways, ahead) * ahead;  // the distance stays as chosen
    const glm::dvec3 center = eye + distance * ahead + side * sideways;
    // Boxes on the near or far plane within a few of the test's margins (1e-9).
    const double size =
        distance * (kind == 1 || kind == 2 ? 1e-9 : 0.05) * unit(random) * unit(random);
    glm::dvec3 half(size * unit(random), size * unit(random), size * unit(random));
    if (kind == 5) half = glm::dvec3(0.0);  // a point
    if (kind == 6) half.y = 0.0;            // flat
    box.add(center - half), box.add(center + half);
    if (kind == 7 && i % 16 == 7) box.add(eye + glm::dvec3(0x1p501, 0.0, 0.0));  // scaled
    if (kind == 3 && i % 24 == 3) box.add(eye);                                  // the eye
    boxes.push_back(box);
  }
  std::vector<char> expectedInside;
  std::vector<BlockCorners> expected(boxes.size());
  std::size_t inside = 0;
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    expectedInside.push_back(cornersOneByOne(transform, boxes[b], expected[b]));
    inside += expectedInside.back() != 0;
  }
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    // HiddenBlockTest's way: the target's function taken once, called per box.
    const detail::BlockCornersFunction taken = detail::blockCornersFunction();
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      BlockCorners corners;
      const bool lanesInside = detail::blockCorners(constants, boxes[b], corners);
      EXPECT_EQ(lanesInside, expectedInside[b] != 0) << "box " << b;
      BlockCorners takenCorners;
      EXPECT_EQ(taken(constants, boxes[b], takenCorners), lanesInside) << "box " << b;
      if (lanesInside) {
        EXPECT_EQ(std::memcmp(&takenCorners, &corners, sizeof corners), 0) << "box " << b;
      }
      if (!lanesInside || expectedInside[b] == 0) continue;
      EXPECT_EQ(corners.x0, expected[b].x0) << "box " << b;
      EXPECT_EQ(corners.y0, expected[b].y0) << "box " << b;
      EXPECT_EQ(corners.x1, expected[b].x1) << "box " << b;
      EXPECT_EQ(corners.y1, expected[b].y1) << "box " << b;
      EXPECT_TRUE(sameBits(corners.nearest, expected[b].nearest)) << "box " << b;
      EXPECT_TRUE(sameBits(corners.farthest, expected[b].farthest)) << "box " << b;
      EXPECT_FALSE(std::isnan(corners.nearest) || std::isnan(corners.farthest));
    }
  }
  detail::useSimdTarget(0);
  return inside;
}

class HiddenBlockCorners : public EveryTargetTest {};

// Checked to fail with the near or the far plane's margin dropped in the lanes, and with a
// lane's y scaled by the half width.
TEST_F(HiddenBlockCorners, LanesGiveTheCornerByCornerBitsOnEveryTarget) {
  Camera perspective;
  perspective.position = {1.5, -2.0, 7.0};
  perspective.focalPoint = {0.2, 0.3, -0.4};
  perspective.viewUp = {0.1, 1.0, 0.2};
  perspective.nearClip = 0.5, perspective.farClip = 30.0;
  Camera parallel = perspective;
  parallel.parallelProjection = true, parallel.parallelScale = 3.0;
  parallel.nearClip = -2.0;
  Camera far = perspective;  // far from the origin: the eye-relative differences matter
  far.position += glm::dvec3(1e6, -3e6, 2e5), far.focalPoint += glm::dvec3(1e6, -3e6, 2e5);
  for (const Camera& camera : {perspective, parallel, far}) {
    SCOPED_TRACE(camera.parallelProjection ? "parallel" : "perspective");
    const std::size_t inside = expectTheLanesCorners(camera, 33);
    // Both answers often: inside boxes are what the test is for.
    EXPECT_GT(inside, 400u);
    EXPECT_LT(inside, 3600u);
  }
}

// A box whose corners straddle the near plane (some behind the eye) is never inside; a point
// box (a degenerate block) well inside is, with finite bounds and one distance.
TEST_F(HiddenBlockCorners, NearPlaneStraddlersAreOutsideAndPointBoxesFinite) {
  Camera camera;
  camera.position = {0.0, 0.0, 5.0};
  camera.nearClip = 1.0, camera.farClip = 20.0;
  const FrameTransform transform(camera, 640, 480);
  Box straddler;
  straddler.add({-0.1, -0.1, 3.5}), straddler.add({0.1, 0.1, 4.5});  // d from 0.5 to 1.5
  Box behind;
  behind.add({-0.1, -0.1, 4.0}), behind.add({0.1, 0.1, 6.0});  // through the eye
  Box point;
  point.add({0.25, -0.125, 0.0});
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    BlockCorners corners;
    EXPECT_FALSE(detail::blockCorners(transform.constants(), straddler, corners));
    EXPECT_FALSE(detail::blockCorners(transform.constants(), behind, corners));
    ASSERT_TRUE(detail::blockCorners(transform.constants(), point, corners));
    EXPECT_EQ(corners.x0, corners.x1);
    EXPECT_EQ(corners.y0, corners.y1);
    EXPECT_EQ(corners.nearest, 5.0);
    EXPECT_EQ(corners.farthest, 5.0);
    BlockCorners expected;
    ASSERT_TRUE(cornersOneByOne(transform, point, expected));
    EXPECT_EQ(corners.x0, expected.x0);
    EXPECT_EQ(corners.y0, expected.y0);
  }
  detail::useSimdTarget(0);
}

// blockCornersFunction (HiddenBlockTest takes it once): the function of the target in use, a
// different one per target; before any dispatch (a process's first render, two at once on two
// threads) the best target's, not Highway's first-call initializer.
TEST_F(HiddenBlockCorners, TheTakenFunctionIsTheTargetInUses) {
  std::vector<detail::BlockCornersFunction> seen;
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    const detail::BlockCornersFunction taken = detail::blockCornersFunction();
    ASSERT_NE(taken, nullptr);
    EXPECT_EQ(detail::blockCornersFunction(), taken);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), taken), 0);
    seen.push_back(taken);
  }
  detail::useSimdTarget(0);
  const detail::BlockCornersFunction best = detail::blockCornersFunction();
  EXPECT_EQ(best, seen.front());
  expectFirstDispatchOnTwoThreadsGives(detail::blockCornersFunction, best);
}

}  // namespace
}  // namespace facet::testing
