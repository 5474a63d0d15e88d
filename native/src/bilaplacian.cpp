// Linear Δ²f = 0 fairing with G1 boundary conditions (section 7.4).
#include "geofair/bilaplacian.h"

#include "geofair/sparse_lu.h"

#include <Eigen/Sparse>
#include <Eigen/UmfPackSupport>

namespace geofair {

Positions bilaplacian_initial_mesh(const FairingRegion& region,
                                   const InnerFairnessWeights& lambda,
                                   const Positions& X) {
  const int nf = region.n_free;
  using Mat3 = Eigen::Matrix3d;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(std::size_t(lambda.offset[nf]) * 7 * 3 + 9 * nf);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * nf);

  // Adds  weight · Δf(q_j)  to the equation block of free vertex `row`: the part linear in
  // the free positions goes to the matrix, the rest (fixed positions) to the right side.
  auto add_laplacian = [&](int row, double weight, int j) {
    const bool free_j = j < nf;
    const Mat3 P = free_j ? Mat3::Identity()
                          : Mat3(region.g1_normals.row(j - nf).transpose() *
                                 region.g1_normals.row(j - nf));
    Vec3 constant = Vec3::Zero();
    auto add_term = [&](int k, double c) {  // weight · c · P f_k
      if (k < nf) {
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            if (P(a, b) != 0.0) triplets.emplace_back(3 * row + a, 3 * k + b, weight * c * P(a, b));
      } else {
        constant += c * X.row(k).transpose();
      }
    };
    add_term(j, -1.0);
    for (int k = lambda.offset[j]; k < lambda.offset[j + 1]; ++k)
      add_term(lambda.neighbour[k], lambda.weight[k]);
    rhs.segment<3>(3 * row) -= weight * (P * constant);
  };
  for (int i = 0; i < nf; ++i) {
    add_laplacian(i, -1.0, i);
    for (int k = lambda.offset[i]; k < lambda.offset[i + 1]; ++k)
      add_laplacian(i, lambda.weight[k], lambda.neighbour[k]);
  }
  Eigen::SparseMatrix<double> K(3 * nf, 3 * nf);
  K.setFromTriplets(triplets.begin(), triplets.end());
  K.makeCompressed();
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  {
    const BlasThreads threads(factorization_blas_threads(3 * nf));
    lu.compute(K);
  }
  if (lu.info() != Eigen::Success)
    throw SolverError("fair: the bilaplacian system Δ²f = 0 could not be factorized (singular "
                      "system: degenerate triangles or a free vertex without a fixed path to "
                      "the boundary)");
  const Eigen::VectorXd f = lu.solve(rhs);
  if (lu.info() != Eigen::Success || !f.allFinite())
    throw SolverError("fair: the bilaplacian system Δ²f = 0 has no finite solution");
  Positions Y = X;
  for (int i = 0; i < nf; ++i) Y.row(i) = f.segment<3>(3 * i).transpose();
  return Y;
}

}  // namespace geofair
