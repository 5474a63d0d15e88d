// The global normal step by Newton's method on eq. (12) (beyond the paper).
#pragma once

#include "geofair/laplace_beltrami.h"
#include "geofair/region.h"
#include "geofair/types.h"

#include <Eigen/UmfPackSupport>

#include <vector>

namespace geofair {

/// Normal offsets t (#V_I) of all free vertices at once that solve the linearized
/// discrete fairness equation
///   Σ_j w_ij (H_i(t) − H_j(t)) = τ_i,   H_k(t) ≈ H_k + Σ_m J_km t_m,
/// at every free vertex i (eq. (12); τ = 0 except for multigrid coarse problems). J is the
/// Jacobian of the Moreton–Séquin estimates (eq. (10)) of all region vertices, the G1
/// boundary vertices included, with respect to moving free vertex m by t_m along its
/// normal; it is measured by forward differences with the normals held fixed (column m
/// touches H_m and H at the ring of m). The cotangent weights w_ij are held fixed.
/// The system (D J) t = τ − D H (D: the Dirichlet operator, #V_I×#V) is a sparse
/// 2-ring fourth-order system, factorized by SuiteSparse's UMFPACK with OpenBLAS (13000
/// free vertices: the whole solve 2.2 s with it, 3.96 s with Eigen's SparseLU; 100000: about
/// 1.3 s per factorization, where SparseLU took 6-9 s). Holding the normals fixed is measured:
/// differentiating the quadric normals too took the disturbed 2000-vertex cap from 14 to 9
/// steps but kept the 13000-vertex cap from converging (residual 150-2000 after 30 steps).
class NewtonStep {
 public:
  explicit NewtonStep(const FairingRegion& region);

  /// \param X      #region×3 positions
  /// \param N      #region×3 unit normals at X (G1 normals in the boundary rows)
  /// \param H      #region Moreton–Séquin mean curvatures at X, N
  /// \param w      cotangent weights per ring slot of the free vertices (DirichletMatrix)
  /// \param defects #V_I defects D H = Σ_j w_ij (H_i − H_j) (DirichletMatrix::defects), 1/length
  /// \param tau    #V_I source, or nullptr
  /// \param t      out: #V_I normal offsets, mesh units, positive along N
  /// \param refresh  measure J and factorize D J at X; otherwise reuse the last
  ///                  factorization (a chord step; the right-hand side is always current)
  /// \return false if the factorization failed (singular system)
  bool solve(const Positions& X, const Positions& N, const Eigen::VectorXd& H,
             const std::vector<double>& w, const Eigen::VectorXd& defects,
             const Eigen::VectorXd* tau, bool refresh, Eigen::VectorXd& t);
  bool factorized() const { return factorized_; }

 private:
  const FairingRegion& region_;
  std::vector<double> jacobian_;  // [m]: ∂H_m/∂t_m; [nf + slot k of m's ring]: ∂H_ring[k]/∂t_m
  std::vector<int> row_offset_, row_column_, row_source_;  // rows of J (see constructor)
  std::vector<Eigen::Triplet<double>> entries_;
  Eigen::SparseMatrix<double> A_;
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu_;
  bool analyzed_ = false;
  bool factorized_ = false;
};

}  // namespace geofair
