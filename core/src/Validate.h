#pragma once

// Precondition checks for the core's API boundary. Each throws facet::Error with a message
// that names the value and prints it (Filament's habit: print every argument).
//
// A name is a string literal or a callable returning the name; callables are invoked only
// on failure, so checking valid input never allocates (re-rendering must not allocate).

#include <cmath>
#include <string>
#include <string_view>
#include <type_traits>

#include <glm/vec3.hpp>

#include "facet/Color.h"

namespace facet::detail {

std::string formatValue(double value);
std::string formatVector(const glm::dvec3& value);

[[noreturn]] void fail(std::string_view name, std::string_view problem);

template <class Name>
std::string nameOf(const Name& name) {
  if constexpr (std::is_invocable_v<const Name&>) {
    return std::string(name());
  } else {
    return std::string(name);
  }
}

template <class Name>
void requireFinite(double value, const Name& name) {
  if (!std::isfinite(value)) fail(nameOf(name), "is " + formatValue(value) + ", must be finite");
}

template <class Name>
void requireNonNegative(double value, const Name& name) {
  requireFinite(value, name);
  if (value < 0.0) fail(nameOf(name), "is " + formatValue(value) + ", must be >= 0");
}

template <class Name>
void requirePositive(double value, const Name& name) {
  requireFinite(value, name);
  if (!(value > 0.0)) fail(nameOf(name), "is " + formatValue(value) + ", must be > 0");
}

template <class Name>
void requireInRange(double value, double low, double high, const Name& name) {
  requireFinite(value, name);
  if (value < low || value > high) {
    fail(nameOf(name), "is " + formatValue(value) + ", must be in [" + formatValue(low) + ", " +
                           formatValue(high) + "]");
  }
}

template <class Name>
void requireFinite(const glm::dvec3& value, const Name& name) {
  if (!std::isfinite(value.x) || !std::isfinite(value.y) || !std::isfinite(value.z)) {
    fail(nameOf(name), "is " + formatVector(value) + ", must be finite");
  }
}

template <class Name>
void requireNonZeroDirection(const glm::dvec3& value, const Name& name) {
  requireFinite(value, name);
  if (value.x == 0.0 && value.y == 0.0 && value.z == 0.0) {
    fail(nameOf(name), "is the zero vector, must be a direction");
  }
}

template <class Name>
void requireColor(const Color& value, const Name& name) {
  const glm::dvec3 channels(value);
  requireFinite(channels, name);
  if (value.r < 0.0f || value.g < 0.0f || value.b < 0.0f) {
    fail(nameOf(name), "is " + formatVector(channels) + ", channels must be >= 0");
  }
}

}  // namespace facet::detail
