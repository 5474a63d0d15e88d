// Projection onto a reference surface (surface_projection.h).
#include "surface_projection.h"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace geofair {

SurfaceProjection::SurfaceProjection(const FairingRegion& region, Positions R, Positions NR)
    : T_(region.triangles), R_(std::move(R)), NR_(std::move(NR)) {
  // Neighbours across edges: the undirected edges of all triangles, sorted, pair up.
  const int m = int(T_.rows());
  std::vector<std::pair<std::uint64_t, int>> edges;  // (edge key, slot 3t + k)
  edges.reserve(3 * std::size_t(m));
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = T_(t, (k + 1) % 3), b = T_(t, (k + 2) % 3);
      edges.emplace_back((std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b)),
                         3 * t + k);
    }
  std::sort(edges.begin(), edges.end());
  across_.assign(3 * std::size_t(m), -1);
  for (std::size_t e = 0; e + 1 < edges.size(); ++e)
    if (edges[e].first == edges[e + 1].first) {
      across_[edges[e].second] = edges[e + 1].second / 3;
      across_[edges[e + 1].second] = edges[e].second / 3;
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
  Eigen::Vector3d b(1.0 / 3, 1.0 / 3, 1.0 / 3);
  // A point off a curved surface can lie outside two neighbouring triangles' planes across
  // their common edge (or outside every plane of a fan): the walk stops where it would turn
  // back, and after kMaxWalk triangles.
  constexpr int kMaxWalk = 1000;
  int previous = -1;
  for (int step = 0;; ++step) {
    const Vec3 a = R_.row(T_(t, 0)).transpose(), e1 = R_.row(T_(t, 1)).transpose() - a,
               e2 = R_.row(T_(t, 2)).transpose() - a;
    // Barycentric coordinates of p's projection onto the triangle's plane.
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const Vec3 q = p - a;
    const double q1 = q.dot(e1), q2 = q.dot(e2), det = d11 * d22 - d12 * d12;
    if (!(det > 0.0)) {  // a degenerate reference triangle: back to the last one
      if (previous >= 0) t = previous;
      break;
    }
    b(1) = (d22 * q1 - d12 * q2) / det;
    b(2) = (d11 * q2 - d12 * q1) / det;
    b(0) = 1.0 - b(1) - b(2);
    int k;
    const double lowest = b.minCoeff(&k);
    if (lowest >= 0.0 || step >= kMaxWalk) break;
    const int next = across_[3 * t + k];
    if (next < 0 || next == previous) break;  // the region's border, or turning back
    previous = t;
    t = next;
  }
  // Clamp to the triangle (outside at the border, where the walk turned back or stopped).
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
