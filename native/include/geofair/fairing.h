// Intrinsic fairing of a mesh region with G1 (or G0) boundary conditions: the discrete
// solution of Δ_B H = 0 (Schneider & Kobbelt 2001, eqs. (4), (12); construction of section 7).
#pragma once

#include "geofair/types.h"

#include <string>
#include <utility>
#include <vector>

namespace geofair {

// StopReason and FairingResult, the outcome of fair: geofair/types.h.

/// Fairs the free vertices of a triangle mesh so that Δ_B H = 0 holds at each of them,
/// with the G1 boundary condition of positions and unit normals at the fixed vertices that
/// share a triangle with a free vertex. (Headers named below without geofair/ are the
/// library's internal ones, in native/src/.)
///
/// With options.boundary = G0 (beyond the paper) the boundary keeps its positions only and
/// H = 0 is prescribed there: S H~ = b has b = 0, so the result has H ≡ 0, the minimal
/// surface spanned by the boundary. boundary_normals is not read, nothing is estimated from
/// the surface around the region (which may then reach the mesh border), and the linear
/// initial mesh is Δ²f = 0 with Δf = 0 at the boundary, i.e. the membrane Δf = 0
/// (bilaplacian.h), the minimal surface's linearization.
///
/// Inner fairness (section 7.3, options.inner_fairness, see inner_fairness_weights): uniform
/// weights give a regular vertex distribution; conformal ones the discrete harmonic map
/// with the cotangent weights of the ORIGINAL mesh, negative weights (obtuse triangles)
/// clamped to 0 (InnerFairness::Conformal, the paper's weights), or with the cotangent
/// weights of the original's intrinsic Delaunay triangulation, which are never negative
/// (InnerFairness::ConformalIntrinsic; Bobenko & Springborn 2007, "A discrete
/// Laplace–Beltrami operator for simplicial surfaces"): the same weights where no edge needs
/// a flip; elsewhere the vertices land on the harmonic map of the original's metric
/// instead of 0.34–3.2 edge lengths off it, but the construction can stall on rough inputs
/// (see inner_fairness.h). Either way only the finest level's weights decide the result.
///
/// The steps of the construction, Newton's method and what goes beyond the paper:
/// docs/ARCHITECTURE.md, "What fair() does".
///
/// The schedule: fair() makes its attempts in order and returns the first that converges
/// (or is cancelled): Newton's method on hierarchies of up to four kinds of coarse weights,
/// on the finest level alone and on two levels, then the paper's iteration with Newton's
/// method tried from its iterate. Iteration::Auto (the default) runs them all; Newton the
/// Newton attempts and returns the last one's result whatever it is; Paper, and the linear
/// bilaplacian outer fairness, the paper's iteration alone. The table of every attempt and
/// retry, with the rule for each, is plan_attempts' in src/schedule.h.
///
/// Remeshing (options.remesh, beyond the paper): Always replaces the region's triangles by
/// remesh_region's isotropic remesh at the mean length of the region's border edges
/// (building_blocks.h; fixed vertices and the region's border edges kept) and fairs that
/// mesh with the G1 normals of the input (the given ones or the estimate from the input's
/// surrounding surface); IfNeeded fairs with the connectivity kept first and, where that
/// does not converge (unless cancelled or out of time) or leaves new folds, remeshes and
/// fairs again, returning the remeshed result if it converged without new folds, else the
/// better of the two (converged first, then fewer new folds, then the smaller residual);
/// the message says which. folds and new_folds of a remeshed result count its own triangles
/// (new: not folded in the remesh before fairing). An explicit time limit covers the whole call; the automatic one
/// applies to each solve. The result's faces, free, remeshed, unreferenced, origin_face and
/// origin_barycentric describe the returned mesh either way.
///
/// Residual: L · max_i |H̄_i − H_i| over the free vertices, with H̄_i = Σ_j w_ij H_j /
/// Σ_j w_ij the cotangent-weighted mean curvature of the neighbours (w_ij of eq. (6)), and L
/// the bounding-box diagonal of the region (free and G1 boundary vertices). It is the
/// Jacobi-scaled residual (b − S H)_i / S_ii of eq. (12) and equals (2A_i/3)|Δ_B H(q_i)| /
/// Σ_j w_ij with Δ_B of eq. (5), A_i the 1-disk area: about h²|Δ_B H| for edge length h.
/// It is dimensionless (the same tolerance means the same on a mesh scaled by any factor),
/// zero exactly when S H = b, and it asks the same local smoothness of H at any resolution.
/// (L³ max|Δ_B H| would ask (L/h)² times more of a fine mesh than of a coarse one;
/// docs/DESIGN_NOTES.md.) Smooth errors are removed by the coarse levels, whose tolerance
/// is 10 times looser; on a single level the same tolerance leaves a larger smooth error,
/// still below the discretization error of the paper's area normals.
///
/// \param V       #V×3 positions, finite where used
/// \param F       #F×3 triangles, consistently oriented, manifold in the region
/// \param free    #V flags, true where a vertex may move; every free vertex must be
///                surrounded by triangles (not on the mesh border)
/// \param boundary_normals #V×3 unit normals read at the G1 boundary vertices, or nullptr
///                for estimate_boundary_normals (building_blocks.h) of the surrounding
///                surface; ignored with options.boundary = G0
/// \param polygon_ids #F polygon each triangle was tessellated from, or nullptr: uniform
///                inner fairness then runs over the polygon mesh's edges, not the
///                diagonals that split its polygons (inner_fairness_weights; beyond the
///                paper). The surface itself is that of the triangles either way.
///
/// The whole call stops unconverged once options.time_limit is spent (result.message). The
/// automatic limit (time_limit < 0, Iteration::Auto) is a limit on time without progress:
/// Newton's attempts end by their own rule (no halving of the residual in newton.patience
/// steps); the paper's iteration, the last attempt, stops once its residual has not fallen
/// below half of its value at the last such fall for T = time_limit_base +
/// time_limit_per_free_vertex × free vertices seconds; and the whole call stops after
/// time_limit_hard_factor × T. With
/// Iteration::Auto a diverging last attempt returns the input unconverged (its residual,
/// the reason in result.message) instead of throwing.
///
/// Positions are worked on in units of the mesh's own size: where the mean edge length of F
/// lies outside [2^-32, 2^32] they are divided by the power of two nearest to it (exactly;
/// the result multiplied back, the fixed rows the input's), so that the squares and fourth
/// powers of lengths in normals, areas and curvatures stay normal doubles. The result is
/// the same at any scale up to the factor and rounding.
///
/// \throw InvalidInputError for invalid input (see extract_region; polygon_ids of the wrong
///        size; a mesh whose squared bounding-box diagonal overflows, above about 1.3e154,
///        or whose squared mean edge length is not a normal double, below about 1.5e-154:
///        the message names the size) or options (a tuning field outside its range,
///        validate_tuning; a NaN time_limit; a negative or NaN deadline.seconds); SolverError
///        (not with Auto's iteration, see above) if a linear solve fails or the iteration
///        diverges (non-finite or exploding residual).
FairingResult fair(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const Positions* boundary_normals, const FairingOptions& options,
                   const std::vector<int>* polygon_ids = nullptr);

/// The checks fair() makes of its options (InvalidInputError naming the option); fill_holes
/// makes them first, since its per-hole fallbacks record a fair() that fails and go on.
void check_fairing_options(const FairingOptions& options);

}  // namespace geofair
