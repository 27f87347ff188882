// Clipping is robust for every finite input (issue 7, defect 3): the clipper itself, swept
// over magnitudes 1e0 … 1e308 and signs through the near, far and guard-band planes, and
// renders whose coverage has a closed form — a floor through the near plane out to ±1e308,
// vertices at w ≈ 0, window coordinates far beyond the fixed-point range.

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "../support/TestRender.h"
#include "Clipper.h"
#include "FrameTransform.h"

namespace facet::testing {
namespace {

using detail::ClipPoint;
using detail::ClipVertex;

Camera lookingDownMinusZ(double nearClip = 0.01, double farClip = 100.0) {
  Camera camera;
  camera.position = {0, 0, 0};
  camera.focalPoint = {0, 0, -1};
  camera.viewAngleDegrees = 90.0;  // tan(45°) = 1: NDC y = view y / distance
  camera.nearClip = nearClip;
  camera.farClip = farClip;
  return camera;
}

bool finite(const ClipPoint& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.d) && std::isfinite(c.h);
}

// Clips random triangles whose corners have magnitudes 10^k (k = 0…308, random signs and
// axes) and checks what the clipper promises: 0 or 3..9 finite vertices, inside every plane
// to rounding, each new one exactly on some plane, w > 0 — and that they reach window
// coordinates inside the guard band (no undefined conversion: the sanitizer build checks).
TEST(Clipper, EveryFiniteMagnitudeGivesFiniteVerticesOnThePlanes) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> exponent(0, 308), pick(0, 5);
  std::uniform_real_distribution<double> mantissa(1.0, 9.99);
  std::size_t clippedTriangles = 0;
  for (bool parallel : {false, true}) {
    for (double nearClip : {1e-300, 1e-8, 0.01, 1.0}) {
      Camera camera = lookingDownMinusZ(nearClip, parallel ? 1e300 : 100.0);
      camera.parallelProjection = parallel;
      const detail::FrameTransform transform(camera, 64, 48);
      for (int trial = 0; trial < 4000; ++trial) {
        ClipVertex triangle[3];
        std::uint32_t planes = 0;
        for (std::uint32_t i = 0; i < 3; ++i) {
          glm::dvec3 p(mantissa(random), mantissa(random), mantissa(random));
          for (int axis = 0; axis < 3; ++axis) {
            p[axis] *= std::pow(10.0, exponent(random) * (pick(random) < 3 ? 1 : -1));
            if (!std::isfinite(p[axis])) p[axis] = std::numeric_limits<double>::max();
            if (pick(random) < 3) p[axis] = -p[axis];
          }
          triangle[i] = {transform.toClip(p), i, static_cast<std::uint8_t>(7u & ~(1u << i))};
          const std::uint32_t code = transform.outcode(triangle[i].clip);
          ASSERT_EQ(code & detail::kNonFinite, 0u)
              << "finite point " << p.x << " " << p.y << " " << p.z << " became non-finite";
          planes |= code;
        }
        ClipVertex out[detail::kMaxClippedVertices];
        const int count = detail::clipTriangle(transform, triangle, planes, out);
        ASSERT_TRUE(count == 0 || (count >= 3 && count <= detail::kMaxClippedVertices)) << count;
        clippedTriangles += count > 0 && planes != 0;
        for (int i = 0; i < count; ++i) {
          const ClipPoint& c = out[i].clip;
          ASSERT_TRUE(finite(c)) << "vertex " << i << " of trial " << trial;
          ASSERT_GT(parallel ? c.h : c.d, 0.0) << "w of vertex " << i;
          bool onAPlane = false;
          for (int plane = 0; plane < detail::kClipPlaneCount; ++plane) {
            const double distance = transform.planeDistance(c, plane);
            onAPlane |= distance == 0.0;
            const double scale = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.d), c.h});
            ASSERT_GE(distance, -1e-12 * scale * 2e4) << "plane " << plane << ", trial " << trial;
          }
          if (out[i].source == ClipVertex::kNewVertex) {
            EXPECT_TRUE(onAPlane) << "a new vertex lies exactly on the plane it was clipped to";
          }
          const detail::WindowVertex w = transform.toWindow(c);
          ASSERT_LE(std::abs(w.x), 1 << 24);
          ASSERT_LE(std::abs(w.y), 1 << 24);
          ASSERT_TRUE(std::isfinite(w.depth));
        }
      }
    }
  }
  EXPECT_GT(clippedTriangles, 1000u) << "the sweep should clip many triangles";
}

