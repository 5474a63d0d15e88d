// Section 7.4's nested iteration: the levels of a progressive mesh of the region solved
// coarsest first, the base level from the linear initial mesh, each finer level from the
// prolongation of the coarser solution, by Newton's method or by the paper's iteration.
#pragma once

#include "geofair/types.h"

#include "inner_fairness.h"
#include "region.h"

#include <string>
#include <utility>
#include <vector>

namespace geofair {

/// FairingResult::phase_seconds.
using Phases = std::vector<std::pair<std::string, double>>;

/// The reference geometry of the uniform coarse weights of Newton's hierarchy
/// (coarse_level_weights). Smoothed: the smoothed copy Xs of the input, whose vertex
/// distribution is about uniform where the input's is (regular meshes, of any metric).
/// Membrane: the membrane of the finest uniform weights (membrane_positions), the
/// distribution an irregular connectivity asks for, which Xs does not know (random samples
/// of a surface: docs/DESIGN_NOTES.md, "Flattened caps"). Own: no reference; each coarse
/// level takes its own uniform weights, whose distribution follows the finest one's where
/// decimation keeps the connectivity about as irregular (the 1M-vertex irregular cap:
/// docs/DESIGN_NOTES.md, "Coarse levels of large irregular caps").
enum class CoarseReference { Smoothed, Membrane, Own };

/// One attempt of fair()'s schedule (schedule.h): the iteration, on how many levels, and
/// for Newton's method the reference of its uniform coarse weights.
struct Attempt {
  Iteration iteration = Iteration::Newton;  ///< Newton or Paper
  int levels = 1;
  CoarseReference reference = CoarseReference::Smoothed;
  /// With CoarseReference::Membrane: the hierarchy is decimated on the membrane, where the
  /// coarse weights place the vertices, instead of on the smoothed copy Xs (on an irregular
  /// connectivity the membrane lies many edge lengths from Xs, and coarse triangles valid on
  /// Xs fold there; the membrane of a loop on a curved surface is far from its shape, and
  /// coarse triangles valid on it fold after the prolongation). On Xs the base level is
  /// solved with Xs's weights first (docs/DESIGN_NOTES.md, "The membrane attempt's
  /// hierarchy").
  bool decimate_on_membrane = false;
};

/// What every attempt solves: the region, itself as the finest level (region-local ids as
/// its `global` ids), the original positions X0 (#region×3), the finest level's inner
/// fairness weights, the options, and the length L of the residual (fairing.h).
struct Problem {
  const FairingRegion& region;
  const FairingRegion& finest_level;
  const Positions& X0;
  const InnerFairnessWeights& lambda_finest;
  const FairingOptions& options;
  double L;
};

/// The outcome of an attempt: the result without its vertices (nor its phases), the
/// region's positions.
struct SolveRun {
  FairingResult result;
  Positions X;
  bool cancelled = false;
  bool unchanged = false;  ///< X is the input: stopped before the finest level's solve
};

/// Solves `problem` by the attempt's iteration on a progressive mesh of attempt.levels
/// levels (one: the region alone). Newton's method (Construction::run_newton) solves each
/// level from its linear initial mesh or prolongation, its hierarchy coarsening the G1
/// boundary too (kNewtonDecimation); a coarse level that stops unconverged with a merit
/// above NewtonTuning::coarse_merit ends the run unconverged, and a base level where
/// Newton's method fails from the linear initial mesh runs the paper's iteration and one
/// Newton attempt from its iterate. The paper's iteration (section 7, Construction::run)
/// solves the finer levels by nonlinear multigrid cycles (multigrid.h) and, with
/// Iteration::Auto, tries Newton's method from the finest level's iterate after
/// ScheduleTuning::newton_attempt_first iterations and each doubling. Coarse levels stop at
/// a looser tolerance with the weights of coarse_level_weights. A stop requested before a
/// level, or a cancellation on a coarse level, returns the input unchanged.
/// `newton_iterations` accumulates Newton's steps, `phases` the wall time of the phases.
/// \throw SolverError if a level diverges or a linear solve fails.
SolveRun solve_levels(const Problem& problem, const Attempt& attempt, int& newton_iterations,
                      Phases& phases);

/// True where options.stop_requested asks the solve to stop (fair's time limit).
bool stop_requested(const FairingOptions& options);

/// A run stopped before it changed anything: the input X0, unconverged.
SolveRun stopped_run(const Positions& X0, Iteration iteration);

/// The residual (see fair) of X on `level` (region-local ids), or the largest finite double
/// where it is not finite (degenerate triangles), so that a result never carries NaN or ∞.
double finite_residual(const FairingRegion& level, const InnerFairnessWeights& lambda,
                       const FairingOptions& options, double L, const Positions& X);

}  // namespace geofair
