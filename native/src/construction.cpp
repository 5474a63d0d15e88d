// The construction loop of sections 7.1-7.3 on one mesh.
#include "construction.h"

#include "common.h"
#include "mean_curvature.h"
#include "parallel.h"
#include "surface_projection.h"
#include "vertex_update.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace geofair {
namespace {

// Levels with at least this many free vertices factorize the first Newton step's
// preconditioner during their last relaxation (NewtonRun::factorize_ahead_merit; docs/NEWTON.md,
// "The first factorization beside the last relaxation"). Below, the factorization costs
// little, and small fills keep their steps.
constexpr int kPrefactorizeMin = 500;

// Sets this thread's loop threads back to `saved` (if > 0) at restore() or on leaving the
// scope.
class LoopThreadsRestore {
 public:
  explicit LoopThreadsRestore(int& saved) : saved_(saved) {}
  ~LoopThreadsRestore() { restore(); }
  LoopThreadsRestore(const LoopThreadsRestore&) = delete;
  LoopThreadsRestore& operator=(const LoopThreadsRestore&) = delete;
  void restore() {
    if (saved_ > 0) set_loop_threads(saved_), saved_ = 0;
  }

 private:
  int& saved_;
};

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
      tangential_solver_(region.rings, lambda_, region.n_free,
                         options.tuning.paper.tangential_iterations, options.tuning.tangential),
      newton_(region, options.tuning.newton, options.normal_weighting),
      probe_dirichlet_(region) {
  N_.bottomRows(region.n - region.n_free) = region.g1_normals;
}

void Construction::curvatures(const Positions& X) { curvatures(X, N_, H_); }

void Construction::curvatures(const Positions& X, Positions& N, Eigen::VectorXd& H) const {
  const OneRings& rings = region_.rings;
  const NormalWeighting w = options_.normal_weighting;
  const int nf = region_.n_free, n = region_.n;
  // G0: H = 0 prescribed on the boundary; its tangent planes, which only the spiral samples
  // of free neighbours read, follow the surface (Max's weights, as on coarse levels).
  const bool g0 = region_.boundary == BoundaryCondition::G0;
  const bool parallel = n > kParallelMin;
  parallel_for(nf, parallel, [&](int i) { N.row(i) = vertex_normal(rings, X, i, w); });
  if (g0) {
    parallel_for(n - nf, parallel, [&](int k) {
      const Vec3 normal = vertex_normal(rings, X, nf + k, NormalWeighting::Max);
      if (normal.squaredNorm() > 0.0) N.row(nf + k) = normal;
    });
  }
  parallel_for(g0 ? nf : n, parallel, [&](int i) {
    H(i) = moreton_sequin(rings, X, N, i, X.row(i), N.row(i), needs_spiral_samples(rings, i)).H;
  });
  if (g0) H.tail(n - nf).setZero();
}

double Construction::merit() const {
  const OneRings& r = region_.rings;
  const std::vector<double>& w = dirichlet_.weights();
  const Eigen::VectorXd d = dirichlet_.defects(H_);
  double sum = 0.0;
  for (int i = 0; i < region_.n_free; ++i) {
    double sum_w = 0.0;
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k) sum_w += w[k];
    const double deviation = (d(i) - (source_ ? (*source_)(i) : 0.0)) / std::max(sum_w, 1e-300);
    sum += deviation * deviation;
  }
  return length_ * std::sqrt(sum / region_.n_free);
}

double Construction::evaluate(const Positions& X) {
  curvatures(X);
  dirichlet_.assemble(X);
  return length_ * dirichlet_.max_mean_deviation(H_, source_);
}

Eigen::VectorXd Construction::target_curvatures(bool global) {
  Eigen::VectorXd b = dirichlet_.rhs(H_);
  if (source_) b += *source_;
  Eigen::VectorXd H_target = H_.head(region_.n_free);
  if (global)
    solver_.global_step(dirichlet_.S(), b, H_target);
  else
    gauss_seidel_sweep(dirichlet_.S(), b, H_target);
  return H_target;
}

