// fair()'s schedule of attempts (schedule.h).
#include "schedule.h"

#include "progressive_mesh.h"

namespace geofair {
namespace {

// Levels of the Newton hierarchy: as many as keep newton_min_base_free free vertices on the
// base level (one level below four times that).
int newton_levels(const FairingRegion& region, const ScheduleTuning& schedule) {
  int levels = 1;
  for (double n = region.n_free / 4.0; n >= schedule.newton_min_base_free; n /= 4.0) ++levels;
  return levels;
}

// The share of the free vertices whose valence is not 6 (free vertices are interior: their
// ring is closed).
double irregularity(const FairingRegion& region) {
  if (region.n_free == 0) return 0.0;
  const std::vector<int>& offset = region.rings.offset;
  int irregular = 0;
  for (int i = 0; i < region.n_free; ++i) irregular += offset[i + 1] - offset[i] != 6;
  return double(irregular) / region.n_free;
}

}  // namespace

std::vector<Attempt> plan_attempts(const Problem& p) {
  const FairingOptions& o = p.options;
  const ScheduleTuning& schedule = o.tuning.schedule;
  std::vector<Attempt> attempts;
  const bool intrinsic = o.outer_fairness == OuterFairness::Intrinsic;
  const bool newton = intrinsic && o.iteration != Iteration::Paper;
  const bool uniform = o.inner_fairness == InnerFairness::Uniform;
  const int levels = o.levels > 0 ? o.levels : newton_levels(p.region, schedule);
  if (newton && levels > 1) {
    // The membrane needs symmetric finest weights (InnerFairnessWeights::row_sum given). It
    // goes first on an irregular connectivity, the smoothed copy on a regular one.
    const bool membrane =
        uniform && p.lambda_finest.row_sum.size() == std::size_t(p.lambda_finest.size());
    const bool membrane_first =
        membrane && irregularity(p.region) >= schedule.membrane_first_irregularity;
    if (membrane_first)
      attempts.push_back({Iteration::Newton, levels, CoarseReference::Membrane, true});
    attempts.push_back({Iteration::Newton, levels, CoarseReference::Smoothed});
    if (membrane && !membrane_first) {
      attempts.push_back({Iteration::Newton, levels, CoarseReference::Membrane});
      attempts.push_back({Iteration::Newton, levels, CoarseReference::Membrane, true});
    }
    if (uniform) attempts.push_back({Iteration::Newton, levels, CoarseReference::Own});
  }
  if (newton) attempts.push_back({Iteration::Newton, 1, CoarseReference::Smoothed});
  // A region a little too small for the default hierarchy: two levels where one fails.
  if (newton && levels == 1 && o.levels == 0 && p.region.n_free >= schedule.newton_retry_min_free)
    attempts.push_back({Iteration::Newton, 2, CoarseReference::Smoothed});
  if (!newton || o.iteration == Iteration::Auto) {
    const int paper_levels = !intrinsic     ? 1
                             : o.levels > 0 ? o.levels
                                            : default_levels(p.region.n_free);
    attempts.push_back({Iteration::Paper, paper_levels, CoarseReference::Smoothed});
  }
  return attempts;
}

SolveRun run_attempts(const Problem& p, const std::vector<Attempt>& attempts,
                      int& newton_iterations, Phases& phases) {
  const FairingOptions& options = p.options;
  for (std::size_t a = 0; a < attempts.size(); ++a) {
    const Attempt& attempt = attempts[a];
    const bool last = a + 1 == attempts.size();
    if (a > 0 && stop_requested(options)) return stopped_run(p.X0, attempts[a - 1].iteration);
    if (options.attempt_started) options.attempt_started(attempt.iteration == Iteration::Paper);
    SolveRun run;
    try {
      run = solve_levels(p, attempt, newton_iterations, phases);
    } catch (const SolverError&) {
      if (last) throw;  // Newton's last attempt, or the paper's iteration
      continue;
    }
    if (run.result.converged || run.cancelled || last) {
      if (attempt.iteration == Iteration::Newton) run.result.newton_iterations = newton_iterations;
      return run;
    }
  }
  return stopped_run(p.X0, Iteration::Newton);  // not reached: the last attempt returns
}

}  // namespace geofair
