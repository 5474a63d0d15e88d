// Intrinsic Delaunay triangulation of a triangle mesh by intrinsic edge flips, and its
// cotangent Laplacian, whose weights are never negative.
//
// Bobenko & Springborn 2007, "A discrete Laplace–Beltrami operator for simplicial
// surfaces" (DCG 38); Fisher, Springborn, Schröder & Bobenko 2006, "An algorithm for the
// construction of intrinsic Delaunay triangulations with applications to digital geometry
// processing"; Sharp, Soliman & Crane 2019, "Navigating intrinsic triangulations".
//
// Beyond Schneider & Kobbelt 2001: the cotangent weights of eq. (5) are negative across
// edges whose two opposite angles sum to more than π (obtuse and needle triangles). The
// intrinsic Delaunay triangulation has the same vertices and the same metric (the surface
// is not moved) but other edges — geodesics of the piecewise-flat surface — chosen so that
// every edge satisfies α + β ≤ π; its cotangent Laplacian then has non-negative weights
// (a discrete maximum principle), stays positive semi-definite, and keeps the linear
// precision of the original on flat regions (Bobenko & Springborn 2007).
#pragma once

#include "geofair/laplace_beltrami.h"
#include "geofair/types.h"

namespace geofair {

/// An intrinsic triangulation on the vertices of a mesh.
struct IntrinsicTriangulation {
  /// #T×3 vertex indices, counter-clockwise as the input. An intrinsic triangle may repeat
  /// a vertex and two triangles may share two vertices twice (not a simplicial complex).
  Triangles triangles;
  /// #T×3 edge lengths: lengths(t, k) is the length of the edge from corner k to corner
  /// k+1 (mod 3) of triangle t, in mesh units, measured along the input surface.
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> lengths;
  /// Number of edge flips performed (0: the input was intrinsically Delaunay).
  int flips = 0;
};

/// Intrinsic Delaunay triangulation of (V, F) by the flip algorithm: every interior edge
/// whose opposite angles α, β satisfy cot α + cot β < −1e-12 (i.e. α + β > π) is flipped
/// in the intrinsic metric of its two triangles (their layout in the plane) until none is
/// left. Border edges are never flipped. Terminates on every mesh (Bobenko & Springborn
/// 2007); O(#flips) work after the O(#F) setup.
/// \throw SolverError if round-off made the flips cycle (more than 100·#F + 1000 flips).
///
/// \param V  #V×3 positions, mesh units
/// \param F  #F×3 consistently oriented manifold triangles
/// \throw InvalidInputError for non-finite positions or invalid topology (out-of-range
///        index, repeated vertex, non-manifold or inconsistently oriented edge).
IntrinsicTriangulation intrinsic_delaunay(const Positions& V, const Triangles& F);

/// The cotangent Laplacian of an intrinsic triangulation, #V×#V, with the conventions of
/// cotangent_laplacian: L_ij = Σ cot of the angles opposite the edges between i and j (one
/// per adjacent triangle), L_ii = −Σ_j L_ij. Symmetric, constants in its null space; for an
/// intrinsic Delaunay triangulation every L_ij with i ≠ j is ≥ 0 (to round-off). A
/// triangle of vanishing area contributes cot = ±1e12 as in cotangent_weights.
SparseRowMatrix intrinsic_laplacian(int n_vertices, const IntrinsicTriangulation& T);

/// intrinsic_laplacian(V.rows(), intrinsic_delaunay(V, F)): the intrinsic Delaunay
/// cotangent Laplacian (Bobenko & Springborn 2007). Equals cotangent_laplacian(V, F) where
/// no edge is flipped. \throw InvalidInputError as intrinsic_delaunay.
SparseRowMatrix intrinsic_delaunay_laplacian(const Positions& V, const Triangles& F,
                                             int* flips = nullptr);

}  // namespace geofair
