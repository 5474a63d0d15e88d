// working_scale (mesh_scale.h).
#include "mesh_scale.h"

#include "geofair/errors.h"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

namespace geofair {

namespace {

// x · 2^exponent in scientific notation ("7.1e-162"), also where the value itself is not a
// double (beyond DBL_MAX or below the subnormals).
std::string scientific(double x, int exponent) {
  const double digits = std::log10(x) + exponent * std::log10(2.0);
  double decade = std::floor(digits);
  double mantissa = std::pow(10.0, digits - decade);
  if (mantissa >= 9.95) mantissa /= 10.0, decade += 1.0;
  char text[48];
  std::snprintf(text, sizeof text, "%.1fe%+d", mantissa, int(decade));
  return text;
}

}  // namespace

double working_scale(const Positions& V, const Triangles& F, const char* caller) {
  const Eigen::Index n = V.rows();
  if (F.rows() == 0) return 1.0;
  // The largest coordinate, to measure in units of its power of two (no overflow).
  double largest = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int v = F(f, c);
      if (v < 0 || v >= n || !V.row(v).allFinite()) return 1.0;
      largest = std::max(largest, V.row(v).cwiseAbs().maxCoeff());
    }
  if (!(largest > 0.0)) return 1.0;
  const int unit = std::ilogb(largest);  // lengths below in units of 2^unit
  const double to_unit = std::ldexp(1.0, -unit);
  Vec3 low = Vec3::Constant(DBL_MAX), high = Vec3::Constant(-DBL_MAX);
  double sum = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const Vec3 a = V.row(F(f, c)).transpose() * to_unit;
      const Vec3 b = V.row(F(f, (c + 1) % 3)).transpose() * to_unit;
      sum += (b - a).norm();
      low = low.cwiseMin(a), high = high.cwiseMax(a);
    }
  const double mean = sum / double(3 * F.rows());
  if (!(mean > 0.0)) return 1.0;
  const double diagonal = (high - low).norm();
  // log2 of the mean edge length and of the diagonal in the caller's units.
  const double log_mean = std::log2(mean) + unit, log_diagonal = std::log2(diagonal) + unit;
  const std::string who = std::string(caller) + ": ";
  if (2.0 * log_diagonal >= std::log2(DBL_MAX))
    throw InvalidInputError(who + "a mesh of size " + scientific(diagonal, unit) +
                            " is too large: squared lengths overflow (the bounding-box "
                            "diagonal must stay below " +
                            scientific(std::sqrt(DBL_MAX), 0) + "; scale the mesh down)");
  if (2.0 * log_mean < std::log2(DBL_MIN))
    throw InvalidInputError(who + "edge lengths of " + scientific(mean, unit) +
                            " are too small: squared lengths underflow (the mean edge length "
                            "must be at least " +
                            scientific(std::sqrt(DBL_MIN), 0) + "; scale the mesh up)");
  if (std::abs(log_mean) <= kScaleBand) return 1.0;
  return std::ldexp(1.0, int(std::lround(log_mean)));
}

}  // namespace geofair
