// Rim::Trim: the teeth and spikes of a hole's rim removed before its fill
// (hole_filling_internal.h, trim_rim).
#include "hole_filling_internal.h"

#include "geofair/hole_filling.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_map>
#include <utility>

namespace geofair::hole_filling {

namespace {

// The loop of the hole grown by `removed` (rows of F), oriented like the input loop, or
// empty where the grown hole's border is not one simple loop clear of other borders.
std::vector<int> grown_loop(const Triangles& F, const DirectedEdges& edges,
                            const std::vector<int>& loop, const std::set<int>& removed,
                            const std::vector<bool>& other_border) {
  const int n = int(loop.size());
  std::set<std::pair<int, int>> hole_edges;  // a -> b in the direction of the missing face
  for (int k = 0; k < n; ++k) hole_edges.insert({loop[k], loop[(k + 1) % n]});
  std::unordered_map<int, int> next;
  bool simple = true;
  auto add = [&](int a, int b) { simple = next.emplace(a, b).second && simple; };
  // The loop's edges whose triangle stays, and the removed triangles' edges to a kept one
  // (x -> y of a removed triangle: the kept twin has y -> x, the missing face x -> y).
  for (int k = 0; k < n; ++k) {
    const int a = loop[k], b = loop[(k + 1) % n];
    if (!removed.count(edges.triangle(b, a))) add(a, b);
  }
  for (int f : removed)
    for (int c = 0; c < 3; ++c) {
      const int x = F(f, c), y = F(f, (c + 1) % 3);
      const int twin = edges.triangle(y, x);
      if (twin < 0) {
        if (!hole_edges.count({y, x})) return {};  // another border: holes would merge
        continue;
      }
      if (!removed.count(twin)) add(x, y);
    }
  if (!simple || next.size() < 3) return {};
  // Walk from the first input loop vertex still on the border (a stable start).
  int start = next.begin()->first;
  for (int v : loop)
    if (next.count(v)) {
      start = v;
      break;
    }
  std::vector<int> out;
  int v = start;
  do {
    if (other_border[size_t(v)] || out.size() >= next.size()) return {};
    out.push_back(v);
    const auto it = next.find(v);
    if (it == next.end()) return {};
    v = it->second;
  } while (v != start);
  if (out.size() != next.size()) return {};  // more than one loop
  return out;
}

double corner_angle(const Positions& V, int at, int b, int c) {
  const Vec3 u = (V.row(b) - V.row(at)).transpose(), w = (V.row(c) - V.row(at)).transpose();
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

// Removes `faces` (all or none) from the hole grown from the input `loop` by `removed`: only
// where it stays one simple loop clear of other borders with at most as many faces removed
// as `loop` has vertices. True where they were; `removed` and `hole_loop` then updated.
bool remove_faces(const Triangles& F, const DirectedEdges& edges, const std::vector<int>& loop,
                  const std::vector<bool>& other_border, const std::vector<int>& faces,
                  std::set<int>& removed, std::vector<int>& hole_loop) {
  std::set<int> trial = removed;
  for (int f : faces) trial.insert(f);
  if (trial.size() == removed.size() || trial.size() > loop.size()) return false;
  std::vector<int> grown = grown_loop(F, edges, loop, trial, other_border);
  if (grown.empty()) return false;
  removed = std::move(trial);
  hole_loop = std::move(grown);
  return true;
}

}  // namespace

TrimmedHole trim_rim(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                     const std::vector<int>& loop, const std::vector<bool>& other_border,
                     const TrimmedHole* start) {
  TrimmedHole out = start ? *start : TrimmedHole{loop, {}};
  std::set<int> removed(out.removed.begin(), out.removed.end());
  for (int round = 0; round < kTrimRounds; ++round) {
    // Per loop vertex, the faces to remove: a tooth alone, or a spike's remaining fan.
    std::vector<std::vector<int>> groups;
    const std::vector<int>& cur = out.loop;
    const int m = int(cur.size());
    for (int i = 0; i < m; ++i) {
      const int v = cur[i], prev = cur[(i + m - 1) % m], next = cur[(i + 1) % m];
      std::vector<int> fan;
      double angle = 0.0;
      edges.for_each_triangle_at(v, [&](int f) {
        if (removed.count(f)) return;
        fan.push_back(f);
        int c = 0;
        while (F(f, c) != v) ++c;
        angle += corner_angle(V, v, F(f, (c + 1) % 3), F(f, (c + 2) % 3));
      });
      if (fan.empty()) continue;
      const bool tooth = fan.size() == 1 && (F.row(fan[0]).array() == prev).any() &&
                         (F.row(fan[0]).array() == next).any();
      if (tooth || angle < kTrimSpikeAngle) groups.push_back(std::move(fan));
    }
    bool changed = false;
    auto try_remove = [&](const std::vector<int>& faces) {
      const bool done = remove_faces(F, edges, loop, other_border, faces, removed, out.loop);
      changed = changed || done;
      return done;
    };
    for (const auto& group : groups)
      if (!try_remove(group) && group.size() > 1)
        for (int f : group) try_remove({f});
    if (!changed) break;
  }
  out.removed.assign(removed.begin(), removed.end());
  return out;
}

TrimmedHole trim_faces(const Triangles& F, const DirectedEdges& edges, const std::vector<int>& loop,
                       const TrimmedHole& now, const std::vector<int>& faces,
                       const std::vector<bool>& other_border) {
  TrimmedHole out = now;
  std::set<int> removed(now.removed.begin(), now.removed.end());
  for (int f : faces) remove_faces(F, edges, loop, other_border, {f}, removed, out.loop);
  out.removed.assign(removed.begin(), removed.end());
  return out;
}

}  // namespace geofair::hole_filling