// The intersection of an edge with the near plane, from a point far behind the eye (1e18)
// to one far in front, used to be NaN (issue 7): now it is on the plane, between the ends.
TEST(Clipper, EdgeFromFarBehindToFarInFrontCrossesTheNearPlaneWhereItShould) {
  const Camera camera = lookingDownMinusZ(1.0, 100.0);
  const detail::FrameTransform transform(camera, 64, 48);
  for (double magnitude : {1e18, 1e100, 1e200, 1e300, std::numeric_limits<double>::max()}) {
    const ClipVertex triangle[3] = {{transform.toClip({0.0, -1.0, magnitude}), 0, 6},
                                    {transform.toClip({1.0, -1.0, -magnitude}), 1, 5},
                                    {transform.toClip({-1.0, -1.0, -magnitude}), 2, 3}};
    ClipVertex out[detail::kMaxClippedVertices];
    const int count = detail::clipTriangle(transform, triangle, detail::kBeyondNear, out);
    ASSERT_EQ(count, 4) << "magnitude " << magnitude;
    for (int i = 0; i < count; ++i) {
      const ClipPoint& c = out[i].clip;
      ASSERT_TRUE(finite(c)) << "magnitude " << magnitude;
      EXPECT_GE(c.d, c.h * camera.nearClip) << "magnitude " << magnitude;
      // The floor y = −1 stays y = −1: with a 90° view angle, y/h is the view-space y.
      EXPECT_NEAR(c.y / c.h, -1.0, 1e-9) << "magnitude " << magnitude;
    }
  }
}

// Which side of the clipping the pixel center (px, py) is on, for a plane at distance 1 from
// the eye along screen axis `axis` (0: x, 1: y) on side `side` (±1), seen by
// lookingDownMinusZ on a width × height image: the ray through the center meets the plane
// at view distance 1/(side·ndc·scale), visible up to the far plane. Returns +1 covered, −1
// not, 0 within `margin` pixels of the boundary (either answer is right there).
int expectedCoverage(int axis, double side, int px, int py, int width, int height, double farClip,
                     double margin) {
  const double aspect = double(width) / height;
  const double ndc =
      axis == 0 ? (2.0 * (px + 0.5) / width - 1.0) * aspect : 2.0 * (py + 0.5) / height - 1.0;
  const double pixelsPerUnit = axis == 0 ? width / (2.0 * aspect) : height / 2.0;
  const double threshold = 1.0 / farClip;  // side·ndc ≥ 1/f: hit before the far plane
  const double offset = (side * ndc - threshold) * pixelsPerUnit;
  return offset > margin ? 1 : (offset < -margin ? -1 : 0);
}

// A huge triangle in the plane {axis} = side (a floor, ceiling or wall at distance 1) from
// +magnitude (behind the eye) to −magnitude (in front), ±magnitude across: it crosses the
// near, far and guard-band planes. The visible part is exactly the plane's points nearer
// than the far plane: a half-image whose edge has a closed form.
Mesh hugeTriangleInPlane(int axis, double side, double magnitude, bool reversed) {
  Mesh mesh;
  const auto point = [&](double across, double z) {
    glm::dvec3 p(0.0, 0.0, z);
    p[axis] = side;
    p[1 - axis] = across;
    return p;
  };
  mesh.addPoint(point(-magnitude, magnitude));
  mesh.addPoint(point(magnitude, magnitude));
  mesh.addPoint(point(0.0, -magnitude));
  mesh.addPolygon(reversed ? std::vector<std::int64_t>{0, 2, 1}
                           : std::vector<std::int64_t>{0, 1, 2});
  return mesh;
}

