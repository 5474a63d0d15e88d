// Common types and options of the geofair library: the bottom layer, with errors.h and
// tuning.h, that the API headers (fairing.h, building_blocks.h, hole_filling.h, ...) and the
// library's internal headers both include. Of geofair's headers it includes errors.h and
// tuning.h alone, which include none. The types that the algorithms share with the API
// (FairingResult, RemeshedRegion, HoleChoice, ...) live here, not in the API header that
// exports their functions.
//
// Units: lengths are in mesh units; mean curvature H is in 1/length. Sign convention:
// H > 0 on a sphere whose normals point outward (H = 1/r there).
#pragma once

#include "geofair/errors.h"
#include "geofair/tuning.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace geofair {

/// #V×3 vertex positions (row-major, float64).
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F×3 triangle vertex indices (row-major), counter-clockwise seen from the normal side.
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Vec3 = Eigen::Vector3d;

/// How the tangent plane of a free vertex is estimated (Schneider & Kobbelt 2001, section 6).
enum class NormalWeighting {
  Area,     ///< normalized sum of face cross products: the paper's choice (section 6)
  Angle,    ///< face normals weighted by the incident angle (Thürmer & Wüthrich 1998)
  Max,      ///< cross products divided by the squared edge lengths (Max 1999)
  Quadric,  ///< tangent plane of the least-squares quadric (osculating paraboloid) through
            ///< the one-ring (see vertex_normal; beyond the paper): consistent on irregular
            ///< meshes of any smooth surface. The default.
};

/// Inner fairness: where vertices sit on the surface (Schneider & Kobbelt 2001, section 7.3).
enum class InnerFairness {
  Uniform,    ///< λ_ij = 1/valence: regular vertex distribution
  Conformal,  ///< λ_ij ∝ cot α_ij + cot β_ij of the ORIGINAL mesh (negative ones clamped
              ///< to 0; mean value weights where the positive ones do not surround the
              ///< vertex, see inner_fairness.h): discrete harmonic map, the paper's
              ///< conformal inner fairness
  /// λ_ij ∝ L_ij of the intrinsic Delaunay triangulation of the ORIGINAL mesh (Bobenko &
  /// Springborn 2007): the discrete harmonic map without clamping, non-negative weights on
  /// any mesh; the same as Conformal on a mesh that needs no flip (see inner_fairness.h).
  ConformalIntrinsic,
};

/// Outer fairness: which surface is computed.
enum class OuterFairness {
  Intrinsic,    ///< Δ_B H = 0, eq. (4)/(12): the paper's intrinsic fairing
  Bilaplacian,  ///< the linear Δ²f = 0 solution alone (section 7.4's initial mesh)
};

/// How the discrete equations (12) are solved. Both solve the same equations with the
/// same discretization; they differ in speed and in the meshes they converge on.
enum class Iteration {
  Auto,    ///< Newton; where it fails to converge, the paper's iteration with Newton
           ///< attempts from its iterate (fairing.h, ScheduleTuning)
  Newton,  ///< Newton's method on the normal offsets of all free vertices at once, level
           ///< by level on the progressive mesh (nested iteration, section 7.4; levels)
           ///< (Construction::run_newton, newton_step.h; beyond the paper)
  Paper,   ///< the local/global iteration of section 7 with progressive-mesh multigrid (7.4)
};

/// The boundary condition at the fixed vertices next to the free ones (beyond the paper's
/// G1). Δ_B H = 0 is of fourth order and needs two conditions on the boundary.
enum class BoundaryCondition {
  G1,  ///< positions and unit normals (the paper's); H of the boundary vertices estimated
       ///< from their one-sided rings and the prescribed normals. The default.
  /// Positions only, with H = 0 on the boundary: the solution has H ≡ 0, the minimal
  /// surface spanned by the boundary (Blender's Fair Positions, CGAL's continuity 0 are
  /// its linear counterpart Δf = 0). No boundary normals are read or estimated.
  G0,
};

/// How the normal of a G1 boundary vertex is estimated from the surface around the region.
enum class BoundaryNormalEstimate {
  /// Tangent plane of a least-squares quadric through the surrounding fixed vertices (see
  /// estimate_boundary_normals): error O(h²) on a smooth surface. The default.
  Quadric,
  /// Area-weighted normal of the surrounding triangles: one-sided, tilted by about half a
  /// ring's angle, error O(h). The estimate of earlier releases; the quadric's fallback.
  Area,
};

