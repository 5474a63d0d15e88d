// The vertex update of the construction (Schneider & Kobbelt 2001, sections 7.2, 7.3):
// move every free vertex so that its mean curvature becomes the target H~, eq. (13).
#pragma once

#include "inner_fairness.h"
#include "region.h"
#include "geofair/types.h"

#include <Eigen/Core>

#include <vector>

namespace geofair {

/// One Gauss–Seidel-ordered pass over the free vertices of `region`.
///
/// For free vertex i with unit normal n (recomputed from the current, partly updated
/// positions), q~ = Σ λ_ij q_j − ⟨Σ λ_ij q_j − q_i, n⟩ n is the inner-fairness position
/// projected into the tangent plane (7.3). With the distances |q_j − q~| held fixed the
/// Moreton–Séquin H is linear in the offset t along n (7.2): H(t) = H(0) + t H′, so
/// t = (H~_i − H(0)) / H′ and q_i ← q~ + s t n. |t| is limited to half the mean distance to
/// the neighbours, which only acts far from the solution (a noisy start).
///
/// Coupling (beyond the paper): with `coupling`, t is divided by max(1, ρ_i), the factor by
/// which the neighbours' reaction amplifies the vertex's own (see coupling_factors).
///
/// \param X       #region×3 positions, updated in place (boundary rows untouched)
/// \param N       #region×3 unit normals; free rows are refreshed as vertices move
/// \param H_target #V_I target curvatures H~
/// \param lambda  inner fairness weights (inner_fairness_weights)
/// \param subset  free vertices to update, in this order; nullptr: all free vertices
/// \param coupling #V_I factors ρ_i from coupling_factors, or nullptr for the paper's step
/// \param tangential false: move along the normal only (q~ = q_i)
/// \return the largest displacement of a vertex in this pass (length units).
double update_free_vertices(const FairingRegion& region, const InnerFairnessWeights& lambda,
                            const Eigen::VectorXd& H_target, NormalWeighting weighting,
                            double damping, Positions& X, Positions& N,
                            const std::vector<int>* subset = nullptr,
                            const std::vector<double>* coupling = nullptr, bool tangential = true);

/// Coupling factors ρ_i (#V_I, dimensionless) of the vertex update, measured by a finite
/// difference: ρ_i = (∂/∂t_i)(H_i − Σ_j w_ij H_j / Σ_j w_ij) / H′_i, where t_i moves q_i
/// along its normal, normals and mean curvatures of q_i and its ring are re-estimated, and
/// w_ij are the cotangent weights of S. The vertex update makes H_i equal to H~_i as if the
/// neighbours' H stayed fixed; ρ_i says how much faster the defect of the discrete
/// eq. (12) really changes. ρ_i ≈ 1.2 on a regular mesh, up to ≈ 2 on irregular ones.
///
/// Why (beyond Schneider & Kobbelt's update): next to a G1 boundary vertex whose one-sided
/// fan is thin, the least-squares fit (11) is nearly singular in the inward direction
/// (Lemma 1), H of that boundary vertex reacts far more strongly to the free neighbour than
/// the neighbour's own H, and with s·ρ > 2 the update overshoots and the vertex oscillates
/// (the paper's "alternating between two positions", section 7.5; docs/DESIGN_NOTES.md).
///
/// \param weights w_ij per ring slot of the free vertices (DirichletMatrix::weights)
/// \param H       #region mean curvatures of the positions X with normals N
/// \param X, N    positions and normals (restored on return)
/// With a G0 boundary (region.boundary) the boundary neighbours' H = 0 does not react.
/// \param rho     output, #V_I; 1 where undefined (H′ ≤ 0 or Σ_j w_ij ≤ 0)
void coupling_factors(const FairingRegion& region, const std::vector<double>& weights,
                      NormalWeighting weighting, const Eigen::VectorXd& H, Positions& X,
                      Positions& N, std::vector<double>& rho);

}  // namespace geofair
