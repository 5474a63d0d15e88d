// LiveFairing's state between frames (live.h): the live mesh, the warm start and what the
// frames are solved with. live.cpp holds the frames, live_remesh.cpp the remeshes of
// remesh IfNeeded (the connectivity that follows the drag).
#pragma once

#include "geofair/types.h"

#include "common.h"
#include "construction.h"
#include "detail_coding.h"
#include "displacement_predictor.h"
#include "nested_iteration.h"
#include "region.h"

#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace geofair {

// Names of live.cpp and live_remesh.cpp alone (each opens the namespace).
namespace live_detail {

constexpr const char* kUpdate = "LiveFairing.update";

// "1 Newton step", "3 Newton steps".
inline std::string newton_steps(int n) {
  return std::to_string(n) + (n == 1 ? " Newton step" : " Newton steps");
}

// Frames between remesh attempts for folds that a remesh left (RemeshTrigger).
constexpr int kRemeshRetry = 3;

// The secant predictor's largest multiple of the last frame's response (warm_start) ...
constexpr double kSecantLimit = 2.0;
// ... and of either of the last two frames' responses in their combination (a steady
// rotation takes about 2 and -1).
constexpr double kTwoStepSecantLimit = 4.0;

// The last two warm frames' changes of the region's positions (#region×3 each; empty after a
// cold frame or a remesh): the secant predictor's (LiveState::warm_start).
struct DragSteps {
  Positions last, before;
  void push(Positions step) { before = std::move(last), last = std::move(step); }
  void clear() { last.resize(0, 3), before.resize(0, 3); }
};

// With remesh IfNeeded, a converged frame whose smallest triangle angle falls below this
// fraction of the live mesh's own remeshes at the next frame: a handle dragged towards the
// border squeezes the triangles between them, and their angles collapse a few frames before
// they fold (docs/LIVE.md, "Remeshing frames").
constexpr double kDegenerateAngle = 1.0 / 3.0;

// The smallest angle of triangles T (rows into X), radians (live_remesh.cpp).
double smallest_angle(const Positions& X, const Triangles& T);

}  // namespace live_detail

// When a frame remeshes (remesh IfNeeded): after a warm start that did not converge; after
// one that converged with more folded edges than the input, unless a remesh after a warm
// start left folds or failed within kRemeshRetry frames (folds_tried); and first, before
// its warm start, after a frame whose smallest triangle angle fell below kDegenerateAngle of
// the live mesh's own, while no remesh of either kind failed within kRemeshRetry frames.
// Frames are counted as LiveFairing::frames().
struct RemeshTrigger {
  // The frame of the last remesh after a warm frame that left folds, failed, or was cut
  // short by the time limit.
  int folds_tried = -live_detail::kRemeshRetry;
  int degenerate_tried = -live_detail::kRemeshRetry;  // the last remesh-first that failed
  double mesh_angle = 0.0;  // the smallest angle of the last frame solved anew, radians
  bool next = false;        // the next frame remeshes first
  bool deferred = false;    // `next` was kept once already: a remesh-first out of time
  std::string reason;       // why, for that frame's message

  // A converged warm frame with `folds` folded edges, the input `input_folds`.
  bool wants(int folds, int input_folds, int frame) const {
    return folds > input_folds && frame - folds_tried >= live_detail::kRemeshRetry;
  }
  // Whether a frame's angles are watched: no remesh failed in the last kRemeshRetry frames.
  bool watching(int frame) const {
    return frame - folds_tried >= live_detail::kRemeshRetry &&
           frame - degenerate_tried >= live_detail::kRemeshRetry;
  }
  // A frame taken with smallest angle `angle`: `next` where it degenerated.
  void check_angle(double angle);
};

// How a warm remesh that was not taken ended (LiveState::warm_remesh).
struct RemeshFailure {
  bool remesh_threw = false;  // remesh_region failed: a cold fair of the same remesh would too
  std::string why;            // one clause for the frame's message
};

// Which predictors a frame's warm start ran Newton from (LiveState::warm_newton): the secant
// one, and where Newton did not converge from it or failed, the harmonic one.
struct WarmStarts {
  bool harmonic_after_secant = false;
  int secant_steps = 0;        // of a secant start that ran unconverged
  std::string secant_failure;  // the secant start's SolverError, else empty
  // The frame's `steps` Newton steps (both starts') by start, for its message.
  std::string steps_text(int steps) const {
    if (!harmonic_after_secant) return live_detail::newton_steps(steps);
    if (!secant_failure.empty())
      return live_detail::newton_steps(steps) +
             " from the harmonic predictor (the secant one failed: " + secant_failure + ")";
    return live_detail::newton_steps(secant_steps) + " from the secant predictor and " +
           live_detail::newton_steps(steps - secant_steps) + " from the harmonic one";
  }
};

// LiveFairing's state (live.h): the live mesh, its prepared region and construction, the
// warm start, and the counts and deadline of the frames.
struct LiveState {
  Triangles F;              // the live mesh: the input's, or the last remesh's
  std::vector<bool> free;
  int input_rows = 0;       // the constructor's vertex count (update accepts it or the live mesh's)
  int input_folds = 0;      // folded edges of the constructor's frame (the input's own)
  RemeshTrigger trigger;    // remesh IfNeeded: when a frame remeshes
  std::vector<int> unreferenced;  // rows in no face since a remesh (their last positions kept)
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
  live_detail::DragSteps drag_steps;  // the last warm frames' changes of X, the secant predictor's
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
    Positions X, pending;
    live_detail::DragSteps drag_steps;
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
                                           RemeshFailure& failure);

  // The frame's remesh first (RemeshTrigger::next): the frame taken where the warm solve on
  // the remesh converged; else nullopt, `failed` (where it was tried) and frame_note saying
  // how it ended. A remesh cut short by the frame's time limit is kept for the next frame,
  // once.
  std::optional<FairingResult> remesh_first(const Positions& V, const Positions* boundary_normals,
                                            Phases& phases, std::optional<RemeshFailure>& failed);

  // A warm_remesh result taken: as take_warm, on the new mesh, whose result is the
  // reference of later frames (switch_mesh).
  void take_warm_remesh(FairingResult& result, Phases& phases);

  // After a warm frame taken (remesh IfNeeded): whether its triangles degenerated
  // (RemeshTrigger), so that the next frame remeshes first.
  void check_degenerate();
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
    if (options.remesh == Remesh::IfNeeded)
      trigger.mesh_angle = live_detail::smallest_angle(X, region.triangles);
    warm = true;
    drag_steps.clear();
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
  // harmonic one (`starts` says which ran); Y its solution, `phases` its phases from `laps`;
  // the report's iterations count both starts' steps. The construction takes the frame's
  // boundary and, for conformal inner fairness, the weights of X0. SolverError where the
  // harmonic start fails; nullopt where no start ran to its end (the frame's time was spent
  // first, or after a secant start that failed).
  std::optional<IterationReport> warm_newton(const Positions& X0, Positions& Y, Phases& phases,
                                             Laps& laps, WarmStarts& starts);

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
  // extended by what the remesh did. `first_failed`: how update's remesh-first failed, if
  // it did (after a failed warm solve on it only its cold fair is tried; after a failed
  // remesh none).
  FairingResult solve_anew(const Positions& V, const Positions& W,
                           const Positions* boundary_normals, std::optional<FairingResult> folded,
                           Phases& phases, std::string& why,
                           const std::optional<RemeshFailure>& first_failed);
};

}  // namespace geofair
