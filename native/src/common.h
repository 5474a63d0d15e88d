// Small helpers shared by the library's sources (not part of the public API).
#pragma once

#include "geofair/types.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace geofair {

/// An orthonormal basis (bx, by) of the plane with unit normal n, with bx × by = n: the
/// tangent-plane frame of eqs. (9), (10) and of the quadric normal fits.
inline void tangent_basis(const Vec3& n, Vec3& bx, Vec3& by) {
  const Vec3 helper = std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  bx = n.cross(helper).normalized();
  by = n.cross(bx);
}

/// x in a message: one decimal of scientific notation ("1.2e-05").
inline std::string scientific(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1e", x);
  return text;
}

/// Rows `ids` of X (#ids×3), e.g. a region's positions from the caller's by region.global.
inline Positions gather(const Positions& X, const std::vector<int>& ids) {
  Positions Y(Eigen::Index(ids.size()), 3);
  for (std::size_t i = 0; i < ids.size(); ++i) Y.row(Eigen::Index(i)) = X.row(ids[i]);
  return Y;
}

// The bounding-box diagonal of positions X (a region's: the residual's length L, fairing.h).
inline double diagonal(const Positions& X) {
  return (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
}

/// Wall-clock seconds between calls, for FairingResult::phase_seconds.
class Laps {
 public:
  /// Seconds since the last call (the first call: since construction).
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

/// The options of a solve that follows `spent` seconds of the same call: an explicit time
/// limit less what is spent (the automatic one applies to each solve).
inline FairingOptions options_after(const FairingOptions& options, double spent) {
  FairingOptions rest = options;
  if (options.time_limit >= 0.0) rest.time_limit = std::max(0.0, options.time_limit - spent);
  return rest;
}

/// Whether a call with `options` has time left after `spent` seconds: neither its explicit
/// time limit nor its deadline (FairingOptions::deadline) is reached.
inline bool has_time_left(const FairingOptions& options, double spent) {
  return (!(options.time_limit >= 0.0) || spent < options.time_limit) &&
         !(options.deadline && std::chrono::steady_clock::now() >= options.deadline->at);
}

}  // namespace geofair
