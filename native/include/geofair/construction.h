// The iterative construction of a discrete solution of Δ_B H = 0 on one mesh (Schneider &
// Kobbelt 2001, sections 7.1-7.3), used on the single level and on every multigrid level.
#pragma once

#include "geofair/curvature_solve.h"
#include "geofair/laplace_beltrami.h"
#include "geofair/region.h"
#include "geofair/types.h"

#include <vector>

namespace geofair {

/// How an iteration ended.
struct IterationReport {
  int iterations = 0;      ///< iterations M_k -> M_{k+1} performed
  double residual = 0.0;   ///< L³·max|Δ_B H| of the final mesh
  bool converged = false;  ///< residual <= tolerance
  bool cancelled = false;  ///< the progress callback asked to stop
};

/// State of the construction on one region: normals, mean curvatures, the Dirichlet matrix
/// S and the CG solver, reused across iterations.
class Construction {
 public:
  /// \param region  the mesh to fair (kept by reference)
  /// \param lambda  inner fairness weights per ring slot (inner_fairness_weights)
  /// \param length  L, the length that makes the residual dimensionless (see fairing.h)
  Construction(const FairingRegion& region, std::vector<double> lambda,
               const FairingOptions& options, double length);

  /// Normals and Moreton–Séquin H of all vertices of X (#region×3), S and the residual.
  double evaluate(const Positions& X);

  /// Iterates until the residual reaches the tolerance or `max_iterations` iterations;
  /// local (Gauss–Seidel) and global (CG) steps alternate. `progress` receives
  /// (iteration_offset + k, residual). Every vertex update divides its normal step by the
  /// coupling factor max(1, ρ_i) (coupling_factors in vertex_update.h), refreshed every
  /// kCouplingRefresh iterations.
  /// \throw SolverError if the iteration diverges.
  IterationReport run(Positions& X, int max_iterations, int iteration_offset = 0);

  /// Restores outer fairness locally (the third prolongation step of section 7.4): `steps`
  /// passes of a Gauss–Seidel sweep for H~ restricted to `subset` (free vertex ids) followed
  /// by the vertex update of those vertices only.
  void local_steps(Positions& X, const std::vector<int>& subset, int steps);

  const std::vector<double>& lambda() const { return lambda_; }

 private:
  void curvatures(const Positions& X, const std::vector<int>* subset);

  const FairingRegion& region_;
  std::vector<double> lambda_;
  const FairingOptions& options_;
  double length_;
  Positions N_;
  Eigen::VectorXd H_;
  DirichletMatrix dirichlet_;
  CurvatureSolver solver_;
  std::vector<double> coupling_;  // ρ_i of the free vertices
};

/// Iterations between refreshes of the coupling factors: they follow the mesh shape, which
/// changes slowly; one refresh costs about three iterations.
constexpr int kCouplingRefresh = 8;

}  // namespace geofair
