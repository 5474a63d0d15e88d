// Uniform and discrete-conformal inner fairness weights (section 7.3), the latter from the
// intrinsic Delaunay triangulation (Bobenko & Springborn 2007), and the global tangential step.
#include "inner_fairness.h"

#include "common.h"
#include "curvature_solve.h"
#include "intrinsic_delaunay.h"
#include "laplace_beltrami.h"
#include "parallel.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <vector>

namespace geofair {

namespace {

// λ_ij = w_ij / Σ_k w_ik over vertex i's weights [begin, end), w clamped at 0; uniform if
// they all vanish (or are not finite). Returns the sum Σ_k w_ik, or 0 for the uniform
// fallback (whose weights are not those of the neighbours' rows: no symmetric row sum).
double normalize(double* w, int m) {
  double sum = 0.0;
  for (int k = 0; k < m; ++k) {
    w[k] = std::max(w[k], 0.0);
    sum += w[k];
  }
  if (!(sum > 0.0) || !std::isfinite(sum)) {
    std::fill(w, w + m, 1.0 / m);
    return 0.0;
  }
  for (int k = 0; k < m; ++k) w[k] /= sum;
  return sum;
}

// The angles at q_i between consecutive neighbours of its closed ring (3D, in (0, π)).
void ring_angles(const OneRings& rings, const Positions& X, int i, double* alpha) {
  const int begin = rings.offset[i], m = rings.valence(i);
  const Vec3 qi = X.row(i);
  for (int k = 0; k < m; ++k) {
    const Vec3 a = Vec3(X.row(rings.ring[begin + k])) - qi;
    const Vec3 b = Vec3(X.row(rings.ring[begin + (k + 1) % m])) - qi;
    alpha[k] = std::atan2(a.cross(b).norm(), a.dot(b));
  }
}

// True if the neighbours with a positive weight w surround q_i: no angle of at least π
// (the ring's angles scaled to a full turn) lies between two consecutive ones. Otherwise
// the convex combination of those neighbours puts q_i on the border of their hull.
bool surrounded_by_positive_weights(const double* w, const double* alpha, int m) {
  double total = 0.0;
  for (int k = 0; k < m; ++k) total += alpha[k];
  int first = 0;
  while (first < m && !(w[first] > 0.0)) ++first;
  if (first == m || !(total > 0.0)) return false;
  double gap = 0.0;
  for (int s = 1; s <= m; ++s) {
    const int k = (first + s) % m;
    gap += alpha[(k + m - 1) % m];
    if (w[k] > 0.0) {
      if (gap * (2.0 * M_PI / total) >= M_PI) return false;
      gap = 0.0;
    }
  }
  return true;
}

// Floater's mean value weights of q_i's closed ring in X (Floater 2003): w_ij =
// (tan(α_{j−1}/2) + tan(α_j/2)) / |q_j − q_i| with α the ring angles; positive.
void mean_value_weights(const OneRings& rings, const Positions& X, int i, const double* alpha,
                        double* w) {
  const int begin = rings.offset[i], m = rings.valence(i);
  for (int k = 0; k < m; ++k) {
    const double length = (X.row(rings.ring[begin + k]) - X.row(i)).norm();
    w[k] = (std::tan(alpha[(k + m - 1) % m] / 2) + std::tan(alpha[k] / 2)) / length;
  }
}

// Keeps lambda.row_sum only if every vertex with weights has one (see InnerFairnessWeights).
void drop_row_sums_unless_symmetric(InnerFairnessWeights& lambda) {
  for (int i = 0; i < lambda.size(); ++i)
    if (lambda.offset[i + 1] > lambda.offset[i] && !(lambda.row_sum[i] > 0.0)) {
      lambda.row_sum.clear();
      return;
    }
}

// Uniform weights over the polygon mesh's edges: λ_ij = 1/m_i over the m_i ring neighbours
// not across a polygon diagonal. A vertex left with none (or a free vertex with fewer than
// three: bogus polygon ids, or a vertex inside a polygon's outline) keeps its whole ring,
// the weights of `uniform` (the triangles' umbrella).
InnerFairnessWeights polygon_uniform_weights(const FairingRegion& region,
                                             InnerFairnessWeights uniform) {
  const OneRings& rings = region.rings;
  const std::vector<std::uint8_t>& diagonal = region.polygon_diagonal;
  std::vector<std::uint8_t> whole_ring(region.n, 1);
  for (int i = 0; i < region.n; ++i) {
    const int begin = rings.offset[i], m = rings.valence(i);
    int edges = 0;
    for (int k = begin; k < begin + m; ++k) edges += !diagonal[k];
    if (edges == 0 || (i < region.n_free && edges < 3)) continue;
    whole_ring[i] = 0;
    for (int k = begin; k < begin + m; ++k) uniform.weight[k] = diagonal[k] ? 0.0 : 1.0;
    uniform.row_sum[i] = normalize(uniform.weight.data() + begin, m);
  }
  // An edge of the polygon mesh counts at both ends; a diagonal only at an end that kept its
  // ring: symmetric (S_i λ_ij = S_j λ_ji) unless a diagonal joins such an end to another.
  for (int i = 0; i < region.n && !uniform.row_sum.empty(); ++i)
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k)
      if (diagonal[k] && whole_ring[i] != whole_ring[rings.ring[k]]) {
        uniform.row_sum.clear();
        break;
      }
  return uniform;
}

}  // namespace

