// Inner fairness: the generalized Laplacian Δ(q_i) = -q_i + Σ_j λ_ij q_j that decides where
// vertices sit on the surface (Schneider & Kobbelt 2001, section 7.3).
#pragma once

#include "region.h"
#include "sparse_lu.h"
#include "geofair/types.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <unsupported/Eigen/IterativeSolvers>

#include <vector>

namespace geofair {

/// Inner fairness weights λ_ij of every vertex of a region, in flat (CSR) arrays for the
/// inner loops: vertex i (0 .. size()-1) has the neighbours neighbour[offset[i] ..
/// offset[i+1]) with the weights weight[...], each ≥ 0, summing to 1 (a convex combination).
///
/// The neighbours are the one-ring (in ring order, one entry per ring slot), except for
/// InnerFairness::ConformalIntrinsic on a mesh that is not intrinsically Delaunay: its
/// intrinsic edges can join vertices that are not mesh neighbours (and miss some that
/// are), and the neighbours of vertex i are the other ends of its intrinsic edges, in
/// increasing order.
struct InnerFairnessWeights {
  std::vector<int> offset;     ///< #vertices + 1
  std::vector<int> neighbour;  ///< vertex ids (local ids of the region)
  std::vector<double> weight;  ///< λ_ij, dimensionless
  /// S_i = Σ_k w_ik, the row sums of the weights w before their normalization
  /// λ_ij = w_ij / S_i (the valence for uniform weights), #vertices. The uniform, cotangent
  /// and intrinsic weights are symmetric (w_ij = w_ji), so S_i λ_ij = S_j λ_ji:
  /// bilaplacian_initial_mesh then solves a symmetric system. Empty where that does not
  /// hold: a vertex with mean value weights (Conformal, see inner_fairness_weights), or one
  /// whose weights all vanish or are not finite and fall back to uniform weights of its own.
  std::vector<double> row_sum;

