// LiveFairing: a region faired again for new fixed positions, warm-started from the last
// frame (live.h).
#include "geofair/live.h"

#include "common.h"
#include "construction.h"
#include "displacement_predictor.h"
#include "fairing_internal.h"
#include "inner_fairness.h"
#include "mesh_scale.h"
#include "nested_iteration.h"
#include "parallel.h"
#include "region.h"
#include "sparse_lu.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <numeric>
#include <optional>
#include <string>

namespace geofair {
namespace {

constexpr const char* kUpdate = "LiveFairing.update";

std::string scientific(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1e", x);
  return text;
}

std::string steps(int n) { return std::to_string(n) + (n == 1 ? " Newton step" : " Newton steps"); }

// The bounding-box diagonal of the region's positions X (the residual's length L, fairing.h).
double diagonal(const Positions& X) {
  return (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
}

// Frames between remesh attempts for folds that a remesh left (LiveFairing::State).
constexpr int kRemeshRetry = 3;

// The secant predictor's largest multiple of the last frame's response (warm_frame).
constexpr double kSecantLimit = 2.0;

// With remesh IfNeeded, a converged frame whose smallest triangle angle falls below this
// fraction of the live mesh's own remeshes at the next frame: a handle dragged towards the
// border squeezes the triangles between them, and their angles collapse a few frames before
// they fold (docs/LIVE.md, "Remeshing frames").
constexpr double kDegenerateAngle = 1.0 / 3.0;

// The smallest angle of triangles T (rows into X), radians.
double smallest_angle(const Positions& X, const Triangles& T) {
  double smallest = M_PI;
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 3; ++c) {
      const Eigen::RowVector3d a = X.row(T(t, (c + 1) % 3)) - X.row(T(t, c));
      const Eigen::RowVector3d b = X.row(T(t, (c + 2) % 3)) - X.row(T(t, c));
      smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)));
    }
  return smallest;
}

// Detail coding (Kobbelt et al. 1998; Botsch & Kobbelt 2004): the offsets x_i − b_i of a
// region x from its base b, per free vertex in the base's local frame (n_i, t_i, n_i × t_i),
// so that a new base b' gets them back in its own frames: x'_i = b'_i + α n'_i + β t'_i +
// γ n'_i × t'_i. n_i is the area-weighted normal of b's triangles at i, t_i the direction to
// the first ring neighbour (with a tangential part) projected into the tangent plane.
class DetailCoding {
 public:
  // base, x: #region×3 (local ids); only the free rows are coded.
  DetailCoding(const FairingRegion& region, const Positions& base, const Positions& x)
      : region_(region), coefficients_(region.n_free, 3) {
    const Positions frames = local_frames(base);
    for (int i = 0; i < region.n_free; ++i) {
      const Vec3 d = (x.row(i) - base.row(i)).transpose();
      const Vec3 n = frames.row(2 * i).transpose(), t = frames.row(2 * i + 1).transpose();
      coefficients_.row(i) << d.dot(n), d.dot(t), d.dot(n.cross(t));
    }
  }

  // The free rows of `base` with the details added in its frames.
  void decode(Positions& base) const {
    const Positions frames = local_frames(base);
    for (int i = 0; i < region_.n_free; ++i) {
      const Vec3 n = frames.row(2 * i).transpose(), t = frames.row(2 * i + 1).transpose();
      const Eigen::RowVector3d c = coefficients_.row(i);
      base.row(i) += (c(0) * n + c(1) * t + c(2) * n.cross(t)).transpose();
    }
  }

