// Projection of moved vertices back onto a reference surface (the region's mesh before a
// tangential relaxation), so that long tangential moves keep the shape.
#pragma once

#include "region.h"

#include <geofair/types.h>

#include <vector>

namespace geofair {

/// The region's triangle mesh at positions R (#region×3) with unit vertex normals NR
/// (#region×3), interpolated by Phong tessellation (Boubekeur & Alexa 2008) with shape
/// factor 1/2, which lifts edge midpoints and centroids onto a sphere through the corners
/// where the linear mesh lies h²/(8r) inside it (Boubekeur & Alexa's 3/4 overshoots by a
/// quarter of that). Each free vertex starts in a triangle around its reference position.
class SurfaceProjection {
 public:
  SurfaceProjection(const FairingRegion& region, Positions R, Positions NR);

  /// Moves free vertex i at X.row(i) onto the reference surface: walks from its last
  /// triangle across the edges towards the point, in each triangle's plane (clamped at
  /// the region's border), then lifts the point found onto the Phong surface.
  void project(int i, Positions& X);

 private:
  const Triangles& T_;
  Positions R_, NR_;
  std::vector<int> across_;   // 3 per triangle: the triangle across edge (k+1, k+2), or -1
  std::vector<int> current_;  // per free vertex: the triangle it was last projected into
};

}  // namespace geofair