InnerFairnessWeights ring_inner_fairness_weights(const OneRings& rings, const Positions& X0,
                                                 InnerFairness type) {
  const int nv = int(rings.offset.size()) - 1;
  InnerFairnessWeights lambda;
  lambda.offset = rings.offset;
  lambda.neighbour = rings.ring;
  lambda.weight.assign(rings.ring.size(), 1.0);
  lambda.row_sum.assign(nv, 0.0);
  std::vector<double> alpha;
  for (int i = 0; i < nv; ++i) {
    const int begin = rings.offset[i], m = rings.valence(i);
    if (m == 0) continue;
    double* w = lambda.weight.data() + begin;
    if (type != InnerFairness::Uniform) cotangent_weights(rings, X0, i, w);
    bool symmetric = true;
    if (type != InnerFairness::Uniform && rings.closed(i)) {
      alpha.resize(m);
      ring_angles(rings, X0, i, alpha.data());
      if (!surrounded_by_positive_weights(w, alpha.data(), m)) {
        mean_value_weights(rings, X0, i, alpha.data(), w);
        symmetric = false;
      }
    }
    const double sum = normalize(w, m);
    lambda.row_sum[i] = symmetric ? sum : 0.0;
  }
  drop_row_sums_unless_symmetric(lambda);
  return lambda;
}

InnerFairnessWeights inner_fairness_weights(const FairingRegion& region, const Positions& X0,
                                            InnerFairness type) {
  if (type == InnerFairness::Uniform && !region.polygon_diagonal.empty())
    return polygon_uniform_weights(region, ring_inner_fairness_weights(region.rings, X0, type));
  if (type != InnerFairness::ConformalIntrinsic)
    return ring_inner_fairness_weights(region.rings, X0, type);
  int flips = 0;
  const SparseRowMatrix L =
      intrinsic_delaunay_laplacian(X0, region.triangles, &flips);
  // Intrinsically Delaunay already: the mesh's own cotangent weights, as the paper's.
  if (flips == 0) return ring_inner_fairness_weights(region.rings, X0, type);
  InnerFairnessWeights lambda;
  lambda.offset.assign(1, 0);
  lambda.neighbour.reserve(L.nonZeros());
  lambda.weight.reserve(L.nonZeros());
  lambda.row_sum.assign(region.n, 0.0);
  for (int i = 0; i < region.n; ++i) {
    for (SparseRowMatrix::InnerIterator it(L, i); it; ++it) {
      if (it.col() == i) continue;
      lambda.neighbour.push_back(int(it.col()));
      lambda.weight.push_back(it.value());
    }
    lambda.offset.push_back(int(lambda.neighbour.size()));
    lambda.row_sum[i] =
        normalize(lambda.weight.data() + lambda.offset[i], lambda.offset[i + 1] - lambda.offset[i]);
  }
  drop_row_sums_unless_symmetric(lambda);
  return lambda;
}

