// fair(): the region, the schedule of attempts (schedule.h) under a time limit, and the
// result's message (Schneider & Kobbelt 2001, section 7 and Fig. 6).
#include "geofair/fairing.h"

#include "common.h"
#include "displacement_predictor.h"
#include "fairing_internal.h"
#include "inner_fairness.h"
#include "mesh_scale.h"
#include "nested_iteration.h"
#include "parallel.h"
#include "region.h"
#include "remesh.h"
#include "schedule.h"
#include "sparse_lu.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numeric>
#include <optional>
#include <string>

namespace geofair {

void check_fairing_options(const FairingOptions& o) {
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance))
    throw InvalidInputError("fair: tolerance must be a positive finite number");
  if (o.max_iterations < 0) throw InvalidInputError("fair: max_iterations must be >= 0");
  if (!(o.damping > 0.0 && o.damping <= 1.0))
    throw InvalidInputError("fair: damping must lie in (0, 1]");
  if (o.cg_iterations < 1) throw InvalidInputError("fair: cg_iterations must be >= 1");
  if (o.levels < 0) throw InvalidInputError("fair: levels must be >= 0");
  if (std::isnan(o.time_limit)) throw InvalidInputError("fair: time_limit must not be NaN");
  if (o.deadline && !(o.deadline->seconds >= 0.0))
    throw InvalidInputError("fair: deadline.seconds must be >= 0");
  validate_tuning(o.tuning);
}

// The threads of one solve: GEOFAIR_NUM_THREADS where set, else max_threads() less the
// cores that other processes keep busy now (the runnable tasks of /proc/loadavg, not counting
// this process's own; none known where there is no /proc). On a busy machine the threads of
// a parallel loop wait for each other at every barrier, so a core taken by another process
// is left to it (docs/DESIGN_NOTES.md, "Threads"). Declared in parallel.h.
int solve_threads() {
  if (const int n = requested_threads_from_environment(); n > 0) return n;
  int runnable = 0, own = 0;
#ifdef __linux__
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%*f %*f %*f %d", &runnable) != 1) runnable = 0;
    std::fclose(f);
  }
  std::error_code error;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", error)) {
    if (FILE* f = std::fopen((task.path() / "stat").string().c_str(), "r")) {
      // pid (comm) state ...: the state follows the last ')'.
      char line[512];
      if (std::fgets(line, sizeof line, f))
        if (const char* close = std::strrchr(line, ')'); close && close[1] && close[2] == 'R')
          ++own;
      std::fclose(f);
    }
  }
#endif
  const int busy_elsewhere = std::max(0, runnable - std::max(own, 1));
  return std::clamp(machine_cores() - busy_elsewhere, 1, max_threads());
}

namespace {

// fair()'s time limit (FairingOptions::time_limit; the automatic rule in fairing.h): it
// stops the iterations through the progress callback, which every iteration of the user's
// problem calls (the user's callback still sees each call), and the long steps in between
// (a level's initial mesh, the relaxations, the next attempt) through stop_requested.
class TimeLimit {
 public:
  using Clock = std::chrono::steady_clock;

  TimeLimit(const FairingOptions& options, long n_free)
      : user_(options), deadline_(options.deadline) {
    const ScheduleTuning& schedule = options.tuning.schedule;
    const bool automatic = options.time_limit < 0.0 && options.iteration == Iteration::Auto;
    const double none = std::numeric_limits<double>::infinity();
    // The automatic limit: `stall_` seconds without a halving of the residual, `limit_` in all.
    stall_ = automatic ? schedule.time_limit_base +
                             schedule.time_limit_per_free_vertex * double(n_free)
                       : none;
    limit_ = options.time_limit >= 0.0 ? options.time_limit
             : automatic               ? schedule.time_limit_hard_factor * stall_
                                       : none;
  }
  TimeLimit(const TimeLimit&) = delete;
  TimeLimit& operator=(const TimeLimit&) = delete;

  // The user's options with the limit's callbacks (they refer to this object).
  FairingOptions options() {
    FairingOptions timed = user_;
    timed.attempt_started = [this](bool paper) {
      counting_ = paper;
      fallen_to_ = std::numeric_limits<double>::infinity();
      last_fall_ = Clock::now();
    };
    timed.progress = [this](int k, double residual) {
      if (std::isfinite(residual) && residual <= 0.5 * fallen_to_) {
        fallen_to_ = residual;
        last_fall_ = Clock::now();
      }
      if (spent()) return false;
      if (user_.progress && !user_.progress(k, residual)) {
        user_cancelled_ = true;
        return false;
      }
      return true;
    };
    timed.stop_requested = [this] {
      if (spent()) return true;
      if (user_.stop_requested && user_.stop_requested()) {
        user_cancelled_ = true;
        return true;
      }
      return false;
    };
    return timed;
  }

