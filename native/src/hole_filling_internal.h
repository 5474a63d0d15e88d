// The steps of fill_holes (geofair/hole_filling.h), for the library and its unit tests.
#pragma once

#include "geofair/types.h"

#include <cstdint>
#include <string>
#include <vector>

namespace geofair::hole_filling {

/// Validates the triangles (indices, manifold, orientation) and the coordinates they use.
/// \throw InvalidInputError naming `caller`.
void check_mesh(const Positions& V, const Triangles& F, const char* caller);

/// The (unnormalized) normal of triangle (a, b, c): twice its vector area.
inline Vec3 triangle_normal(const Positions& V, int a, int b, int c) {
  return (V.row(b) - V.row(a)).cross(V.row(c) - V.row(a)).transpose();
}

/// The directed edges (a, b) of a mesh's triangles, each with its triangle, grouped by
/// their first vertex (compressed rows: one pass over the triangles, no hashing, so that a
/// small hole in a mesh of millions of triangles costs little). F must be valid
/// (indices >= 0, each directed edge in one triangle: a consistently oriented manifold).
class DirectedEdges {
 public:
  explicit DirectedEdges(const Triangles& F);
  /// The third vertex of the triangle with the directed edge a -> b, or -1.
  int third(int a, int b) const {
    const int k = slot(a, b);
    return k < 0 ? -1 : third_[k];
  }
  bool has(int a, int b) const { return slot(a, b) >= 0; }
  /// The triangle (row of F) with the directed edge a -> b, or -1.
  int triangle(int a, int b) const {
    const int k = slot(a, b);
    return k < 0 ? -1 : triangle_[k];
  }
  /// Calls f(t) for each triangle t (a row of F) with a corner at vertex v.
  template <class Function>
  void for_each_triangle_at(int v, Function f) const {
    if (v < 0 || v + 1 >= int(offset_.size())) return;
    for (int k = offset_[v]; k < offset_[v + 1]; ++k) f(triangle_[k]);
  }
  /// Calls f(a, b) for each directed edge whose reverse is not an edge (a border edge).
  template <class Function>
  void for_each_border_edge(Function f) const {
    for (int a = 0; a + 1 < int(offset_.size()); ++a)
      for (int k = offset_[a]; k < offset_[a + 1]; ++k)
        if (!has(to_[k], a)) f(a, to_[k]);
  }

 private:
  // The slot of edge a -> b in to_, third_ and triangle_, or -1.
  int slot(int a, int b) const {
    if (a < 0 || a + 1 >= int(offset_.size())) return -1;
    for (int k = offset_[a]; k < offset_[a + 1]; ++k)
      if (to_[k] == b) return k;
    return -1;
  }
  std::vector<int> offset_;  // edges from vertex a: slots offset_[a] .. offset_[a + 1] - 1
  std::vector<int> to_, third_, triangle_;
};

/// The boundary loops of a valid F (checked before) from its directed edges, as
/// boundary_loops returns them. \throw InvalidInputError, naming `caller`, where a vertex
/// is on the border twice.
std::vector<std::vector<int>> border_loops(const DirectedEdges& edges, const char* caller);

/// The boundary loops of a valid F (checked before) split by `rule` (geofair::holes_to_fill),
/// with V in the working scale (mesh_scale.h); a piece of border that passes twice through
/// a vertex is left open with the reason, not refused. \throw InvalidInputError, naming
/// `caller`, for a negative rule.max_hole_edges.
HoleChoice choose_holes(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                        const HoleRule& rule, const char* caller);

/// Up to three of `open` as one clause each ("the loop at vertex 7 (40 edges), <reason>").
std::string describe_open(const std::vector<OpenLoop>& open);

/// The holes to fill: `loops` checked (boundary loops of F, oriented in the direction of
/// the missing face, see boundary_loops), or where `loops` is empty the holes of
/// choose_holes(rule). \throw InvalidInputError as fill_holes.
std::vector<std::vector<int>> holes_to_fill(const Positions& V, const Triangles& F,
                                            const std::vector<std::vector<int>>& loops,
                                            const HoleRule& rule = {});
/// The same from the directed edges of a valid F (checked before), V in the working scale;
/// `left_open` (if given) receives the loops that the rule leaves open.
std::vector<std::vector<int>> holes_to_fill(const Positions& V, const Triangles& F,
                                            const std::vector<std::vector<int>>& loops,
                                            const DirectedEdges& edges, const HoleRule& rule,
                                            std::vector<OpenLoop>* left_open = nullptr);

/// Loops longer than this are not searched by Liepa's O(n³) triangulation: their patch is a
/// fan around a vertex at the centroid (split_inner_edges).
constexpr int kMaxLiepaLoop = 500;

/// Liepa's triangulation of one oriented loop (#loop − 2 triangles, oriented like the mesh):
/// minimal largest dihedral angle, then minimal area. mesh_edges gives the mesh's triangles
/// at the loop's edges, for the dihedral angles there.
Triangles triangulate_loop(const Positions& V, const std::vector<int>& loop,
                           const DirectedEdges& mesh_edges);

/// A triangulated hole with every edge across it split at its midpoint, so that each of its
/// triangles has a vertex off the loop (a free vertex for remesh_region and fair); for an
/// empty `patch` the centroid fan of the loop.
struct SplitPatch {
  Positions new_vertices;  ///< the midpoints, to be appended to V (indices from #V on)
  Triangles faces;         ///< the patch's triangles, with the midpoints' indices
};
SplitPatch split_inner_edges(const Positions& V, const Triangles& patch,
                             const std::vector<int>& loop);

/// A hole with its rim trimmed (Rim::Trim): the loop of the hole grown by the removed faces.
struct TrimmedHole {
  std::vector<int> loop;     ///< oriented like boundary_loops' loops; the input loop if none removed
  std::vector<int> removed;  ///< rows of F removed, sorted
};

/// Trims the rim of one oriented hole loop of a valid F: up to kTrimRounds rounds, each
/// removing the teeth (triangles with two edges on the current loop) and the triangles at
/// loop vertices whose remaining triangles span less than kTrimSpikeAngle there; a removal
/// is made only where the hole stays one simple loop that touches no other border (a vertex
/// with `other_border` true) and at most as many faces as the loop has vertices are removed.
/// `start`: a trim of `loop` to go on from (trim_faces'), else none.
TrimmedHole trim_rim(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                     const std::vector<int>& loop, const std::vector<bool>& other_border,
                     const TrimmedHole* start = nullptr);

/// The hole `now` (trim_rim's, grown from the input `loop`) grown further by `faces` (rows of
/// F at its rim), one at a time: each is removed only where the hole stays one simple loop
/// that touches no other border, while fewer faces than the loop has vertices are removed.
TrimmedHole trim_faces(const Triangles& F, const DirectedEdges& edges, const std::vector<int>& loop,
                       const TrimmedHole& now, const std::vector<int>& faces,
                       const std::vector<bool>& other_border);

}  // namespace geofair::hole_filling
