// Small meshes with known geometry for the unit tests.
#pragma once

#include "geofair/types.h"

#include <cmath>
#include <vector>

namespace geofair::testing {

struct Mesh {
  Positions V;
  Triangles F;
};

/// The planar grid [−1, 1]² with n×n quads, each split along its rising diagonal; vertex
/// (i, j) has id j·(n+1) + i. `jitter` moves every interior vertex by up to this fraction of
/// the spacing (a fixed pseudo-random pattern).
inline Mesh planar_grid(int n, double jitter = 0.0) {
  Mesh m;
  m.V.resize((n + 1) * (n + 1), 3);
  const double h = 2.0 / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const int v = j * (n + 1) + i;
      const bool interior = i > 0 && j > 0 && i < n && j < n;
      const double dx = interior ? jitter * h * std::sin(12.9898 * v) : 0.0;
      const double dy = interior ? jitter * h * std::cos(78.233 * v) : 0.0;
      m.V.row(v) << -1.0 + i * h + dx, -1.0 + j * h + dy, 0.0;
    }
  m.F.resize(2 * n * n, 3);
  int t = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.F.row(t++) << a, b, c;
      m.F.row(t++) << a, c, d;
    }
  return m;
}

/// A regular hexagon of unit circumradius in the plane z = 0 around a centre vertex (id 0)
/// raised to z = `apex_height`: six triangles (0, k, k+1).
inline Mesh hexagon_fan(double apex_height = 0.0) {
  Mesh m;
  m.V.resize(7, 3);
  m.V.row(0) << 0, 0, apex_height;
  for (int k = 0; k < 6; ++k) m.V.row(k + 1) << std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0;
  m.F.resize(6, 3);
  for (int k = 0; k < 6; ++k) m.F.row(k) << 0, k + 1, (k + 1) % 6 + 1;
  return m;
}

/// Adds a vertex at the centroid of every triangle and splits the triangle into three:
/// the new vertices have valence 3.
inline Mesh split_centroids(const Mesh& in) {
  Mesh m;
  const int nv = int(in.V.rows()), nf = int(in.F.rows());
  m.V.resize(nv + nf, 3);
  m.V.topRows(nv) = in.V;
  m.F.resize(3 * nf, 3);
  for (int t = 0; t < nf; ++t) {
    const int a = in.F(t, 0), b = in.F(t, 1), c = in.F(t, 2), o = nv + t;
    m.V.row(o) = (in.V.row(a) + in.V.row(b) + in.V.row(c)) / 3.0;
    m.F.row(3 * t) << a, b, o;
    m.F.row(3 * t + 1) << b, c, o;
    m.F.row(3 * t + 2) << c, a, o;
  }
  return m;
}

/// The planar grid [−1, 1]² with n×n quads, each split into four by its centre vertex:
/// the centres have valence 4.
inline Mesh centred_quads(int n) {
  Mesh g = planar_grid(n);
  Mesh m;
  const int nv = int(g.V.rows());
  m.V.resize(nv + n * n, 3);
  m.V.topRows(nv) = g.V;
  m.F.resize(4 * n * n, 3);
  int t = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1, o = nv + j * n + i;
      m.V.row(o) = (g.V.row(a) + g.V.row(c)) / 2.0;
      m.F.row(t++) << a, b, o;
      m.F.row(t++) << b, c, o;
      m.F.row(t++) << c, d, o;
      m.F.row(t++) << d, a, o;
    }
  return m;
}

/// Lifts a planar mesh inside the disc of radius r (the grids' [−1, 1]² for r > √2) onto the
/// upper hemisphere of radius r by the vertical projection z = sqrt(r² − x² − y²) (the faces
/// then face outward).
inline Mesh onto_sphere(Mesh m, double r) {
  for (int v = 0; v < m.V.rows(); ++v) {
    const double x = m.V(v, 0), y = m.V(v, 1);
    m.V(v, 2) = std::sqrt(r * r - x * x - y * y);
  }
  return m;
}

/// Outward unit normals of a sphere centred at the origin.
inline Positions sphere_normals(const Positions& V) { return V.rowwise().normalized(); }

/// true for the vertices within `radius` of the origin in the xy-plane.
inline std::vector<bool> inside(const Positions& V, double radius) {
  std::vector<bool> free(V.rows());
  for (int v = 0; v < V.rows(); ++v) free[v] = V.row(v).head<2>().norm() < radius;
  return free;
}

}  // namespace geofair::testing
