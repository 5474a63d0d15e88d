// Hole filling (geofair/hole_filling.h): each hole's chain of fills, from its patch
// (hole_patch.cpp) remeshed and faired to the linear fill, and the filled mesh; which loops
// are holes: hole_loops.cpp.
#include "geofair/hole_filling.h"

#include "common.h"
#include "hole_filling_internal.h"
#include "mesh_scale.h"
#include "region.h"
#include "remesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace geofair {

using hole_filling::DirectedEdges;
using hole_filling::triangle_normal;

const char* fill_method_name(FillMethod method) {
  switch (method) {
    case FillMethod::Intrinsic: return "intrinsic";
    case FillMethod::IntrinsicFiner: return "intrinsic_finer";
    case FillMethod::IntrinsicTrimmed: return "intrinsic_trimmed";
    case FillMethod::G0: return "g0";
    case FillMethod::Linear: return "linear";
    case FillMethod::None: return "none";
  }
  return "none";
}

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

// The rings of the input's triangles around a loop (without `removed`, sorted rows of F):
// first[r] the triangles of ring r (ring 0: those at the loop's vertices).
std::vector<std::vector<int>> rings_around(const Triangles& F, const DirectedEdges& edges,
                                           const std::vector<int>& loop,
                                           const std::vector<int>& removed, int rings) {
  std::vector<std::vector<int>> out(static_cast<size_t>(rings));
  std::unordered_map<int, bool> seen_vertex, seen_face;
  std::vector<int> front = loop;
  for (int v : loop) seen_vertex[v] = true;
  for (int r = 0; r < rings; ++r) {
    std::vector<int> next;
    for (int v : front)
      edges.for_each_triangle_at(v, [&](int f) {
        if (std::binary_search(removed.begin(), removed.end(), f) || seen_face[f]) return;
        seen_face[f] = true;
        out[size_t(r)].push_back(f);
        for (int c = 0; c < 3; ++c)
          if (!seen_vertex[F(f, c)]) {
            seen_vertex[F(f, c)] = true;
            next.push_back(F(f, c));
          }
      });
    std::sort(out[size_t(r)].begin(), out[size_t(r)].end());
    front = std::move(next);
  }
  return out;
}

// Folded edges of the triangles T.row(first .. end - 1): edges among them and with the
// other triangles whose two normals have a non-positive dot product (bench/holes.py's test).
// `others`, if given, gets the rows below `first` on such an edge (sorted, once each).
int fill_folds(const Positions& X, const Triangles& T, Eigen::Index first, Eigen::Index end,
               std::vector<int>* others = nullptr) {
  std::map<std::pair<int, int>, std::vector<Eigen::Index>> by_edge;
  std::unordered_map<int, bool> fill_vertex;
  for (Eigen::Index t = first; t < end; ++t)
    for (int c = 0; c < 3; ++c) fill_vertex[T(t, c)] = true;
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int a = T(t, c), b = T(t, (c + 1) % 3);
      if (fill_vertex.count(a) && fill_vertex.count(b)) by_edge[std::minmax(a, b)].push_back(t);
    }
  auto normal = [&](Eigen::Index t) { return triangle_normal(X, T(t, 0), T(t, 1), T(t, 2)); };
  int folds = 0;
  std::set<int> folded_others;
  for (const auto& [edge, faces] : by_edge) {
    (void)edge;
    auto in_fill = [&](Eigen::Index t) { return t >= first && t < end; };
    if (faces.size() != 2 || (!in_fill(faces[0]) && !in_fill(faces[1]))) continue;
    if (!(normal(faces[0]).dot(normal(faces[1])) <= 0.0)) continue;
    ++folds;
    for (const Eigen::Index t : faces)
      if (t < first) folded_others.insert(int(t));
  }
  if (others) others->assign(folded_others.begin(), folded_others.end());
  return folds;
}

// One fill tried for a hole: the new vertices and triangles in the caller's indices (a
// new vertex k encoded as -(k + 1)), fair()'s result on the hole's submesh, the attempt.
struct Tried {
  FillAttempt attempt;
  FairingResult fairing;
  Positions vertices;
  Triangles faces;
  std::vector<int> removed;  // rows of F removed at the rim (sorted)
  std::vector<int> folded_rim;  // rows of F that fold against the fill (sorted)
  bool made = false;         // false: refused before fair (attempt.message says why)
  bool ok() const { return made && attempt.converged && attempt.folds == 0; }
};

