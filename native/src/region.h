// Mesh connectivity as ordered one-rings, and the fairing region with its G1 boundary.
//
// Schneider & Kobbelt 2001, section 4: V_I are the free (inner) vertices, V_B the fixed
// vertices next to them; N(q_i) is the one-ring, D(q_i) the one-disk.
#pragma once

#include "geofair/types.h"

#include <cstdint>
#include <string>
#include <vector>

namespace geofair {

/// Ordered one-rings of a triangle mesh, in flat (CSR) arrays for the inner loops.
///
/// For vertex i the neighbours are ring[offset[i] .. offset[i+1]), counter-clockwise
/// around the vertex normal. Slot k (a global index into ring) with successor k+1 (cyclic
/// within the vertex) spans the triangle (i, ring[k], ring[k+1]) iff has_face[k] != 0.
/// A closed fan has every has_face set; a vertex on the mesh border has one gap per
/// border fan. across[k] is the third vertex of the other triangle at edge
/// (ring[k], ring[k+1]), or -1 if that edge is on the border.
struct OneRings {
  std::vector<int> offset;        ///< #V+1
  std::vector<int> ring;          ///< neighbour vertex ids
  std::vector<std::uint8_t> has_face;  ///< per slot: triangle (i, ring[k], next) exists
  std::vector<int> across;        ///< per slot: opposite vertex across edge (ring[k], next)

