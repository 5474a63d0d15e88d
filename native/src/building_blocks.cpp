// The compositions of fair()'s steps that the library exports on their own
// (geofair/building_blocks.h); the single building blocks are defined with their layers.
#include "geofair/building_blocks.h"

#include "common.h"
#include "inner_fairness.h"
#include "progressive_mesh.h"
#include "region.h"
#include "sparse_lu.h"

namespace geofair {

std::pair<Positions, double> relax_inner_fairness(const Positions& V, const Triangles& F,
                                                  const std::vector<bool>& free,
                                                  const Positions& normals, InnerFairness inner,
                                                  TangentPlanes planes,
                                                  const std::vector<int>* polygon_ids) {
  if (normals.rows() != V.rows())
    throw InvalidInputError("normals must have the shape of vertices " +
                            std::to_string(V.rows()) + "×3");
  const FairingRegion region = extract_region(V, F, free, &normals, true, polygon_ids);
  Positions X = gather(V, region.global);
  Positions N = gather(normals, region.global);
  for (int i = 0; i < region.n; ++i) N.row(i) = N.row(i).normalized();
  if (!N.allFinite()) throw InvalidInputError("normals must be nonzero and finite");
  const InnerFairnessWeights lambda = inner_fairness_weights(region, X, inner);
  TangentialSolver solver(region.rings, lambda, region.n_free,
                          PaperIterationTuning{}.tangential_iterations);
  const BlasThreads blas_threads(1);  // as fair() (sparse_lu.h)
  const double scale = solver.relax(lambda, N, X, /*lagged=*/false, planes);
  if (!(scale > 0.0))
    throw SolverError("relax_inner_fairness: the tangential system is singular or an edge "
                      "has zero length");
  Positions out = V;
  for (int i = 0; i < region.n_free; ++i) out.row(region.global[i]) = X.row(i);
  return {std::move(out), scale};
}

std::vector<Triangles> progressive_mesh_levels(const Positions& V, const Triangles& F,
                                               const std::vector<bool>& free, int levels,
                                               bool coarsen_boundary) {
  Positions placeholder_normals = Positions::Zero(V.rows(), 3);
  placeholder_normals.col(2).setOnes();  // the hierarchy does not read normals
  const FairingRegion region =
      extract_region(V, F, free, &placeholder_normals, /*check_orientation=*/false);
  const Positions X = gather(V, region.global);
  const int n = levels > 0 ? levels : default_levels(region.n_free);
  const Positions smoothed = hierarchy_positions(region, X, nullptr);
  std::vector<Triangles> out;
  for (Triangles T : build_progressive_mesh(region, smoothed, n,
                                            coarsen_boundary ? kNewtonDecimation : kPaperDecimation)
                         .triangles) {
    for (Eigen::Index k = 0; k < T.size(); ++k) T.data()[k] = region.global[T.data()[k]];
    out.push_back(std::move(T));
  }
  return out;
}

}  // namespace geofair