// The rings of input triangles whose vertices the G1 normals are estimated from
// (estimate_boundary_normals: two rings through the surrounding triangles) and one more.
constexpr int kSurroundingRings = 3;

// The first ring of a hole as a submesh of its own: local rows in order of first use by
// the ring's triangles, then the loop's.
struct LocalRing {
  std::vector<int> global;             // local row -> input row
  std::unordered_map<int, int> local;  // input row -> local row
  Triangles faces;                     // the ring's triangles in local rows
  std::vector<int> loop;               // the loop in local rows
};

LocalRing local_ring(const Triangles& F, const std::vector<int>& ring,
                     const std::vector<int>& loop) {
  LocalRing out;
  auto add = [&](int v) {
    if (out.local.emplace(v, int(out.global.size())).second) out.global.push_back(v);
    return out.local.at(v);
  };
  out.faces.resize(Eigen::Index(ring.size()), 3);
  for (size_t k = 0; k < ring.size(); ++k)
    for (int c = 0; c < 3; ++c) out.faces(Eigen::Index(k), c) = add(F(ring[k], c));
  for (int v : loop) out.loop.push_back(add(v));
  return out;
}

// Why a patch of triangles T of X is refused before the remesh at edge length L (about one
// vertex per two triangles of area sqrt(3)/4 L²); empty when it is not.
std::string fill_size_refusal(const Positions& X, const Triangles& T, double L, double unit) {
  double area = 0.0;
  for (int t = 0; t < T.rows(); ++t)
    area += 0.5 * triangle_normal(X, T(t, 0), T(t, 1), T(t, 2)).norm();
  const double estimate = area / (std::sqrt(3.0) / 2.0 * L * L);
  if (estimate <= kMaxFillVertices) return {};
  char text[160];
  std::snprintf(text, sizeof text, "about %.3g new vertices at edge length %.3g (at most %d)",
                estimate, L * unit, kMaxFillVertices);
  return text;
}

// The remeshed first ring with the outer rings appended, for the G1 normals' samples: their
// triangles after the remesh's, their vertices outside the first ring after its rows, fixed.
struct FillSubmesh {
  Positions vertices;
  Triangles faces;
  std::vector<bool> free;
};

FillSubmesh with_outer_rings(const Positions& V, const Triangles& F,
                             const std::vector<std::vector<int>>& rings,
                             const std::unordered_map<int, int>& local, const RemeshedRegion& r) {
  FillSubmesh out{r.vertices, r.faces, r.free};
  std::unordered_map<int, int> outer_row;
  std::vector<int> outer_rows;
  for (size_t ring = 1; ring < rings.size(); ++ring)
    for (int f : rings[ring]) {
      out.faces.conservativeResize(out.faces.rows() + 1, Eigen::NoChange);
      for (int c = 0; c < 3; ++c) {
        const int v = F(f, c);
        const auto it = local.find(v);
        int row;
        if (it != local.end()) {
          row = it->second;
        } else {
          const auto [o, fresh] =
              outer_row.emplace(v, int(out.vertices.rows() + outer_rows.size()));
          if (fresh) outer_rows.push_back(v);
          row = o->second;
        }
        out.faces(out.faces.rows() - 1, c) = row;
      }
    }
  append_rows(out.vertices, gather(V, outer_rows));
  out.free.resize(size_t(out.vertices.rows()), false);
  return out;
}

// fair()'s options for a fill by `method`: no remesh (the patch is a remesh already), the
// fills' own step and iteration limits, and the G0 or the linear fill where the method is one.
FairingOptions fill_fairing_options(const FairingOptions& options, FillMethod method) {
  FairingOptions fairing = options;
  fairing.remesh = Remesh::Off;
  fairing.tuning.newton.max_step = options.tuning.newton.fill_max_step;
  fairing.max_iterations =
      std::min(options.max_iterations, options.tuning.schedule.fill_max_iterations);
  if (method == FillMethod::G0) fairing.boundary = BoundaryCondition::G0;
  if (method == FillMethod::Linear) fairing.outer_fairness = OuterFairness::Bilaplacian;
  return fairing;
}