  int size() const { return int(offset.size()) - 1; }
};

/// Inner fairness weights λ of a fairing region (Schneider & Kobbelt 2001, section 7.3) for
/// all its vertices, free and G1 boundary; X0 #region×3 the ORIGINAL positions.
///
/// Uniform: λ_ij = 1/valence over the one-ring. Where the region carries polygon diagonals
/// (FairingRegion::polygon_diagonal, a triangulated polygon mesh), over the polygon mesh's
/// edges instead: λ_ij = 1/m_i for the m_i neighbours not across a diagonal, 0 across one,
/// so that the vertex distribution does not depend on how the polygons were split into
/// triangles. A vertex left with no such neighbour, or a free vertex with fewer than three,
/// keeps its whole ring (row_sum then empty).
///
/// Conformal (the paper's): λ_ij = w_ij / Σ_k w_ik with the cotangent weights
/// w_ij = cot α_ij + cot β_ij of the mesh X0 itself, per ring slot: a discrete harmonic map
/// (Pinkall & Polthier 1993), approximately conformal to the original. w_ij < 0 across an
/// edge whose opposite angles sum to more than π (obtuse and needle triangles); such
/// weights are clamped to 0 so that λ stays a convex combination (with negative weights
/// q_i = Σ_j λ_ij q_j has no maximum principle and the iteration can diverge). Clamping
/// changes the map: on the obtuse lattices of bench/negative_weights.py the vertices land
/// 0.34–3.2 mean edge lengths away from the harmonic map of the original's metric.
/// Where the neighbours left with a positive weight do not surround the vertex (an angle of
/// at least π between two consecutive ones, the ring's angles scaled to a full turn: at
/// sharp cone points of the original, never on a planar ring), their convex combination
/// would put it on the border of their hull and collapse its triangles; such a vertex takes
/// Floater's mean value weights of its original ring instead (positive; not symmetric, so
/// row_sum is left empty). docs/REAL_MESHES.md, "The face of Fig. 10".
///
/// ConformalIntrinsic: the same with the Laplace–Beltrami operator of Bobenko & Springborn
/// 2007 ("A discrete Laplace–Beltrami operator for simplicial surfaces", DCG 38):
/// λ_ij = L_ij / Σ_k L_ik with L the cotangent Laplacian of the intrinsic Delaunay
/// triangulation of X0 over the region's triangles (intrinsic_delaunay.h). That
/// triangulation describes the same piecewise-flat surface (no vertex moves) with edges
/// across which α + β ≤ π, so L_ij ≥ 0 and nothing needs clamping at a free vertex: every
/// edge there is interior and flippable. The conformal fairing then puts the vertices where
/// the discrete harmonic map of the original's metric puts them (tests/test_negative_weights.py,
/// to round-off on a plane). Where the mesh is already intrinsically Delaunay (no flip,
/// e.g. no obtuse triangle) the weights are exactly those of Conformal, per ring slot;
/// otherwise the neighbours are those of the intrinsic edges (see InnerFairnessWeights).
/// Clamping stays only where the triangulation cannot help: border edges of the region
/// (between two G1 boundary vertices: one triangle, never flipped; they enter only the
/// one-sided Laplacian of G1 boundary vertices in the linear initial mesh, bilaplacian.h),
/// and round-off (the flips stop at cot α + cot β ≥ −1e-12). Not what Conformal does: the
/// harmonic map of a rough original (noise as large as the features) onto the smooth
/// faired surface can bring two vertices much closer than an edge length, where the
/// construction oscillates and stalls (a limit of the iteration, not of the weights;
/// docs/DESIGN_NOTES.md).
///
/// A vertex whose weights all vanish (on the region's border) or are not finite (a
/// degenerate ring) falls back to uniform weights over its neighbours.
/// \throw InvalidInputError as intrinsic_delaunay (not for a valid region).
InnerFairnessWeights inner_fairness_weights(const FairingRegion& region, const Positions& X0,
                                            InnerFairness type);

/// The weights of inner_fairness_weights for Uniform and Conformal, per ring slot of
/// `rings` (the neighbours are the one-rings), X0 #V×3; ConformalIntrinsic is taken as
/// Conformal. Used where the mesh's own edges are wanted: by the coarse multigrid levels
/// (fairing.h), and by inner_fairness_weights.
InnerFairnessWeights ring_inner_fairness_weights(const OneRings& rings, const Positions& X0,
                                                 InnerFairness type);

/// Σ_j λ_ij q_j for vertex i, positions X (#region×3).
inline Vec3 weighted_centroid(const InnerFairnessWeights& lambda, const Positions& X, int i) {
  Vec3 c = Vec3::Zero();
  for (int k = lambda.offset[i]; k < lambda.offset[i + 1]; ++k)
    c += lambda.weight[k] * X.row(lambda.neighbour[k]).transpose();
  return c;
}


/// Interpolation of corrections from a coarser level (multigrid.h, coarse_space):
/// row i, free vertex i of the level, holds the weights of the coarser level's free vertices
/// (columns) in the value at i; `vertex[c]` is the level-local id of column c's vertex.
/// `lambda`: the coarser level's inner fairness weights, one row per column c (its
/// neighbours as column ids, -1 for a G1 boundary vertex), for the coarse-grid operator.
struct CoarseSpace {
  Eigen::SparseMatrix<double, Eigen::RowMajor> P;
  std::vector<int> vertex;
  InnerFairnessWeights lambda;
};

/// The global step of inner fairness (beyond the paper): moves every free
/// vertex within its tangent plane so that the tangential part of the generalized Laplacian
/// vanishes at all free vertices at once, instead of one vertex at a time.
///
/// The vertex update of section 7.3 moves q_i to the tangential projection of Σ_j λ_ij q_j,
/// a Jacobi/Gauss–Seidel relaxation of the linear inner-fairness condition: low-frequency
/// tangential errors take O(#V_I) iterations to vanish, and while vertices drift the
/// discretization of H changes and keeps the residual of eq. (12) up. Linearized with the
/// tangent planes fixed, the condition is
///   T_iᵀ (Σ_j λ_ij (q_j + T_j u_j) − (q_i + T_i u_i)) = 0   for all free i,
/// a 2#V_I×2#V_I sparse system for the tangential offsets u_i (T_i = 3×2 basis of the tangent
/// plane of unit normal n_i; boundary vertices do not move). `iterations` BiCGSTAB
/// iterations (the system is not symmetric for λ_ij ≠ λ_ji) from u = 0, then
/// q_i ← q_i + s T_i u_i with |T_i u_i| limited to half the mean distance to the neighbours.
/// Mirrors the paper's global CG step for H~ (section 7.1); docs/DESIGN_NOTES.md.
class TangentialSolver {
 public:
  /// \param rings    one-rings of the region (the step length limit uses them)
  /// \param pattern  inner fairness weights whose neighbours give the sparsity pattern;
  ///                 every step must pass weights with the same neighbours
  /// \param n_free   free vertices are 0 .. n_free-1 of `rings`
  /// \param iterations  BiCGSTAB iterations of step() (PaperIterationTuning)
  /// \param tuning   relax()'s limits and iterations
  TangentialSolver(const OneRings& rings, const InnerFairnessWeights& pattern, int n_free,
                   int iterations, const TangentialTuning& tuning = {});

