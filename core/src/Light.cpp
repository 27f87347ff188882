#include "facet/Light.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/trigonometric.hpp>

#include "Overloaded.h"
#include "Validate.h"

namespace facet {
namespace {

double quadraticFactor(const QuadraticAttenuation& q, double distance) {
  // A zero coefficient contributes exactly 0, even at infinite distance (avoids 0·inf = NaN).
  const double linearTerm = q.linear == 0.0 ? 0.0 : q.linear * distance;
  const double quadraticTerm = q.quadratic == 0.0 ? 0.0 : q.quadratic * distance * distance;
  const double denominator = q.constant + linearTerm + quadraticTerm;
  if (std::isnan(denominator)) return 0.0;
  return 1.0 / std::max(denominator, 1.0 / kMaxAttenuation);
}

double falloffDistanceFactor(const FalloffDistanceAttenuation& f, double distance) {
  if (distance <= f.distance) return 1.0;
  const double factor = f.distance / distance;
  return factor > 0.0 ? factor : 0.0;  // negative or NaN F (invalid input) gives 0
}

// cos of an angle in degrees, exact at the angles where a cone's edge case is decided.
double cosDegrees(double degrees) {
  if (degrees == 90.0) return 0.0;
  if (degrees == 180.0) return -1.0;
  return std::cos(glm::radians(degrees));
}

double linearConeFactor(const LinearSpotCone& cone, double cosAngle) {
  const double angle = glm::degrees(std::acos(cosAngle));
  if (angle <= cone.fullIntensityAngleDegrees) return 1.0;
  const double zeroAngle = cone.fullIntensityAngleDegrees + cone.falloffAngleDegrees;
  if (!(cone.falloffAngleDegrees > 0.0) || angle >= zeroAngle) return 0.0;
  return (zeroAngle - angle) / cone.falloffAngleDegrees;
}

double exponentConeFactor(const ExponentSpotCone& cone, double cosAngle) {
  // VTK's shaders treat a cone angle above 90 degrees as "not a spotlight".
  if (cone.coneAngleDegrees > 90.0) return 1.0;
  if (cosAngle < cosDegrees(cone.coneAngleDegrees)) return 0.0;
  const double factor = std::pow(std::max(cosAngle, 0.0), cone.exponent);
  return factor > 0.0 ? std::min(factor, 1.0) : 0.0;
}

template <class Name>
void validateAttenuation(const Attenuation& attenuation, const Name& name) {
  std::visit(detail::Overloaded{
                 [](const NoAttenuation&) {},
                 [&](const QuadraticAttenuation& q) {
                   detail::requireNonNegative(q.constant, [&] { return name() + ".constant"; });
                   detail::requireNonNegative(q.linear, [&] { return name() + ".linear"; });
                   detail::requireNonNegative(q.quadratic, [&] { return name() + ".quadratic"; });
                 },
                 [&](const FalloffDistanceAttenuation& f) {
                   detail::requireNonNegative(f.distance, [&] { return name() + ".distance"; });
                 },
             },
             attenuation);
}

template <class Name>
void validateCone(const SpotCone& cone, const Name& name) {
  std::visit(detail::Overloaded{
                 [&](const LinearSpotCone& c) {
                   detail::requireInRange(c.fullIntensityAngleDegrees, 0.0, 180.0,
                                          [&] { return name() + ".fullIntensityAngleDegrees"; });
                   detail::requireNonNegative(c.falloffAngleDegrees,
                                              [&] { return name() + ".falloffAngleDegrees"; });
                 },
                 [&](const ExponentSpotCone& c) {
                   detail::requireInRange(c.coneAngleDegrees, 0.0, 180.0,
                                          [&] { return name() + ".coneAngleDegrees"; });
                   detail::requireNonNegative(c.exponent, [&] { return name() + ".exponent"; });
                 },
             },
             cone);
}

template <class Name>
void validateLight(const Light& light, const Name& name) {
  std::visit(
      detail::Overloaded{
          [&](const DirectionalLight& l) {
            detail::requireNonZeroDirection(l.direction, [&] { return name() + ".direction"; });
            detail::requireColor(l.color, [&] { return name() + ".color"; });
            detail::requireFinite(l.intensity, [&] { return name() + ".intensity"; });
          },
          [&](const PointLight& l) {
            detail::requireFinite(l.position, [&] { return name() + ".position"; });
            detail::requireColor(l.color, [&] { return name() + ".color"; });
            detail::requireFinite(l.intensity, [&] { return name() + ".intensity"; });
            validateAttenuation(l.attenuation, [&] { return name() + ".attenuation"; });
          },
          [&](const SpotLight& l) {
            detail::requireFinite(l.position, [&] { return name() + ".position"; });
            detail::requireNonZeroDirection(l.direction, [&] { return name() + ".direction"; });
            detail::requireColor(l.color, [&] { return name() + ".color"; });
            detail::requireFinite(l.intensity, [&] { return name() + ".intensity"; });
            validateAttenuation(l.attenuation, [&] { return name() + ".attenuation"; });
            validateCone(l.cone, [&] { return name() + ".cone"; });
          },
      },
      light);
}

}  // namespace

double attenuationFactor(const Attenuation& attenuation, double distance) {
  return std::visit(detail::Overloaded{
                        [&](const NoAttenuation&) { return distance >= 0.0 ? 1.0 : 0.0; },
                        [&](const auto& a) { return attenuationFactor(a, distance); },
                    },
                    attenuation);
}

double attenuationFactor(const QuadraticAttenuation& attenuation, double distance) {
  return distance >= 0.0 ? quadraticFactor(attenuation, distance) : 0.0;
}

double attenuationFactor(const FalloffDistanceAttenuation& attenuation, double distance) {
  return distance >= 0.0 ? falloffDistanceFactor(attenuation, distance) : 0.0;
}

double spotFactor(const SpotCone& cone, double cosAngleFromAxis) {
  return std::visit([&](const auto& c) { return spotFactor(c, cosAngleFromAxis); }, cone);
}

double spotFactor(const LinearSpotCone& cone, double cosAngleFromAxis) {
  if (std::isnan(cosAngleFromAxis)) return 0.0;
  return linearConeFactor(cone, std::clamp(cosAngleFromAxis, -1.0, 1.0));
}

double spotFactor(const ExponentSpotCone& cone, double cosAngleFromAxis) {
  if (std::isnan(cosAngleFromAxis)) return 0.0;
  return exponentConeFactor(cone, std::clamp(cosAngleFromAxis, -1.0, 1.0));
}

void validate(const LightSet& lightSet) {
  detail::requireColor(lightSet.ambient.color, "LightSet.ambient.color");
  detail::requireFinite(lightSet.ambient.intensity, "LightSet.ambient.intensity");
  for (std::size_t i = 0; i < lightSet.lights.size(); ++i) {
    validateLight(lightSet.lights[i], [i] { return "LightSet.lights[" + std::to_string(i) + "]"; });
  }
}

}  // namespace facet
