// Section 7.4's nested iteration on a progressive mesh, by Newton's method or the paper's
// iteration: one level loop (solve_levels) and what each iteration does on a level.
#include "nested_iteration.h"

#include "bilaplacian.h"
#include "common.h"
#include "construction.h"
#include "multigrid.h"
#include "progressive_mesh.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <future>
#include <limits>
#include <memory>

namespace geofair {

bool stop_requested(const FairingOptions& options) {
  return options.stop_requested && options.stop_requested();
}

SolveRun stopped_run(const Positions& X0, Iteration iteration) {
  SolveRun run;
  run.result.iteration = iteration;
  run.X = X0;
  run.cancelled = run.unchanged = true;
  return run;
}

double finite_residual(const FairingRegion& level, const InnerFairnessWeights& lambda,
                       const FairingOptions& options, double L, const Positions& X) {
  const double residual = Construction(level, lambda, options, L).evaluate(X);
  return std::isfinite(residual) ? residual : std::numeric_limits<double>::max();
}

namespace {

std::string level_phase(int l, const char* what) {
  return "level " + std::to_string(l) + " " + what;
}

// The progressive mesh an attempt solves on, coarsest first, measured on Xs (see
// solve_levels); one level (the region) if levels is 1 or the mesh cannot be decimated.
ProgressiveMesh build_hierarchy(const FairingRegion& region, const Positions& Xs, int levels,
                                const Decimation& rules, const HierarchyTuning& tuning) {
  ProgressiveMesh hierarchy;
  if (levels > 1) hierarchy = build_progressive_mesh(region, Xs, levels, rules, tuning);
  if (hierarchy.triangles.size() < 2) {
    hierarchy.triangles.assign(1, region.triangles);
    hierarchy.splits.assign(1, VertexSplits{});
  }
  return hierarchy;
}

// The inner fairness weights of a coarse level, whose vertex distribution only starts the
// next level (only the finest level's weights decide the result):
// - the paper's iteration: the conformal weights of the smoothed copy Xs, whatever the
//   inner fairness (uniform weights pull free vertices against a boundary that is denser
//   than the coarse interior; docs/DESIGN_NOTES.md);
// - Newton's method, conformal inner fairness: those of the original mesh X0 at the level's
//   connectivity (the collapses keep the vertices, so that is the original mesh replayed);
// - Newton's method, uniform: the intrinsic Delaunay cotangent weights of the reference
//   geometry Xr (CoarseReference), where the finest level's uniform weights are about at
//   equilibrium; the level's own uniform weights where Xr is empty (CoarseReference::Own).
//   On a regular mesh a decimated level's own uniform weights place its vertices unlike
//   the finest level's, and its own cotangent weights are negative at obtuse triangles;
//   either makes consecutive levels' distributions differ by many edge lengths
//   (docs/REAL_MESHES.md, "Regular caps").
InnerFairnessWeights coarse_level_weights(const FairingRegion& level, Iteration iteration,
                                          const Positions& X0, const Positions& Xs,
                                          const Positions& Xr, InnerFairness inner) {
  if (iteration == Iteration::Paper)
    return ring_inner_fairness_weights(level.rings, gather(Xs, level.global),
                                       InnerFairness::Conformal);
  if (inner == InnerFairness::Uniform && Xr.rows() == 0)  // CoarseReference::Own
    return inner_fairness_weights(level, gather(X0, level.global), InnerFairness::Uniform);
  if (inner == InnerFairness::Uniform)
    return inner_fairness_weights(level, gather(Xr, level.global),
                                  InnerFairness::ConformalIntrinsic);
  return inner_fairness_weights(level, gather(X0, level.global), inner);
}

// The levels solved so far, in region-local ids: positions (the original where no level
// has moved a vertex yet), and the mean curvatures and unit normals of the last level.
struct LevelSolution {
  Positions X;
  Eigen::VectorXd H;
  Positions N;

  explicit LevelSolution(const Positions& X0)
      : X(X0), H(Eigen::VectorXd::Zero(X0.rows())), N(Positions::Zero(X0.rows(), 3)) {}

