// Mesh connectivity as ordered one-rings, and the fairing region with its G1 boundary.
//
// Schneider & Kobbelt 2001, section 4: V_I are the free (inner) vertices, V_B the fixed
// vertices next to them; N(q_i) is the one-ring, D(q_i) the one-disk.
#pragma once

#include "geofair/types.h"

#include <cstdint>
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
  int prev_slot(int i, int k) const { return k > offset[i] ? k - 1 : offset[i + 1] - 1; }
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
  Positions g1_normals;     ///< (n - n_free)×3 prescribed unit normals of V_B
  /// Per ring slot of `rings` (empty: no polygons given): 1 where the edge from the vertex
  /// to that neighbour is a diagonal of one of the caller's polygons (both its triangles
  /// were tessellated from the same polygon, extract_region's polygon_ids), 0 where it is
  /// an edge of the polygon mesh.
  std::vector<std::uint8_t> polygon_diagonal;
};

/// How the normal of a G1 boundary vertex is estimated from the surface around the region.
enum class BoundaryNormalEstimate {
  /// Tangent plane of a least-squares quadric through the surrounding fixed vertices (see
  /// estimate_boundary_normals): error O(h²) on a smooth surface. The default.
  Quadric,
  /// Area-weighted normal of the surrounding triangles: one-sided, tilted by about half a
  /// ring's angle, error O(h). The estimate of earlier releases; the quadric's fallback.
  Area,
};

/// Unit normals of the G1 boundary vertices estimated from the surrounding surface.
///
/// The G1 boundary is the set of fixed vertices that share a triangle with a free vertex;
/// the *surrounding triangles* of a vertex are its triangles without a free vertex (the
/// fixed surface around the region: free vertices' positions never enter, since fairing
/// replaces them).
///
/// Quadric (beyond the paper): n0 = the area-weighted normal of the surrounding triangles
/// (one-sided: error O(h) for edge length h). The samples are the fixed vertices within two
/// rings reached through surrounding triangles (the vertices of the surrounding triangles at
/// the vertex, and of the triangles without a free vertex at those). In the frame of n0,
/// with the vertex q at the origin and lengths in units of the samples' rms distance, the
/// heights z = ⟨p − q, n0⟩ of the samples p at tangent coordinates (x, y) are fitted by the
/// paraboloid z = a x + b y + c x² + d xy + e y² through q (least squares, each equation
/// weighted by 1/|p − q|²); the normal is that of the fitted plane, (n0 − a b_x − b b_y)/|…|,
/// and the fit is repeated once in that normal's frame. Taylor's theorem makes the error
/// O(h²) on a smooth surface wherever the samples determine the five coefficients
/// (tests/test_boundary_normals.py asserts the order on spheres and cylinders). Falls back to n0 where the
/// fit is ill-conditioned: fewer than 6 samples, a sample that is not finite, a condition
/// number above 1e6 of the column-equilibrated 5×5 normal equations (for instance all
/// samples on two straight rows, where y and y² cannot be told apart), a fitted plane
/// tilted by 45° or more against the frame's, or a result facing away from n0.
///
/// Sign: oriented like the faces (positive dot product with n0, whose triangles are
/// counter-clockwise seen from the normal side). Dimensionless unit vectors.
///
/// \param V        #V×3 positions, mesh units
/// \param F        #F×3 consistently oriented triangles
/// \param free     #V flags, true where a vertex may move
/// \param method   Quadric (default) or Area
/// \param caller   function name used at the start of error messages
/// \return #V×3: unit normals at G1 boundary vertices; zero rows at every other vertex and
///         at G1 boundary vertices without a surrounding triangle (the region reaches the
///         mesh border there) or whose surrounding triangles are all degenerate; a row is
///         not finite where a vertex of the surrounding triangles is not.
/// \throw InvalidInputError if free has the wrong size or a triangle index is out of range.
Positions estimate_boundary_normals(const Positions& V, const Triangles& F,
                                    const std::vector<bool>& free,
                                    BoundaryNormalEstimate method = BoundaryNormalEstimate::Quadric,
                                    const char* caller = "boundary_normals");

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
/// \throw InvalidInputError if no vertex is free, a free vertex is in no triangle or on
///        the mesh border, a boundary normal is missing (no surrounding triangle), zero,
///        not unit length (|1-|n|| > 1e-6), not finite or pointing against the surface's
///        orientation, or the topology is invalid; if polygon_ids has not #F entries.
FairingRegion extract_region(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                             const Positions* boundary_normals, bool check_orientation = true,
                             const std::vector<int>* polygon_ids = nullptr);

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

}  // namespace geofair
