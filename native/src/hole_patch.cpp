// Liepa's triangulation of a hole's loop, and the split of its edges across the hole
// (hole_filling_internal.h).
#include "hole_filling_internal.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <vector>

namespace geofair::hole_filling {

namespace {

// The dihedral angle between two triangles by its cosine, as the monotonic measure
// 1 - cos: 0 for a flat continuation, 2 for a fold; unit normals, zero for a degenerate
// triangle (the worst measure).
double fold_measure(const Vec3& n1, const Vec3& n2) {
  if (n1.isZero() || n2.isZero()) return 2.0;
  return 1.0 - n1.dot(n2);
}

Vec3 unit_or_zero(const Vec3& n) {
  const double length = n.norm();
  return length > 0.0 ? Vec3(n / length) : Vec3::Zero();
}

// Liepa's weight of a (sub)triangulation: its largest dihedral angle, then its area.
struct Weight {
  double fold = 0.0;  ///< fold_measure of the largest dihedral angle
  double area = 0.0;
  bool operator<(const Weight& o) const {
    return fold < o.fold || (fold == o.fold && area < o.area);
  }
};

}  // namespace

Triangles triangulate_loop(const Positions& V, const std::vector<int>& loop,
                           const DirectedEdges& mesh_edges) {
  const int n = int(loop.size());
  if (n > kMaxLiepaLoop) return Triangles(0, 3);
  // outer[i]: unit normal of the mesh's triangle at loop edge (i, i+1) (it has the edge
  // i+1 -> i), zero where there is none.
  std::vector<Vec3> outer(n, Vec3::Zero());
  for (int i = 0; i < n; ++i) {
    const int c = mesh_edges.third(loop[(i + 1) % n], loop[i]);
    if (c >= 0) outer[i] = unit_or_zero(triangle_normal(V, loop[(i + 1) % n], loop[i], c));
  }
  const double inf = std::numeric_limits<double>::infinity();
  const size_t cells = size_t(n) * n;
  std::vector<Weight> W(cells, Weight{inf, inf});
  std::vector<int> split(cells, -1);
  std::vector<Vec3> normal(cells, Vec3::Zero());  // unit normal of (i, split, k)
  auto at = [n](int i, int k) { return size_t(i) * n + k; };
  for (int i = 0; i + 1 < n; ++i) {
    W[at(i, i + 1)] = Weight{};
    normal[at(i, i + 1)] = outer[i];  // across loop edge (i, i+1): the mesh's triangle
  }
  const bool closing = !outer[n - 1].isZero();  // the mesh's triangle at loop edge (n-1, 0)
  for (int span = 2; span < n; ++span) {
    for (int i = 0; i + span < n; ++i) {
      const int k = i + span;
      Weight& best = W[at(i, k)];
      for (int m = i + 1; m < k; ++m) {
        const Weight& left = W[at(i, m)];
        const Weight& right = W[at(m, k)];
        if (std::max(left.fold, right.fold) > best.fold) continue;  // cannot win
        const Vec3 raw = triangle_normal(V, loop[i], loop[m], loop[k]);
        const double length = raw.norm();
        const Vec3 nt = length > 0.0 ? Vec3(raw / length) : Vec3::Zero();
        // The fold with the triangle across edge (a, b): the sub-polygon's, or at a loop
        // edge the mesh's where there is one.
        auto across = [&](int a, int b) {
          const Vec3& other = normal[at(a, b)];
          return b == a + 1 && other.isZero() ? 0.0 : fold_measure(nt, other);
        };
        Weight w{std::max({left.fold, right.fold, across(i, m), across(m, k)}),
                 left.area + right.area + 0.5 * length};
        if (span == n - 1 && closing) w.fold = std::max(w.fold, fold_measure(nt, outer[n - 1]));
        if (w < best) {
          best = w;
          split[at(i, k)] = m;
          normal[at(i, k)] = nt;
        }
      }
    }
  }
  Triangles T(n - 2, 3);
  int t = 0;
  std::vector<std::pair<int, int>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, k] = stack.back();
    stack.pop_back();
    if (k - i < 2) continue;
    const int m = split[at(i, k)];
    T.row(t++) << loop[i], loop[m], loop[k];
    stack.push_back({i, m});
    stack.push_back({m, k});
  }
  return T;
}

