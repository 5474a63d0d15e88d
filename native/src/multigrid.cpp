// Prolongation and nonlinear multigrid cycles of section 7.4.
#include "multigrid.h"

#include "inner_fairness.h"

#include <algorithm>
#include <cstdint>
#include <cmath>

namespace geofair {

std::vector<double> split_weights(const VertexSplits& splits, InnerFairness inner,
                                  const Positions& X0) {
  std::vector<double> weights(splits.ring.size());
  auto cot = [](const Vec3& o, const Vec3& a, const Vec3& b) {
    const Vec3 u = a - o, v = b - o;
    const double c = u.cross(v).norm();
    return c > 0.0 ? u.dot(v) / c : 0.0;
  };
  for (std::size_t s = 0; s < splits.size(); ++s) {
    const int* ring = splits.ring.data() + splits.offset[s];
    double* w = weights.data() + splits.offset[s];
    const int m = splits.offset[s + 1] - splits.offset[s];
    std::fill(w, w + m, 1.0 / m);
    if (inner == InnerFairness::Uniform) continue;
    // The ring of a split free vertex is a closed fan: cotangents of both triangles.
    const Vec3 q = X0.row(splits.vertex[s]);
    double sum = 0.0;
    std::vector<double> c(m);
    for (int k = 0; k < m; ++k) {
      const Vec3 prev = X0.row(ring[(k + m - 1) % m]), here = X0.row(ring[k]),
                 next = X0.row(ring[(k + 1) % m]);
      c[k] = std::max(0.0, cot(prev, q, here) + cot(next, q, here));
      sum += c[k];
    }
    if (sum > 0.0 && std::isfinite(sum))
      for (int k = 0; k < m; ++k) w[k] = c[k] / sum;
  }
  return weights;
}

namespace {

// Rows of coarse_space's interpolation P, per free vertex of the level: (column, weight).
using InterpolationRows = std::vector<std::vector<std::pair<int, double>>>;

// The rows of P: a kept vertex its own column; a new vertex (is_new) the mean over its ring
// of the coarse vertices' values and the boundary's zeros; with none of those in its ring,
// the mean of its ring's rows, in rounds outwards.
InterpolationRows interpolation_rows(const OneRings& r, int nf,
                                     const std::vector<std::uint8_t>& is_new,
                                     const std::vector<int>& column, std::size_t n_columns) {
  InterpolationRows rows(nf);
  for (int i = 0; i < nf; ++i)
    if (!is_new[i]) rows[i].emplace_back(column[i], 1.0);
  std::vector<int> pending;
  for (int i = 0; i < nf; ++i) {
    if (!is_new[i]) continue;
    int m = 0;
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k)
      if (r.ring[k] >= nf || !is_new[r.ring[k]]) ++m;
    if (m == 0) {
      pending.push_back(i);
      continue;
    }
    for (int k = r.offset[i]; k < r.offset[i + 1]; ++k)
      if (r.ring[k] < nf && !is_new[r.ring[k]]) rows[i].emplace_back(column[r.ring[k]], 1.0 / m);
  }
  std::vector<double> sum(n_columns, 0.0);
  std::vector<int> touched;
  while (!pending.empty()) {
    std::vector<int> next, done;
    std::vector<std::vector<std::pair<int, double>>> fresh;
    for (const int i : pending) {
      int m = 0;
      for (int k = r.offset[i]; k < r.offset[i + 1]; ++k) {
        const int j = r.ring[k];
        if (j < nf && rows[j].empty()) continue;
        ++m;
        if (j >= nf) continue;
        for (const auto& [c, w] : rows[j]) {
          if (sum[c] == 0.0) touched.push_back(c);
          sum[c] += w;
        }
      }
      if (m == 0) {
        next.push_back(i);
        continue;
      }
      auto& row = fresh.emplace_back();
      for (const int c : touched) row.emplace_back(c, sum[c] / m), sum[c] = 0.0;
      touched.clear();
      done.push_back(i);
    }
    if (done.empty()) break;  // cannot happen: every free vertex reaches the boundary
    for (std::size_t d = 0; d < done.size(); ++d) rows[done[d]] = std::move(fresh[d]);
    pending.swap(next);
  }
  return rows;
}

// The coarser level's weights in coarse_space's column ids (`column`: the column of each
// free vertex of the level, -1 for a new one): coarser vertex b is region vertex
// coarser.global[b], a vertex of the level that no split of it adds.
InnerFairnessWeights column_weights(const FairingRegion& level, const FairingRegion& coarser,
                                    const InnerFairnessWeights& coarser_lambda,
                                    const std::vector<int>& column, std::size_t n_columns) {
  std::vector<int> local_of_global(
      std::size_t(*std::max_element(level.global.begin(), level.global.end())) + 1, -1);
  for (int i = 0; i < level.n; ++i) local_of_global[level.global[i]] = i;
  auto column_of = [&](int b) {
    return b < coarser.n_free ? column[local_of_global[coarser.global[b]]] : -1;
  };
  std::vector<int> coarser_of_column(n_columns);
  for (int b = 0; b < coarser.n_free; ++b) coarser_of_column[column_of(b)] = b;
  InnerFairnessWeights lambda;
  lambda.offset.assign(1, 0);
  for (const int b : coarser_of_column) {
    for (int k = coarser_lambda.offset[b]; k < coarser_lambda.offset[b + 1]; ++k) {
      lambda.neighbour.push_back(column_of(coarser_lambda.neighbour[k]));
      lambda.weight.push_back(coarser_lambda.weight[k]);
    }
    lambda.offset.push_back(int(lambda.neighbour.size()));
  }
  return lambda;
}

}  // namespace

