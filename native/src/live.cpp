// LiveFairing: a region faired again for new fixed positions, warm-started from the last
// frame (live.h); its state is live_state.h's, its remeshes live_remesh.cpp's.
#include "geofair/live.h"
#include "live_state.h"

#include "fairing_internal.h"
#include "inner_fairness.h"
#include "mesh_scale.h"
#include "parallel.h"
#include "sparse_lu.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

namespace geofair {

using namespace live_detail;

FairingResult LiveState::live_mesh_result(Positions vertices, const Positions& X0,
                                          const Positions& Y, FoldCount& folds) const {
  FairingResult result;
  result.vertices = std::move(vertices);
  keep_connectivity(result, F, free);
  result.unreferenced = unreferenced;
  result.iteration = Iteration::Newton;
  // Folds: only edges with a free vertex count, and both their triangles are the region's.
  std::vector<bool> local_free(std::size_t(region.n), false);
  std::fill(local_free.begin(), local_free.begin() + region.n_free, true);
  folds = count_folds(X0, Y, region.triangles, local_free);
  result.folds = folds.folds;
  result.new_folds = folds.new_folds;
  return result;
}

FairingResult LiveState::warm_result(const Positions& V, const Positions& X0,
                                     const Positions& Y,
                                     const IterationReport& report) const {
  FoldCount folds;
  FairingResult result = live_mesh_result(caller_positions(V, Y), X0, Y, folds);
  result.converged = true;
  result.iterations = report.iterations;
  result.iterations_per_level = {report.iterations};
  result.vertices_per_level = {region.n};
  result.residual = report.residual;
  result.stop_reason = StopReason::Converged;
  result.newton_iterations = report.iterations;
  result.message = "converged (residual " + scientific(report.residual) + ", tolerance " +
                   scientific(options.tolerance) + "); warm start from the last frame (" +
                   newton_steps(report.iterations) + ")" + fold_note(folds);
  return result;
}

namespace {

// The secant start's coefficients (c1, c2) of the last two warm frames' fixed moves a and b
// for this frame's fixed moves m, or nullopt where the last frame's alone is to be used.
template <class A, class B>
std::optional<std::pair<double, double>> two_frame_fit(const A& a, const B& b, const Positions& m) {
  const double aa = a.squaredNorm(), ab = a.cwiseProduct(b).sum(), bb = b.squaredNorm();
  const double am = a.cwiseProduct(m).sum(), bm = b.cwiseProduct(m).sum();
  const double det = aa * bb - ab * ab;
  double c1 = 0.0, c2 = 0.0;
  if (det > 1e-8 * aa * bb) {  // least squares
    c1 = (bb * am - ab * bm) / det, c2 = (aa * bm - ab * am) / det;
  } else {
    // Parallel moves (a translation along a line: b = β a, and α a the part of m along a):
    // the free vertices' response as a function of the handle's place on the line,
    // interpolated quadratically through the last three frames and evaluated at this one.
    // c1 + β c2 = α; (2, −1) for equal steps, (0, 0) for none, (−1, 0) going back.
    const double beta = ab / aa, alpha = am / aa;
    if (!(std::abs(beta) > 1e-3 && std::abs(1.0 + beta) > 1e-3)) return std::nullopt;
    const double k = alpha * (alpha + 1.0) / (1.0 + beta);
    c1 = alpha + k, c2 = -k / beta;
  }
  if (!(std::abs(c1) <= kTwoStepSecantLimit && std::abs(c2) <= kTwoStepSecantLimit))
    return std::nullopt;
  return std::make_pair(c1, c2);
}

}  // namespace

Positions LiveState::warm_start(const Positions& X0, bool secant) const {
  const int nb = region.n - region.n_free;
  Positions Y = X;
  Positions moves = X0.bottomRows(nb) - X.bottomRows(nb);
  const Positions& s1 = drag_steps.last;
  const Positions& s2 = drag_steps.before;
  if (secant && s1.rows() > 0 && moves.any() && s1.bottomRows(nb).any()) {
    // The fixed vertices' moves fitted by the last two frames' moves (two_frame_fit), the
    // free vertices moved by the same combination of those frames' responses: a drag that
    // turns at a steady rate repeats in that span (m_k = 2 cos θ m_{k−1} − m_{k−2} for a
    // rotation by θ a frame). The last frame's alone where only one warm frame precedes or
    // the fit fails.
    const auto a = s1.bottomRows(nb);
    std::optional<std::pair<double, double>> c;
    if (s2.rows() == s1.rows()) c = two_frame_fit(a, s2.bottomRows(nb), moves);
    if (!c) c = {std::clamp(a.cwiseProduct(moves).sum() / a.squaredNorm(), -kSecantLimit, kSecantLimit),
                 0.0};
    const auto [c1, c2] = *c;
    moves -= c1 * a;
    Y.topRows(region.n_free) += c1 * s1.topRows(region.n_free);
    if (c2 != 0.0) {
      moves -= c2 * s2.bottomRows(nb);
      Y.topRows(region.n_free) += c2 * s2.topRows(region.n_free);
    }
  }
  predictor->predict(moves, Y);
  Y.bottomRows(nb) = X0.bottomRows(nb);
  return Y;
}

Positions LiveState::frame_boundary(const Positions& W,
                                    const Positions* boundary_normals) {
  std::optional<Positions> normals;
  if (boundary_normals) normals = *boundary_normals;  // unit vectors: no scaling
  set_boundary_normals(region, W, F, free, normals ? &*normals : nullptr, kUpdate);
  finest->g1_normals = region.g1_normals;
  Positions X0 = gather(W, region.global);
  if (!(diagonal(X0) > 0.0))
    throw InvalidInputError(std::string(kUpdate) + ": the region has zero extent");
  return X0;
}

std::optional<IterationReport> LiveState::warm_newton(const Positions& X0, Positions& Y,
                                                      Phases& phases, Laps& laps,
                                                      WarmStarts& starts) {
  const double L = diagonal(X0);
  if (options.inner_fairness != InnerFairness::Uniform) {
    InnerFairnessWeights lambda = inner_fairness_weights(*finest, X0, options.inner_fairness);
    if (!construction->set_lambda(lambda))  // other intrinsic edges: another pattern
      construction = std::make_unique<Construction>(*finest, std::move(lambda), options, L);
  }
  construction->set_boundary(finest->g1_normals, L);
  NewtonRun run;
  run.max_iterations = live.max_warm_steps;
  run.tolerance = options.tolerance;
  run.patience = options.tuning.newton.patience;
  run.polish_at_convergence = true;
  run.warm = true;
  run.stop = [this] { return out_of_time(); };
  std::optional<IterationReport> report;  // of the last start that ran
  // The secant start first; where Newton does not converge from it or fails (a drag whose
  // response changes, as triangles squeeze), the harmonic one.
  const bool secant_first =
      drag_steps.last.rows() > 0 && drag_steps.last.bottomRows(region.n - region.n_free).any();
  for (const bool secant : {true, false}) {
    if (secant && !secant_first) continue;
    if (!secant && out_of_time()) break;  // the secant start spent the frame's time
    if (secant_first && !secant) {
      starts.harmonic_after_secant = true;
      starts.secant_steps = report ? report->iterations : 0;
    }
    Y = warm_start(X0, secant);
    // The secant start carries the last frame's tangential response: the polish near
    // convergence is enough (the harmonic one squeezes vertices against a moving handle).
    run.skip_relaxation = secant;
    phases.emplace_back("boundary data and predictor", laps.lap());
    try {
      report = construction->run_newton(Y, run);
    } catch (const SolverError& error) {
      if (!secant) throw;
      starts.secant_failure = error.what();
      report.reset();
      continue;
    }
    laps.lap();  // run_newton's own seconds, below
    phases.emplace_back("warm inner fairness", report->relax_seconds);
    phases.emplace_back("warm Newton steps", report->step_seconds);
    phases.emplace_back("warm polishes", report->polish_seconds);
    if ((report->converged && Y.topRows(region.n_free).allFinite()) || report->cancelled) break;
  }
  if (report && starts.harmonic_after_secant) report->iterations += starts.secant_steps;
  return report;
}

std::optional<FairingResult> LiveState::warm_frame(const Positions& V,
                                                   const Positions& W,
                                                   const Positions* boundary_normals,
                                                   Phases& phases, std::string& why) {
  Laps laps;
  const Positions X0 = frame_boundary(W, boundary_normals);
  Positions Y;
  std::optional<IterationReport> report;
  WarmStarts starts;
  // A numerical failure anywhere in the warm start (the weights, a new construction, Newton's
  // steps) leaves the frame to the cold path.
  try {
    report = warm_newton(X0, Y, phases, laps, starts);
  } catch (const SolverError& error) {
    why = error.what();
    return std::nullopt;
  }
  if (!report) {
    why = starts.secant_failure.empty()
              ? "stopped at the time limit before it started"
              : "the secant start failed (" + starts.secant_failure +
                    "), and the time limit came before the harmonic one";
    return std::nullopt;
  }
  if (!report->converged || !Y.topRows(region.n_free).allFinite()) {
    why = "residual " + scientific(report->residual) + " after " +
          starts.steps_text(report->iterations) +
          (out_of_time() ? ", stopped at the time limit" : "");
    return std::nullopt;
  }
  pending = Y;  // X becomes Y where update() returns this frame (take_warm)
  FairingResult result = warm_result(V, X0, Y, *report);
  if (starts.harmonic_after_secant) result.message += "; " + starts.steps_text(report->iterations);
  phases.emplace_back("result", laps.lap());
  return result;
}

void LiveState::prepare(Triangles F_new, std::vector<bool> free_new,
                        std::optional<std::vector<int>> polygons, const Positions& V,
                        const Positions* boundary_normals) {
  // Everything is built first; the state then changes by moves alone, which do not throw.
  Positions V0_new = V / scale;
  FairingRegion region_new = extract_region(V0_new, F_new, free_new, boundary_normals, true,
                                            polygons ? &*polygons : nullptr, options.boundary);
  auto finest_new = std::make_unique<FairingRegion>(region_new);
  std::iota(finest_new->global.begin(), finest_new->global.end(), 0);
  const Positions X0 = gather(V0_new, region_new.global);
  auto construction_new = std::make_unique<Construction>(
      *finest_new, inner_fairness_weights(*finest_new, X0, options.inner_fairness), options,
      diagonal(X0));
  construction_new->prepare_newton();  // the symbolic analysis, once per mesh
  auto predictor_new = std::make_unique<DisplacementPredictor>(*finest_new);
  std::vector<bool> used(free_new.size(), false);
  for (Eigen::Index f = 0; f < F_new.rows(); ++f)
    for (int c = 0; c < 3; ++c) used[std::size_t(F_new(f, c))] = true;
  std::vector<int> used_fixed_new;
  for (std::size_t v = 0; v < free_new.size(); ++v)
    if (used[v] && !free_new[v]) used_fixed_new.push_back(int(v));
  F = std::move(F_new);
  free = std::move(free_new);
  polygon_ids = std::move(polygons);
  V0 = std::move(V0_new);
  region = std::move(region_new);
  construction = std::move(construction_new);  // before finest: they refer to it
  predictor = std::move(predictor_new);
  finest = std::move(finest_new);
  used_fixed = std::move(used_fixed_new);
}

LiveFairing::LiveFairing(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                         const Positions* boundary_normals, const FairingOptions& options,
                         const LiveOptions& live, const std::vector<int>* polygon_ids)
    : state_(std::make_unique<LiveState>()) {
  LiveState& s = *state_;
  if (options.remesh == Remesh::Always)
    throw InvalidInputError("LiveFairing: remesh must be off or if_needed");
  if (options.remesh == Remesh::IfNeeded && live.details)
    throw InvalidInputError("LiveFairing: details=True keeps the input's triangles (its details "
                            "are coded per vertex): remesh must be off");
  if (live.max_warm_steps < 1) throw InvalidInputError("LiveFairing: max_warm_steps must be >= 1");
  s.input_rows = int(V.rows());
  if (polygon_ids) s.polygon_ids = *polygon_ids;
  s.options = options;
  s.options.progress = nullptr;
  s.live = live;
  // The cold solve first: fair's checks of the input and options, and the first frame, on
  // the input's triangles (the frames remesh).
  FairingOptions kept = s.options;
  kept.remesh = Remesh::Off;
  FairingResult first = fair(V, F, free, boundary_normals, kept, polygon_ids);
  s.options.deadline.reset();  // a point in time: the constructor's solve alone
  s.scale = working_scale(V, F, "LiveFairing");
  s.prepare(F, free, s.polygon_ids, V, boundary_normals);
  if (live.details) {
    // The input's details over its base (the cold fair): the first frame is the input.
    if (!first.converged)
      throw SolverError("LiveFairing: details=True needs the input's base, and its fair did not "
                        "converge (" + first.message + ")");
    s.X = gather(first.vertices / s.scale, s.region.global);
    s.details = std::make_unique<DetailCoding>(*s.finest, s.X, gather(s.V0, s.region.global));
    s.warm = true;
    first.vertices = V;
    s.last = std::move(first);
    return;
  }
  if (first.converged)
    s.adopt(first);
  else
    s.last = std::move(first);
  s.input_folds = s.last.folds;
}

LiveFairing::~LiveFairing() = default;
LiveFairing::LiveFairing(LiveFairing&&) noexcept = default;
LiveFairing& LiveFairing::operator=(LiveFairing&&) noexcept = default;

FairingResult LiveFairing::result() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->last;
}
int LiveFairing::frames() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->frames;
}
int LiveFairing::cold_frames() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->cold_frames;
}
int LiveFairing::remeshes() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->remeshes;
}

