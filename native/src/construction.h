// The iterative construction of a discrete solution of Δ_B H = 0 on one mesh (Schneider &
// Kobbelt 2001, sections 7.1-7.3), used on the single level and on every multigrid level.
#pragma once

#include "curvature_solve.h"
#include "inner_fairness.h"
#include "laplace_beltrami.h"
#include "newton_step.h"
#include "region.h"
#include "geofair/types.h"

#include <functional>
#include <vector>

namespace geofair {

/// How an iteration ended.
struct IterationReport {
  int iterations = 0;      ///< iterations M_k -> M_{k+1} performed
  double residual = 0.0;   ///< L·max|H̄ − H| of the final mesh (see fairing.h)
  bool converged = false;  ///< residual <= tolerance
  bool cancelled = false;  ///< the progress callback asked to stop
  bool stalled = false;    ///< run_newton: no halving of the residual in `patience` steps
  /// run_newton's wall-clock seconds: the tangential relaxations before the steps, the
  /// polishes, and the rest (the Newton steps and their evaluations).
  double relax_seconds = 0.0, polish_seconds = 0.0, step_seconds = 0.0;
};

/// How Construction::run_newton runs on a level and when it stops.
struct NewtonRun {
  int max_iterations = 0;              ///< Newton steps at most
  double tolerance = 0.0;              ///< the residual that ends the run converged
  int iteration_offset = 0;            ///< the first step's number in progress reports
  int patience = 20;                   ///< steps without a halving of the residual: stalled
  bool polish_at_convergence = false;  ///< inner fairness at the converged shape (finest level)
  bool prolongated = false;            ///< X prolongated from a coarser level: a local step first
  bool from_initial_mesh = false;      ///< X a linear initial mesh: the far-start rule
  /// > 0: stop (stalled) once the merit is at most this and the last step did not halve it,
  /// a rejected step included (a coarse level crawling near its solution: the next level's
  /// steps do better).
  double crawl_merit = 0.0;
  /// X the solution of nearby boundary data, with the new data's fixed rows (LiveFairing's
  /// warm start): the tangential relaxations before the steps turn their planes from the
  /// first one on, are preconditioned by the factorization of the last call's, and stop after
  /// the first that the stretch limit did not cut short; the polish comes near convergence
  /// (NewtonTuning::warm_polish_residual) and solves to TangentialTuning::warm_lagged_tolerance.
  bool warm = false;
  /// X already near inner fairness (a warm start that repeats the last frame's response):
  /// no tangential relaxation before the steps, only the polish.
  bool skip_relaxation = false;
  /// The first step's preconditioner factorized on a second thread during the last
  /// relaxation (relax_before_steps) where the merit there is below this (0: never). fair()
  /// sets it on every level above the base: infinite on the finest,
  /// NewtonTuning::prefactorize_merit on the coarse ones, since a coarse level far from its
  /// solution took more steps from it (docs/NEWTON.md).
  double factorize_ahead_merit = 0.0;
  /// Asked before each step: true ends the run (cancelled; LiveFairing's frame time limit).
  std::function<bool()> stop;
};

/// State of the construction on one region: normals, mean curvatures, the Dirichlet matrix
/// S and the CG solver, reused across iterations.
class Construction {
 public:
  /// \param region  the mesh to fair (kept by reference)
  /// \param lambda  inner fairness weights (inner_fairness_weights)
  /// \param length  L, the length that makes the residual dimensionless (see fairing.h)
  /// options.tuning: the paper's iteration's, Newton's and the tangential solves' tuning.
  Construction(const FairingRegion& region, InnerFairnessWeights lambda,
               const FairingOptions& options, double length);

  /// Normals and Moreton–Séquin H of all vertices of X (#region×3), S and the residual
  /// (with the source term, if one is set). With a G0 boundary its H is 0 and its normals
  /// are re-estimated from X (they enter the spiral samples of free neighbours only).
  double evaluate(const Positions& X);

  /// Iterates until the residual reaches `tolerance` or `max_iterations` iterations; local
  /// (Gauss–Seidel) and global (CG) steps alternate, and global steps move the vertices
  /// tangentially by TangentialSolver before the update along the normals. Every vertex
  /// update divides its normal step by the coupling factor max(1, ρ_i) (coupling_factors in
  /// vertex_update.h), refreshed every tuning.paper.coupling_refresh iterations.
  /// `progress` receives (iteration_offset + k, residual).
  /// \throw SolverError if the iteration diverges.
  IterationReport run(Positions& X, int max_iterations, double tolerance,
                      int iteration_offset = 0);

