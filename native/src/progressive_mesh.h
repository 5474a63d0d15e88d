// The mesh hierarchy of the multigrid construction: a progressive mesh of the fairing region
// built by half-edge collapses (Hoppe 1996; Schneider & Kobbelt 2001, section 7.4, Fig. 6).
#pragma once

#include "region.h"
#include "geofair/types.h"

#include <vector>

namespace geofair {

struct InnerFairnessWeights;  // inner_fairness.h

/// Vertex splits in flat arrays: split s re-inserts vertex[s] (region-local id) with the
/// one-ring ring[offset[s] .. offset[s+1]) it had before it was collapsed, in order
/// around it (that ring exists when the split is replayed).
struct VertexSplits {
  std::vector<int> vertex;
  std::vector<int> offset{0};
  std::vector<int> ring;
  std::size_t size() const { return vertex.size(); }
};

/// Nested meshes of a fairing region, coarsest first. The vertex set of each level is a
/// subset of the next (half-edge collapses never move a vertex); G1 boundary vertices are
/// never collapsed, so every level has the full boundary.
struct ProgressiveMesh {
  /// Per level: triangles in region-local vertex ids.
  std::vector<Triangles> triangles;
  /// Per level ≥ 1: the vertex splits that turn the previous level into this one, in
  /// replay order (the reverse of the collapse order). Level 0: none.
  std::vector<VertexSplits> splits;
};

/// Number of levels picked for a region with `n_free` free vertices (the paper's iteration):
/// one level up to 1000 free vertices, where a single level converges within a few thousand
/// iterations (docs/DESIGN_NOTES.md); above, the vertex count grows 4× per level and the base
/// mesh keeps at most about 250 free vertices.
int default_levels(int n_free);

/// The copy of X (#region×3) the hierarchy is measured on: `sweeps` Jacobi sweeps
/// q ← (q + Σ_j λ_ij q_j)/2 of the free vertices with the inner-fairness weights λ
/// (inner_fairness_weights of the region; nullptr: uniform). The fairing moves the vertices that way, and on a
/// noisy input (normal noise comparable to the edge length) the raw positions make the
/// quality and flip tests meaningless and fold coarse triangles (docs/DESIGN_NOTES.md).
Positions hierarchy_positions(const FairingRegion& region, const Positions& X,
                              const InnerFairnessWeights* lambda,
                              int sweeps = HierarchyTuning{}.smoothing);

/// The rules of build_progressive_mesh's collapses.
struct Decimation {
  /// G1 boundary vertices collapse too, along the region's border (see
  /// build_progressive_mesh); else they are never collapsed.
  bool coarsen_boundary = false;
  /// The valence range that collapses keep at free vertices.
  int min_valence = 5, max_valence = 8;
  /// Free vertices of valence below 5 collapse first (their priority is scaled by 1e-4).
  bool low_valence_first = false;
  /// A collapse is refused if a triangle around it would end below this quality
  /// 4√3·area / Σ edge² (dimensionless, in (0, 1]: 1 equilateral; 0.25 admits angles up to
  /// about 155°, 0.4 up to about 140°).
  double min_quality = 0.25;
};

/// The hierarchy of the paper's iteration (Paper): the boundary locked, valences 5..8.
constexpr Decimation kPaperDecimation{};

/// The hierarchy of Newton's method on the levels (nested_iteration.cpp; beyond the paper): the
/// boundary coarsened (a locked boundary joins a dense boundary to a sparse interior by
/// fans of long triangles), free valences 4..10, valences 3 and 4 collapsed first (they
/// hold the largest defects after a prolongation when they survive into coarse levels);
/// docs/DESIGN_NOTES.md. Triangles of quality 0.4 at least: the obtuse triangles of a
/// decimated regular mesh left its coarse Newton systems near singular (docs/REAL_MESHES.md,
/// "Regular caps").
constexpr Decimation kNewtonDecimation{true, 4, 10, true, 0.4};

/// Builds the hierarchy with OpenMesh's decimater and a priority module of our own: an edge
/// is collapsed shortest first (so the smallest edge length of the coarse mesh grows), but
/// never if a triangle around it would become distorted (quality 4√3·area / Σ edge² below
/// rules.min_quality, or its normal turns by more than 60°), never from a G1 boundary vertex
/// (but see rules.coarsen_boundary below), and never
/// if a free vertex would end with a valence outside [rules.min_valence, rules.max_valence].
/// Level ℓ keeps about n_free / 4^(levels−1−ℓ) free vertices, but at least
/// tuning.min_free_per_boundary times as many as there are G1 boundary vertices (the
/// coarsest level is clamped to that, and fewer levels come back if that leaves nothing to
/// coarsen or the mesh cannot be decimated that far).
///
/// Why the two limits: a base mesh of mostly thin boundary fans ends the construction in a
/// limit cycle, and at coarse vertices of valence 3 and 4 the spiral-sample estimate of H is
/// far off, so the multigrid cycles stall (docs/DESIGN_NOTES.md).
///
/// With rules.coarsen_boundary (kNewtonDecimation) the G1 boundary is coarsened too: a
/// boundary vertex may collapse along the region's border into its neighbour on the same
/// border loop (never a fixed vertex inside the region, whose fan is closed, and no loop
/// below tuning.min_boundary_loop vertices), and level ℓ keeps about #region / 4^(levels−1−ℓ)
/// vertices in all, without the floor above (fewer levels come back if a level would keep
/// fewer than tuning.min_level_free free vertices). The kept boundary vertices keep their
/// positions and G1 normals, so every level is a coarser discretization of the same
/// boundary-value problem, with edges of one length up to the border.
///
/// \param X       #region×3 positions to measure on (hierarchy_positions of the input)
/// \param levels  requested number of levels, ≥ 1
/// \param rules   kPaperDecimation or kNewtonDecimation
/// \param tuning  the levels' floors (HierarchyTuning)
ProgressiveMesh build_progressive_mesh(const FairingRegion& region, const Positions& X,
                                       int levels, const Decimation& rules = kPaperDecimation,
                                       const HierarchyTuning& tuning = {});

/// The fairing region of one level: its free vertices (region-local ids below n_free)
/// first, then its boundary vertices; `global` maps to region-local ids.
FairingRegion level_region(const FairingRegion& region, const Triangles& triangles);

}  // namespace geofair
