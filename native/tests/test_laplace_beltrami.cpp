// Cotangent Laplace–Beltrami operator (Schneider & Kobbelt 2001, section 5, eqs. (5)-(7)).
#include "geofair/building_blocks.h"
#include "laplace_beltrami.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace geofair {
namespace {

TEST(CotangentLaplacian, RegularHexagonHasWeightsTwoCot60) {
  // Every spoke is opposite two 60° angles.
  const testing::Mesh m = testing::hexagon_fan();
  const SparseRowMatrix L = cotangent_laplacian(m.V, m.F);
  for (int k = 1; k <= 6; ++k) EXPECT_NEAR(L.coeff(0, k), 2.0 / std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(L.coeff(0, 0), -12.0 / std::sqrt(3.0), 1e-13);
  // A border edge has one triangle: cot 60° from the centre's angle.
  EXPECT_NEAR(L.coeff(1, 2), 1.0 / std::sqrt(3.0), 1e-14);
}

TEST(CotangentLaplacian, WeightIsNegativeAcrossTwoObtuseAngles) {
  // Two triangles on the edge (0, 1) whose opposite angles are both 120°.
  testing::Mesh m;
  const double y = 0.5 / std::sqrt(3.0);  // apex height of a 30-120-30 triangle on a unit base
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0.5, y, 0, 0.5, -y, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 1, 0, 3;
  const SparseRowMatrix L = cotangent_laplacian(m.V, m.F);
  EXPECT_NEAR(L.coeff(0, 1), -2.0 / std::sqrt(3.0), 1e-13);
}

TEST(CotangentLaplacian, SymmetricWithConstantsInTheNullSpace) {
  const testing::Mesh m = testing::onto_sphere(testing::planar_grid(6, 0.3), 3.0);
  const SparseRowMatrix L = cotangent_laplacian(m.V, m.F);
  const Eigen::MatrixXd D(L);
  EXPECT_LT((D - D.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((D * Eigen::VectorXd::Ones(D.cols())).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(CotangentLaplacian, LinearFunctionsAreHarmonicOnAPlanarMesh) {
  // Linear precision: Σ_j w_ij (f_j − f_i) = 0 at interior vertices of any planar mesh.
  const int n = 8;
  const testing::Mesh m = testing::planar_grid(n, 0.3);
  const SparseRowMatrix L = cotangent_laplacian(m.V, m.F);
  const Eigen::VectorXd f = 2.0 * m.V.col(0) - 3.0 * m.V.col(1) + Eigen::VectorXd::Constant(m.V.rows(), 1.0);
  const Eigen::VectorXd Lf = L * f;
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) EXPECT_NEAR(Lf(j * (n + 1) + i), 0.0, 1e-12);
}

TEST(CotangentLaplacian, MeanCurvatureNormalOnASphere) {
  // Eq. (5): Σ_j w_ij (q_j − q_i) = 2·(2A_i/3)·H n with H = 1/r; the vector points inward.
  const double r = 3.0;
  const testing::Mesh m = testing::onto_sphere(testing::planar_grid(16), r);
  const SparseRowMatrix L = cotangent_laplacian(m.V, m.F);
  const Positions LX = L * m.V;
  const int centre = 8 * 17 + 8;
  const Vec3 q = m.V.row(centre), lx = LX.row(centre);
  EXPECT_GT(lx.normalized().dot(-q.normalized()), 1.0 - 1e-3);
  // Mixed area A_i/3 of the six triangles, eq. (5): |Σ w (q_j − q_i)| / (4 A_i / 3) ≈ 1/r.
  double area = 0.0;
  for (int t = 0; t < m.F.rows(); ++t)
    for (int c = 0; c < 3; ++c)
      if (m.F(t, c) == centre) {
        const Vec3 a = m.V.row(m.F(t, 0)), b = m.V.row(m.F(t, 1)), d = m.V.row(m.F(t, 2));
        area += 0.5 * (b - a).cross(d - a).norm();
      }
  EXPECT_NEAR(lx.norm() / (4.0 * area / 3.0), 1.0 / r, 2e-3);
}

}  // namespace
}  // namespace geofair
