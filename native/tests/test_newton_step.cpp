// The preconditioner of Newton's step (newton_step.h): the Jacobian of the defects with the
// weights held fixed, its normals estimated anew in each column.
#include "newton_step.h"

#include "common.h"
#include "construction.h"
#include "inner_fairness.h"
#include "laplace_beltrami.h"
#include "meshes.h"
#include "region.h"

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

}  // namespace
}  // namespace geofair
