// libFuzzer target for geofair::fill_holes with Rim::Trim (and Keep): it must either return a
// filled mesh whose input rows are bit-identical and first, whose faces are the input's less
// removed_faces (in order) then the fill's, with finite positions and valid indices, and a
// record for every hole; or throw one of the two documented exceptions. Anything else (a
// crash, a sanitizer report, another exception, NaN) is a bug.
//
// Input layout: fuzz_input.h's, the flag of a vertex read as "cut": the triangles with a
// vertex flagged are dropped, which cuts holes into the seeds' grids. The option byte picks rim (bit 0: trim unless clear and bit 7 set), the boundary
// (bit 1: G0), keep_outer_borders (bit 2), max_hole_edges (bits 3-4: 0, 4, 8 or 16) and the
// iteration (bits 5-6).
#include "fuzz_input.h"
#include "geofair/hole_filling.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::Reader in{data, size};
  const fuzz::Input input = fuzz::read_input(in);
  const auto& [V, all, cut, flags] = input;
  const int nv = int(V.rows());
  std::vector<int> kept_rows;
  for (int f = 0; f < all.rows(); ++f)
    if (!cut[all(f, 0)] && !cut[all(f, 1)] && !cut[all(f, 2)]) kept_rows.push_back(f);
  geofair::Triangles F(static_cast<Eigen::Index>(kept_rows.size()), 3);
  for (std::size_t k = 0; k < kept_rows.size(); ++k) F.row(Eigen::Index(k)) = all.row(kept_rows[k]);

  geofair::FairingOptions options;
  options.boundary = flags & 2 ? geofair::BoundaryCondition::G0 : geofair::BoundaryCondition::G1;
  options.iteration = static_cast<geofair::Iteration>((flags >> 5) % 3);
  options.max_iterations = 30;
  options.time_limit = 0.5;  // the whole chain: more inputs per second
  geofair::HoleRule rule;
  rule.keep_outer_borders = flags & 4;
  rule.max_hole_edges = (flags >> 3) % 4 == 0 ? 0 : 2 << ((flags >> 3) % 4);
  const geofair::Rim rim = !(flags & 1) && (flags & 128) ? geofair::Rim::Keep : geofair::Rim::Trim;
  try {
    const geofair::FillResult r = geofair::fill_holes(V, F, {}, options, 0.0, rule, rim);
    if (!r.vertices.allFinite() || !std::isfinite(r.residual)) std::abort();
    if (r.vertices.rows() < nv || (r.vertices.topRows(nv).array() != V.array()).any()) std::abort();
    const auto& removed = r.removed_faces;
    if (!std::is_sorted(removed.begin(), removed.end())) std::abort();
    if (rim == geofair::Rim::Keep && !removed.empty()) std::abort();
    Eigen::Index row = 0;
    for (int f = 0; f < F.rows(); ++f) {
      if (std::binary_search(removed.begin(), removed.end(), f)) continue;
      if (row >= r.faces.rows() || (r.faces.row(row).array() != F.row(f).array()).any()) std::abort();
      ++row;
    }
    if (r.faces.size() > 0 && (r.faces.minCoeff() < 0 || r.faces.maxCoeff() >= r.vertices.rows()))
      std::abort();
    for (const geofair::HoleFill& h : r.holes)
      if (h.method == geofair::FillMethod::None && h.reason.empty()) std::abort();
  } catch (const geofair::InvalidInputError&) {
  } catch (const geofair::SolverError&) {
  }
  return 0;
}
