#include "Validate.h"

#include <cmath>
#include <cstdio>

#include "facet/Error.h"

namespace facet::detail {

std::string formatValue(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string formatVector(const glm::dvec3& value) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.17g, %.17g, %.17g)", value.x, value.y, value.z);
  return buffer;
}

void fail(std::string_view name, std::string_view problem) {
  throw Error(std::string(name) + " " + std::string(problem));
}

void requireFinite(double value, std::string_view name) {
  if (!std::isfinite(value)) fail(name, "is " + formatValue(value) + ", must be finite");
}

void requireNonNegative(double value, std::string_view name) {
  requireFinite(value, name);
  if (value < 0.0) fail(name, "is " + formatValue(value) + ", must be >= 0");
}

void requireInRange(double value, double low, double high, std::string_view name) {
  requireFinite(value, name);
  if (value < low || value > high) {
    fail(name, "is " + formatValue(value) + ", must be in [" + formatValue(low) + ", " +
                   formatValue(high) + "]");
  }
}

void requireFinite(const glm::dvec3& value, std::string_view name) {
  if (!std::isfinite(value.x) || !std::isfinite(value.y) || !std::isfinite(value.z)) {
    fail(name, "is " + formatVector(value) + ", must be finite");
  }
}

void requireNonZeroDirection(const glm::dvec3& value, std::string_view name) {
  requireFinite(value, name);
  if (value.x == 0.0 && value.y == 0.0 && value.z == 0.0) {
    fail(name, "is the zero vector, must be a direction");
  }
}

void requireColor(const Color& value, std::string_view name) {
  const glm::dvec3 channels(value);
  requireFinite(channels, name);
  if (value.r < 0.0f || value.g < 0.0f || value.b < 0.0f) {
    fail(name, "is " + formatVector(channels) + ", channels must be >= 0");
  }
}

}  // namespace facet::detail
