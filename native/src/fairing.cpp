// The fairing driver: progressive-mesh multigrid around the construction of section 7
// (Schneider & Kobbelt 2001, Fig. 6).
#include "geofair/fairing.h"

#include "geofair/bilaplacian.h"
#include "geofair/construction.h"
#include "geofair/inner_fairness.h"
#include "geofair/multigrid.h"
#include "geofair/progressive_mesh.h"
#include "geofair/region.h"

#include <algorithm>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <cmath>
#include <deque>
#include <memory>
#include <numeric>
#include <string>

namespace geofair {
namespace {

void check_options(const FairingOptions& o) {
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance))
    throw InvalidInputError("fair: tolerance must be a positive finite number");
  if (o.max_iterations < 0) throw InvalidInputError("fair: max_iterations must be >= 0");
  if (!(o.damping > 0.0 && o.damping <= 1.0))
    throw InvalidInputError("fair: damping must lie in (0, 1]");
  if (o.cg_iterations < 1) throw InvalidInputError("fair: cg_iterations must be >= 1");
  if (o.levels < 0) throw InvalidInputError("fair: levels must be >= 0");
}

// Tolerance of the coarse levels, relative to options.tolerance. They only start the next
// level, whose cycles correct the smooth error anyway. Measured on the 13000-vertex cap
// (Max's normals; iterations coarse to fine): factor 3: 6591/1140/420/280, 10:
// 4631/790/180/110, 30: 5199/830/320/260, 1e4: 3145/680/660/680, each with a max radial
// error of 4-6e-6.
constexpr double kCoarseTolerance = 10;
// ... or this many iterations of a coarse level. Decimated coarse levels can end in a limit
// cycle far above their tolerance when solved on their own (the 13000-vertex cap with two
// fixed rings: the 601-vertex base level oscillates around residual 30 for 20000
// iterations, the 1192- and 3627-vertex levels as bases of 3 and 2 levels just as long),
// while the finer levels still converge quickly with their corrections: with this cap
// the iterations went from 84381/20490/420/100 (66 s) to 7500/1060/480/100 (9 s), with
// the same max radial error, 4e-6.
constexpr int kCoarseIterations = 500;
// Auto uses Newton's method up to this many free vertices. The sparse LU factors of the
// linear initial mesh (3#V_I unknowns) and of its 2-ring system grow faster than the mesh:
// peak memory 2.2 GiB at 100000 free vertices (bench/speed.py), where the paper's
// iteration did not converge in 1500 s and Newton's method took 42 s.
constexpr int kNewtonMaxFree = 150000;

Positions gather(const Positions& X, const std::vector<int>& ids) {
  Positions Y(Eigen::Index(ids.size()), 3);
  for (std::size_t i = 0; i < ids.size(); ++i) Y.row(Eigen::Index(i)) = X.row(ids[i]);
  return Y;
}

}  // namespace

