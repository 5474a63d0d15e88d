// Sparse LU factorization of a sequence of matrices with one sparsity pattern.
#pragma once

#include <Eigen/Sparse>

#include <algorithm>
#include <memory>

namespace geofair {

/// The index in A.valuePtr() of the stored entry at (outer, inner) of a compressed sparse
/// matrix: (row, column) if A is row-major, (column, row) if column-major. The entry must
/// be stored (in the pattern); the inner indices of each outer vector are sorted.
template <class Sparse>
int stored_entry(const Sparse& A, int outer, int inner) {
  const auto* begin = A.innerIndexPtr() + A.outerIndexPtr()[outer];
  const auto* end = A.innerIndexPtr() + A.outerIndexPtr()[outer + 1];
  return int(std::lower_bound(begin, end, inner) - A.innerIndexPtr());
}

/// The threads of the BLAS that UMFPACK's dense kernels call, for the lifetime of this
/// object; the earlier count is restored after. Only OpenBLAS can be told (looked up at run
/// time); with another BLAS this does nothing.
///
/// fair(), LiveFairing and relax_inner_fairness run their BLAS on one thread: OpenBLAS's
/// threaded kernels round otherwise than its serial ones, so results would depend on the
/// thread count, and its threads wait for work by spinning, which takes the cores from the
/// loops between the BLAS calls (docs/DESIGN_NOTES.md, "Threads").
class BlasThreads {
 public:
  explicit BlasThreads(int threads);
  ~BlasThreads();
  BlasThreads(const BlasThreads&) = delete;
  BlasThreads& operator=(const BlasThreads&) = delete;

 private:
  int previous_ = 0;
};

/// Newton preconditioners analyzed ahead (PatternLU::analyze, Construction::prepare_newton)
/// with at least this many unknowns take METIS's nested dissection ordering. Only the
/// finest level's is analyzed ahead, on the second thread during the decimation, where the
/// ordering's cost is hidden; the coarse levels keep AMD, analyzed on the critical path,
/// where METIS cost more than it saved (docs/DESIGN_NOTES.md).
constexpr int kNestedDissectionMin = 10000;

/// PatternLU factorizes systems of at least this many unknowns with UMFPACK's long-index
/// interface (umfpack_dl_*): with int indices its workspace is addressed in int units, and
/// large factorizations failed for lack of them. Below, int indices, which are faster (docs/DESIGN_NOTES.md).
constexpr int kWideIndexMin = 500000;

/// SuiteSparse's UMFPACK (through Eigen's UmfPackSupport, with BLAS) for square sparse
/// matrices that change values but not pattern from one factorization to the next: the
/// symbolic analysis (ordering) runs at the first factorization only (and again if the
/// pattern changes), the factorized matrix
/// is kept (UMFPACK's solves read it, so the caller may change its own copy), and the solves
/// do no iterative refinement (their accuracy is that of the factorization, about 1e-12
/// relative here; refinement doubled the cost of a solve). Used by the Newton step
/// (newton_step.h) and the direct tangential solve (inner_fairness.h).
class PatternLU {
 public:
  PatternLU();
  ~PatternLU();
  PatternLU(const PatternLU&) = delete;
  PatternLU& operator=(const PatternLU&) = delete;

  /// The symbolic analysis (fill-reducing ordering) of A's pattern ahead of the first
  /// factorization, from the pattern alone: A's values are replaced by the identity's, so
  /// the pattern may be given before the matrix is known (fair() analyzes the finest
  /// level's Newton preconditioner on its second thread during the decimation). With
  /// `nested_dissection` the ordering is METIS's nested dissection instead of UMFPACK's
  /// default (AMD): slower to compute, but less fill (docs/DESIGN_NOTES.md).
  void analyze(const Eigen::SparseMatrix<double>& pattern, bool nested_dissection);
  /// Factorizes A; false if it is singular (then factorized() is false).
  bool factorize(const Eigen::SparseMatrix<double>& A);
  bool factorized() const;
  /// x with A x = b for the last factorized A (requires factorized()).
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  // The factorizations (sparse_lu.cpp, the one place that names the sparse solver, with
  // bilaplacian.cpp): UMFPACK, or Eigen's SparseLU in a portable build (GEOFAIR_PORTABLE).
  struct Factors;
  std::unique_ptr<Factors> factors_;
};

/// An Eigen iterative solver's preconditioner (the interface of Eigen's preconditioners)
/// that applies a PatternLU factorized earlier, of a nearby matrix: an inexact Newton step
/// or a repeated tangential solve keeps one factorization over several systems whose
/// matrices change little, and the Krylov iterations make up for the change.
struct LaggedFactorization {

  const PatternLU* lu = nullptr;
  template <class M> LaggedFactorization& analyzePattern(const M&) { return *this; }
  template <class M> LaggedFactorization& factorize(const M&) { return *this; }
  template <class M> LaggedFactorization& compute(const M&) { return *this; }
  template <class V> Eigen::VectorXd solve(const V& b) const { return lu->solve(b); }
  Eigen::ComputationInfo info() const { return Eigen::Success; }
};

/// Sets an Eigen::GMRES (its preconditioner already set) to the operator A without restart:
/// at most `iterations` iterations to the relative residual `tolerance`.
template <class Gmres, class Operator>
void set_up_gmres(Gmres& gmres, const Operator& A, int iterations, double tolerance) {
  gmres.setMaxIterations(iterations);
  gmres.set_restart(iterations);
  gmres.setTolerance(tolerance);
  gmres.compute(A);
}

}  // namespace geofair
