// The multigrid construction on the levels of a progressive mesh (Schneider & Kobbelt 2001,
// section 7.4, Fig. 6; prolongation after Guskov et al. 1999), with nonlinear coarse-grid
// corrections (full approximation scheme) added to the paper's coarse-to-fine iteration.
#pragma once

#include "construction.h"
#include "progressive_mesh.h"
#include "region.h"
#include "geofair/types.h"

#include <deque>
#include <memory>
#include <vector>

namespace geofair {

/// λ of every vertex split over the ring it is split into (layout of VertexSplits::ring):
/// uniform, or for conformal inner fairness the clamped cotangent weights of the positions
/// X0 (#level×3), as ring_inner_fairness_weights computes them.
std::vector<double> split_weights(const VertexSplits& splits, InnerFairness inner,
                                  const Positions& X0);

/// Inserts the vertices a level adds to the coarser one, replaying the vertex splits in
/// order (section 7.4; a G1 boundary vertex that a coarsened boundary re-inserts keeps its
/// position in X and takes its prescribed normal, only its H is interpolated):
///  1. each new vertex q_i at Σ_j w_ij q_j over the ring it is split into (`weights`: the
///     conformal weights of the smoothed input, i.e. the inner-fairness position of the
///     coarse levels), with H and the normal interpolated the same way;
///  2. the 1-disks D(q_i) are relaxed, Δq_l = 0, by `sweeps` Gauss–Seidel sweeps
///     of q_l ← Σ_j λ_lj q_j (`lambda`, the level's inner fairness) over their union;
///  3. outer fairness is restored: each new vertex moves along its normal onto the surface
///     predicted by the tangent planes and mean curvatures of its split ring, the average of
///     t_j = (−⟨q_i − q_j, n_j⟩ − H_j/2 · |q_i − q_j|²_tangential) / ⟨n_i, n_j⟩.
/// Deviation from the paper: step 2 moves the old vertices too, but only within the coarse
/// surface's tangent plane, kept on its osculating paraboloid q = p + d − H/2 |d|² n (with
/// the normal turned to n + H d); the paper relaxes them in space and step 3 runs the
/// construction on D(q_i), which moved the coarse vertices off the coarse solution
/// (docs/DESIGN_NOTES.md).
///
/// \param level    the finer level's region
/// \param splits   the level's vertex splits, in level-local ids
/// \param weights  split_weights of `splits`
/// \param lambda   inner fairness weights of `level`
/// \param X        #level×3 positions: valid for all but the new vertices, which are set
/// \param H        #level mean curvatures, valid for the old vertices; the new are set
/// \param N        #level×3 unit normals, valid for the old vertices; the new are set
/// \param sweeps   step 2's sweeps (MultigridTuning::prolongation_sweeps)
void prolongate(const FairingRegion& level, const VertexSplits& splits,
                const std::vector<double>& weights, const InnerFairnessWeights& lambda,
                Positions& X, Eigen::VectorXd& H, Positions& N,
                int sweeps = MultigridTuning{}.prolongation_sweeps);

/// The interpolation of corrections that vanish on the G1 boundary from the next coarser
/// level to `level` (whose vertex splits, in level-local ids, are `splits`; a split of a G1
/// boundary vertex adds no unknown), as a sparse
/// matrix: a vertex of the coarser level keeps its value; a new vertex takes the mean over
/// its ring of the coarser level's vertices (the boundary counting as zeros), or, with
/// none of those in its ring, the mean of its ring's rows. Columns: the coarser level's free
/// vertices, in increasing level-local id. The coarse space of the finest level's tangential
/// solves (TangentialSolver::set_coarse_space); the replayed splits of prolongate
/// interpolate too, but their rows fill up (docs/DESIGN_NOTES.md, "Multigrid cycles"). The
/// levels are those of the progressive mesh of section 7.4.
/// \param level    the finer level's region
/// \param splits   its vertex splits, in level-local ids
/// \param coarser  the coarser level's region (its `global` ids and those of `level` are
///                 ids of one region)
/// \param coarser_lambda  the coarser level's inner fairness weights
/// \return P: #V_I(level) × #V_I(coarser level), dimensionless weights in [0, 1] whose row
///         sums are 1 away from the boundary and less next to it; `vertex`: the coarser
///         level's free vertices (level-local ids), one per column; `lambda`: the rows of
///         coarser_lambda of those vertices, neighbours renumbered to columns (-1: G1
///         boundary). Throws nothing.
CoarseSpace coarse_space(const FairingRegion& level, const VertexSplits& splits,
                         const FairingRegion& coarser,
                         const InnerFairnessWeights& coarser_lambda);

/// One level of the hierarchy with everything the cycles need.
struct MultigridLevel {
  FairingRegion region;
  std::unique_ptr<Construction> construction;
  /// The splits from the next coarser level (level-local ids) and their weights; empty on
  /// the base level.
  VertexSplits splits;
  std::vector<double> weights;
  /// Level-local id of every vertex of the next coarser level.
  std::vector<int> from_coarser;
};

/// Nonlinear multigrid cycles (full approximation scheme, Brandt 1977) on the levels
/// 0 .. l of a hierarchy. Beyond the paper, which only iterates each level after the
/// prolongation: on the finer levels the construction's local vertex update removes smooth
/// errors at a rate that falls like 1/#V_I (docs/DESIGN_NOTES.md).
///
/// A cycle on level l (tangential: inner fairness on; coarse problems: normal moves only):
///  1. `smoothing` iterations of the construction on level l (MultigridTuning);
///  2. the defects d = Σ_j w_ij (H_i − H_j) − τ of level l are restricted to level l−1 by
///     the transpose of the split interpolation below; with the injected positions Y_c,
///     τ_c = d_c(Y_c) − R d, and the coarse problem d_c(Y) = τ_c is solved approximately
///     (by a cycle on l−1, or on the base level by iterating until its residual fell by
///     base_reduction, at most base_iterations);
///  3. the change Y − Y_c of the coarse vertices is interpolated to the new vertices of
///     level l by the split weights, replayed in order, and added;
///  4. `smoothing` iterations again. A correction that leaves the residual above the one
///     before it is undone (and smoothing repeated without it), one whose coarse problem
///     diverges is dropped; then the level's corrections are damped and paused for a while
///     (on a noisy input some corrections are many times the error; min_correction,
///     max_skip; docs/DESIGN_NOTES.md).
/// The normal-only coarse problems correct the smooth error of the shape; the tangential
/// one is the global inner-fairness step's (inner_fairness.h); docs/DESIGN_NOTES.md.
class Multigrid {
 public:
  /// \param levels  coarsest first; kept by reference (a deque: the constructions refer to
  ///                the regions, which must not move)
  /// \param tuning  the cycles' iterations and damping
  Multigrid(std::deque<MultigridLevel>& levels, const MultigridTuning& tuning)
      : levels_(levels), tuning_(tuning) {}

  /// Cycles on level l until its residual is at most `tolerance` or level l performed
  /// `max_iterations` iterations (the coarser levels' iterations inside the cycles are not
  /// counted). Reports the iterations of level l.
  IterationReport solve(int l, Positions& X, double tolerance, int max_iterations,
                        int iteration_offset);

 private:
  void cycle(int l, Positions& X, const Eigen::VectorXd* tau, bool top, int offset);
  // Steps 2 and 3 of a cycle on level l at X: the coarse problem solved by a cycle on l−1,
  // its change interpolated to level l in D (#level×3). False where it diverged.
  bool coarse_correction(int l, const Positions& X, const Eigen::VectorXd* tau, bool top,
                         int offset, Positions& D);

  std::deque<MultigridLevel>& levels_;
  MultigridTuning tuning_;
  bool cancelled_ = false;
  int budget_ = 0;  // iterations left for level l's smoothing

  // Per level: the factor its corrections are applied with, how many cycles to run
  // without one, and how many corrections in a row were undone.
  struct CorrectionState {
    double damping = 1.0;
    int skip = 0;
    int rejections = 0;
  };
  std::vector<CorrectionState> state_;
};

}  // namespace geofair