FairingResult LiveState::unsolved_frame(const Positions& V, const Positions& W,
                                        Phases& phases, const std::string& why) {
  Positions vertices = last.vertices;
  for (std::size_t v = 0; v < free.size(); ++v)  // fixed rows bit-identical to V's
    if (!free[v]) vertices.row(Eigen::Index(v)) = V.row(Eigen::Index(v));
  // Folds and residual of the positions (with details: of the base, as a warm frame's).
  const Positions X0 = gather(W, region.global);
  Positions Y;
  if (warm) {
    Y = X;
    Y.bottomRows(region.n - region.n_free) = X0.bottomRows(region.n - region.n_free);
  } else {
    Y = gather(vertices / scale, region.global);
  }
  FoldCount folds;
  FairingResult result = live_mesh_result(std::move(vertices), X0, Y, folds);
  double residual = std::numeric_limits<double>::max();  // where it cannot be evaluated
  try {
    construction->set_boundary(finest->g1_normals, diagonal(X0));
    residual = construction->evaluate(Y);
  } catch (const std::exception&) {
  }
  result.residual = std::isfinite(residual) ? residual : std::numeric_limits<double>::max();
  result.iterations_per_level = {0};
  result.vertices_per_level = {region.n};
  result.stop_reason = StopReason::TimeLimit;
  result.message = "stopped at the time limit of " + scientific(deadline->seconds) +
                   " s before a solve anew (residual " + scientific(result.residual) +
                   "; the warm start did not converge: " + why +
                   "): the free vertices are the last converged frame's" + fold_note(folds) +
                   frame_note;
  result.phase_seconds = std::move(phases);
  ++frames;
  return result;
}

