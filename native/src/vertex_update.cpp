// Vertex update along the normal with inner fairness (sections 7.2, 7.3).
#include "vertex_update.h"

#include "inner_fairness.h"
#include "mean_curvature.h"

#include <algorithm>
#include <cmath>

namespace geofair {

double update_free_vertices(const FairingRegion& region, const InnerFairnessWeights& lambda,
                            const Eigen::VectorXd& H_target, NormalWeighting weighting,
                            double damping, Positions& X, Positions& N,
                            const std::vector<int>* subset,
                            const std::vector<double>* coupling, bool tangential) {
  const OneRings& rings = region.rings;
  double largest = 0.0;
  const int count = subset ? int(subset->size()) : region.n_free;
  for (int s = 0; s < count; ++s) {
    const int i = subset ? (*subset)[s] : s;
    const Vec3 n = vertex_normal(rings, X, i, weighting);
    if (n.squaredNorm() == 0.0) continue;  // degenerate ring: leave the vertex this pass
    N.row(i) = n;
    const Vec3 q = X.row(i);
    const Vec3 c = weighted_centroid(lambda, X, i);
    const Vec3 q_tilde = tangential ? Vec3(c - (c - q).dot(n) * n) : q;
    const CurvatureEstimate est =
        moreton_sequin(rings, X, N, i, q_tilde, n, needs_spiral_samples(rings, i));
    double t = 0.0;
    if (std::abs(est.dH_dt) > 0.0) t = (H_target(i) - est.H) / est.dH_dt;
    const double limit = 0.5 * rings.mean_neighbour_distance(X, i, q_tilde);
    t = std::clamp(t, -limit, limit);
    if (coupling) t /= std::max(1.0, (*coupling)[i]);
    const Vec3 q_new = q_tilde + damping * t * n;
    if (!q_new.allFinite()) continue;
    largest = std::max(largest, (q_new - q).norm());
    X.row(i) = q_new;
  }
  return largest;
}

void coupling_factors(const FairingRegion& region, const std::vector<double>& weights,
                      NormalWeighting weighting, const Eigen::VectorXd& H, Positions& X,
                      Positions& N, std::vector<double>& rho) {
  const OneRings& rings = region.rings;
  const int nf = region.n_free;
  const bool g0 = region.boundary == BoundaryCondition::G0;
  rho.assign(nf, 1.0);
  std::vector<Vec3> saved;
  auto estimate = [&](int j) {
    return moreton_sequin(rings, X, N, j, X.row(j), N.row(j), needs_spiral_samples(rings, j)).H;
  };
  for (int i = 0; i < nf; ++i) {
    const int begin = rings.offset[i], end = rings.offset[i + 1];
    const Vec3 q = X.row(i), n = N.row(i);
    const double dH_dt =
        moreton_sequin(rings, X, N, i, q, n, needs_spiral_samples(rings, i)).dH_dt;
    double sum_w = 0.0;
    for (int k = begin; k < end; ++k) sum_w += weights[k];
    if (!(dH_dt > 0.0) || !(sum_w > 0.0)) continue;
    // A step small against the ring (H is smooth in t there) and large against round-off.
    const double h = 1e-4 * rings.mean_neighbour_distance(X, i, q);
    saved.assign({N.row(i).transpose()});
    for (int k = begin; k < end; ++k) saved.push_back(N.row(rings.ring[k]));
    X.row(i) = q + h * n;
    N.row(i) = vertex_normal(rings, X, i, weighting);
    for (int k = begin; k < end; ++k)
      if (rings.ring[k] < nf)
        N.row(rings.ring[k]) = vertex_normal(rings, X, rings.ring[k], weighting);
    double defect = estimate(i) - H(i);
    for (int k = begin; k < end; ++k)
      if (rings.ring[k] < nf || !g0)  // G0: the boundary's H = 0 does not react
        defect -= weights[k] / sum_w * (estimate(rings.ring[k]) - H(rings.ring[k]));
    X.row(i) = q;
    N.row(i) = saved[0];
    for (int k = begin; k < end; ++k) N.row(rings.ring[k]) = saved[1 + k - begin];
    const double r = defect / (h * dH_dt);
    if (std::isfinite(r)) rho[i] = r;
  }
}

}  // namespace geofair