// Sets out.vertices and out.faces: the remesh's new rows (free, from n_fixed on) as faired,
// and the fill's triangles S.row(first .. end - 1) in the caller's indices (fixed rows are
// input rows, `global` of the local ones; a new vertex k is -(k + 1)).
void fill_in_caller_indices(Tried& out, const std::vector<int>& global, const RemeshedRegion& r,
                            int n_fixed, const Triangles& S, Eigen::Index first,
                            Eigen::Index end) {
  std::vector<int> to_caller(size_t(r.vertices.rows()), 0);
  for (size_t k = 0; k < global.size(); ++k) to_caller[k] = global[k];
  std::vector<int> rows;
  for (int v = n_fixed; v < int(r.vertices.rows()); ++v)
    if (r.free[size_t(v)]) {
      to_caller[size_t(v)] = -(int(rows.size()) + 1);
      rows.push_back(v);
    }
  out.vertices = gather(out.fairing.vertices, rows);
  out.faces.resize(end - first, 3);
  for (Eigen::Index t = first; t < end; ++t)
    for (int c = 0; c < 3; ++c) out.faces(t - first, c) = to_caller[size_t(S(t, c))];
}

// Triangulates, splits and remeshes one hole at edge length L, and fairs it on its own
// submesh: the patch and the input's triangles within kSurroundingRings rings of the loop
// (the remesh sees the first ring alone, for the valences at the loop).
// An attempt whose fill raised: not made, its error as the message.
Tried failed_fill(FillMethod method, const std::vector<int>& removed, const char* what,
                  double seconds) {
  Tried out;
  out.attempt.method = method;
  out.removed = removed;
  out.attempt.message = std::string("failed: ") + what;
  out.attempt.seconds = seconds;
  return out;
}

Tried try_fill(const Positions& V, const Triangles& F, const DirectedEdges& edges,
               const std::vector<int>& loop, const std::vector<int>& removed, double L,
               FillMethod method, const FairingOptions& options, double unit) {
  Laps laps;
  Tried out;
  out.attempt.method = method;
  out.removed = removed;
  const auto rings = rings_around(F, edges, loop, removed, kSurroundingRings);
  // Local rows: the vertices of the first ring, then the split's midpoints, then the rest.
  const LocalRing ring = local_ring(F, rings[0], loop);
  Positions X = gather(V, ring.global);
  Triangles T = ring.faces;
  const Triangles patch =
      hole_filling::triangulate_loop(X, ring.loop, hole_filling::DirectedEdges(T));
  const auto split = hole_filling::split_inner_edges(X, patch, ring.loop);
  const int n_fixed = int(X.rows());
  append_rows(X, split.new_vertices);
  append_rows(T, split.faces);
  out.attempt.message = fill_size_refusal(X, split.faces, L, unit);
  if (!out.attempt.message.empty()) return out;
  std::vector<bool> free(size_t(X.rows()), false);
  for (int v = n_fixed; v < int(X.rows()); ++v) free[size_t(v)] = true;
  // A fill that fails (a linear solve with an explicit iteration, or a submesh that fair
  // refuses, e.g. its cut-off outer ring touching itself) is recorded; the chain goes on.
  try {
    RemeshOptions remesh;
    remesh.target_edge_length = L;
    const RemeshedRegion r = remesh_region(X, T, free, remesh);
    const Eigen::Index kept = Eigen::Index(rings[0].size());  // remesh_region keeps them first
    const Eigen::Index fill_end = r.faces.rows();
    const FillSubmesh sub = with_outer_rings(V, F, rings, ring.local, r);
    const double prepared = laps.lap();
    const FairingOptions fairing = fill_fairing_options(options, method);
    out.fairing = fair(sub.vertices, sub.faces, sub.free, nullptr, fairing);
    out.fairing.phase_seconds.insert(out.fairing.phase_seconds.begin(), {"fill", prepared});
    out.made = true;
    out.attempt.converged = out.fairing.converged;
    std::vector<int> folded;  // rows of the submesh's first ring: rings[0] in order
    out.attempt.folds = fill_folds(out.fairing.vertices, sub.faces, kept, fill_end, &folded);
    for (const int t : folded) out.folded_rim.push_back(rings[0][size_t(t)]);
    std::sort(out.folded_rim.begin(), out.folded_rim.end());
    out.attempt.message = out.fairing.message;
    fill_in_caller_indices(out, ring.global, r, n_fixed, sub.faces, kept, fill_end);
    out.attempt.seconds = prepared + laps.lap();
  } catch (const SolverError& error) {
    return failed_fill(method, removed, error.what(), laps.lap());
  } catch (const InvalidInputError& error) {
    return failed_fill(method, removed, error.what(), laps.lap());
  }
  return out;
}

