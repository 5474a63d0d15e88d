// The construction loop of sections 7.1-7.3 on one mesh.
#include "geofair/construction.h"

#include "geofair/mean_curvature.h"
#include "geofair/vertex_update.h"

#include <cmath>
#include <string>

namespace geofair {

Construction::Construction(const FairingRegion& region, std::vector<double> lambda,
                           const FairingOptions& options, double length)
    : region_(region),
      lambda_(std::move(lambda)),
      options_(options),
      length_(length),
      N_(region.n, 3),
      H_(region.n),
      dirichlet_(region),
      solver_(options.cg_iterations) {
  N_.bottomRows(region.n - region.n_free) = region.g1_normals;
}

void Construction::curvatures(const Positions& X, const std::vector<int>* subset) {
  const OneRings& rings = region_.rings;
  const NormalWeighting w = options_.normal_weighting;
  if (!subset) {
    for (int i = 0; i < region_.n_free; ++i) N_.row(i) = vertex_normal(rings, X, i, w);
    for (int i = 0; i < region_.n; ++i)
      H_(i) = moreton_sequin(rings, X, N_, i, X.row(i), N_.row(i), needs_spiral_samples(rings, i)).H;
    return;
  }
  for (int i : *subset) {
    N_.row(i) = vertex_normal(rings, X, i, w);
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
      if (rings.ring[k] < region_.n_free) N_.row(rings.ring[k]) = vertex_normal(rings, X, rings.ring[k], w);
  }
  auto estimate = [&](int j) {
    H_(j) = moreton_sequin(rings, X, N_, j, X.row(j), N_.row(j), needs_spiral_samples(rings, j)).H;
  };
  for (int i : *subset) {
    estimate(i);
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k) estimate(rings.ring[k]);
  }
}

double Construction::evaluate(const Positions& X) {
  curvatures(X, nullptr);
  dirichlet_.assemble(X);
  return length_ * length_ * length_ * dirichlet_.max_laplace_beltrami(H_);
}

IterationReport Construction::run(Positions& X, int max_iterations, int iteration_offset) {
  const int nf = region_.n_free;
  IterationReport report;
  double first_residual = 0.0;
  for (int k = 0;; ++k) {
    const double residual = evaluate(X);
    if (!std::isfinite(residual))
      throw SolverError("fair: the iteration diverged (non-finite mean curvature at iteration " +
                        std::to_string(iteration_offset + k) + ")");
    if (k == 0) first_residual = residual;
    if (residual > 1e6 * std::max(first_residual, 1.0))
      throw SolverError("fair: the iteration diverged (residual grew from " +
                        std::to_string(first_residual) + " to " + std::to_string(residual) +
                        " by iteration " + std::to_string(iteration_offset + k) + ")");
    report.iterations = k;
    report.residual = residual;
    report.converged = residual <= options_.tolerance;
    if (report.converged || k >= max_iterations) break;
    if (options_.progress && !options_.progress(iteration_offset + k, residual)) {
      report.cancelled = true;
      break;
    }
    const Eigen::VectorXd b = dirichlet_.rhs(H_);
    Eigen::VectorXd H_target = H_.head(nf);
    if (k % 2 == 0)
      gauss_seidel_sweep(dirichlet_.S(), b, H_target);
    else
      solver_.global_step(dirichlet_.S(), b, H_target);
    if (k % kCouplingRefresh == 0)
      coupling_factors(region_, dirichlet_.weights(), options_.normal_weighting, H_, X, N_,
                       coupling_);
    const double step = update_free_vertices(region_, lambda_, H_target, options_.normal_weighting,
                                             options_.damping, X, N_, nullptr, &coupling_);
    if (!(step <= length_))
      throw SolverError("fair: the iteration diverged (a vertex moved by more than the region's "
                        "size in iteration " + std::to_string(iteration_offset + k) + ")");
  }
  return report;
}

void Construction::local_steps(Positions& X, const std::vector<int>& subset, int steps) {
  const OneRings& rings = region_.rings;
  std::vector<double> w;
  Eigen::VectorXd H_target(region_.n_free);
  for (int step = 0; step < steps; ++step) {
    // The first pass needs every normal (spiral samples look one ring further).
    curvatures(X, step == 0 ? nullptr : &subset);
    if (step == 0) {
      dirichlet_.assemble(X);
      coupling_factors(region_, dirichlet_.weights(), options_.normal_weighting, H_, X, N_,
                       coupling_);
    }
    // One Gauss–Seidel sweep of Σ_j w_ij (H~_i − H_j) = 0 over the subset (section 7.1).
    for (int i : subset) H_target(i) = H_(i);
    for (int i : subset) {
      w.resize(rings.valence(i));
      cotangent_weights(rings, X, i, w.data());
      double sum_w = 0.0, sum = 0.0;
      for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k) {
        sum_w += w[k - rings.offset[i]];
        sum += w[k - rings.offset[i]] * H_(rings.ring[k]);
      }
      if (sum_w > 0.0) H_(i) = H_target(i) = sum / sum_w;
    }
    update_free_vertices(region_, lambda_, H_target, options_.normal_weighting, options_.damping, X,
                         N_, &subset, &coupling_);
  }
}

}  // namespace geofair
