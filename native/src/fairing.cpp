// The fairing driver: progressive-mesh multigrid around the construction of section 7
// (Schneider & Kobbelt 2001, Fig. 6).
#include "geofair/fairing.h"

#include "bilaplacian.h"
#include "common.h"
#include "construction.h"
#include "inner_fairness.h"
#include "multigrid.h"
#include "progressive_mesh.h"
#include "region.h"
#include "sparse_lu.h"

#include <algorithm>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <cmath>
#include <cstdio>
#include <chrono>
#include <cstring>
#include <deque>
#include <filesystem>
#include <future>
#include <limits>
#include <memory>
#include <numeric>
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
  if (o.levels < 0) throw InvalidInputError("fair: levels must be >= 0");
  if (std::isnan(o.time_limit)) throw InvalidInputError("fair: time_limit must not be NaN");
  validate_tuning(o.tuning);
}

#ifdef _OPENMP
// The threads of one solve: OpenMP's maximum (OMP_NUM_THREADS, else the cores) less the
// cores that other processes keep busy now (the runnable tasks of /proc/loadavg, not
// counting this process's own). On a busy machine the threads of a parallel loop wait for
// each other at every barrier, so a core taken by another process is left to it; libgomp's
// dynamic adjustment also counted this process's own earlier solves (docs/DESIGN_NOTES.md,
// "Threads of a solve").
int solve_threads() {
  static const int max_threads = omp_get_max_threads();  // before the first call sets it
  int runnable = 0, own = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%*f %*f %*f %d", &runnable) != 1) runnable = 0;
    std::fclose(f);
  }
  std::error_code error;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", error)) {
    if (FILE* f = std::fopen((task.path() / "stat").c_str(), "r")) {
      // pid (comm) state ...: the state follows the last ')'.
      char line[512];
      if (std::fgets(line, sizeof line, f))
        if (const char* close = std::strrchr(line, ')'); close && close[1] && close[2] == 'R')
          ++own;
      std::fclose(f);
    }
  }
  const int busy_elsewhere = std::max(0, runnable - std::max(own, 1));
  return std::clamp(omp_get_num_procs() - busy_elsewhere, 1, max_threads);
}
#endif

using Phases = std::vector<std::pair<std::string, double>>;  // FairingResult::phase_seconds

std::string level_phase(int l, const char* what) {
  return "level " + std::to_string(l) + " " + what;
}

Positions gather(const Positions& X, const std::vector<int>& ids) {
  Positions Y(Eigen::Index(ids.size()), 3);
  for (std::size_t i = 0; i < ids.size(); ++i) Y.row(Eigen::Index(i)) = X.row(ids[i]);
  return Y;
}