// Whether `a` is a better fill than `b` (neither converged without folds): made, fewer
// folded edges, then converged; else the earlier (b).
bool better(const Tried& a, const Tried& b) {
  if (!a.made || !b.made) return a.made && !b.made;
  if (a.attempt.folds != b.attempt.folds) return a.attempt.folds < b.attempt.folds;
  return a.attempt.converged && !b.attempt.converged;
}

// A hole as its fills after the rim's trim see it: this hole's trim (`own`: its loop and the
// faces it removed; the input loop and none unless rim="trim" and the rim has something to
// trim) and the faces removed in all, with `committed`.
struct HoleRim {
  hole_filling::TrimmedHole own;
  std::vector<int> removed;

  const std::vector<int>& loop() const { return own.loop; }
  bool trimmed() const { return !own.removed.empty(); }
  // Sets the trim to `trim` (of the input loop) on top of `committed`.
  void set(hole_filling::TrimmedHole trim, const std::vector<int>& committed) {
    own = std::move(trim);
    removed.clear();
    std::set_union(committed.begin(), committed.end(), own.removed.begin(), own.removed.end(),
                   std::back_inserter(removed));
  }
};

HoleRim hole_rim(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                 const std::vector<int>& loop, const std::vector<int>& committed,
                 const std::vector<bool>& other_border, Rim rim) {
  HoleRim out{{loop, {}}, committed};
  if (rim == Rim::Trim) out.set(hole_filling::trim_rim(V, F, edges, loop, other_border), committed);
  return out;
}

// One hole's fallback chain (fill_holes): its record and the fill kept.
struct Chain {
  HoleFill record;
  Tried kept;
  bool cancelled = false;
};

// A hole's chain done: its record from the fill kept, or why none was made. `committed`:
// as fill_one_hole's.
Chain finished(Chain chain, const std::vector<int>& committed) {
  HoleFill& h = chain.record;
  if (!chain.kept.made) {
    h.reason = chain.cancelled ? "cancelled"
                               : "cannot be filled: it would take " + h.attempts.front().message;
    return chain;
  }
  const Tried& k = chain.kept;
  h.method = k.attempt.method;
  h.converged = k.attempt.converged;
  h.folds = k.attempt.folds;
  h.residual = k.fairing.residual;
  h.new_vertices = int(k.vertices.rows());
  h.new_faces = int(k.faces.rows());
  std::set_difference(k.removed.begin(), k.removed.end(), committed.begin(), committed.end(),
                      std::back_inserter(h.removed_faces));
  return chain;
}

