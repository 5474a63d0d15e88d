// Inner fairness weights (Schneider & Kobbelt 2001, section 7.3).
#include "geofair/inner_fairness.h"
#include "geofair/laplace_beltrami.h"
#include "geofair/region.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace geofair {
namespace {

std::vector<double> cotangents(const OneRings& rings, const Positions& X, int i) {
  std::vector<double> w(rings.valence(i));
  cotangent_weights(rings, X, i, w.data());
  return w;
}

TEST(ConformalWeights, ClampedCotangentWeightsOnAPlanarMesh) {
  // A jittered grid has obtuse triangles, hence negative cotangent weights; in the plane
  // the positive ones always surround their vertex, so every weight is the clamped one.
  const testing::Mesh m = testing::planar_grid(8, 0.45);
  const OneRings rings = build_one_rings(int(m.V.rows()), m.F, "test");
  const InnerFairnessWeights lambda = ring_inner_fairness_weights(rings, m.V, InnerFairness::Conformal);
  int negative = 0;
  for (int i = 0; i < lambda.size(); ++i) {
    if (!rings.closed(i)) continue;
    std::vector<double> w = cotangents(rings, m.V, i);
    double sum = 0.0;
    for (double& x : w) {
      negative += x < 0.0;
      x = std::max(x, 0.0);
      sum += x;
    }
    for (int k = 0; k < rings.valence(i); ++k)
      EXPECT_NEAR(lambda.weight[lambda.offset[i] + k], w[k] / sum, 1e-15) << "vertex " << i;
  }
  EXPECT_GT(negative, 0);
  EXPECT_EQ(lambda.row_sum.size(), std::size_t(lambda.size()));  // symmetric weights
}

TEST(ConformalWeights, MeanValueWeightsWhereThePositiveOnesDoNotSurroundTheVertex) {
  // A sharp cone point of valence 4 (angle sum 141°) from the face of Fig. 10: two of its
  // cotangent weights are negative, and the two positive ones lie on one side of it.
  // Clamped, λ would put the vertex on the segment between those two and collapse its
  // triangles; the mean value weights keep all four neighbours.
  testing::Mesh m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, -0.534, -0.318, 0.325, -0.606, -0.302, 0.019, -0.267, -0.189, -0.094,
      -0.055, -0.164, 0.108;
  m.F.resize(4, 3);
  m.F << 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1;
  const OneRings rings = build_one_rings(5, m.F, "test");
  ASSERT_TRUE(rings.closed(0));
  const std::vector<double> w = cotangents(rings, m.V, 0);
  EXPECT_EQ(std::count_if(w.begin(), w.end(), [](double x) { return x > 0.0; }), 2);

  const InnerFairnessWeights lambda = ring_inner_fairness_weights(rings, m.V, InnerFairness::Conformal);
  double sum = 0.0;
  for (int k = lambda.offset[0]; k < lambda.offset[1]; ++k) {
    EXPECT_GT(lambda.weight[k], 0.05);
    sum += lambda.weight[k];
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
  EXPECT_TRUE(lambda.row_sum.empty());  // not symmetric
  // The weighted centroid lies off the segment between the two positively weighted
  // neighbours, by more than a tenth of the ring's mean edge length.
  int a = -1, b = -1;
  for (int k = 0; k < 4; ++k)
    if (w[k] > 0.0) (a < 0 ? a : b) = rings.ring[rings.offset[0] + k];
  const Vec3 c = weighted_centroid(lambda, m.V, 0), p = m.V.row(a), q = m.V.row(b);
  const double t = std::clamp((c - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
  EXPECT_GT((c - p - t * (q - p)).norm(), 0.1 * rings.mean_neighbour_distance(m.V, 0, Vec3::Zero()));
}

}  // namespace
}  // namespace geofair
