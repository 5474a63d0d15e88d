// Moreton–Séquin mean curvature with the spiral samples (Schneider & Kobbelt 2001,
// section 6, eqs. (8)-(11), section 6.2).
#include "geofair/building_blocks.h"
#include "mean_curvature.h"
#include "meshes.h"
#include "small_ldlt.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

namespace geofair {
namespace {

// Max |H − 1/r| over the vertices within `radius` of the axis, with the exact normals.
double sphere_error(const testing::Mesh& m, double r, double radius, bool exact_normals = true) {
  const Positions N = testing::sphere_normals(m.V);
  const Eigen::VectorXd H = mean_curvature(m.V, m.F, exact_normals ? &N : nullptr);
  const std::vector<bool> in = testing::inside(m.V, radius);
  double error = 0.0;
  for (int v = 0; v < m.V.rows(); ++v)
    if (in[v]) error = std::max(error, std::abs(H(v) - 1.0 / r));
  return error;
}

// The quadric normal fit's written-out LDLT gives Eigen's LDLT solution bit for bit: on
// normal equations like the fit's, on positive definite, indefinite and singular matrices.
TEST(SmallLDLT, BitIdenticalToEigen) {
#if defined(EIGEN_VECTORIZE_FMA) || defined(__ARM_FEATURE_FMA) || defined(__FMA__)
  GTEST_SKIP() << "fused multiply-adds: Eigen's order of rounding differs from the written-out one";
#endif
  if (Eigen::internal::packet_traits<double>::size != 2)
    GTEST_SKIP() << "Eigen sums packets of other than two doubles here";
  using M5 = Eigen::Matrix<double, 5, 5>;
  using V5 = Eigen::Matrix<double, 5, 1>;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int differ = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    M5 A = M5::Zero(), B;
    for (int k = 0; k < 25; ++k) B.data()[k] = gauss(rng);
    switch (trial % 4) {
      case 0:  // the fit's: weighted rows (x, y, x²/2, xy, y²/2) of ring samples, regularized
        for (int s = 0; s < 5 + trial % 9; ++s) {
          const double x = uniform(rng), y = uniform(rng), w = 2.0 / (x * x + y * y + 1e-3);
          V5 row;
          row << w * x, w * y, 0.5 * w * x * x, w * x * y, 0.5 * w * y * y;
          A.noalias() += row * row.transpose();
        }
        A.diagonal().array() += 1e-12 * A.trace();
        break;
      case 1: A = B * B.transpose(); break;
      case 2: A = B + B.transpose(); break;  // indefinite: pivots of both signs
      default:                               // rank 2, or zero
        B.rightCols(3).setZero();
        A = trial % 8 == 3 ? M5::Zero() : M5(B * B.transpose());
    }
    V5 b;
    for (int k = 0; k < 5; ++k) b(k) = gauss(rng);
    const V5 eigen = A.ldlt().solve(b), ours = solve_small_ldlt<5>(A, b);
    differ += std::memcmp(eigen.data(), ours.data(), sizeof(double) * 5) != 0;
  }
  EXPECT_EQ(differ, 0);
}

TEST(MeanCurvature, ZeroOnAPlane) {
  const testing::Mesh m = testing::planar_grid(6, 0.3);
  const Eigen::VectorXd H = mean_curvature(m.V, m.F, nullptr);
  EXPECT_LT(H.cwiseAbs().maxCoeff(), 1e-12);
}

TEST(MeanCurvature, SignFollowsTheNormals) {
  const double r = 3.0;
  const testing::Mesh m = testing::onto_sphere(testing::planar_grid(8), r);
  const Positions N = testing::sphere_normals(m.V), inward = -N;
  const int centre = 4 * 9 + 4;
  EXPECT_NEAR(mean_curvature(m.V, m.F, &N)(centre), 1.0 / r, 1e-3);
  EXPECT_NEAR(mean_curvature(m.V, m.F, &inward)(centre), -1.0 / r, 1e-3);
}

TEST(MeanCurvature, ExactOnASphereWithExactNormals) {
  // Every sample of eq. (8) lies on the sphere, and the circle through q_i and q_j that
  // touches the tangent plane at q_i is a circle of the sphere: κ̃_j = 1/r for every j.
  const double r = 3.0;
  EXPECT_LT(sphere_error(testing::onto_sphere(testing::planar_grid(8, 0.2), r), r, 0.6), 1e-12);
}

TEST(MeanCurvature, QuadricNormalsAreConsistent) {
  // With the default (quadric) normals instead of exact ones H still converges.
  const double r = 3.0;
  const double coarse =
      sphere_error(testing::onto_sphere(testing::planar_grid(8, 0.2), r), r, 0.6, false);
  const double fine =
      sphere_error(testing::onto_sphere(testing::planar_grid(16, 0.2), r), r, 0.6, false);
  EXPECT_LT(fine, coarse / 2.0);
  EXPECT_LT(fine, 0.01 / r);
}

TEST(MeanCurvature, ValenceFourUsesTheSpiralSamples) {
  // The centres of split quads have valence 4 with samples on two lines (Lemma 1). The
  // spiral samples of section 6.2 lie on the sphere (the plane E cuts it in a circle that
  // touches both tangent planes), so H stays exact; midpoints of the ring edges would not.
  const double r = 3.0;
  const testing::Mesh m = testing::onto_sphere(testing::centred_quads(8), r);
  EXPECT_LT(sphere_error(m, r, 0.6), 1e-9);
}

TEST(MeanCurvature, ValenceThreeUsesTheSpiralSamples) {
  const double r = 3.0;
  const testing::Mesh m = testing::onto_sphere(testing::split_centroids(testing::planar_grid(8)), r);
  EXPECT_LT(sphere_error(m, r, 0.6), 1e-9);
}

TEST(SpiralSample, LiesOnTheCircleThroughTwoPointsWithTheirNormals) {
  // Both circles of section 6.2 are the circle itself when a, b and their normals come
  // from one circle: the sample is its point halfway between them.
  const double r = 2.0, angle = 0.7;
  const Vec3 a(r, 0, 0), b(r * std::cos(angle), r * std::sin(angle), 0);
  const Vec3 p = spiral_sample(a, a / r, b, b / r, (a + b).normalized());
  EXPECT_NEAR(p.norm(), r, 1e-12);
  EXPECT_NEAR(std::atan2(p.y(), p.x()), angle / 2.0, 1e-12);
  EXPECT_NEAR(p.z(), 0.0, 1e-12);
}

}  // namespace
}  // namespace geofair
