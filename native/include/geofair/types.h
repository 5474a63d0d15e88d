// Common types and options of the geofair library.
//
// Units: lengths are in mesh units; mean curvature H is in 1/length. Sign convention:
// H > 0 on a sphere whose normals point outward (H = 1/r there).
#pragma once

#include "geofair/errors.h"
#include "geofair/tuning.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <functional>

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
  /// 0 = picked from the region (Newton: as many as keep 700 free vertices on the base
  /// level, schedule.cpp; Paper: default_levels, one level up to 1000 free vertices).
  int levels = 0;
  /// Wall-clock bound on the whole call, seconds: the solve stops unconverged once it is
  /// spent (FairingResult::message says so). Negative: automatic with Iteration::Auto (the
  /// paper's iteration stops once its residual has not halved for T = time_limit_base +
  /// time_limit_per_free_vertex × free vertices seconds, the call after time_limit_hard_factor × T;
  /// tuning.schedule, fairing.h), none with an iteration chosen explicitly (the reference
  /// iterations run to max_iterations); infinity: none.
  double time_limit = -1.0;
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

}  // namespace geofair
