// Local (Gauss–Seidel) and global (preconditioned CG) steps of section 7.1.
#include "curvature_solve.h"

#include "parallel.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace geofair {

void gauss_seidel_sweep(const SparseRowMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                        bool forward, int blocks) {
  const int n = int(A.rows());
  const double* value = A.valuePtr();
  const int* column = A.innerIndexPtr();
  const int* outer = A.outerIndexPtr();
  blocks = std::clamp(blocks, 1, std::max(1, n / 2));
  // First row of block k: whole 2×2 blocks (even boundaries) to each block of rows.
  auto first_row = [&](int k) {
    return k == blocks ? n : 2 * int(std::int64_t(n / 2) * k / blocks);
  };
  Eigen::VectorXd start;
  if (blocks > 1) start = x;  // one block reads only its own rows
  parallel_for(blocks, blocks > 1, [&](int block) {
    const int lo = first_row(block), hi = first_row(block + 1);
    // The row's entries in column order (sorted), as runs: columns before the block read
    // the start, the block's own columns x, the diagonal is kept apart, columns after the
    // block the start again; each run subtracts in the same order as one loop would.
    auto relax_row = [&](int r) {
      double sum = b(r), diagonal = 0.0;
      int p = outer[r];
      const int end = outer[r + 1];
      for (; p < end && column[p] < lo; ++p) sum -= value[p] * start(column[p]);
      for (; p < end && column[p] < r; ++p) sum -= value[p] * x(column[p]);
      if (p < end && column[p] == r) diagonal = value[p++];
      for (; p < end && column[p] < hi; ++p) sum -= value[p] * x(column[p]);
      for (; p < end; ++p) sum -= value[p] * start(column[p]);
      if (diagonal != 0.0) x(r) = sum / diagonal;
    };
    if (forward)
      for (int r = lo; r < hi; ++r) relax_row(r);
    else
      for (int r = hi; r-- > lo;) relax_row(r);
  });
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
