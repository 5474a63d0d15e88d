// The construction loop of sections 7.1-7.3 on one mesh.
#include "geofair/construction.h"

#include "geofair/mean_curvature.h"
#include "geofair/vertex_update.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace geofair {
namespace {

// Throws if the residual of iteration k is not finite or has grown a millionfold.
void check_divergence(double residual, double first_residual, int k) {
  if (!std::isfinite(residual))
    throw SolverError("fair: the iteration diverged (non-finite mean curvature at iteration " +
                      std::to_string(k) + ")");
  if (residual > 1e6 * std::max(first_residual, 1.0))
    throw SolverError("fair: the iteration diverged (residual grew from " +
                      std::to_string(first_residual) + " to " + std::to_string(residual) +
                      " by iteration " + std::to_string(k) + ")");
}

}  // namespace

Construction::Construction(const FairingRegion& region, InnerFairnessWeights lambda,
                           const FairingOptions& options, double length)
    : region_(region),
      lambda_(std::move(lambda)),
      options_(options),
      length_(length),
      N_(region.n, 3),
      H_(region.n),
      dirichlet_(region),
      solver_(options.cg_iterations),
      tangential_solver_(region.rings, lambda_, region.n_free, kTangentialIterations),
      newton_(region) {
  N_.bottomRows(region.n - region.n_free) = region.g1_normals;
}

void Construction::curvatures(const Positions& X) {
  const OneRings& rings = region_.rings;
  const NormalWeighting w = options_.normal_weighting;
  const int nf = region_.n_free, n = region_.n;
#pragma omp parallel if (n > kParallelMin)
  {
#pragma omp for schedule(static)
    for (int i = 0; i < nf; ++i) N_.row(i) = vertex_normal(rings, X, i, w);
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i)
      H_(i) = moreton_sequin(rings, X, N_, i, X.row(i), N_.row(i), needs_spiral_samples(rings, i)).H;
  }
}

double Construction::evaluate(const Positions& X) {
  curvatures(X);
  dirichlet_.assemble(X);
  return length_ * dirichlet_.max_mean_deviation(H_, source_);
}

IterationReport Construction::run(Positions& X, int max_iterations, double tolerance,
                                  int iteration_offset) {
  const int nf = region_.n_free;
  IterationReport report;
  double first_residual = 0.0;
  for (int k = 0;; ++k) {
    const double residual = evaluate(X);
    if (k == 0) first_residual = residual;
    check_divergence(residual, first_residual, iteration_offset + k);
    report.iterations = k;
    report.residual = residual;
    report.converged = residual <= tolerance;
    if (report.converged || k >= max_iterations) break;
    // Coarse-grid problems (with a source) are not the user's residual: no progress there.
    if (options_.progress && !source_ && !options_.progress(iteration_offset + k, residual)) {
      report.cancelled = true;
      break;
    }
    Eigen::VectorXd b = dirichlet_.rhs(H_);
    if (source_) b += *source_;
    Eigen::VectorXd H_target = H_.head(nf);
    const bool global = k % 2 == 1;
    if (global)
      solver_.global_step(dirichlet_.S(), b, H_target);
    else
      gauss_seidel_sweep(dirichlet_.S(), b, H_target);
    if (iterations_++ % kCouplingRefresh == 0 || coupling_.empty())
      coupling_factors(region_, dirichlet_.weights(), options_.normal_weighting, H_, X, N_,
                       coupling_);
    const Positions X_before = X;
    if (global && tangential_) tangential_solver_.step(lambda_, N_, options_.damping, X);
    double step = update_free_vertices(region_, lambda_, H_target, options_.normal_weighting,
                                       options_.damping, X, N_, nullptr, &coupling_,
                                       tangential_ && !global);
    if (global) step = (X - X_before).rowwise().norm().maxCoeff();
    if (!(step <= length_))
      throw SolverError("fair: the iteration diverged (a vertex moved by more than the region's "
                        "size in iteration " + std::to_string(iteration_offset + k) + ")");
  }
  return report;
}

IterationReport Construction::run_newton(Positions& X, int max_iterations, double tolerance,
                                         int iteration_offset) {
  const int nf = region_.n_free;
  const OneRings& rings = region_.rings;
  IterationReport report;
  // Inner fairness first: the vertex distribution that satisfies it can lie many edge
  // lengths from that of the initial mesh (up to 10 on the disturbed 100000-vertex cap), and
  // the tangential steps between Newton steps, which limit each vertex's move to half an
  // edge, then spend tens of steps getting there while H at the vertices they clamp jumps.
  // At least two direct solves (the second corrects the tangent planes of the first), more
  // while the stretch limit cuts a solve short.
  if (tangential_)
    for (int p = 0; p < kNewtonRelaxations; ++p) {
      evaluate(X);  // the normals at X
      const double scale = tangential_solver_.relax(lambda_, N_, X);
      if (scale <= 0.0 || (p > 0 && scale == 1.0)) break;
    }
  double residual = evaluate(X);
  const double first_residual = residual;
  double best = residual;
  int best_at = 0;
  Eigen::VectorXd t;
  for (int k = 0;; ++k) {
    check_divergence(residual, first_residual, iteration_offset + k);
    report.iterations = k;
    report.residual = residual;
    report.converged = residual <= tolerance;
    if (residual < 0.5 * best) best = residual, best_at = k;
    report.stalled = k - best_at >= kNewtonPatience;
    if (report.converged || report.stalled || k >= max_iterations) break;
    if (options_.progress && !source_ && !options_.progress(iteration_offset + k, residual)) {
      report.cancelled = true;
      break;
    }
    if (!newton_.solve(X, N_, H_, dirichlet_.weights(), dirichlet_.defects(H_), source_, t))
      throw SolverError("fair: the Newton system is singular (degenerate triangles)");
    // Step length: no vertex moves by more than kNewtonStep mean distances to its neighbours.
    double ratio = 0.0;
    for (int i = 0; i < nf; ++i)
      ratio = std::max(ratio, std::abs(t(i)) / rings.mean_neighbour_distance(X, i));
    const double s = std::min(1.0, kNewtonStep / ratio);
    for (int i = 0; i < nf; ++i) X.row(i) += s * t(i) * N_.row(i);
    if (tangential_) tangential_solver_.step(lambda_, N_, options_.damping, X);
    ++iterations_;
    residual = evaluate(X);
  }
  return report;
}

}  // namespace geofair