/// The linearization of inner fairness in TangentialSolver::relax. Fixed: the tangent
/// planes held fixed (section 7.3's update, all vertices at once). Turning: with the first-
/// order turn of each tangent plane as its vertex moves along the surface (the normal's
/// derivative D_i times the normal part ℓ_i of the Laplacian vector: diagonal blocks
/// I + ℓ_i D_i), Newton's linearization. ℓ_i D_i is of order (h·κ)²/2, as small as the
/// smallest eigenvalues of the fixed-plane system on a smooth surface: without it repeated
/// solves reduce the distance to inner fairness only by a constant factor, with it
/// quadratically (docs/DESIGN_NOTES.md, "Tangential solves").
enum class TangentPlanes { Fixed, Turning };

/// Whether fair() replaces the region's triangles by an isotropic remesh (remesh_region,
/// building_blocks.h; beyond the paper, whose section 7.5 suggests it where the connectivity
/// need not be kept).
enum class Remesh {
  Off,       ///< the connectivity kept (the paper's setting). The default.
  Always,    ///< remesh the region, then fair the new mesh
  /// Fair with the connectivity kept; where that does not converge or folds triangles that
  /// were not folded, remesh and fair again, and return the better result.
  IfNeeded,
};

/// Progress report: (iteration, residual). Return false to cancel the run.
using ProgressCallback = std::function<bool(int iteration, double residual)>;

/// Options of geofair::fair. Defaults follow the paper except normal_weighting (Quadric; the
/// paper's is Area), see docs/ACCURACY_AND_SPEED.md.
struct FairingOptions {
  InnerFairness inner_fairness = InnerFairness::Uniform;
  OuterFairness outer_fairness = OuterFairness::Intrinsic;
  NormalWeighting normal_weighting = NormalWeighting::Quadric;
  Iteration iteration = Iteration::Auto;
  BoundaryCondition boundary = BoundaryCondition::G1;
  /// Remesh the region first (Always) or where the connectivity fails (IfNeeded); see fair.
  Remesh remesh = Remesh::Off;
  /// Stop when the residual L·max|H̄ − H| (see fairing.h) falls below this. Dimensionless.
  double tolerance = 1e-4;
  /// Upper bound on the number of iterations M_k -> M_{k+1} spent solving each level (the
  /// iterations that the cycles of a finer level run on it as its coarse grid are not
  /// counted).
  int max_iterations = 20000;
  /// Damping s of the vertex update q <- q~ + s t n (section 7.2); 0 < s <= 1.
  double damping = 0.9;
  /// Conjugate-gradient iterations n of a global step (section 7.1).
  int cg_iterations = 10;
  /// Levels of the progressive-mesh multigrid (section 7.4): 1 = single level,
  /// 0 = picked from the region (Newton: as many as keep tuning.schedule.newton_min_base_free
  /// free vertices on the base level, schedule.cpp; Paper: default_levels, one level up to
  /// 1000 free vertices).
  int levels = 0;
  /// Wall-clock bound on the whole call, seconds: the solve stops unconverged once it is
  /// spent (FairingResult::message says so). Negative: automatic with Iteration::Auto (the
  /// paper's iteration stops once its residual has not halved for T = time_limit_base +
  /// time_limit_per_free_vertex × free vertices seconds, the call after time_limit_hard_factor × T;
  /// tuning.schedule, fairing.h), none with an iteration chosen explicitly (the reference
  /// iterations run to max_iterations); infinity: none.
  double time_limit = -1.0;
  /// A point in time at which the call stops unconverged as at an explicit time_limit,
  /// whatever time_limit is (the automatic limit still applies), and `seconds`, the bound it
  /// stands for, which the message names (>= 0; fair raises InvalidInputError otherwise).
  /// LiveFairing::update gives the solves of a frame its time limit so. Empty: none.
  struct Deadline {
    std::chrono::steady_clock::time_point at;
    double seconds = 0.0;
  };
  std::optional<Deadline> deadline;
  /// Called once per iteration; may be empty.
  ProgressCallback progress;
  /// Polled between the long steps that report no progress (a level's linear initial mesh,
  /// each tangential relaxation before Newton's steps, the next attempt after a failed
  /// one); returning true stops the solve there unconverged, as a progress callback
  /// returning false does. fair() polls its time limit through it; may be empty.
  std::function<bool()> stop_requested;
  /// Called at the start of each attempt of fair()'s schedule (Newton's method on the
  /// hierarchy, on it with the membrane's coarse weights, on the finest level alone, the
  /// paper's iteration), with true for the
  /// paper's iteration, which ends no other way than by converging or max_iterations:
  /// fair()'s automatic time limit counts the time without progress from there. May be empty.
  std::function<void(bool paper)> attempt_started;
  /// The solvers' numerical choices beyond the paper's options (tuning.h).
  SolverTuning tuning;
};

