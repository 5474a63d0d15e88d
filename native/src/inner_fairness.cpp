// Uniform and discrete-conformal inner fairness weights (section 7.3).
#include "geofair/inner_fairness.h"

#include "geofair/laplace_beltrami.h"

#include <algorithm>
#include <cmath>

namespace geofair {

std::vector<double> inner_fairness_weights(const OneRings& rings, const Positions& X0,
                                           InnerFairness type) {
  const int nv = int(rings.offset.size()) - 1;
  std::vector<double> lambda(rings.ring.size(), 0.0);
  for (int i = 0; i < nv; ++i) {
    const int begin = rings.offset[i], m = rings.valence(i);
    if (m == 0) continue;
    double sum = 0.0;
    if (type == InnerFairness::Conformal) {
      cotangent_weights(rings, X0, i, lambda.data() + begin);
      for (int k = begin; k < begin + m; ++k) {
        lambda[k] = std::max(lambda[k], 0.0);
        sum += lambda[k];
      }
    }
    if (!(sum > 0.0) || !std::isfinite(sum)) {
      std::fill(lambda.begin() + begin, lambda.begin() + begin + m, 1.0);
      sum = m;
    }
    for (int k = begin; k < begin + m; ++k) lambda[k] /= sum;
  }
  return lambda;
}

Vec3 weighted_centroid(const OneRings& rings, const std::vector<double>& lambda,
                       const Positions& X, int i) {
  Vec3 c = Vec3::Zero();
  for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
    c += lambda[k] * X.row(rings.ring[k]).transpose();
  return c;
}

TangentialSolver::TangentialSolver(const OneRings& rings, int n_free, int iterations)
    : rings_(rings), n_free_(n_free) {
  // Block pattern: 2×2 blocks at (i, i) and at (i, j) for free ring neighbours j.
  std::vector<Eigen::Triplet<double>> pattern;
  for (int i = 0; i < n_free; ++i) {
    auto block = [&](int j) {
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) pattern.emplace_back(2 * i + a, 2 * j + b, 1.0);
    };
    block(i);
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
      if (rings.ring[k] < n_free) block(rings.ring[k]);
  }
  A_.resize(2 * n_free, 2 * n_free);
  A_.setFromTriplets(pattern.begin(), pattern.end());
  A_.makeCompressed();
  // Blocks are found through the first of their four entries (row 2i, column 2j); the
  // second row of the block starts at the same offset in row 2i+1.
  auto find = [&](int row, int col) {
    const int* inner = A_.innerIndexPtr() + A_.outerIndexPtr()[row];
    const int* end = A_.innerIndexPtr() + A_.outerIndexPtr()[row + 1];
    return int(std::lower_bound(inner, end, col) - A_.innerIndexPtr());
  };
  diag_value_.resize(n_free);
  slot_value_.assign(rings.offset[n_free], -1);
  for (int i = 0; i < n_free; ++i) {
    diag_value_[i] = find(2 * i, 2 * i);
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
      if (rings.ring[k] < n_free) slot_value_[k] = find(2 * i, 2 * rings.ring[k]);
  }
  solver_.setMaxIterations(iterations);
  solver_.setTolerance(1e-12);
}

void TangentialSolver::step(const std::vector<double>& lambda, const Positions& N, double damping,
                            Positions& X) {
  const int nf = n_free_;
  std::vector<Vec3> t1(nf), t2(nf);
  for (int i = 0; i < nf; ++i) {
    const Vec3 n = N.row(i);
    const Vec3 helper = std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    t1[i] = n.cross(helper).normalized();
    t2[i] = n.cross(t1[i]);
  }
  double* values = A_.valuePtr();
  const int* outer = A_.outerIndexPtr();
  // Entry (row 2i+a, column 2j+b) of the block whose first entry is at p.
  auto entry = [&](int i, int p, int a, int b) -> double& {
    return values[p + b + (a ? outer[2 * i + 1] - outer[2 * i] : 0)];
  };
  Eigen::VectorXd rhs(2 * nf);
  for (int i = 0; i < nf; ++i) {
    const int p = diag_value_[i];
    entry(i, p, 0, 0) = entry(i, p, 1, 1) = 1.0;
    entry(i, p, 0, 1) = entry(i, p, 1, 0) = 0.0;
    const Vec3 residual = weighted_centroid(rings_, lambda, X, i) - X.row(i).transpose();
    rhs(2 * i) = residual.dot(t1[i]);
    rhs(2 * i + 1) = residual.dot(t2[i]);
    for (int k = rings_.offset[i]; k < rings_.offset[i + 1]; ++k) {
      if (slot_value_[k] < 0) continue;
      const int j = rings_.ring[k], q = slot_value_[k];
      entry(i, q, 0, 0) = -lambda[k] * t1[i].dot(t1[j]);
      entry(i, q, 0, 1) = -lambda[k] * t1[i].dot(t2[j]);
      entry(i, q, 1, 0) = -lambda[k] * t2[i].dot(t1[j]);
      entry(i, q, 1, 1) = -lambda[k] * t2[i].dot(t2[j]);
    }
  }
  solver_.compute(A_);
  const Eigen::VectorXd u = solver_.solve(rhs);
  if (!u.allFinite()) return;  // a breakdown: leave the tangential positions to the local steps
  for (int i = 0; i < nf; ++i) {
    double mean_distance = 0.0;
    for (int k = rings_.offset[i]; k < rings_.offset[i + 1]; ++k)
      mean_distance += (X.row(rings_.ring[k]) - X.row(i)).norm();
    mean_distance /= rings_.valence(i);
    Vec3 d = u(2 * i) * t1[i] + u(2 * i + 1) * t2[i];
    const double len = d.norm();
    if (len > 0.5 * mean_distance) d *= 0.5 * mean_distance / len;
    X.row(i) += damping * d.transpose();
  }
}

}  // namespace geofair