  /// \param lambda  inner fairness weights, with the neighbours of the constructor's pattern
  /// \param X       #region×3 positions, free rows updated in place
  /// \param N       #region×3 unit normals of the free vertices at X
  /// \param damping s in (0, 1]
  void step(const InnerFairnessWeights& lambda, const Positions& N, double damping, Positions& X);

  /// The same linearized system solved directly (sparse LU, SuiteSparse's UMFPACK), and the
  /// whole step scaled by one factor so that no edge of the ring stretches or shrinks by more
  /// than tuning.max_stretch of its length (instead of limiting each vertex's move): for bringing
  /// a mesh to inner fairness from afar, where the distribution that satisfies it lies many
  /// edge lengths away (construction.h, run_newton). Arguments as for step(): X #region×3,
  /// free rows moved in place (mesh units), N #region×3 unit normals at X.
  /// With `lagged`, a factorization of an earlier call (at nearby normals, as in the
  /// repeated polishes of a converged shape) preconditions GMRES on the new system to the
  /// relative residual tuning.lagged_tolerance instead of a new factorization; a fresh one
  /// is taken if there is none or GMRES does not converge in tuning.lagged_iterations.
  /// `planes`: the linearization (TangentPlanes): Turning near inner fairness, where it
  /// converges quadratically.
  /// `lagged_tolerance`: GMRES's relative residual on the lagged factorization, if not
  /// tuning.lagged_tolerance (0).
  /// \return the scale applied, in (0, 1]; 0 if the system was singular or an edge has zero
  ///         length (X unchanged)
  double relax(const InnerFairnessWeights& lambda, const Positions& N, Positions& X,
               bool lagged = false, TangentPlanes planes = TangentPlanes::Fixed,
               double lagged_tolerance = 0.0);

