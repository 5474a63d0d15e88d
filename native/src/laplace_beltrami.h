// Cotangent Laplace–Beltrami operator and the Dirichlet matrix S of Δ_B H = 0.
//
// Schneider & Kobbelt 2001, section 5, eqs. (5)-(7) (Pinkall & Polthier 1993; Desbrun et
// al. 1999).
#pragma once

#include "region.h"
#include "geofair/types.h"

#include <Eigen/Sparse>

#include <vector>

namespace geofair {

/// Exported by geofair/building_blocks.h, which documents it and gives the defaults.
SparseRowMatrix cotangent_laplacian(const Positions& V, const Triangles& F);

/// Cotangent weights w_ij = cot α_ij + cot β_ij of the ring slots of vertex i, written to
/// w[0 .. valence). α, β are the angles opposite edge (q_i, q_j) in the (one or two)
/// triangles at that edge (eq. (5)). Dimensionless. A triangle whose area vanishes
/// contributes cot = ±1e12 instead of ±inf.
void cotangent_weights(const OneRings& rings, const Positions& X, int i, double* w);


/// The discrete Dirichlet problem Σ_j w_ij (H_i - H_j) = 0 at the free vertices,
/// S H_I = b with S_ii = Σ_j w_ij (6), S_ij = -w_ij for free q_j (7),
/// b_i = Σ_{q_j ∈ V_B} w_ij H_j.
///
/// S is #V_I×#V_I, symmetric and positive definite while no triangle area vanishes: it is
/// the stiffness matrix of piecewise-linear functions (its quadratic form is the Dirichlet
/// energy), so the negative weights of obtuse triangles keep it definite; they only cost
/// the M-matrix property (maximum principle), see intrinsic_delaunay.h and
/// tests/test_negative_weights.py. The sparsity pattern is built once; assemble() refreshes
/// values.
class DirichletMatrix {
 public:
  explicit DirichletMatrix(const FairingRegion& region);

  /// Recomputes the cotangent weights of every free vertex from positions X (#region×3).
  void assemble(const Positions& X);

  /// b for the current weights and the mean curvatures H (#region, boundary rows used).
  Eigen::VectorXd rhs(const Eigen::VectorXd& H) const;

  /// max_i |H̄_i − H_i| over the free vertices, H̄_i = Σ_j w_ij H_j / Σ_j w_ij the
  /// cotangent-weighted mean of the neighbours: the Jacobi-scaled residual |(b − S H_I)_i| /
  /// S_ii of eq. (12), equal to (2 A_i / 3) |Δ_B H(q_i)| / Σ_j w_ij with Δ_B of eq. (5), so
  /// about h² |Δ_B H| for edge length h. Units: 1/length. NaN if any value is NaN.
  /// With `source` (#V_I), |Σ_j w_ij (H_i − H_j) − source_i| / Σ_j w_ij instead.
  double max_mean_deviation(const Eigen::VectorXd& H,
                            const Eigen::VectorXd* source = nullptr) const;

  /// d_i = Σ_j w_ij (H_i − H_j) = (S H_I − b)_i, #V_I, 1/length.
  Eigen::VectorXd defects(const Eigen::VectorXd& H) const;

  const SparseRowMatrix& S() const { return S_; }
  /// w_ij per ring slot of the free vertices (indexed like OneRings::ring), from assemble().
  const std::vector<double>& weights() const { return slot_weight_; }

 private:
  const FairingRegion& region_;
  SparseRowMatrix S_;
  std::vector<double> slot_weight_;  // w_ij per ring slot of the free vertices
  std::vector<int> slot_value_;      // index into S_'s values, or -1 for a boundary neighbour
  std::vector<int> diag_value_;      // index of S_ii
};

}  // namespace geofair