TangentialSolver::TangentialSolver(const OneRings& rings, const InnerFairnessWeights& pattern,
                                   int n_free, int iterations,
                                   const TangentialTuning& tuning)
    : rings_(rings), n_free_(n_free), tuning_(tuning) {
  // Block pattern: 2×2 blocks at (i, i) and at (i, j) for free neighbours j (of λ: with
  // intrinsic weights not necessarily ring neighbours).
  const std::vector<int>& offset = pattern.offset;
  const std::vector<int>& neighbour = pattern.neighbour;
  std::vector<Eigen::Triplet<double>> blocks;
  for (int i = 0; i < n_free; ++i) {
    auto block = [&](int j) {
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) blocks.emplace_back(2 * i + a, 2 * j + b, 1.0);
    };
    block(i);
    for (int k = offset[i]; k < offset[i + 1]; ++k)
      if (neighbour[k] < n_free) block(neighbour[k]);
  }
  A_.resize(2 * n_free, 2 * n_free);
  A_.setFromTriplets(blocks.begin(), blocks.end());
  A_.makeCompressed();
  // Blocks are found through the first of their four entries (row 2i, column 2j); the
  // second row of the block starts at the same offset in row 2i+1.
  diag_value_.resize(n_free);
  slot_value_.assign(offset[n_free], -1);
  for (int i = 0; i < n_free; ++i) {
    diag_value_[i] = stored_entry(A_, 2 * i, 2 * i);
    for (int k = offset[i]; k < offset[i + 1]; ++k)
      if (neighbour[k] < n_free) slot_value_[k] = stored_entry(A_, 2 * i, 2 * neighbour[k]);
  }
  solver_.setMaxIterations(iterations);
  solver_.setTolerance(1e-12);
}

Eigen::VectorXd TangentialSolver::assemble(const InnerFairnessWeights& lambda, const Positions& N,
                                           const Positions& X, TangentPlanes planes) {
  const int nf = n_free_;
  // Tangent bases: the last ones carried over to the new tangent planes (projected), so
  // that the system changes only as much as the normals do (a lagged factorization stays a
  // good preconditioner, see relax); new ones where there are none or the projection is
  // short. The solution, a tangential move, does not depend on the bases.
  const bool carry = t1_.size() == std::size_t(nf);
  t1_.resize(nf), t2_.resize(nf);
  for (int i = 0; i < nf; ++i) {
    const Vec3 n = N.row(i);
    Vec3 t = carry ? Vec3(t1_[i] - t1_[i].dot(n) * n) : Vec3(Vec3::Zero());
    if (!(t.norm() > 0.5)) t = n.cross(std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY());
    t1_[i] = t.normalized();
    t2_[i] = n.cross(t1_[i]);
  }
  double* values = A_.valuePtr();
  const int* outer = A_.outerIndexPtr();
  // Entry (row 2i+a, column 2j+b) of the block whose first entry is at p.
  auto entry = [&](int i, int p, int a, int b) -> double& {
    return values[p + b + (a ? outer[2 * i + 1] - outer[2 * i] : 0)];
  };
  Eigen::VectorXd rhs(2 * nf);
  for (int i = 0; i < nf; ++i) {
    const int p = diag_value_[i];
    entry(i, p, 0, 0) = entry(i, p, 1, 1) = 1.0;
    entry(i, p, 0, 1) = entry(i, p, 1, 0) = 0.0;
    const Vec3 residual = weighted_centroid(lambda, X, i) - X.row(i).transpose();
    rhs(2 * i) = residual.dot(t1_[i]);
    rhs(2 * i + 1) = residual.dot(t2_[i]);
    // With turning planes: the tangent plane turns as the vertex moves along the surface, by
    // the normal's derivative D_i (2×2 in the basis, fitted to the ring's normals), and the
    // normal part ℓ_i of the residual tilts into it: diagonal block I + ℓ_i D_i.
    if (planes == TangentPlanes::Turning) {
      const Eigen::Matrix2d turn = residual.dot(N.row(i)) * normal_derivative(N, X, i);
      if (turn.allFinite() && turn.norm() < tuning_.max_turn)
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) entry(i, p, a, b) += turn(a, b);
    }
    for (int k = lambda.offset[i]; k < lambda.offset[i + 1]; ++k) {
      if (slot_value_[k] < 0) continue;
      const int j = lambda.neighbour[k], q = slot_value_[k];
      const double w = lambda.weight[k];
      entry(i, q, 0, 0) = -w * t1_[i].dot(t1_[j]);
      entry(i, q, 0, 1) = -w * t1_[i].dot(t2_[j]);
      entry(i, q, 1, 0) = -w * t2_[i].dot(t1_[j]);
      entry(i, q, 1, 1) = -w * t2_[i].dot(t2_[j]);
    }
  }
  return rhs;
}

