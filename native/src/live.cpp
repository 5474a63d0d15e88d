// LiveFairing: a region faired again for new fixed positions, warm-started from the last
// frame (live.h).
#include "geofair/live.h"

#include "common.h"
#include "construction.h"
#include "inner_fairness.h"
#include "mesh_scale.h"
#include "nested_iteration.h"
#include "parallel.h"
#include "region.h"
#include "sparse_lu.h"

#include <Eigen/SparseCholesky>

#include <cmath>
#include <cstdio>
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

// The warm start's predictor: the harmonic extension (uniform weights, Δu = 0 at the free
// vertices) of the fixed vertices' moves since the last frame into the free ones, so that the
// vertices next to a moving handle move with it instead of being squashed against it (a
// start within Newton's reach where the last frame alone folds its triangles).
class DisplacementPredictor {
 public:
  explicit DisplacementPredictor(const FairingRegion& region) : region_(region) {
    const OneRings& rings = region.rings;
    const int nf = region.n_free;
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < nf; ++i) {
      entries.emplace_back(i, i, double(rings.valence(i)));
      for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
        if (rings.ring[k] < nf) entries.emplace_back(i, rings.ring[k], -1.0);
    }
    Eigen::SparseMatrix<double> L(nf, nf);
    L.setFromTriplets(entries.begin(), entries.end());
    ldlt_.compute(L);
  }

  // Adds to the free rows of Y the extension of `moves` (#V_B×3, the fixed rows' moves);
  // false (Y unchanged) where the factorization or the solve failed.
  bool predict(const Positions& moves, Positions& Y) const {
    if (ldlt_.info() != Eigen::Success) return false;
    const OneRings& rings = region_.rings;
    const int nf = region_.n_free;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf, 3);
    for (int i = 0; i < nf; ++i)
      for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
        if (rings.ring[k] >= nf) rhs.row(i) += moves.row(rings.ring[k] - nf);
    const Eigen::MatrixXd u = ldlt_.solve(rhs);
    if (ldlt_.info() != Eigen::Success || !u.allFinite()) return false;
    Y.topRows(nf) += u;
    return true;
  }

 private:
  const FairingRegion& region_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

}  // namespace

struct LiveFairing::State {
  Triangles F;
  std::vector<bool> free;
  std::optional<std::vector<int>> polygon_ids;
  FairingOptions options;  // the user's, without a progress callback
  LiveOptions live;
  double scale = 1.0;       // working_scale of the construction's V: positions are V / scale
  Positions V0;             // the construction's V / scale: the free rows' original positions
  std::vector<int> used_fixed;  // fixed vertices of a triangle, checked for finiteness
  FairingRegion region;     // in the caller's ids (global), its boundary normals the last frame's
  FairingRegion finest;     // the same with region-local ids: what the construction works on
  std::unique_ptr<Construction> construction;  // kept between frames (the warm start)
  std::unique_ptr<DisplacementPredictor> predictor;
  Positions X;              // the last converged frame's region positions (local ids, / scale)
  bool warm = false;        // X is a converged solution to start from
  FairingResult last;
  int frames = 0, cold_frames = 0;

  // The frame's input (/ scale): V's fixed rows, the original free rows.
  Positions frame_input(const Positions& V) const {
    Positions W = V / scale;
    for (int i = 0; i < region.n_free; ++i) W.row(region.global[i]) = V0.row(region.global[i]);
    return W;
  }

  // The caller's positions of the result: V's rows, the free rows from the region's Y.
  Positions caller_positions(const Positions& V, const Positions& Y) const {
    Positions out = V;
    for (int i = 0; i < region.n_free; ++i) out.row(region.global[i]) = scale * Y.row(i);
    return out;
  }

  // The warm start adopts a converged result (caller's positions).
  void adopt(const FairingResult& result) {
    X = gather(result.vertices / scale, region.global);
    warm = true;
    last = result;
  }

  // The warm start of one frame from X for the frame's input W (/ scale); nullopt where it
  // did not converge (`why` then says how it ended).
  std::optional<FairingResult> warm_frame(const Positions& V, const Positions& W,
                                          const Positions* boundary_normals, Phases& phases,
                                          std::string& why);
};