FairingResult LiveState::cold_frame(const Positions& V, const Positions& W,
                                    const Positions* boundary_normals,
                                    const std::string& why) const {
  FairingOptions kept = timed_options();
  kept.remesh = Remesh::Off;
  FairingResult cold =
      fair(scale * W, F, free, boundary_normals, kept, polygon_ids ? &*polygon_ids : nullptr);
  for (std::size_t v = 0; v < free.size(); ++v)  // fixed rows bit-identical to V's
    if (!free[v]) cold.vertices.row(Eigen::Index(v)) = V.row(Eigen::Index(v));
  cold.unreferenced = unreferenced;
  cold.message += "; cold path (fair): the warm start did not converge (" + why + ")";
  return cold;
}

void LiveState::check_input(const Positions& V_in, const Positions* normals_in,
                            std::optional<Positions>& padded,
                            std::optional<Positions>& padded_normals) const {
  const Eigen::Index n = Eigen::Index(free.size());
  if (V_in.rows() != n && V_in.rows() != input_rows)
    throw InvalidInputError(std::string(kUpdate) + ": vertices has " +
                            std::to_string(V_in.rows()) + " rows, the mesh " +
                            (n == input_rows ? std::to_string(n)
                                             : std::to_string(input_rows) + " or " +
                                                   std::to_string(n) + " (remeshed)") +
                            " vertices");
  if (normals_in && normals_in->rows() != V_in.rows())
    throw InvalidInputError(std::string(kUpdate) + ": boundary_normals has " +
                            std::to_string(normals_in->rows()) + " rows for " +
                            std::to_string(V_in.rows()) + " vertices");
  if (V_in.rows() != n) {
    padded = live_rows(V_in, last.vertices);
    if (normals_in) padded_normals = live_rows(*normals_in, Positions::Zero(n, 3));
  }
  if (!unreferenced.empty()) {  // rows in no face keep their last positions, not the caller's
    if (!padded) padded = V_in;
    for (int v : unreferenced) padded->row(v) = last.vertices.row(v);
  }
  const Positions& V = padded ? *padded : V_in;
  for (int v : used_fixed)
    if (!V.row(v).allFinite())
      throw InvalidInputError(std::string(kUpdate) + ": vertex " + std::to_string(v) +
                              " has a non-finite coordinate");
}