CoarseSpace coarse_space(const FairingRegion& level, const VertexSplits& splits,
                         const FairingRegion& coarser,
                         const InnerFairnessWeights& coarser_lambda) {
  const int nf = level.n_free;
  const OneRings& r = level.rings;
  std::vector<int> column(nf, -1);
  std::vector<std::uint8_t> is_new(nf, 0);
  for (const int v : splits.vertex)
    if (v < nf) is_new[v] = 1;  // new G1 boundary vertices are no unknowns
  CoarseSpace coarse;
  for (int i = 0; i < nf; ++i)
    if (!is_new[i]) {
      column[i] = int(coarse.vertex.size());
      coarse.vertex.push_back(i);
    }
  const InterpolationRows rows = interpolation_rows(r, nf, is_new, column, coarse.vertex.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < nf; ++i)
    for (const auto& [c, w] : rows[i]) entries.emplace_back(i, c, w);
  coarse.P.resize(nf, Eigen::Index(coarse.vertex.size()));
  coarse.P.setFromTriplets(entries.begin(), entries.end());

  coarse.lambda = column_weights(level, coarser, coarser_lambda, column, coarse.vertex.size());
  return coarse;
}

void prolongate(const FairingRegion& level, const VertexSplits& splits,
                const std::vector<double>& weights, const InnerFairnessWeights& lambda,
                Positions& X, Eigen::VectorXd& H, Positions& N, int sweeps) {
  const OneRings& rings = level.rings;

  // 1. Inner-fairness position over the split ring; H and normal interpolated alike.
  for (std::size_t s = 0; s < splits.size(); ++s) {
    Vec3 q = Vec3::Zero(), n = Vec3::Zero();
    double h = 0.0;
    for (int k = splits.offset[s]; k < splits.offset[s + 1]; ++k) {
      const int j = splits.ring[k];
      q += weights[k] * X.row(j).transpose();
      n += weights[k] * N.row(j).transpose();
      h += weights[k] * H(j);
    }
    const int v = splits.vertex[s];
    H(v) = h;
    if (v >= level.n_free) {
      // A boundary vertex (the boundary coarsened): its position is fixed, its normal
      // prescribed (G1) or its H (G0).
      N.row(v) = level.g1_normals.row(v - level.n_free);
      if (level.boundary == BoundaryCondition::G0) H(v) = 0.0;
      continue;
    }
    X.row(v) = q;
    N.row(v) = n.normalized();
  }

  // 2. Relax the union of the 1-disks (free vertices); old vertices stay on the coarse
  //    surface's osculating paraboloid.
  std::vector<std::uint8_t> is_new(level.n, 0), in_disk(level.n, 0);
  for (int v : splits.vertex) is_new[v] = 1;
  std::vector<int> disk;
  auto add = [&](int j) {
    if (j < level.n_free && !in_disk[j]) {
      in_disk[j] = 1;
      disk.push_back(j);
    }
  };
  for (int v : splits.vertex) {
    add(v);
    for (int k = rings.offset[v]; k < rings.offset[v + 1]; ++k) add(rings.ring[k]);
  }
  const Positions P = X, NP = N;
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (int l : disk) {
      const Vec3 c = weighted_centroid(lambda, X, l);
      if (is_new[l]) {
        X.row(l) = c;
        continue;
      }
      const Vec3 p = P.row(l), n = NP.row(l);
      Vec3 d = c - p;
      d -= d.dot(n) * n;
      X.row(l) = p + d - 0.5 * H(l) * d.squaredNorm() * n;
      N.row(l) = (n + H(l) * d).normalized();
    }

  // 3. Lift each new vertex onto the surface its split ring predicts (H > 0 bends away
  //    from the normal: the surface lies H/2·(tangential distance)² below a tangent plane).
  for (std::size_t s = 0; s < splits.size(); ++s) {
    const int v = splits.vertex[s];
    if (v >= level.n_free) continue;
    const Vec3 q = X.row(v), n = N.row(v);
    double t = 0.0, sum_w = 0.0;
    for (int k = splits.offset[s]; k < splits.offset[s + 1]; ++k) {
      const int j = splits.ring[k];
      const Vec3 nj = N.row(j), d = q - X.row(j).transpose();
      const double cos = n.dot(nj), dn = d.dot(nj);
      if (!(cos > 0.5)) continue;  // a tangent plane too steep to predict from
      t += weights[k] * (-dn - 0.5 * H(j) * (d.squaredNorm() - dn * dn)) / cos;
      sum_w += weights[k];
    }
    if (sum_w > 0.0 && std::isfinite(t)) X.row(v) = q + (t / sum_w) * n;
  }
}