std::optional<FairingResult> LiveFairing::State::warm_frame(const Positions& V,
                                                            const Positions& W,
                                                            const Positions* boundary_normals,
                                                            Phases& phases, std::string& why) {
  Laps laps;
  // The boundary data of the frame: normals (the given ones, or estimated from W), the
  // residual's length, and for conformal inner fairness the weights of the frame's input.
  std::optional<Positions> normals;
  if (boundary_normals) normals = *boundary_normals;  // unit vectors: no scaling
  set_boundary_normals(region, W, F, free, normals ? &*normals : nullptr, kUpdate);
  finest.g1_normals = region.g1_normals;
  const Positions X0 = gather(W, region.global);
  const double L = diagonal(X0);
  if (!(L > 0.0)) throw InvalidInputError(std::string(kUpdate) + ": the region has zero extent");
  if (options.inner_fairness != InnerFairness::Uniform) {
    InnerFairnessWeights lambda = inner_fairness_weights(finest, X0, options.inner_fairness);
    if (!construction->set_lambda(lambda))  // other intrinsic edges: another pattern
      construction = std::make_unique<Construction>(finest, std::move(lambda), options, L);
  }
  construction->set_boundary(finest.g1_normals, L);
  // The start: the last frame, its free vertices moved with the fixed ones (the predictor).
  const int nb = region.n - region.n_free;
  Positions Y = X;
  predictor->predict(X0.bottomRows(nb) - X.bottomRows(nb), Y);
  Y.bottomRows(nb) = X0.bottomRows(nb);
  phases.emplace_back("boundary data and predictor", laps.lap());

  NewtonRun run;
  run.max_iterations = live.max_warm_steps;
  run.tolerance = options.tolerance;
  run.patience = options.tuning.newton.patience;
  run.polish_at_convergence = true;
  run.warm = true;
  IterationReport report;
  try {
    report = construction->run_newton(Y, run);
  } catch (const SolverError& error) {
    why = error.what();
    return std::nullopt;
  }
  laps.lap();  // run_newton's own seconds, below
  phases.emplace_back("warm inner fairness", report.relax_seconds);
  phases.emplace_back("warm Newton steps", report.step_seconds);
  phases.emplace_back("warm polishes", report.polish_seconds);
  if (!report.converged || !Y.topRows(region.n_free).allFinite()) {
    why = "residual " + scientific(report.residual) + " after " + steps(report.iterations);
    return std::nullopt;
  }
  X = Y;
  FairingResult result;
  result.vertices = caller_positions(V, Y);
  result.faces = F;
  result.free = free;
  result.origin_face.assign(free.size(), -1);
  result.origin_barycentric = Positions::Zero(Eigen::Index(free.size()), 3);
  result.converged = true;
  result.iterations = report.iterations;
  result.iterations_per_level = {report.iterations};
  result.vertices_per_level = {region.n};
  result.residual = report.residual;
  result.stop_reason = StopReason::Converged;
  result.iteration = Iteration::Newton;
  result.newton_iterations = report.iterations;
  result.message = "converged (residual " + scientific(report.residual) + ", tolerance " +
                   scientific(options.tolerance) + "); warm start from the last frame (" +
                   steps(report.iterations) + ")";
  // Folds: only edges with a free vertex count, and both their triangles are the region's.
  std::vector<bool> local_free(std::size_t(region.n), false);
  std::fill(local_free.begin(), local_free.begin() + region.n_free, true);
  const FoldCount folds = count_folds(X0, Y, region.triangles, local_free);
  result.folds = folds.folds;
  result.new_folds = folds.new_folds;
  if (folds.folds > 0)
    result.message += "; " + std::to_string(folds.folds) +
                      (folds.folds == 1 ? " edge folds" : " edges fold") +
                      " over (triangles flipped), " + std::to_string(folds.new_folds) +
                      " of them not in the input";
  phases.emplace_back("result", laps.lap());
  return result;
}