// A fan around a new vertex at the loop's centroid, for loops too long for Liepa's O(n³)
// search (the remesh and the fairing decide the shape; the fan gives the connectivity).
SplitPatch centroid_fan(const Positions& V, const std::vector<int>& loop) {
  const int n = int(loop.size()), c = int(V.rows());
  SplitPatch out;
  out.new_vertices = Positions::Zero(1, 3);
  for (int v : loop) out.new_vertices.row(0) += V.row(v) / double(n);
  out.faces.resize(n, 3);
  for (int i = 0; i < n; ++i) out.faces.row(i) << loop[i], loop[(i + 1) % n], c;
  return out;
}

SplitPatch split_inner_edges(const Positions& V, const Triangles& patch,
                             const std::vector<int>& loop) {
  if (patch.rows() == 0) return centroid_fan(V, loop);
  std::map<std::pair<int, int>, bool> on_loop;
  const int n = int(loop.size());
  for (int i = 0; i < n; ++i) {
    on_loop[std::minmax(loop[i], loop[(i + 1) % n])] = true;
  }
  SplitPatch out;
  std::map<std::pair<int, int>, int> midpoint;
  std::vector<Vec3> added;
  const int base = int(V.rows());
  auto mid = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    if (on_loop.count(key)) return -1;
    auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    const int index = base + int(added.size());
    added.push_back(0.5 * (V.row(a) + V.row(b)).transpose());
    midpoint.emplace(key, index);
    return index;
  };
  std::vector<std::array<int, 3>> faces;
  for (int f = 0; f < patch.rows(); ++f) {
    const int v[3] = {patch(f, 0), patch(f, 1), patch(f, 2)};
    const int m[3] = {mid(v[0], v[1]), mid(v[1], v[2]), mid(v[2], v[0])};
    const int splits = (m[0] >= 0) + (m[1] >= 0) + (m[2] >= 0);
    if (splits == 0) {  // a hole of three vertices: its one triangle gets a centroid below
      faces.push_back({v[0], v[1], v[2]});
      continue;
    }
    if (splits == 3) {  // 1-to-4
      faces.push_back({v[0], m[0], m[2]});
      faces.push_back({v[1], m[1], m[0]});
      faces.push_back({v[2], m[2], m[1]});
      faces.push_back({m[0], m[1], m[2]});
      continue;
    }
    // Rotate so that edge (r0, r1) is split and, with two splits, (r1, r2) too.
    int r = 0;
    while (!(m[r] >= 0 && (splits == 1 || m[(r + 1) % 3] >= 0))) ++r;
    const int a = v[r], b = v[(r + 1) % 3], c = v[(r + 2) % 3];
    const int ab = m[r], bc = m[(r + 1) % 3];
    if (splits == 1) {
      faces.push_back({a, ab, c});
      faces.push_back({ab, b, c});
    } else {
      faces.push_back({a, ab, c});
      faces.push_back({ab, b, bc});
      faces.push_back({ab, bc, c});
    }
  }
  // A hole of three vertices has no edge across it: its one triangle gets a centroid.
  if (added.empty() && faces.size() == 1) {
    const auto [a, b, c] = faces[0];
    added.push_back((V.row(a) + V.row(b) + V.row(c)).transpose() / 3.0);
    faces = {{a, b, base}, {b, c, base}, {c, a, base}};
  }
  out.new_vertices.resize(Eigen::Index(added.size()), 3);
  for (size_t k = 0; k < added.size(); ++k) out.new_vertices.row(Eigen::Index(k)) = added[k];
  out.faces.resize(Eigen::Index(faces.size()), 3);
  for (size_t k = 0; k < faces.size(); ++k)
    out.faces.row(Eigen::Index(k)) << faces[k][0], faces[k][1], faces[k][2];
  return out;
}

}  // namespace geofair::hole_filling
