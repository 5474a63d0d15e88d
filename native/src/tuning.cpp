// Range checks of the solver tuning (tuning.h).
#include "geofair/tuning.h"

#include "geofair/types.h"

#include <cmath>
#include <sstream>
#include <string>

namespace geofair {
namespace {

// Throws unless lo <= value <= hi (with open ends where lo_open / hi_open).
void check(const char* name, double value, double lo, double hi, bool lo_open = false,
           bool hi_open = false) {
  const bool ok = std::isfinite(value) && (lo_open ? value > lo : value >= lo) &&
                  (hi_open ? value < hi : value <= hi);
  if (ok) return;
  std::ostringstream s;
  s << "fair: tuning." << name << " must be in " << (lo_open ? "(" : "[") << lo << ", " << hi
    << (hi_open ? ")" : "]") << ", got " << value;
  throw InvalidInputError(s.str());
}

constexpr double kInf = 1e300;

}  // namespace

void validate_tuning(const SolverTuning& t) {
  check("paper.coupling_refresh", t.paper.coupling_refresh, 1, kInf);
  check("paper.tangential_iterations", t.paper.tangential_iterations, 1, kInf);

  const NewtonTuning& n = t.newton;
  check("newton.patience", n.patience, 1, kInf);
  check("newton.coarse_patience", n.coarse_patience, 1, kInf);
  check("newton.max_step", n.max_step, 0, kInf, true);
  check("newton.relaxations", n.relaxations, 1, kInf);
  check("newton.polishes", n.polishes, 0, kInf);
  check("newton.polished_move", n.polished_move, 0, kInf, true);
  check("newton.polish_contraction", n.polish_contraction, 0, kInf);
  check("newton.product_step", n.product_step, 0, 0.01, true);
  check("newton.merit_growth", n.merit_growth, 1, kInf);
  check("newton.shift_start", n.shift_start, 0, kInf, true);
  check("newton.shift_increase", n.shift_increase, 1, kInf, true);
  check("newton.shift_max", n.shift_max, n.shift_start, kInf);
  check("newton.shift_negligible", n.shift_negligible, 0, 1, false, true);
  check("newton.krylov_iterations", n.krylov_iterations, 1, kInf);
  check("newton.krylov_tolerance", n.krylov_tolerance, 0, 1, true, true);
  check("newton.shift_refactorization", n.shift_refactorization, 1, kInf, true);

  const TangentialTuning& g = t.tangential;
  check("tangential.max_stretch", g.max_stretch, 0, 1, true, true);
  check("tangential.max_turn", g.max_turn, 0, kInf, true);
  check("tangential.lagged_tolerance", g.lagged_tolerance, 0, 1, true, true);
  check("tangential.lagged_iterations", g.lagged_iterations, 1, kInf);
  check("tangential.two_grid_sweeps", g.two_grid_sweeps, 1, kInf);
  check("tangential.two_grid_blocks", g.two_grid_blocks, 1, kInf);
  check("tangential.two_grid_iterations", g.two_grid_iterations, 1, kInf);
  check("tangential.two_grid_tolerance", g.two_grid_tolerance, 0, 1, true, true);

  const MultigridTuning& m = t.multigrid;
  check("multigrid.prolongation_sweeps", m.prolongation_sweeps, 0, kInf);
  check("multigrid.min_correction", m.min_correction, 0, 1, true);
  check("multigrid.max_skip", m.max_skip, 0, 30);
  check("multigrid.smoothing", m.smoothing, 1, kInf);
  check("multigrid.base_reduction", m.base_reduction, 0, 1, true, true);
  check("multigrid.base_iterations", m.base_iterations, 1, kInf);

  const HierarchyTuning& h = t.hierarchy;
  check("hierarchy.smoothing", h.smoothing, 0, kInf);
  check("hierarchy.min_free_per_boundary", h.min_free_per_boundary, 0, kInf, true);
  check("hierarchy.min_boundary_loop", h.min_boundary_loop, 3, kInf);
  check("hierarchy.min_level_free", h.min_level_free, 1, kInf);

  const BilaplacianTuning& b = t.bilaplacian;
  check("bilaplacian.cg_iterations", b.cg_iterations, 1, kInf);
  check("bilaplacian.initial_mesh_residual", b.initial_mesh_residual, 0, 1, true, true);
  check("bilaplacian.newton_initial_mesh_residual", b.newton_initial_mesh_residual, 0, 1, true,
        true);
  check("bilaplacian.exact_residual", b.exact_residual, 0, 1, true, true);

  const ScheduleTuning& s = t.schedule;
  check("schedule.time_limit_base", s.time_limit_base, 0, kInf);
  check("schedule.time_limit_per_free", s.time_limit_per_free, 0, kInf);
  check("schedule.newton_attempt_first", s.newton_attempt_first, 1, kInf);
  check("schedule.newton_attempt_steps", s.newton_attempt_steps, 1, kInf);
  check("schedule.newton_min_base_free", s.newton_min_base_free, 1, kInf);
  check("schedule.coarse_newton_steps", s.coarse_newton_steps, 1, kInf);
  check("schedule.coarse_tolerance", s.coarse_tolerance, 1, kInf);
  check("schedule.coarse_iterations", s.coarse_iterations, 1, kInf);
}

}  // namespace geofair