  // Keeps the solution Y (#level×3) of `level` and its construction's H and normals.
  void store(const FairingRegion& level, const Positions& Y, const Construction& construction) {
    for (int i = 0; i < level.n; ++i) {
      X.row(level.global[i]) = Y.row(i);
      H(level.global[i]) = construction.mean_curvatures()(i);
      N.row(level.global[i]) = construction.normals().row(i);
    }
  }

  // The positions of a finer `level` (#level×3): the stored solution, with the vertices the
  // level adds prolongated (multigrid.h, prolongate) by its splits (`region_splits`, in
  // region-local ids). Out: the splits in level-local ids, their weights (the conformal
  // weights of the smoothed copy Xs on every level: splits and their transposes interpolate
  // smooth corrections; those of a noisy original are not smooth, and the finest level's
  // corrections got undone), and the level-local id of every region vertex (-1 where not
  // in the level). `sweeps`: prolongate's.
  Positions prolongated(const FairingRegion& level, const VertexSplits& region_splits,
                        const Positions& Xs, const InnerFairnessWeights& lambda,
                        VertexSplits& splits, std::vector<double>& weights,
                        std::vector<int>& local, int sweeps) const {
    local.assign(X.rows(), -1);
    for (int i = 0; i < level.n; ++i) local[level.global[i]] = i;
    splits = region_splits;
    for (int& v : splits.vertex) v = local[v];
    for (int& v : splits.ring) v = local[v];
    weights = split_weights(splits, InnerFairness::Conformal, gather(Xs, level.global));
    Positions Y = gather(X, level.global);
    Eigen::VectorXd H_level(level.n);
    for (int i = 0; i < level.n; ++i) H_level(i) = H(level.global[i]);
    Positions N_level = gather(N, level.global);
    prolongate(level, splits, weights, lambda, Y, H_level, N_level, sweeps);
    return Y;
  }
};

// Newton's method from the iterates of the paper's iteration on a level (the finest, or the
// base level of the Newton hierarchy).
class NewtonAttempts {
 public:
  // `patience`: steps without a halving of the residual that end an attempt.
  NewtonAttempts(const FairingRegion& level, const InnerFairnessWeights& lambda,
                 const FairingOptions& options, double L, int patience)
      : level_(level), lambda_(lambda), options_(options), L_(L), patience_(patience) {}

  // Runs Newton's method from a copy of Y, the iterate after `paper_iterations` iterations of
  // the level. If it converges, Y becomes its result and `report` says so; else Y and
  // `report` are left as they are (report.cancelled set if the progress callback stopped
  // the attempt).
  void try_from(Positions& Y, double tolerance, int paper_iterations, int iteration_offset,
                IterationReport& report) {
    if (!construction_) construction_ = std::make_unique<Construction>(level_, lambda_, options_, L_);
    Positions Z = Y;
    IterationReport attempt;
    try {
      NewtonRun run;
      run.max_iterations = options_.tuning.schedule.newton_attempt_steps;
      run.tolerance = tolerance;
      run.iteration_offset = iteration_offset;
      run.patience = patience_;
      run.polish_at_convergence = true;
      attempt = construction_->run_newton(Z, run);
    } catch (const SolverError&) {
      return;  // diverged or singular from this iterate: the paper's iteration goes on
    }
    steps_ += attempt.iterations;
    if (attempt.converged) {
      Y = std::move(Z);
      report.converged = true;
      report.residual = attempt.residual;
      converged_after_ = paper_iterations;
    }
    report.cancelled = report.cancelled || attempt.cancelled;
  }

  int steps() const { return steps_; }
  // Paper iterations before the first attempt (each later one after a doubling).
  int first_after() const { return options_.tuning.schedule.newton_attempt_first; }
  // The iterations of the level's paper iteration after which an attempt converged, or -1.
  int converged_after() const { return converged_after_; }

