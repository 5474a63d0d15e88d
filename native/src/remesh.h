// Isotropic remeshing of a fairing region (beyond the paper; section 7.5's closing remark:
// where the final mesh need not keep its connectivity, edges are flipped to avoid long
// triangles, vertices inserted where needed and removed where the density is too high).
#pragma once

#include "geofair/types.h"

#include <vector>

namespace geofair {

struct RemeshOptions {
  /// Target edge length in mesh units; <= 0: the mean length of the region's boundary
  /// edges (the edges between two fixed vertices on faces that have a free vertex).
  double target_edge_length = 0.0;
  int iterations = 5;  ///< rounds of split, collapse, flip, tangential relaxation
};

/// The region's new triangles. Rows of the input's fixed vertices keep their index and
/// position; the input's free rows are reused by the new free vertices in order and extra
/// ones are appended, so `vertices` has max(#V, #fixed + #new free) rows; free rows that the
/// new region does not use are listed in `unreferenced` (not in any face, not free).
struct RemeshedRegion {
  Positions vertices;           ///< rows: as above
  Triangles faces;              ///< the faces outside the region unchanged, then the new ones
  std::vector<bool> free;       ///< true at the new region's free vertices
  std::vector<int> unreferenced;
  /// Where each vertex lies on the input region's surface: the input face (index into F)
  /// and barycentric coordinates in it (rows summing to 1); -1 and zeros for vertices that
  /// are not free. Lets a caller carry per-corner data (UVs) over from the input.
  std::vector<int> origin_face;
  Positions origin_barycentric;
};

/// Replaces the triangles of the region (the faces with a free vertex) by an isotropic
/// remesh (Botsch & Kobbelt 2004): splits of edges longer than 4/3 of the target length,
/// collapses of those shorter than 4/5, flips towards valence 6 (4 at the mesh border),
/// tangential relaxation, each new vertex projected onto the input region. Fixed vertices
/// and the region's boundary edges are kept. Raises InvalidInputError for a region that is
/// not an oriented 2-manifold.
RemeshedRegion remesh_region(const Positions& V, const Triangles& F,
                             const std::vector<bool>& free, const RemeshOptions& options);

}  // namespace geofair
