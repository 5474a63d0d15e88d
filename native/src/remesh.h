// Isotropic remeshing of a fairing region (beyond the paper; section 7.5's closing remark:
// where the final mesh need not keep its connectivity, edges are flipped to avoid long
// triangles, vertices inserted where needed and removed where the density is too high).
// The interface is public: remesh_region, exported by geofair/building_blocks.h, which
// documents it and gives the default; RemeshOptions and RemeshedRegion in geofair/types.h.
#pragma once

#include "geofair/types.h"

#include <vector>

namespace geofair {

RemeshedRegion remesh_region(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                             const RemeshOptions& options);

}  // namespace geofair
