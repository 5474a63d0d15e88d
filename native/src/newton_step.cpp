// Newton's method for the normal offsets, see newton_step.h.
#include "newton_step.h"

#include "common.h"
#include "mean_curvature.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <system_error>

namespace geofair {

NewtonStep::NewtonStep(const FairingRegion& region, const NewtonTuning& tuning,
                       NormalWeighting weighting)
    : region_(region), tuning_(tuning), weighting_(weighting) {
  // Rows of J: region vertex k holds (m, ∂H_k/∂t_m) for m = k (if free) and for the free
  // vertices m of its ring; the entry of column m at row k lives at slot k of m's ring.
  const OneRings& r = region.rings;
  const int nf = region.n_free, n = region.n;
  row_offset_.assign(n + 1, 0);
  for (int m = 0; m < nf; ++m) {
    ++row_offset_[m + 1];
    for (int k = r.offset[m]; k < r.offset[m + 1]; ++k) ++row_offset_[r.ring[k] + 1];
  }
  for (int k = 0; k < n; ++k) row_offset_[k + 1] += row_offset_[k];
  std::vector<int> fill(row_offset_.begin(), row_offset_.end() - 1);
  row_column_.resize(row_offset_.back());
  row_source_.resize(row_offset_.back());
  for (int m = 0; m < nf; ++m) {
    row_column_[fill[m]] = m, row_source_[fill[m]++] = m;
    for (int k = r.offset[m]; k < r.offset[m + 1]; ++k) {
      const int j = r.ring[k];
      row_column_[fill[j]] = m, row_source_[fill[j]++] = nf + k;
    }
  }
  // The pattern of A = D J (2-ring) and, per term of the assembly in assemble(), the index of
  // its entry in A's values.
  auto for_each_term = [&](auto&& term) {
    for (int i = 0; i < nf; ++i) {
      for (int k = r.offset[i]; k < r.offset[i + 1]; ++k)
        for (int p = row_offset_[r.ring[k]]; p < row_offset_[r.ring[k] + 1]; ++p)
          term(i, row_column_[p]);
      for (int p = row_offset_[i]; p < row_offset_[i + 1]; ++p) term(i, row_column_[p]);
    }
  };
  // The distinct entries (i, c) row by row (a row's terms repeat them), each term's entry
  // among them, then A's compressed columns by counting (rows ascending in each column):
  // the pattern without sorting the terms.
  std::vector<int> entry_row, entry_column, term_pair, last_row(nf, -1), slot(nf);
  for_each_term([&](int i, int c) {
    if (last_row[c] != i) {
      last_row[c] = i, slot[c] = int(entry_column.size());
      entry_row.push_back(i), entry_column.push_back(c);
    }
    term_pair.push_back(slot[c]);
  });
  const int nnz = int(entry_column.size());
  A_.resize(nf, nf);
  A_.resizeNonZeros(nnz);
  int* start = A_.outerIndexPtr();
  std::fill(start, start + nf + 1, 0);
  for (const int c : entry_column) ++start[c + 1];
  for (int c = 0; c < nf; ++c) start[c + 1] += start[c];
  std::fill(A_.valuePtr(), A_.valuePtr() + nnz, 0.0);
  std::vector<int> next(start, start + nf), pair_entry(nnz);
  for (int q = 0; q < nnz; ++q) {
    pair_entry[q] = next[entry_column[q]]++;
    A_.innerIndexPtr()[pair_entry[q]] = entry_row[q];
  }
  term_entry_.resize(term_pair.size());
  for (std::size_t t = 0; t < term_pair.size(); ++t) term_entry_[t] = pair_entry[term_pair[t]];
  auto entry = [&](int i, int c) { return stored_entry(A_, c, i); };  // A is column-major
  diagonal_entry_.resize(nf);
  for (int c = 0; c < nf; ++c) diagonal_entry_[c] = entry(c, c);
}

void NewtonStep::assemble(const Positions& X, const Positions& N, const Eigen::VectorXd& H,
                          const std::vector<double>& w) {
  const OneRings& r = region_.rings;
  const int nf = region_.n_free;
  const bool g0 = region_.boundary == BoundaryCondition::G0;
  // Columns of J by forward differences: move free vertex m by h along its normal and
  // re-estimate the normals and H at m and its ring (a G1 boundary's normals are fixed).
  // Each thread moves vertices in its own copy of X.
  jacobian_.resize(std::size_t(nf) + r.offset[nf]);
  auto normal = [&](const Positions& Y, int k) -> Vec3 {
    const Vec3 estimate = k < nf ? vertex_normal(r, Y, k, weighting_) : Vec3(Vec3::Zero());
    return estimate.squaredNorm() > 0.0 ? estimate : Vec3(N.row(k).transpose());
  };
  parallel_chunks(nf, nf > kParallelMin, [&](int, int first, int last) {
    Positions Y = X;
    for (int m = first; m < last; ++m) {
      const int begin = r.offset[m], end = r.offset[m + 1];
      const double h = 1e-6 * r.mean_neighbour_distance(X, m);
      Y.row(m) = X.row(m) + h * N.row(m);
      const Vec3 n_m = normal(Y, m);
      jacobian_[m] =
          (moreton_sequin(r, Y, N, m, Y.row(m), n_m, needs_spiral_samples(r, m)).H - H(m)) / h;
      for (int k = begin; k < end; ++k) {
        const int j = r.ring[k];
        if (j >= nf && g0) {  // H = 0 prescribed on a G0 boundary
          jacobian_[nf + k] = 0.0;
          continue;
        }
        jacobian_[nf + k] = (moreton_sequin(r, Y, N, j, Y.row(j), normal(Y, j),
                                            needs_spiral_samples(r, j)).H - H(j)) / h;
      }
      Y.row(m) = X.row(m);
    }
  });
  // A = D J, row i: Σ_j w_ij (J(i, ·) − J(j, ·)) over the ring j of i (terms in the
  // constructor's order).
  double* value = A_.valuePtr();
  std::fill(value, value + A_.nonZeros(), 0.0);
  const int* entry = term_entry_.data();
  for (int i = 0; i < nf; ++i) {
    double sum_w = 0.0;
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k) {
      const int j = r.ring[k];
      sum_w += w[k];
      for (int p = row_offset_[j]; p < row_offset_[j + 1]; ++p)
        value[*entry++] -= w[k] * jacobian_[row_source_[p]];
    }
    for (int p = row_offset_[i]; p < row_offset_[i + 1]; ++p)
      value[*entry++] += sum_w * jacobian_[row_source_[p]];
  }
}

