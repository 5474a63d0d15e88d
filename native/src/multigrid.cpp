// Prolongation of section 7.4.
#include "geofair/multigrid.h"

#include "geofair/inner_fairness.h"

#include <algorithm>

namespace geofair {
namespace {

// λ of a closed fan: uniform, or clamped cotangent weights of the original positions.
void split_weights(const int* ring, int m, int center, InnerFairness inner, const Positions& X0,
                   std::vector<double>& lambda) {
  lambda.assign(m, 1.0 / m);
  if (inner != InnerFairness::Conformal) return;
  const Vec3 q = X0.row(center);
  auto cot = [](const Vec3& o, const Vec3& a, const Vec3& b) {
    const Vec3 u = a - o, v = b - o;
    const double c = u.cross(v).norm();
    return c > 0.0 ? u.dot(v) / c : 0.0;
  };
  double sum = 0.0;
  std::vector<double> w(m, 0.0);
  for (int k = 0; k < m; ++k) {
    const Vec3 prev = X0.row(ring[(k + m - 1) % m]), here = X0.row(ring[k]),
               next = X0.row(ring[(k + 1) % m]);
    w[k] = std::max(0.0, cot(prev, q, here) + cot(next, q, here));
    sum += w[k];
  }
  if (sum > 0.0)
    for (int k = 0; k < m; ++k) lambda[k] = w[k] / sum;
}

}  // namespace

void prolongate(const FairingRegion& level, const VertexSplits& splits, InnerFairness inner,
                const Positions& X0, Positions& X, Construction& construction) {
  const OneRings& rings = level.rings;
  const std::vector<double>& lambda = construction.lambda();

  // 1. Each new vertex at the inner-fairness position of the ring it is split into.
  std::vector<double> w;
  for (std::size_t s = 0; s < splits.size(); ++s) {
    const int* ring = splits.ring.data() + splits.offset[s];
    const int m = splits.offset[s + 1] - splits.offset[s];
    split_weights(ring, m, splits.vertex[s], inner, X0, w);
    Vec3 q = Vec3::Zero();
    for (int k = 0; k < m; ++k) q += w[k] * X.row(ring[k]).transpose();
    X.row(splits.vertex[s]) = q;
  }

  // The union of the 1-disks of the new vertices (free vertices only).
  std::vector<std::uint8_t> in_disk(level.n, 0);
  std::vector<int> disk;
  auto add = [&](int j) {
    if (j < level.n_free && !in_disk[j]) {
      in_disk[j] = 1;
      disk.push_back(j);
    }
  };
  for (int i : splits.vertex) {
    add(i);
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k) add(rings.ring[k]);
  }

  // 2. Relax the disks: Δq_l = Σ_j λ_lj q_j − q_l = 0.
  for (int sweep = 0; sweep < 2; ++sweep)
    for (int l : disk) X.row(l) = weighted_centroid(rings, lambda, X, l);

  // 3. Restore outer fairness locally.
  construction.local_steps(X, disk, 2);
}

}  // namespace geofair
