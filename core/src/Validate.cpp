#include "Validate.h"

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

}  // namespace facet::detail
