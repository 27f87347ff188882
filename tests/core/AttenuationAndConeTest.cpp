// Distance attenuation and spot cones: the seeds' numbers and the chosen edge behaviour.

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "facet/Light.h"

namespace facet {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double cosDegrees(double degrees) {
  return std::cos(degrees * M_PI / 180.0);
}

TEST(QuadraticAttenuation, SixthDefaultGivesTheFormulasValues) {
  // 1/(1 + 0.0001·d²): the formula's values, not the guide's misprinted 0.99/0.52/0.29.
  const QuadraticAttenuation sixth;
  EXPECT_DOUBLE_EQ(attenuationFactor(sixth, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(sixth, 100.0), 0.5);
  EXPECT_DOUBLE_EQ(attenuationFactor(sixth, 300.0), 0.1);
  EXPECT_DOUBLE_EQ(attenuationFactor(sixth, 500.0), 1.0 / 26.0);
}

TEST(QuadraticAttenuation, GuidePrintedValuesNeedOtherConstants) {
  // The discrepancy noted in Light.h: the printed 0.52 and 0.29 at d = 300, 500 come from
  // k = 1e-5 (0.526 and 0.286, printed truncated), 0.99 at d = 100 from k = 1e-6.
  const QuadraticAttenuation k5{1.0, 0.0, 1e-5};
  EXPECT_NEAR(attenuationFactor(k5, 300.0), 0.52, 0.01);
  EXPECT_NEAR(attenuationFactor(k5, 500.0), 0.29, 0.01);
  EXPECT_NEAR(attenuationFactor(QuadraticAttenuation{1.0, 0.0, 1e-6}, 100.0), 0.99, 0.01);
}

TEST(QuadraticAttenuation, VtkConstantLinearQuadratic) {
  const QuadraticAttenuation vtk{2.0, 0.5, 0.25};
  EXPECT_DOUBLE_EQ(attenuationFactor(vtk, 4.0), 1.0 / (2.0 + 2.0 + 4.0));
  EXPECT_DOUBLE_EQ(attenuationFactor(QuadraticAttenuation{1.0, 0.0, 0.0}, 1e9), 1.0);
}

TEST(QuadraticAttenuation, EdgesStayFinite) {
  const QuadraticAttenuation noConstant{0.0, 1.0, 1.0};
  EXPECT_DOUBLE_EQ(attenuationFactor(noConstant, 0.0), kMaxAttenuation) << "light on surface";
  EXPECT_DOUBLE_EQ(attenuationFactor(QuadraticAttenuation{}, 1e200), 0.0) << "d² overflows";
  EXPECT_DOUBLE_EQ(attenuationFactor(QuadraticAttenuation{}, kInf), 0.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(QuadraticAttenuation{1.0, 0.0, 0.0}, kInf), 1.0)
      << "0·inf must not make NaN";
  EXPECT_DOUBLE_EQ(attenuationFactor(QuadraticAttenuation{}, kNaN), 0.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(QuadraticAttenuation{}, -1.0), 0.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(QuadraticAttenuation{0.0, 0.0, 0.0}, 5.0), kMaxAttenuation);
}

TEST(FalloffDistance, FullWithinThenInverseDistance) {
  const FalloffDistanceAttenuation f{50.0};
  EXPECT_DOUBLE_EQ(attenuationFactor(f, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(f, 50.0), 1.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(f, 100.0), 0.5) << "half at 2F";
  EXPECT_DOUBLE_EQ(attenuationFactor(f, 150.0), 1.0 / 3.0) << "a third at 3F";
  EXPECT_DOUBLE_EQ(attenuationFactor(f, kInf), 0.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(FalloffDistanceAttenuation{0.0}, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(FalloffDistanceAttenuation{0.0}, 1.0), 0.0);
}

TEST(NoAttenuation, AlwaysOne) {
  EXPECT_DOUBLE_EQ(attenuationFactor(NoAttenuation{}, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(attenuationFactor(NoAttenuation{}, 1e300), 1.0);
}

TEST(LinearSpotCone, ALightTouchNumbers) {
  const LinearSpotCone cone{20.0, 15.0};
  EXPECT_DOUBLE_EQ(spotFactor(cone, cosDegrees(0.0)), 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(cone, cosDegrees(10.0)), 1.0) << "full inside 20°";
  EXPECT_NEAR(spotFactor(cone, cosDegrees(27.5)), 0.5, 1e-12) << "half way through falloff";
  EXPECT_DOUBLE_EQ(spotFactor(cone, cosDegrees(36.0)), 0.0) << "zero past 35°";
  EXPECT_DOUBLE_EQ(spotFactor(cone, cosDegrees(170.0)), 0.0);
}

TEST(LinearSpotCone, ZeroFalloffIsAHardEdge) {
  const LinearSpotCone cone{20.0, 0.0};
  EXPECT_DOUBLE_EQ(spotFactor(cone, cosDegrees(19.9)), 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(cone, cosDegrees(20.1)), 0.0);
}

TEST(LinearSpotCone, ExtremeAngles) {
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{0.0, 0.0}, 1.0), 1.0) << "0° cone: axis only";
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{0.0, 0.0}, cosDegrees(0.01)), 0.0);
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{90.0, 0.0}, cosDegrees(89.0)), 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{90.0, 0.0}, cosDegrees(91.0)), 0.0);
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{180.0, 0.0}, -1.0), 1.0) << "180°: everywhere";
}

TEST(SpotCone, CosineRoundedPastOneIsClampedNotNaN) {
  const double justAboveOne = std::nextafter(1.0, 2.0);
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{}, justAboveOne), 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{}, 1.5), 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{30.0, 5.0}, justAboveOne), 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{}, -1.5), 0.0);
  EXPECT_DOUBLE_EQ(spotFactor(LinearSpotCone{}, kNaN), 0.0);
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{}, kNaN), 0.0);
}

TEST(ExponentSpotCone, VtkModel) {
  const ExponentSpotCone cone{30.0, 2.0};
  EXPECT_DOUBLE_EQ(spotFactor(cone, cosDegrees(20.0)), std::pow(cosDegrees(20.0), 2.0));
  EXPECT_DOUBLE_EQ(spotFactor(cone, cosDegrees(31.0)), 0.0);
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{30.0, 0.0}, cosDegrees(29.0)), 1.0);
}

TEST(ExponentSpotCone, AnglesAboveNinetyMeanNoCone) {
  // vtkLight: "a value of 90 (or more) indicates ... just a positional light"; VTK's shaders
  // apply the cone up to and including 90°.
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{180.0, 3.0}, cosDegrees(170.0)), 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{90.0, 1.0}, 0.0), 0.0) << "edge: cos^1 = 0";
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{90.0, 0.0}, 0.0), 1.0) << "edge: cos^0 = 1";
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{90.0, 1.0}, -0.01), 0.0);
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{0.0, 1.0}, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{0.0, 1.0}, cosDegrees(0.01)), 0.0);
}

TEST(ExponentSpotCone, HugeExponentStaysInRange) {
  const double f = spotFactor(ExponentSpotCone{90.0, 1e6}, cosDegrees(1.0));
  EXPECT_GE(f, 0.0);
  EXPECT_LE(f, 1.0);
  EXPECT_DOUBLE_EQ(spotFactor(ExponentSpotCone{90.0, 1e6}, 1.0), 1.0);
}

}  // namespace
}  // namespace facet
