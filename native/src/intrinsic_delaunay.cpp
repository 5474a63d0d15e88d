// Intrinsic Delaunay triangulation by edge flips (Fisher et al. 2006; Bobenko & Springborn
// 2007): the mesh is a piecewise-flat surface given by its edge lengths; an edge is flipped
// within the planar layout of its two triangles, so no vertex moves.
#include "intrinsic_delaunay.h"

#include "region.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace geofair {
namespace {

// Halfedge h = 3t + k runs from corner k to corner k+1 of triangle t.
inline int next_of(int h) { return h - h % 3 + (h % 3 + 1) % 3; }
inline int prev_of(int h) { return h - h % 3 + (h % 3 + 2) % 3; }

// Twice the area of a triangle with side lengths a, b, c (Kahan's stable Heron formula);
// 0 for a degenerate or impossible triangle.
double twice_area(double a, double b, double c) {
  std::array<double, 3> s{a, b, c};
  std::sort(s.begin(), s.end(), std::greater<double>());
  const double x = s[0], y = s[1], z = s[2];
  const double r = (x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z));
  return r > 0.0 ? 0.5 * std::sqrt(r) : 0.0;
}

struct Flipper {
  Triangles T;
  std::vector<double> len;  // per halfedge
  std::vector<int> twin;    // per halfedge, -1 on the border

  // cot of the angle opposite halfedge h in its triangle: (b² + c² − a²) / (4 area).
  double cot_opposite(int h) const {
    const double a = len[h], b = len[next_of(h)], c = len[prev_of(h)];
    const double num = b * b + c * c - a * a;
    const double den = 2.0 * twice_area(a, b, c);
    return num / std::max(den, std::max(1e-12 * std::abs(num), 1e-300));
  }

  bool degenerate(int h) const {
    return !(twice_area(len[h], len[next_of(h)], len[prev_of(h)]) > 0.0);
  }

  bool needs_flip(int h) const {
    const int g = twin[h];
    if (g < 0 || degenerate(h) || degenerate(g)) return false;
    return cot_opposite(h) + cot_opposite(g) < -1e-12;
  }

  // Flips the edge of h; returns the four outer halfedges (new ids) to re-check.
  std::array<int, 4> flip(int h) {
    const int g = twin[h];
    const int t1 = h / 3, t2 = g / 3;
    const int h1 = next_of(h), h2 = prev_of(h), g1 = next_of(g), g2 = prev_of(g);
    const int a = T(t1, h % 3), b = T(t1, h1 % 3), c = T(t1, h2 % 3), d = T(t2, g2 % 3);
    const double l_ab = len[h], l_bc = len[h1], l_ca = len[h2], l_ad = len[g1], l_db = len[g2];
    // Layout: a = (0, 0), b = (l_ab, 0), c above, d below the x axis.
    const double xc = (l_ab * l_ab + l_ca * l_ca - l_bc * l_bc) / (2.0 * l_ab);
    const double yc = std::sqrt(std::max(l_ca * l_ca - xc * xc, 0.0));
    const double xd = (l_ab * l_ab + l_ad * l_ad - l_db * l_db) / (2.0 * l_ab);
    const double yd = -std::sqrt(std::max(l_ad * l_ad - xd * xd, 0.0));
    const double l_cd = std::hypot(xc - xd, yc - yd);
    // New triangles t1 = (c, a, d), t2 = (d, b, c); the outer halfedges get new ids.
    const int n_ca = 3 * t1, n_ad = 3 * t1 + 1, n_dc = 3 * t1 + 2;
    const int n_db = 3 * t2, n_bc = 3 * t2 + 1, n_cd = 3 * t2 + 2;
    const std::array<std::pair<int, int>, 4> moved{{{h2, n_ca}, {g1, n_ad}, {g2, n_db}, {h1, n_bc}}};
    auto renumber = [&](int old) {
      for (const auto& [from, to] : moved)
        if (old == from) return to;
      return old;
    };
    std::array<int, 4> outer_twin;
    for (int s = 0; s < 4; ++s) outer_twin[s] = renumber(twin[moved[s].first]);
    const std::array<double, 4> outer_len{l_ca, l_ad, l_db, l_bc};
    T.row(t1) << c, a, d;
    T.row(t2) << d, b, c;
    for (int s = 0; s < 4; ++s) {
      const int e = moved[s].second, o = outer_twin[s];
      len[e] = outer_len[s];
      twin[e] = o;
      if (o >= 0) twin[o] = e;
    }
    len[n_dc] = len[n_cd] = l_cd;
    twin[n_dc] = n_cd;
    twin[n_cd] = n_dc;
    return {n_ca, n_ad, n_db, n_bc};
  }
};

}  // namespace