  // Stopped where the caller asked: cancelled, or at an explicit time limit or the deadline.
  bool stopped_by_caller() const {
    return user_cancelled_ || at_deadline_ || (timed_out_ && user_.time_limit >= 0.0);
  }

  // Why an unconverged solve ended.
  StopReason reason() const {
    return timed_out_ || at_deadline_ ? StopReason::TimeLimit
           : stalled_        ? StopReason::NoProgress
           : user_cancelled_ ? StopReason::Cancelled
                             : StopReason::MaxIterations;
  }

  // Why an unconverged solve ended, with its figures.
  std::string why_not(const std::string& figures) const {
    if (timed_out_ || at_deadline_)
      return "stopped at the time limit of " +
             scientific(timed_out_ ? limit_ : deadline_->seconds) + " s (" + figures + ")";
    if (stalled_)
      return "stopped: the residual did not halve in " + scientific(stall_) +
             " s, the automatic time limit (" + figures + ")";
    if (user_cancelled_) return "cancelled (" + figures + ")";
    return "did not converge within max_iterations (" + figures + ")";
  }

 private:
  static double seconds_since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  }
  bool spent() {
    timed_out_ = timed_out_ || seconds_since(start_) > limit_;
    at_deadline_ = at_deadline_ || (deadline_ && Clock::now() >= deadline_->at);
    stalled_ = stalled_ || (counting_ && seconds_since(last_fall_) > stall_);
    return timed_out_ || at_deadline_ || stalled_;
  }

  const FairingOptions& user_;
  const std::optional<FairingOptions::Deadline> deadline_;
  double stall_ = 0.0, limit_ = 0.0;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_fall_ = start_;  // when the residual last halved
  double fallen_to_ = std::numeric_limits<double>::infinity();
  bool counting_ = false;  // the attempt whose time without progress is limited has started
  bool timed_out_ = false, at_deadline_ = false, stalled_ = false, user_cancelled_ = false;
};

// The residual (see fair) of the input positions themselves; the largest finite double where
// it is not finite (degenerate triangles), so that a result never carries NaN or ∞.
double input_residual(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                      const Positions* boundary_normals, const FairingOptions& options,
                      const std::vector<int>* polygon_ids) {
  FairingRegion region = extract_region(V, F, free, boundary_normals, true, polygon_ids,
                                        options.boundary);
  const Positions X0 = gather(V, region.global);
  std::iota(region.global.begin(), region.global.end(), 0);
  const double L = diagonal(X0);
  return finite_residual(region, inner_fairness_weights(region, X0, options.inner_fairness),
                         options, L, X0);
}

