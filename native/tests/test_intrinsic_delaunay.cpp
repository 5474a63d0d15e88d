// Intrinsic Delaunay triangulation and its cotangent Laplacian (Bobenko & Springborn 2007).
#include "geofair/building_blocks.h"
#include "intrinsic_delaunay.h"
#include "meshes.h"

#include <gtest/gtest.h>

namespace geofair {
namespace {

TEST(IntrinsicDelaunay, DelaunayMeshNeedsNoFlipAndKeepsTheCotangentLaplacian) {
  // A low pyramid over a regular hexagon: every angle acute, so no edge needs a flip.
  const testing::Mesh m = testing::hexagon_fan(0.3);
  int flips = -1;
  const SparseRowMatrix L = intrinsic_delaunay_laplacian(m.V, m.F, &flips);
  EXPECT_EQ(flips, 0);
  EXPECT_LT(Eigen::MatrixXd(L - cotangent_laplacian(m.V, m.F)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(IntrinsicDelaunay, FlipsAnEdgeAcrossTwoObtuseAnglesInThePlane) {
  // The planar quad a, b, c, d with the long diagonal ab: the flip makes it cd, and in the
  // plane the intrinsic triangulation is the flipped mesh.
  testing::Mesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 2, 0, 0, 1, 0.3, 0, 1, -0.3, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 1, 0, 3;
  const IntrinsicTriangulation T = intrinsic_delaunay(m.V, m.F);
  EXPECT_EQ(T.flips, 1);
  testing::Mesh flipped = m;
  flipped.F << 0, 3, 2, 3, 1, 2;
  const SparseRowMatrix L = intrinsic_laplacian(4, T);
  EXPECT_LT(Eigen::MatrixXd(L - cotangent_laplacian(flipped.V, flipped.F)).cwiseAbs().maxCoeff(),
            1e-12);
  EXPECT_EQ(L.coeff(0, 1), 0.0);
}

TEST(IntrinsicDelaunay, WeightsAreNeverNegative) {
  // A strongly jittered grid has obtuse pairs (negative cotangent weights); the intrinsic
  // Delaunay Laplacian has none, and still annihilates constants.
  const testing::Mesh m = testing::onto_sphere(testing::planar_grid(10, 0.45), 3.0);
  const SparseRowMatrix C = cotangent_laplacian(m.V, m.F);
  double most_negative = 0.0;
  for (int i = 0; i < C.outerSize(); ++i)
    for (SparseRowMatrix::InnerIterator it(C, i); it; ++it)
      if (it.col() != i) most_negative = std::min(most_negative, it.value());
  ASSERT_LT(most_negative, -1e-3) << "the test mesh should have a negative cotangent weight";
  int flips = 0;
  const SparseRowMatrix L = intrinsic_delaunay_laplacian(m.V, m.F, &flips);
  EXPECT_GT(flips, 0);
  for (int i = 0; i < L.outerSize(); ++i)
    for (SparseRowMatrix::InnerIterator it(L, i); it; ++it)
      if (it.col() != i) EXPECT_GE(it.value(), -1e-12);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.V.rows());
  EXPECT_LT((L * ones).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(IntrinsicDelaunay, KeepsLinearPrecisionOnAPlanarMesh) {
  const int n = 10;
  const testing::Mesh m = testing::planar_grid(n, 0.45);
  const SparseRowMatrix L = intrinsic_delaunay_laplacian(m.V, m.F);
  const Eigen::VectorXd f = m.V.col(0) + 2.0 * m.V.col(1);
  const Eigen::VectorXd Lf = L * f;
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) EXPECT_NEAR(Lf(j * (n + 1) + i), 0.0, 1e-10);
}

}  // namespace
}  // namespace geofair
