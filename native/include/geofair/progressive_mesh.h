// The mesh hierarchy of the multigrid construction: a progressive mesh of the fairing region
// built by half-edge collapses (Hoppe 1996; Schneider & Kobbelt 2001, section 7.4, Fig. 6).
#pragma once

#include "geofair/region.h"
#include "geofair/types.h"

#include <vector>

namespace geofair {

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

/// Number of levels picked for a region with `n_free` free vertices: the vertex count
/// grows 4× per level and the base mesh keeps at most about 250 free vertices.
int default_levels(int n_free);

/// Builds the hierarchy with OpenMesh's decimater and a priority module of our own: an edge
/// is collapsed shortest first (so the smallest edge length of the coarse mesh grows), but
/// never if a triangle around it would become distorted (quality 4√3·area / Σ edge² below
/// 0.25, or its normal turns by more than 60°), and never from a G1 boundary vertex.
/// Level ℓ keeps about n_free / 4^(levels−1−ℓ) free vertices; fewer levels come back if the
/// mesh cannot be decimated that far, or if a level would keep fewer free vertices than
/// half the G1 boundary vertices (the boundary is never coarsened, so such a level is mostly
/// thin boundary fans, on which the construction converges badly or not at all: measured
/// on a 20000-vertex cap, a base mesh of 126 free and 480 boundary vertices ends in a limit
/// cycle).
///
/// Priorities and the quality test are measured on a copy of X smoothed by
/// kHierarchySmoothing Jacobi sweeps q ← (q + Σ_j λ_ij q_j)/2 of the free vertices, the
/// inner-fairness Laplacian of section 7.3: the fairing will move the vertices that way,
/// and on a noisy input (normal noise comparable to the edge length) the raw normals make
/// the flip test meaningless — measured on the 2000-vertex cap disturbed as in the tests,
/// the unsmoothed hierarchy has 6 and 20 triangles folded over on its coarse levels.
///
/// \param X       #region×3 positions used for the priorities (the original mesh)
/// \param levels  requested number of levels, ≥ 1
/// \param lambda  inner fairness weights per ring slot of the region (inner_fairness_weights),
///                or nullptr for uniform weights
ProgressiveMesh build_progressive_mesh(const FairingRegion& region, const Positions& X, int levels,
                                       const std::vector<double>* lambda = nullptr);

/// Smoothing sweeps applied to the copy the hierarchy is measured on.
constexpr int kHierarchySmoothing = 10;

/// The fairing region of one level: its free vertices (region-local ids below n_free)
/// first, then its boundary vertices; `global` maps to region-local ids.
FairingRegion level_region(const FairingRegion& region, const Triangles& triangles);

}  // namespace geofair
