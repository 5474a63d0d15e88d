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

// kOuterBorderArea, HoleRule, OpenLoop and HoleChoice (holes_to_fill's): geofair/types.h.

/// The holes that fill_holes fills when it is given no loops: the boundary loops of
/// boundary_loops(V, F) that `rule` does not leave open (see HoleRule), and those it does
/// with the reason. A piece of border that passes more than once through a vertex (holes
/// that touch there, which boundary_loops refuses) is left open as "not a simple loop",
/// its vertices sorted in place of a loop: give its loops to fill_holes one at a time.
/// Scale-invariant (measured in units of the mesh's size, working_scale).
/// \throw InvalidInputError for invalid triangles (see fair), a negative
///        rule.max_hole_edges, or a mesh whose squared lengths overflow or underflow (see
///        fill_holes).
HoleChoice holes_to_fill(const Positions& V, const Triangles& F, const HoleRule& rule = {});

/// The most new vertices fill_holes makes (about 14 GiB for the solve at the README's
/// 6–7 KiB per free vertex); a fill estimated above it is refused.
constexpr int kMaxFillVertices = 2000000;

/// Rim::Trim removes the triangles at a loop vertex whose triangles span less than this
/// angle there (radians; a spike into the hole, whose fill folds over it: docs/DESIGN_NOTES.md,
/// "Filling holes").
constexpr double kTrimSpikeAngle = 1.5707963267948966;  // 90°
/// The most rounds of Rim::Trim's teeth and spikes, each removing the current loop's (run
/// again after each round of kFoldTrimRounds).
constexpr int kTrimRounds = 3;
/// The most rounds of Rim::Trim's second kind: the input triangles that fold against the
/// last fill (share a folded edge with it) removed and the hole filled again.
constexpr int kFoldTrimRounds = 3;

/// fill_holes tries a hole at half its loop's edge length (FillMethod::IntrinsicFiner) only
/// where its first fill has at most this many new vertices: the finer fill has four times as
/// many, and on bench/holes.py it mended holes of 100 and 1,000 vertices, never one of
/// 10,000, whose two fills outlasted the benchmark's 120 s (docs/DESIGN_NOTES.md).
constexpr int kMaxFinerFillVertices = 5000;

/// What fill_holes may do to the input's triangles at a hole's loop.
enum class Rim {
  Keep,  ///< every input face stays as it is (the library's default)
  /// Where the fill of the loop as it is folds or does not converge, the rim may be trimmed
  /// first: teeth (triangles with two loop edges) and the triangles at loop vertices whose
  /// own side spans less than kTrimSpikeAngle are removed, kTrimRounds rounds at most, as
  /// long as the hole stays one simple loop (MeshFix's remove-and-fill, Attene 2010); where
  /// the fill still folds, the input triangles that fold against it (kFoldTrimRounds rounds
  /// at most, each with the teeth and spikes it uncovers). At most as many faces as the
  /// loop has vertices are removed.
  Trim,
};

/// How a hole was filled (HoleFill::method), in the order fill_holes tries them, except that
/// IntrinsicTrimmed goes before IntrinsicFiner. With options.boundary G0 the first fill is G0,
/// and IntrinsicFiner and IntrinsicTrimmed are G0 fills too.
enum class FillMethod {
  Intrinsic,         ///< the G1 intrinsic fill at the loop's edge length (options.boundary)
  IntrinsicFiner,    ///< the same at half the loop's edge length
  IntrinsicTrimmed,  ///< the same after the rim was trimmed (Rim::Trim)
  G0,                ///< positions only at the loop: the minimal surface, H = 0
  Linear,            ///< the linear Δ²f = 0 fill of the same patch (section 7.4's initial
                     ///< mesh; CGAL's triangulate_refine_and_fair_hole's kind of fill)
  None,              ///< left open (HoleFill::reason says why)
};

/// "intrinsic", "intrinsic_finer", "intrinsic_trimmed", "g0", "linear" or "none".
const char* fill_method_name(FillMethod method);

/// One fill tried for a hole (HoleFill::attempts).
struct FillAttempt {
  FillMethod method = FillMethod::None;
  bool converged = false;
  int folds = 0;         ///< folded edges of the fill (see HoleFill::folds)
  double seconds = 0.0;  ///< wall-clock time of the attempt
  std::string message;   ///< fair()'s message, or why the attempt was not made
};

