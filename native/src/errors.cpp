// The key functions of the exceptions (geofair/errors.h).
#include "geofair/errors.h"

namespace geofair {

InvalidInputError::~InvalidInputError() = default;
SolverError::~SolverError() = default;

}  // namespace geofair
