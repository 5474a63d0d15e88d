// The fairing driver: progressive-mesh multigrid around the construction of section 7
// (Schneider & Kobbelt 2001, Fig. 6).
#include "geofair/fairing.h"

#include "geofair/bilaplacian.h"
#include "geofair/construction.h"
#include "geofair/inner_fairness.h"
#include "geofair/multigrid.h"
#include "geofair/progressive_mesh.h"
#include "geofair/region.h"

#include <cmath>
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

Positions gather(const Positions& X, const std::vector<int>& ids) {
  Positions Y(Eigen::Index(ids.size()), 3);
  for (std::size_t i = 0; i < ids.size(); ++i) Y.row(Eigen::Index(i)) = X.row(ids[i]);
  return Y;
}

}  // namespace

FairingResult fair(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const Positions* boundary_normals, const FairingOptions& options) {
  check_options(options);
  const FairingRegion region = extract_region(V, F, free, boundary_normals);

  const Positions X0 = gather(V, region.global);  // the original mesh
  const double L = (X0.colwise().maxCoeff() - X0.colwise().minCoeff()).norm();
  if (!(L > 0.0)) throw InvalidInputError("fair: the region has zero extent");

  const int levels = options.levels > 0 ? options.levels : default_levels(region.n_free);
  ProgressiveMesh hierarchy;
  if (levels > 1 && options.outer_fairness == OuterFairness::Intrinsic) {
    const std::vector<double> lambda =
        inner_fairness_weights(region.rings, X0, options.inner_fairness);
    hierarchy = build_progressive_mesh(region, X0, levels, &lambda);
  }
  if (hierarchy.triangles.empty())
    hierarchy.triangles.push_back(region.triangles), hierarchy.splits.emplace_back();

  // The finest level is the region itself, with region-local ids as its "global" ids.
  FairingRegion finest_level = region;
  std::iota(finest_level.global.begin(), finest_level.global.end(), 0);

  FairingResult result;
  Positions X = X0;  // region positions, filled in level by level
  for (std::size_t l = 0; l < hierarchy.triangles.size(); ++l) {
    const bool finest = l + 1 == hierarchy.triangles.size();
    const FairingRegion level = finest ? finest_level : level_region(region, hierarchy.triangles[l]);
    // Conformal weights come from the original mesh with this level's connectivity: the
    // original is replayed in parallel with the faired mesh.
    std::vector<double> lambda =
        inner_fairness_weights(level.rings, gather(X0, level.global), options.inner_fairness);
    Positions Y = gather(X, level.global);
    if (l == 0) Y = bilaplacian_initial_mesh(level, lambda, Y);
    Construction construction(level, std::move(lambda), options, L);
    if (l > 0) {
      std::vector<int> local(region.n, -1);
      for (int i = 0; i < level.n; ++i) local[level.global[i]] = i;
      VertexSplits splits = hierarchy.splits[l];
      for (int& v : splits.vertex) v = local[v];
      for (int& v : splits.ring) v = local[v];
      prolongate(level, splits, options.inner_fairness, gather(X0, level.global), Y, construction);
    }
    IterationReport report;
    if (options.outer_fairness == OuterFairness::Bilaplacian) {
      // The linear solution is exact; the residual says how far it is from Δ_B H = 0.
      report.residual = construction.evaluate(Y);
      report.converged = true;
    } else {
      report = construction.run(Y, options.max_iterations, result.iterations);
    }
    for (int i = 0; i < level.n; ++i) X.row(level.global[i]) = Y.row(i);
    result.iterations += report.iterations;
    result.iterations_per_level.push_back(report.iterations);
    result.vertices_per_level.push_back(level.n);
    result.residual = report.residual;
    result.converged = report.converged;
    if (report.cancelled) {
      result.converged = false;
      break;
    }
  }

  result.vertices = V;
  for (int i = 0; i < region.n_free; ++i) result.vertices.row(region.global[i]) = X.row(i);
  if (!result.vertices.allFinite())
    throw SolverError("fair: the iteration produced non-finite positions");
  return result;
}

}  // namespace geofair
