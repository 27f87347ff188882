// The projection in SIMD lanes (TransformBatch.h) against FrameTransform::project point by
// point, byte for byte, on every instruction set this CPU has (project() as the library
// compiles it, detail::projectPoint: this file's own flags could fuse its products): perspective
// and parallel cameras, data far from the origin, huge far/near ratios, points behind the eye,
// beyond the guard band, on the near plane, beyond kLargeCoordinate, and not finite; float and
// double points; runs that do not fill the last group of lanes.

#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "FrameTransform.h"
#include "SetupBatch.h"
#include "TransformBatch.h"
#include "facet/Camera.h"

namespace facet::testing {
namespace {

using detail::FrameTransform;
using detail::WindowVertex;

constexpr int kWidth = 1920, kHeight = 1080;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMax = std::numeric_limits<double>::max();

struct CameraCase {
  std::string name;
  Camera camera;
};

Camera cameraAt(glm::dvec3 position, glm::dvec3 direction, double near, double far, bool parallel) {
  Camera c;
  c.position = position;
  c.focalPoint = position + direction;
  c.viewUp = {0.3, 1.0, -0.2};
  c.viewAngleDegrees = 35.0;
  c.parallelProjection = parallel;
  c.parallelScale = 2.5;
  c.windowCenter = {0.1, -0.05};
  c.nearClip = near;
  c.farClip = far;
  return c;
}

std::vector<CameraCase> cameraCases() {
  const glm::dvec3 direction{0.3, -0.2, -1.0};
  std::vector<CameraCase> cases;
  for (bool parallel : {false, true}) {
    const std::string kind = parallel ? "parallel, " : "perspective, ";
    cases.push_back(
        {kind + "near the origin", cameraAt({1, 2, 10}, direction, 0.1, 100.0, parallel)});
    cases.push_back({kind + "1e9 from the origin",
                     cameraAt({1e9 + 1, 1e9 + 2, 1e9 + 10}, direction, 0.1, 100.0, parallel)});
    cases.push_back(
        {kind + "far/near 1e18", cameraAt({1, 2, 10}, direction, 1e-6, 1e12, parallel)});
    cases.push_back(
        {kind + "near below 2^-480", cameraAt({1, 2, 10}, direction, 1e-300, 1e300, parallel)});
  }
  return cases;
}

// Points around the camera's view: along the view from behind the eye to beyond the far
// plane (log-spaced), across it out to beyond the guard band, a few on the near plane, and
// the stiff values: NaN, infinities, DBL_MAX, beyond kLargeCoordinate from the eye, the eye.
std::vector<double> pointsFor(const Camera& camera, std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> kind(0, 19);
  const glm::dvec3 forward = glm::normalize(camera.focalPoint - camera.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.viewUp));
  const glm::dvec3 up = glm::cross(right, forward);
  const double logNear = std::log(camera.nearClip), logFar = std::log(camera.farClip);
  const double stiff[] = {kNaN, kInf, -kInf, kMax, -kMax, 0x1p500, 0x1p501, 1e-310};
  std::vector<double> xyz;
  for (std::size_t i = 0; i < count; ++i) {
    const int k = kind(random);
    double t = std::exp(logNear - 1.0 + (logFar - logNear + 2.0) * (0.5 + 0.5 * unit(random)));
    if (k == 0) t = -t;                         // behind the eye
    if (k == 1) t = camera.nearClip;            // on the near plane
    const double spread = k == 2 ? 40.0 : 1.2;  // beyond the guard band
    const double lateral = camera.parallelProjection ? camera.parallelScale * 2.0 : t * 0.7;
    glm::dvec3 p = camera.position + t * forward + spread * lateral * unit(random) * right +
                   spread * lateral * unit(random) * up;
    if (k == 3) p = camera.position;
    if (k == 4) p[random() % 3] = stiff[random() % std::size(stiff)];
    if (k == 5) p = camera.position + 0x1p500 * (0.9 + 0.2 * unit(random)) * forward;
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  }
  return xyz;
}

std::string describe(const WindowVertex& v) {
  return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", key " +
         std::to_string(v.depth) + ", outcode " + std::to_string(v.outcode) + ", residues " +
         std::to_string(v.residueX) + " " + std::to_string(v.residueY) + ")";
}

// projectPoints against project(), point by point: the number of vertices that differ.
template <class Scalar>
std::size_t differences(const FrameTransform& transform, const std::vector<Scalar>& xyz) {
  const std::size_t count = xyz.size() / 3;
  std::vector<WindowVertex> batch(count + 1);
  batch[count].x = 12345;  // nothing is written past the run
  const std::uint32_t any = detail::projectPoints(transform, xyz.data(), count, batch.data());
  std::uint32_t expectedAny = 0;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const WindowVertex expected = detail::projectPoint(
        transform, {double(xyz[3 * i]), double(xyz[3 * i + 1]), double(xyz[3 * i + 2])});
    expectedAny |= expected.outcode;
    if (std::memcmp(&expected, &batch[i], sizeof expected) != 0 && ++differing <= 5) {
      ADD_FAILURE() << "point " << i << " (" << xyz[3 * i] << ", " << xyz[3 * i + 1] << ", "
                    << xyz[3 * i + 2] << "): lanes " << describe(batch[i]) << ", project "
                    << describe(expected);
    }
  }
  EXPECT_EQ(any, expectedAny);
  EXPECT_EQ(batch[count].x, 12345);
  return differing;
}

class TransformBatches : public EveryTargetTest {};

TEST_F(TransformBatches, LanesGiveProjectsBytesOnEveryTarget) {
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  ASSERT_GE(targets.size(), 1u);
  for (const detail::SimdTarget& target : targets) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    ASSERT_STREQ(detail::simdTargetInUse(), target.name);
    unsigned seed = 1;
    for (const CameraCase& c : cameraCases()) {
      SCOPED_TRACE(c.name);
      const FrameTransform transform(c.camera, kWidth, kHeight);
      const std::vector<double> xyz = pointsFor(c.camera, 20000, seed++);
      std::size_t inside = 0;
      for (std::size_t i = 0; i < xyz.size(); i += 3)
        inside += detail::projectPoint(transform, {xyz[i], xyz[i + 1], xyz[i + 2]}).outcode ==
                  detail::kInside;
      EXPECT_GT(inside, 4000u) << "most points should be drawn";
      EXPECT_EQ(differences(transform, xyz), 0u);
      const std::vector<float> asFloat(xyz.begin(), xyz.end());
      EXPECT_EQ(differences(transform, asFloat), 0u);
      // Runs shorter than a group of lanes, and ones that end inside a group.
      for (std::size_t points : {0, 1, 3, 7, 9, 17}) {
        const std::vector<double> run(xyz.begin(), xyz.begin() + 3 * points);
        EXPECT_EQ(differences(transform, run), 0u) << points << " points";
      }
    }
  }
}

}  // namespace
}  // namespace facet::testing