LiveFairing::LiveFairing(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                         const Positions* boundary_normals, const FairingOptions& options,
                         const LiveOptions& live, const std::vector<int>* polygon_ids)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  if (options.remesh != Remesh::Off)
    throw InvalidInputError("LiveFairing: remesh must be off");
  if (live.max_warm_steps < 1) throw InvalidInputError("LiveFairing: max_warm_steps must be >= 1");
  if (live.details) throw InvalidInputError("LiveFairing: details=True is not implemented yet");
  s.F = F;
  s.free = free;
  if (polygon_ids) s.polygon_ids = *polygon_ids;
  s.options = options;
  s.options.progress = nullptr;
  s.live = live;
  // The cold solve first: fair's checks of the input and options, and the first frame.
  FairingResult first = fair(V, F, free, boundary_normals, s.options, polygon_ids);
  s.scale = working_scale(V, F, "LiveFairing");
  s.V0 = V / s.scale;
  s.region = extract_region(s.V0, F, free, boundary_normals, true, polygon_ids, options.boundary);
  s.finest = s.region;
  std::iota(s.finest.global.begin(), s.finest.global.end(), 0);
  const Positions X0 = gather(s.V0, s.region.global);
  const double L = diagonal(X0);
  s.construction = std::make_unique<Construction>(
      s.finest, inner_fairness_weights(s.finest, X0, options.inner_fairness), s.options, L);
  s.construction->prepare_newton();  // the symbolic analysis, once
  s.predictor = std::make_unique<DisplacementPredictor>(s.finest);
  std::vector<bool> used(std::size_t(V.rows()), false);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) used[std::size_t(F(f, c))] = true;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (used[std::size_t(v)] && !free[std::size_t(v)]) s.used_fixed.push_back(int(v));
  if (first.converged)
    s.adopt(first);
  else
    s.last = std::move(first);
}

LiveFairing::~LiveFairing() = default;
LiveFairing::LiveFairing(LiveFairing&&) noexcept = default;
LiveFairing& LiveFairing::operator=(LiveFairing&&) noexcept = default;

const FairingResult& LiveFairing::result() const { return state_->last; }
int LiveFairing::frames() const { return state_->frames; }
int LiveFairing::cold_frames() const { return state_->cold_frames; }

FairingResult LiveFairing::update(const Positions& V, const Positions* boundary_normals) {
  State& s = *state_;
  const Eigen::Index n = Eigen::Index(s.free.size());
  if (V.rows() != n)
    throw InvalidInputError(std::string(kUpdate) + ": vertices has " + std::to_string(V.rows()) +
                            " rows, the mesh " + std::to_string(n) + " vertices");
  for (int v : s.used_fixed)
    if (!V.row(v).allFinite())
      throw InvalidInputError(std::string(kUpdate) + ": vertex " + std::to_string(v) +
                              " has a non-finite coordinate");
  if (boundary_normals && boundary_normals->rows() != n)
    throw InvalidInputError(std::string(kUpdate) + ": boundary_normals has " +
                            std::to_string(boundary_normals->rows()) + " rows for " +
                            std::to_string(n) + " vertices");
  set_loop_threads(solve_threads());
  const BlasThreads blas_threads(1);
  Laps laps;
  const Positions W = s.frame_input(V);
  Phases phases;
  std::string why = "the last frame did not converge";
  if (s.warm) {
    // The boundary data are the frame's own; X changes only where the frame converged.
    if (auto result = s.warm_frame(V, W, boundary_normals, phases, why)) {
      result->phase_seconds = std::move(phases);
      s.last = *result;
      ++s.frames;
      return std::move(*result);
    }
  }
  // The cold path: fair() of the frame's input, its whole schedule.
  const double warm_seconds = laps.lap();
  FairingResult cold = fair(s.scale * W, s.F, s.free, boundary_normals, s.options,
                            s.polygon_ids ? &*s.polygon_ids : nullptr);
  ++s.frames;
  ++s.cold_frames;
  for (int v = 0; v < int(n); ++v)  // fixed rows bit-identical to V's
    if (!s.free[std::size_t(v)]) cold.vertices.row(v) = V.row(v);
  cold.message += "; cold path (fair): the warm start did not converge (" + why + ")";
  if (warm_seconds > 0.0) phases.emplace_back("warm start", warm_seconds);
  phases.insert(phases.end(), cold.phase_seconds.begin(), cold.phase_seconds.end());
  cold.phase_seconds = std::move(phases);
  if (cold.converged) s.adopt(cold);
  return cold;
}

}  // namespace geofair
