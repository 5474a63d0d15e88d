// The global normal step by Newton's method on eq. (12) (beyond the paper).
#pragma once

#include "laplace_beltrami.h"
#include "region.h"
#include "sparse_lu.h"
#include "geofair/types.h"

#include <unsupported/Eigen/IterativeSolvers>

#include <functional>
#include <future>
#include <vector>

namespace geofair {
class JacobianOperator;
}  // namespace geofair

namespace Eigen::internal {
// JacobianOperator is a matrix-free operator for Eigen's iterative solvers (Eigen's
// "Matrix-free solvers" page): it borrows the traits of a sparse matrix.
template <>
struct traits<geofair::JacobianOperator> : traits<SparseMatrix<double>> {};
}  // namespace Eigen::internal

namespace geofair {

/// A square operator v ↦ J v given by a function, for Eigen's GMRES.
class JacobianOperator : public Eigen::EigenBase<JacobianOperator> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum {
    ColsAtCompileTime = Eigen::Dynamic,
    MaxColsAtCompileTime = Eigen::Dynamic,
    IsRowMajor = false
  };
  using Function = std::function<void(const Eigen::VectorXd& v, Eigen::VectorXd& Jv)>;

  JacobianOperator(Eigen::Index n, const Function& product) : n_(n), product_(&product) {}
  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& Jv) const { (*product_)(v, Jv); }
  template <class Rhs>
  Eigen::Product<JacobianOperator, Rhs, Eigen::AliasFreeProduct> operator*(
      const Eigen::MatrixBase<Rhs>& x) const {
    return {*this, x.derived()};
  }

 private:
  Eigen::Index n_;
  const Function* product_;
};

}  // namespace geofair

namespace Eigen::internal {
template <class Rhs>
struct generic_product_impl<geofair::JacobianOperator, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<geofair::JacobianOperator, Rhs,
                                generic_product_impl<geofair::JacobianOperator, Rhs>> {
  template <class Dest>
  static void scaleAndAddTo(Dest& dst, const geofair::JacobianOperator& J, const Rhs& v,
                            const double& alpha) {
    Eigen::VectorXd Jv;
    J.apply(v, Jv);
    dst.noalias() += alpha * Jv;
  }
};
}  // namespace Eigen::internal

namespace geofair {

/// Normal offsets t (#V_I) of all free vertices at once that solve the linearized
/// discrete fairness equation at every free vertex i (eq. (12); τ = 0 except for
/// multigrid coarse problems):
///   d_i(t) = Σ_j w_ij (H_i − H_j)(X + t N) = τ_i,   d(t) ≈ d(0) + J t.
/// J is the Jacobian of the defects with everything that depends on the positions
/// recomputed: the normals (quadric fits), the Moreton–Séquin H of all region vertices
/// (eq. (10), with the spiral samples of 6.2 that read the neighbours' normals) and the
/// cotangent weights w_ij (eq. (6)). It is never assembled: Eigen's GMRES
/// (NewtonTuning::krylov_iterations, relative residual krylov_tolerance, or the caller's
/// tighter one on a fresh factorization, see solve) reads only its
/// products J v, which the caller computes by a forward difference of the defects (one
/// evaluation of the whole mesh per product).
///
/// The preconditioner is the sparse LU factorization (SuiteSparse's UMFPACK with OpenBLAS)
/// of an approximate Jacobian D J_1 that holds the weights fixed and keeps, of each
/// column, what lies in the ring: the derivatives of H by forward differences at each free
/// vertex m and its ring, with the normals of m and of its free ring neighbours estimated
/// anew (column m touches H_m and the H of m's ring; not a G0 boundary's, whose H = 0 is
/// prescribed), so D J_1 is a 2-ring sparse matrix. Left out: the weights' change and the
/// reach of the spiral samples (valence 3 and 4) and of the normal fit's flaps (valence
/// below 5) beyond the ring. It is factorized at the first step and again only after a step
/// whose GMRES needed more than half of its iterations or failed, once the iterations beyond
/// those of the factorization's first solve (as it ran, tighter or not; docs/NEWTON.md) add
/// up to NewtonTuning::refactorization_products
/// (a lagged factorization ages as the iterate moves on, over the frames of LiveFairing
/// too), or when the shift σ differs from the factorized one by more than
/// NewtonTuning::shift_refactorization (shifts below shift_negligible count as none).
///
/// Why the normals in the preconditioner: the Jacobian with the normals held fixed ignores
/// how the fitted normals tilt with the neighbours, and on decimated coarse levels GMRES
/// then ran out of iterations far from its tolerance (docs/DESIGN_NOTES.md, "The Newton
/// preconditioner's normals"). Why the products of the exact Jacobian: Newton's
/// method on the preconditioner's matrix alone (then with the normals held fixed) converged
/// only linearly; with the exact products it converges quadratically (docs/NEWTON.md).
class NewtonStep {
 public:
  /// `weighting`: the normal estimate of the construction (Construction::curvatures).
  NewtonStep(const FairingRegion& region, const NewtonTuning& tuning, NormalWeighting weighting);