  int valence(int i) const { return offset[i + 1] - offset[i]; }
  /// The slot after k around the same vertex i (cyclic).
  int next_slot(int i, int k) const { return k + 1 < offset[i + 1] ? k + 1 : offset[i]; }
  /// True if the fan of i is closed (i is not on the mesh border).
  bool closed(int i) const;
  /// Mean distance from vertex i, at q, to its ring neighbours in X (#V×3), mesh units: the
  /// local mesh size h that step limits and finite-difference steps are measured in.
  double mean_neighbour_distance(const Positions& X, int i, const Vec3& q) const {
    double sum = 0.0;
    for (int k = offset[i]; k < offset[i + 1]; ++k)
      sum += (X.row(ring[k]).transpose() - q).norm();
    return sum / valence(i);
  }
  double mean_neighbour_distance(const Positions& X, int i) const {
    return mean_neighbour_distance(X, i, X.row(i).transpose());
  }
};

/// Builds the one-rings of a triangle mesh with OpenMesh.
///
/// \param n_vertices  number of vertices #V (vertices in no triangle get an empty ring)
/// \param triangles   #F×3 vertex indices in [0, #V), consistently oriented
/// \param caller      function name used at the start of error messages
/// \param triangle_ids optional #F original triangle indices, used in error messages
/// \throw InvalidInputError for an index out of range, a triangle with a repeated vertex,
///        a non-manifold edge or an orientation that disagrees with a neighbour (the
///        offending triangle index is named).
OneRings build_one_rings(int n_vertices, const Triangles& triangles, const char* caller,
                         const std::vector<int>* triangle_ids = nullptr);

/// The checks of build_one_rings alone, without building the rings.
/// \throw InvalidInputError as build_one_rings, with the same message.
void check_triangles(int n_vertices, const Triangles& triangles, const char* caller);

/// That `free` has a flag per row of V and every index of F is a row of V.
/// \throw InvalidInputError naming `caller`, the size or the first index out of range
void check_indices(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const char* caller);

/// That every vertex a triangle of F uses has finite coordinates (also far from a region:
/// fair() returns its position).
/// \throw InvalidInputError naming `caller` and the first such vertex
void check_finite(const Positions& V, const Triangles& F, const char* caller);

/// The part of a mesh that fairing works on.
///
/// Local vertex ids: [0, n_free) are the free vertices V_I, [n_free, n) the G1 boundary
/// V_B (fixed vertices that share a triangle with a free vertex). The region's triangles
/// are those with at least one free vertex.
struct FairingRegion {
  int n_free = 0;
  int n = 0;
  std::vector<int> global;  ///< local -> index in the caller's mesh
  OneRings rings;           ///< one-rings within the region's triangles (local ids)
  Triangles triangles;      ///< region triangles (local ids)
  /// (n - n_free)×3 unit normals of V_B: with G1 the prescribed ones; with G0 the
  /// one-sided normals of the region's own triangles at the input, only a start for the
  /// tangent planes that spiral samples and prolongations read (the construction
  /// re-estimates them from the current positions), no boundary condition.
  Positions g1_normals;
  /// G1: positions and g1_normals prescribed; G0: positions only, H = 0 on V_B.
  BoundaryCondition boundary = BoundaryCondition::G1;
  /// Per ring slot of `rings` (empty: no polygons given): 1 where the edge from the vertex
  /// to that neighbour is a diagonal of one of the caller's polygons (both its triangles
  /// were tessellated from the same polygon, extract_region's polygon_ids), 0 where it is
  /// an edge of the polygon mesh.
  std::vector<std::uint8_t> polygon_diagonal;
};


/// Extracts the fairing region of a mesh.
///
/// \param V        #V×3 positions (only checked for finiteness where used)
/// \param F        #F×3 consistently oriented triangles
/// \param free     #V flags, true where a vertex may move
/// \param boundary_normals  #V×3 prescribed unit normals, read at G1 boundary vertices
///        only; nullptr: estimate_boundary_normals (Quadric) of the surrounding surface.
/// \param check_orientation  if true (default), a prescribed normal whose dot product with
///        the estimate of estimate_boundary_normals is negative is an error (the normals or
///        the faces are flipped); vertices without an estimate are not checked. False for
///        callers that pass placeholder normals (the hierarchy alone).
/// \param polygon_ids  #F polygon of the caller's mesh each triangle was tessellated from
///        (Blender's loop triangles' polygon_index), or nullptr: fills
///        region.polygon_diagonal. An edge is a diagonal where its two triangles carry the
///        same id.
/// \param boundary  G0: boundary_normals is not read and nothing is estimated from the
///        surrounding surface (the region may reach the mesh border); see g1_normals.
/// \throw InvalidInputError if no vertex is free, a free vertex is in no triangle or on
///        the mesh border, a boundary normal is missing (no surrounding triangle), zero,
///        not unit length (|1-|n|| > 1e-6), not finite or pointing against the surface's
///        orientation, or the topology is invalid; if polygon_ids has not #F entries.
FairingRegion extract_region(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                             const Positions* boundary_normals, bool check_orientation = true,
                             const std::vector<int>* polygon_ids = nullptr,
                             BoundaryCondition boundary = BoundaryCondition::G1);

/// Exported by geofair/building_blocks.h, which documents it and gives the defaults.
Positions estimate_boundary_normals(const Positions& V, const Triangles& F,
                                    const std::vector<bool>& free, BoundaryNormalEstimate method,
                                    const char* caller);

/// The boundary normals of `region` (extracted from V, F, free) for new positions V of its
/// vertices (LiveFairing, same mesh): G1 normals as extract_region sets them (the given ones
/// checked against the surface's orientation, or the estimate of the surrounding surface),
/// with G0 the one-sided normals of the region's triangles. Messages start with `caller`.
/// \throw InvalidInputError as extract_region for the normals.
void set_boundary_normals(FairingRegion& region, const Positions& V, const Triangles& F,
                          const std::vector<bool>& free, const Positions* boundary_normals,
                          const char* caller);

/// Folded edges of a result (beyond the paper): edges with a free endpoint whose two
/// triangles face apart (the cross products of their edges have a negative dot product).
struct FoldCount {
  int folds = 0;      ///< such edges in `after`
  int new_folds = 0;  ///< those of them whose triangles did not face apart in `before`
};

/// Counts the folded edges of `after` and those that are new against `before`. A converged
/// solve can flip triangles over where the surface turns faster than the mesh resolves, or
/// keep folds of a folded input (docs/REAL_MESHES.md); fair reports both.
///
/// \param before, after  #V×3 positions of one mesh, mesh units
/// \param F       #F×3 consistently oriented triangles (edges in more than two are skipped)
/// \param free    #V flags, true where a vertex may move
/// \pre the indices of F are in [0, #V) and before, after and free have #V rows (fair has
///      checked them); nothing is raised. Degenerate triangles (zero normal) never fold.
FoldCount count_folds(const Positions& before, const Positions& after, const Triangles& F,
                      const std::vector<bool>& free);

/// What a result's message says of its folds ("; 3 edges fold over ..."); empty where none.
std::string fold_note(const FoldCount& folds);

}  // namespace geofair
