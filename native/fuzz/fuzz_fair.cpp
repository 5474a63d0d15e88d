// libFuzzer target for the library's entry points: geofair::fair, mean_curvature,
// intrinsic_delaunay_laplacian and estimate_boundary_normals must either return finite
// geometry (fair: with the fixed vertices untouched; boundary normals: unit or zero rows),
// or throw one of the two documented exceptions. Anything else (a crash, a sanitizer
// report, another exception, NaN in the result) is a bug.
//
// Input layout: fuzz_input.h's, the flag of a vertex read as free, the option byte as inner
// and outer fairness, levels and normal weighting; then per triangle a polygon id (0..15:
// any grouping of triangles into polygons, bogus ones included; passed to fair only where
// the first one is below 8).
#include "fuzz_input.h"
#include "geofair/building_blocks.h"
#include "geofair/fairing.h"
#include "intrinsic_delaunay.h"
#include "mean_curvature.h"
#include "region.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::Reader in{data, size};
  const fuzz::Input input = fuzz::read_input(in);
  const auto& [V, F, free, flags] = input;
  const int nv = int(V.rows()), nf = int(F.rows());
  std::vector<int> polygons(nf);
  for (int f = 0; f < nf; ++f) polygons[f] = in.next() % 16;

  try {
    const Eigen::VectorXd H = geofair::mean_curvature(V, F, nullptr);
    if (!H.allFinite()) std::abort();
  } catch (const geofair::InvalidInputError&) {
  } catch (const geofair::SolverError&) {
  }

  try {
    const geofair::SparseRowMatrix L = geofair::intrinsic_delaunay_laplacian(V, F);
    for (int k = 0; k < L.nonZeros(); ++k)
      if (!std::isfinite(L.valuePtr()[k])) std::abort();
  } catch (const geofair::InvalidInputError&) {
  } catch (const geofair::SolverError&) {
  }

  // Boundary normals: every row a unit vector or zero (the positions are finite).
  try {
    const geofair::Positions N = geofair::estimate_boundary_normals(V, F, free);
    for (int v = 0; v < nv; ++v) {
      const double len = N.row(v).norm();
      if (!std::isfinite(len) || (len != 0.0 && std::abs(len - 1.0) > 1e-9)) std::abort();
    }
  } catch (const geofair::InvalidInputError&) {
  }

  geofair::FairingOptions options;
  // Conformal inner fairness with the mesh's or the intrinsic Delaunay weights, picked by the
  // bits that also pick the levels (a quotient beside their remainder).
  options.inner_fairness = !(flags & 1)                ? geofair::InnerFairness::Uniform
                           : ((flags >> 2) / 3) % 2 == 0 ? geofair::InnerFairness::Conformal
                                                         : geofair::InnerFairness::ConformalIntrinsic;
  options.outer_fairness = flags & 2 ? geofair::OuterFairness::Bilaplacian : geofair::OuterFairness::Intrinsic;
  options.max_iterations = 30;
  options.levels = 1 + (flags >> 2) % 3;
  options.normal_weighting = static_cast<geofair::NormalWeighting>((flags >> 6) % 4);
  try {
    const geofair::FairingResult r =
        geofair::fair(V, F, free, nullptr, options, polygons[0] < 8 ? &polygons : nullptr);
    if (!r.vertices.allFinite() || !std::isfinite(r.residual)) std::abort();
    for (int v = 0; v < nv; ++v)
      if (!free[v] && (r.vertices.row(v).array() != V.row(v).array()).any()) std::abort();
  } catch (const geofair::InvalidInputError&) {
  } catch (const geofair::SolverError&) {
  }
  return 0;
}
