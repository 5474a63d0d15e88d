// Target mean curvatures H~ from the Dirichlet problem S H~ = b (Schneider & Kobbelt 2001,
// section 7.1, factorization step I).
//
// The problem is not solved exactly: starting from the current H, the construction
// alternates a local step (one Gauss–Seidel sweep) and a global step (n conjugate-gradient
// iterations with a diagonal preconditioner).
#pragma once

#include "laplace_beltrami.h"

#include <Eigen/IterativeLinearSolvers>

namespace geofair {

/// One Gauss–Seidel sweep on A x = b, in place: the construction's local step on S H = b
/// (forward, one block), and the smoother of the tangential solves' two-grid
/// preconditioner (inner_fairness.cpp). Rows are relaxed in order (`forward`) or in reverse;
/// with `blocks` > 1 the rows are cut into that many fixed blocks of whole row pairs, swept
/// in parallel, each block reading the others' values of the start of the sweep (a hybrid
/// Gauss–Seidel: the result does not depend on the threads). A row without a diagonal
/// entry, or with a zero one, keeps its value. A must be compressed with its column indices
/// sorted within each row (as setFromTriplets and makeCompressed leave them).
void gauss_seidel_sweep(const SparseRowMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                        bool forward = true, int blocks = 1);

/// The global step: `iterations` conjugate-gradient iterations with a diagonal (Jacobi)
/// preconditioner on S H = b, starting from H, in place.
class CurvatureSolver {
 public:
  explicit CurvatureSolver(int iterations);
  /// \throw SolverError if the iteration produced a non-finite value.
  void global_step(const SparseRowMatrix& S, const Eigen::VectorXd& b, Eigen::VectorXd& H);

 private:
  Eigen::ConjugateGradient<SparseRowMatrix, Eigen::Lower | Eigen::Upper,
                           Eigen::DiagonalPreconditioner<double>>
      cg_;
};

}  // namespace geofair