IterationReport Multigrid::solve(int l, Positions& X, double tolerance, int max_iterations,
                                 int iteration_offset) {
  Construction& construction = *levels_[l].construction;
  const long start = construction.iterations();
  IterationReport report;
  cancelled_ = false;
  state_.assign(levels_.size(), CorrectionState{});
  for (;;) {
    construction.set_source(nullptr, true);
    report.residual = construction.evaluate(X);
    report.converged = report.residual <= tolerance;
    report.cancelled = cancelled_;
    budget_ = max_iterations - int(construction.iterations() - start);
    if (report.converged || cancelled_ || budget_ <= 0) break;
    cycle(l, X, nullptr, true, iteration_offset + int(construction.iterations() - start));
  }
  report.iterations = int(construction.iterations() - start);
  return report;
}

namespace {

// The defects of `level` (#level, zero at the G1 boundary) restricted to the coarser level
// in place: the transpose of the split interpolation, last split first; a split's vertex
// ends at zero.
void restrict_to_coarser(const MultigridLevel& level, Eigen::VectorXd& defect) {
  const VertexSplits& splits = level.splits;
  for (std::size_t s = splits.size(); s-- > 0;) {
    const int v = splits.vertex[s];
    for (int k = splits.offset[s]; k < splits.offset[s + 1]; ++k)
      defect(splits.ring[k]) += level.weights[k] * defect(v);
    defect(v) = 0.0;
  }
}

// A change D (#level×3) given at the coarser level's vertices interpolated in place to the
// vertices the splits add (the split weights, first split first).
void interpolate_from_coarser(const MultigridLevel& level, Positions& D) {
  const VertexSplits& splits = level.splits;
  for (std::size_t s = 0; s < splits.size(); ++s) {
    Vec3 d = Vec3::Zero();
    for (int k = splits.offset[s]; k < splits.offset[s + 1]; ++k)
      d += level.weights[k] * D.row(splits.ring[k]).transpose();
    D.row(splits.vertex[s]) = d;
  }
}

}  // namespace