 private:
  const FairingRegion& level_;
  const InnerFairnessWeights& lambda_;
  const FairingOptions& options_;
  double L_;
  int patience_;
  std::unique_ptr<Construction> construction_;
  int steps_ = 0, converged_after_ = -1;
};

// The paper's iteration on the finest level (`paper(budget, iteration_offset)` runs up to
// `budget` iterations on Y and reports), in slices ending after attempts.first_after(), 2×,
// 4×, ... iterations, with a Newton attempt from Y after each.
template <class Paper>
IterationReport paper_with_newton_attempts(Paper&& paper, Positions& Y, int budget,
                                           double tolerance, int iteration_offset,
                                           NewtonAttempts& attempts) {
  IterationReport report;
  int done = 0;
  for (int next = attempts.first_after();; next = next > budget / 2 ? budget : 2 * next) {
    const IterationReport slice = paper(std::min(budget, next) - done, iteration_offset + done);
    done += slice.iterations;
    report.residual = slice.residual;
    report.converged = slice.converged;
    report.cancelled = slice.cancelled;
    if (report.converged || report.cancelled || done >= budget) break;
    attempts.try_from(Y, tolerance, done, iteration_offset + done, report);
    if (report.converged || report.cancelled) break;
  }
  report.iterations = done;
  return report;
}

// The base level of Newton's hierarchy, when Newton's method fails from its linear initial
// mesh (a base level decimated a thousandfold is rough): one slice of the paper's iteration
// from that mesh and one Newton attempt from its iterate; where that fails too, the next
// attempt of the hierarchy is the better use of the time. `failed`: the report of the
// failed Newton run, whose phases the result keeps.
IterationReport base_level_fallback(const FairingRegion& level, Construction& construction,
                                    Positions& Y, const Positions& initial,
                                    const FairingOptions& options, double L, double tolerance,
                                    const IterationReport& failed, int newton_iterations,
                                    double& paper_seconds) {
  Laps laps;
  Y = initial;
  NewtonAttempts attempts(level, construction.lambda(), options, L,
                          options.tuning.newton.coarse_patience);
  IterationReport fallback = construction.run(
      Y, std::min(options.max_iterations, attempts.first_after()), tolerance, newton_iterations);
  if (!fallback.converged && !fallback.cancelled)
    attempts.try_from(Y, tolerance, fallback.iterations, newton_iterations, fallback);
  construction.evaluate(Y);  // its normals and H (an attempt's construction solved it)
  paper_seconds = laps.lap();
  fallback.iterations = attempts.steps();
  fallback.relax_seconds = failed.relax_seconds;
  fallback.step_seconds = failed.step_seconds;
  fallback.polish_seconds = failed.polish_seconds;
  return fallback;
}

// Solves the base level (coarser than the finest) of the Newton hierarchy from its linear
// initial mesh Y, which becomes the level's solution: Newton's method, and where that fails,
// base_level_fallback. `presolve_on`: null, or the smoothed copy Xs where the membrane's
// attempt decimated on it; then the level is solved with Xs's weights first, and from there
// with its own (Newton's method does not converge from the linear initial mesh with them,
// where the membrane is far from Xs). Returns the report of the last solve, its
// `iterations` the Newton steps not yet added to `newton_iterations`; `paper_seconds`: the
// time of the paper's iteration.
IterationReport solve_base_level(const FairingRegion& level, Construction& construction,
                                 Positions& Y, const Positions& X0, const Positions* presolve_on,
                                 const FairingOptions& options, double L, int budget,
                                 double tolerance, int& newton_iterations,
                                 double& paper_seconds) {
  const Positions initial = Y;
  NewtonRun run;
  run.max_iterations = budget;
  run.tolerance = tolerance;
  run.patience = options.tuning.newton.coarse_patience;
  run.from_initial_mesh = true;
  bool presolved = false;
  IterationReport first;  // the smoothed copy's solve
  if (presolve_on && presolve_on->rows() > 0) {
    Construction smoothed(level,
                          coarse_level_weights(level, Iteration::Newton, X0, *presolve_on,
                                               *presolve_on, options.inner_fairness),
                          options, L);
    Positions Z = Y;
    run.iteration_offset = newton_iterations;
    first = smoothed.run_newton(Z, run);
    newton_iterations += first.iterations;
    presolved = first.converged;
    if (presolved) Y = std::move(Z);  // else from the linear initial mesh as without it
  }
  run.iteration_offset = newton_iterations;
  run.from_initial_mesh = !presolved;
  IterationReport report = construction.run_newton(Y, run);
  report.relax_seconds += first.relax_seconds;
  report.step_seconds += first.step_seconds;
  report.polish_seconds += first.polish_seconds;
  if (report.converged || report.cancelled) return report;
  newton_iterations += report.iterations;
  return base_level_fallback(level, construction, Y, initial, options, L, tolerance, report,
                             newton_iterations, paper_seconds);
}

// What an iteration does on a level of solve_levels' loop.
class LevelIteration {
 public:
  virtual ~LevelIteration() = default;
  // The residual the base level's linear initial mesh is solved to.
  virtual double initial_mesh_residual() const = 0;
  // The construction of level l (levels[l], its splits and from_coarser set): its inner
  // fairness weights are `coarse_lambda` on a coarse level, Problem::lambda_finest on the
  // finest.
  virtual Construction& set_up(int l, bool finest, InnerFairnessWeights coarse_lambda) = 0;
  // Solves level l from Y, with the construction of set_up.
  virtual IterationReport solve(int l, bool finest, Positions& Y, Phases& phases) = 0;
  // False where the level's outcome ends the run unconverged (with `result` set).
  virtual bool accept(int /*l*/, bool /*finest*/, const IterationReport& /*report*/,
                      FairingResult& /*result*/) {
    return true;
  }
  // Counts the level's iterations into `result` once it is stored.
  virtual void count(int l, const IterationReport& report, FairingResult& result) = 0;
  // The run's last figures once the loop ended.
  virtual void finish(FairingResult& /*result*/) {}
};

// Newton's method on a level (Construction::run_newton), the coarse levels with coarse
// spaces for their relaxations.
class NewtonLevels final : public LevelIteration {
 public:
  // `presolve_on`: solve_base_level's.
  NewtonLevels(const Problem& p, std::deque<MultigridLevel>& levels, const Positions* presolve_on,
               int& newton_iterations)
      : p_(p), levels_(levels), presolve_on_(presolve_on), newton_(newton_iterations) {
    // The finest level's construction does not depend on the hierarchy: it is set up, with
    // the symbolic analysis of its Newton preconditioner, on another thread while this one
    // decimates and solves the coarser levels, which take longer (docs/DESIGN_NOTES.md,
    // "Threads").
    finest_ = std::async(std::launch::async, [&p] {
      auto construction =
          std::make_unique<Construction>(p.finest_level, p.lambda_finest, p.options, p.L);
      construction->prepare_newton();
      return construction;
    });
  }