// Tries the fills of one hole in fill_holes' order and keeps the first that converges
// without a folded edge, else the best (better). `committed`: rows of F removed for the
// holes before (sorted); `spent`: seconds of the call so far, advanced here.
Chain fill_one_hole(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                    const std::vector<int>& loop, const std::vector<int>& committed,
                    const std::vector<bool>& other_border, double target_edge_length, Rim rim,
                    const FairingOptions& options, double unit, double& spent) {
  Chain chain;
  chain.record.loop = loop;
  Laps watch;
  std::vector<int> last_folded_rim;  // the last fill's (Tried::folded_rim)
  auto time_left = [&] { return has_time_left(options, spent); };
  // Tries one fill; true once the chain is done (a fill without folds, or cancelled).
  auto attempt = [&](const std::vector<int>& hole, const std::vector<int>& removed, double L,
                     FillMethod method) {
    FairingOptions now = options_after(options, spent);
    // Out of time, the linear fill (one linear solve) is still made: every hole is closed.
    if (method == FillMethod::Linear && !time_left()) {
      now.time_limit = -1.0;
      now.deadline.reset();
    }
    Tried tried = try_fill(V, F, edges, hole, removed, L, method, now, unit);
    spent += watch.lap();
    last_folded_rim = tried.folded_rim;
    chain.record.attempts.push_back(tried.attempt);
    chain.cancelled = tried.made && tried.fairing.stop_reason == StopReason::Cancelled;
    if (tried.ok() || better(tried, chain.kept)) chain.kept = std::move(tried);
    return chain.kept.ok() || chain.cancelled;
  };
  auto finish = [&] { return finished(std::move(chain), committed); };
  const double L = target_edge_length > 0.0 ? target_edge_length : mean_loop_edge_length(V, loop);
  const bool linear_only = options.outer_fairness == OuterFairness::Bilaplacian;
  const FillMethod first = linear_only                                  ? FillMethod::Linear
                           : options.boundary == BoundaryCondition::G1 ? FillMethod::Intrinsic
                                                                        : FillMethod::G0;
  if (!time_left()) {
    attempt(loop, committed, L, FillMethod::Linear);
    return finish();
  }
  if (attempt(loop, committed, L, first)) return finish();
  if (!chain.kept.made) return finish();  // over the size limit: no other fill is smaller
  const Eigen::Index first_size = chain.kept.vertices.rows();
  if (linear_only) return finish();
  // With rim="trim", a rim that has something to trim is trimmed before the finer fill: the
  // folds of a ragged rim sit at its teeth and slits, which a finer fill keeps.
  HoleRim hole = hole_rim(V, F, edges, loop, committed, other_border, rim);
  auto L_hole = [&] {
    return hole.trimmed() && target_edge_length <= 0.0 ? mean_loop_edge_length(V, hole.loop()) : L;
  };
  if (hole.trimmed() && time_left() &&
      attempt(hole.loop(), hole.removed, L_hole(), FillMethod::IntrinsicTrimmed))
    return finish();
  // Then the input triangles that fold against the last fill are trimmed too, and the hole
  // filled again (a crumpled rim, whose G1 normals no smooth fill meets). The later fills
  // take the last rim: on the corpus its finer fill mends holes that earlier rims' do not.
  for (int round = 0; rim == Rim::Trim && round < kFoldTrimRounds && time_left(); ++round) {
    hole_filling::TrimmedHole grown =
        hole_filling::trim_faces(F, edges, loop, hole.own, last_folded_rim, other_border);
    if (grown.removed.size() == hole.own.removed.size()) break;
    grown = hole_filling::trim_rim(V, F, edges, loop, other_border, &grown);  // new teeth
    hole.set(std::move(grown), committed);
    if (attempt(hole.loop(), hole.removed, L_hole(), FillMethod::IntrinsicTrimmed)) return finish();
  }
  // Half the edge length: four times the vertices; not for large fills (their time). On the
  // input's rim, then on the trimmed one.
  if (target_edge_length <= 0.0 && first_size <= kMaxFinerFillVertices) {
    if (time_left() && attempt(loop, committed, 0.5 * L, FillMethod::IntrinsicFiner))
      return finish();
    if (hole.trimmed() && time_left() &&
        attempt(hole.loop(), hole.removed, 0.5 * L_hole(), FillMethod::IntrinsicFiner))
      return finish();
  }
  if (first == FillMethod::Intrinsic && time_left() &&
      attempt(hole.loop(), hole.removed, L_hole(), FillMethod::G0))
    return finish();
  attempt(hole.loop(), hole.removed, L_hole(), FillMethod::Linear);
  return finish();
}

