#pragma once

// Precondition checks for the core's API boundary. Each throws facet::Error with a message
// that names the value and prints it (Filament's habit: print every argument).

#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "facet/Color.h"

namespace facet::detail {

std::string formatValue(double value);
std::string formatVector(const glm::dvec3& value);

[[noreturn]] void fail(std::string_view name, std::string_view problem);

void requireFinite(double value, std::string_view name);
void requireNonNegative(double value, std::string_view name);
void requireInRange(double value, double low, double high, std::string_view name);
void requireFinite(const glm::dvec3& value, std::string_view name);
void requireNonZeroDirection(const glm::dvec3& value, std::string_view name);
void requireColor(const Color& value, std::string_view name);

}  // namespace facet::detail
