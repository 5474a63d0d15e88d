// Range checks of the solver tuning (tuning.h).
#include "geofair/tuning.h"

#include "geofair/errors.h"

#include <cmath>
#include <sstream>

namespace geofair {

void validate_tuning(const SolverTuning& tuning) {
  for_each_tuning_field(tuning, [](const char* name, double value, double lo, double hi,
                                   bool lo_open, bool hi_open, const char* bound) {
    const bool ok = std::isfinite(value) && (lo_open ? value > lo : value >= lo) &&
                    (hi_open ? value < hi : value <= hi);
    if (ok) return;
    std::ostringstream s;
    s << "fair: tuning." << name << " must be in " << (lo_open ? "(" : "[") << lo << ", ";
    if (hi >= kUnbounded) s << "inf)";
    else s << hi << (hi_open ? ")" : "]");
    if (bound) s << " (bounded by " << bound << ")";
    s << ", got " << value;
    throw InvalidInputError(s.str());
  });
}

}  // namespace geofair
