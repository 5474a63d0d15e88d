// Cotangent weights and the Dirichlet matrix S (Schneider & Kobbelt 2001, eqs. (6), (7)).
#include "laplace_beltrami.h"

#include "common.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <vector>

namespace geofair {
namespace {

// cot of the angle at o in the triangle (o, a, b).
inline double cot_at(const Vec3& o, const Vec3& a, const Vec3& b) {
  const Vec3 u = a - o, v = b - o;
  const double cross = u.cross(v).norm();
  const double dot = u.dot(v);
  const double floor = 1e-12 * std::abs(dot);
  return dot / std::max(cross, floor > 0.0 ? floor : 1e-300);
}

}  // namespace

void cotangent_weights(const OneRings& rings, const Positions& X, int i, double* w) {
  const int begin = rings.offset[i], end = rings.offset[i + 1];
  const Vec3 qi = X.row(i);
  for (int k = begin; k < end; ++k) w[k - begin] = 0.0;
  for (int k = begin; k < end; ++k) {
    if (!rings.has_face[k]) continue;
    const int k1 = rings.next_slot(i, k);
    const Vec3 qj = X.row(rings.ring[k]), qj1 = X.row(rings.ring[k1]);
    // Triangle (i, j, j1): the angle at j1 is opposite edge (i, j), the angle at j
    // opposite edge (i, j1).
    w[k - begin] += cot_at(qj1, qi, qj);
    w[k1 - begin] += cot_at(qj, qi, qj1);
  }
}

SparseRowMatrix cotangent_laplacian(const Positions& V, const Triangles& F) {
  const int nv = int(V.rows());
  if (!V.allFinite())
    throw InvalidInputError("cotangent_laplacian: vertices contain a non-finite coordinate");
  const OneRings r = build_one_rings(nv, F, "cotangent_laplacian");
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(r.ring.size() + nv);
  std::vector<double> w;
  for (int i = 0; i < nv; ++i) {
    w.resize(r.valence(i));
    cotangent_weights(r, V, i, w.data());
    double sum = 0.0;
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k) {
      triplets.emplace_back(i, r.ring[k], w[k - r.offset[i]]);
      sum += w[k - r.offset[i]];
    }
    triplets.emplace_back(i, i, -sum);
  }
  SparseRowMatrix L(nv, nv);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

DirichletMatrix::DirichletMatrix(const FairingRegion& region) : region_(region) {
  const OneRings& r = region.rings;
  const int nf = region.n_free;
  std::vector<Eigen::Triplet<double>> pattern;
  pattern.reserve(r.offset[nf] + nf);
  for (int i = 0; i < nf; ++i) {
    pattern.emplace_back(i, i, 1.0);
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k)
      if (r.ring[k] < nf) pattern.emplace_back(i, r.ring[k], 1.0);
  }
  S_.resize(nf, nf);
  S_.setFromTriplets(pattern.begin(), pattern.end());
  S_.makeCompressed();
  slot_weight_.assign(r.offset[nf], 0.0);
  slot_value_.assign(r.offset[nf], -1);
  diag_value_.assign(nf, -1);
  const int* outer = S_.outerIndexPtr();
  const int* inner = S_.innerIndexPtr();
  auto find = [&](int row, int col) {
    const int* it = std::lower_bound(inner + outer[row], inner + outer[row + 1], col);
    return int(it - inner);
  };
  for (int i = 0; i < nf; ++i) {
    diag_value_[i] = find(i, i);
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k)
      if (r.ring[k] < nf) slot_value_[k] = find(i, r.ring[k]);
  }
}

void DirichletMatrix::assemble(const Positions& X) {
  const OneRings& r = region_.rings;
  double* values = S_.valuePtr();
  std::fill(values, values + S_.nonZeros(), 0.0);
  const int nf = region_.n_free;
  // Row i of S and the slots of vertex i are written by vertex i alone.
  parallel_for(nf, nf > kParallelMin, [&](int i) {
    cotangent_weights(r, X, i, slot_weight_.data() + r.offset[i]);
    double diag = 0.0;
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k) {
      diag += slot_weight_[k];
      if (slot_value_[k] >= 0) values[slot_value_[k]] -= slot_weight_[k];
    }
    values[diag_value_[i]] += diag;
  });
}

Eigen::VectorXd DirichletMatrix::rhs(const Eigen::VectorXd& H) const {
  const OneRings& r = region_.rings;
  const int nf = region_.n_free;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(nf);
  parallel_for(nf, nf > kParallelMin, [&](int i) {
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k)
      if (r.ring[k] >= nf) b(i) += slot_weight_[k] * H(r.ring[k]);
  });
  return b;
}

Eigen::VectorXd DirichletMatrix::defects(const Eigen::VectorXd& H) const {
  const OneRings& r = region_.rings;
  const int nf = region_.n_free;
  Eigen::VectorXd d(nf);
  parallel_for(nf, nf > kParallelMin, [&](int i) {
    double sum = 0.0;
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k)
      sum += slot_weight_[k] * (H(i) - H(r.ring[k]));
    d(i) = sum;
  });
  return d;
}

double DirichletMatrix::max_mean_deviation(const Eigen::VectorXd& H,
                                           const Eigen::VectorXd* source) const {
  const OneRings& r = region_.rings;
  const int nf = region_.n_free;
  // Each chunk's largest deviation (NaN if it met one), combined after: max is order-free.
  std::vector<double> chunk_worst(std::size_t(loop_threads()), 0.0);
  parallel_chunks(nf, nf > kParallelMin, [&](int t, int first, int last) {
    double worst = 0.0;
    for (int i = first; i < last && !std::isnan(worst); ++i) {
      double sum = 0.0, sum_w = 0.0;
      for (int k = r.offset[i]; k < r.offset[i + 1]; ++k) {
        sum += slot_weight_[k] * (H(r.ring[k]) - H(i));
        sum_w += slot_weight_[k];
      }
      if (source) sum += (*source)(i);
      const double deviation = std::abs(sum) / std::max(sum_w, 1e-300);
      worst = std::isnan(deviation) ? deviation : std::max(worst, deviation);
    }
    chunk_worst[std::size_t(t)] = worst;
  });
  double worst = 0.0;
  for (const double w : chunk_worst) {
    if (std::isnan(w)) return std::numeric_limits<double>::quiet_NaN();
    worst = std::max(worst, w);
  }
  return worst;
}

}  // namespace geofair
