// Inner fairness: the generalized Laplacian Δ(q_i) = -q_i + Σ_j λ_ij q_j that decides where
// vertices sit on the surface (Schneider & Kobbelt 2001, section 7.3).
#pragma once

#include "geofair/region.h"
#include "geofair/types.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>

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

/// The global step of inner fairness (beyond the paper, measured below): moves every free
/// vertex within its tangent plane so that the tangential part of the generalized Laplacian
/// vanishes at all free vertices at once, instead of one vertex at a time.
///
/// The vertex update of section 7.3 moves q_i to the tangential projection of Σ_j λ_ij q_j,
/// a Jacobi/Gauss–Seidel relaxation of the linear inner-fairness condition: low-frequency
/// tangential errors take O(#V_I) iterations to vanish, and while vertices drift the
/// discretization of H changes and keeps the residual of eq. (12) up. Linearized with the
/// tangent planes fixed, the condition is
///   T_iᵀ (Σ_j λ_ij (q_j + T_j u_j) − (q_i + T_i u_i)) = 0   for all free i,
/// a 2#V_I×2#V_I sparse system for the tangential offsets u_i (T_i = 3×2 basis of the tangent
/// plane of unit normal n_i; boundary vertices do not move). `iterations` BiCGSTAB
/// iterations (the system is not symmetric for λ_ij ≠ λ_ji) from u = 0, then
/// q_i ← q_i + s T_i u_i with |T_i u_i| limited to half the mean distance to the neighbours.
/// Mirrors the paper's global CG step for H~ (section 7.1). Measured on the 2000-vertex cap
/// with multigrid: the fine level needs 550 instead of 3250 iterations.
class TangentialSolver {
 public:
  /// \param n_free  free vertices are 0 .. n_free-1 of `rings`
  TangentialSolver(const OneRings& rings, int n_free, int iterations);

  /// \param lambda  inner fairness weights per ring slot
  /// \param X       #region×3 positions, free rows updated in place
  /// \param N       #region×3 unit normals of the free vertices at X
  /// \param damping s in (0, 1]
  void step(const std::vector<double>& lambda, const Positions& N, double damping, Positions& X);

 private:
  const OneRings& rings_;
  int n_free_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> A_;
  std::vector<int> slot_value_;  // per ring slot of a free vertex: index of its 2×2 block, or -1
  std::vector<int> diag_value_;  // per free vertex: index of its diagonal 2×2 block
  Eigen::BiCGSTAB<Eigen::SparseMatrix<double, Eigen::RowMajor>, Eigen::IdentityPreconditioner>
      solver_;
};

}  // namespace geofair
