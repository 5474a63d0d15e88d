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

#include "laplace_beltrami.h"
#include "geofair/types.h"

namespace geofair {

/// Exported by geofair/building_blocks.h, which documents them and gives the defaults.
IntrinsicTriangulation intrinsic_delaunay(const Positions& V, const Triangles& F);
SparseRowMatrix intrinsic_delaunay_laplacian(const Positions& V, const Triangles& F, int* flips);

/// The cotangent Laplacian of an intrinsic triangulation, #V×#V, with the conventions of
/// cotangent_laplacian: L_ij = Σ cot of the angles opposite the edges between i and j (one
/// per adjacent triangle), L_ii = −Σ_j L_ij. Symmetric, constants in its null space; for an
/// intrinsic Delaunay triangulation every L_ij with i ≠ j is ≥ 0 (to round-off). A
/// triangle of vanishing area contributes cot = ±1e12 as in cotangent_weights.
SparseRowMatrix intrinsic_laplacian(int n_vertices, const IntrinsicTriangulation& T);


}  // namespace geofair
