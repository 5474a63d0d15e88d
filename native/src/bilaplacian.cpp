// Linear Δ²f = 0 fairing with G1 boundary conditions (section 7.4).
#include "bilaplacian.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#ifdef GEOFAIR_PORTABLE
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#else
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#endif

namespace geofair {
namespace {

// The sparse Cholesky and LU factorizations: SuiteSparse's (CHOLMOD's supernodal LLᵀ,
// UMFPACK), or in a portable build Eigen's own.
#ifdef GEOFAIR_PORTABLE
using CholeskyLLT = Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;
using SparseLUFactorization = Eigen::SparseLU<Eigen::SparseMatrix<double>>;
#else
using CholeskyLLT = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;
using SparseLUFactorization = Eigen::UmfPackLU<Eigen::SparseMatrix<double>>;
#endif

// The preconditioner I₃ ⊗ K_s⁻¹ for Eigen's ConjugateGradient (the interface of Eigen's
// preconditioners): the three coordinate blocks of a vector solved at once with one
// Cholesky factorization (CHOLMOD) of the scalar matrix K_s.
struct CoordinateBlocks {
  const CholeskyLLT* llt = nullptr;
  template <class M> CoordinateBlocks& analyzePattern(const M&) { return *this; }
  template <class M> CoordinateBlocks& factorize(const M&) { return *this; }
  template <class M> CoordinateBlocks& compute(const M&) { return *this; }
  template <class V> Eigen::VectorXd solve(const V& b) const {
    Eigen::VectorXd z = b;  // x, y, z blocks: the columns of an (n, 3) matrix
    Eigen::Map<Eigen::MatrixXd> blocks(z.data(), z.size() / 3, 3);
    blocks = llt->solve(Eigen::MatrixXd(blocks));
    return z;
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }
};

// The linear system K f = rhs of Δ²f = 0 at the free vertices (bilaplacian_initial_mesh),
// unknowns by coordinate: x of all free vertices, then y, then z (a*nf + i); with the
// triplets of the scalar matrix K_s (the same equations with the boundary vertices'
// Laplacians left out: K = I₃ ⊗ K_s + E, E positive semidefinite of rank at most the
// number of boundary vertices next to free ones).
struct BilaplacianSystem {
  Eigen::SparseMatrix<double> K;
  std::vector<Eigen::Triplet<double>> scalar;
  Eigen::VectorXd rhs;
};

// Equation block i is scaled by S_i = Σ_k w_ik (InnerFairnessWeights::row_sum) where
// `scaled` (the row sums are given, that is where the weights w are symmetric). The system
// is then symmetric positive definite: with M = λ − I (so S_i M_ij = w_ij − S_i δ_ij,
// symmetric),
//   S_i Δ²f(q_i) = Σ_j (S_i M_ij) (P_j / S_j) (S_j M_jk) f_k,
// P_j = I at a free vertex and n_j n_jᵀ at a boundary vertex; the free-free part of
// W − S is nonsingular and the P_j / S_j are positive semidefinite.
BilaplacianSystem assemble_bilaplacian(const FairingRegion& region,
                                       const InnerFairnessWeights& lambda, const Positions& X,
                                       bool scaled) {
  using Mat3 = Eigen::Matrix3d;
  const int nf = region.n_free;
  BilaplacianSystem system;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<Eigen::Triplet<double>>& scalar = system.scalar;
  triplets.reserve(std::size_t(lambda.offset[nf]) * 7 * 3 + 9 * nf);
  scalar.reserve(std::size_t(lambda.offset[nf]) * 7 + nf);
  Eigen::VectorXd& rhs = system.rhs;
  rhs = Eigen::VectorXd::Zero(3 * nf);
  // Adds  weight · Δf(q_j)  to the equation block of free vertex `row`: the part linear in
  // the free positions goes to the matrix, the rest (fixed positions) to the right side;
  // the terms of free j also to K_s.
  auto add_laplacian = [&](int row, double weight, int j) {
    const bool free_j = j < nf;
    const Mat3 P = free_j                     ? Mat3::Identity()
                   : region.boundary == BoundaryCondition::G0 ? Mat3::Zero()
                                              : Mat3(region.g1_normals.row(j - nf).transpose() *
                                                     region.g1_normals.row(j - nf));
    Vec3 constant = Vec3::Zero();
    auto add_term = [&](int k, double c) {  // weight · c · P f_k
      if (k < nf) {
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            if (P(a, b) != 0.0) triplets.emplace_back(a * nf + row, b * nf + k, weight * c * P(a, b));
        if (free_j) scalar.emplace_back(row, k, weight * c);
      } else {
        constant += c * X.row(k).transpose();
      }
    };
    add_term(j, -1.0);
    for (int k = lambda.offset[j]; k < lambda.offset[j + 1]; ++k)
      add_term(lambda.neighbour[k], lambda.weight[k]);
    const Vec3 r = weight * (P * constant);
    for (int a = 0; a < 3; ++a) rhs(a * nf + row) -= r(a);
  };
  for (int i = 0; i < nf; ++i) {
    const double s = scaled ? lambda.row_sum[i] : 1.0;
    add_laplacian(i, -s, i);
    for (int k = lambda.offset[i]; k < lambda.offset[i + 1]; ++k)
      add_laplacian(i, s * lambda.weight[k], lambda.neighbour[k]);
  }
  system.K.resize(3 * nf, 3 * nf);
  system.K.setFromTriplets(triplets.begin(), triplets.end());
  system.K.makeCompressed();
  return system;
}

// The symmetric system by conjugate gradients preconditioned by I₃ ⊗ K_s⁻¹, K_s factorized
// by CHOLMOD's supernodal Cholesky (#V_I unknowns instead of 3#V_I). The preconditioned
// matrix is the identity plus a low-rank term, so CG's iterations are bounded by that rank
// and do not grow with the free vertices inside: about half the time of a direct solve of
// K (docs/DESIGN_NOTES.md, "The linear initial mesh's solver"). False where K_s cannot be
// factorized or CG does not converge.
bool solve_by_cg(const BilaplacianSystem& system, int nf, double relative_residual,
                 int max_cg_iterations, Eigen::VectorXd& f) {
  Eigen::SparseMatrix<double> Ks(nf, nf);
  Ks.setFromTriplets(system.scalar.begin(), system.scalar.end());
  CholeskyLLT llt;
  llt.compute(Ks);
  if (llt.info() != Eigen::Success) return false;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                           CoordinateBlocks>
      cg;
  cg.preconditioner().llt = &llt;
  cg.setMaxIterations(max_cg_iterations);
  cg.setTolerance(relative_residual);
  cg.compute(system.K);
  f = cg.solve(system.rhs);
  return cg.info() == Eigen::Success && f.allFinite();
}

// The system by UMFPACK's LU of K.
Eigen::VectorXd solve_by_lu(const BilaplacianSystem& system) {
  SparseLUFactorization lu;
  lu.compute(system.K);
  if (lu.info() != Eigen::Success)
    throw SolverError("fair: the bilaplacian system Δ²f = 0 could not be factorized (singular "
                      "system: degenerate triangles or a free vertex without a fixed path to "
                      "the boundary)");
  Eigen::VectorXd f = lu.solve(system.rhs);
  if (lu.info() != Eigen::Success || !f.allFinite())
    throw SolverError("fair: the bilaplacian system Δ²f = 0 has no finite solution");
  return f;
}

}  // namespace

Positions bilaplacian_initial_mesh(const FairingRegion& region,
                                   const InnerFairnessWeights& lambda, const Positions& X,
                                   double relative_residual, int max_cg_iterations) {
  const int nf = region.n_free;
  const bool scaled = lambda.row_sum.size() == std::size_t(lambda.size());
  const BilaplacianSystem system = assemble_bilaplacian(region, lambda, X, scaled);
  Eigen::VectorXd f;
  // Symmetric where scaled: CG; otherwise (weights without symmetric row sums, e.g. a vertex
  // whose weights fell back to uniform, or CG not converging) the LU of K.
  if (!(scaled && solve_by_cg(system, nf, relative_residual, max_cg_iterations, f)))
    f = solve_by_lu(system);
  Positions Y = X;
  for (int i = 0; i < nf; ++i) Y.row(i) = Vec3(f(i), f(nf + i), f(2 * nf + i)).transpose();
  return Y;
}

Positions membrane_positions(const FairingRegion& region, const InnerFairnessWeights& lambda,
                             const Positions& X) {
  const int nf = region.n_free;
  if (lambda.row_sum.size() != std::size_t(lambda.size()))
    throw InvalidInputError("membrane_positions: the inner fairness weights are not symmetric");
  // Row i scaled by S_i: S_i f_i − Σ_j w_ij f_j = Σ_{j fixed} w_ij x_j with w_ij = S_i λ_ij.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(std::size_t(lambda.offset[nf]) + std::size_t(nf));
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf, 3);
  for (int i = 0; i < nf; ++i) {
    const double S = lambda.row_sum[i];
    triplets.emplace_back(i, i, S);
    for (int k = lambda.offset[i]; k < lambda.offset[i + 1]; ++k) {
      const int j = lambda.neighbour[k];
      if (j < 0) continue;
      const double w = S * lambda.weight[k];
      if (j < nf)
        triplets.emplace_back(i, j, -w);
      else
        rhs.row(i) += w * X.row(j);
    }
  }
  Eigen::SparseMatrix<double> K(nf, nf);
  K.setFromTriplets(triplets.begin(), triplets.end());
  CholeskyLLT llt;
  llt.compute(K);
  if (llt.info() != Eigen::Success)
    throw SolverError("fair: the membrane system Δf = 0 could not be factorized");
  const Eigen::MatrixXd f = llt.solve(rhs);
  if (llt.info() != Eigen::Success || !f.allFinite())
    throw SolverError("fair: the membrane system Δf = 0 has no finite solution");
  Positions Y = X;
  Y.topRows(nf) = f;
  return Y;
}

}  // namespace geofair
