// Entry points of fair() (geofair/fairing.h) for the library's other parts.
#pragma once

#include "geofair/types.h"

#include <vector>

namespace geofair {

/// Sets the result's connectivity members (faces, free, origin_face, origin_barycentric)
/// where the input's triangles F are kept: each vertex its own, no origin face.
void keep_connectivity(FairingResult& result, const Triangles& F, const std::vector<bool>& free);

/// fair() of a remesh (remesh_region) of the region of another surface of the same mesh
/// (options.remesh is not read): `surface` (#V×3, mesh units, finite) gives the positions
/// the remesher follows, V the fixed positions and the boundary normals' estimate (G1, as
/// fair()); the new free vertices follow the fixed ones' moves from `surface` to V (their
/// harmonic extension) before the fair. Where that fair does not converge or folds, the
/// region is remeshed once more at 4/5 of the edge length and the better result returned.
/// LiveFairing remeshes the last converged frame this way: its free vertices fit its own
/// fixed ones, not a handle that has moved on. Throws InvalidInputError as fair() does, and
/// for a `surface` of other rows or with non-finite values.
FairingResult fair_remeshed_from(const Positions& V, const Positions& surface, const Triangles& F,
                                 const std::vector<bool>& free, const Positions* boundary_normals,
                                 const FairingOptions& options);

/// fair_remeshed_from's first remesh without its fair, in the units of V (no working scale):
/// the remesh of `surface`'s region, its new free vertices moved with the fixed ones from
/// `surface` to V. Throws InvalidInputError as fair_remeshed_from.
RemeshedRegion remesh_followed(const Positions& V, const Positions& surface, const Triangles& F,
                               const std::vector<bool>& free, const Positions* boundary_normals,
                               BoundaryCondition boundary);

}  // namespace geofair