bool Multigrid::coarse_correction(int l, const Positions& X, const Eigen::VectorXd* tau,
                                  bool top, int offset, Positions& D) {
  MultigridLevel& level = levels_[l];
  Construction& construction = *level.construction;
  const int nf = level.region.n_free;
  Eigen::VectorXd defect = Eigen::VectorXd::Zero(level.region.n);
  defect.head(nf) = construction.defects();
  if (tau) defect.head(nf) -= *tau;
  restrict_to_coarser(level, defect);

  // The coarse problem d_c(Y) = d_c(Y_c) − R d at the injected positions Y_c.
  MultigridLevel& coarse = levels_[l - 1];
  const std::vector<int>& map = level.from_coarser;
  Positions Yc(coarse.region.n, 3);
  for (int c = 0; c < coarse.region.n; ++c) Yc.row(c) = X.row(map[c]);
  coarse.construction->set_source(nullptr, false);
  coarse.construction->evaluate(Yc);
  Eigen::VectorXd tau_c = coarse.construction->defects();
  for (int c = 0; c < coarse.region.n_free; ++c) tau_c(c) -= defect(map[c]);
  Positions Y = Yc;
  bool solved = true;
  try {
    cycle(l - 1, Y, &tau_c, false, offset + tuning_.smoothing);
  } catch (const SolverError&) {
    solved = false;  // the coarse problem diverged: smooth without its correction
  }
  coarse.construction->set_source(nullptr, true);
  construction.set_source(tau, top);
  if (cancelled_ || !solved) return solved;

  // The coarse change, interpolated to the new vertices.
  D = Positions::Zero(level.region.n, 3);
  for (int c = 0; c < coarse.region.n_free; ++c) D.row(map[c]) = Y.row(c) - Yc.row(c);
  interpolate_from_coarser(level, D);
  return true;
}

void Multigrid::cycle(int l, Positions& X, const Eigen::VectorXd* tau, bool top, int offset) {
  MultigridLevel& level = levels_[l];
  Construction& construction = *level.construction;
  const int nf = level.region.n_free;
  construction.set_source(tau, top);
  if (l == 0) {
    const double r0 = construction.evaluate(X);
    const IterationReport base =
        construction.run(X, tuning_.base_iterations, tuning_.base_reduction * r0, offset);
    cancelled_ = cancelled_ || base.cancelled;
    return;
  }
  CorrectionState& state = state_[l];

  // Smoothing iterations count against the budget only on the level being solved.
  auto smooth = [&](int at_offset) {
    const int n = top ? std::min(tuning_.smoothing, budget_) : tuning_.smoothing;
    IterationReport r = construction.run(X, n, 0.0, at_offset);
    if (top) budget_ -= r.iterations;
    cancelled_ = cancelled_ || r.cancelled;
    return r;
  };
  const IterationReport pre = smooth(offset);
  if (cancelled_ || budget_ <= 0) return;
  if (state.skip > 0) {  // corrections did not help lately: smooth only
    --state.skip;
    smooth(offset + tuning_.smoothing);
    return;
  }
  auto reject = [&] {
    state.damping = std::max(state.damping / 2, tuning_.min_correction);
    state.skip = std::min((1 << std::min(state.rejections, 30)) - 1, tuning_.max_skip);
    ++state.rejections;
  };

  Positions D;
  const bool solved = coarse_correction(l, X, tau, top, offset, D);
  if (cancelled_) return;
  if (!solved) {
    reject();
    smooth(offset + tuning_.smoothing);
    return;
  }
  const Positions X_pre = X;
  X.topRows(nf) += state.damping * D.topRows(nf);
  IterationReport post;
  try {
    post = smooth(offset + tuning_.smoothing);
  } catch (const SolverError&) {
    post.residual = HUGE_VAL;
  }
  if (cancelled_) return;
  if (post.residual <= pre.residual) {  // keep the correction
    state.damping = std::min(2 * state.damping, 1.0);
    state.rejections = 0;
    return;
  }
  // It made things worse: undo it, damp and pause the corrections, smooth instead.
  X = X_pre;
  reject();
  smooth(offset + 2 * tuning_.smoothing);
}

}  // namespace geofair
