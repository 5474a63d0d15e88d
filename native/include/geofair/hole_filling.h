// Hole filling: a triangulated, refined and intrinsically faired patch per boundary loop
// (beyond the paper; its fairing with the G1 boundary of section 4 and eq. (12)).
#pragma once

#include "geofair/fairing.h"
#include "geofair/types.h"

#include <vector>

namespace geofair {

/// The boundary loops (holes) of a triangle mesh, each a cyclic list of vertex indices in
/// the direction of the missing face: loop vertex a followed by b means that the mesh has a
/// triangle with the directed edge b -> a and none with a -> b, so a triangle (a, b, c) added
/// to fill the hole is oriented like its neighbours.
///
/// Every border of the mesh is a loop, also an open mesh's outer border.
///
/// \throw InvalidInputError for invalid triangles (see fair) or a vertex on the border twice
///        (two holes touch there; fill them one at a time).
std::vector<std::vector<int>> boundary_loops(const Positions& V, const Triangles& F);

/// The most new vertices fill_holes makes (about 14 GiB for the solve at the README's
/// 6–7 KiB per free vertex); a fill estimated above it is refused.
constexpr int kMaxFillVertices = 2000000;

/// Triangulates each hole's loop, refines the patch to the edge length of its surroundings
/// and fairs it with fair(): Δ_B H = 0 on the new vertices, with the G1 boundary (or G0 with
/// options.boundary) at the loop vertices, whose normals are estimated from the faces around
/// the hole as fair() estimates them (geofair::estimate_boundary_normals).
///
/// Triangulation: Liepa's dynamic programme (Liepa 2003, "Filling holes in meshes") over the
/// loop's triangulations, by the largest dihedral angle between adjacent triangles (the
/// mesh's faces at the loop included), then the area (loops over 500 vertices: a fan to the
/// centroid); the edges across the hole are split at their midpoints (the new, free
/// vertices) and each hole's patch is remeshed isotropically (remesh_region) at
/// `target_edge_length` (0: the mean length of the loop's edges). Where that fill does not
/// converge or folds an edge and target_edge_length is 0, the holes are filled once more at
/// half the loops' edge lengths (ragged loops need a finer fill next to them) and the better
/// result is returned; its message says so. The time spent filling counts against an
/// explicit options.time_limit; phase_seconds starts with "fill".
///
/// \param loops  the holes, each a cyclic list of vertex indices along one boundary loop
///               (any start vertex, either direction); empty: every boundary loop of F,
///               an open mesh's outer border included
/// \return the result of fair() on the filled mesh: vertices (#V + k)×3 with the input's
///         rows first and bit-identical, faces (#F + l)×3 with the input's first, free true
///         exactly at the k new vertices, remeshed true (origin_face -1: the fill has no
///         input surface).
/// \throw InvalidInputError for invalid input (see fair), a loop that is not a boundary loop
///        of F (the offending pair of vertices is named), a loop given twice, a mesh
///        without a hole, a negative or non-finite target_edge_length, or a fill of more
///        than kMaxFillVertices new vertices; otherwise as fair().
FairingResult fill_holes(const Positions& V, const Triangles& F,
                         const std::vector<std::vector<int>>& loops,
                         const FairingOptions& options, double target_edge_length = 0.0);

}  // namespace geofair
