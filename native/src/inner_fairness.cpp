// Uniform and discrete-conformal inner fairness weights (section 7.3).
#include "geofair/inner_fairness.h"

#include "geofair/laplace_beltrami.h"

#include <algorithm>

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

}  // namespace geofair
