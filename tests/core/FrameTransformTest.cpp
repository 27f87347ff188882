// FrameTransform::toViewer (the specular term's direction to the eye) from points at any
// finite distance: the square of a distance beyond ~1e154 (or below ~1e-154) leaves double's
// range although the distance and the direction do not (between ~1e-162 and ~1e-154 the
// square is subnormal: a length from it is off by up to a percent, not 0).

#include <cmath>
#include <initializer_list>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "FrameTransform.h"
#include "facet/Camera.h"

namespace facet::testing {
namespace {

TEST(FrameTransform, ToViewerPointsAtTheEyeFromAnyFiniteDistance) {
  Camera camera;  // the eye at the origin, looking down −z
  camera.position = {0.0, 0.0, 0.0};
  camera.focalPoint = {0.0, 0.0, -1.0};
  const detail::FrameTransform transform(camera, 64, 48);
  for (const glm::dvec3 away : {glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.6, -0.8, 0.0),
                                glm::normalize(glm::dvec3(1.0, 2.0, -3.0))}) {
    for (const double distance :
         {1e-300, 1e-200, 1e-161, 1e-158, 1e-155, 1.0, 1e100, 1e160, 1e200, 1e300}) {
      const glm::dvec3 toViewer = transform.toViewer(away * distance);
      EXPECT_NEAR(glm::length(toViewer + away), 0.0, 1e-12)
          << "distance " << distance << ", direction (" << away.x << ", " << away.y << ", "
          << away.z << ") gave (" << toViewer.x << ", " << toViewer.y << ", " << toViewer.z << ")";
    }
  }
  // The eye at the point: no direction; the view's back direction, as before.
  EXPECT_EQ(transform.toViewer(glm::dvec3(0.0)), glm::dvec3(0.0, 0.0, 1.0));
}

}  // namespace
}  // namespace facet::testing