FairingResult LiveFairing::update(const Positions& V_in, const Positions* normals_in,
                                  double time_limit) {
  LiveState& s = *state_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (std::isnan(time_limit)) throw InvalidInputError(std::string(kUpdate) + ": time_limit is NaN");
  // This frame's deadline (none for an infinite limit), cleared on the way out.
  struct FrameDeadline {
    LiveState& s;
    ~FrameDeadline() { s.deadline.reset(); }
  } frame_deadline{s};
  if (time_limit >= 0.0 && std::isfinite(time_limit))
    s.deadline = FairingOptions::Deadline{
        std::chrono::steady_clock::now() +
            std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                std::chrono::duration<double>(std::min(time_limit, 1e9))),
        time_limit};
  std::optional<Positions> padded, padded_normals;
  s.check_input(V_in, normals_in, padded, padded_normals);
  const Positions& V = padded ? *padded : V_in;  // the live mesh's rows
  const Positions* boundary_normals = padded_normals ? &*padded_normals : normals_in;
  set_loop_threads(solve_threads());
  const BlasThreads blas_threads(1);
  Laps laps;
  const Positions W = s.frame_input(V);
  Phases phases;
  std::string why = "the last frame did not converge";
  // With remesh="if_needed", a converged warm frame with folds (RemeshTrigger::wants) is
  // kept only where remeshing does not do better.
  std::optional<FairingResult> folded;
  std::optional<RemeshFailure> first_failed;
  s.frame_note.clear();
  const RemeshTrigger trigger = s.trigger;  // a frame that raises leaves it as it was
  try {
    if (s.warm) {
      if (auto result = s.remesh_first(V, boundary_normals, phases, first_failed))
        return std::move(*result);
      // The boundary data are the frame's own.
      if (auto result = s.warm_frame(V, W, boundary_normals, phases, why)) {
        if (s.options.remesh != Remesh::IfNeeded ||
            !s.trigger.wants(result->folds, s.input_folds, s.frames)) {
          s.take_warm(*result, phases);
          s.check_degenerate();
          return std::move(*result);
        }
        why = std::to_string(result->folds) + " folded edges, the input " +
              std::to_string(s.input_folds);
        folded = std::move(result);
      }
    }
    const double warm_seconds = laps.lap();
    if (warm_seconds > 0.0) phases.emplace_back("warm start", warm_seconds);
    return s.solve_anew(V, W, boundary_normals, std::move(folded), phases, why, first_failed);
  } catch (...) {
    s.trigger = trigger;
    throw;
  }
}