// The region, its finest inner fairness weights, and the schedule's attempts; the result's
// vertices and figures, its message only a note on the path taken (or empty).
FairingResult solve(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                    const Positions* boundary_normals, const FairingOptions& options,
                    const std::vector<int>* polygon_ids) {
  set_loop_threads(solve_threads());
  const BlasThreads blas_threads(1);  // results independent of the thread count (sparse_lu.h)
  const FairingRegion region = extract_region(V, F, free, boundary_normals, true, polygon_ids,
                                              options.boundary);
  const Positions X0 = gather(V, region.global);  // the original mesh
  const double L = diagonal(X0);
  if (!(L > 0.0)) throw InvalidInputError("fair: the region has zero extent");
  // The finest level is the region itself, with region-local ids as its "global" ids.
  FairingRegion finest_level = region;
  std::iota(finest_level.global.begin(), finest_level.global.end(), 0);
  // Inner fairness weights of the finest level (the region, from the original mesh): the
  // same for every attempt.
  const InnerFairnessWeights lambda_finest =
      inner_fairness_weights(finest_level, X0, options.inner_fairness);
  const Problem problem{region, finest_level, X0, lambda_finest, options, L};

  int newton_iterations = 0;
  Phases phases;
  SolveRun run = run_attempts(problem, plan_attempts(problem), newton_iterations, phases);
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

// The folded edges of the result (count_folds), in its message too.
void count_result_folds(FairingResult& result, const Positions& V, const Triangles& F,
                        const std::vector<bool>& free) {
  const FoldCount folds = count_folds(V, result.vertices, F, free);
  result.folds = folds.folds;
  result.new_folds = folds.new_folds;
  result.message += fold_note(folds);
}

// The result's message: how the solve ended, then solve()'s note on the path taken.
void describe(FairingResult& result, const FairingOptions& options, const TimeLimit& limit) {
  const std::string how = std::move(result.message);
  const std::string figures =
      "residual " + scientific(result.residual) + ", tolerance " + scientific(options.tolerance);
  result.message = result.converged ? "converged (" + figures + ")" : limit.why_not(figures);
  result.stop_reason = result.converged ? StopReason::Converged : limit.reason();
  if (!how.empty()) result.message += "; " + how;
}

// fair() with the connectivity kept (options.remesh not read): the schedule's solve under
// the time limit, its message and folds.
FairingResult fair_kept(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                        const Positions* boundary_normals, const FairingOptions& options,
                        const std::vector<int>* polygon_ids) {
  TimeLimit limit(options, std::count(free.begin(), free.end(), true));
  const FairingOptions timed = limit.options();
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
    result.stop_reason = StopReason::Diverged;
    count_result_folds(result, V, F, free);
    keep_connectivity(result, F, free);
    return result;
  }
  describe(result, options, limit);
  count_result_folds(result, V, F, free);
  // Where uniform inner fairness fails, its vertex distribution is often what breaks (it can
  // fold or flatten triangles of an irregular region, docs/REAL_MESHES.md): say so.
  if (!result.converged && !limit.stopped_by_caller() &&
      options.inner_fairness == InnerFairness::Uniform &&
      options.outer_fairness == OuterFairness::Intrinsic)
    result.message += "; uniform inner fairness can degenerate the triangles of an irregular "
                      "region, conformal inner fairness converges on more meshes";
  keep_connectivity(result, F, free);
  return result;
}

// fair_remeshed_from's second remesh: its target edge length relative to the first's.
constexpr double kFinerRemesh = 0.8;

// Moves a remesh of another surface to V: the fixed rows (which keep their index) to V's,
// the free ones by the harmonic extension of the fixed ones' moves (DisplacementPredictor),
// so that the vertices next to a handle that has moved on are not left under it.
// `normals`: the G1 normals of the kept rows (nullptr with G0), which the remesh's region
// needs but the extension does not read.
void follow_fixed_moves(const Positions& V, RemeshedRegion& mesh, const Positions* normals,
                        BoundaryCondition boundary) {
  const FairingRegion region =
      extract_region(mesh.vertices, mesh.faces, mesh.free, normals, true, nullptr, boundary);
  const int nb = region.n - region.n_free;
  Positions moves(nb, 3);
  for (int b = 0; b < nb; ++b) {
    const int v = region.global[region.n_free + b];
    moves.row(b) = V.row(v) - mesh.vertices.row(v);
  }
  Positions Y = Positions::Zero(region.n, 3);
  DisplacementPredictor(region).predict(moves, Y);  // where it fails, the free rows stay
  for (int i = 0; i < region.n_free; ++i) mesh.vertices.row(region.global[i]) += Y.row(i);
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!mesh.free[std::size_t(v)]) mesh.vertices.row(v) = V.row(v);
}

// A remesh of the input's region (remesh_region) with the G1 normals of the input at the
// kept rows (nullopt with G0; the remesh's region needs them, the extension does not read
// them).
struct RemeshedInput {
  RemeshedRegion mesh;
  std::optional<Positions> normals;
};

// remesh_region's remesh of the region of `surface` (the input's rows) with the G1 normals of
// `input` (the input's region: the given normals, or the estimate from the input's
// surrounding surface); with `follow`, moved to V's fixed positions (follow_fixed_moves).
RemeshedInput remesh_input(const FairingRegion& input, const Positions& V, const Positions& surface,
                           const Triangles& F, const std::vector<bool>& free,
                           BoundaryCondition boundary, bool follow, const RemeshOptions& remesh) {
  RemeshedInput out{remesh_region(surface, F, free, remesh), std::nullopt};
  if (boundary == BoundaryCondition::G1) {
    out.normals = Positions::Zero(out.mesh.vertices.rows(), 3);
    for (int b = 0; b < input.n - input.n_free; ++b)
      out.normals->row(input.global[input.n_free + b]) = input.g1_normals.row(b);
  }
  if (follow) follow_fixed_moves(V, out.mesh, out.normals ? &*out.normals : nullptr, boundary);
  return out;
}