  double initial_mesh_residual() const override {
    return p_.options.tuning.bilaplacian.newton_initial_mesh_residual;
  }

  Construction& set_up(int l, bool finest, InnerFairnessWeights coarse_lambda) override {
    MultigridLevel& level = levels_[l];
    level.construction = finest ? finest_.get()
                                : std::make_unique<Construction>(
                                      level.region, std::move(coarse_lambda), p_.options, p_.L);
    if (l > 0) {
      CoarseSpace coarse =
          coarse_space(level.region, level.splits, levels_[l - 1].region, coarser_lambda_);
      CoarseSpace next = finest ? CoarseSpace{} : coarse;  // the next level's coarser space
      level.construction->set_coarse_space(std::move(coarse), std::move(coarser_space_));
      coarser_space_ = std::move(next);
    }
    return *level.construction;
  }

  IterationReport solve(int l, bool finest, Positions& Y, Phases& phases) override {
    const FairingOptions& options = p_.options;
    const SolverTuning& tuning = options.tuning;
    Construction& construction = *levels_[l].construction;
    const double tolerance = options.tolerance * (finest ? 1.0 : tuning.schedule.coarse_tolerance);
    const int budget =
        finest ? options.max_iterations
               : std::min(options.max_iterations, tuning.schedule.coarse_newton_steps);
    IterationReport report;
    double paper_seconds = 0.0;
    if (l == 0 && !finest) {
      report = solve_base_level(levels_[l].region, construction, Y, p_.X0, presolve_on_, options,
                                p_.L, budget, tolerance, newton_, paper_seconds);
    } else {
      NewtonRun newton_run;
      newton_run.max_iterations = budget;
      newton_run.tolerance = tolerance;
      newton_run.iteration_offset = newton_;
      newton_run.patience = finest ? tuning.newton.patience : tuning.newton.coarse_patience;
      newton_run.polish_at_convergence = finest;
      newton_run.factorize_ahead_merit = finest ? std::numeric_limits<double>::infinity()
                                                : tuning.newton.prefactorize_merit;
      newton_run.prolongated = l > 0;
      newton_run.from_initial_mesh = l == 0;
      if (!finest) newton_run.crawl_merit = tuning.newton.coarse_merit;
      report = construction.run_newton(Y, newton_run);
    }
    phases.emplace_back(level_phase(l, "inner fairness"), report.relax_seconds);
    phases.emplace_back(level_phase(l, "Newton steps"), report.step_seconds);
    phases.emplace_back(level_phase(l, "polishes"), report.polish_seconds);
    if (paper_seconds > 0.0) phases.emplace_back(level_phase(l, "paper iterations"), paper_seconds);
    newton_ += report.iterations;
    return report;
  }

