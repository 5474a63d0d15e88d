// Inner fairness weights (Schneider & Kobbelt 2001, section 7.3).
#include "inner_fairness.h"
#include "laplace_beltrami.h"
#include "region.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
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

// A planar grid of quads, each split into two triangles (planar_grid: triangles 2q and
// 2q + 1 are quad q), free within radius 0.6 of its centre (the G1 boundary then stays off
// the grid's border).
Positions region_positions(const Positions& V, const FairingRegion& region) {
  Positions X(region.n, 3);
  for (int i = 0; i < region.n; ++i) X.row(i) = V.row(region.global[i]);
  return X;
}

FairingRegion quad_grid_region(const testing::Mesh& m, const std::vector<int>* polygon_ids) {
  Positions up = Positions::Zero(m.V.rows(), 3);
  up.col(2).setOnes();
  return extract_region(m.V, m.F, testing::inside(m.V, 0.6), &up, true, polygon_ids);
}

TEST(UniformWeights, OverThePolygonEdgesOfATriangulatedQuadGrid) {
  const testing::Mesh m = testing::planar_grid(8);
  std::vector<int> quads(m.F.rows());
  for (int t = 0; t < int(quads.size()); ++t) quads[t] = t / 2;
  const FairingRegion region = quad_grid_region(m, &quads);
  const Positions X0 = region_positions(m.V, region);
  const InnerFairnessWeights lambda = inner_fairness_weights(region, X0, InnerFairness::Uniform);
  const double h = 0.25;
  for (int i = 0; i < region.n_free; ++i) {
    int kept = 0;
    for (int k = lambda.offset[i]; k < lambda.offset[i + 1]; ++k) {
      const double distance = (X0.row(lambda.neighbour[k]) - X0.row(i)).norm();
      const bool diagonal = distance > 1.2 * h;  // the quad's diagonal is h·√2 long
      EXPECT_EQ(bool(region.polygon_diagonal[k]), diagonal) << "vertex " << i;
      EXPECT_DOUBLE_EQ(lambda.weight[k], diagonal ? 0.0 : 0.25) << "vertex " << i;
      kept += !diagonal;
    }
    EXPECT_EQ(kept, 4) << "vertex " << i;
  }
  EXPECT_EQ(lambda.row_sum.size(), std::size_t(region.n));  // still symmetric

  // Without polygons: 1/valence over the triangles' edges, diagonals included.
  const FairingRegion triangles = quad_grid_region(m, nullptr);
  EXPECT_TRUE(triangles.polygon_diagonal.empty());
  const InnerFairnessWeights plain = inner_fairness_weights(triangles, X0, InnerFairness::Uniform);
  for (int i = 0; i < triangles.n_free; ++i)
    for (int k = plain.offset[i]; k < plain.offset[i + 1]; ++k)
      EXPECT_DOUBLE_EQ(plain.weight[k], 1.0 / triangles.rings.valence(i));
}

TEST(UniformWeights, BogusPolygonsKeepTheTriangleUmbrella) {
  // One "polygon" for all triangles: every interior edge is a diagonal, so every vertex
  // keeps its whole ring, and the weights are those without polygons.
  const testing::Mesh m = testing::planar_grid(8);
  const std::vector<int> one(m.F.rows(), 7);
  const FairingRegion region = quad_grid_region(m, &one);
  const FairingRegion plain_region = quad_grid_region(m, nullptr);
  const Positions X0 = region_positions(m.V, region);
  const InnerFairnessWeights lambda = inner_fairness_weights(region, X0, InnerFairness::Uniform);
  const InnerFairnessWeights plain = inner_fairness_weights(plain_region, X0, InnerFairness::Uniform);
  EXPECT_EQ(lambda.weight, plain.weight);
  EXPECT_EQ(lambda.row_sum, plain.row_sum);
}

TEST(UniformWeights, PolygonIdsOfTheWrongSizeAreAnError) {
  const testing::Mesh m = testing::planar_grid(4);
  const std::vector<int> short_ids(m.F.rows() - 1, 0);
  EXPECT_THROW(quad_grid_region(m, &short_ids), InvalidInputError);
}


// check_triangles refuses what build_one_rings refuses, with the same message, and accepts
// what it accepts.
TEST(Region, CheckTrianglesAgreesWithBuildOneRings) {
  const testing::Mesh m = testing::hexagon_fan();
  auto message = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const InvalidInputError& e) {
      return e.what();
    }
    return "";
  };
  std::vector<Triangles> cases;
  cases.push_back(m.F);  // valid
  Triangles out_of_range = m.F;
  out_of_range(2, 1) = 7;
  cases.push_back(out_of_range);
  Triangles repeated = m.F;
  repeated(3, 2) = repeated(3, 1);
  cases.push_back(repeated);
  Triangles flipped = m.F;
  std::swap(flipped(4, 1), flipped(4, 2));
  cases.push_back(flipped);
  Triangles third_face(m.F.rows() + 1, 3);  // a third triangle on the edge (0, 1)
  third_face << m.F, m.F.row(0);
  third_face.bottomRows(1)(0, 2) = m.F(3, 2);
  cases.push_back(third_face);
  for (size_t k = 0; k < cases.size(); ++k) {
    const int n = int(m.V.rows());
    const std::string expected = message([&] { build_one_rings(n, cases[k], "test"); });
    EXPECT_EQ(message([&] { check_triangles(n, cases[k], "test"); }), expected) << "case " << k;
    EXPECT_EQ(expected.empty(), k == 0) << "case " << k;
  }
}

}  // namespace
}  // namespace geofair