IntrinsicTriangulation intrinsic_delaunay(const Positions& V, const Triangles& F) {
  const char* fn = "intrinsic_delaunay";
  const int nv = int(V.rows()), nt = int(F.rows());
  if (!V.allFinite())
    throw InvalidInputError(std::string(fn) + ": vertices contain a non-finite coordinate");
  check_triangles(nv, F, fn);  // indices, manifoldness and orientation
  Flipper m;
  m.T = F;
  m.len.resize(3 * std::size_t(nt));
  m.twin.assign(3 * std::size_t(nt), -1);
  std::unordered_map<long long, int> directed;
  directed.reserve(3 * std::size_t(nt));
  auto key = [nv](int i, int j) { return (long long)i * nv + j; };
  for (int h = 0; h < 3 * nt; ++h) {
    const int i = F(h / 3, h % 3), j = F(h / 3, (h % 3 + 1) % 3);
    m.len[h] = (V.row(j) - V.row(i)).norm();
    directed.emplace(key(i, j), h);
  }
  std::vector<int> stack;
  for (int h = 0; h < 3 * nt; ++h) {
    const int i = F(h / 3, h % 3), j = F(h / 3, (h % 3 + 1) % 3);
    const auto it = directed.find(key(j, i));
    if (it != directed.end()) m.twin[h] = it->second;
    if (m.twin[h] > h) stack.push_back(h);
  }
  IntrinsicTriangulation out;
  // Bobenko & Springborn prove termination; the bound only guards against round-off cycles.
  const long long max_flips = 100LL * nt + 1000;
  while (!stack.empty()) {
    const int h = stack.back();
    stack.pop_back();
    if (!m.needs_flip(h)) continue;
    if (++out.flips > max_flips)
      throw SolverError(std::string(fn) + ": the edge flips did not terminate");
    for (int e : m.flip(h)) stack.push_back(e);
  }
  out.triangles = std::move(m.T);
  out.lengths.resize(nt, 3);
  for (int h = 0; h < 3 * nt; ++h) out.lengths(h / 3, h % 3) = m.len[h];
  return out;
}

SparseRowMatrix intrinsic_laplacian(int n_vertices, const IntrinsicTriangulation& T) {
  Flipper m;  // for cot_opposite only
  const int nt = int(T.triangles.rows());
  m.len.resize(3 * std::size_t(nt));
  for (int h = 0; h < 3 * nt; ++h) m.len[h] = T.lengths(h / 3, h % 3);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(12 * std::size_t(nt));
  for (int h = 0; h < 3 * nt; ++h) {
    const int i = T.triangles(h / 3, h % 3), j = T.triangles(h / 3, (h % 3 + 1) % 3);
    if (i == j) continue;  // a loop edge of an intrinsic triangle: no term
    const double w = m.cot_opposite(h);
    triplets.emplace_back(i, j, w);
    triplets.emplace_back(j, i, w);
    triplets.emplace_back(i, i, -w);
    triplets.emplace_back(j, j, -w);
  }
  SparseRowMatrix L(n_vertices, n_vertices);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

SparseRowMatrix intrinsic_delaunay_laplacian(const Positions& V, const Triangles& F, int* flips) {
  const IntrinsicTriangulation T = intrinsic_delaunay(V, F);
  if (flips) *flips = T.flips;
  return intrinsic_laplacian(int(V.rows()), T);
}

}  // namespace geofair