  // A coarse level that did not converge would start the next one from a worse mesh than
  // its own linear initial mesh: the hierarchy is abandoned. One that stopped with a small
  // merit (the RMS of the scaled defects) is converged but for a few vertices, which the
  // next level's steps reach.
  bool accept(int l, bool finest, const IterationReport& report, FairingResult& result) override {
    const Construction& construction = *levels_[l].construction;
    if (!finest && !report.converged && !report.cancelled &&
        construction.merit() > p_.options.tuning.newton.coarse_merit) {
      result.residual = report.residual;
      result.converged = false;
      return false;
    }
    if (!finest) coarser_lambda_ = construction.lambda();
    return true;
  }

  // Also frees the level's construction, splits and weights: the next level needs only
  // its region, weights and coarse space.
  void count(int l, const IterationReport& report, FairingResult& result) override {
    MultigridLevel& level = levels_[l];
    level.construction.reset();
    level.splits = VertexSplits();
    level.weights = std::vector<double>();
    result.iterations_per_level.push_back(report.iterations);
    result.iterations += report.iterations;
  }

 private:
  const Problem& p_;
  std::deque<MultigridLevel>& levels_;
  const Positions* presolve_on_;
  int& newton_;
  std::future<std::unique_ptr<Construction>> finest_;
  InnerFairnessWeights coarser_lambda_;  // the inner fairness weights of level l - 1
  CoarseSpace coarser_space_;  // the coarse space of level l - 1 (from level l - 2), if any
};

// The paper's iteration on a level (Construction::run), the finer levels by multigrid
// cycles on the coarser ones; with Iteration::Auto Newton attempts from the finest
// level's iterate.
class PaperLevels final : public LevelIteration {
 public:
  PaperLevels(const Problem& p, std::deque<MultigridLevel>& levels)
      : p_(p),
        levels_(levels),
        multigrid_(levels, p.options.tuning.multigrid),
        attempts_(p.finest_level, p.lambda_finest, p.options, p.L,
                  p.options.tuning.newton.patience),
        coarse_options_(p.options) {
    // Coarse levels estimate normals with Max's weights where the fitted normal is asked
    // for: the fit, consistent on the finest mesh, is ill-conditioned on the decimated rings
    // of coarse levels (short and long edges, low valence), and the cycles need several
    // times the iterations there (docs/DESIGN_NOTES.md, "Coarse levels"). The coarse levels
    // only supply corrections; the finest level's equations decide the result.
    if (p.options.normal_weighting == NormalWeighting::Quadric)
      coarse_options_.normal_weighting = NormalWeighting::Max;
  }

  double initial_mesh_residual() const override {
    const BilaplacianTuning& tuning = p_.options.tuning.bilaplacian;
    return p_.options.outer_fairness == OuterFairness::Bilaplacian ? tuning.exact_residual
                                                                   : tuning.initial_mesh_residual;
  }

  Construction& set_up(int l, bool finest, InnerFairnessWeights coarse_lambda) override {
    MultigridLevel& level = levels_[l];
    if (finest) coarse_lambda = p_.lambda_finest;  // the construction keeps its own copy
    level.construction = std::make_unique<Construction>(
        level.region, std::move(coarse_lambda), finest ? p_.options : coarse_options_, p_.L);
    return *level.construction;
  }

