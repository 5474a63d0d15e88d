// libFuzzer target for geofair::fair with the region remeshed (Remesh::Always or IfNeeded,
// fair(remesh=True) in Python): it must either return finite geometry with the input's fixed
// rows bit-identical, faces indexing its rows, and origin data of its size, or throw one of
// the two documented exceptions. Anything else is a bug.
//
// Input layout: fuzz_input.h's, the flag of a vertex read as free; the option byte picks
// Always or IfNeeded (bit 0), the boundary (bit 1: G0) and the inner fairness (bits 2-3).
#include "fuzz_input.h"
#include "geofair/fairing.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::Reader in{data, size};
  const fuzz::Input input = fuzz::read_input(in);
  const auto& [V, F, free, flags] = input;
  const int nv = int(V.rows());

  geofair::FairingOptions options;
  options.remesh = flags & 1 ? geofair::Remesh::IfNeeded : geofair::Remesh::Always;
  options.boundary = flags & 2 ? geofair::BoundaryCondition::G0 : geofair::BoundaryCondition::G1;
  options.inner_fairness = static_cast<geofair::InnerFairness>((flags >> 2) % 3);
  options.max_iterations = 30;
  options.time_limit = 2.0;
  try {
    const geofair::FairingResult r = geofair::fair(V, F, free, nullptr, options);
    const Eigen::Index rows = r.vertices.rows();
    if (!r.vertices.allFinite() || !std::isfinite(r.residual) || rows < nv) std::abort();
    for (int v = 0; v < nv; ++v)
      if (!free[v] && (r.vertices.row(v).array() != V.row(v).array()).any()) std::abort();
    if (r.faces.size() > 0 && (r.faces.minCoeff() < 0 || r.faces.maxCoeff() >= rows)) std::abort();
    if (r.remeshed && (Eigen::Index(r.origin_face.size()) != rows || r.origin_barycentric.rows() != rows ||
                       Eigen::Index(r.free.size()) != rows))
      std::abort();
  } catch (const geofair::InvalidInputError&) {
  } catch (const geofair::SolverError&) {
  }
  return 0;
}
