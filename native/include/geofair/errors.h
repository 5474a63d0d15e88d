// The exceptions of the geofair library.
#pragma once

#include <stdexcept>

namespace geofair {

/// A violated precondition of a public function (bad shapes, indices, NaN, topology).
/// Messages start with the function name. Mapped to Python's ValueError.
class InvalidInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A numerical failure (a solver broke down, the iteration diverged).
/// Mapped to Python's RuntimeError.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace geofair
