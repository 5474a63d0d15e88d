// Detail coding of a region over its base (LiveFairing's details=True, live.h).
#pragma once

#include "region.h"
#include "geofair/types.h"

namespace geofair {

// Detail coding (Kobbelt et al. 1998; Botsch & Kobbelt 2004): the offsets x_i − b_i of a
// region x from its base b, per free vertex in the base's local frame (n_i, t_i, n_i × t_i),
// so that a new base b' gets them back in its own frames: x'_i = b'_i + α n'_i + β t'_i +
// γ n'_i × t'_i. n_i is the area-weighted normal of b's triangles at i, t_i the direction to
// the first ring neighbour (with a tangential part) projected into the tangent plane.
class DetailCoding {
 public:
  // base, x: #region×3 (local ids); only the free rows are coded.
  DetailCoding(const FairingRegion& region, const Positions& base, const Positions& x)
      : region_(region), coefficients_(region.n_free, 3) {
    const Positions frames = local_frames(base);
    for (int i = 0; i < region.n_free; ++i) {
      const Vec3 d = (x.row(i) - base.row(i)).transpose();
      const Vec3 n = frames.row(2 * i).transpose(), t = frames.row(2 * i + 1).transpose();
      coefficients_.row(i) << d.dot(n), d.dot(t), d.dot(n.cross(t));
    }
  }

  // The free rows of `base` with the details added in its frames.
  void decode(Positions& base) const {
    const Positions frames = local_frames(base);
    for (int i = 0; i < region_.n_free; ++i) {
      const Vec3 n = frames.row(2 * i).transpose(), t = frames.row(2 * i + 1).transpose();
      const Eigen::RowVector3d c = coefficients_.row(i);
      base.row(i) += (c(0) * n + c(1) * t + c(2) * n.cross(t)).transpose();
    }
  }

 private:
  // Rows 2i and 2i + 1: the unit normal and tangent of free vertex i at X (zero where
  // degenerate: its details are then dropped, not made up).
  Positions local_frames(const Positions& X) const {
    const OneRings& rings = region_.rings;
    Positions normals = Positions::Zero(region_.n, 3);
    for (Eigen::Index f = 0; f < region_.triangles.rows(); ++f) {
      const int a = region_.triangles(f, 0), b = region_.triangles(f, 1),
                c = region_.triangles(f, 2);
      const Eigen::RowVector3d area = (X.row(b) - X.row(a)).cross(X.row(c) - X.row(a));
      normals.row(a) += area, normals.row(b) += area, normals.row(c) += area;
    }
    Positions frames = Positions::Zero(2 * region_.n_free, 3);
    for (int i = 0; i < region_.n_free; ++i) {
      const double length = normals.row(i).norm();
      if (!(length > 0.0)) continue;
      const Vec3 n = normals.row(i).transpose() / length;
      for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k) {
        const Vec3 e = (X.row(rings.ring[k]) - X.row(i)).transpose();
        const Vec3 t = e - e.dot(n) * n;
        if (t.norm() > 1e-3 * e.norm()) {
          frames.row(2 * i) = n.transpose();
          frames.row(2 * i + 1) = t.normalized().transpose();
          break;
        }
      }
    }
    return frames;
  }

  const FairingRegion& region_;
  Positions coefficients_;  // #V_I×3: (α, β, γ), mesh units / scale
};

}  // namespace geofair
