// The exceptions of the geofair library. A bottom header: it includes no other geofair
// header. Their destructors are defined in errors.cpp (the key function), so that their
// vtables and type_info live in that one object file, not weakly in every one that throws.
#pragma once

#include <stdexcept>

namespace geofair {

/// A violated precondition of a public function (bad shapes, indices, NaN, topology).
/// Messages start with the function name. Mapped to Python's ValueError.
class InvalidInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
  ~InvalidInputError() override;
};

/// A numerical failure (a solver broke down, the iteration diverged).
/// Mapped to Python's RuntimeError.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  ~SolverError() override;
};

}  // namespace geofair
