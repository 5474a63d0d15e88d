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
/// through n_b only next to the boundary; the 3#V_I×3#V_I system is solved by sparse LU.
///
/// \param X       #region×3 positions (boundary rows are the fixed data)
/// \param lambda  inner fairness weights of every region vertex (inner_fairness_weights)
/// \return #region×3 positions with the free rows replaced.
/// \throw SolverError if the sparse factorization fails.
Positions bilaplacian_initial_mesh(const FairingRegion& region,
                                   const InnerFairnessWeights& lambda,
                                   const Positions& X);

}  // namespace geofair