/// What fill_holes did with one hole.
struct HoleFill {
  std::vector<int> loop;  ///< the hole's loop (input vertex indices, as boundary_loops orders it)
  FillMethod method = FillMethod::None;  ///< the fill kept; None: left open
  bool converged = false;                ///< the kept fill's fair() converged
  /// Folded edges of the kept fill: edges of its triangles, among them and with the input's
  /// triangles at the loop, whose two triangles' normals have a non-positive dot product.
  int folds = 0;
  double residual = 0.0;           ///< the kept fill's normalized residual (see fair)
  int new_vertices = 0, new_faces = 0;
  std::vector<int> removed_faces;  ///< input face indices removed at the rim (Rim::Trim), sorted
  std::vector<FillAttempt> attempts;  ///< every fill tried, in order
  /// Left open: why, one clause for a user; filled: empty.
  std::string reason;
};

/// fill_holes' result: fair()'s fields for the whole filled mesh, and one record per hole.
struct FillResult : FairingResult {
  /// The holes in the order of the loops (given, or holes_to_fill's), then the boundary
  /// loops that holes_to_fill's rule left open (method None, with the reason).
  std::vector<HoleFill> holes;
  std::vector<int> removed_faces;  ///< the union of the holes' removed_faces, sorted
};

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
/// `target_edge_length` (0: the mean length of the loop's edges).
///
/// Every hole gets a fill: each is filled and faired on its own (its patch and the input's
/// triangles within three rings of its loop, which hold everything the G1 normals are
/// estimated from), trying in turn (FillMethod) the intrinsic fill, with rim = Trim the same
/// on the trimmed rim (where it has something to trim) and on the rim trimmed of the input
/// triangles that fold against the last fill (Rim::Trim), the intrinsic fill at half the
/// loop's edge length (on the input's rim, then on the trimmed one at half its own loop's;
/// only where target_edge_length is 0 and the first fill has at most kMaxFinerFillVertices
/// new vertices), then G0 and the linear Δ²f = 0 fill (both on the last trimmed rim where
/// it was trimmed), each with max_iterations at most
/// SolverTuning::schedule.fill_max_iterations, and keeps the first that converges without a
/// folded edge, else the one with the fewest folded edges (converged first among equals,
/// then the earlier). HoleFill records which; result.message sums it up. A hole is left
/// open only where no fill can be made: one over kMaxFillVertices (its reason says so; if
/// no hole can be filled at all, InvalidInputError). The time spent counts against an explicit options.time_limit (and
/// options.deadline); once it is spent, the holes not yet filled get the linear fill alone.
/// phase_seconds starts with "fill" (triangulations and remeshes), then fair()'s phases
/// summed over the holes.
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
/// \param rim    Keep (default) or Trim (see Rim)
/// \return vertices (#V + k)×3 with the input's rows first and bit-identical (with Trim,
///         rows whose every face was removed stay, listed in `unreferenced`); faces: the
///         input's (without removed_faces, in their order) first, then each hole's fill in
///         the order of `holes`; free true exactly at the k new vertices; remeshed true
///         (origin_face -1: the fill has no input surface); converged: every fill converged;
///         residual the largest; folds, new_folds the fills' folded edges (HoleFill::folds)
///         summed; iterations and newton_iterations summed.
/// \throw InvalidInputError for invalid input (see fair), a loop that is not a boundary loop
///        of F (the offending pair of vertices is named), a loop given twice, a mesh
///        without a hole to fill (no boundary loop, or `rule` leaves every one open: the
///        message says why), a negative or non-finite target_edge_length, a negative
///        rule.max_hole_edges, a mesh whose squared bounding-box diagonal overflows (above
///        about 1.3e154) or whose squared mean edge length underflows (below about
///        1.5e-154; the message names the size), or no hole that can be filled under
///        kMaxFillVertices new vertices; otherwise as fair().
FillResult fill_holes(const Positions& V, const Triangles& F,
                      const std::vector<std::vector<int>>& loops, const FairingOptions& options,
                      double target_edge_length = 0.0, const HoleRule& rule = {},
                      Rim rim = Rim::Keep);

}  // namespace geofair