  IterationReport solve(int l, bool finest, Positions& Y, Phases& phases) override {
    Laps laps;
    const FairingOptions& options = p_.options;
    Construction& construction = *levels_[l].construction;
    IterationReport report;
    if (options.outer_fairness == OuterFairness::Bilaplacian) {
      // The linear solution is exact; the residual says how far it is from Δ_B H = 0.
      report.residual = construction.evaluate(Y);
      report.converged = true;
    } else {
      // Coarse levels only start the next one: a looser tolerance.
      const ScheduleTuning& schedule = options.tuning.schedule;
      const double tolerance = options.tolerance * (finest ? 1.0 : schedule.coarse_tolerance);
      const int budget = finest ? options.max_iterations
                                : std::min(options.max_iterations, schedule.coarse_iterations);
      auto paper = [&](int slice, int offset) {
        return l == 0 ? construction.run(Y, slice, tolerance, offset)
                      : multigrid_.solve(l, Y, tolerance, slice, offset);
      };
      report = finest && options.iteration == Iteration::Auto
                   ? paper_with_newton_attempts(paper, Y, budget, tolerance, iterations_,
                                                attempts_)
                   : paper(budget, iterations_);
    }
    phases.emplace_back(level_phase(l, "iterations"), laps.lap());
    return report;
  }

  // The iterations of every level so far, with those the finer levels' cycles ran on it.
  void count(int /*l*/, const IterationReport& /*report*/, FairingResult& result) override {
    iterations_ = 0;
    for (const MultigridLevel& done : levels_) iterations_ += int(done.construction->iterations());
    result.iterations = iterations_;
  }

  void finish(FairingResult& result) override {
    for (const MultigridLevel& done : levels_)
      if (done.construction)
        result.iterations_per_level.push_back(int(done.construction->iterations()));
    result.newton_iterations += attempts_.steps();
    if (attempts_.converged_after() >= 0)
      result.message = "Newton's method converged from the paper's iterate after " +
                       std::to_string(attempts_.converged_after()) + " iterations";
  }

 private:
  const Problem& p_;
  std::deque<MultigridLevel>& levels_;
  Multigrid multigrid_;
  NewtonAttempts attempts_;
  FairingOptions coarse_options_;
  int iterations_ = 0;  // of all levels so far (FairingResult::iterations)
};

// The copies of the positions that an attempt's hierarchy is measured on (Xs, #region×3, empty
// for one level; progressive_mesh.h), whose conformal weights also interpolate the splits:
// - Attempt::decimate_on_membrane: the membrane Xm, where the attempt's uniform coarse
//   weights place the vertices (coarse_level_weights). Decimated on another copy, a coarse
//   triangle valid there folds on the membrane where an irregular connectivity moves
//   vertices by many edge lengths, and the base level's relaxations and Newton steps
//   wander (docs/DESIGN_NOTES.md, "The membrane attempt's hierarchy");
// - else a smoothed copy of the input (hierarchy_positions: on a noisy input the raw
//   positions fold coarse triangles, and the splits interpolate smooth corrections);
// and the reference of Newton's uniform coarse weights (Xr; coarse_level_weights).
struct HierarchyPositions {
  HierarchyPositions(const Attempt& attempt)
      : newton(attempt.iteration == Iteration::Newton),
        membrane(newton && attempt.reference == CoarseReference::Membrane),
        on_membrane(membrane && attempt.decimate_on_membrane && attempt.levels > 1),
        own_reference(!newton || attempt.reference == CoarseReference::Own) {}

  // The hierarchy of the attempt, decimated on Xs (made here with Xm where needed).
  ProgressiveMesh build(const Problem& p, const Attempt& attempt) {
    if (on_membrane)
      Xm = membrane_positions(p.region, p.lambda_finest, p.X0);
    else if (attempt.levels > 1)
      smoothed = hierarchy_positions(p.region, p.X0, &p.lambda_finest,
                                     p.options.tuning.hierarchy.smoothing);
    ProgressiveMesh hierarchy =
        build_hierarchy(p.region, Xs(), attempt.levels,
                        newton ? kNewtonDecimation : kPaperDecimation, p.options.tuning.hierarchy);
    coarse_levels = hierarchy.triangles.size() > 1;
    if (membrane && coarse_levels && !on_membrane)  // only once the mesh could be decimated
      Xm = membrane_positions(p.region, p.lambda_finest, p.X0);
    return hierarchy;
  }
  const Positions& Xs() const { return on_membrane ? Xm : smoothed; }
  // Empty: the coarse levels' own positions.
  const Positions& Xr() const {
    return own_reference ? none : membrane && coarse_levels ? Xm : Xs();
  }
  void release() { smoothed = Xm = Positions(); }

