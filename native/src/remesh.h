// Isotropic remeshing of a fairing region (beyond the paper; section 7.5's closing remark:
// where the final mesh need not keep its connectivity, edges are flipped to avoid long
// triangles, vertices inserted where needed and removed where the density is too high).
// The interface is public (geofair/building_blocks.h: RemeshOptions, RemeshedRegion,
// remesh_region); the implementation is remesh.cpp.
#pragma once

#include "geofair/building_blocks.h"
