// Hole filling: a triangulated, refined and intrinsically faired patch per boundary loop
// (beyond the paper; its fairing with the G1 boundary of section 4 and eq. (12)).
#pragma once

#include "geofair/fairing.h"
#include "geofair/types.h"

#include <string>
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

/// A connected part's boundary loop of the largest spanned area is its outer border where
/// it spans at least this fraction of the area of the part's triangles
/// (HoleRule::keep_outer_borders).
constexpr double kOuterBorderArea = 0.3;

/// Which boundary loops are holes when fill_holes is given none (holes_to_fill).
struct HoleRule {
  /// Leave the outer borders of open surfaces open: in each connected part of the mesh, the
  /// boundary loop of the largest spanned area |½ Σ_i (p_i − c) × (p_{i+1} − c)| (its
  /// vertices p_i about their centroid c), where that area is at least kOuterBorderArea
  /// times the area of the part's triangles. A sheet's border spans about the sheet's own
  /// area (a height field's: its area projected on the plane), a hole in a closed surface a
  /// small part of it: a sphere missing a cap of polar angle θ spans (1 − cos θ)/2 of the
  /// rest, below 30 % up to θ = 66° (30 % of the sphere cut away). A part has at most one
  /// outer border: a hole in a sheet is filled whatever its size, and of an open tube's
  /// two ends the larger one stays open if it spans 30 % (a ring), else neither.
  /// false: every boundary loop is a hole.
  bool keep_outer_borders = true;
  /// Leave loops of more edges than this open (Blender's Fill Holes' Sides, MeshLab's Close
  /// Holes' maximum size); 0: no limit.
  int max_hole_edges = 0;
};

/// A boundary loop that holes_to_fill leaves open, and why.
struct OpenLoop {
  std::vector<int> loop;  ///< as boundary_loops returns it
  /// One clause for a user, e.g. "an outer border: it spans 95 % of the area of its part's
  /// triangles (a hole less than 30 %)".
  std::string reason;
};

/// The boundary loops of a mesh split by a HoleRule.
struct HoleChoice {
  std::vector<std::vector<int>> holes;  ///< the loops to fill, in boundary_loops' order
  std::vector<OpenLoop> left_open;      ///< the others, in the same order
};

/// The holes that fill_holes fills when it is given no loops: the boundary loops of
/// boundary_loops(V, F) that `rule` does not leave open (see HoleRule), and those it does
/// with the reason. Scale-invariant (measured in units of the mesh's size, working_scale).
/// 	hrow InvalidInputError as boundary_loops, for a negative rule.max_hole_edges, or a mesh
///        whose squared lengths overflow or underflow (see fill_holes).
HoleChoice holes_to_fill(const Positions& V, const Triangles& F, const HoleRule& rule = {});

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
/// Positions are worked on in units of the mesh's own size (divided by a power of two where
/// the mean edge length lies outside [2^-32, 2^32], exactly), so a mesh scaled by any factor
/// whose squared lengths stay finite, normal doubles is filled with the same surface up to
/// that factor; fair() does the same.
///
/// \param loops  the holes, each a cyclic list of vertex indices along one boundary loop
///               (any start vertex, either direction); empty: holes_to_fill(V, F, rule),
///               the boundary loops that `rule` does not leave open (by default every loop
///               but the outer borders of open surfaces; the result's message names how
///               many were left open)
/// \param rule   which loops are holes where `loops` is empty (HoleRule); not read otherwise
/// \return the result of fair() on the filled mesh: vertices (#V + k)×3 with the input's
///         rows first and bit-identical, faces (#F + l)×3 with the input's first, free true
///         exactly at the k new vertices, remeshed true (origin_face -1: the fill has no
///         input surface).
/// \throw InvalidInputError for invalid input (see fair), a loop that is not a boundary loop
///        of F (the offending pair of vertices is named), a loop given twice, a mesh
///        without a hole to fill (no boundary loop, or `rule` leaves every one open: the
///        message says why), a negative or non-finite target_edge_length, a negative
///        rule.max_hole_edges, a mesh whose squared bounding-box diagonal overflows (above
///        about 1.3e154) or whose squared mean edge length underflows (below about
///        1.5e-154; the message names the size), or a fill of more than kMaxFillVertices
///        new vertices; otherwise as fair().
FairingResult fill_holes(const Positions& V, const Triangles& F,
                         const std::vector<std::vector<int>>& loops,
                         const FairingOptions& options, double target_edge_length = 0.0,
                         const HoleRule& rule = {});

}  // namespace geofair