  /// Newton's method on eq. (12) instead (newton_step.h; beyond the paper). The vertex
  /// distribution is first brought to inner fairness by tangential solves
  /// (TangentialSolver::relax, at most tuning.newton.relaxations; the first with fixed tangent
  /// planes, the next with turning ones). Then per iteration the normal offsets of all free
  /// vertices from one inexact Newton step (NewtonStep, with the products of the exact
  /// Jacobian), scaled so that no vertex moves by more than max_step mean distances to
  /// its neighbours, globalized by pseudo-transient continuation (Kelley & Keyes 1998): the
  /// first step is Newton's; a step that raises merit() by more than merit_growth is taken
  /// back and the next
  /// solves (J + σ M) t = −d instead (an implicit Euler step of the flow ∂t/∂τ = −M⁻¹ d,
  /// M_i = Σ_j |w_ij| / h_i², about J's diagonal), σ starting at shift_start and growing by
  /// shift_increase per taken-back step; an accepted step scales σ by the merit's ratio
  /// (switched evolution relaxation), so σ vanishes as the merit falls and the steps
  /// become Newton's again. Above shift_max the run stops as stalled. The tangential
  /// (inner-fairness) relaxation is not interleaved with the steps: if
  /// `newton_run.polish_at_convergence` is set, where the residual reaches the tolerance (a
  /// warm run's: warm_polish_residual times it, so that the last step takes up its change) one
  /// tangential solve with turning tangent planes restores inner fairness (direct, or on the two-grid
  /// preconditioner of set_coarse_space), each vertex lifted back by −H/2·|d|² along its
  /// normal over its tangential move d; that changes the discretization of H, so the
  /// residual may rise and the steps go on. The polish repeats (at once if the residual is
  /// still within that bound, else when it is again) while the next one would
  /// move a vertex by more than polished_move mean distances to its neighbours (predicted
  /// from the last one's move by the quadratic convergence, polish_contraction), at most
  /// `polishes` times (all of options.tuning.newton).
  /// Stops like run(), and also when the residual has not halved in `newton_run.patience`
  /// iterations (report.stalled): far from a solution on a badly shaped mesh the
  /// linearization can fail to contract; report.cancelled where options.stop_requested
  /// stopped the tangential solves before the first step.
  /// \throw SolverError if the iteration diverges or the Newton system is singular.
  ///
  /// With `newton_run.prolongated` (X prolongated from a coarser level, multigrid.h) one
  /// local step of the construction (a Gauss–Seidel sweep for H̃, eq. (12), and the vertex
  /// update along the normals of section 7.2 without coupling factors or tangential move)
  /// comes between the relaxation and the first Newton step: the "smooth the level"
  /// after the prolongation. The prolongation leaves errors of the size of an edge at the new
  /// vertices, where H is far from linear in their offsets; the local step, which solves
  /// for each vertex's H on its own, takes them out. The step is kept only if it lowers the
  /// residual. Not on the linear initial mesh, whose error is smooth (docs/NEWTON.md).
  ///
  /// `newton_run.patience`: the number of steps without a halving of the residual after
  /// which the run stops as stalled (NewtonTuning::patience; coarse levels of a hierarchy
  /// coarse_patience). `newton_run.from_initial_mesh` (X is a linear initial mesh): the run
  /// also stops as stalled where its merit is above NewtonTuning::far_merit after far_steps
  IterationReport run_newton(Positions& X, const NewtonRun& newton_run);

  /// Prepares run_newton ahead of the level's turn: the symbolic analysis of its Newton
  /// preconditioner (NewtonStep::analyze), which depends only on the mesh. fair() calls it
  /// for the finest level on its second thread while the coarser levels are built.
  void prepare_newton() { newton_.analyze(); }

  /// New boundary data on the same mesh (LiveFairing): the unit normals of the G1 boundary
  /// (#V_B×3, held fixed by the construction; with G0 only a start, re-estimated) and the
  /// length L of the residual (see fairing.h).
  void set_boundary(const Positions& g1_normals, double length) {
    N_.bottomRows(region_.n - region_.n_free) = g1_normals;
    length_ = length;
  }

  /// New inner fairness weights (LiveFairing: the conformal weights of a new original);
  /// false, and nothing changed, where their neighbours are not those of the current ones
  /// (the tangential solver's pattern).
  bool set_lambda(InnerFairnessWeights lambda) {
    if (lambda.offset != lambda_.offset || lambda.neighbour != lambda_.neighbour) return false;
    lambda_ = std::move(lambda);
    return true;
  }

