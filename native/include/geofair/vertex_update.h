// The vertex update of the construction (Schneider & Kobbelt 2001, sections 7.2, 7.3):
// move every free vertex so that its mean curvature becomes the target H~, eq. (13).
#pragma once

#include "geofair/region.h"
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
/// \param X       #region×3 positions, updated in place (boundary rows untouched)
/// \param N       #region×3 unit normals; free rows are refreshed as vertices move
/// \param H_target #V_I target curvatures H~
/// \param lambda  inner fairness weights per ring slot (inner_fairness_weights)
/// \param subset  free vertices to update, in this order; nullptr: all free vertices
/// \return the largest displacement of a vertex in this pass (length units).
double update_free_vertices(const FairingRegion& region, const std::vector<double>& lambda,
                            const Eigen::VectorXd& H_target, NormalWeighting weighting,
                            double damping, Positions& X, Positions& N,
                            const std::vector<int>* subset = nullptr);

}  // namespace geofair