// fair() of a remeshed input; `seconds` its remesh's, counted against the time limit.
FairingResult fair_remesh(RemeshedInput input, const FairingOptions& options, double seconds) {
  RemeshedRegion& mesh = input.mesh;
  // The new triangles come from no polygon: polygon_ids no longer apply.
  FairingResult result =
      fair_kept(mesh.vertices, mesh.faces, mesh.free, input.normals ? &*input.normals : nullptr,
                options_after(options, seconds), nullptr);
  result.remeshed = true;
  result.unreferenced = std::move(mesh.unreferenced);
  result.origin_face = std::move(mesh.origin_face);
  result.origin_barycentric = std::move(mesh.origin_barycentric);
  result.phase_seconds.insert(result.phase_seconds.begin(), {"remesh", seconds});
  return result;
}

// fair() on remesh_region's remesh of the region of V (Remesh::Always and IfNeeded).
FairingResult fair_remeshed(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                            const Positions* boundary_normals, const FairingOptions& options,
                            const std::vector<int>* polygon_ids) {
  Laps laps;
  // The input's region: fair()'s checks and messages, and the input's G1 normals.
  const FairingRegion input =
      extract_region(V, F, free, boundary_normals, true, polygon_ids, options.boundary);
  RemeshedInput remeshed = remesh_input(input, V, V, F, free, options.boundary, false, {});
  const double seconds = laps.lap();
  return fair_remesh(std::move(remeshed), options, seconds);
}

// Why a result of the connectivity kept asks for a remesh ("" where it does not).
std::string remesh_reason(const FairingResult& kept) {
  if (!kept.converged) return "with its connectivity the region did not converge";
  if (kept.new_folds > 0)
    return "with its connectivity the region folded " + std::to_string(kept.new_folds) +
           (kept.new_folds == 1 ? " edge" : " edges");
  return "";
}

// Whether result a is better than b: converged first, then fewer new folds, then the
// smaller residual.
bool better(const FairingResult& a, const FairingResult& b) {
  if (a.converged != b.converged) return a.converged;
  if (a.new_folds != b.new_folds) return a.new_folds < b.new_folds;
  return a.residual < b.residual;
}

// Whether a second attempt may follow `first`, which took `spent` seconds: not after a
// cancel or where the time limit or the deadline is spent.
bool time_left(const FairingResult& first, const FairingOptions& options, double spent) {
  return first.stop_reason != StopReason::Cancelled && has_time_left(options, spent);
}

// `out` (one of two attempts, a and b) with the Newton steps and the phases of both.
FairingResult& with_both_costs(FairingResult& out, FairingResult& a, const FairingResult& b) {
  out.newton_iterations = a.newton_iterations + b.newton_iterations;
  auto phases = std::move(a.phase_seconds);
  phases.insert(phases.end(), b.phase_seconds.begin(), b.phase_seconds.end());
  out.phase_seconds = std::move(phases);
  return out;
}

// Remesh::IfNeeded: the connectivity kept first; where it fails (remesh_reason) and time is
// left, the remesh too, and the better of the two (the remesh where it converged without
// new folds); the phases and Newton steps of both.
FairingResult fair_if_needed(const Positions& V, const Triangles& F,
                             const std::vector<bool>& free, const Positions* boundary_normals,
                             const FairingOptions& options, const std::vector<int>* polygon_ids) {
  Laps laps;
  FairingResult kept = fair_kept(V, F, free, boundary_normals, options, polygon_ids);
  const std::string reason = remesh_reason(kept);
  const double spent = laps.lap();
  if (reason.empty() || !time_left(kept, options, spent)) return kept;
  FairingResult remeshed;
  try {
    remeshed = fair_remeshed(V, F, free, boundary_normals, options_after(options, spent), polygon_ids);
  } catch (const std::exception& error) {  // the remesh or its solve failed: keep the first
    kept.message += std::string("; remeshing failed (") + error.what() + ")";
    return kept;
  }
  const bool use_remesh = (remeshed.converged && remeshed.new_folds == 0) || better(remeshed, kept);
  FairingResult& out = use_remesh ? remeshed : kept;
  const FairingResult& other = use_remesh ? kept : remeshed;
  out.message += use_remesh ? "; remeshed: " + reason
                            : "; remeshing did not help (" + other.message + ")";
  return std::move(with_both_costs(out, kept, remeshed));
}

