// The linear initial mesh: Δ²f = 0 with G1 boundary conditions (Schneider & Kobbelt 2001,
// section 7.4, last part; Fig. 1c).
#pragma once

#include "geofair/inner_fairness.h"
#include "geofair/region.h"
#include "geofair/types.h"

#include <vector>

namespace geofair {

/// Solves Δ(Δf)(q_i) = 0 at every free vertex for the free positions, with the
/// generalized Laplacian Δf(q_i) = Σ_j λ_ij f_j − f_i of the chosen inner fairness.
///
/// G1 boundary: a boundary vertex q_b sees only its one-sided ring inside the region, so
/// its Laplacian is taken as the normal component of the one-sided umbrella,
/// Δf(q_b) = n_b n_bᵀ (Σ_j λ_bj f_j − f_b): a smooth surface's Laplacian is normal to it,
/// and since the normal curvature is even in the direction, the one-sided average sees
/// the same normal offset as the full ring would. This couples the three coordinates
/// through n_b only next to the boundary. With symmetric weights (known row sums, see
/// InnerFairnessWeights::row_sum) the 3#V_I×3#V_I system, its equations scaled by the row
/// sums, is symmetric positive definite and is solved by conjugate gradients preconditioned
/// by the Cholesky factorization of its scalar part (the coordinates decoupled away from
/// the boundary), to the relative residual `relative_residual`; otherwise, or if that
/// fails, by sparse LU (UMFPACK).
///
/// \param X       #region×3 positions (boundary rows are the fixed data)
/// \param lambda  inner fairness weights of every region vertex (inner_fairness_weights)
/// \param relative_residual  ‖b − K f‖ / ‖b‖ at which conjugate gradients stop
///                 (kNewtonInitialMeshResidual or kInitialMeshResidual for an initial
///                 mesh that Newton's method or the paper's iteration refines,
///                 kExactResidual where the linear solution is the result)
/// \return #region×3 positions with the free rows replaced.
/// \throw SolverError if the sparse factorization fails.
Positions bilaplacian_initial_mesh(const FairingRegion& region,
                                   const InnerFairnessWeights& lambda, const Positions& X,
                                   double relative_residual);

/// Conjugate-gradient iterations of bilaplacian_initial_mesh at most before it falls back
/// to sparse LU (the preconditioned matrix is the identity plus a term of rank at most the
/// number of boundary vertices next to free ones, so CG needs about that many).
constexpr int kBilaplacianIterations = 300;
/// Relative residual of a linear initial mesh that the paper's iteration refines: its
/// errors lie far below the distance the iteration moves the vertices, and that iteration
/// is sensitive to its start (docs/DESIGN_NOTES.md).
constexpr double kInitialMeshResidual = 1e-8;
/// ... and of the base level that Newton's method refines (fairing.cpp, newton_multigrid):
/// the same steps and results with fewer conjugate-gradient iterations (docs/DESIGN_NOTES.md).
constexpr double kNewtonInitialMeshResidual = 1e-5;
/// Relative residual where the linear solution is the result (OuterFairness::Bilaplacian):
/// that of a direct solve.
constexpr double kExactResidual = 1e-12;

}  // namespace geofair
