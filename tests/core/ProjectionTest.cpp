// Points land on the pixels vtkCamera's formulas put them, computed here independently
// (camera basis by hand, frustum and ortho in closed form), for random cameras.

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../support/TestRender.h"
#include "facet/Camera.h"

namespace facet::testing {
namespace {

struct Expected {
  glm::dvec2 window;  // pixels
  double depth;       // window depth in [0, 1]
};

struct Basis {
  glm::dvec3 right, up, forward;
};

Basis basisOf(const Camera& c) {
  const glm::dvec3 forward = glm::normalize(c.focalPoint - c.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, c.viewUp));
  return {right, glm::cross(right, forward), forward};
}

// vtkCamera: frustum/ortho from the view angle or parallel scale, the window center, the
// clipping range; OpenGL's NDC; window = (ndc + 1)/2 · size.
Expected project(const Camera& c, const glm::dvec3& world, int width, int height) {
  const Basis b = basisOf(c);
  const glm::dvec3 v = world - c.position;
  const double x = glm::dot(v, b.right), y = glm::dot(v, b.up), distance = glm::dot(v, b.forward);
  const double aspect = double(width) / height, n = c.nearClip, f = c.farClip;
  glm::dvec3 ndc;
  if (c.parallelProjection) {
    ndc.x = x / (c.parallelScale * aspect) - c.windowCenter.x;
    ndc.y = y / c.parallelScale - c.windowCenter.y;
    ndc.z = (2.0 * distance - (f + n)) / (f - n);
  } else {
    const double t = std::tan(c.viewAngleDegrees * M_PI / 360.0);
    ndc.x = x / (distance * t * aspect) - c.windowCenter.x;
    ndc.y = y / (distance * t) - c.windowCenter.y;
    ndc.z = (f + n) / (f - n) - 2.0 * f * n / ((f - n) * distance);
  }
  return {{(ndc.x + 1.0) * 0.5 * width, (ndc.y + 1.0) * 0.5 * height}, (ndc.z + 1.0) * 0.5};
}

// The world point at `distance` along the view that projects to window point `w`.
glm::dvec3 unproject(const Camera& c, glm::dvec2 w, double distance, int width, int height) {
  const Basis b = basisOf(c);
  const double aspect = double(width) / height;
  const double nx = 2.0 * w.x / width - 1.0 + c.windowCenter.x;
  const double ny = 2.0 * w.y / height - 1.0 + c.windowCenter.y;
  double x, y;
  if (c.parallelProjection) {
    x = nx * c.parallelScale * aspect;
    y = ny * c.parallelScale;
  } else {
    const double t = std::tan(c.viewAngleDegrees * M_PI / 360.0);
    x = nx * distance * t * aspect;
    y = ny * distance * t;
  }
  return c.position + x * b.right + y * b.up + distance * b.forward;
}

Camera randomCamera(std::mt19937& random, bool parallel) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Camera c;
  c.position = {50 * u(random), 50 * u(random), 50 * u(random)};
  c.focalPoint =
      c.position + glm::dvec3(u(random), u(random), u(random)) * 10.0 + glm::dvec3(0.0, 0.0, 0.1);
  c.viewUp = {u(random), u(random), u(random)};
  c.viewAngleDegrees = 20.0 + 60.0 * std::abs(u(random));
  c.parallelProjection = parallel;
  c.parallelScale = 2.0 + 10.0 * std::abs(u(random));
  c.windowCenter = {0.3 * u(random), 0.3 * u(random)};
  c.nearClip = 0.5 + std::abs(u(random));
  c.farClip = c.nearClip + 40.0 + 100.0 * std::abs(u(random));
  return c;
}

TEST(Projection, MatricesAgreeWithTheClosedForms) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Camera c = randomCamera(random, i % 2 == 1);
    const int width = 320, height = 200;
    const glm::dvec3 p = unproject(c, {320 * std::abs(u(random)), 200 * std::abs(u(random))},
                                   c.nearClip + 30.0 * std::abs(u(random)), width, height);
    const glm::dvec4 clip =
        clipFromView(c, double(width) / height) * viewFromWorld(c) * glm::dvec4(p, 1.0);
    const Expected e = project(c, p, width, height);
    EXPECT_NEAR((clip.x / clip.w + 1.0) * 0.5 * width, e.window.x, 1e-7);
    EXPECT_NEAR((clip.y / clip.w + 1.0) * 0.5 * height, e.window.y, 1e-7);
    EXPECT_NEAR((clip.z / clip.w + 1.0) * 0.5, e.depth, 1e-9);
  }
}

// A tiny triangle facing the camera, centered on the world point that projects to a pixel
// center, must cover exactly that pixel, at the expected depth.
TEST(Projection, RandomCamerasPutPointsOnThePredictedPixel) {
  std::mt19937 random(12);
  std::uniform_int_distribution<int> px(0, 319), py(0, 199);
  std::uniform_real_distribution<double> fraction(0.05, 0.95);
  const int width = 320, height = 200;
  for (int i = 0; i < 60; ++i) {
    const Camera c = randomCamera(random, i % 2 == 1);
    const int x = px(random), y = py(random);
    const double distance = c.nearClip + fraction(random) * (c.farClip - c.nearClip);
    const glm::dvec2 center(x + 0.5, y + 0.5);
    Mesh triangle;  // corners 0.3 px from the center, in the plane at `distance`
    for (double angle : {0.0, 2.1, 4.2}) {
      triangle.addPoint(unproject(c, center + 0.3 * glm::dvec2(std::cos(angle), std::sin(angle)),
                                  distance, width, height));
    }
    triangle.addPolygon({0, 1, 2});
    const Rendered r = renderScene(oneMeshScene(triangle.view()), c, width, height);
    SCOPED_TRACE("camera " + std::to_string(i) +
                 (c.parallelProjection ? " parallel" : " perspective"));
    ASSERT_EQ(r.stats.pixelsCovered, 1u);
    EXPECT_EQ(r.framebuffer.polygonIdAt(x, y), 0) << "expected pixel (" << x << ", " << y << ")";
    const Expected e = project(c, triangle.points[0], width, height);
    EXPECT_NEAR(r.framebuffer.depthAt(x, y), e.depth, 2e-6);
  }
}

TEST(Projection, ImageRowZeroIsTheBottom) {
  Mesh low;  // a triangle in the lower-left corner of the pixel camera's view
  low.addPoint({1.0, 1.0, 0.0});
  low.addPoint({6.0, 1.0, 0.0});
  low.addPoint({1.0, 6.0, 0.0});
  low.addPolygon({0, 1, 2});
  Camera camera;
  camera.parallelProjection = true;
  camera.parallelScale = 10.0;  // 20 × 20 world units on a 20 × 20 image
  camera.position = {10.0, 10.0, 5.0};
  camera.focalPoint = {10.0, 10.0, 0.0};
  const Rendered r = renderScene(oneMeshScene(low.view()), camera, 20, 20);
  EXPECT_EQ(r.framebuffer.polygonIdAt(2, 2), 0);
  EXPECT_EQ(r.framebuffer.polygonIdAt(2, 17), Framebuffer::kBackgroundId);
}

}  // namespace
}  // namespace facet::testing