 private:
  // Rows 2i and 2i + 1: the unit normal and tangent of free vertex i at X (zero where
  // degenerate: its details are then dropped, not made up).
  Positions local_frames(const Positions& X) const {
    const OneRings& rings = region_.rings;
    Positions normals = Positions::Zero(region_.n, 3);
    for (Eigen::Index f = 0; f < region_.triangles.rows(); ++f) {
      const int a = region_.triangles(f, 0), b = region_.triangles(f, 1),
                c = region_.triangles(f, 2);
      const Eigen::RowVector3d area = (X.row(b) - X.row(a)).cross(X.row(c) - X.row(a));
      normals.row(a) += area, normals.row(b) += area, normals.row(c) += area;
    }
    Positions frames = Positions::Zero(2 * region_.n_free, 3);
    for (int i = 0; i < region_.n_free; ++i) {
      const double length = normals.row(i).norm();
      if (!(length > 0.0)) continue;
      const Vec3 n = normals.row(i).transpose() / length;
      for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k) {
        const Vec3 e = (X.row(rings.ring[k]) - X.row(i)).transpose();
        const Vec3 t = e - e.dot(n) * n;
        if (t.norm() > 1e-3 * e.norm()) {
          frames.row(2 * i) = n.transpose();
          frames.row(2 * i + 1) = t.normalized().transpose();
          break;
        }
      }
    }
    return frames;
  }

  const FairingRegion& region_;
  Positions coefficients_;  // #V_I×3: (α, β, γ), mesh units / scale
};

}  // namespace

struct LiveFairing::State {
  Triangles F;              // the live mesh: the input's, or the last remesh's
  std::vector<bool> free;
  int input_rows = 0;       // the constructor's vertex count (update accepts it or the live mesh's)
  int input_folds = 0;      // folded edges of the constructor's frame (the input's own)
  int remesh_tried = -kRemeshRetry;  // the frame (count) of the last remesh that left folds
  double mesh_angle = 0.0;  // the smallest angle of the last frame solved anew, radians
  bool remesh_next = false;  // the last frame's triangles degenerated (kDegenerateAngle)
  int degenerate_tried = -kRemeshRetry;  // the frame of the last such remesh that failed
  std::vector<int> unreferenced;  // rows in no face since a remesh (their last positions kept)

  // Whether a converged warm frame with `folds` folded edges is remeshed (remesh
  // IfNeeded): more than the input has, and kRemeshRetry frames after the last remesh
  // attempt that left folds (or failed).
  bool wants_remesh(int folds) const {
    return folds > input_folds && frames - remesh_tried >= kRemeshRetry;
  }
  std::optional<std::vector<int>> polygon_ids;
  FairingOptions options;  // the user's, without a progress callback
  LiveOptions live;
  double scale = 1.0;       // working_scale of the construction's V: positions are V / scale
  Positions V0;             // the construction's V / scale: the free rows' original positions
  std::vector<int> used_fixed;  // fixed vertices of a triangle, checked for finiteness
  FairingRegion region;     // in the caller's ids (global), its boundary normals the last frame's
  // The same with region-local ids: what the construction and the predictor work on (on
  // the heap: they keep a reference to it, and prepare() builds a new one before it swaps).
  std::unique_ptr<FairingRegion> finest;
  std::unique_ptr<Construction> construction;  // kept between frames (the warm start)
  std::unique_ptr<DisplacementPredictor> predictor;
  std::unique_ptr<DetailCoding> details;  // details=True: the input's details over its base
  Positions X;              // the last converged frame's region positions (local ids, / scale);
                            // with details its base
  bool warm = false;        // X is a converged solution to start from
  Positions pending;         // a warm frame's solution until update() takes it (X's update)
  Positions last_step;      // the last warm frame's change of X (#region×3; empty after a cold
                            // frame), the secant predictor's
  FairingResult last;
  int frames = 0, cold_frames = 0, remeshes = 0;
  // The end of the frame being solved (update()'s time_limit), if it has one.
  std::optional<FairingOptions::Deadline> deadline;
  mutable std::mutex mutex;  // update() and result() take turns

  // Makes (F_new, free_new) the live mesh with V0 = V / scale (V: its rows): the region,
  // the construction with its symbolic analysis, the predictor, the fixed vertices to check.
  // Throws (InvalidInputError, SolverError) before it changes the state.
  void prepare(Triangles F_new, std::vector<bool> free_new,
               std::optional<std::vector<int>> polygons, const Positions& V,
               const Positions* boundary_normals);