FairingResult fair(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const Positions* boundary_normals, const FairingOptions& options) {
  check_options(options);
#ifdef _OPENMP
  // Threads only as far as the machine is idle (libgomp: cores minus the load average):
  // on a busy machine the threads of a parallel loop wait for each other at every barrier.
  omp_set_dynamic(1);
#endif
  const FairingRegion region = extract_region(V, F, free, boundary_normals);

  const Positions X0 = gather(V, region.global);  // the original mesh
  const double L = (X0.colwise().maxCoeff() - X0.colwise().minCoeff()).norm();
  if (!(L > 0.0)) throw InvalidInputError("fair: the region has zero extent");

  // The finest level is the region itself, with region-local ids as its "global" ids.
  FairingRegion finest_level = region;
  std::iota(finest_level.global.begin(), finest_level.global.end(), 0);
  auto finish = [&](FairingResult& result, const Positions& X) {
    result.vertices = V;
    for (int i = 0; i < region.n_free; ++i) result.vertices.row(region.global[i]) = X.row(i);
    if (!result.vertices.allFinite())
      throw SolverError("fair: the iteration produced non-finite positions");
    return result;
  };

  // Inner fairness weights of the finest level (the region, from the original mesh): for
  // Newton's method, the hierarchy and the paper's finest level alike.
  const InnerFairnessWeights lambda_finest =
      inner_fairness_weights(finest_level, X0, options.inner_fairness);

  int newton_iterations = 0;
  const bool newton =
      options.iteration == Iteration::Newton ||
      (options.iteration == Iteration::Auto && region.n_free <= kNewtonMaxFree);
  if (options.outer_fairness == OuterFairness::Intrinsic && newton) {
    Positions Y = bilaplacian_initial_mesh(finest_level, lambda_finest, X0);
    Construction construction(finest_level, lambda_finest, options, L);
    IterationReport report;
    bool failed = false;
    try {
      report = construction.run_newton(Y, options.max_iterations, options.tolerance);
    } catch (const SolverError&) {
      if (options.iteration == Iteration::Newton) throw;
      failed = true;
    }
    newton_iterations = int(construction.iterations());
    if (!failed &&
        (report.converged || report.cancelled || options.iteration == Iteration::Newton)) {
      FairingResult result;
      result.iteration = Iteration::Newton;
      result.newton_iterations = result.iterations = newton_iterations;
      result.iterations_per_level = {newton_iterations};
      result.vertices_per_level = {region.n};
      result.residual = report.residual;
      result.converged = report.converged;
      return finish(result, Y);
    }
  }

  const int levels = options.levels > 0 ? options.levels : default_levels(region.n_free);
  ProgressiveMesh hierarchy;
  Positions Xs;  // the smoothed copy the hierarchy is measured on
  if (levels > 1 && options.outer_fairness == OuterFairness::Intrinsic) {
    Xs = hierarchy_positions(region, X0, &lambda_finest);
    hierarchy = build_progressive_mesh(region, Xs, levels);
  }
  if (hierarchy.triangles.empty())
    hierarchy.triangles.push_back(region.triangles), hierarchy.splits.emplace_back();

  FairingResult result;
  result.iteration = Iteration::Paper;
  result.newton_iterations = newton_iterations;
  Positions X = X0;                                  // region positions, level by level
  Eigen::VectorXd H = Eigen::VectorXd::Zero(region.n);  // mean curvatures of the last level
  Positions N = Positions::Zero(region.n, 3);        // and its unit normals
  // Coarse levels estimate normals with Max's weights where the fitted normal is asked for:
  // the fit, consistent on the finest mesh, is ill-conditioned on the decimated rings of
  // coarse levels (short and long edges, low valence): with it there, the 2000-vertex
  // irregular cylinder patch took 15,900 iterations (10,300 on the coarsest level) instead
  // of 4,200. The coarse levels only supply corrections; the finest level's equations
  // decide the result.
  FairingOptions coarse_options = options;
  if (options.normal_weighting == NormalWeighting::Quadric)
    coarse_options.normal_weighting = NormalWeighting::Max;
  std::deque<MultigridLevel> levels_built;
  Multigrid multigrid(levels_built);
  const int n_levels = int(hierarchy.triangles.size());
  for (int l = 0; l < n_levels; ++l) {
    const bool finest = l + 1 == n_levels;
    MultigridLevel& level = levels_built.emplace_back();
    level.region = finest ? finest_level : level_region(region, hierarchy.triangles[l]);
    const FairingRegion& lr = level.region;
    // Inner fairness of the finest level as asked, with conformal weights from the original
    // mesh. Coarse levels, whose vertex distribution does not reach the result, take the
    // conformal weights of the smoothed copy with their connectivity (see fairing.h).
    InnerFairnessWeights lambda =
        finest ? lambda_finest
               : ring_inner_fairness_weights(lr.rings, gather(Xs, lr.global),
                                             InnerFairness::Conformal);
    Positions Y = gather(X, lr.global);
    if (l == 0) {
      Y = bilaplacian_initial_mesh(lr, lambda, Y);
    } else {
      std::vector<int> local(region.n, -1);
      for (int i = 0; i < lr.n; ++i) local[lr.global[i]] = i;
      level.splits = hierarchy.splits[l];
      for (int& v : level.splits.vertex) v = local[v];
      for (int& v : level.splits.ring) v = local[v];
      // Splits and their transposes interpolate smooth corrections: conformal weights of
      // the smoothed copy on every level (those of a noisy original are not smooth, and the
      // finest level's corrections got undone on the 1200-vertex cap with conformal inner
      // fairness).
      level.weights =
          split_weights(level.splits, InnerFairness::Conformal, gather(Xs, lr.global));
      const FairingRegion& coarser = levels_built[l - 1].region;
      level.from_coarser.resize(coarser.n);
      for (int c = 0; c < coarser.n; ++c) level.from_coarser[c] = local[coarser.global[c]];
      Eigen::VectorXd H_level(lr.n);
      Positions N_level = gather(N, lr.global);
      for (int i = 0; i < lr.n; ++i) H_level(i) = H(lr.global[i]);
      prolongate(lr, level.splits, level.weights, lambda, Y, H_level, N_level);
    }
    level.construction = std::make_unique<Construction>(lr, std::move(lambda),
                                                        finest ? options : coarse_options, L);
    Construction& construction = *level.construction;
    IterationReport report;
    if (options.outer_fairness == OuterFairness::Bilaplacian) {
      // The linear solution is exact; the residual says how far it is from Δ_B H = 0.
      report.residual = construction.evaluate(Y);
      report.converged = true;
    } else {
      // Coarse levels only start the next one: a looser tolerance.
      const double tolerance = options.tolerance * (finest ? 1.0 : kCoarseTolerance);
      const int budget =
          finest ? options.max_iterations : std::min(options.max_iterations, kCoarseIterations);
      report = l == 0 ? construction.run(Y, budget, tolerance, result.iterations)
                      : multigrid.solve(l, Y, tolerance, budget, result.iterations);
    }
    for (int i = 0; i < lr.n; ++i) {
      X.row(lr.global[i]) = Y.row(i);
      H(lr.global[i]) = construction.mean_curvatures()(i);
      N.row(lr.global[i]) = construction.normals().row(i);
    }
    result.iterations = 0;
    for (const MultigridLevel& done : levels_built)
      result.iterations += int(done.construction->iterations());
    result.vertices_per_level.push_back(lr.n);
    result.residual = report.residual;
    result.converged = report.converged;
    if (report.cancelled) {
      result.converged = false;
      break;
    }
  }
  for (const MultigridLevel& done : levels_built)
    result.iterations_per_level.push_back(int(done.construction->iterations()));

  return finish(result, X);
}

}  // namespace geofair