  /// Multigrid coarse-grid problems (multigrid.h): solve Σ_j w_ij (H_i − H_j) = τ_i
  /// (#V_I, kept by pointer; nullptr: eq. (12) itself) instead of 0, and move along the
  /// normals only (no inner fairness) if `tangential` is false.
  void set_source(const Eigen::VectorXd* tau, bool tangential) {
    source_ = tau;
    tangential_ = tangential;
  }

  /// The next coarser level of a progressive mesh as the coarse space of the tangential
  /// solves (TangentialSolver::set_coarse_space): the polishes of run_newton then need no
  /// factorization at this level's size.
  void set_coarse_space(CoarseSpace coarse, CoarseSpace coarser = {}) {
    tangential_solver_.set_coarse_space(std::move(coarse), std::move(coarser));
  }

  /// L · the root mean square of the Jacobi-scaled defects (H̄_i − H_i, with the source if
  /// set) of the positions last evaluated: the merit that run_newton's steps must lower.
  double merit() const;

  /// The defects d_i = Σ_j w_ij (H_i − H_j) (#V_I, 1/length) of the positions last evaluated.
  Eigen::VectorXd defects() const { return dirichlet_.defects(H_); }
  /// Mean curvatures (#region) and unit normals (#region×3) of the positions last evaluated.
  const Eigen::VectorXd& mean_curvatures() const { return H_; }
  const Positions& normals() const { return N_; }
  /// Iterations performed by run() and run_newton() so far, all calls together.
  long iterations() const { return iterations_; }

  const InnerFairnessWeights& lambda() const { return lambda_; }

 private:
  // H̃ of section 7.1 at the positions last evaluated (#V_I): one Gauss–Seidel sweep
  // (local) or the CG solve (global, CurvatureSolver) of S H̃ = b (+ the source τ) from H.
  Eigen::VectorXd target_curvatures(bool global);
  void curvatures(const Positions& X);
  void curvatures(const Positions& X, Positions& N, Eigen::VectorXd& H) const;
  // The parts of run_newton: the tangential solves towards inner fairness before the steps
  // (false if options.stop_requested stopped them);
  // the local step after a prolongation, kept if it lowers `residual` (returns the residual
  // of X); one polish at a converged shape (returns the largest move in mean distances to
  // the neighbours); the continuation's M_i = Σ_j |w_ij| / h_i² (#V_I, 1/length²); and
  // J v by a forward difference of the defects d0 at X, everything recomputed at X + ε v N.
  bool relax_before_steps(Positions& X, const NewtonRun& newton_run);
  // The largest move of a free vertex from `before` to X, in mean distances to its
  // neighbours at `before`.
  double longest_move(const Positions& before, const Positions& X) const;
  double local_step(Positions& X, double residual);
  double polish(Positions& X, bool warm);
  void shift_mass(const Positions& X, Eigen::VectorXd& mass) const;
  void jacobian_product(const Positions& X, const Eigen::VectorXd& d0, const Eigen::VectorXd& v,
                        Eigen::VectorXd& out);
  // The state of run_newton's pseudo-transient continuation: the shift σ (dimensionless),
  // the merit of the current iterate, and the step's work vectors.
  struct Continuation {
    double sigma = 0.0;
    double merit = 0.0;
    double tolerance = 0.0;  // run_newton's
    bool reach = false;      // GMRES aims a step at the tolerance (NewtonTuning::krylov_reach)
    Eigen::VectorXd mass, t, d0;
  };
  enum class StepOutcome { Taken, Rejected, Stalled };
  // One step of the continuation from X (evaluated, `residual` its residual): taken, or
  // taken back with σ raised, Stalled where σ passed shift_max.
  StepOutcome continuation_step(Positions& X, Continuation& c, double& residual);

  const FairingRegion& region_;
  InnerFairnessWeights lambda_;
  const FairingOptions& options_;
  double length_;
  Positions N_;
  Eigen::VectorXd H_;
  DirichletMatrix dirichlet_;
  CurvatureSolver solver_;
  std::vector<double> coupling_;  // ρ_i of the free vertices
  TangentialSolver tangential_solver_;
  NewtonStep newton_;
  // Scratch state of the Jacobian products of run_newton.
  DirichletMatrix probe_dirichlet_;
  Positions probe_X_, probe_N_;
  Eigen::VectorXd probe_H_;
  const Eigen::VectorXd* source_ = nullptr;
  bool tangential_ = true;
  // This thread's loop threads while the first Newton factorization runs beside the
  // relaxation (relax_before_steps), else 0.
  int overlap_threads_ = 0;
  long iterations_ = 0;
};


}  // namespace geofair