  // The caller's V (input_rows or the live mesh's rows) as the live mesh's rows: rows the
  // caller's mesh lacks (rows a remesh appended, free) are taken from `fill`.
  Positions live_rows(const Positions& V, const Positions& fill) const {
    if (V.rows() == fill.rows()) return V;
    Positions out = fill;
    out.topRows(V.rows()) = V;
    return out;
  }

  // What a frame's remesh starts from: V's fixed rows (check_input: rows in no face the last
  // frame's) and the last converged frame's free rows (the caller's are not read).
  Positions remesh_source(const Positions& V) const {
    Positions U = V;
    for (std::size_t v = 0; v < free.size(); ++v)
      if (free[v]) U.row(Eigen::Index(v)) = last.vertices.row(Eigen::Index(v));
    return U;
  }

  // The remesh of a frame (Remesh::IfNeeded): fair_remeshed_from, the last converged
  // frame's surface remeshed, then faired with the frame's fixed positions.
  FairingResult remesh_frame(const Positions& V, const Positions* boundary_normals) const;

  // The live mesh's parts that prepare() replaces, with the warm start on them.
  struct LiveMesh {
    Triangles F;
    std::vector<bool> free;
    std::optional<std::vector<int>> polygon_ids;
    Positions V0;
    FairingRegion region;
    std::unique_ptr<FairingRegion> finest;
    std::unique_ptr<Construction> construction;  // after finest: it refers to it
    std::unique_ptr<DisplacementPredictor> predictor;
    std::vector<int> used_fixed, unreferenced;
    Positions X, pending, last_step;
    double mesh_angle = 0.0;
  };
  // Exchanges the live mesh with `other` (a warm remesh keeps the old one to go back to).
  void swap_mesh(LiveMesh& other) noexcept;

  // The remesh of remesh_frame, its new free vertices moved with the fixed ones, made the
  // live mesh and solved by a warm frame from there (Newton's method from the remesh, no
  // hierarchy); nullopt, the live mesh as it was, where that does not converge without more
  // folds than the input, or the remesh fails (`failure` says which). `reason`: why the
  // frame remeshes.
  std::optional<FairingResult> warm_remesh(const Positions& V, const Positions* boundary_normals,
                                           const std::string& reason, Phases& phases,
                                           std::string& failure);

  // A warm_remesh result taken: as take_warm, on the new mesh, whose result is the
  // reference of later frames (switch_mesh).
  void take_warm_remesh(FairingResult& result, Phases& phases);

  // After a warm frame taken (remesh IfNeeded): whether its triangles degenerated
  // (kDegenerateAngle), so that the next frame remeshes first; `reason` says how.
  void check_degenerate();
  std::string degenerate_reason;
  // What the frame being solved tried before (a failed remesh): appended to its message.
  std::string frame_note;

  // update()'s checks of its input. Where V_in (and normals_in) has the input's rows and
  // the live mesh more (a remesh), or rows are in no face, `padded` (`padded_normals`) gets
  // the live mesh's rows (those in no face their last positions).
  void check_input(const Positions& V_in, const Positions* normals_in,
                   std::optional<Positions>& padded,
                   std::optional<Positions>& padded_normals) const;

  // The options of the frame's solve anew: with a frame time limit, its deadline (fair's
  // own limit, automatic or explicit, stays).
  FairingOptions timed_options() const {
    FairingOptions timed = options;
    timed.deadline = deadline;
    return timed;
  }
  bool out_of_time() const {
    return deadline && std::chrono::steady_clock::now() >= deadline->at;
  }

  // The frame whose warm start spent its time limit: unconverged, V's fixed rows and the
  // last converged frame's free rows (W the frame's input, / scale).
  FairingResult unsolved_frame(const Positions& V, const Positions& W, Phases& phases,
                               const std::string& why);

