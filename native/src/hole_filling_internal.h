// The steps of fill_holes (geofair/hole_filling.h), for the library and its unit tests.
#pragma once

#include "geofair/types.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace geofair::hole_filling {

/// The directed edges (a, b) of a mesh's triangles, each to the triangle's third vertex.
class DirectedEdges {
 public:
  explicit DirectedEdges(const Triangles& F);
  /// The third vertex of the triangle with the directed edge a -> b, or -1.
  int third(int a, int b) const {
    auto it = map_.find(key(a, b));
    return it == map_.end() ? -1 : it->second;
  }
  bool has(int a, int b) const { return map_.count(key(a, b)) != 0; }
  /// Calls f(a, b) for each directed edge whose reverse is not an edge (a border edge).
  template <class Function>
  void for_each_border_edge(Function f) const {
    for (const auto& [k, third] : map_) {
      const int a = int(k >> 32), b = int(k & 0xffffffffu);
      if (!has(b, a)) f(a, b);
    }
  }

 private:
  static std::uint64_t key(int a, int b) {
    return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
  }
  std::unordered_map<std::uint64_t, int> map_;
};

/// The holes to fill: `loops` checked (boundary loops of F, oriented in the direction of
/// the missing face, see boundary_loops), or every boundary loop of F when `loops` is empty.
/// \throw InvalidInputError as fill_holes.
std::vector<std::vector<int>> holes_to_fill(const Positions& V, const Triangles& F,
                                            const std::vector<std::vector<int>>& loops);

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

}  // namespace geofair::hole_filling