void LiveState::take_warm(FairingResult& result, Phases& phases) {
  result.message += frame_note;
  result.phase_seconds = std::move(phases);
  drag_steps.push(pending - X);
  X = std::move(pending);
  last = result;
  ++frames;
}

void LiveState::take_anew(FairingResult& result, Phases& phases,
                          const Positions* boundary_normals) {
  result.message += frame_note;
  phases.insert(phases.end(), result.phase_seconds.begin(), result.phase_seconds.end());
  result.phase_seconds = std::move(phases);
  if (result.converged && result.remeshed) {
    switch_mesh(result, boundary_normals);
    ++remeshes;
  }
  ++frames;
  if (result.converged) adopt(result);  // the live mesh and warm start stay otherwise
}

FairingResult LiveState::solve_anew(const Positions& V, const Positions& W,
                                    const Positions* boundary_normals,
                                    std::optional<FairingResult> folded,
                                    Phases& phases, std::string& why,
                                    const std::optional<RemeshFailure>& first_failed) {
  // Remeshed from the last converged frame's surface: triangles that fit the dragged shape.
  const bool wanted = options.remesh == Remesh::IfNeeded && warm && !out_of_time();
  // After a remesh that threw, the same remesh would throw again.
  bool remesh = wanted && !(first_failed && first_failed->remesh_threw);
  if (remesh && !first_failed) {  // warm on the remesh; where that fails, its cold fair
    const std::string reason =
        std::string(folded ? "the warm start folded: " : "the warm start did not converge: ") + why;
    RemeshFailure failure;
    if (auto result = warm_remesh(V, boundary_normals, reason, phases, failure)) {
      take_warm_remesh(*result, phases);
      return std::move(*result);
    }
    why += "; " + failure.why;
    remesh = !failure.remesh_threw;
  }
  std::optional<FairingResult> remeshed;
  if (remesh && !out_of_time()) remeshed = try_remesh(V, boundary_normals, bool(folded), why);
  // Taken where it converged, unless the warm frame converged with as few folds: the cold
  // path on the live mesh, whose triangles no longer fit, folds as the warm start did.
  const bool use_remesh = remeshed && remeshed->converged &&
                          (!folded || remeshed->folds < folded->folds);
  if (wanted)  // a remesh that leaves folds or fails is tried again kRemeshRetry frames on
    trigger.folds_tried = use_remesh && remeshed->folds <= input_folds ? -kRemeshRetry : frames;
  if (use_remesh) {
    take_anew(*remeshed, phases, boundary_normals);
    return std::move(*remeshed);
  }
  if (remeshed) why += "; remeshing did not help (" + remeshed->message + ")";
  if (folded) {  // remeshing did not do better: the folded warm frame stands
    if (const auto note = why.find("; "); note != std::string::npos)
      folded->message += why.substr(note);  // what the remesh did
    take_warm(*folded, phases);
    return std::move(*folded);
  }
  if (out_of_time()) return unsolved_frame(V, W, phases, why);
  FairingResult cold = cold_frame(V, W, boundary_normals, why);
  ++cold_frames;  // (take_anew counts the frame)
  const bool with_details = bool(details);
  take_anew(cold, phases, boundary_normals);
  if (!cold.converged && with_details)
    cold.vertices = caller_positions(cold.vertices, gather(cold.vertices / scale, region.global));
  return cold;
}

}  // namespace geofair