  // The cold path: fair() of the frame's input W (/ scale) on the live mesh, its whole
  // schedule; V's fixed rows, `why` the warm start's end.
  FairingResult cold_frame(const Positions& V, const Positions& W,
                           const Positions* boundary_normals, const std::string& why) const;

  // remesh_frame with the reason in its message (`folded`: the warm start converged with
  // more folds; else it did not converge, `why`); nullopt (why extended) where it threw.
  std::optional<FairingResult> try_remesh(const Positions& V, const Positions* boundary_normals,
                                          bool folded, std::string& why) const;

  // Makes a remeshed result's mesh the live one (prepare; V0, the reference of later
  // frames' input and conformal weights, is the result itself: the remesh's own positions
  // before its fair lie on the last frame's surface, stretched at the handle, and conformal
  // weights of them folded the next frames; boundary_normals: the old mesh's rows or nullptr).
  void switch_mesh(const FairingResult& result, const Positions* boundary_normals);

  // The frame's input (/ scale): V's fixed rows, the original free rows.
  Positions frame_input(const Positions& V) const {
    Positions W = V / scale;
    for (int i = 0; i < region.n_free; ++i) W.row(region.global[i]) = V0.row(region.global[i]);
    return W;
  }

  // The caller's positions of the result: V's rows, the free rows from the region's Y (with
  // details, Y's base with the details added).
  Positions caller_positions(const Positions& V, Positions Y) const {
    if (details) details->decode(Y);
    Positions out = V;
    for (int i = 0; i < region.n_free; ++i) out.row(region.global[i]) = scale * Y.row(i);
    return out;
  }

  // The warm start adopts a converged cold result (caller's positions; with details its base,
  // which gets them here).
  void adopt(FairingResult& result) {
    X = gather(result.vertices / scale, region.global);
    if (options.remesh == Remesh::IfNeeded) mesh_angle = smallest_angle(X, region.triangles);
    warm = true;
    last_step.resize(0, 3);
    if (details) result.vertices = caller_positions(result.vertices, X);
    last = result;
  }

  // A result on the live mesh (not remeshed) with the caller's `vertices`, which are Y
  // (region-local, / scale); `folds` Y's against X0.
  FairingResult live_mesh_result(Positions vertices, const Positions& X0, const Positions& Y,
                                 FoldCount& folds) const;

  // The FairingResult of a converged warm start Y (region-local, / scale) from X0.
  FairingResult warm_result(const Positions& V, const Positions& X0, const Positions& Y,
                            const IterationReport& report) const;

  // The start of a warm frame for the region positions X0 (its fixed rows the frame's): the
  // last frame, its free vertices moved with the fixed ones (the predictor). With `secant`, the
  // part α·m of the fixed vertices' moves along the last warm frame's moves m brings α times
  // that frame's free response (a steady drag repeats its response), the rest its harmonic
  // extension; else the harmonic extension of all of it.
  Positions warm_start(const Positions& X0, bool secant) const;

  // A frame's boundary data for its input W (/ scale): the G1 normals (the given ones, or
  // estimated from W); returns the region's rows of W. InvalidInputError for a region of zero
  // extent.
  Positions frame_boundary(const Positions& W, const Positions* boundary_normals);

  // Newton's method from the warm start for the region positions X0 (frame_boundary's):
  // from the secant start, and where Newton does not converge from it or fails, from the
  // harmonic one (`retried`); Y its solution, `phases` its phases from `laps`. The
  // construction takes the frame's boundary and, for conformal inner fairness, the weights
  // of X0. SolverError where the harmonic start fails.
  IterationReport warm_newton(const Positions& X0, Positions& Y, Phases& phases, Laps& laps,
                              bool& retried);

  // The warm start of one frame from X for the frame's input W (/ scale); nullopt where it
  // did not converge (`why` then says how it ended).
  std::optional<FairingResult> warm_frame(const Positions& V, const Positions& W,
                                          const Positions* boundary_normals, Phases& phases,
                                          std::string& why);