Eigen::Matrix2d TangentialSolver::normal_derivative(const Positions& N, const Positions& X,
                                                    int i) const {
  // Least squares over the ring: T_iᵀ(n_j − n_i) ≈ D T_iᵀ(q_j − q_i), symmetrized.
  Eigen::Matrix2d M = Eigen::Matrix2d::Zero(), B = Eigen::Matrix2d::Zero();
  for (int k = rings_.offset[i]; k < rings_.offset[i + 1]; ++k) {
    const int j = rings_.ring[k];
    const Vec3 dq = (X.row(j) - X.row(i)).transpose(), dn = (N.row(j) - N.row(i)).transpose();
    const Eigen::Vector2d a(dq.dot(t1_[i]), dq.dot(t2_[i])), b(dn.dot(t1_[i]), dn.dot(t2_[i]));
    M += a * a.transpose();
    B += b * a.transpose();
  }
  if (!(M.determinant() > 1e-12 * M.trace() * M.trace())) return Eigen::Matrix2d::Zero();
  const Eigen::Matrix2d D = B * M.inverse();
  return 0.5 * (D + D.transpose());
}

void TangentialSolver::step(const InnerFairnessWeights& lambda, const Positions& N, double damping,
                            Positions& X) {
  const Eigen::VectorXd rhs = assemble(lambda, N, X, TangentPlanes::Fixed);
  solver_.compute(A_);
  const Eigen::VectorXd u = solver_.solve(rhs);
  if (!u.allFinite()) return;  // a breakdown: leave the tangential positions to the local steps
  for (int i = 0; i < n_free_; ++i) {
    const double mean_distance = rings_.mean_neighbour_distance(X, i);
    Vec3 d = u(2 * i) * t1_[i] + u(2 * i + 1) * t2_[i];
    const double len = d.norm();
    if (len > 0.5 * mean_distance) d *= 0.5 * mean_distance / len;
    X.row(i) += damping * d.transpose();
  }
}