// The progressive mesh fair() solves on, coarsest first, measured on a smoothed copy Xs of
// the input (progressive_mesh.h, hierarchy_positions: on a noisy input the raw positions
// fold coarse triangles, and the splits interpolate smooth corrections); one level (the
// region, Xs empty) if levels is 1 or the mesh cannot be decimated.
ProgressiveMesh build_hierarchy(const FairingRegion& region, const Positions& X0,
                                const InnerFairnessWeights& lambda_finest, int levels,
                                const Decimation& rules, const HierarchyTuning& tuning,
                                Positions& Xs) {
  ProgressiveMesh hierarchy;
  if (levels > 1) {
    Xs = hierarchy_positions(region, X0, &lambda_finest, tuning.smoothing);
    hierarchy = build_progressive_mesh(region, Xs, levels, rules, tuning);
  }
  if (hierarchy.triangles.size() < 2) {
    hierarchy.triangles.assign(1, region.triangles);
    hierarchy.splits.assign(1, VertexSplits{});
  }
  return hierarchy;
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
  // corrections got undone), and the
  // level-local id of every region vertex (-1 where not in the level). `sweeps`: prolongate's.
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

// Levels of the Newton hierarchy: as many as keep newton_min_base_free free vertices on the
// base level (one level below twice that).
int newton_levels(const FairingRegion& region, const ScheduleTuning& schedule) {
  int levels = 1;
  for (double n = region.n_free / 4.0; n >= schedule.newton_min_base_free; n /= 4.0) ++levels;
  return levels;
}

// The inner fairness weights of a coarse level of the Newton hierarchy, whose vertex
// distribution only starts the next level. Conformal ones: those of the original mesh at
// the level's connectivity (the collapses keep the vertices, so that is the original mesh
// replayed alongside). Uniform: the intrinsic Delaunay cotangent weights of a reference
// geometry Xr (CoarseReference, below), where the finest level's uniform weights are about at
// equilibrium; the level's own uniform weights where Xr is empty (CoarseReference::Own). On
// a regular mesh a decimated level's own uniform weights place its vertices unlike the
// finest level's, and its own cotangent weights are negative at obtuse triangles; either
// makes consecutive levels' vertex distributions differ by many edge lengths
// (docs/REAL_MESHES.md, "Regular caps").
InnerFairnessWeights coarse_level_weights(const FairingRegion& level, const Positions& X0,
                                          const Positions& Xr, InnerFairness inner) {
  if (inner == InnerFairness::Uniform && Xr.rows() == 0)  // CoarseReference::Own
    return inner_fairness_weights(level, gather(X0, level.global), InnerFairness::Uniform);
  if (inner == InnerFairness::Uniform)
    return inner_fairness_weights(level, gather(Xr, level.global),
                                  InnerFairness::ConformalIntrinsic);
  return inner_fairness_weights(level, gather(X0, level.global), inner);
}

// The reference geometry of a uniform hierarchy's coarse weights (coarse_level_weights).
// Smoothed: the smoothed copy Xs of the input, whose vertex distribution is about uniform
// where the input's is (regular meshes, of any metric). Membrane: the membrane of the finest
// uniform weights (membrane_positions), the distribution an irregular connectivity asks for,
// which Xs does not know (random samples of a surface: docs/DESIGN_NOTES.md, "Flattened caps").
// Own: no reference; each coarse level takes its own uniform weights, whose distribution
// follows the finest one's where decimation keeps the connectivity about as irregular (the
// 1M-vertex irregular cap: docs/DESIGN_NOTES.md, "Coarse levels of large irregular caps").
enum class CoarseReference { Smoothed, Membrane, Own };

// The outcome of newton_multigrid or paper_multigrid: the result without its vertices (nor
// its phases), the region's positions.
struct SolveRun {
  FairingResult result;
  Positions X;
  bool cancelled = false;
  bool unchanged = false;  ///< X is the input: stopped before the finest level's solve
};

// True where options.stop_requested asks the solve to stop (fair's time limit).
bool stop_requested(const FairingOptions& options) {
  return options.stop_requested && options.stop_requested();
}

// A run stopped before it changed anything: the input, unconverged.
SolveRun stopped_run(const Positions& X0, Iteration iteration) {
  SolveRun run;
  run.result.iteration = iteration;
  run.X = X0;
  run.cancelled = run.unchanged = true;
  return run;
}

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

// Solves the base level (coarser than the finest) of the Newton hierarchy from its linear
// initial mesh Y, which becomes the level's solution: Newton's method, and where that fails
// from so far a start (a base level decimated a thousandfold is rough), the paper's iteration
// and a Newton attempt from its iterate, as fair() solves a single level. With the
// membrane's weights the level is solved with the smoothed copy's weights first, and from
// there with its own (Newton's method does not converge from the linear initial mesh with
// them, rough where the connectivity is irregular). Returns the report of the last solve,
// its `iterations` the Newton steps not yet added to `newton_iterations`; `paper_seconds`:
// the time of the paper's iteration.
IterationReport solve_base_level(const FairingRegion& level, Construction& construction,
                                 Positions& Y, const Positions& X0, const Positions& Xs,
                                 CoarseReference reference, const FairingOptions& options,
                                 double L, int budget, double tolerance, int& newton_iterations,
                                 double& paper_seconds) {
  const NewtonTuning& newton = options.tuning.newton;
  const Positions initial = Y;
  NewtonRun run;
  run.max_iterations = budget;
  run.tolerance = tolerance;
  run.patience = newton.coarse_patience;
  run.from_initial_mesh = true;
  bool presolved = false;
  IterationReport first;  // the smoothed copy's solve
  if (reference == CoarseReference::Membrane) {
    Construction smoothed(level, coarse_level_weights(level, X0, Xs, options.inner_fairness),
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
  // One slice of the paper's iteration and one Newton attempt from its iterate: where that
  // fails too, the next attempt of the hierarchy is the better use of the time.
  Laps laps;
  Y = initial;
  NewtonAttempts attempts(level, construction.lambda(), options, L, newton.coarse_patience);
  IterationReport fallback = construction.run(
      Y, std::min(options.max_iterations, attempts.first_after()), tolerance, newton_iterations);
  if (!fallback.converged && !fallback.cancelled)
    attempts.try_from(Y, tolerance, fallback.iterations, newton_iterations, fallback);
  construction.evaluate(Y);  // its normals and H (an attempt's construction solved it)
  paper_seconds = laps.lap();
  fallback.iterations = attempts.steps();
  fallback.relax_seconds = report.relax_seconds;
  fallback.step_seconds = report.step_seconds;
  fallback.polish_seconds = report.polish_seconds;
  return fallback;
}

// Newton's method level by level on a progressive mesh of the region (section 7.4's
// nested iteration with Newton steps as the solver of every level): the base level from
// the linear Δ²f = 0 initial mesh, each finer level from the prolongation of the coarser
// solution (multigrid.h, prolongate), each with the tangential relaxation first
// (Construction::run_newton). The finest level uses the requested inner fairness, the
// coarse levels coarse_level_weights. Coarse levels stop at a looser tolerance, after
// schedule.coarse_newton_steps or after newton.coarse_patience steps without progress; one that ends
// unconverged ends the run unconverged. `newton_iterations` accumulates the steps of all
// levels, `phases` the wall time of its phases. With levels = 1 it is the single-level
// Newton iteration from the linear initial mesh.
// \throw SolverError if a level diverges or its Newton system is singular.
SolveRun newton_multigrid(const FairingRegion& region, const FairingRegion& finest_level,
                           const Positions& X0, const InnerFairnessWeights& lambda_finest,
                           const FairingOptions& options, double L, int levels,
                           CoarseReference reference, int& newton_iterations, Phases& phases) {
  // The finest level's construction does not depend on the hierarchy: it is set up, with
  // the symbolic analysis of its Newton preconditioner, on another thread while this one
  // decimates and solves the coarser levels, which take longer (docs/DESIGN_NOTES.md,
  // "Threads of a solve").
  std::future<std::unique_ptr<Construction>> finest_construction =
      std::async(std::launch::async, [&finest_level, &lambda_finest, &options, L] {
        auto construction = std::make_unique<Construction>(finest_level, lambda_finest, options, L);
        construction->prepare_newton();
        return construction;
      });
  Laps laps;
  Positions Xs;
  ProgressiveMesh hierarchy = build_hierarchy(region, X0, lambda_finest, levels,
                                              kNewtonDecimation, options.tuning.hierarchy, Xs);
  // The coarse weights' reference geometry (coarse_level_weights; empty: their own).
  Positions Xr = reference == CoarseReference::Own ? Positions()
                 : reference == CoarseReference::Membrane && hierarchy.triangles.size() > 1
                     ? membrane_positions(region, lambda_finest, X0)
                     : Xs;
  SolveRun run;
  FairingResult& result = run.result;
  result.iteration = Iteration::Newton;
  phases.emplace_back("hierarchy", laps.lap());
  LevelSolution solution(X0);
  std::deque<FairingRegion> regions;  // the constructions refer to them
  InnerFairnessWeights coarser_lambda;  // the inner fairness weights of level l - 1
  CoarseSpace coarser_space;  // the coarse space of level l - 1 (from level l - 2), if any
  const int n_levels = int(hierarchy.triangles.size());
  for (int l = 0; l < n_levels; ++l) {
    if (stop_requested(options)) {  // before the level's initial mesh: the input unchanged
      run.cancelled = run.unchanged = true;
      result.converged = false;
      solution.X = X0;
      break;
    }
    const bool finest = l + 1 == n_levels;
    const FairingRegion& lr =
        regions.emplace_back(finest ? finest_level : level_region(region, hierarchy.triangles[l]));
    InnerFairnessWeights coarse_lambda =
        finest ? InnerFairnessWeights{} : coarse_level_weights(lr, X0, Xr, options.inner_fairness);
    const InnerFairnessWeights& lambda = finest ? lambda_finest : coarse_lambda;
    Positions Y;
    VertexSplits level_splits;
    std::vector<double> level_weights;
    if (l == 0) {
      Y = bilaplacian_initial_mesh(lr, lambda, gather(X0, lr.global),
                                   options.tuning.bilaplacian.newton_initial_mesh_residual,
                                   options.tuning.bilaplacian.cg_iterations);
    } else {
      std::vector<int> local;
      Y = solution.prolongated(lr, hierarchy.splits[l], Xs, lambda, level_splits, level_weights,
                               local, options.tuning.multigrid.prolongation_sweeps);
    }
    if (finest) hierarchy = ProgressiveMesh(), Xs = Xr = Positions();  // memory of the finest steps
    phases.emplace_back(level_phase(l, "initial mesh"), laps.lap());
    const std::unique_ptr<Construction> level_construction =
        finest ? finest_construction.get()
               : std::make_unique<Construction>(lr, std::move(coarse_lambda), options, L);
    Construction& construction = *level_construction;
    if (l > 0) {
      CoarseSpace coarse = coarse_space(lr, level_splits, regions[l - 1], coarser_lambda);
      CoarseSpace next = finest ? CoarseSpace{} : coarse;  // the next level's coarser space
      construction.set_coarse_space(std::move(coarse), std::move(coarser_space));
      coarser_space = std::move(next);
    }
    phases.emplace_back(level_phase(l, "set-up"), laps.lap());
    const SolverTuning& tuning = options.tuning;
    const double tolerance =
        options.tolerance * (finest ? 1.0 : tuning.schedule.coarse_tolerance);
    const int budget = finest ? options.max_iterations
                              : std::min(options.max_iterations, tuning.schedule.coarse_newton_steps);
    IterationReport report;
    double paper_seconds = 0.0;
    if (l == 0 && !finest) {
      report = solve_base_level(lr, construction, Y, X0, Xs, reference, options, L, budget,
                                tolerance, newton_iterations, paper_seconds);
    } else {
      NewtonRun newton_run;
      newton_run.max_iterations = budget;
      newton_run.tolerance = tolerance;
      newton_run.iteration_offset = newton_iterations;
      newton_run.patience = finest ? tuning.newton.patience : tuning.newton.coarse_patience;
      newton_run.polish_at_convergence = finest;
      newton_run.prolongated = l > 0;
      newton_run.from_initial_mesh = l == 0;
      report = construction.run_newton(Y, newton_run);
    }
    laps.lap();
    phases.emplace_back(level_phase(l, "inner fairness"), report.relax_seconds);
    phases.emplace_back(level_phase(l, "Newton steps"), report.step_seconds);
    phases.emplace_back(level_phase(l, "polishes"), report.polish_seconds);
    if (paper_seconds > 0.0) phases.emplace_back(level_phase(l, "paper iterations"), paper_seconds);
    newton_iterations += report.iterations;
    // A coarse level that did not converge would start the next one from a worse mesh than
    // its own linear initial mesh: the hierarchy is abandoned (the caller solves the finest
    // level alone). One that stopped with a small merit (the RMS of the scaled defects) is
    // converged but for a few vertices, which the next level's steps reach.
    if (!finest && !report.converged && !report.cancelled &&
        construction.merit() > tuning.newton.coarse_merit) {
      result.residual = report.residual;
      result.converged = false;
      break;
    }
    if (!finest) coarser_lambda = construction.lambda();
    solution.store(lr, Y, construction);
    result.iterations_per_level.push_back(report.iterations);
    result.vertices_per_level.push_back(lr.n);
    result.iterations += report.iterations;
    result.residual = report.residual;
    result.converged = finest && report.converged;
    if (report.cancelled) {
      // Cancelled on a coarse level: the input unchanged rather than a mix of levels.
      run.cancelled = true;
      if (!finest) solution.X = X0, run.unchanged = true;
      break;
    }
  }
  run.X = std::move(solution.X);
  return run;
}

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

}  // namespace

namespace {

std::string scientific(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1e", x);
  return text;
}

FairingResult solve(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                    const Positions* boundary_normals, const FairingOptions& options,
                    const std::vector<int>* polygon_ids);

// The residual (see fair) of X on `level` (region-local ids), or the largest finite double
// where it is not finite (degenerate triangles), so that a result never carries NaN or ∞.
double finite_residual(const FairingRegion& level, const InnerFairnessWeights& lambda,
                       const FairingOptions& options, double L, const Positions& X) {
  const double residual = Construction(level, lambda, options, L).evaluate(X);
  return std::isfinite(residual) ? residual : std::numeric_limits<double>::max();
}

// The residual (see fair) of the input positions themselves; the largest finite double where
// it is not finite (degenerate triangles), so that a result never carries NaN or ∞.
double input_residual(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                      const Positions* boundary_normals, const FairingOptions& options,
                      const std::vector<int>* polygon_ids) {
  FairingRegion region = extract_region(V, F, free, boundary_normals, true, polygon_ids);
  const Positions X0 = gather(V, region.global);
  std::iota(region.global.begin(), region.global.end(), 0);
  const double L = (X0.colwise().maxCoeff() - X0.colwise().minCoeff()).norm();
  return finite_residual(region, inner_fairness_weights(region, X0, options.inner_fairness),
                         options, L, X0);
}

}  // namespace

FairingResult fair(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const Positions* boundary_normals, const FairingOptions& options,
                   const std::vector<int>* polygon_ids) {
  check_options(options);
  // The time limit stops the iterations through the progress callback, which every
  // iteration of the user's problem calls (the user's callback still sees each call), and
  // the steps in between through stop_requested.
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const long n_free = std::count(free.begin(), free.end(), true);
  const ScheduleTuning& schedule = options.tuning.schedule;
  const bool automatic = options.time_limit < 0.0 && options.iteration == Iteration::Auto;
  // The automatic limit: `stall` seconds without a halving of the residual, `limit` in all.
  const double stall = automatic ? schedule.time_limit_base +
                                       schedule.time_limit_per_free * double(n_free)
                                 : std::numeric_limits<double>::infinity();
  const double limit = options.time_limit >= 0.0 ? options.time_limit
                       : automatic ? schedule.time_limit_hard_factor * stall
                                   : std::numeric_limits<double>::infinity();
  auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  Clock::time_point last_fall = start;  // when the residual last halved
  double fallen_to = std::numeric_limits<double>::infinity();
  bool counting = false;  // the attempt whose time without progress is limited has started
  bool timed_out = false, stalled = false, user_cancelled = false;
  FairingOptions timed = options;
  auto spent = [&] {
    timed_out = timed_out || seconds_since(start) > limit;
    stalled = stalled || (counting && seconds_since(last_fall) > stall);
    return timed_out || stalled;
  };
  timed.attempt_started = [&](bool paper) {
    counting = paper;
    fallen_to = std::numeric_limits<double>::infinity();
    last_fall = Clock::now();
  };
  timed.progress = [&](int k, double residual) {
    if (std::isfinite(residual) && residual <= 0.5 * fallen_to) {
      fallen_to = residual;
      last_fall = Clock::now();
    }
    if (spent()) return false;
    if (options.progress && !options.progress(k, residual)) {
      user_cancelled = true;
      return false;
    }
    return true;
  };
  // The long steps without progress reports (a level's initial mesh, the relaxations, the
  // next attempt) poll the time limit too.
  timed.stop_requested = [&] {
    if (spent()) return true;
    if (options.stop_requested && options.stop_requested()) {
      user_cancelled = true;
      return true;
    }
    return false;
  };
  // The folded edges of the result, in the message too.
  auto count_result_folds = [&](FairingResult& result) {
    const FoldCount folds = count_folds(V, result.vertices, F, free);
    result.folds = folds.folds;
    result.new_folds = folds.new_folds;
    if (folds.folds > 0)
      result.message += "; " + std::to_string(folds.folds) +
                        (folds.folds == 1 ? " edge folds" : " edges fold") +
                        " over (triangles flipped), " + std::to_string(folds.new_folds) +
                        " of them not in the input";
  };
  FairingResult result;
  try {
    result = solve(V, F, free, boundary_normals, timed, polygon_ids);
  } catch (const SolverError& error) {
    // Auto's last resort, the paper's iteration, diverged: an unconverged result (the input)
    // rather than an exception; an explicitly chosen iteration raises.
    if (options.iteration != Iteration::Auto) throw;
    result = FairingResult{};
    result.vertices = V;
    result.residual = input_residual(V, F, free, boundary_normals, options, polygon_ids);
    result.message = std::string(error.what()) + "; the input is returned unchanged";
    count_result_folds(result);
    return result;
  }
  const std::string how = std::move(result.message);  // solve's note on the path taken, if any
  const std::string figures =
      "residual " + scientific(result.residual) + ", tolerance " + scientific(options.tolerance);
  if (result.converged)
    result.message = "converged (" + figures + ")";
  else if (timed_out)
    result.message = "stopped at the time limit of " + scientific(limit) + " s (" + figures + ")";
  else if (stalled)
    result.message = "stopped: the residual did not halve in " + scientific(stall) +
                     " s, the automatic time limit (" + figures + ")";
  else if (user_cancelled)
    result.message = "cancelled (" + figures + ")";
  else
    result.message = "did not converge within max_iterations (" + figures + ")";
  if (!how.empty()) result.message += "; " + how;
  count_result_folds(result);
  // Where uniform inner fairness fails, its vertex distribution is often what breaks (it can
  // fold or flatten triangles of an irregular region, docs/REAL_MESHES.md): say so.
  if (!result.converged && !user_cancelled && options.inner_fairness == InnerFairness::Uniform &&
      options.outer_fairness == OuterFairness::Intrinsic)
    result.message += "; uniform inner fairness can degenerate the triangles of an irregular "
                      "region, conformal inner fairness converges on more meshes";
  return result;
}

namespace {

// Newton's method as Auto and Newton run it: on the hierarchy of newton_levels levels (or
// options.levels), then, if a level fails there, on the finest level alone. True with the
// run in `out` where it converged or was cancelled, also by options.stop_requested before
// an attempt (and with Newton, where the last attempt ended); false where Auto goes on with
// the paper's iteration.
// \throw SolverError with Iteration::Newton if the last attempt diverges.
bool solve_by_newton(const FairingRegion& region, const FairingRegion& finest_level,
                     const Positions& X0, const InnerFairnessWeights& lambda_finest,
                     const FairingOptions& options, double L, int& newton_iterations,
                     Phases& phases, SolveRun& out) {
  const int levels =
      options.levels > 0 ? options.levels : newton_levels(region, options.tuning.schedule);
  // The hierarchy first; if a level fails there, with uniform inner fairness the hierarchy
  // again with the membrane as the coarse levels' reference, and again with each level's
  // own uniform weights; then the finest level alone; then, for a region solved as one
  // level by default, two levels.
  using Attempt = std::pair<int, CoarseReference>;
  std::vector<Attempt> attempts;
  if (levels > 1) {
    attempts.emplace_back(levels, CoarseReference::Smoothed);
    if (options.inner_fairness == InnerFairness::Uniform &&
        lambda_finest.row_sum.size() == std::size_t(lambda_finest.size()))
      attempts.emplace_back(levels, CoarseReference::Membrane);
    if (options.inner_fairness == InnerFairness::Uniform)
      attempts.emplace_back(levels, CoarseReference::Own);
  }
  attempts.emplace_back(1, CoarseReference::Smoothed);
  // A region a little too small for the default hierarchy: two levels where one fails.
  if (levels == 1 && options.levels == 0 &&
      region.n_free >= options.tuning.schedule.newton_retry_min_free)
    attempts.emplace_back(2, CoarseReference::Smoothed);
  for (std::size_t a = 0; a < attempts.size(); ++a) {
    const auto [attempt, reference] = attempts[a];
    const bool last = a + 1 == attempts.size();
    if (a > 0 && stop_requested(options)) {
      out = stopped_run(X0, Iteration::Newton);
      out.result.newton_iterations = newton_iterations;
      return true;
    }
    SolveRun run;
    bool failed = false;
    if (options.attempt_started) options.attempt_started(false);
    try {
      run = newton_multigrid(region, finest_level, X0, lambda_finest, options, L, attempt,
                             reference, newton_iterations, phases);
    } catch (const SolverError&) {
      if (options.iteration == Iteration::Newton && last) throw;
      failed = true;
    }
    if (!failed && (run.result.converged || run.cancelled ||
                    (options.iteration == Iteration::Newton && last))) {
      run.result.newton_iterations = newton_iterations;
      out = std::move(run);
      return true;
    }
  }
  return false;
}

// The paper's iteration (section 7) on its progressive mesh: the base level from the linear
// initial mesh, each finer level prolongated and solved by nonlinear multigrid cycles on
// the coarser ones; with Auto, Newton attempts from the finest level's iterate
// (paper_with_newton_attempts). `newton_iterations`: the steps of Newton's method before.
SolveRun paper_multigrid(const FairingRegion& region, const FairingRegion& finest_level,
                          const Positions& X0, const InnerFairnessWeights& lambda_finest,
                          const FairingOptions& options, double L, int newton_iterations,
                          Phases& phases) {
  const int levels = options.levels > 0 ? options.levels : default_levels(region.n_free);
  Laps laps;
  Positions Xs;  // the smoothed copy the hierarchy is measured on
  const ProgressiveMesh hierarchy = build_hierarchy(
      region, X0, lambda_finest,
      options.outer_fairness == OuterFairness::Intrinsic ? levels : 1, kPaperDecimation,
      options.tuning.hierarchy, Xs);

  FairingResult result;
  result.iteration = Iteration::Paper;
  result.newton_iterations = newton_iterations;
  phases.emplace_back("hierarchy", laps.lap());
  LevelSolution solution(X0);
  // Coarse levels estimate normals with Max's weights where the fitted normal is asked for:
  // the fit, consistent on the finest mesh, is ill-conditioned on the decimated rings of
  // coarse levels (short and long edges, low valence), and the cycles need several times
  // the iterations there (docs/DESIGN_NOTES.md, "Coarse levels"). The coarse levels only
  // supply corrections; the finest level's equations decide the result.
  FairingOptions coarse_options = options;
  if (options.normal_weighting == NormalWeighting::Quadric)
    coarse_options.normal_weighting = NormalWeighting::Max;
  std::deque<MultigridLevel> levels_built;
  Multigrid multigrid(levels_built, options.tuning.multigrid);
  NewtonAttempts attempts(finest_level, lambda_finest, options, L, options.tuning.newton.patience);
  const int n_levels = int(hierarchy.triangles.size());
  bool unchanged = false;
  for (int l = 0; l < n_levels; ++l) {
    if (stop_requested(options)) {  // before the level's initial mesh: the input unchanged
      result.converged = false;
      solution.X = X0;
      unchanged = true;
      break;
    }
    const bool finest = l + 1 == n_levels;
    MultigridLevel& level = levels_built.emplace_back();
    level.region = finest ? finest_level : level_region(region, hierarchy.triangles[l]);
    const FairingRegion& lr = level.region;
    // Inner fairness of the finest level as asked, with conformal weights from the original
    // mesh. Coarse levels, whose vertex distribution does not reach the result, take the
    // conformal weights of the smoothed copy with their connectivity (see fairing.h).
    InnerFairnessWeights lambda =
        finest ? lambda_finest
               : ring_inner_fairness_weights(lr.rings, gather(Xs, lr.global),
                                             InnerFairness::Conformal);
    Positions Y;
    if (l == 0) {
      Y = bilaplacian_initial_mesh(lr, lambda, gather(X0, lr.global),
                                   options.outer_fairness == OuterFairness::Bilaplacian
                                       ? options.tuning.bilaplacian.exact_residual
                                       : options.tuning.bilaplacian.initial_mesh_residual,
                                   options.tuning.bilaplacian.cg_iterations);
    } else {
      std::vector<int> local;
      Y = solution.prolongated(lr, hierarchy.splits[l], Xs, lambda, level.splits, level.weights,
                               local, options.tuning.multigrid.prolongation_sweeps);
      const FairingRegion& coarser = levels_built[l - 1].region;
      level.from_coarser.resize(coarser.n);
      for (int c = 0; c < coarser.n; ++c) level.from_coarser[c] = local[coarser.global[c]];
    }
    phases.emplace_back(level_phase(l, "initial mesh"), laps.lap());
    level.construction = std::make_unique<Construction>(lr, std::move(lambda),
                                                        finest ? options : coarse_options, L);
    Construction& construction = *level.construction;
    phases.emplace_back(level_phase(l, "set-up"), laps.lap());
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
                      : multigrid.solve(l, Y, tolerance, slice, offset);
      };
      report = finest && options.iteration == Iteration::Auto
                   ? paper_with_newton_attempts(paper, Y, budget, tolerance, result.iterations,
                                                attempts)
                   : paper(budget, result.iterations);
    }
    phases.emplace_back(level_phase(l, "iterations"), laps.lap());
    solution.store(lr, Y, construction);
    result.iterations = 0;
    for (const MultigridLevel& done : levels_built)
      result.iterations += int(done.construction->iterations());
    result.vertices_per_level.push_back(lr.n);
    result.residual = report.residual;
    result.converged = report.converged;
    if (report.cancelled) {
      result.converged = false;
      break;
    }
  }
  for (const MultigridLevel& done : levels_built)
    result.iterations_per_level.push_back(int(done.construction->iterations()));
  result.newton_iterations += attempts.steps();
  if (attempts.converged_after() >= 0)
    result.message = "Newton's method converged from the paper's iterate after " +
                     std::to_string(attempts.converged_after()) + " iterations";

  SolveRun run;
  run.result = std::move(result);
  run.X = std::move(solution.X);
  run.unchanged = unchanged;
  return run;
}

FairingResult solve(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                    const Positions* boundary_normals, const FairingOptions& options,
                    const std::vector<int>* polygon_ids) {
#ifdef _OPENMP
  omp_set_dynamic(0);
  omp_set_num_threads(solve_threads());
#endif
  const BlasThreads blas_threads(1);  // more only for large factorizations (sparse_lu.h)
  const FairingRegion region = extract_region(V, F, free, boundary_normals, true, polygon_ids);

  const Positions X0 = gather(V, region.global);  // the original mesh
  const double L = (X0.colwise().maxCoeff() - X0.colwise().minCoeff()).norm();
  if (!(L > 0.0)) throw InvalidInputError("fair: the region has zero extent");

  // The finest level is the region itself, with region-local ids as its "global" ids.
  FairingRegion finest_level = region;
  std::iota(finest_level.global.begin(), finest_level.global.end(), 0);
  // Inner fairness weights of the finest level (the region, from the original mesh): for
  // Newton's method, the hierarchy and the paper's finest level alike.
  const InnerFairnessWeights lambda_finest =
      inner_fairness_weights(finest_level, X0, options.inner_fairness);

  int newton_iterations = 0;
  Phases phases;
  SolveRun run;
  // Auto tries Newton's method at every size: it is the faster also at a million free
  // vertices (docs/ACCURACY_AND_SPEED.md).
  const bool newton = options.outer_fairness == OuterFairness::Intrinsic &&
                      options.iteration != Iteration::Paper;
  if (!(newton && solve_by_newton(region, finest_level, X0, lambda_finest, options, L,
                                  newton_iterations, phases, run))) {
    if (newton && stop_requested(options)) {
      run = stopped_run(X0, Iteration::Newton);
    } else {
      if (options.attempt_started) options.attempt_started(true);
      run = paper_multigrid(region, finest_level, X0, lambda_finest, options, L,
                            newton_iterations, phases);
    }
  }
  FairingResult& result = run.result;
  if (run.unchanged) {  // the residual of what is returned: the input's
    result.newton_iterations = newton_iterations;
    result.residual = finite_residual(finest_level, lambda_finest, options, L, X0);
  }
  result.phase_seconds = std::move(phases);
  if (!run.X.topRows(region.n_free).allFinite())
    throw SolverError("fair: the iteration produced non-finite positions");
  result.vertices = V;
  for (int i = 0; i < region.n_free; ++i) result.vertices.row(region.global[i]) = run.X.row(i);
  return result;
}

}  // namespace

}  // namespace geofair
