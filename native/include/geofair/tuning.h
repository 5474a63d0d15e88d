// Tuning of geofair::fair's solvers: the numerical choices beyond the paper's options,
// grouped by the stage that reads them, each with its unit and meaning here and its valid
// range in for_each_tuning_field below (the one table of names and ranges). The defaults
// are the values the tests and benchmarks measure (the measurements are in docs/, named per
// field). Set them through FairingOptions::tuning; fair() rejects a value outside its range
// (validate_tuning; the fields' names and ranges: for_each_tuning_field).
#pragma once

namespace geofair {

/// The paper's iteration (section 7; Construction::run).
struct PaperIterationTuning {
  /// Iterations between refreshes of the coupling factors ρ_i (vertex_update.h): they follow
  /// the mesh shape, which changes slowly; one refresh costs about three iterations.
  int coupling_refresh = 16;
  /// BiCGSTAB iterations of a global tangential step (TangentialSolver::step).
  int tangential_iterations = 10;
};

/// Newton's method on eq. (12) (Construction::run_newton, NewtonStep; docs/NEWTON.md).
struct NewtonTuning {
  /// Steps without a halving of the residual after which a run stops as stalled ...
  int patience = 20;
  /// ... on the coarse levels of a hierarchy, which only start the next level: one that has
  /// stopped making progress is abandoned for the single level (docs/REAL_MESHES.md,
  /// "Regular caps").
  int coarse_patience = 8;
  /// A coarse level that stops unconverged with its merit (Construction::merit, the RMS of
  /// the scaled defects; dimensionless, like the residual) at most this starts the next
  /// level all the same: its max-norm residual is that of a few vertices; a prolongated
  /// coarse level stops as soon as its merit is at most this and a step no longer halves it
  /// (docs/DESIGN_NOTES.md, "Coarse levels of large irregular caps").
  double coarse_merit = 1e-2;
  /// A run from a linear initial mesh or from a prolongated coarser level whose merit
  /// (Construction::merit) is still above far_merit after far_steps steps stops as stalled:
  /// that start lies outside Newton's region of convergence, and the steps up to `patience`
  /// would only delay the next attempt (docs/NEWTON.md, "NewtonTuning::far_merit").
  int far_steps = 5;
  double far_merit = 1.0;
  /// A coarse level factorizes its first step's preconditioner beside its last relaxation
  /// (as the finest level does) where its merit there is below this: from farther the
  /// first steps need the preconditioner of their own positions (docs/NEWTON.md, "The
  /// first factorization beside the last relaxation"). Dimensionless; 0: never.
  double prefactorize_merit = 1.0;
  /// Largest move of a vertex in one step, in mean distances to its neighbours ...
  double max_step = 4.0;
  /// ... in the fairs of fill_holes, which start from a hole's linear fill, farther from
  /// the solution than a region's initial mesh (docs/NEWTON.md, "NewtonTuning::max_step").
  double fill_max_step = 1.0;
  /// Tangential solves towards inner fairness before the first step, at most: more than one
  /// where the stretch limit cuts a solve short.
  int relaxations = 8;
  /// A relaxation solve that moves a vertex by more than this many mean distances to its
  /// neighbours puts the free vertices back onto the surface the relaxations started from
  /// (SurfaceProjection): a long move in a tangent plane leaves a curved surface by about
  /// κ·d²/2, and Newton's steps do not recover from that (docs/DESIGN_NOTES.md, "Relaxations
  /// on the surface").
  double projection_move = 1.0;
  /// Tangential solves (polishes) at convergence, at most ...
  int polishes = 8;
  /// ... repeated while the next one would move a vertex by more than this many mean
  /// distances to its neighbours: one solve leaves inner fairness less exact than the
  /// paper's iteration does ...
  double polished_move = 1e-3;
  /// ... the next move predicted as polish_contraction · δ² after a move δ (the polishes
  /// converge quadratically; 1 leaves a margin over the measured contraction, and with
  /// polished_move = 1e-3 polishing stops after a move δ ≤ 0.032).
  double polish_contraction = 1.0;
  /// A LiveFairing frame's warm run polishes once its residual is below this multiple of the
  /// tolerance (a cold run at the tolerance): the polish moves the residual, and the step
  /// that still follows takes that up instead of a step after it (dimensionless, at least 1;
  /// 1 polishes at convergence).
  double warm_polish_residual = 300.0;
  /// Forward-difference step of the Jacobian products: the largest vertex move as a
  /// fraction of L (the region's diagonal).
  double product_step = 1e-7;
  /// A step that raises the merit by more than this factor is taken back: Newton's method
  /// converges non-monotonically on rough inputs, so a moderate rise is kept.
  double merit_growth = 4.0;
  /// Pseudo-transient continuation: the shift σ after the first taken-back step
  /// (dimensionless; M is about J's diagonal) ...
  double shift_start = 1e-2;
  /// ... multiplied by this per further taken-back step ...
  double shift_increase = 10.0;
  /// ... up to this: a step that short which still raises the merit ends the run (stalled).
  double shift_max = 1e8;
  /// Shifts below this count as none (dimensionless).
  double shift_negligible = 1e-3;
  /// GMRES iterations of a step at most (Eigen's GMRES without restart); a step that needs
  /// more than half of them refactorizes its preconditioner at the next step.
  int krylov_iterations = 30;
  /// The preconditioner ages as the iterate moves away from where it was factorized: it is
  /// refactorized at the next step once the GMRES iterations beyond its first solve's add up
  /// to this many Jacobian products (about what assembling and factorizing it costs).
  int refactorization_products = 15;
  /// GMRES's relative residual ‖P⁻¹(b − J t)‖/‖P⁻¹ b‖ of a step (an inexact Newton step).
  double krylov_tolerance = 1e-3;
  /// In a cold run (not a LiveFairing frame's warm one), a step from residual r on a fresh
  /// factorization solves GMRES to krylov_reach · tolerance / r instead (the run's
  /// tolerance), where that lies below krylov_tolerance and not below krylov_tolerance_min:
  /// a step that can end the run is not left short by the linear solve's error (a forcing
  /// term aimed at the tolerance, in the manner of Eisenstat and Walker). Dimensionless;
  /// 0 turns this off.
  double krylov_reach = 0.5;
  /// The tightest GMRES tolerance of such a step; a step that would need a tighter one solves
  /// to krylov_tolerance (it starts too far to end the run). Dimensionless, at most
  /// krylov_tolerance; equal to it turns the rule off.
  double krylov_tolerance_min = 1e-5;
  /// The preconditioner of a shifted step is refactorized when the shift differs from the
  /// factorized one by more than this factor (dimensionless).
  double shift_refactorization = 4.0;
};

/// Global tangential solves of inner fairness (TangentialSolver::relax, inner_fairness.h).
struct TangentialTuning {
  /// Largest relative stretch or shrinkage of an edge per relax.
  double max_stretch = 0.5;
  /// The turn of the tangent plane ℓ_i D_i is left out of a diagonal block where its norm
  /// reaches this (it is about (h·κ)²/2: larger only on a noisy mesh, where the
  /// linearization means nothing). Dimensionless.
  double max_turn = 0.5;
  /// GMRES's relative residual on a lagged factorization ...
  double lagged_tolerance = 1e-8;
  /// ... and its iteration limit there; beyond it the system is factorized anew.
  int lagged_iterations = 20;
  /// The relative residual of a LiveFairing frame's polish instead of lagged_tolerance: its
  /// move is about 5e-3 mean neighbour distances, so that 1e-2 of it lies far below
  /// NewtonTuning::polished_move, and what one frame's polish leaves the next one's takes
  /// up. Each decade below costs another iteration on the aging factorization.
  double warm_lagged_tolerance = 1e-2;
  /// Gauss–Seidel sweeps before and after the coarse-grid correction of the two-grid
  /// preconditioner ...
  int two_grid_sweeps = 2;
  /// ... and the blocks of rows of those sweeps: Gauss–Seidel within a block, the other
  /// blocks' values from the start of the sweep, one thread per block; systems of at most
  /// 2,500 rows are swept as one block (inner_fairness.cpp, kBlockedSweepMin). Fixed, so
  /// results do not depend on the thread count (docs/DESIGN_NOTES.md, "Tangential solves").
  int two_grid_blocks = 2;
  /// GMRES's iteration limit on the two-grid preconditioner; beyond it the system is
  /// factorized.
  int two_grid_iterations = 40;
  /// ... and its relative residual: a solve's error only leaves the next polish a little
  /// more to do (docs/DESIGN_NOTES.md, "Tangential solves").
  double two_grid_tolerance = 1e-3;
};

/// The paper's progressive-mesh multigrid (section 7.4; Multigrid, multigrid.h).
struct MultigridTuning {
  /// Gauss–Seidel sweeps of the relaxation after a prolongation (prolongate, step 2).
  int prolongation_sweeps = 2;
  /// After an undone correction a level's corrections are damped by 2, down to this
  /// factor (dimensionless): a correction that does not help costs its coarse problem and
  /// the smoothing, a paused cycle nothing extra ...
  double min_correction = 1.0 / 16;
  /// ... and after r undone in a row paused for 2^(r−1) − 1 cycles, at most this many.
  int max_skip = 15;
  /// Smoothing iterations before and after each coarse-grid correction
  /// (docs/DESIGN_NOTES.md, "Multigrid cycles").
  int smoothing = 10;
  /// The base level of a cycle iterates until its residual fell by this factor: a cheaper
  /// base solve needs more cycles and costs more (docs/DESIGN_NOTES.md, "Multigrid
  /// cycles") ...
  double base_reduction = 0.05;
  /// ... or this many iterations.
  int base_iterations = 200;
};

/// The progressive mesh's levels (progressive_mesh.h).
struct HierarchyTuning {
  /// Smoothing sweeps of hierarchy_positions (the copy the decimation measures on).
  int smoothing = 10;
  /// Free vertices a coarse level keeps at least, per G1 boundary vertex (boundary locked).
  double min_free_per_boundary = 0.5;
  /// Vertices a border loop of G1 boundary vertices keeps at least (boundary coarsened).
  int min_boundary_loop = 12;
  /// Free vertices a level keeps at least (boundary coarsened): a coarser one is not built.
  int min_level_free = 16;
};

/// The linear initial mesh Δ²f = 0 (bilaplacian.h).
struct BilaplacianTuning {
  /// Conjugate-gradient iterations at most before sparse LU takes over (the preconditioned
  /// matrix is the identity plus a term of rank at most the boundary vertices next to free
  /// ones, so CG needs about that many).
  int cg_iterations = 300;
  /// Relative residual of an initial mesh that the paper's iteration refines: its errors
  /// lie far below the iteration's moves, and that iteration is sensitive to its start
  /// (docs/DESIGN_NOTES.md) ...
  double initial_mesh_residual = 1e-8;
  /// ... of the base level that Newton's method refines (the same steps and results with
  /// fewer iterations) ...
  double newton_initial_mesh_residual = 1e-5;
  /// ... and where the linear solution is the result (OuterFairness::Bilaplacian): that of
  /// a direct solve.
  double exact_residual = 1e-12;
};

/// fair()'s schedule: levels, budgets and the time limit (fairing.h).
struct ScheduleTuning {
  /// The automatic time limit (FairingOptions::time_limit < 0) stops the paper's iteration
  /// once its residual has not halved for this many seconds ...
  double time_limit_base = 5.0;
  /// ... plus this many seconds per free vertex ...
  double time_limit_per_free_vertex = 2e-4;
  /// ... and any solve after this many times that span (a hard cap).
  double time_limit_hard_factor = 5.0;
  /// Iteration::Auto, where it runs the paper's iteration: Newton's method is tried from the
  /// paper's iterate after this many iterations of the finest level and after each doubling
  /// (docs/REAL_MESHES.md, "Newton from the paper's iterate") ...
  int newton_attempt_first = 100;
  /// ... each attempt at most this many Newton steps (or NewtonTuning::patience steps
  /// without halving its residual).
  int newton_attempt_steps = 60;
  /// fill_holes' fairs run at most this many iterations (FairingOptions::max_iterations,
  /// where that is lower, else this): a fill not converged by then gives way to the next
  /// fill of its hole (docs/DESIGN_NOTES.md, "Filling holes").
  int fill_max_iterations = 2000;
  /// The Newton hierarchy keeps at least this many free vertices on its base level (one
  /// level below four times this; docs/DESIGN_NOTES.md, "Coarse levels").
  int newton_min_base_free = 400;
  /// A region solved as one level with at least this many free vertices where Newton's
  /// method fails on that level tries two levels before the paper's iteration
  /// (docs/DESIGN_NOTES.md, "Coarse levels of large irregular caps").
  int newton_retry_min_free = 1400;
  /// With uniform inner fairness, the hierarchy attempt whose coarse levels take the
  /// membrane's weights goes before the one with the smoothed copy's where at least this
  /// share of the free vertices has a valence other than 6 (an irregular connectivity sets
  /// its own uniform distribution, which the membrane reproduces and the smoothed copy does
  /// not; docs/DESIGN_NOTES.md, "Flattened caps"). 0: always first; above 1: never.
  double membrane_first_irregularity = 0.55;
  /// Steps of a coarse level of the Newton hierarchy at most: it only starts the next
  /// level.
  int coarse_newton_steps = 30;
  /// Tolerance of the coarse levels (both hierarchies) relative to FairingOptions::tolerance:
  /// they only start the next level, whose cycles correct the smooth error anyway
  /// (docs/DESIGN_NOTES.md, "Coarse levels").
  double coarse_tolerance = 10.0;
  /// Iterations of a coarse level of the paper's hierarchy at most: decimated coarse levels
  /// can end in a limit cycle far above their tolerance (docs/DESIGN_NOTES.md, "Coarse
  /// levels").
  int coarse_iterations = 500;
};

/// All tuning of fair() (FairingOptions::tuning).
struct SolverTuning {
  PaperIterationTuning paper;
  NewtonTuning newton;
  TangentialTuning tangential;
  MultigridTuning multigrid;
  HierarchyTuning hierarchy;
  BilaplacianTuning bilaplacian;
  ScheduleTuning schedule;
};

/// Calls f(name, field, lo, hi, lo_open, hi_open) for every field of `t` (a SolverTuning,
/// const or not): its dotted name ("newton.patience"), a reference to it, its valid range
/// [lo, hi], open at an end where lo_open / hi_open (hi = kUnbounded: none), and the name of
/// the field whose value lo or hi is (bound; nullptr for a constant range). The one table of
/// the fields' names and ranges: validate_tuning and the Python bindings read it.
constexpr double kUnbounded = 1e300;
template <class Tuning, class Visit>
void for_each_tuning_field(Tuning& t, Visit&& visit) {
  constexpr double inf = kUnbounded;
  const auto f = [&visit](const char* name, auto& field, double lo, double hi, bool lo_open,
                          bool hi_open, const char* bound = nullptr) {
    visit(name, field, lo, hi, lo_open, hi_open, bound);
  };
  f("paper.coupling_refresh", t.paper.coupling_refresh, 1, inf, false, false);
  f("paper.tangential_iterations", t.paper.tangential_iterations, 1, inf, false, false);
  f("newton.patience", t.newton.patience, 1, inf, false, false);
  f("newton.coarse_patience", t.newton.coarse_patience, 1, inf, false, false);
  f("newton.coarse_merit", t.newton.coarse_merit, 0, inf, false, false);
  f("newton.far_steps", t.newton.far_steps, 1, inf, false, false);
  f("newton.far_merit", t.newton.far_merit, 0, inf, true, false);
  f("newton.prefactorize_merit", t.newton.prefactorize_merit, 0, inf, false, false);
  f("newton.max_step", t.newton.max_step, 0, inf, true, false);
  f("newton.fill_max_step", t.newton.fill_max_step, 0, inf, true, false);
  f("newton.relaxations", t.newton.relaxations, 1, inf, false, false);
  f("newton.projection_move", t.newton.projection_move, 0, inf, false, false);
  f("newton.polishes", t.newton.polishes, 0, inf, false, false);
  f("newton.polished_move", t.newton.polished_move, 0, inf, true, false);
  f("newton.polish_contraction", t.newton.polish_contraction, 0, inf, false, false);
  f("newton.warm_polish_residual", t.newton.warm_polish_residual, 1, inf, false, false);
  f("newton.product_step", t.newton.product_step, 0, 0.01, true, false);
  f("newton.merit_growth", t.newton.merit_growth, 1, inf, false, false);
  f("newton.shift_start", t.newton.shift_start, 0, inf, true, false);
  f("newton.shift_increase", t.newton.shift_increase, 1, inf, true, false);
  f("newton.shift_max", t.newton.shift_max, t.newton.shift_start, inf, false, false,
    "newton.shift_start");
  f("newton.shift_negligible", t.newton.shift_negligible, 0, 1, false, true);
  f("newton.krylov_iterations", t.newton.krylov_iterations, 1, inf, false, false);
  f("newton.krylov_tolerance", t.newton.krylov_tolerance, 0, 1, true, true);
  f("newton.krylov_reach", t.newton.krylov_reach, 0, inf, false, false);
  f("newton.krylov_tolerance_min", t.newton.krylov_tolerance_min, 0, t.newton.krylov_tolerance,
    true, false, "newton.krylov_tolerance");
  f("newton.refactorization_products", t.newton.refactorization_products, 0, inf, false, false);
  f("newton.shift_refactorization", t.newton.shift_refactorization, 1, inf, true, false);
  f("tangential.max_stretch", t.tangential.max_stretch, 0, 1, true, true);
  f("tangential.max_turn", t.tangential.max_turn, 0, inf, true, false);
  f("tangential.lagged_tolerance", t.tangential.lagged_tolerance, 0, 1, true, true);
  f("tangential.lagged_iterations", t.tangential.lagged_iterations, 1, inf, false, false);
  f("tangential.warm_lagged_tolerance", t.tangential.warm_lagged_tolerance, 0, 1, true, true);
  f("tangential.two_grid_sweeps", t.tangential.two_grid_sweeps, 1, inf, false, false);
  f("tangential.two_grid_blocks", t.tangential.two_grid_blocks, 1, inf, false, false);
  f("tangential.two_grid_iterations", t.tangential.two_grid_iterations, 1, inf, false, false);
  f("tangential.two_grid_tolerance", t.tangential.two_grid_tolerance, 0, 1, true, true);
  f("multigrid.prolongation_sweeps", t.multigrid.prolongation_sweeps, 0, inf, false, false);
  f("multigrid.min_correction", t.multigrid.min_correction, 0, 1, true, false);
  f("multigrid.max_skip", t.multigrid.max_skip, 0, 30, false, false);
  f("multigrid.smoothing", t.multigrid.smoothing, 1, inf, false, false);
  f("multigrid.base_reduction", t.multigrid.base_reduction, 0, 1, true, true);
  f("multigrid.base_iterations", t.multigrid.base_iterations, 1, inf, false, false);
  f("hierarchy.smoothing", t.hierarchy.smoothing, 0, inf, false, false);
  f("hierarchy.min_free_per_boundary", t.hierarchy.min_free_per_boundary, 0, inf, true, false);
  f("hierarchy.min_boundary_loop", t.hierarchy.min_boundary_loop, 3, inf, false, false);
  f("hierarchy.min_level_free", t.hierarchy.min_level_free, 1, inf, false, false);
  f("bilaplacian.cg_iterations", t.bilaplacian.cg_iterations, 1, inf, false, false);
  f("bilaplacian.initial_mesh_residual", t.bilaplacian.initial_mesh_residual, 0, 1, true, true);
  f("bilaplacian.newton_initial_mesh_residual", t.bilaplacian.newton_initial_mesh_residual, 0, 1,
    true, true);
  f("bilaplacian.exact_residual", t.bilaplacian.exact_residual, 0, 1, true, true);
  f("schedule.time_limit_base", t.schedule.time_limit_base, 0, inf, false, false);
  f("schedule.time_limit_per_free_vertex", t.schedule.time_limit_per_free_vertex, 0, inf, false,
    false);
  f("schedule.time_limit_hard_factor", t.schedule.time_limit_hard_factor, 1, inf, false, false);
  f("schedule.newton_attempt_first", t.schedule.newton_attempt_first, 1, inf, false, false);
  f("schedule.newton_attempt_steps", t.schedule.newton_attempt_steps, 1, inf, false, false);
  f("schedule.fill_max_iterations", t.schedule.fill_max_iterations, 1, inf, false, false);
  f("schedule.newton_min_base_free", t.schedule.newton_min_base_free, 1, inf, false, false);
  f("schedule.newton_retry_min_free", t.schedule.newton_retry_min_free, 1, inf, false, false);
  f("schedule.membrane_first_irregularity", t.schedule.membrane_first_irregularity, 0, inf, false,
    false);
  f("schedule.coarse_newton_steps", t.schedule.coarse_newton_steps, 1, inf, false, false);
  f("schedule.coarse_tolerance", t.schedule.coarse_tolerance, 1, inf, false, false);
  f("schedule.coarse_iterations", t.schedule.coarse_iterations, 1, inf, false, false);
}

/// Checks every field of `tuning` against its range (for_each_tuning_field).
/// \throw InvalidInputError naming the field and its range ("fair: tuning.newton.patience
///        must be in [1, inf), got 0").
void validate_tuning(const SolverTuning& tuning);

}  // namespace geofair