double TangentialSolver::relax(const InnerFairnessWeights& lambda, const Positions& N,
                               Positions& X, bool lagged, TangentPlanes planes,
                               double lagged_tolerance) {
  const int nf = n_free_;
  const Eigen::VectorXd rhs = assemble(lambda, N, X, planes);
  Eigen::VectorXd u;
  if (!coarse_.vertex.empty() && !solve_two_grid(rhs, lagged, u)) u.resize(0);
  if (u.size() == 0 && lagged && direct_.factorized()) {
    lagged_.preconditioner().lu = &direct_;
    set_up_gmres(lagged_, A_, tuning_.lagged_iterations,
                 lagged_tolerance > 0.0 ? lagged_tolerance : tuning_.lagged_tolerance);
    u = lagged_.solve(rhs);
    if (lagged_.info() != Eigen::Success) u.resize(0);
  }
  if (u.size() == 0) {
    if (!direct_.factorize(A_)) return 0.0;
    u = direct_.solve(rhs);
  }
  if (!u.allFinite()) return 0.0;
  // One scale for the whole step: no edge stretches or shrinks by more than max_stretch of
  // its length (the offsets of boundary vertices are 0).
  auto offset = [&](int i) {
    return i < nf ? Vec3(u(2 * i) * t1_[i] + u(2 * i + 1) * t2_[i]) : Vec3(Vec3::Zero());
  };
  double stretch = 0.0;
  for (int i = 0; i < nf; ++i)
    for (int k = rings_.offset[i]; k < rings_.offset[i + 1]; ++k) {
      const int j = rings_.ring[k];
      stretch = std::max(stretch, (offset(i) - offset(j)).norm() / (X.row(j) - X.row(i)).norm());
    }
  if (!std::isfinite(stretch)) return 0.0;
  const double scale = stretch > tuning_.max_stretch ? tuning_.max_stretch / stretch : 1.0;
  for (int i = 0; i < nf; ++i) X.row(i) += scale * offset(i).transpose();
  return scale;
}

bool TangentialSolver::solve_two_grid(const Eigen::VectorXd& rhs, bool lagged,
                                      Eigen::VectorXd& u) {
  const int nc = int(coarse_.vertex.size());
  const bool three_grid = !coarser_.vertex.empty();
  if (!lagged || !(three_grid ? coarser_lu_.factorized() : coarse_lu_.factorized())) {
    // Block (a, b) of T_aᵀ T_b for vertices a, b with tangent bases of the last assemble().
    auto add_block = [&](std::vector<Eigen::Triplet<double>>& entries, int row, int col, int a,
                         int b, double w) {
      entries.emplace_back(2 * row, 2 * col, w * t1_[a].dot(t1_[b]));
      entries.emplace_back(2 * row, 2 * col + 1, w * t1_[a].dot(t2_[b]));
      entries.emplace_back(2 * row + 1, 2 * col, w * t2_[a].dot(t1_[b]));
      entries.emplace_back(2 * row + 1, 2 * col + 1, w * t2_[a].dot(t2_[b]));
    };
    // P̃ from the rows' vertices `row_vertex` (this level's ids) to the columns of `space`
    // (vertices space.vertex[c], mapped to this level's ids by `column_vertex`): block
    // (i, c) = P_ic T_iᵀ T_c, the coarse tangential move of column c's vertex carried over
    // into the tangent plane of row i's.
    auto interpolation = [&](const CoarseSpace& space, auto row_vertex, auto column_vertex) {
      std::vector<Eigen::Triplet<double>> entries;
      entries.reserve(4 * std::size_t(space.P.nonZeros()));
      for (int i = 0; i < space.P.rows(); ++i)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(space.P, i); it; ++it)
          add_block(entries, i, int(it.col()), row_vertex(i), column_vertex(int(it.col())),
                    it.value());
      Eigen::SparseMatrix<double> P(2 * space.P.rows(), 2 * space.P.cols());
      P.setFromTriplets(entries.begin(), entries.end());
      return P;
    };
    // The system of assemble() with fixed tangent planes on a coarser level with weights
    // `lambda` (columns as unknowns; G1 boundary neighbours do not move), in the tangent
    // bases here of the columns' vertices `vertex(c)`.
    auto coarse_system = [&](const InnerFairnessWeights& lambda, int n, auto vertex) {
      std::vector<Eigen::Triplet<double>> entries;
      entries.reserve(4 * (std::size_t(n) + lambda.neighbour.size()));
      for (int c = 0; c < n; ++c) {
        entries.emplace_back(2 * c, 2 * c, 1.0);
        entries.emplace_back(2 * c + 1, 2 * c + 1, 1.0);
        for (int k = lambda.offset[c]; k < lambda.offset[c + 1]; ++k)
          if (const int d = lambda.neighbour[k]; d >= 0)
            add_block(entries, c, d, vertex(c), vertex(d), -lambda.weight[k]);
      }
      Eigen::SparseMatrix<double> A(2 * n, 2 * n);
      A.setFromTriplets(entries.begin(), entries.end());
      A.makeCompressed();
      return A;
    };
    auto coarse_vertex = [&](int c) { return coarse_.vertex[c]; };
    coarse_P_ = interpolation(coarse_, [](int i) { return i; }, coarse_vertex);
    Eigen::SparseMatrix<double> coarse_A = coarse_system(coarse_.lambda, nc, coarse_vertex);
    if (three_grid) {
      auto coarser_vertex = [&](int c) { return coarse_.vertex[coarser_.vertex[c]]; };
      coarser_P_ = interpolation(coarser_, coarse_vertex, coarser_vertex);
      coarse_rows_ = coarse_A;
      if (!coarser_lu_.factorize(
              coarse_system(coarser_.lambda, int(coarser_.vertex.size()), coarser_vertex)))
        return false;
    } else if (!coarse_lu_.factorize(coarse_A)) {
      return false;
    }
  }
  two_grid_.preconditioner().solver = this;
  two_grid_.preconditioner().three_grid = three_grid;
  set_up_gmres(two_grid_, A_, tuning_.two_grid_iterations, tuning_.two_grid_tolerance);
  u = two_grid_.solve(rhs);
  return two_grid_.info() == Eigen::Success && u.allFinite();
}