TEST(ClippingRenders, FloorsAndWallsThroughEveryPlaneOutToTheLargestDouble) {
  const int width = 64, height = 48;
  const Camera camera = lookingDownMinusZ(0.01, 100.0);
  std::size_t checked = 0;
  for (int exponent = 3; exponent <= 308; exponent += 5) {
    const double magnitude =
        exponent == 308 ? std::numeric_limits<double>::max() : std::pow(10.0, exponent);
    for (int axis : {0, 1}) {
      for (double side : {-1.0, 1.0}) {
        for (bool reversed : {false, true}) {
          const Mesh mesh = hugeTriangleInPlane(axis, side, magnitude, reversed);
          const Rendered r = renderScene(oneMeshScene(mesh.view()), camera, width, height);
          SCOPED_TRACE("magnitude 1e" + std::to_string(exponent) + ", axis " +
                       std::to_string(axis) + ", side " + std::to_string(side));
          ASSERT_EQ(r.stats.polygonsNonFinite, 0u);
          std::size_t wrong = 0;
          for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
              const int expected =
                  expectedCoverage(axis, side, x, y, width, height, camera.farClip, 0.5);
              const bool covered = r.framebuffer.polygonIdAt(x, y) == 0;
              wrong += expected != 0 && covered != (expected > 0);
              checked += expected != 0;
              const float depth = r.framebuffer.depthAt(x, y);
              ASSERT_TRUE(depth >= 0.0f && depth <= 1.0f) << depth;
            }
          }
          EXPECT_EQ(wrong, 0u);
        }
      }
    }
  }
  EXPECT_GT(checked, 100000u);
}

// A floor triangle with its near corners in the eye's plane (w = 0, or ±1e-300 of it) and its
// apex 100 in front: clipped at the near plane, it shows the floor between the near and far
// planes within the triangle's widening sides.
TEST(ClippingRenders, VerticesAtWNearZero) {
  const int width = 80, height = 60;
  const Camera camera = lookingDownMinusZ(0.01, 50.0);
  for (double z :
       {0.0, 1e-300, -1e-300, 1e-30, -1e-30, std::numeric_limits<double>::denorm_min()}) {
    Mesh floor;
    floor.addPoint({-1.0, -1.0, z});
    floor.addPoint({1.0, -1.0, z});
    floor.addPoint({0.0, -1.0, -100.0});
    floor.addPolygon({0, 1, 2});
    const Rendered r = renderScene(oneMeshScene(floor.view()), camera, width, height);
    std::size_t wrong = 0, covered = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const double ny = 2.0 * (y + 0.5) / height - 1.0;
        const double nx = (2.0 * (x + 0.5) / width - 1.0) * width / height;
        if (ny >= -1e-9) {
          wrong += r.framebuffer.polygonIdAt(x, y) == 0;
          continue;
        }
        const double distance = -1.0 / ny, halfWidth = (100.0 - distance) / 100.0;
        // Half a pixel of slack, in world units at that distance, on both tests.
        const double slack = 0.5 * 2.0 / height * distance * distance;
        const double across = std::abs(nx * distance) - halfWidth;
        const double beyond = distance - camera.farClip;
        if (std::abs(across) < slack || std::abs(beyond) < slack * 4) continue;
        const bool expected = across < 0.0 && beyond < 0.0;
        covered += expected;
        wrong += (r.framebuffer.polygonIdAt(x, y) == 0) != expected;
      }
    }
    EXPECT_EQ(wrong, 0u) << "z = " << z;
    EXPECT_GT(covered, 300u) << "z = " << z;
  }
}