  /// Products J v of the Jacobian of the defects (#V_I in, #V_I out, 1/length²: defects
  /// per unit of normal offset) at the current positions.
  using JacobianProduct = JacobianOperator::Function;

  /// \param X      #region×3 positions
  /// \param N      #region×3 unit normals at X (G1 normals, or G0 estimates, in the boundary
  ///               rows)
  /// \param H      #region Moreton–Séquin mean curvatures at X, N
  /// \param w      cotangent weights per ring slot of the free vertices (DirichletMatrix)
  /// \param defects #V_I defects d = Σ_j w_ij (H_i − H_j) (DirichletMatrix::defects), 1/length
  /// \param tau    #V_I source, or nullptr
  /// \param product J v at X (see JacobianProduct)
  /// \param shift  pseudo-transient continuation (run_newton): solve (J + σ M) t = τ − d
  ///               instead, with σ = shift.sigma ≥ 0 (dimensionless) and M = shift.mass
  ///               (#V_I, 1/length², positive); σ = 0 is Newton's step
  /// \param krylov_tolerance GMRES's relative residual ‖P⁻¹(b − J t)‖/‖P⁻¹ b‖ for this step
  ///               where the factorization is fresh (made at this step or just before it);
  ///               on a lagged one NewtonTuning::krylov_tolerance. A solve that stops short
  ///               of it but within krylov_tolerance is taken.
  /// \param t      out: #V_I normal offsets, mesh units, positive along N
  /// \return false if the preconditioner's factorization failed (singular system) or the
  ///         step is not finite
  struct Shift {
    double sigma = 0.0;
    const Eigen::VectorXd* mass = nullptr;
  };
  bool solve(const Positions& X, const Positions& N, const Eigen::VectorXd& H,
             const std::vector<double>& w, const Eigen::VectorXd& defects,
             const Eigen::VectorXd* tau, const JacobianProduct& product, const Shift& shift,
             double krylov_tolerance, Eigen::VectorXd& t);

  /// The symbolic analysis of the preconditioner's pattern (PatternLU::analyze) now rather
  /// than at the first step: with METIS's nested dissection from kNestedDissectionMin free
  /// vertices on.
  void analyze() { lu_.analyze(A_, A_.rows() >= kNestedDissectionMin); }

  /// The first step's preconditioner ahead of the step: assembled at X (N, H, w as in
  /// solve()) on this thread, factorized on another where `async` (else here), which solve()
  /// then waits for and uses with no shift. Construction::relax_before_steps calls it before
  /// its last relaxation.
  void prefactorize(const Positions& X, const Positions& N, const Eigen::VectorXd& H,
                    const std::vector<double>& w, bool async);
  /// Waits for prefactorize()'s factorization and drops it: the next solve() factorizes.
  void discard_prefactorization();

 private:
  // Fills A_ = D J_1 at X (the preconditioner's matrix, see the class comment).
  void assemble(const Positions& X, const Positions& N, const Eigen::VectorXd& H,
                const std::vector<double>& w);
  const FairingRegion& region_;
  NewtonTuning tuning_;
  NormalWeighting weighting_;
  std::vector<double> jacobian_;  // [m]: ∂H_m/∂t_m; [nf + slot k of m's ring]: ∂H_ring[k]/∂t_m
  std::vector<int> row_offset_, row_column_, row_source_;  // rows of J_1 (see constructor)
  std::vector<int> term_entry_;  // per term of the assembly of A: its index in A's values
  std::vector<int> diagonal_entry_;  // per free vertex: the index of A_ii in A's values
  double factorized_sigma_ = 0.0;    // the shift σ of the last factorization
  Eigen::SparseMatrix<double> A_;
  PatternLU lu_;
  bool refactorize_ = true;
  int first_iterations_ = 0;  // GMRES iterations of the first solve on the factorization
  int extra_products_ = 0;    // iterations beyond first_iterations_ since, summed
  // GMRES preconditioned by the last factorization of D J_1, of an earlier iterate.
  Eigen::GMRES<JacobianOperator, LaggedFactorization> gmres_;
  // prefactorize()'s factorization (true if it succeeded), waited for by the next solve();
  // the last member, so that its thread ends before A_ and lu_ go.
  bool prefactorized_ = false;
  std::future<bool> prefactorization_;
  // Waits for prefactorize()'s factorization; true if one is in place for solve().
  bool finish_prefactorization();
};

}  // namespace geofair