void NewtonStep::prefactorize(const Positions& X, const Positions& N, const Eigen::VectorXd& H,
                              const std::vector<double>& w, bool async) {
  discard_prefactorization();
  assemble(X, N, H, w);
  factorized_sigma_ = 0.0;
  refactorize_ = false;
  if (async) {
    try {
      prefactorization_ = std::async(std::launch::async, [this] { return lu_.factorize(A_); });
    } catch (const std::system_error&) {  // no thread to be had: factorized here
      async = false;
    }
  }
  if (!async) lu_.factorize(A_);
  prefactorized_ = true;
}

bool NewtonStep::finish_prefactorization() {
  if (!prefactorized_) return false;
  prefactorized_ = false;
  const bool factorized =
      prefactorization_.valid() ? prefactorization_.get() : lu_.factorized();
  if (!factorized) refactorize_ = true;
  return factorized;
}

void NewtonStep::discard_prefactorization() {
  if (finish_prefactorization()) refactorize_ = true;
}

bool NewtonStep::solve(const Positions& X, const Positions& N, const Eigen::VectorXd& H,
                       const std::vector<double>& w, const Eigen::VectorXd& defects,
                       const Eigen::VectorXd* tau, const JacobianProduct& product,
                       const Shift& shift, double krylov_tolerance, Eigen::VectorXd& t) {
  bool ahead = finish_prefactorization();  // a fresh factorization, made before the call
  Eigen::VectorXd b = tau ? Eigen::VectorXd(*tau - defects) : Eigen::VectorXd(-defects);
  const double sigma = shift.mass ? shift.sigma : 0.0;
  const JacobianProduct shifted = [&](const Eigen::VectorXd& v, Eigen::VectorXd& Jv) {
    product(v, Jv);
    if (sigma > 0.0) Jv += sigma * shift.mass->cwiseProduct(v);
  };
  // A factorization with a shift that differs by more than a factor shift_refactorization
  // (shifts below shift_negligible count as none) preconditions poorly: refactorize.
  auto effective = [this](double s) { return std::max(s, tuning_.shift_negligible); };
  const double ratio = effective(sigma) / effective(factorized_sigma_);
  if (ratio > tuning_.shift_refactorization || ratio < 1.0 / tuning_.shift_refactorization)
    refactorize_ = true;
  // With the factorization of an earlier step first; if GMRES does not converge on it,
  // refactorize at X and solve again.
  const JacobianOperator J(b.size(), shifted);
  gmres_.preconditioner().lu = &lu_;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const bool fresh = refactorize_ || !lu_.factorized();
    if (fresh) {
      assemble(X, N, H, w);
      if (sigma > 0.0)
        for (int i = 0; i < region_.n_free; ++i)
          A_.valuePtr()[diagonal_entry_[i]] += sigma * (*shift.mass)(i);
      factorized_sigma_ = sigma;
      if (!lu_.factorize(A_)) return false;
      refactorize_ = false;
    }
    // A lagged factorization converges slowly: each decade below krylov_tolerance costs it
    // several iterations, a fresh one about one.
    set_up_gmres(gmres_, J, tuning_.krylov_iterations,
                 fresh || ahead ? krylov_tolerance : tuning_.krylov_tolerance);
    t = gmres_.solve(b);
    // The iterations a stale factorization costs beyond a fresh one's, summed until a
    // refactorization would have been cheaper.
    const int iterations = int(gmres_.iterations());
    if (fresh || ahead) first_iterations_ = iterations, extra_products_ = 0;
    ahead = false;
    extra_products_ += std::max(0, iterations - first_iterations_);
    if (iterations > tuning_.krylov_iterations / 2 ||
        extra_products_ >= tuning_.refactorization_products)
      refactorize_ = true;
    // A tighter solve that stops short of its target still made the ordinary step.
    const bool solved =
        gmres_.info() == Eigen::Success || gmres_.error() <= tuning_.krylov_tolerance;
    if (solved && t.allFinite()) return true;
    refactorize_ = true;
    if (fresh) break;
  }
  return t.allFinite() && gmres_.iterations() > 0;
}

}  // namespace geofair