// Triangles in the plane 10 in front whose far corners are up to 1e300 pixels off screen
// (beyond the 2^15-pixel fixed-point range by far), one edge crossing the image along the
// line y = 0.3·x (view units): the guard band clips them, and coverage is the half plane
// below the line. The clipper interpolates in double, so the crossing is placed to within
// about 2^-53 of the corners' magnitude: exact to the pixel up to corners ~1e14 screen
// sizes away; beyond, the triangle is still clipped and drawn (no NaN, nothing out of
// range), its edge off by that rounding.
TEST(ClippingRenders, WindowCoordinatesFarBeyondTheFixedPointRange) {
  const int width = 64, height = 48;
  const Camera camera = lookingDownMinusZ(1.0, 100.0);
  const double distance = 10.0;
  for (int exponent = 2; exponent <= 300; exponent += 2) {
    const double far = std::pow(10.0, exponent);
    Mesh mesh;
    mesh.addPoint({-far, -0.3 * far, -distance});
    mesh.addPoint({far, -far, -distance});
    mesh.addPoint({far, 0.3 * far, -distance});
    mesh.addPolygon({0, 1, 2});
    const Rendered r = renderScene(oneMeshScene(mesh.view()), camera, width, height);
    std::size_t wrong = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const double vx = (2.0 * (x + 0.5) / width - 1.0) * width / height * distance;
        const double vy = (2.0 * (y + 0.5) / height - 1.0) * distance;
        const double below = (0.3 * vx - vy) * height / (2.0 * distance);  // pixels
        if (std::abs(below) < 0.5) continue;
        wrong += (r.framebuffer.polygonIdAt(x, y) == 0) != (below > 0.0);
      }
    }
    if (exponent <= 14) {
      EXPECT_EQ(wrong, 0u) << "corners at 1e" << exponent;
    } else {
      EXPECT_GT(r.stats.pixelsCovered, 0u) << "corners at 1e" << exponent;
    }
    for (float depth : r.framebuffer.depth())
      ASSERT_TRUE(depth >= 0.0f && depth <= 1.0f) << depth;
    if (exponent >= 4) {
      EXPECT_EQ(r.stats.trianglesClipped, 1u) << "corners at 1e" << exponent;
    }
  }
}

// The fuzzer's "extreme zoom" (fuzz/crashes/README.md, now fixed): a view angle of 1e-100°
// or a parallel scale of 1e-100 (both valid) puts clip coordinates near 1e100, where a new
// vertex interpolated toward the guard band used to land ulp(1e100) off its plane and reach
// roundToInteger outside int32 (undefined; the sanitized build checks). Random triangles hit
// it within a few dozen tries: render a few hundred, in both projections.
TEST(ClippingRenders, ExtremeZoomGivesAValidImage) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (const bool parallel : {false, true}) {
    Camera camera;
    camera.position = {0, 0, 4};
    camera.viewAngleDegrees = 1e-100;
    camera.parallelProjection = parallel;
    camera.parallelScale = 1e-100;
    camera.nearClip = 1;
    camera.farClip = 10;
    std::size_t covered = 0;
    for (int trial = 0; trial < 300; ++trial) {
      Mesh mesh;
      for (int k = 0; k < 3; ++k)
        mesh.addPoint({coordinate(random), coordinate(random), coordinate(random)});
      mesh.addPolygon({0, 1, 2});
      const Rendered r = renderScene(oneMeshScene(mesh.view()), camera, 8, 8);
      covered += r.stats.pixelsCovered;
      for (float depth : r.framebuffer.depth())
        ASSERT_TRUE(depth >= 0.0f && depth <= 1.0f) << depth << (parallel ? " parallel" : "");
    }
    // A triangle around the view axis fills the whole (tiny) view: some must.
    EXPECT_GT(covered, 0u) << (parallel ? "parallel" : "perspective");
  }
}

}  // namespace
}  // namespace facet::testing