namespace {

// Gauss–Seidel sweeps of systems of more rows than this run in two_grid_blocks blocks (a
// numerical choice, kept apart from the threads' kParallelMin: the blocks change the result).
constexpr int kBlockedSweepMin = 2500;

// x ≈ A⁻¹ b by two_grid_sweeps Gauss–Seidel sweeps on A, forward, then the correction
// P coarse⁻¹ Pᵀ of the residual, then as many sweeps backward.
template <class CoarseSolve>
Eigen::VectorXd two_grid_cycle(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A,
                               const Eigen::SparseMatrix<double>& P, const Eigen::VectorXd& b,
                               const TangentialTuning& tuning, const CoarseSolve& coarse_solve) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(A.rows());
  const int blocks = A.rows() > kBlockedSweepMin ? tuning.two_grid_blocks : 1;
  for (int s = 0; s < tuning.two_grid_sweeps; ++s) gauss_seidel_sweep(A, b, x, true, blocks);
  const Eigen::VectorXd residual = b - A * x;
  x += P * coarse_solve(Eigen::VectorXd(P.transpose() * residual));
  for (int s = 0; s < tuning.two_grid_sweeps; ++s) gauss_seidel_sweep(A, b, x, false, blocks);
  return x;
}

}  // namespace

Eigen::VectorXd TangentialSolver::TwoGrid::solve(const Eigen::VectorXd& b) const {
  const TangentialSolver& s = *solver;
  if (!three_grid)
    return two_grid_cycle(s.A_, s.coarse_P_, b, s.tuning_,
                          [&](const Eigen::VectorXd& r) { return s.coarse_lu_.solve(r); });
  return two_grid_cycle(s.A_, s.coarse_P_, b, s.tuning_, [&](const Eigen::VectorXd& r) {
    return two_grid_cycle(s.coarse_rows_, s.coarser_P_, r, s.tuning_,
                          [&](const Eigen::VectorXd& rc) { return s.coarser_lu_.solve(rc); });
  });
}

}  // namespace geofair
