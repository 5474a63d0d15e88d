// Projection onto a reference surface (surface_projection.h).
#include "surface_projection.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace geofair {

SurfaceProjection::SurfaceProjection(const FairingRegion& region, const Positions& R,
                                     const Positions& NR)
    : T_(region.triangles), R_(R), NR_(NR) {
  const int m = int(T_.rows());
  across_.assign(3 * std::size_t(m), -1);
  std::unordered_map<std::uint64_t, int> half;  // directed edge (a, b) -> slot 3t + k
  half.reserve(3 * std::size_t(m));
  auto key = [](int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) half[key(T_(t, (k + 1) % 3), T_(t, (k + 2) % 3))] = 3 * t + k;
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const auto it = half.find(key(T_(t, (k + 2) % 3), T_(t, (k + 1) % 3)));
      if (it != half.end()) across_[3 * t + k] = it->second / 3;
    }
  current_.assign(region.n_free, -1);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k)
      if (T_(t, k) < region.n_free && current_[T_(t, k)] < 0) current_[T_(t, k)] = t;
}

void SurfaceProjection::project(int i, Positions& X) {
  const Vec3 p = X.row(i).transpose();
  int t = current_[i];
  if (t < 0) return;
  Eigen::Vector3d b;
  const int max_steps = 4 * int(T_.rows()) + 16;
  for (int step = 0;; ++step) {
    const Vec3 a = R_.row(T_(t, 0)).transpose(), e1 = R_.row(T_(t, 1)).transpose() - a,
               e2 = R_.row(T_(t, 2)).transpose() - a;
    // Barycentric coordinates of p's projection onto the triangle's plane.
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const Vec3 q = p - a;
    const double q1 = q.dot(e1), q2 = q.dot(e2), det = d11 * d22 - d12 * d12;
    if (!(det > 0.0)) break;  // a degenerate reference triangle: stay where the walk is
    b(1) = (d22 * q1 - d12 * q2) / det;
    b(2) = (d11 * q2 - d12 * q1) / det;
    b(0) = 1.0 - b(1) - b(2);
    int k;
    const double lowest = b.minCoeff(&k);
    if (lowest >= 0.0 || step >= max_steps) break;
    if (across_[3 * t + k] < 0) break;  // the region's border: clamped below
    t = across_[3 * t + k];
  }
  // Clamp to the triangle (outside only at the border or after a degenerate one).
  b = b.cwiseMax(0.0);
  const double sum = b.sum();
  b = sum > 0.0 ? Eigen::Vector3d(b / sum) : Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3);
  current_[i] = t;
  Vec3 linear = Vec3::Zero(), phong = Vec3::Zero();
  for (int k = 0; k < 3; ++k) linear += b(k) * R_.row(T_(t, k)).transpose();
  for (int k = 0; k < 3; ++k) {
    const Vec3 x = R_.row(T_(t, k)).transpose(), n = NR_.row(T_(t, k)).transpose();
    phong += b(k) * (linear - (linear - x).dot(n) * n);
  }
  X.row(i) = (0.5 * (linear + phong)).transpose();
}

}  // namespace geofair
