// Inner fairness: the generalized Laplacian Δ(q_i) = -q_i + Σ_j λ_ij q_j that decides where
// vertices sit on the surface (Schneider & Kobbelt 2001, section 7.3).
#pragma once

#include "geofair/region.h"
#include "geofair/types.h"

#include <vector>

namespace geofair {

/// Weights λ_ij per ring slot of every vertex 0 .. rings.offset.size()-2, with Σ_j λ_ij = 1.
///
/// Uniform: λ_ij = 1/valence. Conformal: λ_ij = w_ij / Σ_k w_ik with the cotangent weights
/// w_ij of the ORIGINAL positions X0 (a discrete harmonic map, approximately conformal to
/// the original mesh). Negative cotangent weights (obtuse triangles) are clamped to 0 so
/// that λ stays a convex combination; a vertex whose weights all vanish falls back to
/// uniform weights.
std::vector<double> inner_fairness_weights(const OneRings& rings, const Positions& X0,
                                           InnerFairness type);

/// Σ_j λ_ij q_j for vertex i.
Vec3 weighted_centroid(const OneRings& rings, const std::vector<double>& lambda,
                       const Positions& X, int i);

}  // namespace geofair