  /// Gives relax a coarse space (the next coarser level of a progressive mesh, whose
  /// vertices are vertices of this one): relax then solves by GMRES preconditioned by a
  /// two-grid cycle instead of factorizing the system, tuning.two_grid_sweeps symmetric Gauss–Seidel
  /// sweeps around a coarse-grid correction P̃ A_c⁻¹ P̃ᵀ (P̃: the interpolation carried into
  /// the tangent bases, P_ic T_iᵀ T_c). A_c is the coarser level's own linearized system
  /// (fixed tangent planes, weights coarse.lambda) in the tangent bases T_c of its vertices
  /// here: the operator rediscretized on the coarse mesh, 1-ring sparse, rather than the
  /// Galerkin product P̃ᵀ A P̃, whose stencil is wider: as good a preconditioner, cheaper
  /// to build and factorize (docs/DESIGN_NOTES.md). A_c (with `coarser` below: the next
  /// coarser system) is factorized at the first relax and, with `lagged`, kept for the
  /// next ones. If GMRES does not converge in tuning.two_grid_iterations (to
  /// tuning.two_grid_tolerance), the system is factorized.
  ///
  /// `coarser`: the coarse space of the coarser level itself (its rows the columns of
  /// `coarse`, its `vertex` column ids of `coarse`), or empty. With it the coarse-grid
  /// correction is not A_c's LU but a cycle of the same kind on A_c around the LU of the
  /// next coarser level's system (in the tangent bases here): a three-grid cycle, which
  /// factorizes a system 4 times smaller, with the same GMRES iterations
  /// (docs/DESIGN_NOTES.md).
  void set_coarse_space(CoarseSpace coarse, CoarseSpace coarser = {}) {
    coarse_ = std::move(coarse);
    coarser_ = std::move(coarser);
  }

 private:
  // Fills A_ at the tangent planes of N and returns the right-hand side.
  Eigen::VectorXd assemble(const InnerFairnessWeights& lambda, const Positions& N,
                           const Positions& X, TangentPlanes planes);
  // The derivative of the unit normal along the surface at free vertex i, in the basis
  // (t1_[i], t2_[i]) of the last assemble(): 2×2, symmetric, 1/mesh units (the shape
  // operator up to the normal's sign); zero if the ring spans no plane.
  Eigen::Matrix2d normal_derivative(const Positions& N, const Positions& X, int i) const;

  const OneRings& rings_;
  int n_free_;
  TangentialTuning tuning_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> A_;
  std::vector<int> slot_value_;  // per weight of a free vertex: index of its 2×2 block, or -1
  std::vector<int> diag_value_;  // per free vertex: index of its diagonal 2×2 block
  std::vector<Vec3> t1_, t2_;    // tangent bases of the last assemble()
  // The tangential move u (2 per free vertex) of the system assembled last, by GMRES with
  // the two-grid preconditioner; false if it did not converge.
  bool solve_two_grid(const Eigen::VectorXd& rhs, bool lagged, Eigen::VectorXd& u);

  // Two-grid cycle on A_ (see set_coarse_space), as an Eigen preconditioner; with
  // three_grid the coarse correction is itself a two-grid cycle.
  struct TwoGrid {
    const TangentialSolver* solver = nullptr;
    bool three_grid = false;
    template <class M> TwoGrid& analyzePattern(const M&) { return *this; }
    template <class M> TwoGrid& factorize(const M&) { return *this; }
    template <class M> TwoGrid& compute(const M&) { return *this; }
    Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
    Eigen::ComputationInfo info() const { return Eigen::Success; }
  };

  PatternLU direct_;
  Eigen::GMRES<Eigen::SparseMatrix<double, Eigen::RowMajor>, LaggedFactorization> lagged_;
  CoarseSpace coarse_, coarser_;
  Eigen::SparseMatrix<double> coarse_P_;  // P̃ of the last coarse factorization
  PatternLU coarse_lu_;
  // The three-grid cycle's: A_c by rows, P̃ from the coarser level, that level's LU.
  Eigen::SparseMatrix<double, Eigen::RowMajor> coarse_rows_;
  Eigen::SparseMatrix<double> coarser_P_;
  PatternLU coarser_lu_;
  Eigen::GMRES<Eigen::SparseMatrix<double, Eigen::RowMajor>, TwoGrid> two_grid_;
  Eigen::BiCGSTAB<Eigen::SparseMatrix<double, Eigen::RowMajor>, Eigen::IdentityPreconditioner>
      solver_;
};

}  // namespace geofair
