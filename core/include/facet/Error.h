#pragma once

/// @file Error.h
/// The one error type of the core API (see Conventions.h, "Errors").

#include <stdexcept>
#include <string>

namespace facet {

/// Thrown for bad input at the core's API boundary. The message names the offending value,
/// e.g. `PointLight.intensity is NaN`.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace facet