IterationReport Construction::run(Positions& X, int max_iterations, double tolerance,
                                  int iteration_offset) {
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
    const bool global = k % 2 == 1;
    const Eigen::VectorXd H_target = target_curvatures(global);
    if (iterations_++ % options_.tuning.paper.coupling_refresh == 0 || coupling_.empty())
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

double Construction::longest_move(const Positions& before, const Positions& X) const {
  double move = 0.0;
  for (int i = 0; i < region_.n_free; ++i)
    move = std::max(move, (X.row(i) - before.row(i)).norm() /
                              region_.rings.mean_neighbour_distance(before, i));
  return move;
}

bool Construction::relax_before_steps(Positions& X, const NewtonRun& newton_run) {
  // Inner fairness first: the vertex distribution that satisfies it can lie many edge
  // lengths from that of the initial mesh or of a prolongated one, and the Newton steps
  // do not move vertices tangentially (docs/NEWTON.md, NewtonTuning::relaxations). At least two
  // direct solves (the second corrects the tangent planes of the first), more while the
  // stretch limit cuts a solve short. The first holds the tangent planes fixed: far from
  // inner fairness turning planes made the base level of a large hierarchy stall.
  // Long moves are put back onto the surface of X and its normals as the relaxations
  // found them (the projection is set up the first time it is needed). A warm start is near
  // inner fairness: turning planes and the last factorization from the first solve on, and
  // one solve unless the stretch limit cut it short (the polish near convergence follows).
  const NewtonTuning& newton = options_.tuning.newton;
  const bool warm = newton_run.warm;
  Positions surface, surface_normals;
  std::unique_ptr<SurfaceProjection> projection;
  double last_scale = 0.0;  // of the last solve
  bool prefactorized = false;
  for (int p = 0; p < newton.relaxations; ++p) {
    // Each solve factorizes a system of the level's size (seconds at 10^5 vertices).
    if (options_.stop_requested && options_.stop_requested()) return false;
    evaluate(X);  // the normals at X
    // After a solve that took its whole step the vertices lie near inner fairness, and a
    // Newton preconditioner factorized here needs no more GMRES iterations than one at the
    // relaxed positions: it is factorized on a second thread while this one finishes the
    // relaxations and the local step on one core (run_newton restores the threads).
    const double ahead_merit = newton_run.factorize_ahead_merit;
    if (ahead_merit > 0.0 && p > 0 && last_scale == 1.0 && !warm &&
        region_.n_free >= kPrefactorizeMin && merit() < ahead_merit) {
      const bool async = loop_threads() > 1;
      newton_.prefactorize(X, N_, H_, dirichlet_.weights(), async);
      prefactorized = true;
      if (async) overlap_threads_ = loop_threads(), set_loop_threads(1);
    }
    if (p == 0) surface = X, surface_normals = N_;
    const Positions before = X;
    const bool near = p > 0 || warm;
    const double scale = tangential_solver_.relax(
        lambda_, N_, X, /*lagged=*/near, near ? TangentPlanes::Turning : TangentPlanes::Fixed);
    if (longest_move(before, X) > newton.projection_move) {
      if (!projection)
        projection = std::make_unique<SurfaceProjection>(region_, std::move(surface),
                                                         std::move(surface_normals));
      for (int i = 0; i < region_.n_free; ++i) projection->project(i, X);
    }
    if (prefactorized && scale < 1.0) {  // the vertices move on: factorized at the steps
      newton_.discard_prefactorization();
      LoopThreadsRestore(overlap_threads_).restore();  // the loops on all threads again
      prefactorized = false;
    }
    last_scale = scale;
    if (scale <= 0.0 || ((p > 0 || warm) && scale == 1.0)) break;
  }
  return true;
}

double Construction::local_step(Positions& X, double residual) {
  // The construction's local step (sections 7.1-7.2), with the paper's vertex update (no
  // coupling factors) and no tangential move (the relaxation has just placed the vertices),
  // kept if it lowers the residual.
  const Positions before = X;
  update_free_vertices(region_, lambda_, target_curvatures(/*global=*/false),
                       options_.normal_weighting, options_.damping, X, N_, nullptr, nullptr,
                       /*tangential=*/false);
  const double smoothed = evaluate(X);
  if (smoothed < residual) return smoothed;
  X = before;
  return evaluate(X);
}

double Construction::polish(Positions& X, bool warm) {
  // The tangential solve moves the vertices in their tangent planes; each is lifted back by
  // the surface's drop −H/2·|d|² over the tangential move d (as in prolongate). N_ and H_
  // are those of X. The solve is preconditioned by the factorization of the relaxation
  // before the steps (lagged); a warm run's solves to its own tolerance.
  const OneRings& rings = region_.rings;
  const Positions before = X;
  tangential_solver_.relax(lambda_, N_, X, /*lagged=*/true, TangentPlanes::Turning,
                           warm ? options_.tuning.tangential.warm_lagged_tolerance : 0.0);
  double move = 0.0;  // the largest move, in mean distances to the neighbours
  for (int i = 0; i < region_.n_free; ++i) {
    const Vec3 d = (X.row(i) - before.row(i)).transpose();
    X.row(i) -= (0.5 * H_(i) * d.squaredNorm()) * N_.row(i);
    move = std::max(move, d.norm() / rings.mean_neighbour_distance(before, i));
  }
  return move;
}

void Construction::shift_mass(const Positions& X, Eigen::VectorXd& mass) const {
  const OneRings& rings = region_.rings;
  mass.resize(region_.n_free);
  for (int i = 0; i < region_.n_free; ++i) {
    double sum_w = 0.0;
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
      sum_w += std::abs(dirichlet_.weights()[k]);
    const double h = rings.mean_neighbour_distance(X, i);
    mass(i) = std::max(sum_w, 1e-12) / (h * h);
  }
}

void Construction::jacobian_product(const Positions& X, const Eigen::VectorXd& d0,
                                    const Eigen::VectorXd& v, Eigen::VectorXd& out) {
  const int nf = region_.n_free;
  const double v_max = v.cwiseAbs().maxCoeff();
  if (!(v_max > 0.0)) {
    out = Eigen::VectorXd::Zero(nf);
    return;
  }
  const double eps = options_.tuning.newton.product_step * length_ / v_max;
  probe_X_ = X;
  for (int i = 0; i < nf; ++i) probe_X_.row(i) += (eps * v(i)) * N_.row(i);
  curvatures(probe_X_, probe_N_, probe_H_);
  probe_dirichlet_.assemble(probe_X_);
  out = (probe_dirichlet_.defects(probe_H_) - d0) / eps;
}

// Pseudo-transient continuation: the step solves (J + σ M) t = −d, an implicit Euler step of
// the flow ∂t/∂τ = −M⁻¹ d with σ = 1/Δτ; σ = 0 is Newton's step. A step that raises the
// merit by more than merit_growth is taken back and σ raised; accepted steps scale σ by the
// merit's ratio (switched evolution relaxation), so close to the solution the steps are
// Newton's and converge quadratically.
Construction::StepOutcome Construction::continuation_step(Positions& X, Continuation& c,
                                                          double& residual) {
  const NewtonTuning& newton = options_.tuning.newton;
  const int nf = region_.n_free;
  const OneRings& rings = region_.rings;
  auto product = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    jacobian_product(X, c.d0, v, out);
  };
  c.d0 = dirichlet_.defects(H_);
  if (c.sigma > 0.0) shift_mass(X, c.mass);
  // An inexact Newton step: GMRES to krylov_tolerance, or, in a cold run, tighter where that
  // would leave the step above the run's tolerance but a solve down to krylov_tolerance_min
  // would not (NewtonTuning::krylov_reach; docs/NEWTON.md).
  const double reaching = newton.krylov_reach * c.tolerance / residual;
  const bool aimed = c.reach && reaching < newton.krylov_tolerance &&
                     reaching >= newton.krylov_tolerance_min;
  const double krylov_tolerance = aimed ? reaching : newton.krylov_tolerance;
  if (!newton_.solve(X, N_, H_, dirichlet_.weights(), c.d0, source_, product, {c.sigma, &c.mass},
                     krylov_tolerance, c.t))
    throw SolverError("fair: the Newton system is singular (degenerate triangles)");
  // Step length: no vertex moves by more than max_step mean distances to its neighbours.
  double ratio = 0.0;
  for (int i = 0; i < nf; ++i)
    ratio = std::max(ratio, std::abs(c.t(i)) / rings.mean_neighbour_distance(X, i));
  const double s = std::min(1.0, newton.max_step / ratio);
  const Positions before = X;
  for (int i = 0; i < nf; ++i) X.row(i) += s * c.t(i) * N_.row(i);
  ++iterations_;
  const double trial = evaluate(X);
  const double trial_merit = merit();
  if (!(trial_merit < newton.merit_growth * c.merit) || !std::isfinite(trial)) {
    X = before;
    residual = evaluate(X);
    c.sigma = std::max(newton.shift_increase * c.sigma, newton.shift_start);
    return c.sigma > newton.shift_max ? StepOutcome::Stalled : StepOutcome::Rejected;
  }
  c.sigma *= trial_merit / c.merit;
  if (c.sigma < newton.shift_negligible * newton.shift_negligible) c.sigma = 0.0;
  c.merit = trial_merit;
  residual = trial;
  return StepOutcome::Taken;
}