  // A warm frame's result taken, `phases` its phases: its solution (pending) becomes X.
  void take_warm(FairingResult& result, Phases& phases);

  // A frame solved anew (remeshed or cold) taken, its phases after `phases`: a converged one
  // becomes the warm start, on its mesh where remeshed (boundary_normals: the frame's rows).
  void take_anew(FairingResult& result, Phases& phases, const Positions* boundary_normals);

  // The frame whose warm start did not converge or, with `folded`, converged with more folded
  // edges than the input: with remesh IfNeeded remeshed where that converges with fewer
  // folds, else the folded warm frame, else the cold path; `why` the warm start's end,
  // extended by what the remesh did. `warm_remeshed`: this frame's warm remesh has failed
  // already (update's remesh before the triangles fold), so only its cold fair is tried.
  FairingResult solve_anew(const Positions& V, const Positions& W,
                           const Positions* boundary_normals, std::optional<FairingResult> folded,
                           Phases& phases, std::string& why, bool warm_remeshed);
};

FairingResult LiveFairing::State::live_mesh_result(Positions vertices, const Positions& X0,
                                                   const Positions& Y, FoldCount& folds) const {
  FairingResult result;
  result.vertices = std::move(vertices);
  result.faces = F;
  result.free = free;
  result.unreferenced = unreferenced;
  result.origin_face.assign(free.size(), -1);
  result.origin_barycentric = Positions::Zero(Eigen::Index(free.size()), 3);
  result.iteration = Iteration::Newton;
  // Folds: only edges with a free vertex count, and both their triangles are the region's.
  std::vector<bool> local_free(std::size_t(region.n), false);
  std::fill(local_free.begin(), local_free.begin() + region.n_free, true);
  folds = count_folds(X0, Y, region.triangles, local_free);
  result.folds = folds.folds;
  result.new_folds = folds.new_folds;
  return result;
}

FairingResult LiveFairing::State::warm_result(const Positions& V, const Positions& X0,
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
                   steps(report.iterations) + ")" + fold_note(folds);
  return result;
}

Positions LiveFairing::State::warm_start(const Positions& X0, bool secant) const {
  const int nb = region.n - region.n_free;
  Positions Y = X;
  Positions moves = X0.bottomRows(nb) - X.bottomRows(nb);
  const double last = secant && last_step.rows() > 0 ? last_step.bottomRows(nb).squaredNorm() : 0.0;
  if (last > 0.0) {
    const double alpha = std::clamp(moves.cwiseProduct(last_step.bottomRows(nb)).sum() / last,
                                    -kSecantLimit, kSecantLimit);
    moves -= alpha * last_step.bottomRows(nb);
    Y.topRows(region.n_free) += alpha * last_step.topRows(region.n_free);
  }
  predictor->predict(moves, Y);
  Y.bottomRows(nb) = X0.bottomRows(nb);
  return Y;
}