// The building blocks' types (building_blocks.h).

/// A sparse matrix in compressed rows.
using SparseRowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// An intrinsic triangulation on the vertices of a mesh.
struct IntrinsicTriangulation {
  /// #T×3 vertex indices, counter-clockwise as the input. An intrinsic triangle may repeat
  /// a vertex and two triangles may share two vertices twice (not a simplicial complex).
  Triangles triangles;
  /// #T×3 edge lengths: lengths(t, k) is the length of the edge from corner k to corner
  /// k+1 (mod 3) of triangle t, in mesh units, measured along the input surface.
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> lengths;
  /// Number of edge flips performed (0: the input was intrinsically Delaunay).
  int flips = 0;
};

/// Options of remesh_region.
struct RemeshOptions {
  /// Target edge length L in mesh units; <= 0: the mean length of the region's border edges
  /// (the edges of the region's triangles that have one of them on one side only), or of all
  /// its edges where it has no border.
  double target_edge_length = 0.0;
  int iterations = 5;  ///< rounds of split, collapse, flip, tangential relaxation; >= 0
};

/// The remeshed region (remesh_region) in the caller's rows.
///
/// Rows: the input's fixed vertices keep their index and position (bit-identical); an input
/// free vertex that survives keeps its row, the other new free vertices take the input's
/// remaining free rows in increasing order, then rows appended after #V, so `vertices` has
/// max(#V, #fixed + #new free) rows. Input free rows left over are listed in `unreferenced`
/// (in no face, not free, their input position kept).
struct RemeshedRegion {
  Positions vertices;      ///< #V'×3, mesh units
  /// #F'×3: the input faces without a free vertex (unchanged, in input order), then the
  /// region's new triangles, oriented like the input's; each has a free vertex.
  Triangles faces;
  std::vector<bool> free;  ///< #V': true exactly at the new region's free vertices
  std::vector<int> unreferenced;
  /// #V': for a free vertex, the input face (row of F) its position lies on; -1 elsewhere.
  std::vector<int> origin_face;
  /// #V'×3: barycentric coordinates in origin_face (rows sum to 1, the position is
  /// Σ_k b_k V[F(origin_face, k)] to round-off); zeros where origin_face is -1. Lets a caller
  /// carry per-corner data (UVs) over from the input.
  Positions origin_barycentric;
  double target_edge_length = 0.0;  ///< the target length L the remesh used, mesh units
};

// The outcome of fair (fairing.h).

/// Why geofair::fair returned: the first clause of FairingResult::message as a value.
enum class StopReason {
  Converged,      ///< residual <= tolerance
  MaxIterations,  ///< a level spent options.max_iterations (or Newton's method stalled)
  TimeLimit,      ///< options.time_limit, or the automatic limit's hard cap, was spent
  NoProgress,     ///< the automatic time limit: the residual did not halve for its span
  Cancelled,      ///< options.progress returned false or options.stop_requested true
  Diverged,       ///< Auto's last attempt failed (SolverError); the input is returned
};

