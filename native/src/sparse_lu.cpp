// PatternLU's factorizations and the BLAS threads under UMFPACK, see sparse_lu.h.
#include "sparse_lu.h"

#ifdef GEOFAIR_PORTABLE
#include <Eigen/SparseLU>
#else
#include <Eigen/UmfPackSupport>
#endif

#include <algorithm>
#include <cstdint>

#include "geofair/blas.h"

#ifdef GEOFAIR_BLAS_LOADER
#include "blas_loader.h"
#elif !defined(GEOFAIR_PORTABLE) && !defined(_WIN32)
#include <dlfcn.h>
#define GEOFAIR_OPENBLAS_LOOKUP
#endif

namespace geofair {
namespace {

// OpenBLAS's own calls, looked up at run time: the BLAS behind Debian's libblas.so.3 is a
// choice of the machine (update-alternatives), and another BLAS has no such calls.
using SetThreads = void (*)(int);
using GetThreads = int (*)();
#ifdef GEOFAIR_BLAS_LOADER
SetThreads set_threads() { return loaded_blas_set_threads(); }
GetThreads get_threads() { return loaded_blas_get_threads(); }
#else
// OpenBLAS's call `name`: in the global scope, else in an OpenBLAS already loaded as a
// dependency of UMFPACK (RTLD_NOLOAD: never loads one).
// None in the portable build (no BLAS under Eigen's solvers) or on Windows (no dlfcn.h).
void* openblas_symbol([[maybe_unused]] const char* name) {
#ifdef GEOFAIR_OPENBLAS_LOOKUP
  if (void* f = dlsym(RTLD_DEFAULT, name)) return f;
  if (void* library = dlopen("libopenblas.so.0", RTLD_LAZY | RTLD_NOLOAD))
    return dlsym(library, name);
#endif
  return nullptr;
}
SetThreads set_threads() {
  static const auto f =
      reinterpret_cast<SetThreads>(openblas_symbol("openblas_set_num_threads"));
  return f;
}
GetThreads get_threads() {
  static const auto f =
      reinterpret_cast<GetThreads>(openblas_symbol("openblas_get_num_threads"));
  return f;
}
#endif

}  // namespace

#ifndef GEOFAIR_BLAS_LOADER
// The BLAS is linked (or, in the portable build, not used): nothing to load.
bool blas_loaded_at_run_time() { return false; }
void load_blas(const std::string&) {}
bool blas_loaded() { return true; }
#endif

BlasThreads::BlasThreads(int threads) {
  if (set_threads() && get_threads()) {
    previous_ = get_threads()();
    if (previous_ != threads) set_threads()(threads);
  }
}

BlasThreads::~BlasThreads() {
  if (previous_ > 0 && previous_ != get_threads()()) set_threads()(previous_);
}

namespace {

// UMFPACK with Index as its index type: int (umfpack_di_*) or SuiteSparse_long
// (umfpack_dl_*); in a portable build (GEOFAIR_PORTABLE) Eigen's SparseLU with COLAMD.
template <class Index>
struct IndexedFactors {
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, Index>;
  Matrix matrix;
#ifdef GEOFAIR_PORTABLE
  Eigen::SparseLU<Matrix, Eigen::COLAMDOrdering<Index>> lu;
#else
  Eigen::UmfPackLU<Matrix> lu;
#endif
  bool analyzed = false, factorized = false;

  void analyze(const Eigen::SparseMatrix<double>& pattern, bool nested_dissection) {
    matrix = pattern;
    for (int c = 0; c < matrix.outerSize(); ++c)
      for (typename Matrix::InnerIterator it(matrix, c); it; ++it)
        it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
#ifndef GEOFAIR_PORTABLE
    if (nested_dissection) lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
#else
    (void)nested_dissection;  // no METIS: COLAMD's ordering
#endif
    analyze_matrix();
  }
  bool factorize(const Eigen::SparseMatrix<double>& A) {
    factorized = false;
    // A new pattern (or the first) is analyzed anew.
    if (analyzed && !same_pattern(A)) analyzed = false;
    matrix = A;
    if (!analyzed) analyze_matrix();
    lu.factorize(matrix);
    factorized = lu.info() == Eigen::Success;
    return factorized;
  }
  // The symbolic analysis of matrix's pattern; solves without iterative refinement.
  void analyze_matrix() {
#ifndef GEOFAIR_PORTABLE
    lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
#endif
    lu.analyzePattern(matrix);
    analyzed = true;
  }
  bool same_pattern(const Eigen::SparseMatrix<double>& A) const {
    return A.rows() == matrix.rows() && A.cols() == matrix.cols() &&
           A.nonZeros() == matrix.nonZeros() && A.isCompressed() &&
           std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1,
                      matrix.outerIndexPtr()) &&
           std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(),
                      matrix.innerIndexPtr());
  }
};

}  // namespace

struct PatternLU::Factors {
  IndexedFactors<int> narrow;
#ifdef GEOFAIR_PORTABLE
  IndexedFactors<std::int64_t> wide;
#else
  IndexedFactors<SuiteSparse_long> wide;
#endif
  bool wide_in_use = false;  // kWideIndexMin unknowns or more
};

PatternLU::PatternLU() : factors_(std::make_unique<Factors>()) {}
PatternLU::~PatternLU() = default;

void PatternLU::analyze(const Eigen::SparseMatrix<double>& pattern, bool nested_dissection) {
  Factors& f = *factors_;
  f.wide_in_use = pattern.rows() >= kWideIndexMin;
  f.wide_in_use ? f.wide.analyze(pattern, nested_dissection)
                : f.narrow.analyze(pattern, nested_dissection);
}

bool PatternLU::factorize(const Eigen::SparseMatrix<double>& A) {
  Factors& f = *factors_;
  f.wide_in_use = A.rows() >= kWideIndexMin;
  return f.wide_in_use ? f.wide.factorize(A) : f.narrow.factorize(A);
}

bool PatternLU::factorized() const {
  return factors_->wide_in_use ? factors_->wide.factorized : factors_->narrow.factorized;
}

Eigen::VectorXd PatternLU::solve(const Eigen::VectorXd& b) const {
  if (factors_->wide_in_use) return factors_->wide.lu.solve(b);
  return factors_->narrow.lu.solve(b);
}

}  // namespace geofair
