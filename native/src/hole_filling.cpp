// Hole filling: Liepa's triangulation of each loop, its edges across the hole split, the
// patch remeshed and faired (geofair/hole_filling.h).
#include "geofair/hole_filling.h"

#include "common.h"
#include "hole_filling_internal.h"
#include "mesh_scale.h"
#include "region.h"
#include "remesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>

namespace geofair {

namespace {

using hole_filling::DirectedEdges;

// Validates the triangles (indices, manifold, orientation) and the coordinates they use.
void check_mesh(const Positions& V, const Triangles& F, const char* caller) {
  build_one_rings(int(V.rows()), F, caller);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (!V.row(F(f, c)).allFinite())
        throw InvalidInputError(std::string(caller) + ": vertex " + std::to_string(F(f, c)) +
                                " has a non-finite coordinate");
}

std::string pair_name(int a, int b) {
  return "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

// The loop in the direction of the missing face, or an error naming the first pair of
// consecutive vertices that is not a boundary edge.
std::vector<int> oriented_loop(const std::vector<int>& loop, const DirectedEdges& edges,
                               int n_vertices) {
  const int n = int(loop.size());
  if (n < 3)
    throw InvalidInputError("fill_holes: a loop needs at least 3 vertices, got " +
                            std::to_string(n));
  auto is_boundary = [&](int a, int b) {  // a -> b runs along the missing face
    return edges.has(b, a) && !edges.has(a, b);
  };
  for (int v : loop)
    if (v < 0 || v >= n_vertices)
      throw InvalidInputError("fill_holes: loop vertex " + std::to_string(v) + " out of range");
  bool forward = true, backward = true;
  for (int k = 0; k < n; ++k) {
    const int a = loop[k], b = loop[(k + 1) % n];
    forward = forward && is_boundary(a, b);
    backward = backward && is_boundary(b, a);
    if (!forward && !backward)
      throw InvalidInputError("fill_holes: vertices " + pair_name(a, b) +
                              " of a loop are not a boundary edge of the mesh");
  }
  std::vector<int> out = loop;
  if (!forward) std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<std::vector<int>> boundary_loops(const Positions& V, const Triangles& F) {
  check_mesh(V, F, "boundary_loops");
  return hole_filling::border_loops(DirectedEdges(F), "boundary_loops");
}

HoleChoice holes_to_fill(const Positions& V, const Triangles& F, const HoleRule& rule) {
  check_mesh(V, F, "holes_to_fill");
  const double scale = working_scale(V, F, "holes_to_fill");
  return hole_filling::choose_holes(scale == 1.0 ? V : Positions(V / scale), F, DirectedEdges(F),
                                    rule, "holes_to_fill");
}

namespace hole_filling {

DirectedEdges::DirectedEdges(const Triangles& F) {
  const int n = F.size() > 0 ? F.maxCoeff() + 1 : 0;
  offset_.assign(size_t(n) + 1, 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++offset_[size_t(F(f, c)) + 1];
  for (int v = 0; v < n; ++v) offset_[v + 1] += offset_[v];
  const size_t m = size_t(3 * F.rows());
  to_.resize(m), third_.resize(m), triangle_.resize(m);
  std::vector<int> next(offset_.begin(), offset_.end() - 1);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int k = next[F(f, c)]++;
      to_[k] = F(f, (c + 1) % 3), third_[k] = F(f, (c + 2) % 3), triangle_[k] = f;
    }
}

std::vector<std::vector<int>> border_loops(const DirectedEdges& edges, const char* caller) {
  std::map<int, int> next;  // loop successor in the direction of the missing face
  edges.for_each_border_edge([&](int a, int b) {
    if (!next.emplace(b, a).second)
      throw InvalidInputError(std::string(caller) + ": vertex " + std::to_string(b) +
                              " lies on the border twice (two holes, or one hole's border, "
                              "touch there)");
  });
  std::vector<std::vector<int>> loops;
  std::map<int, bool> done;
  for (const auto& [start, unused] : next) {
    (void)unused;
    if (done[start]) continue;
    std::vector<int> loop;
    for (int v = start; !done[v]; v = next.at(v)) {
      done[v] = true;
      loop.push_back(v);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

namespace {

Vec3 triangle_normal(const Positions& V, int a, int b, int c) {
  return (V.row(b) - V.row(a)).cross(V.row(c) - V.row(a)).transpose();
}

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

namespace {

// The area a loop spans: the norm of its vector area about its centroid.
double spanned_area(const Positions& V, const std::vector<int>& loop) {
  Vec3 centre = Vec3::Zero();
  for (int v : loop) centre += V.row(v).transpose();
  centre /= double(loop.size());
  Vec3 sum = Vec3::Zero();
  for (size_t k = 0; k < loop.size(); ++k) {
    const Vec3 a = V.row(loop[k]).transpose() - centre;
    const Vec3 b = V.row(loop[(k + 1) % loop.size()]).transpose() - centre;
    sum += a.cross(b);
  }
  return 0.5 * sum.norm();
}

// The connected part of each vertex (its smallest vertex index; union-find over F) and the
// area of each part's triangles, by part.
std::pair<std::vector<int>, std::vector<double>> parts(const Positions& V, const Triangles& F) {
  std::vector<int> parent(size_t(V.rows()));
  for (size_t v = 0; v < parent.size(); ++v) parent[v] = int(v);
  auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 1; c < 3; ++c) {
      const int a = root(F(f, 0)), b = root(F(f, c));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<double> area(parent.size(), 0.0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    area[root(F(f, 0))] += 0.5 * triangle_normal(V, F(f, 0), F(f, 1), F(f, 2)).norm();
  for (size_t v = 0; v < parent.size(); ++v) parent[v] = root(int(v));
  return {std::move(parent), std::move(area)};
}

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f %%", 100.0 * fraction);
  return text;
}

}  // namespace

HoleChoice choose_holes(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                        const HoleRule& rule, const char* caller) {
  if (rule.max_hole_edges < 0)
    throw InvalidInputError(std::string(caller) + ": max_hole_edges must be >= 0 (0: no limit)");
  HoleChoice out;
  auto loops = border_loops(edges, caller);
  if (loops.empty()) return out;
  // Each part's outer border: its loop of the largest spanned area (the first of equals), if
  // that is at least kOuterBorderArea of the part's area.
  std::vector<int> outer(loops.size(), 0);
  std::vector<double> spanned(loops.size(), 0.0);
  std::vector<double> area;
  std::vector<int> part;
  if (rule.keep_outer_borders) {
    std::tie(part, area) = parts(V, F);
    std::map<int, size_t> largest;  // part -> its loop of the largest spanned area
    for (size_t l = 0; l < loops.size(); ++l) {
      spanned[l] = spanned_area(V, loops[l]);
      const auto [it, first] = largest.emplace(part[size_t(loops[l][0])], l);
      if (!first && spanned[l] > spanned[it->second]) it->second = l;
    }
    for (const auto& [p, l] : largest)
      outer[l] = spanned[l] > 0.0 && spanned[l] >= kOuterBorderArea * area[size_t(p)];
  }
  for (size_t l = 0; l < loops.size(); ++l) {
    auto& loop = loops[l];
    std::string reason;
    if (outer[l]) {
      const double fraction = spanned[l] / area[size_t(part[size_t(loop[0])])];
      reason = "an outer border: it spans " + percent(fraction) +
               " of the area of its part's triangles (a hole less than " +
               percent(kOuterBorderArea) + ")";
    }
    if (reason.empty() && rule.max_hole_edges > 0 && int(loop.size()) > rule.max_hole_edges)
      reason = "more edges than max_hole_edges = " + std::to_string(rule.max_hole_edges);
    if (reason.empty())
      out.holes.push_back(std::move(loop));
    else
      out.left_open.push_back({std::move(loop), std::move(reason)});
  }
  return out;
}

std::vector<std::vector<int>> holes_to_fill(const Positions& V, const Triangles& F,
                                            const std::vector<std::vector<int>>& loops,
                                            const HoleRule& rule) {
  check_mesh(V, F, "fill_holes");
  const double scale = working_scale(V, F, "fill_holes");
  return holes_to_fill(scale == 1.0 ? V : Positions(V / scale), F, loops, DirectedEdges(F), rule);
}

std::string describe_open(const std::vector<OpenLoop>& open) {
  std::string text;
  for (size_t k = 0; k < open.size() && k < 3; ++k)
    text += std::string(k ? "; " : "") + "the loop at vertex " + std::to_string(open[k].loop[0]) +
            " (" + std::to_string(open[k].loop.size()) + " edges), " + open[k].reason;
  if (open.size() > 3) text += "; and " + std::to_string(open.size() - 3) + " more";
  return text;
}

std::vector<std::vector<int>> holes_to_fill(const Positions& V, const Triangles& F,
                                            const std::vector<std::vector<int>>& loops,
                                            const DirectedEdges& edges, const HoleRule& rule,
                                            std::vector<OpenLoop>* left_open) {
  if (loops.empty()) {
    HoleChoice choice = choose_holes(V, F, edges, rule, "fill_holes");
    if (choice.holes.empty() && choice.left_open.empty())
      throw InvalidInputError("fill_holes: the mesh has no hole (no boundary edge)");
    if (choice.holes.empty())
      throw InvalidInputError(
          "fill_holes: the mesh has no hole to fill, every boundary loop is left open: " +
          describe_open(choice.left_open) +
          ". Give the loops to fill, keep_outer_borders=False or a larger max_hole_edges");
    if (left_open) *left_open = std::move(choice.left_open);
    return std::move(choice.holes);
  }
  std::vector<std::vector<int>> out;
  std::map<int, int> owner;
  for (size_t l = 0; l < loops.size(); ++l) {
    out.push_back(oriented_loop(loops[l], edges, int(V.rows())));
    for (int v : loops[l])
      if (!owner.emplace(v, int(l)).second)
        throw InvalidInputError("fill_holes: vertex " + std::to_string(v) +
                                " is on two of the given loops (or twice on one)");
  }
  return out;
}

}  // namespace hole_filling

namespace {

double mean_loop_edge_length(const Positions& V, const std::vector<int>& loop) {
  double sum = 0.0;
  for (size_t k = 0; k < loop.size(); ++k)
    sum += (V.row(loop[k]) - V.row(loop[(k + 1) % loop.size()])).norm();
  return sum / double(loop.size());
}

// Appends rows to a matrix.
template <class Matrix>
void append_rows(Matrix& M, const Matrix& rows) {
  const Eigen::Index n = M.rows();
  M.conservativeResize(n + rows.rows(), Eigen::NoChange);
  M.bottomRows(rows.rows()) = rows;
}

// One hole's fill: the new vertices (to be appended after `base` rows) and the new
// triangles, in the caller's indices.
struct Fill {
  Positions vertices;
  Triangles faces;
};

// Triangulates, splits and remeshes one hole at edge length L. The remesh sees only the
// patch and the mesh's triangles at the loop (the valences there), not the whole mesh.
Fill fill_one(const Positions& V, const Triangles& F, const DirectedEdges& edges,
              const std::vector<int>& loop, double L, int base, double unit) {
  // Local rows: the vertices of the triangles at the loop, then the split's midpoints.
  std::vector<int> global;
  std::unordered_map<int, int> local;
  auto add = [&](int v) {
    if (local.emplace(v, int(global.size())).second) global.push_back(v);
    return local.at(v);
  };
  std::vector<int> around;  // the mesh's triangles at the loop vertices
  for (int v : loop) edges.for_each_triangle_at(v, [&](int f) { around.push_back(f); });
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  Triangles T(Eigen::Index(around.size()), 3);
  for (size_t k = 0; k < around.size(); ++k)
    for (int c = 0; c < 3; ++c) T(Eigen::Index(k), c) = add(F(around[k], c));
  std::vector<int> local_loop;
  for (int v : loop) local_loop.push_back(add(v));
  Positions X(Eigen::Index(global.size()), 3);
  for (size_t k = 0; k < global.size(); ++k) X.row(Eigen::Index(k)) = V.row(global[k]);
  const Triangles patch = hole_filling::triangulate_loop(V, loop, edges);
  Triangles local_patch(patch.rows(), 3);
  for (int t = 0; t < patch.rows(); ++t)
    for (int c = 0; c < 3; ++c) local_patch(t, c) = local.at(patch(t, c));
  const auto split = hole_filling::split_inner_edges(X, local_patch, local_loop);
  const int n_fixed = int(X.rows());
  append_rows(X, split.new_vertices);
  append_rows(T, split.faces);
  // About one vertex per two triangles of area sqrt(3)/4 L² (refused before the remesh).
  double area = 0.0;
  for (int t = 0; t < split.faces.rows(); ++t) {
    const auto a = X.row(split.faces(t, 0)), b = X.row(split.faces(t, 1)),
               c = X.row(split.faces(t, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  const double estimate = area / (std::sqrt(3.0) / 2.0 * L * L);
  if (!(estimate <= kMaxFillVertices)) {
    char text[96];
    std::snprintf(text, sizeof text, "%.3g new vertices at edge length %.3g", estimate, L * unit);
    throw InvalidInputError("fill_holes: the hole at vertex " + std::to_string(loop[0]) +
                            " would take about " + text + " (at most " +
                            std::to_string(kMaxFillVertices) +
                            "): give a larger target_edge_length");
  }
  std::vector<bool> free(X.rows(), false);
  for (int v = n_fixed; v < int(X.rows()); ++v) free[v] = true;
  RemeshOptions remesh;
  remesh.target_edge_length = L;
  const RemeshedRegion r = remesh_region(X, T, free, remesh);
  // Its new vertices: the free rows (the unreferenced ones are not free); the fixed rows
  // are the mesh's.
  std::vector<int> to_caller(r.vertices.rows(), -1);
  for (int v = 0; v < n_fixed; ++v) to_caller[v] = global[v];
  Fill fill;
  std::vector<int> rows;
  for (int v = n_fixed; v < int(r.vertices.rows()); ++v)
    if (r.free[v]) {
      to_caller[v] = base + int(rows.size());
      rows.push_back(v);
    }
  fill.vertices.resize(Eigen::Index(rows.size()), 3);
  for (size_t k = 0; k < rows.size(); ++k) fill.vertices.row(Eigen::Index(k)) = r.vertices.row(rows[k]);
  const Eigen::Index kept = Eigen::Index(around.size());  // remesh_region keeps them first
  fill.faces.resize(r.faces.rows() - kept, 3);
  for (Eigen::Index t = kept; t < r.faces.rows(); ++t)
    for (int c = 0; c < 3; ++c) fill.faces(t - kept, c) = to_caller[r.faces(t, c)];
  return fill;
}

// All holes filled at `scale` times their edge lengths, then faired together (the phase
// "fill" first in phase_seconds).
FairingResult fill_and_fair(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                            const std::vector<std::vector<int>>& holes,
                            const std::vector<double>& lengths, double scale,
                            const FairingOptions& options, double unit) {
  Laps laps;
  std::vector<Fill> fills;
  Eigen::Index rows = V.rows(), faces = F.rows();
  for (size_t h = 0; h < holes.size(); ++h) {
    fills.push_back(fill_one(V, F, edges, holes[h], scale * lengths[h], int(rows), unit));
    rows += fills.back().vertices.rows();
    faces += fills.back().faces.rows();
  }
  Positions X(rows, 3);
  Triangles T(faces, 3);
  X.topRows(V.rows()) = V;
  T.topRows(F.rows()) = F;
  rows = V.rows(), faces = F.rows();
  for (const Fill& fill : fills) {
    X.middleRows(rows, fill.vertices.rows()) = fill.vertices;
    T.middleRows(faces, fill.faces.rows()) = fill.faces;
    rows += fill.vertices.rows();
    faces += fill.faces.rows();
  }
  std::vector<bool> free(X.rows(), false);
  for (int v = int(V.rows()); v < int(X.rows()); ++v) free[v] = true;
  const double seconds = laps.lap();
  FairingOptions fairing = options_after(options, seconds);
  fairing.remesh = Remesh::Off;  // the patches are remeshed already
  FairingResult result = fair(X, T, free, nullptr, fairing);
  result.faces = std::move(T);
  result.free = std::move(free);
  result.remeshed = true;
  result.phase_seconds.insert(result.phase_seconds.begin(), {"fill", seconds});
  return result;
}

// fill_holes on V in the working scale (positions divided by `unit`, a power of two).
FairingResult fill_scaled(const Positions& V, const Triangles& F,
                          const std::vector<std::vector<int>>& loops,
                          const FairingOptions& options, double target_edge_length,
                          const HoleRule& rule, double unit) {
  const DirectedEdges edges(F);
  std::vector<OpenLoop> left_open;
  const auto holes = hole_filling::holes_to_fill(V, F, loops, edges, rule, &left_open);
  std::vector<double> lengths;
  for (const auto& loop : holes)
    lengths.push_back(target_edge_length > 0.0 ? target_edge_length
                                               : mean_loop_edge_length(V, loop));
  Laps laps;
  FairingResult result = fill_and_fair(V, F, edges, holes, lengths, 1.0, options, unit);
  const bool failed = !result.converged || result.new_folds > 0;
  const double spent = laps.lap();
  const bool time_left = !(options.time_limit >= 0.0) || spent < options.time_limit;
  const auto added = result.vertices.rows() - V.rows();
  const std::string open_note =
      left_open.empty() ? "" : "; left open: " + hole_filling::describe_open(left_open);
  if (!failed || target_edge_length > 0.0 || !time_left || 4 * added > kMaxFillVertices ||
      result.stop_reason == StopReason::Cancelled) {
    result.message += open_note;
    return result;
  }
  // A ragged loop asks for a finer fill next to it: once more at half the edge length.
  FairingResult finer = fill_and_fair(V, F, edges, holes, lengths, 0.5,
                                      options_after(options, spent), unit);
  const bool finer_ok = finer.converged && finer.new_folds == 0;
  if (finer_ok || (finer.converged && !result.converged)) {
    finer.message += "; filled at half the loops' edge length (at their own it did not " +
                     std::string(result.converged ? "stay free of folds)" : "converge)") +
                     open_note;
    return finer;
  }
  result.message += "; at half the loops' edge length neither (" + finer.message + ")" + open_note;
  return result;
}

}  // namespace

FairingResult fill_holes(const Positions& V, const Triangles& F,
                         const std::vector<std::vector<int>>& loops,
                         const FairingOptions& options, double target_edge_length,
                         const HoleRule& rule) {
  if (!(target_edge_length >= 0.0) || !std::isfinite(target_edge_length))
    throw InvalidInputError("fill_holes: target_edge_length must be finite and >= 0");
  check_mesh(V, F, "fill_holes");
  const double scale = working_scale(V, F, "fill_holes");
  if (scale == 1.0) return fill_scaled(V, F, loops, options, target_edge_length, rule, 1.0);
  // Divided and multiplied by a power of two: exact, the fill sees edges about 1 long.
  FairingResult result =
      fill_scaled(V / scale, F, loops, options, target_edge_length / scale, rule, scale);
  result.vertices *= scale;
  result.vertices.topRows(V.rows()) = V;  // the input's rows, also where V / scale was subnormal
  return result;
}

}  // namespace geofair
