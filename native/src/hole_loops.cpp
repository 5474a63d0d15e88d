// Which boundary loops are holes: the loops of a mesh's border, the rule that leaves outer
// borders open (choose_holes), and the loops a caller gives, checked and oriented
// (hole_filling_internal.h).
#include "geofair/hole_filling.h"

#include "hole_filling_internal.h"
#include "mesh_scale.h"
#include "region.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace geofair {

namespace hole_filling {

// Validates the triangles (indices, manifold, orientation) and the coordinates they use.
void check_mesh(const Positions& V, const Triangles& F, const char* caller) {
  check_triangles(int(V.rows()), F, caller);
  check_finite(V, F, caller);
}

namespace {

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

// The border loops, each in the direction of the missing face, from the smallest start vertex
// on, except that the border edges of a connected piece of border that passes more than once
// through a vertex (holes that touch) are not walked: each such piece is returned in
// `pinched` (its vertices, sorted) with that vertex.
static std::vector<std::vector<int>> manifold_border_loops(const DirectedEdges& edges,
                                                    std::vector<std::pair<std::vector<int>, int>>& pinched) {
  std::map<int, std::vector<int>> next;
  edges.for_each_border_edge([&](int a, int b) { next[b].push_back(a); });
  std::map<int, int> parent;  // union-find over the border's vertices
  auto root = [&](int v) {
    while (parent.at(v) != v) v = parent[v] = parent.at(parent.at(v));
    return v;
  };
  for (const auto& [v, successors] : next) {
    parent.emplace(v, v);
    for (int w : successors) parent.emplace(w, w);
  }
  for (const auto& [v, successors] : next)
    for (int w : successors) {
      const int a = root(v), b = root(w);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::map<int, int> pinch;  // component root -> its first vertex with two successors
  for (const auto& [v, successors] : next)
    if (successors.size() > 1) pinch.emplace(root(v), v);
  std::map<int, std::vector<int>> pieces;
  std::vector<std::vector<int>> loops;
  std::map<int, bool> done;
  for (const auto& [start, successors] : next) {
    (void)successors;
    const int r = root(start);
    if (pinch.count(r)) {
      pieces[r].push_back(start);
      continue;
    }
    if (done[start]) continue;
    std::vector<int> loop;
    for (int v = start; !done[v]; v = next.at(v).front()) {
      done[v] = true;
      loop.push_back(v);
    }
    loops.push_back(std::move(loop));
  }
  for (auto& [r, vertices] : pieces) pinched.push_back({std::move(vertices), pinch.at(r)});
  return loops;
}

std::vector<std::vector<int>> border_loops(const DirectedEdges& edges, const char* caller) {
  std::vector<std::pair<std::vector<int>, int>> pinched;
  auto loops = manifold_border_loops(edges, pinched);
  if (!pinched.empty())
    throw InvalidInputError(std::string(caller) + ": vertex " +
                            std::to_string(pinched.front().second) +
                            " lies on the border twice (two holes, or one hole's border, "
                            "touch there)");
  return loops;
}

HoleChoice choose_holes(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                        const HoleRule& rule, const char* caller) {
  if (rule.max_hole_edges < 0)
    throw InvalidInputError(std::string(caller) + ": max_hole_edges must be >= 0 (0: no limit)");
  HoleChoice out;
  std::vector<std::pair<std::vector<int>, int>> pinched;
  auto loops = manifold_border_loops(edges, pinched);
  for (auto& [vertices, vertex] : pinched)
    out.left_open.push_back(
        {std::move(vertices), "not a simple loop: its border passes more than once through vertex " +
                                  std::to_string(vertex) +
                                  " (holes touch there); give its loops one at a time"});
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

using hole_filling::DirectedEdges;

std::vector<std::vector<int>> boundary_loops(const Positions& V, const Triangles& F) {
  hole_filling::check_mesh(V, F, "boundary_loops");
  return hole_filling::border_loops(DirectedEdges(F), "boundary_loops");
}

HoleChoice holes_to_fill(const Positions& V, const Triangles& F, const HoleRule& rule) {
  hole_filling::check_mesh(V, F, "holes_to_fill");
  const double scale = working_scale(V, F, "holes_to_fill");
  return hole_filling::choose_holes(scale == 1.0 ? V : Positions(V / scale), F, DirectedEdges(F),
                                    rule, "holes_to_fill");
}

}  // namespace geofair
