// fair()'s schedule: the attempts it makes, in order, until one converges (fairing.h).
#pragma once

#include "nested_iteration.h"

#include <vector>

namespace geofair {

/// The attempts of fair() for `problem`, in the order they run (docs/ARCHITECTURE.md):
///
/// | # | iteration | levels                    | coarse weights | when                        |
/// |---|-----------|---------------------------|----------------|-----------------------------|
/// | 1 | Newton    | newton_levels (or levels) | Smoothed       | more than one level         |
/// | 2 | Newton    | same                      | Membrane       | 1, uniform, symmetric (*)   |
/// |   |           |                           |                | (before 1 where irregular,  |
/// |   |           |                           |                | decimated on the membrane)  |
/// | 3 | Newton    | same                      | Membrane,      | 2, where 2 is decimated on  |
/// |   |           |                           | decimated on it| the smoothed copy           |
/// | 4 | Newton    | same                      | Own            | 1 and uniform inner fairness|
/// | 5 | Newton    | 1                         | –              | always                      |
/// | 6 | Newton    | 2                         | Smoothed       | one level by default and at |
/// |   |           |                           |                | least newton_retry_min_free |
/// | 7 | Paper     | default_levels (or levels;| –              | Auto: last; Paper: only     |
/// |   |           | 1 with bilaplacian outer) |                |                             |
///
/// "More than one level": the levels asked for (newton_levels or options.levels), before
/// decimation, which may build fewer. (*) The finest weights symmetric
/// (InnerFairnessWeights::row_sum given), which the membrane needs. "Irregular": at least
/// ScheduleTuning::membrane_first_irregularity of the free vertices have a valence other
/// than 6. "Decimated on": Attempt::decimate_on_membrane; where 2 is decimated on the
/// smoothed copy, its base level is solved with the smoothed copy's weights first and then
/// with its own from there (solve_base_level).
/// Newton's attempts (1–6) run with intrinsic outer fairness and Iteration::Auto or Newton;
/// Auto's last attempt is the paper's iteration (7) with Newton attempts from its iterate;
/// Iteration::Paper and the linear bilaplacian outer fairness run 7 alone.
///
/// Every other retry the library makes, inside an attempt and around fair():
///
/// | where                                   | when                          | retry                          |
/// |-----------------------------------------|-------------------------------|--------------------------------|
/// | base level of 1–6 (NewtonLevels)        | Newton fails from the linear  | the paper's iteration, then    |
/// |                                         | initial mesh                  | one Newton attempt from it     |
/// | coarse level of 1–4, 6                  | stops with a merit above      | ends the attempt (the next     |
/// |                                         | NewtonTuning::coarse_merit    | one runs)                      |
/// | finest level of 7 (PaperLevels, Auto)   | after newton_attempt_first    | a Newton attempt from the      |
/// |                                         | iterations, and each doubling | iterate                        |
/// | fair_if_needed (Remesh::IfNeeded)       | no convergence, or new folds  | remesh the region, schedule    |
/// |                                         |                               | again; the better result       |
/// | fill_holes, per hole (hole_filling.cpp) | no fold-free convergence      | intrinsic, intrinsic_trimmed   |
/// |                                         |                               | (rim="trim"), intrinsic_finer  |
/// |                                         |                               | (half the edge length), g0,    |
/// |                                         |                               | linear                         |
/// | LiveFairing::update (live.cpp)          | the warm frame fails          | fair() from the frame's input  |
std::vector<Attempt> plan_attempts(const Problem& problem);

/// Walks `attempts` (plan_attempts) and returns the first run that converged or was
/// cancelled; with Iteration::Newton the last attempt's run whatever its outcome, with Auto
/// the paper's. A stop requested between two attempts returns the input unchanged.
/// `newton_iterations` accumulates Newton's steps of all attempts, `phases` their phases.
/// \throw SolverError where Iteration::Newton's last attempt or the paper's iteration fails.
SolveRun run_attempts(const Problem& problem, const std::vector<Attempt>& attempts,
                      int& newton_iterations, Phases& phases);

}  // namespace geofair
