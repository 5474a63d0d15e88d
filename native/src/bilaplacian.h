// The linear initial mesh: Δ²f = 0 with G1 boundary conditions (Schneider & Kobbelt 2001,
// section 7.4, last part; Fig. 1c).
#pragma once

#include "inner_fairness.h"
#include "region.h"
#include "geofair/types.h"

#include <vector>

namespace geofair {

/// The membrane of the inner fairness weights: solves Δf(q_i) = Σ_j λ_ij f_j − f_i = 0 at
/// every free vertex for the free positions, the fixed ones held. With uniform weights and a
/// planar boundary that is Tutte's embedding of the region: the vertex distribution the
/// connectivity itself asks for, whatever the input's metric. Requires symmetric weights
/// (InnerFairnessWeights::row_sum given): the system scaled by the row sums is symmetric
/// positive definite, solved by a sparse Cholesky factorization (CHOLMOD; Eigen's in a
/// portable build).
///
/// \param X       #region×3 positions (boundary rows are the fixed data)
/// \param lambda  inner fairness weights of every region vertex, with row sums
/// \return #region×3 positions with the free rows replaced.
/// \throw InvalidInputError if lambda has no row sums; SolverError if the factorization fails.
Positions membrane_positions(const FairingRegion& region, const InnerFairnessWeights& lambda,
                             const Positions& X);

/// Solves Δ(Δf)(q_i) = 0 at every free vertex for the free positions, with the
/// generalized Laplacian Δf(q_i) = Σ_j λ_ij f_j − f_i of the chosen inner fairness.
///
/// G1 boundary: a boundary vertex q_b sees only its one-sided ring inside the region, so
/// its Laplacian is taken as the normal component of the one-sided umbrella,
/// Δf(q_b) = n_b n_bᵀ (Σ_j λ_bj f_j − f_b): a smooth surface's Laplacian is normal to it,
/// and since the normal curvature is even in the direction, the one-sided average sees
/// the same normal offset as the full ring would. G0 boundary (region.boundary): Δf(q_b) = 0,
/// the linear counterpart of H = 0 (Δf ≈ 2H n); then Δf = 0 at every free vertex too, so
/// the solution is membrane_positions' (solved here as the system above with P_b = 0,
/// which takes weights without row sums too). This couples the three coordinates
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
///                 (BilaplacianTuning: newton_initial_mesh_residual or
///                 initial_mesh_residual for an initial mesh that Newton's method or the
///                 paper's iteration refines, exact_residual where the linear solution is
///                 the result)
/// \param max_cg_iterations  conjugate-gradient iterations before sparse LU takes over
/// \return #region×3 positions with the free rows replaced.
/// \throw SolverError if the sparse factorization fails.
Positions bilaplacian_initial_mesh(const FairingRegion& region,
                                   const InnerFairnessWeights& lambda, const Positions& X,
                                   double relative_residual,
                                   int max_cg_iterations = BilaplacianTuning{}.cg_iterations);

}  // namespace geofair
