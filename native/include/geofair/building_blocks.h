// The building blocks of fair() that the library exports on their own (the Python module's
// geofair.cotangent_laplacian, intrinsic_delaunay, mean_curvature, boundary_normals,
// relax_inner_fairness and progressive_mesh): Schneider & Kobbelt 2001, sections 5–7; and
// remesh_region, the isotropic remesh of fair()'s remesh mode (beyond the paper).
#pragma once

#include "geofair/types.h"

#include <Eigen/Core>
#include <Eigen/Sparse>

#include <utility>
#include <vector>

namespace geofair {

// SparseRowMatrix, IntrinsicTriangulation, RemeshOptions and RemeshedRegion: geofair/types.h.

/// The cotangent Laplace–Beltrami matrix of a whole triangle mesh, #V×#V:
/// L_ij = w_ij = cot α_ij + cot β_ij for every edge (one cotangent on a border edge),
/// L_ii = −Σ_j L_ij. Symmetric, constants in its null space, negative semi-definite on
/// meshes without obtuse angles; (L f)_i = (2 A_i / 3) Δ_B f(q_i) with eq. (5), and S of
/// eqs. (6), (7) is −L restricted to the free rows and columns.
/// \throw InvalidInputError for invalid topology or non-finite positions.
SparseRowMatrix cotangent_laplacian(const Positions& V, const Triangles& F);

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

/// intrinsic_laplacian(V.rows(), intrinsic_delaunay(V, F)): the intrinsic Delaunay
/// cotangent Laplacian (Bobenko & Springborn 2007). Equals cotangent_laplacian(V, F) where
/// no edge is flipped. \throw InvalidInputError as intrinsic_delaunay.
SparseRowMatrix intrinsic_delaunay_laplacian(const Positions& V, const Triangles& F,
                                             int* flips = nullptr);

/// Mean curvature of every vertex of a triangle mesh (section 6).
///
/// \param V        #V×3 positions
/// \param F        #F×3 consistently oriented triangles
/// \param normals  #V×3 unit normals (the tangent planes), or nullptr to estimate them
///                 with `weighting` from the triangles (section 6; the paper's is Area)
/// \return #V mean curvatures, 1/length, H = 1/r on a sphere with outward normals;
///         0 at vertices that belong to no triangle.
/// \throw InvalidInputError for invalid topology, non-finite positions or normals.
Eigen::VectorXd mean_curvature(const Positions& V, const Triangles& F, const Positions* normals,
                               NormalWeighting weighting = NormalWeighting::Quadric);

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

/// One global tangential solve of inner fairness (section 7.3's condition linearized for all
/// free vertices at once; beyond the paper): every free vertex moves in its tangent plane
/// so that the tangential part of the inner-fairness Laplacian Σ_j λ_ij q_j − q_i vanishes,
/// the move scaled so that no edge stretches or shrinks by more than half its length
/// (TangentialSolver::relax). The vertices are not lifted back onto the surface.
///
/// \param V        #V×3 positions, mesh units
/// \param F        #F×3 consistently oriented triangles
/// \param free     #V flags, true where a vertex may move (the region, as for fair)
/// \param normals  #V×3 normals of the tangent planes, read at the region's vertices and
///                 normalized here
/// \param inner    the inner fairness weights, of the mesh as given
/// \param planes   the linearization: Turning (Newton's) or Fixed (section 7.3's)
/// \param polygon_ids  #F polygon ids or nullptr, as for fair
/// \return the positions (#V×3, free rows moved) and the scale in (0, 1] applied to the move
/// \throw InvalidInputError for invalid input (extract_region; normals of the wrong shape,
///        zero or not finite); SolverError if the system is singular or an edge has zero
///        length.
std::pair<Positions, double> relax_inner_fairness(const Positions& V, const Triangles& F,
                                                  const std::vector<bool>& free,
                                                  const Positions& normals, InnerFairness inner,
                                                  TangentPlanes planes,
                                                  const std::vector<int>* polygon_ids = nullptr);

/// The progressive-mesh hierarchy of fair()'s multigrid (section 7.4), in the input's vertex
/// ids, coarsest level first, the last being the region (the triangles with a free vertex).
/// Measured on the input smoothed by 10 sweeps of the uniform Laplacian.
///
/// \param levels  the number of levels; 0: default_levels of the region
/// \param coarsen_boundary  false: the paper's iteration's hierarchy (G1 boundary vertices
///                never collapse, kPaperDecimation); true: Newton's (kNewtonDecimation)
/// \throw InvalidInputError for invalid input (extract_region).
std::vector<Triangles> progressive_mesh_levels(const Positions& V, const Triangles& F,
                                               const std::vector<bool>& free, int levels,
                                               bool coarsen_boundary);

/// Replaces the triangles of a region (the faces with a free vertex) by an isotropic remesh
/// at edge length L (Botsch & Kobbelt 2004, "A remeshing approach to multiresolution
/// modeling", section 4; beyond Schneider & Kobbelt 2001, whose section 7.5 suggests it).
/// Each iteration splits the edges longer than 4/3 L, collapses those shorter than 4/5 L,
/// flips edges towards valence 6 (4 on the mesh border, counting the edges outside the
/// region), and moves each free vertex to the area-weighted centroid of its one-ring in its
/// tangent plane; every new or moved vertex is projected onto the closest point of the
/// input region's triangles. Fixed vertices never move and are never removed; the region's
/// border edges are never split, flipped or collapsed; a collapse that would create an edge
/// longer than 4/3 L is skipped, and so is any split, collapse, flip or relaxation step that
/// would turn a triangle over or leave it thinner than shape 0.05 (twice the area over the
/// longest edge squared) and than the triangle it replaces (a split of a longest edge: than
/// 0.45 of that), or leave a triangle without a free vertex, or put a vertex on the region's
/// border (docs/DESIGN_NOTES.md, "Remeshing the region").
///
/// \param V  #V×3 positions, mesh units, finite in the region
/// \param F  #F×3 triangles; those with a free vertex must form a consistently oriented
///           2-manifold
/// \param free  #V flags, true where a vertex may move; each free vertex surrounded by
///           triangles (not on the mesh border)
/// \throw InvalidInputError ("remesh_region: ...") for wrong sizes, an index out of range,
///        no free vertex, a free vertex in no triangle or on the mesh border, a non-finite
///        position in the region, a non-manifold or inconsistently oriented region, or
///        invalid options (iterations < 0, a non-finite target length).
RemeshedRegion remesh_region(const Positions& V, const Triangles& F,
                             const std::vector<bool>& free, const RemeshOptions& options = {});

}  // namespace geofair