std::string plural(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// result.message of fill_holes: one clause per method, the folds and what was removed.
std::string fill_summary(const std::vector<HoleFill>& holes, bool cancelled) {
  std::map<FillMethod, size_t> by_method;
  size_t filled = 0, open = 0, unconverged = 0, removed = 0;
  int folds = 0;
  for (const HoleFill& h : holes) {
    if (h.method == FillMethod::None) {
      ++open;
      continue;
    }
    ++filled, ++by_method[h.method];
    unconverged += !h.converged;
    folds += h.folds;
    removed += h.removed_faces.size();
  }
  std::string text = plural(filled, "hole", "holes") + " filled";
  std::string parts;
  for (const auto& [method, count] : by_method)
    parts += std::string(parts.empty() ? "" : ", ") + std::to_string(count) + " " +
             fill_method_name(method);
  if (!parts.empty()) text += " (" + parts + ")";
  text += unconverged ? ", " + std::to_string(unconverged) + " not converged" : ", converged";
  text += ", " + plural(size_t(folds), "folded edge", "folded edges");
  if (removed) text += ", " + plural(removed, "input face", "input faces") + " removed at the rim";
  if (open) text += "; " + plural(open, "hole", "holes") + " not filled";
  if (cancelled) text = "cancelled; " + text;
  return text;
}

// The chains of the holes in order and the rows of F removed for them (sorted).
struct Fills {
  std::vector<Chain> chains;
  std::vector<int> committed;
  bool cancelled = false;
};

// Fills the holes one after another (fill_one_hole); once one is cancelled, the rest are
// recorded as cancelled. `laps` has timed the call so far.
Fills fill_each_hole(const Positions& V, const Triangles& F, const DirectedEdges& edges,
                     const std::vector<std::vector<int>>& holes, double target_edge_length,
                     Rim rim, const FairingOptions& options, double unit, Laps& laps) {
  // Vertices on a border: a trimmed rim must not reach another hole or border.
  std::vector<bool> border(size_t(V.rows()), false);
  edges.for_each_border_edge([&](int a, int b) { border[size_t(a)] = border[size_t(b)] = true; });
  Fills fills;
  double spent = laps.lap();
  for (const auto& loop : holes) {
    if (fills.cancelled) {
      Chain skipped;
      skipped.record.loop = loop;
      skipped.record.reason = "cancelled";
      fills.chains.push_back(std::move(skipped));
      continue;
    }
    for (int v : loop) border[size_t(v)] = false;
    Chain chain = fill_one_hole(V, F, edges, loop, fills.committed, border, target_edge_length,
                                rim, options, unit, spent);
    for (int v : loop) border[size_t(v)] = true;
    fills.cancelled = chain.cancelled;
    if (chain.kept.made && chain.kept.removed.size() > fills.committed.size()) {
      fills.committed = chain.kept.removed;
      for (int f : chain.record.removed_faces)
        for (int c = 0; c < 3; ++c) border[size_t(F(f, c))] = true;
    }
    fills.chains.push_back(std::move(chain));
  }
  return fills;
}

// result.vertices and result.faces: the input's rows, then each fill's new vertices; the
// input's faces less the removed ones (in order), then each fill's triangles.
void assemble_mesh(FillResult& result, const Positions& V, const Triangles& F,
                   const Fills& fills) {
  const std::vector<int>& committed = fills.committed;
  Eigen::Index rows = V.rows(), faces = F.rows() - Eigen::Index(committed.size());
  for (const Chain& c : fills.chains) rows += c.kept.vertices.rows(), faces += c.kept.faces.rows();
  result.vertices.resize(rows, 3);
  result.faces.resize(faces, 3);
  result.vertices.topRows(V.rows()) = V;
  Eigen::Index row = V.rows(), face = 0;
  for (int f = 0; f < F.rows(); ++f)
    if (!std::binary_search(committed.begin(), committed.end(), f))
      result.faces.row(face++) = F.row(f);
  for (const Chain& c : fills.chains) {
    const Tried& k = c.kept;
    if (!k.made) continue;
    result.vertices.middleRows(row, k.vertices.rows()) = k.vertices;
    for (Eigen::Index t = 0; t < k.faces.rows(); ++t, ++face)
      for (int j = 0; j < 3; ++j) {
        const int v = k.faces(t, j);
        result.faces(face, j) = v >= 0 ? v : int(row) - v - 1;
      }
    row += k.vertices.rows();
  }
}

// The fills' fair() results as the call's: converged and the stop reason over all, the largest
// residual, the sums of folds, iterations and phase seconds (by name), the first fill's
// iteration record and the largest fill's levels. A hole without a fill is not converged.
void merge_fairings(FillResult& result, const std::vector<Chain>& chains, bool cancelled) {
  result.converged = true;
  result.stop_reason = cancelled ? StopReason::Cancelled : StopReason::Converged;
  std::map<std::string, size_t> phase_index;
  Eigen::Index largest = -1;
  bool first_fill = true;
  for (const Chain& c : chains) {
    const Tried& k = c.kept;
    if (!k.made) {
      result.converged = false;
      continue;
    }
    const FairingResult& r = k.fairing;
    if (!r.converged && result.converged && !cancelled) result.stop_reason = r.stop_reason;
    result.converged = result.converged && r.converged;
    result.residual = std::max(result.residual, r.residual);
    result.folds += k.attempt.folds;
    result.iterations += r.iterations;
    result.newton_iterations += r.newton_iterations;
    if (first_fill) result.iteration = r.iteration, first_fill = false;
    if (k.vertices.rows() > largest) {
      largest = k.vertices.rows();
      result.iterations_per_level = r.iterations_per_level;
      result.vertices_per_level = r.vertices_per_level;
    }
    for (const auto& [name, seconds] : r.phase_seconds) {
      const auto [it, fresh] = phase_index.emplace(name, result.phase_seconds.size());
      if (fresh) result.phase_seconds.push_back({name, 0.0});
      result.phase_seconds[it->second].second += seconds;
    }
  }
}

// Input rows the rim's trim left in no face of the result: vertices of the removed rows of F
// (sorted) that no face uses.
std::vector<int> unreferenced_rows(const FillResult& result, Eigen::Index n, const Triangles& F,
                                   const std::vector<int>& removed) {
  std::vector<int> out;
  if (removed.empty()) return out;
  std::vector<bool> used(size_t(result.vertices.rows()), false), was(size_t(n), false);
  for (Eigen::Index t = 0; t < result.faces.rows(); ++t)
    for (int j = 0; j < 3; ++j) used[size_t(result.faces(t, j))] = true;
  for (int f : removed)
    for (int j = 0; j < 3; ++j) was[size_t(F(f, j))] = true;
  for (int v = 0; v < int(n); ++v)
    if (was[size_t(v)] && !used[size_t(v)]) out.push_back(v);
  return out;
}

// fill_holes on V in the working scale (positions divided by `unit`, a power of two).
FillResult fill_scaled(const Positions& V, const Triangles& F,
                       const std::vector<std::vector<int>>& loops, const FairingOptions& options,
                       double target_edge_length, const HoleRule& rule, Rim rim, double unit) {
  Laps laps;
  const DirectedEdges edges(F);
  std::vector<OpenLoop> left_open;
  const auto holes = hole_filling::holes_to_fill(V, F, loops, edges, rule, &left_open);
  Fills fills = fill_each_hole(V, F, edges, holes, target_edge_length, rim, options, unit, laps);
  // Refused: no hole can be filled (each over the size limit).
  if (!fills.cancelled && std::none_of(fills.chains.begin(), fills.chains.end(),
                                       [](const Chain& c) { return c.kept.made; }))
    throw InvalidInputError("fill_holes: the hole at vertex " +
                            std::to_string(fills.chains.front().record.loop[0]) + " would take " +
                            fills.chains.front().record.attempts.front().message +
                            ": give a larger target_edge_length");
  FillResult result;
  assemble_mesh(result, V, F, fills);
  merge_fairings(result, fills.chains, fills.cancelled);
  for (Chain& c : fills.chains) result.holes.push_back(std::move(c.record));
  result.new_folds = result.folds;
  result.message = fill_summary(result.holes, fills.cancelled);
  if (!left_open.empty()) result.message += "; left open: " + hole_filling::describe_open(left_open);
  for (auto& open : left_open) {
    HoleFill h;
    h.loop = std::move(open.loop);
    h.reason = std::move(open.reason);
    result.holes.push_back(std::move(h));
  }
  const Eigen::Index rows = result.vertices.rows();
  result.free.assign(size_t(rows), false);
  for (Eigen::Index v = V.rows(); v < rows; ++v) result.free[size_t(v)] = true;
  result.remeshed = true;
  result.origin_face.assign(size_t(rows), -1);
  result.origin_barycentric = Positions::Zero(rows, 3);
  result.removed_faces = fills.committed;
  result.unreferenced = unreferenced_rows(result, V.rows(), F, fills.committed);
  return result;
}

}  // namespace

FillResult fill_holes(const Positions& V, const Triangles& F,
                      const std::vector<std::vector<int>>& loops, const FairingOptions& options,
                      double target_edge_length, const HoleRule& rule, Rim rim) {
  if (!(target_edge_length >= 0.0) || !std::isfinite(target_edge_length))
    throw InvalidInputError("fill_holes: target_edge_length must be finite and >= 0");
  check_fairing_options(options);  // here: a fill's fair() that refuses is only recorded
  hole_filling::check_mesh(V, F, "fill_holes");
  const double scale = working_scale(V, F, "fill_holes");
  if (scale == 1.0) return fill_scaled(V, F, loops, options, target_edge_length, rule, rim, 1.0);
  // Divided and multiplied by a power of two: exact, the fill sees edges about 1 long.
  FillResult result =
      fill_scaled(V / scale, F, loops, options, target_edge_length / scale, rule, rim, scale);
  result.vertices *= scale;
  result.vertices.topRows(V.rows()) = V;  // the input's rows, also where V / scale was subnormal
  return result;
}

}  // namespace geofair