Positions LiveFairing::State::frame_boundary(const Positions& W,
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

IterationReport LiveFairing::State::warm_newton(const Positions& X0, Positions& Y,
                                                Phases& phases, Laps& laps, bool& retried) {
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
  IterationReport report;
  // The secant start first; where Newton does not converge from it or fails (a drag whose
  // response changes, as triangles squeeze), the harmonic one.
  const bool secant_first =
      last_step.rows() > 0 && last_step.bottomRows(region.n - region.n_free).any();
  for (const bool secant : {true, false}) {
    if (secant && !secant_first) continue;
    if (!secant && out_of_time()) break;  // the secant start spent the frame's time
    retried = secant_first && !secant;
    Y = warm_start(X0, secant);
    // The secant start carries the last frame's tangential response: the polish at
    // convergence is enough (the harmonic one squeezes vertices against a moving handle).
    run.skip_relaxation = secant;
    phases.emplace_back("boundary data and predictor", laps.lap());
    try {
      report = construction->run_newton(Y, run);
    } catch (const SolverError&) {
      if (!secant) throw;
      report = IterationReport();
      continue;
    }
    laps.lap();  // run_newton's own seconds, below
    phases.emplace_back("warm inner fairness", report.relax_seconds);
    phases.emplace_back("warm Newton steps", report.step_seconds);
    phases.emplace_back("warm polishes", report.polish_seconds);
    if ((report.converged && Y.topRows(region.n_free).allFinite()) || report.cancelled) break;
  }
  return report;
}

std::optional<FairingResult> LiveFairing::State::warm_frame(const Positions& V,
                                                            const Positions& W,
                                                            const Positions* boundary_normals,
                                                            Phases& phases, std::string& why) {
  Laps laps;
  const Positions X0 = frame_boundary(W, boundary_normals);
  Positions Y;
  IterationReport report;
  bool retried = false;
  // A numerical failure anywhere in the warm start (the weights, a new construction, Newton's
  // steps) leaves the frame to the cold path.
  try {
    report = warm_newton(X0, Y, phases, laps, retried);
  } catch (const SolverError& error) {
    why = error.what();
    return std::nullopt;
  }
  if (!report.converged || !Y.topRows(region.n_free).allFinite()) {
    if (report.iterations == 0 && out_of_time())  // its residual was not evaluated
      why = "stopped at the time limit before its first Newton step";
    else
      why = "residual " + scientific(report.residual) + " after " + steps(report.iterations) +
            (out_of_time() ? ", stopped at the time limit" : "");
    return std::nullopt;
  }
  pending = Y;  // X becomes Y where update() returns this frame (take_warm)
  FairingResult result = warm_result(V, X0, Y, report);
  if (retried)
    result.message += "; from the harmonic predictor (Newton did not converge from the secant one)";
  phases.emplace_back("result", laps.lap());
  return result;
}

void LiveFairing::State::prepare(Triangles F_new, std::vector<bool> free_new,
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

FairingResult LiveFairing::State::remesh_frame(const Positions& V,
                                               const Positions* boundary_normals) const {
  // fair()'s remesh (at the length of the region's border edges, which also resolves the
  // strip that a handle dragged towards the border squeezes) of the last converged frame,
  // whose free vertices fit its fixed ones (with the frame's, those the handle has moved
  // over would fan over it), then its fair with the frame's fixed positions.
  const Positions U = remesh_source(V);
  FairingResult result =
      fair_remeshed_from(U, last.vertices, F, free, boundary_normals, timed_options());
  // Rows in no face: the remesh's spare rows and those of earlier remeshes (never free).
  result.unreferenced.insert(result.unreferenced.end(), unreferenced.begin(), unreferenced.end());
  std::sort(result.unreferenced.begin(), result.unreferenced.end());
  return result;
}

void LiveFairing::State::swap_mesh(LiveMesh& other) noexcept {
  std::swap(F, other.F);
  std::swap(free, other.free);
  std::swap(polygon_ids, other.polygon_ids);
  std::swap(V0, other.V0);
  std::swap(region, other.region);
  std::swap(finest, other.finest);
  std::swap(construction, other.construction);
  std::swap(predictor, other.predictor);
  std::swap(used_fixed, other.used_fixed);
  std::swap(unreferenced, other.unreferenced);
  std::swap(X, other.X);
  std::swap(pending, other.pending);  // a folded warm frame of the old mesh is taken from it
  std::swap(last_step, other.last_step);
  std::swap(mesh_angle, other.mesh_angle);
}

std::optional<FairingResult> LiveFairing::State::warm_remesh(const Positions& V,
                                                            const Positions* boundary_normals,
                                                            const std::string& reason,
                                                            Phases& phases,
                                                            std::string& failure) {
  Laps laps;
  const Positions U = remesh_source(V);
  RemeshedRegion mesh;
  try {
    mesh = remesh_followed(U / scale, last.vertices / scale, F, free, boundary_normals,
                           options.boundary);
  } catch (const std::exception& error) {
    failure = std::string("remeshing failed: ") + error.what();
    return std::nullopt;
  }
  phases.emplace_back("remesh", laps.lap());
  // The new mesh's rows in the caller's units: V's fixed rows, the remesh's free ones, and
  // rows in no face their last positions (as the cold remesh's result).
  Positions V_new = mesh.vertices * scale;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!mesh.free[std::size_t(v)]) V_new.row(v) = V.row(v);
  for (int v : mesh.unreferenced)
    if (v < last.vertices.rows()) V_new.row(v) = last.vertices.row(v);
  std::optional<Positions> normals;
  if (boundary_normals) normals = live_rows(*boundary_normals, Positions::Zero(V_new.rows(), 3));
  const Positions* normals_new = normals ? &*normals : nullptr;
  LiveMesh old;
  swap_mesh(old);
  std::optional<FairingResult> result;
  try {  // anything that throws on the new mesh brings the old one back
    prepare(mesh.faces, mesh.free, std::nullopt, V_new, normals_new);
    unreferenced = mesh.unreferenced;  // with those of earlier remeshes (never free)
    unreferenced.insert(unreferenced.end(), old.unreferenced.begin(), old.unreferenced.end());
    std::sort(unreferenced.begin(), unreferenced.end());
    X = gather(V0, region.global);
    phases.emplace_back("remesh's preparation", laps.lap());
    std::string warm_why;
    result = warm_frame(V_new, frame_input(V_new), normals_new, phases, warm_why);
    if (!result) failure = "its warm start did not converge: " + warm_why;
  } catch (const std::exception& error) {
    result.reset();
    failure = std::string("its warm start failed: ") + error.what();
  }
  if (result && result->folds > input_folds)
    failure = "its warm start converged with " + std::to_string(result->folds) +
              " folded edges, the input " + std::to_string(input_folds);
  if (!result || result->folds > input_folds) {
    swap_mesh(old);
    return std::nullopt;
  }
  result->remeshed = true;
  result->origin_face = std::move(mesh.origin_face);
  result->origin_barycentric = std::move(mesh.origin_barycentric);
  result->message += "; remeshed from the last frame, solved warm on the new mesh (" + reason +
                     ")";
  return result;
}

void LiveFairing::State::take_warm_remesh(FairingResult& result, Phases& phases) {
  remesh_tried = -kRemeshRetry;
  take_warm(result, phases);
  V0 = result.vertices / scale;
  mesh_angle = smallest_angle(X, region.triangles);
  last_step.resize(0, 3);  // a remesh is no drag response
  ++remeshes;
}

void LiveFairing::State::check_degenerate() {
  if (options.remesh != Remesh::IfNeeded || frames - remesh_tried < kRemeshRetry ||
      frames - degenerate_tried < kRemeshRetry)
    return;
  const double angle = smallest_angle(X, region.triangles);
  if (!(angle < kDegenerateAngle * mesh_angle)) return;
  char text[160];
  std::snprintf(text, sizeof text,
                "the last frame's triangles degenerated: smallest angle %.1f°, %.1f° where the "
                "live mesh was last solved anew",
                angle * 180.0 / M_PI, mesh_angle * 180.0 / M_PI);
  degenerate_reason = text;
  remesh_next = true;
}

void LiveFairing::State::switch_mesh(const FairingResult& result,
                                     const Positions* boundary_normals) {
  std::optional<Positions> normals;  // the new rows (free) are not read
  if (boundary_normals)
    normals = live_rows(*boundary_normals, Positions::Zero(result.vertices.rows(), 3));
  std::vector<int> rows_in_no_face = result.unreferenced;
  // The remesh's triangles come from no polygon.
  prepare(result.faces, result.free, std::nullopt, result.vertices, normals ? &*normals : nullptr);
  unreferenced = std::move(rows_in_no_face);
}

LiveFairing::LiveFairing(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                         const Positions* boundary_normals, const FairingOptions& options,
                         const LiveOptions& live, const std::vector<int>* polygon_ids)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
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

FairingResult LiveFairing::State::unsolved_frame(const Positions& V, const Positions& W,
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

FairingResult LiveFairing::State::cold_frame(const Positions& V, const Positions& W,
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

std::optional<FairingResult> LiveFairing::State::try_remesh(const Positions& V,
                                                           const Positions* boundary_normals,
                                                           bool folded,
                                                           std::string& why) const {
  try {
    FairingResult result = remesh_frame(V, boundary_normals);
    result.message += "; remeshed from the last frame (the warm start " +
                      std::string(folded ? "folded: " : "did not converge: ") + why + ")";
    return result;
  } catch (const std::exception& error) {
    why += std::string("; remeshing failed: ") + error.what();
    return std::nullopt;
  }
}

void LiveFairing::State::check_input(const Positions& V_in, const Positions* normals_in,
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
  State& s = *state_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (std::isnan(time_limit)) throw InvalidInputError(std::string(kUpdate) + ": time_limit is NaN");
  // This frame's deadline (none for an infinite limit), cleared on the way out.
  struct FrameDeadline {
    State& s;
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
  // With remesh="if_needed", a converged warm frame with folds (State::wants_remesh) is
  // kept only where remeshing does not do better.
  std::optional<FairingResult> folded;
  bool warm_remeshed = false;  // remeshed before the triangles fold, and that failed
  s.frame_note.clear();
  if (s.warm) {
    if (s.remesh_next && !s.out_of_time()) {
      s.remesh_next = false;
      std::string failure;
      if (auto result = s.warm_remesh(V, boundary_normals, s.degenerate_reason, phases, failure)) {
        s.take_warm_remesh(*result, phases);
        return std::move(*result);
      }
      s.degenerate_tried = s.frames;  // not again for kRemeshRetry frames
      warm_remeshed = true;
      s.frame_note = "; a remesh first (" + s.degenerate_reason + ") was not taken: " + failure;
    }
    // The boundary data are the frame's own.
    if (auto result = s.warm_frame(V, W, boundary_normals, phases, why)) {
      if (s.options.remesh != Remesh::IfNeeded || !s.wants_remesh(result->folds)) {
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
  return s.solve_anew(V, W, boundary_normals, std::move(folded), phases, why, warm_remeshed);
}

void LiveFairing::State::take_warm(FairingResult& result, Phases& phases) {
  result.message += frame_note;
  result.phase_seconds = std::move(phases);
  last_step = pending - X;
  X = std::move(pending);
  last = result;
  ++frames;
}

void LiveFairing::State::take_anew(FairingResult& result, Phases& phases,
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

FairingResult LiveFairing::State::solve_anew(const Positions& V, const Positions& W,
                                             const Positions* boundary_normals,
                                             std::optional<FairingResult> folded,
                                             Phases& phases, std::string& why,
                                             bool warm_remeshed) {
  // Remeshed from the last converged frame's surface: triangles that fit the dragged shape.
  const bool remesh = options.remesh == Remesh::IfNeeded && warm && !out_of_time();
  if (remesh && !warm_remeshed) {  // warm on the remesh first; where that fails, its cold fair
    const std::string reason =
        std::string(folded ? "the warm start folded: " : "the warm start did not converge: ") + why;
    std::string failure;
    if (auto result = warm_remesh(V, boundary_normals, reason, phases, failure)) {
      take_warm_remesh(*result, phases);
      return std::move(*result);
    }
    why += "; solved warm on a remesh, " + failure;
  }
  std::optional<FairingResult> remeshed;
  if (remesh && !out_of_time()) remeshed = try_remesh(V, boundary_normals, bool(folded), why);
  // Taken where it converged, unless the warm frame converged with as few folds: the cold
  // path on the live mesh, whose triangles no longer fit, folds as the warm start did.
  const bool use_remesh = remeshed && remeshed->converged &&
                          (!folded || remeshed->folds < folded->folds);
  if (remesh)  // a remesh that leaves folds is tried again kRemeshRetry frames on
    remesh_tried = use_remesh && remeshed->folds <= input_folds ? -kRemeshRetry : frames;
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