// fair() on positions in the working scale (mesh_scale.h).
FairingResult fair_scaled(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                          const Positions* boundary_normals, const FairingOptions& options,
                          const std::vector<int>* polygon_ids) {
  switch (options.remesh) {
    case Remesh::Always:
      return fair_remeshed(V, F, free, boundary_normals, options, polygon_ids);
    case Remesh::IfNeeded:
      return fair_if_needed(V, F, free, boundary_normals, options, polygon_ids);
    case Remesh::Off:
      break;
  }
  return fair_kept(V, F, free, boundary_normals, options, polygon_ids);
}

// `solve` (of positions and the scale they were divided by) at the working scale
// (mesh_scale.h) of V; the result in V's units, the rows the solve did not move V's.
template <class Solve>
FairingResult at_working_scale(const Positions& V, const Triangles& F, Solve&& solve) {
  const double scale = working_scale(V, F, "fair");
  if (scale == 1.0) return solve(V, 1.0);
  // Divided and multiplied by a power of two: exact, the solve sees edges about 1 long.
  FairingResult result = solve(V / scale, scale);
  result.vertices *= scale;
  // Rows the solve did not move are the input's, also where V / scale was subnormal.
  const Eigen::Index n = std::min(V.rows(), result.vertices.rows());
  for (Eigen::Index v = 0; v < n; ++v)
    if (!result.free[std::size_t(v)]) result.vertices.row(v) = V.row(v);
  for (int v : result.unreferenced) result.vertices.row(v) = V.row(v);
  return result;
}

}  // namespace

void keep_connectivity(FairingResult& result, const Triangles& F, const std::vector<bool>& free) {
  result.faces = F;
  result.free = free;
  result.origin_face.assign(free.size(), -1);
  result.origin_barycentric = Positions::Zero(Eigen::Index(free.size()), 3);
}

FairingResult fair(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const Positions* boundary_normals, const FairingOptions& options,
                   const std::vector<int>* polygon_ids) {
  check_fairing_options(options);
  return at_working_scale(V, F, [&](const Positions& X, double) {
    return fair_scaled(X, F, free, boundary_normals, options, polygon_ids);
  });
}

FairingResult fair_remeshed_from(const Positions& V, const Positions& surface, const Triangles& F,
                                 const std::vector<bool>& free, const Positions* boundary_normals,
                                 const FairingOptions& options) {
  check_fairing_options(options);
  if (surface.rows() != V.rows() || !surface.allFinite())
    throw InvalidInputError("fair: the surface to remesh needs the rows of vertices, finite");
  return at_working_scale(V, F, [&](const Positions& X, double scale) {
    const Positions S = surface / scale;
    Laps laps;
    const FairingRegion input =
        extract_region(X, F, free, boundary_normals, true, nullptr, options.boundary);
    RemeshedInput first = remesh_input(input, X, S, F, free, options.boundary, true, {});
    const double L = first.mesh.target_edge_length, remesh_seconds = laps.lap();
    FairingResult result = fair_remesh(std::move(first), options, remesh_seconds);
    const double spent = remesh_seconds + laps.lap();
    if ((result.converged && result.folds == 0) || !time_left(result, options, spent))
      return result;
    // Where it did not converge or folded (a free vertex fanned over several short border
    // edges of a handle sits inside it under uniform weights), once more at a finer length.
    RemeshOptions finer;
    finer.target_edge_length = kFinerRemesh * L;
    FairingResult second;
    try {
      RemeshedInput again = remesh_input(input, X, S, F, free, options.boundary, true, finer);
      const double again_seconds = laps.lap();
      second = fair_remesh(std::move(again), options_after(options, spent), again_seconds);
    } catch (const std::exception& error) {  // keep the first
      result.message += std::string("; a remesh at 4/5 of the edge length failed (") +
                        error.what() + ")";
      return result;
    }
    const bool take = second.converged && (!result.converged || second.folds < result.folds);
    FairingResult& out = take ? second : result;
    out.message += take ? "; remeshed again at 4/5 of the edge length"
                        : "; a remesh at 4/5 of the edge length did not do better";
    return std::move(with_both_costs(out, result, second));
  });
}

RemeshedRegion remesh_followed(const Positions& V, const Positions& surface, const Triangles& F,
                               const std::vector<bool>& free, const Positions* boundary_normals,
                               BoundaryCondition boundary) {
  if (surface.rows() != V.rows() || !surface.allFinite())
    throw InvalidInputError("fair: the surface to remesh needs the rows of vertices, finite");
  const FairingRegion input =
      extract_region(V, F, free, boundary_normals, true, nullptr, boundary);
  return remesh_input(input, V, surface, F, free, boundary, true, {}).mesh;
}

}  // namespace geofair