IterationReport Construction::run_newton(Positions& X, const NewtonRun& newton_run) {
  const double tolerance = newton_run.tolerance;
  const NewtonTuning& newton = options_.tuning.newton;
  IterationReport report;
  Laps laps;  // report's relax, step and polish seconds
  LoopThreadsRestore threads(overlap_threads_);  // after the local step, or on leaving
  const bool relaxed =
      !tangential_ || newton_run.skip_relaxation ||
      relax_before_steps(X, newton_run);
  report.relax_seconds = laps.lap();
  double residual = evaluate(X);
  if (!relaxed) {
    report.residual = residual;
    report.cancelled = true;
    return report;
  }
  if (newton_run.prolongated) residual = local_step(X, residual);
  threads.restore();
  const double first_residual = residual;
  double best = residual;
  int best_at = 0, polishes = 0;
  bool polished = false;
  probe_N_ = N_;
  probe_H_.resize(region_.n);
  Continuation c;
  c.tolerance = tolerance;
  c.reach = !newton_run.warm;
  c.merit = merit();
  double last_merit = c.merit;  // at the previous step
  const double polish_at = newton_run.warm ? newton.warm_polish_residual * tolerance : tolerance;
  c.mass.resize(region_.n_free);
  for (int k = 0;; ++k) {
    check_divergence(residual, first_residual, newton_run.iteration_offset + k);
    while (residual <= polish_at && tangential_ && newton_run.polish_at_convergence && !polished) {
      // Inner fairness at the converged shape (a warm run's near it); go on if it moved the
      // residual up.
      report.step_seconds += laps.lap();
      const double move = polish(X, newton_run.warm);
      // Another polish (after the steps it needs, if any) while the next would still move a vertex
      // by more than polished_move: the solves converge quadratically, so the next moves
      // about polish_contraction · move².
      polished = newton.polish_contraction * move * move <= newton.polished_move ||
                 ++polishes >= newton.polishes;
      residual = evaluate(X);
      c.merit = merit();
      best = residual, best_at = k;
      report.polish_seconds += laps.lap();
    }
    report.iterations = k;
    report.residual = residual;
    report.converged = residual <= tolerance;
    if (residual < 0.5 * best) best = residual, best_at = k;
    report.stalled = k - best_at >= newton_run.patience ||
                     ((newton_run.from_initial_mesh || newton_run.prolongated) &&
                      k == newton.far_steps && c.merit > newton.far_merit) ||
                     (k > 0 && c.merit <= newton_run.crawl_merit && c.merit > 0.5 * last_merit);
    last_merit = c.merit;
    if (report.converged || report.stalled || k >= newton_run.max_iterations) break;
    if ((options_.progress && !source_ &&
         !options_.progress(newton_run.iteration_offset + k, residual)) ||
        (newton_run.stop && newton_run.stop())) {
      report.cancelled = true;
      break;
    }
    if (continuation_step(X, c, residual) == StepOutcome::Stalled) {
      report.stalled = true;
      report.iterations = k + 1;
      report.residual = residual;
      break;
    }
  }
  report.step_seconds += laps.lap();
  return report;
}

}  // namespace geofair
