// The preconditioner of Newton's step (newton_step.h): the Jacobian of the defects with the
// weights held fixed, its normals estimated anew in each column.
#include "newton_step.h"

#include "common.h"
#include "construction.h"
#include "inner_fairness.h"
#include "laplace_beltrami.h"
#include "meshes.h"
#include "region.h"
#include "sparse_lu.h"

#include <gtest/gtest.h>

#include <cmath>

namespace geofair {
namespace {

// A wavy, jittered grid with a G0 boundary: every free vertex has valence 6, so no H reads
// a neighbour's normal (no spiral samples) and no normal fit reaches beyond the ring (no
// flaps). The Jacobian of the defects with fixed weights then has the preconditioner's
// pattern and values: one GMRES iteration solves the Newton system. With the normals held
// fixed in the preconditioner (its earlier form) the fit's tilt is missed and one iteration
// leaves a residual larger than the right-hand side (docs/DESIGN_NOTES.md, "The Newton
// preconditioner's normals").
TEST(NewtonStep, PreconditionerIsTheJacobianWhereNoSpiralSampleReachesFarther) {
  testing::Mesh m = testing::planar_grid(14, 0.2);
  std::vector<bool> free(m.V.rows());
  for (int v = 0; v < m.V.rows(); ++v) {
    const double x = m.V(v, 0), y = m.V(v, 1);
    m.V(v, 2) = 0.3 * std::sin(2.0 * x) * std::cos(1.5 * y) + 0.2 * x * y;
    free[v] = std::abs(x) < 0.75 && std::abs(y) < 0.75;
  }
  const FairingRegion region =
      extract_region(m.V, m.F, free, nullptr, true, nullptr, BoundaryCondition::G0);
  const int nf = region.n_free;
  ASSERT_GT(nf, 50);
  for (int i = 0; i < nf; ++i) ASSERT_EQ(region.rings.valence(i), 6);
  const Positions X = gather(m.V, region.global);
  // The construction's normals (quadric fits) and mean curvatures, as fair() evaluates them.
  const FairingOptions options;
  Construction construction(region, inner_fairness_weights(region, X, InnerFairness::Uniform),
                            options, 1.0);
  construction.evaluate(X);
  const Positions N = construction.normals();
  const Eigen::VectorXd H = construction.mean_curvatures();
  DirichletMatrix dirichlet(region);
  dirichlet.assemble(X);
  const Eigen::VectorXd d0 = dirichlet.defects(H);
  ASSERT_GT(d0.norm(), 0.0);
  // J v by a central difference of the defects, the weights held at X.
  NewtonStep::JacobianProduct product = [&](const Eigen::VectorXd& v, Eigen::VectorXd& Jv) {
    const double eps = 1e-6 / v.cwiseAbs().maxCoeff();
    Eigen::VectorXd side[2];
    for (int s = 0; s < 2; ++s) {
      Positions Y = X;
      for (int i = 0; i < nf; ++i) Y.row(i) += ((s == 0 ? eps : -eps) * v(i)) * N.row(i);
      construction.evaluate(Y);
      side[s] = dirichlet.defects(construction.mean_curvatures());
    }
    Jv = (side[0] - side[1]) / (2.0 * eps);
  };
  NewtonTuning tuning;
  tuning.krylov_iterations = 1;
  NewtonStep step(region, tuning, NormalWeighting::Quadric);
  Eigen::VectorXd t;
  ASSERT_TRUE(step.solve(X, N, H, dirichlet.weights(), d0, nullptr, product, {},
                         tuning.krylov_tolerance, t));
  Eigen::VectorXd Jt;
  product(t, Jt);
  EXPECT_LT((Jt + d0).norm() / d0.norm(), 1e-4);
}


// PatternLU::copy_factors_after: past the given number of solves on one factorization the
// factors are copied out of UMFPACK and solved by Eigen; the solutions agree with UMFPACK's
// to rounding, on a nonsymmetric matrix with pivoting and row scaling, and a new
// factorization starts the count again (its solves are its own, not the copy's).
TEST(PatternLU, CopiedFactorsSolveAsUmfpackDoes) {
  const int n = 400;
  auto matrix = [&](double shift) {
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, 4.0 + shift + 0.01 * (i % 7));
      t.emplace_back(i, (i + 1) % n, -1.0 - 0.3 * std::sin(i));  // nonsymmetric
      t.emplace_back((i + 1) % n, i, -0.7);
      t.emplace_back(i, (i * 37 + 11) % n, 0.5 * std::cos(i));
      t.emplace_back(i, (i + 20) % n, i % 3 == 0 ? 5.0 : 0.1);  // some rows pivot off the diagonal
    }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
    return A;
  };
  const Eigen::SparseMatrix<double> A = matrix(0.0), B = matrix(1.0);
  PatternLU plain, copied;
  copied.copy_factors_after(2);
  ASSERT_TRUE(plain.factorize(A));
  ASSERT_TRUE(copied.factorize(A));
#ifdef GEOFAIR_PORTABLE
  const bool copies = false;  // Eigen's SparseLU: nothing to copy
#else
  const bool copies = true;
#endif
  for (int k = 0; k < 5; ++k) {  // solves 3 to 5 on the copy
    const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
    const Eigen::VectorXd x = copied.solve(b), y = plain.solve(b);
    EXPECT_EQ(copied.solves_on_copy(), copies && k >= 2) << "solve " << k;
    EXPECT_FALSE(plain.solves_on_copy());
    EXPECT_LT((x - y).norm(), 1e-12 * y.norm()) << "solve " << k;
    EXPECT_LT((A * x - b).norm(), 1e-10 * b.norm()) << "solve " << k;
  }
  ASSERT_TRUE(copied.factorize(B));  // the copy of A's factors is dropped
  EXPECT_FALSE(copied.solves_on_copy());
  ASSERT_TRUE(plain.factorize(B));
  for (int k = 0; k < 4; ++k) {
    const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
    const Eigen::VectorXd x = copied.solve(b);
    EXPECT_EQ(copied.solves_on_copy(), copies && k >= 2) << "solve " << k;
    EXPECT_LT((x - plain.solve(b)).norm(), 1e-12 * x.norm()) << "solve " << k;
    EXPECT_LT((B * x - b).norm(), 1e-10 * b.norm()) << "solve " << k;
  }
}

}  // namespace
}  // namespace geofair
