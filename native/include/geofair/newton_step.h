// The global normal step by Newton's method on eq. (12) (beyond the paper).
#pragma once

#include "geofair/laplace_beltrami.h"
#include "geofair/region.h"
#include "geofair/sparse_lu.h"
#include "geofair/types.h"

#include <unsupported/Eigen/IterativeSolvers>

#include <vector>

namespace geofair {

/// GMRES iterations (also its restart length) before a Newton step refactorizes D J.
/// 13000-vertex cap: 40 gave 16 steps and 1 factorization; 10: 18 steps and 3.
constexpr int kNewtonKrylovIterations = 40;
/// GMRES's relative residual ‖P⁻¹(b − A t)‖/‖P⁻¹ b‖ (P: the lagged factorization): an
/// inexact Newton step.
constexpr double kNewtonKrylovTolerance = 1e-3;

/// Normal offsets t (#V_I) of all free vertices at once that solve the linearized
/// discrete fairness equation
///   Σ_j w_ij (H_i(t) − H_j(t)) = τ_i,   H_k(t) ≈ H_k + Σ_m J_km t_m,
/// at every free vertex i (eq. (12); τ = 0 except for multigrid coarse problems). J is the
/// Jacobian of the Moreton–Séquin estimates (eq. (10)) of all region vertices, the G1
/// boundary vertices included, with respect to moving free vertex m by t_m along its
/// normal; it is measured by forward differences with the normals held fixed (column m
/// touches H_m and H at the ring of m). The cotangent weights w_ij are held fixed.
/// The system (D J) t = τ − D H (D: the Dirichlet operator, #V_I×#V) is a sparse
/// 2-ring fourth-order system. J is measured afresh at every step; the system is solved by
/// GMRES (relative residual kNewtonKrylovTolerance) preconditioned by the sparse LU
/// factorization of the D J of an earlier step, by SuiteSparse's UMFPACK with OpenBLAS, and
/// refactorized only where GMRES does not converge in kNewtonKrylovIterations iterations
/// (then the step is the direct solve). The first step factorizes.
///
/// Measured (bench/speed.py's disturbed caps, 2-core machine under load): 13000 free
/// vertices, a factorization 0.1 s (Eigen's SparseLU: 0.2 s), a GMRES iteration 7 ms, one
/// factorization for all steps; 100000 free vertices (before run_newton relaxed the
/// tangential distribution first): one factorization for all 58 steps, 44 s in all, where
/// refactorizing whenever the residual did not halve (chord steps in between) took 101 s.
/// Holding the normals fixed is measured (before the tangential relaxation too):
/// differentiating the quadric normals as well (the normals of m and its ring follow the
/// move; column m then touches the 2-ring of m) took the 2000-, 13000- and 100000-vertex
/// caps from 11, 16 and 58 steps to 7, 15 and 50, but the costlier Jacobian made the
/// 100000-vertex cap slower, 51 s instead of 44 s (with chord steps instead of GMRES it had
/// kept the 13000-vertex cap from converging).
/// The largest defects during the steps sit at vertices of valence 3 and 4, whose spiral
/// samples (section 6.2) read the neighbours' normals that J holds fixed. Without the
/// tangential solves before the first step (construction.h, kNewtonRelaxations), the
/// residual of the 100000-vertex cap jumped back by about 100x a few times in the last 30
/// of 58 steps, each time at such a vertex right after a tangential step that had clamped
/// thousands of vertices to half an edge. Also measured, not kept: the whole-step scaling
/// of TangentialSolver::relax in every tangential step between Newton steps (100000: 27
/// steps and 32.8 s with 50 BiCGSTAB iterations, a stall with 10 or 25; 13000: slower);
/// direct tangential solves in every step (cost more than they saved at 13000).
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
  /// \return false if the factorization failed (singular system)
  bool solve(const Positions& X, const Positions& N, const Eigen::VectorXd& H,
             const std::vector<double>& w, const Eigen::VectorXd& defects,
             const Eigen::VectorXd* tau, Eigen::VectorXd& t);

 private:
  // GMRES preconditioner: the last factorization of D J, of an earlier iterate.
  struct LaggedFactorization {
    const PatternLU* lu = nullptr;
    template <class M> LaggedFactorization& analyzePattern(const M&) { return *this; }
    template <class M> LaggedFactorization& factorize(const M&) { return *this; }
    template <class M> LaggedFactorization& compute(const M&) { return *this; }
    template <class V> Eigen::VectorXd solve(const V& b) const { return lu->solve(b); }
    Eigen::ComputationInfo info() const { return Eigen::Success; }
  };
  const FairingRegion& region_;
  std::vector<double> jacobian_;  // [m]: ∂H_m/∂t_m; [nf + slot k of m's ring]: ∂H_ring[k]/∂t_m
  std::vector<int> row_offset_, row_column_, row_source_;  // rows of J (see constructor)
  std::vector<int> term_entry_;  // per term of the assembly of A: its index in A's values
  Eigen::SparseMatrix<double> A_;
  PatternLU lu_;
  Eigen::GMRES<Eigen::SparseMatrix<double>, LaggedFactorization> gmres_;
};

}  // namespace geofair
