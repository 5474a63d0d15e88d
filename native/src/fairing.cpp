// The construction algorithm of Schneider & Kobbelt 2001, section 7 (single level).
#include "geofair/fairing.h"

#include "geofair/bilaplacian.h"
#include "geofair/curvature_solve.h"
#include "geofair/inner_fairness.h"
#include "geofair/laplace_beltrami.h"
#include "geofair/mean_curvature.h"
#include "geofair/region.h"
#include "geofair/vertex_update.h"

#include <cmath>
#include <string>

namespace geofair {
namespace {

void check_options(const FairingOptions& o) {
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance))
    throw InvalidInputError("fair: tolerance must be a positive finite number");
  if (o.max_iterations < 0) throw InvalidInputError("fair: max_iterations must be >= 0");
  if (!(o.damping > 0.0 && o.damping <= 1.0))
    throw InvalidInputError("fair: damping must lie in (0, 1]");
  if (o.cg_iterations < 1) throw InvalidInputError("fair: cg_iterations must be >= 1");
}

// Normals (free rows) and mean curvatures (all rows) of the current mesh.
void estimate_curvature(const FairingRegion& region, const Positions& X, NormalWeighting weighting,
                        Positions& N, Eigen::VectorXd& H) {
  const OneRings& rings = region.rings;
  for (int i = 0; i < region.n_free; ++i) N.row(i) = vertex_normal(rings, X, i, weighting);
  for (int i = 0; i < region.n; ++i)
    H(i) = moreton_sequin(rings, X, N, i, X.row(i), N.row(i), needs_spiral_samples(rings, i)).H;
}

}  // namespace

FairingResult fair(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const Positions* boundary_normals, const FairingOptions& options) {
  check_options(options);
  const FairingRegion region = extract_region(V, F, free, boundary_normals);
  const int n = region.n, nf = region.n_free;

  Positions X(n, 3);
  for (int i = 0; i < n; ++i) X.row(i) = V.row(region.global[i]);
  const double L = (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
  if (!(L > 0.0)) throw InvalidInputError("fair: the region has zero extent");

  const std::vector<double> lambda = inner_fairness_weights(region.rings, X, options.inner_fairness);
  X = bilaplacian_initial_mesh(region, lambda, X);

  Positions N(n, 3);
  N.bottomRows(n - nf) = region.g1_normals;
  Eigen::VectorXd H(n);
  DirichletMatrix dirichlet(region);
  CurvatureSolver solver(options.cg_iterations);

  FairingResult result;
  double first_residual = 0.0;
  for (int k = 0;; ++k) {
    estimate_curvature(region, X, options.normal_weighting, N, H);
    dirichlet.assemble(X);
    const double residual = L * L * L * dirichlet.max_laplace_beltrami(H);
    if (!std::isfinite(residual))
      throw SolverError("fair: the iteration diverged (non-finite mean curvature at iteration " +
                        std::to_string(k) + ")");
    if (k == 0) first_residual = residual;
    if (residual > 1e6 * std::max(first_residual, 1.0))
      throw SolverError("fair: the iteration diverged (residual grew from " +
                        std::to_string(first_residual) + " to " + std::to_string(residual) +
                        " by iteration " + std::to_string(k) + ")");
    result.iterations = k;
    result.residual = residual;
    result.converged = residual <= options.tolerance;
    if (options.outer_fairness == OuterFairness::Bilaplacian) {
      result.converged = true;  // the linear solution is exact; the residual says how far
      break;                    // it is from Δ_B H = 0
    }
    if (result.converged || k >= options.max_iterations) break;
    if (options.progress && !options.progress(k, residual)) break;

    const Eigen::VectorXd b = dirichlet.rhs(H);
    Eigen::VectorXd H_target = H.head(nf);
    if (k % 2 == 0)
      gauss_seidel_sweep(dirichlet.S(), b, H_target);
    else
      solver.global_step(dirichlet.S(), b, H_target);
    const double step = update_free_vertices(region, lambda, H_target, options.normal_weighting,
                                             options.damping, X, N);
    if (!(step <= L))
      throw SolverError("fair: the iteration diverged (a vertex moved by more than the region's "
                        "size in iteration " + std::to_string(k) + ")");
  }

  result.vertices = V;
  for (int i = 0; i < nf; ++i) result.vertices.row(region.global[i]) = X.row(i);
  if (!result.vertices.allFinite())
    throw SolverError("fair: the iteration produced non-finite positions");
  return result;
}

}  // namespace geofair
