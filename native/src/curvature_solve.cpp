// Local (Gauss–Seidel) and global (preconditioned CG) steps of section 7.1.
#include "geofair/curvature_solve.h"

#include <limits>

namespace geofair {

void gauss_seidel_sweep(const SparseRowMatrix& S, const Eigen::VectorXd& b, Eigen::VectorXd& H) {
  const int* outer = S.outerIndexPtr();
  const int* inner = S.innerIndexPtr();
  const double* values = S.valuePtr();
  for (Eigen::Index i = 0; i < S.rows(); ++i) {
    double diag = 0.0, sum = b(i);
    for (int p = outer[i]; p < outer[i + 1]; ++p) {
      if (inner[p] == i)
        diag = values[p];
      else
        sum -= values[p] * H(inner[p]);
    }
    if (diag != 0.0) H(i) = sum / diag;
  }
}

CurvatureSolver::CurvatureSolver(int iterations) {
  cg_.setMaxIterations(iterations);
  cg_.setTolerance(std::numeric_limits<double>::epsilon());
}

void CurvatureSolver::global_step(const SparseRowMatrix& S, const Eigen::VectorXd& b,
                                  Eigen::VectorXd& H) {
  cg_.compute(S);
  Eigen::VectorXd x = cg_.solveWithGuess(b, H);
  // NoConvergence is expected: only a fixed number of iterations is asked for.
  if (cg_.info() == Eigen::NumericalIssue || !x.allFinite())
    throw SolverError("fair: the conjugate-gradient step on S H = b broke down (S is not "
                      "positive definite: degenerate or badly obtuse triangles)");
  H = std::move(x);
}

}  // namespace geofair