/// Outcome of geofair::fair.
struct FairingResult {
  /// #V'×3; rows of fixed vertices are bit-identical to the input. #V' = #V unless remeshed
  /// (then max(#V, #fixed + #new free), remesh_region's row layout).
  Positions vertices;
  Triangles faces;          ///< #F'×3: the result's triangles (the input's unless remeshed)
  std::vector<bool> free;   ///< #V': the result's free vertices (the input's unless remeshed)
  bool remeshed = false;    ///< the region's triangles were replaced (FairingOptions::remesh)
  /// Rows of `vertices` in no face (input free rows the remesh did not reuse; their input
  /// positions kept); empty unless remeshed.
  std::vector<int> unreferenced;
  /// #V': for each free vertex of a remeshed region the input face (row of F) it was
  /// created on, on the input surface before fairing; -1 for the other rows and for every
  /// row when not remeshed.
  std::vector<int> origin_face;
  /// #V'×3: barycentric coordinates in origin_face (rows sum to 1); zero rows where
  /// origin_face is -1. Lets a caller carry per-corner data (UVs) over from the input.
  Positions origin_barycentric;
  bool converged = false;  ///< residual <= tolerance was reached
  int iterations = 0;      ///< iterations M_k -> M_{k+1} performed, all levels together
  /// Iterations on each level, coarsest first, including those that the cycles of the finer
  /// levels ran on it as their coarse grid.
  std::vector<int> iterations_per_level;
  std::vector<int> vertices_per_level;    ///< region vertices (free + G1 boundary) per level
  double residual = 0.0;   ///< normalized residual of the returned mesh (see fair)
  /// How the solve ended, one sentence for a user: "converged", or why not (the time
  /// limit, max_iterations, cancelled, no progress) with the residual and tolerance.
  std::string message;
  StopReason stop_reason = StopReason::MaxIterations;  ///< message's first clause as a value
  /// The iteration that produced the result: Newton or Paper (Auto falls back to Paper).
  Iteration iteration = Iteration::Paper;
  /// Newton steps performed, including those of an attempt that Auto abandoned.
  int newton_iterations = 0;
  /// Edges with a free vertex whose two triangles face apart in `vertices` (count_folds):
  /// triangles the result flips over. A converged result can have them where the G1 data
  /// turn faster than the mesh resolves, or keep them from a folded input; `message` then
  /// says so.
  int folds = 0;
  int new_folds = 0;  ///< those of `folds` whose triangles did not face apart in the input
  /// Wall-clock seconds of the solve's phases in the order they ran (for profiling; beyond
  /// the paper): "hierarchy" (smoothed copy and progressive mesh), then per level ℓ
  /// (0 = coarsest) "level ℓ initial mesh" (the linear Δ²f = 0 solve or the prolongation),
  /// "level ℓ set-up" (the level's construction, or the wait for the one built on the second
  /// thread), and for Newton's method "level ℓ inner fairness" (the tangential relaxations
  /// before the steps), "level ℓ Newton steps" and "level ℓ polishes", for the paper's
  /// iteration "level ℓ iterations". An attempt that was abandoned keeps its phases; the
  /// phases do not overlap, so their sum stays below the call's wall time.
  std::vector<std::pair<std::string, double>> phase_seconds;
};

// The choice of the holes that fill_holes fills (hole_filling.h).

/// A connected part's boundary loop of the largest spanned area is its outer border where
/// it spans at least this fraction of the area of the part's triangles
/// (HoleRule::keep_outer_borders).
constexpr double kOuterBorderArea = 0.3;

/// Which boundary loops are holes when fill_holes is given none (holes_to_fill).
struct HoleRule {
  /// Leave the outer borders of open surfaces open: in each connected part of the mesh, the
  /// boundary loop of the largest spanned area |½ Σ_i (p_i − c) × (p_{i+1} − c)| (its
  /// vertices p_i about their centroid c), where that area is at least kOuterBorderArea
  /// times the area of the part's triangles. A sheet's border spans about the sheet's own
  /// area (a height field's: its area projected on the plane), a hole in a closed surface a
  /// small part of it: a sphere missing a cap of polar angle θ spans (1 − cos θ)/2 of the
  /// rest, below 30 % up to θ = 66° (30 % of the sphere cut away). A part has at most one
  /// outer border: a hole in a sheet is filled whatever its size, and of an open tube's
  /// two ends the larger one stays open if it spans 30 % (a ring), else neither.
  /// false: every boundary loop is a hole.
  bool keep_outer_borders = true;
  /// Leave loops of more edges than this open (Blender's Fill Holes' Sides, MeshLab's Close
  /// Holes' maximum size); 0: no limit.
  int max_hole_edges = 0;
};

/// A boundary loop that holes_to_fill leaves open, and why.
struct OpenLoop {
  std::vector<int> loop;  ///< as boundary_loops returns it
  /// One clause for a user, e.g. "an outer border: it spans 95 % of the area of its part's
  /// triangles (a hole less than 30 %)".
  std::string reason;
};

/// The boundary loops of a mesh split by a HoleRule.
struct HoleChoice {
  std::vector<std::vector<int>> holes;  ///< the loops to fill, in boundary_loops' order
  std::vector<OpenLoop> left_open;      ///< the others, in the same order
};

/// Options of LiveFairing beyond fair's (FairingOptions).
struct LiveOptions {
  /// Newton steps each warm start of a frame may take (from the secant predictor, then
  /// where that does not converge from the harmonic one, after its tangential relaxation)
  /// before the frame falls back to the cold path; >= 1.
  int max_warm_steps = 8;
  /// Detail preservation (Kobbelt et al. 1998; Botsch & Kobbelt 2004): the region is split
  /// into its own faired base (Δ_B H = 0 with the input's boundary and handle: the
  /// constructor's cold fair) and the details, the input's offsets from that base per free
  /// vertex in the base's local frame (n_i the area-weighted normal, t_i the direction to a
  /// ring neighbour projected into the tangent plane, n_i × t_i); every frame adds them
  /// back onto the new base in its frames. False: the region is the fair surface itself.
  bool details = false;
};

}  // namespace geofair
