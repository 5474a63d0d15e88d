// Prolongation between the levels of the progressive mesh (Schneider & Kobbelt 2001,
// section 7.4, after Guskov et al. 1999).
#pragma once

#include "geofair/construction.h"
#include "geofair/progressive_mesh.h"
#include "geofair/region.h"
#include "geofair/types.h"

namespace geofair {

/// Inserts the vertices a level adds to the coarser one, replaying the vertex splits in
/// order. For each new vertex q_i:
///  1. q_i = Σ_j λ_ij q_j over the one-ring it has when its split is replayed (its
///     inner-fairness position; conformal weights from the original positions X0);
///  2. the 1-disk D(q_i) is relaxed by solving Δq_l = 0 for its free vertices (two
///     Gauss–Seidel sweeps of the inner-fairness Laplacian of the level);
///  3. outer fairness is restored locally by running the construction on D(q_i)
///     (Construction::local_steps).
/// Steps 2 and 3 run once for the union of the new vertices' 1-disks.
///
/// \param level   the finer level's region
/// \param splits  the level's vertex splits, in level-local ids
/// \param X0      #level×3 original positions (for conformal weights)
/// \param X       #level×3 positions: valid for all but the new vertices, which are set
void prolongate(const FairingRegion& level, const VertexSplits& splits, InnerFairness inner,
                const Positions& X0, Positions& X, Construction& construction);

}  // namespace geofair