  const bool newton, membrane, on_membrane, own_reference;
  bool coarse_levels = false;
  Positions smoothed, Xm;
  const Positions none;
};

}  // namespace

SolveRun solve_levels(const Problem& p, const Attempt& attempt, int& newton_iterations,
                      Phases& phases) {
  std::deque<MultigridLevel> levels;  // kept in place: the constructions refer to the regions
  HierarchyPositions positions(attempt);
  const bool newton = positions.newton;
  std::unique_ptr<LevelIteration> iteration;
  if (newton)  // the membrane's attempt decimated on the smoothed copy presolves on it
    iteration = std::make_unique<NewtonLevels>(
        p, levels,
        positions.membrane && !attempt.decimate_on_membrane ? &positions.smoothed : nullptr,
        newton_iterations);
  Laps laps;
  ProgressiveMesh hierarchy = positions.build(p, attempt);
  const Positions& Xs = positions.Xs();
  const Positions& Xr = positions.Xr();
  if (!newton) iteration = std::make_unique<PaperLevels>(p, levels);
  SolveRun run;
  FairingResult& result = run.result;
  result.iteration = attempt.iteration;
  result.newton_iterations = newton_iterations;  // before this attempt
  phases.emplace_back("hierarchy", laps.lap());
  LevelSolution solution(p.X0);
  const int n_levels = int(hierarchy.triangles.size());
  for (int l = 0; l < n_levels; ++l) {
    if (stop_requested(p.options)) {  // before the level's initial mesh: the input unchanged
      run.cancelled = run.unchanged = true;
      result.converged = false;
      solution.X = p.X0;
      break;
    }
    const bool finest = l + 1 == n_levels;
    MultigridLevel& level = levels.emplace_back();
    level.region = finest ? p.finest_level : level_region(p.region, hierarchy.triangles[l]);
    const FairingRegion& lr = level.region;
    InnerFairnessWeights coarse_lambda;
    if (!finest)
      coarse_lambda =
          coarse_level_weights(lr, attempt.iteration, p.X0, Xs, Xr, p.options.inner_fairness);
    const InnerFairnessWeights& lambda = finest ? p.lambda_finest : coarse_lambda;
    Positions Y;
    if (l == 0) {
      Y = bilaplacian_initial_mesh(lr, lambda, gather(p.X0, lr.global),
                                   iteration->initial_mesh_residual(),
                                   p.options.tuning.bilaplacian.cg_iterations);
    } else {
      std::vector<int> local;
      Y = solution.prolongated(lr, hierarchy.splits[l], Xs, lambda, level.splits, level.weights,
                               local, p.options.tuning.multigrid.prolongation_sweeps);
      if (!newton) {  // the paper's multigrid cycles inject the coarser level through it
        const FairingRegion& coarser = levels[l - 1].region;
        level.from_coarser.resize(coarser.n);
        for (int c = 0; c < coarser.n; ++c) level.from_coarser[c] = local[coarser.global[c]];
      }
    }
    if (finest)  // memory of the finest
      hierarchy = ProgressiveMesh(), positions.release();
    phases.emplace_back(level_phase(l, "initial mesh"), laps.lap());
    Construction& construction = iteration->set_up(l, finest, std::move(coarse_lambda));
    phases.emplace_back(level_phase(l, "set-up"), laps.lap());
    const IterationReport report = iteration->solve(l, finest, Y, phases);
    laps.lap();
    if (!iteration->accept(l, finest, report, result)) break;
    solution.store(lr, Y, construction);
    iteration->count(l, report, result);  // the last use of `construction` (Newton frees it)
    result.vertices_per_level.push_back(lr.n);
    result.residual = report.residual;
    result.converged = finest && report.converged && !report.cancelled;
    if (report.cancelled) {
      // Cancelled on a coarse level: the input unchanged rather than a mix of levels.
      run.cancelled = true;
      if (!finest) solution.X = p.X0, run.unchanged = true;
      break;
    }
  }
  iteration->finish(result);
  run.X = std::move(solution.X);
  return run;
}

}  // namespace geofair
