// Target mean curvatures H~ from the Dirichlet problem S H~ = b (Schneider & Kobbelt 2001,
// section 7.1, factorization step I).
//
// The problem is not solved exactly: starting from the current H, the construction
// alternates a local step (one Gauss–Seidel sweep) and a global step (n conjugate-gradient
// iterations with a diagonal preconditioner).
#pragma once

#include "geofair/laplace_beltrami.h"

#include <Eigen/IterativeLinearSolvers>

namespace geofair {

/// One Gauss–Seidel sweep on S H = b, in place (the local step). H is #V_I.
void gauss_seidel_sweep(const SparseRowMatrix& S, const Eigen::VectorXd& b, Eigen::VectorXd& H);

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
