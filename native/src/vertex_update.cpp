// Vertex update along the normal with inner fairness (sections 7.2, 7.3).
#include "geofair/vertex_update.h"

#include "geofair/inner_fairness.h"
#include "geofair/mean_curvature.h"

#include <algorithm>
#include <cmath>

namespace geofair {

double update_free_vertices(const FairingRegion& region, const std::vector<double>& lambda,
                            const Eigen::VectorXd& H_target, NormalWeighting weighting,
                            double damping, Positions& X, Positions& N,
                            const std::vector<int>* subset) {
  const OneRings& rings = region.rings;
  double largest = 0.0;
  const int count = subset ? int(subset->size()) : region.n_free;
  for (int s = 0; s < count; ++s) {
    const int i = subset ? (*subset)[s] : s;
    const Vec3 n = vertex_normal(rings, X, i, weighting);
    if (n.squaredNorm() == 0.0) continue;  // degenerate ring: leave the vertex this pass
    N.row(i) = n;
    const Vec3 q = X.row(i);
    const Vec3 c = weighted_centroid(rings, lambda, X, i);
    const Vec3 q_tilde = c - (c - q).dot(n) * n;
    const CurvatureEstimate est =
        moreton_sequin(rings, X, N, i, q_tilde, n, needs_spiral_samples(rings, i));
    double t = 0.0;
    if (std::abs(est.dH_dt) > 0.0) t = (H_target(i) - est.H) / est.dH_dt;
    double mean_distance = 0.0;
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
      mean_distance += (X.row(rings.ring[k]).transpose() - q_tilde).norm();
    mean_distance /= rings.valence(i);
    const double limit = 0.5 * mean_distance;
    t = std::clamp(t, -limit, limit);
    const Vec3 q_new = q_tilde + damping * t * n;
    if (!q_new.allFinite()) continue;
    largest = std::max(largest, (q_new - q).norm());
    X.row(i) = q_new;
  }
  return largest;
}

}  // namespace geofair
