// Isotropic remeshing of a fairing region on OpenMesh (Botsch & Kobbelt 2004, "A remeshing
// approach to multiresolution modeling", section 4): splits, collapses, valence flips and
// tangential relaxation, each moved vertex projected back onto the input region.
// docs/DESIGN_NOTES.md, "Remeshing the region", says why the remesher is our own.
#include "remesh.h"

#include "region.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>

namespace geofair {
namespace {

struct RemeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<RemeshTraits>;
using VH = OpenMesh::VertexHandle;
using HH = OpenMesh::HalfedgeHandle;
using EH = OpenMesh::EdgeHandle;
using FH = OpenMesh::FaceHandle;

// Bounds of Botsch & Kobbelt 2004 relative to the target edge length L.
constexpr double kSplitAbove = 4.0 / 3.0;
constexpr double kCollapseBelow = 4.0 / 5.0;
// Shape of a triangle: twice its area over its longest edge squared (√3/2 equilateral, 0
// degenerate). No operation may leave a triangle thinner than this, or thinner than the
// triangle it replaces where that was thinner already; except that a split of a triangle's
// longest edge may halve its shape (kLongestEdgeSplit): longest-edge bisection keeps the
// smallest angle above half the input's (Rivara 1984), while splits of other edges would
// ratchet shapes down without bound.
constexpr double kMinShape = 0.05;
// The fraction of the bound above that a split of a triangle's longest edge must keep: a
// midpoint's children keep half the shape; the rest is room for the projection's offset.
constexpr double kLongestEdgeSplit = 0.45;
// Passes of split_long_edges per iteration.
constexpr int kSplitPasses = 10;

std::string prefix() { return "remesh_region: "; }

Vec3 eig(const Mesh::Point& p) { return Vec3(p[0], p[1], p[2]); }
Mesh::Point om(const Vec3& p) { return Mesh::Point(p.x(), p.y(), p.z()); }

double shape(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return longest > 0.0 ? (b - a).cross(c - a).norm() / longest : 0.0;
}

// Whether triangle (a, b, c), replacing one of normal `before` (a cross product) and shape
// `was`, faces the same way and keeps `fraction` of its shape bound (kMinShape).
bool keeps_shape(const Vec3& before, double was, const Vec3& a, const Vec3& b, const Vec3& c,
                 double fraction = 1.0) {
  const double s = shape(a, b, c);
  return (b - a).cross(c - a).dot(before) > 0.0 && s > 0.0 &&
         s >= fraction * std::min(kMinShape, was);
}

// keeps_shape against the old triangle (p, q, r).
bool keeps_shape(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& a, const Vec3& b,
                 const Vec3& c, double fraction = 1.0) {
  return keeps_shape((q - p).cross(r - p), shape(p, q, r), a, b, c, fraction);
}

// Closest point on triangle (a, b, c) to p, as barycentric coordinates (Ericson,
// Real-Time Collision Detection, section 5.1.5).
Vec3 closest_barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return {1, 0, 0};  // degenerate triangle: its first corner
  const double v = vb / sum, w = vc / sum;
  return {1 - v - w, v, w};
}

// A point on the input surface: face of F, barycentric coordinates, and the position
// Σ b_k V[F(face, k)].
struct SurfacePoint {
  int face = -1;
  Vec3 bary = Vec3::Zero();
  Vec3 position = Vec3::Zero();
  bool on_border = false;  ///< on an edge or corner of the input region's border
};

// Closest points on a set of triangles of (V, F), through a uniform grid of cells: each
// triangle is listed in the cells its bounding box meets; a query searches cubic shells of
// cells around the point until the nearest hit is closer than the next shell.
class SurfaceProjector {
 public:
  SurfaceProjector(const Positions& V, const Triangles& F, std::vector<int> faces, double cell)
      : V_(V), F_(F), faces_(std::move(faces)) {
    mark_border_edges();
    lo_ = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo_;
    for (int f : faces_)
      for (int k = 0; k < 3; ++k) {
        lo_ = lo_.cwiseMin(Vec3(V.row(F(f, k))));
        hi = hi.cwiseMax(Vec3(V.row(F(f, k))));
      }
    // Cells of about an edge length; at most 1e6 along an axis (keys fit in 64 bits).
    const Vec3 extent = (hi - lo_).cwiseMax(0.0);
    h_ = std::max({cell, 1e-6 * extent.maxCoeff(), std::numeric_limits<double>::min()});
    for (int d = 0; d < 3; ++d) dims_[d] = std::int64_t(extent[d] / h_) + 1;
    std::vector<std::pair<std::int64_t, int>> entries;
    for (int t = 0; t < int(faces_.size()); ++t) {
      const int f = faces_[t];
      Vec3 a = V.row(F(f, 0)), b = a;
      for (int k = 1; k < 3; ++k) {
        a = a.cwiseMin(Vec3(V.row(F(f, k))));
        b = b.cwiseMax(Vec3(V.row(F(f, k))));
      }
      const auto i0 = cell_of(a), i1 = cell_of(b);
      for (std::int64_t i = i0[0]; i <= i1[0]; ++i)
        for (std::int64_t j = i0[1]; j <= i1[1]; ++j)
          for (std::int64_t k = i0[2]; k <= i1[2]; ++k) entries.emplace_back(key(i, j, k), t);
    }
    std::sort(entries.begin(), entries.end());
    items_.resize(entries.size());
    for (std::size_t e = 0; e < entries.size(); ++e) {
      items_[e] = entries[e].second;
      auto [it, added] = cells_.try_emplace(entries[e].first, int(e), int(e) + 1);
      if (!added) it->second.second = int(e) + 1;
    }
  }

  SurfacePoint closest(const Vec3& p) const {
    SurfacePoint best;
    double best_d2 = std::numeric_limits<double>::infinity();
    const auto c = cell_of(p);
    double inset = h_;
    for (int d = 0; d < 3; ++d) {
      const double x = p[d] - lo_[d] - double(c[d]) * h_;  // in [0, h) inside the grid
      inset = std::min({inset, x, h_ - x});
    }
    inset = std::max(inset, 0.0);
    std::int64_t reach = 0;  // shells beyond the grid on every side are empty
    for (int d = 0; d < 3; ++d) reach = std::max({reach, c[d], dims_[d] - 1 - c[d]});
    for (std::int64_t r = 0; r <= reach; ++r) {
      Cell first, last;  // the shell's box, clipped to the grid
      for (int d = 0; d < 3; ++d) {
        first[d] = std::max<std::int64_t>(c[d] - r, 0);
        last[d] = std::min<std::int64_t>(c[d] + r, dims_[d] - 1);
      }
      for (std::int64_t i = first[0]; i <= last[0]; ++i)
        for (std::int64_t j = first[1]; j <= last[1]; ++j)
          for (std::int64_t k = first[2]; k <= last[2]; ++k)
            if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) == r)
              scan(key(i, j, k), p, best, best_d2);
      // Cells beyond shell r lie at least r·h + (p's distance to its cell's faces) from p.
      const double reach_r = double(r) * h_ + inset;
      if (best.face >= 0 && best_d2 <= reach_r * reach_r) break;
    }
    return best;
  }

 private:
  using Cell = std::array<std::int64_t, 3>;

  // The triangles listed in cell `key`, against the best point so far.
  void scan(std::int64_t key, const Vec3& p, SurfacePoint& best, double& best_d2) const {
    const auto it = cells_.find(key);
    if (it == cells_.end()) return;
    for (int e = it->second.first; e < it->second.second; ++e) {
      const int t = items_[e], f = faces_[t];
      const Vec3 a = V_.row(F_(f, 0)), b = V_.row(F_(f, 1)), c = V_.row(F_(f, 2));
      const Vec3 w = closest_barycentric(p, a, b, c);
      const Vec3 q = w[0] * a + w[1] * b + w[2] * c;
      const double d2 = (q - p).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        // Edge k (corner k to k+1) holds the points whose coordinate k+2 is exactly 0.
        bool on_border = false;
        for (int k = 0; k < 3; ++k) on_border |= (border_[t] >> k & 1) && w[(k + 2) % 3] == 0.0;
        best = {f, w, q, on_border};
      }
    }
  }
  // border_[t] bit k: edge k of faces_[t] (corner k to k+1) has no other region face.
  void mark_border_edges() {
    const std::int64_t n = V_.rows();
    std::vector<std::int64_t> directed;
    for (int f : faces_)
      for (int k = 0; k < 3; ++k) directed.push_back(F_(f, k) * n + F_(f, (k + 1) % 3));
    std::sort(directed.begin(), directed.end());
    border_.assign(faces_.size(), 0);
    for (std::size_t t = 0; t < faces_.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::int64_t opposite = F_(faces_[t], (k + 1) % 3) * n + F_(faces_[t], k);
        if (!std::binary_search(directed.begin(), directed.end(), opposite))
          border_[t] |= std::uint8_t(1 << k);
      }
  }
  Cell cell_of(const Vec3& p) const {
    Cell c;
    for (int d = 0; d < 3; ++d) {
      const double x = std::floor((p[d] - lo_[d]) / h_);
      c[d] = std::int64_t(std::clamp(x, -1e12, 1e12));
    }
    return c;
  }
  std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (i * dims_[1] + j) * dims_[2] + k;
  }

  const Positions& V_;
  const Triangles& F_;
  std::vector<int> faces_;
  std::vector<std::uint8_t> border_;
  Vec3 lo_;
  double h_ = 1.0;
  Cell dims_{1, 1, 1};
  std::unordered_map<std::int64_t, std::pair<int, int>> cells_;
  std::vector<int> items_;
};

// The input's sizes, indices and options, and that a vertex is free (the region's own
// checks: Remesher's constructor and build).
void check_input(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                 const RemeshOptions& options) {
  check_indices(V, F, free, "remesh_region");
  if (std::find(free.begin(), free.end(), true) == free.end())
    throw InvalidInputError(prefix() + "no vertex is free");
  if (options.iterations < 0) throw InvalidInputError(prefix() + "iterations must be >= 0");
  if (!std::isfinite(options.target_edge_length))
    throw InvalidInputError(prefix() + "target_edge_length must be finite");
}

// Isotropic remesher of one region (Botsch & Kobbelt 2004): the region's triangles as an
// OpenMesh mesh whose fixed vertices never move and whose border edges never change.
class Remesher {
 public:
  Remesher(const Positions& V, const Triangles& F, const std::vector<bool>& free,
           const RemeshOptions& options);
  void run(int iterations) {
    for (int k = 0; k < iterations; ++k) {
      split_long_edges();
      collapse_short_edges();
      equalize_valences();
      relax_tangentially();
    }
  }
  RemeshedRegion result();

 private:
  void build(const std::vector<int>& local_to_global);
  void set_valence_offsets(const std::vector<int>& global_to_local);
  void split_long_edges();
  bool split_ok(EH e, const Vec3& p) const;
  void collapse_short_edges();
  bool collapse_ok(HH h);
  void equalize_valences();
  bool flip_improves(EH e) const;
  void relax_tangentially();
  Vec3 point(VH v) const { return eig(mesh_.point(v)); }
  double length(EH e) const { return mesh_.calc_edge_length(e); }
  bool is_free(VH v) const { return !mesh_.property(fixed_, v); }
  int deviation(VH v, int valence) const {
    const int d = valence + mesh_.property(valence_offset_, v) - 6;
    return d * d;
  }
  void place(VH v, const SurfacePoint& s) {
    mesh_.point(v) = om(s.position);
    mesh_.property(origin_face_, v) = s.face;
    mesh_.property(origin_bary_, v) = {s.bary.x(), s.bary.y(), s.bary.z()};
  }

  const Positions& V_;
  const Triangles& F_;
  const std::vector<bool>& free_;
  std::vector<int> region_faces_;  // input faces with a free vertex
  Mesh mesh_;
  double L_ = 0.0;
  OpenMesh::VPropHandleT<bool> fixed_;
  OpenMesh::VPropHandleT<int> global_;  // input row, -1 for a new vertex
  OpenMesh::VPropHandleT<int> origin_face_;
  OpenMesh::VPropHandleT<std::array<double, 3>> origin_bary_;
  // Edges of the vertex outside the region, plus 2 on the mesh border (target valence 4):
  // a vertex is regular where its region valence plus this offset is 6.
  OpenMesh::VPropHandleT<int> valence_offset_;
  std::unique_ptr<SurfaceProjector> projector_;
};

Remesher::Remesher(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const RemeshOptions& options)
    : V_(V), F_(F), free_(free) {
  const int nv = int(V.rows());
  std::vector<int> global_to_local(nv, -1), local_to_global;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (free[F(f, 0)] || free[F(f, 1)] || free[F(f, 2)]) region_faces_.push_back(int(f));
  for (int f : region_faces_)
    for (int c = 0; c < 3; ++c) global_to_local[F(f, c)] = 0;
  for (int v = 0; v < nv; ++v) {
    if (free[v] && global_to_local[v] < 0)
      throw InvalidInputError(prefix() + "free vertex " + std::to_string(v) +
                              " belongs to no triangle");
    if (global_to_local[v] < 0) continue;
    if (!V.row(v).allFinite())
      throw InvalidInputError(prefix() + "vertex " + std::to_string(v) +
                              " has a non-finite coordinate");
    global_to_local[v] = int(local_to_global.size());
    local_to_global.push_back(v);
  }
  build(local_to_global);
  set_valence_offsets(global_to_local);
  // Target length: the option, else the mean length of the region's border edges (of all
  // its edges where it has no border).
  double sum = 0.0, all = 0.0;
  int count = 0;
  for (EH e : mesh_.edges()) {
    all += length(e);
    if (mesh_.is_boundary(e)) sum += length(e), ++count;
  }
  L_ = options.target_edge_length > 0.0 ? options.target_edge_length
       : count > 0                      ? sum / count
                                        : all / double(mesh_.n_edges());
  if (!(L_ > 0.0) || !std::isfinite(L_))
    throw InvalidInputError(prefix() + "the region's edges have zero length");
  double mean_edge = all / double(mesh_.n_edges());
  projector_ = std::make_unique<SurfaceProjector>(V, F, region_faces_, std::max(mean_edge, L_));
}

// The region's triangles as an OpenMesh mesh with the vertex properties; InvalidInputError
// where they are not an oriented 2-manifold or a free vertex lies on the mesh border.
void Remesher::build(const std::vector<int>& local_to_global) {
  omerr().disable();  // failed add_face calls become exceptions below
  mesh_.request_vertex_status();
  mesh_.request_edge_status();
  mesh_.request_halfedge_status();
  mesh_.request_face_status();
  mesh_.add_property(fixed_);
  mesh_.add_property(global_);
  mesh_.add_property(origin_face_);
  mesh_.add_property(origin_bary_);
  mesh_.add_property(valence_offset_);
  std::vector<VH> handle(V_.rows());
  for (int v : local_to_global) {
    handle[v] = mesh_.add_vertex(om(Vec3(V_.row(v))));
    mesh_.property(fixed_, handle[v]) = !free_[v];
    mesh_.property(global_, handle[v]) = v;
    mesh_.property(origin_face_, handle[v]) = -1;
    mesh_.property(origin_bary_, handle[v]) = {0.0, 0.0, 0.0};
  }
  for (int f : region_faces_) {
    const VH a = handle[F_(f, 0)], b = handle[F_(f, 1)], c = handle[F_(f, 2)];
    if (a == b || b == c || a == c)
      throw InvalidInputError(prefix() + "triangle " + std::to_string(f) + " repeats a vertex");
    if (!mesh_.add_face(a, b, c).is_valid())
      throw InvalidInputError(prefix() + "triangle " + std::to_string(f) +
                              " makes an edge or vertex of the region non-manifold or is "
                              "oriented against its neighbour (the region must be a "
                              "consistently oriented 2-manifold)");
    // A free vertex starts at a corner of one of its input triangles.
    for (int k = 0; k < 3; ++k)
      if (free_[F_(f, k)] && mesh_.property(origin_face_, handle[F_(f, k)]) < 0) {
        mesh_.property(origin_face_, handle[F_(f, k)]) = f;
        std::array<double, 3> corner{0.0, 0.0, 0.0};
        corner[k] = 1.0;
        mesh_.property(origin_bary_, handle[F_(f, k)]) = corner;
      }
  }
  for (VH v : mesh_.vertices())
    if (is_free(v) && mesh_.is_boundary(v))
      throw InvalidInputError(prefix() + "free vertex " +
                              std::to_string(mesh_.property(global_, v)) +
                              " lies on the mesh border (its triangles do not close around "
                              "it)");
}

// valence_offset_ of the region's fixed vertices, from the edges of F outside the region.
void Remesher::set_valence_offsets(const std::vector<int>& global_to_local) {
  // Per region vertex: its edges in F (distinct), its triangles in F.
  std::vector<std::int64_t> edges;
  std::vector<int> faces(mesh_.n_vertices(), 0);
  const std::int64_t n = V_.rows();
  for (Eigen::Index f = 0; f < F_.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F_(f, k), b = F_(f, (k + 1) % 3);
      if (global_to_local[a] >= 0) ++faces[global_to_local[a]];
      if (global_to_local[a] >= 0 || global_to_local[b] >= 0)
        edges.push_back(std::min(a, b) * n + std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<int> valence(mesh_.n_vertices(), 0);
  for (std::int64_t e : edges)
    for (std::int64_t v : {e / n, e % n})
      if (global_to_local[v] >= 0) ++valence[global_to_local[v]];
  for (VH v : mesh_.vertices()) {
    const int outside = valence[v.idx()] - int(mesh_.valence(v));
    const bool border = valence[v.idx()] > faces[v.idx()];
    mesh_.property(valence_offset_, v) = is_free(v) ? 0 : outside + (border ? 2 : 0);
  }
}

// Whether splitting edge e at p keeps the four new triangles' orientation and shape (a
// triangle whose longest edge e is: kLongestEdgeSplit of it).
bool Remesher::split_ok(EH e, const Vec3& p) const {
  for (int k = 0; k < 2; ++k) {
    const HH h = mesh_.halfedge_handle(e, k);  // its triangle (a, b, c): (a, p, c), (p, b, c)
    const Vec3 a = point(mesh_.from_vertex_handle(h)), b = point(mesh_.to_vertex_handle(h));
    const Vec3 c = point(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h)));
    const double ab = (b - a).squaredNorm();
    const bool longest = ab >= (c - b).squaredNorm() && ab >= (a - c).squaredNorm();
    const double fraction = longest ? kLongestEdgeSplit : 1.0;
    if (!keeps_shape(a, b, c, a, p, c, fraction) || !keeps_shape(a, b, c, p, b, c, fraction))
      return false;
  }
  return true;
}

// Splits the edges longer than 4/3 L at their midpoints projected onto the input, longest
// first, where that keeps the triangles' shape (split_ok); the region's border edges are
// kept. Repeated on the edges the splits made, at most kSplitPasses times (bisecting the
// spokes of a sliver fan can go on for long otherwise).
void Remesher::split_long_edges() {
  const double limit = kSplitAbove * L_;
  std::vector<std::pair<double, int>> long_edges;
  for (int pass = 0; pass < kSplitPasses; ++pass) {
    long_edges.clear();
    for (EH e : mesh_.edges())
      if (!mesh_.is_boundary(e) && length(e) > limit) long_edges.emplace_back(length(e), e.idx());
    std::sort(long_edges.begin(), long_edges.end(), std::greater<>());
    int splits = 0;
    for (const auto& [l, i] : long_edges) {
      const EH e = mesh_.edge_handle(i);
      if (!(length(e) > limit)) continue;
      const HH h = mesh_.halfedge_handle(e, 0);
      const SurfacePoint s = projector_->closest(
          0.5 * (point(mesh_.from_vertex_handle(h)) + point(mesh_.to_vertex_handle(h))));
      if (s.on_border || !split_ok(e, s.position)) continue;
      const VH v = mesh_.split(e, om(s.position));
      mesh_.property(fixed_, v) = false;
      mesh_.property(global_, v) = -1;
      mesh_.property(valence_offset_, v) = 0;
      place(v, s);
      ++splits;
    }
    if (splits == 0) return;
  }
}

// Whether collapsing h = (v0 -> v1) into v1's position keeps the mesh valid: v0 free, the
// link condition (is_collapse_ok), no new edge longer than 4/3 L, every triangle of v0's
// ring facing the same way and keeping its shape (keeps_shape), none left without a free
// vertex.
bool Remesher::collapse_ok(HH h) {
  const VH v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
  if (!is_free(v0) || !mesh_.is_collapse_ok(h)) return false;
  const Vec3 p0 = point(v0), p1 = point(v1);
  const double max2 = kSplitAbove * L_ * kSplitAbove * L_;
  for (VH w : mesh_.vv_range(v0))
    if (w != v1 && (point(w) - p1).squaredNorm() > max2) return false;
  const FH left = mesh_.face_handle(h);
  const FH right = mesh_.face_handle(mesh_.opposite_halfedge_handle(h));
  for (HH g : mesh_.voh_range(v0)) {
    const FH f = mesh_.face_handle(g);
    if (!f.is_valid() || f == left || f == right) continue;
    const VH a = mesh_.to_vertex_handle(g);
    const VH b = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(g));
    const Vec3 pa = point(a), pb = point(b);
    if (!keeps_shape(p0, pa, pb, p1, pa, pb)) return false;
    if (!is_free(v1) && !is_free(a) && !is_free(b)) return false;
  }
  return true;
}

// Collapses every edge shorter than 4/5 L whose collapse is valid (collapse_ok), a free
// vertex into its neighbour.
void Remesher::collapse_short_edges() {
  const double limit = kCollapseBelow * L_;
  for (int i = 0; i < int(mesh_.n_edges()); ++i) {
    const EH e = mesh_.edge_handle(i);
    if (mesh_.status(e).deleted() || !(length(e) < limit)) continue;
    for (int k = 0; k < 2; ++k) {
      const HH h = mesh_.halfedge_handle(e, k);
      if (collapse_ok(h)) {
        mesh_.collapse(h);
        break;
      }
    }
  }
}

// Whether flipping interior edge e brings the valences of its four vertices closer to their
// targets (6 inside, as counted with the edges outside the region) without folding its two
// triangles or thinning them (keeps_shape) or leaving one without a free vertex.
bool Remesher::flip_improves(EH e) const {
  if (mesh_.is_boundary(e) || !mesh_.is_flip_ok(e)) return false;
  const HH h = mesh_.halfedge_handle(e, 0), o = mesh_.opposite_halfedge_handle(h);
  const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
  const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
  const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
  const int va = int(mesh_.valence(a)), vb = int(mesh_.valence(b));
  const int vc = int(mesh_.valence(c)), vd = int(mesh_.valence(d));
  // An interior vertex keeps at least 3 edges, one on the border at least 2.
  if (va <= (mesh_.is_boundary(a) ? 2 : 3) || vb <= (mesh_.is_boundary(b) ? 2 : 3)) return false;
  const int before = deviation(a, va) + deviation(b, vb) + deviation(c, vc) + deviation(d, vd);
  const int after =
      deviation(a, va - 1) + deviation(b, vb - 1) + deviation(c, vc + 1) + deviation(d, vd + 1);
  if (after >= before) return false;
  if (!is_free(c) && !is_free(d) && (!is_free(a) || !is_free(b))) return false;
  // Old triangles (a, b, c), (b, a, d); new ones (a, d, c), (d, b, c).
  const Vec3 pa = point(a), pb = point(b), pc = point(c), pd = point(d);
  const Vec3 n_old = (pb - pa).cross(pc - pa) + (pa - pb).cross(pd - pb);
  const double was = std::min(shape(pa, pb, pc), shape(pb, pa, pd));
  const Vec3 n1 = (pd - pa).cross(pc - pa), n2 = (pb - pd).cross(pc - pd);
  return n1.dot(n2) > 0.0 && keeps_shape(n_old, was, pa, pd, pc) &&
         keeps_shape(n_old, was, pd, pb, pc);
}

// Flips interior edges towards valence 6 (Botsch & Kobbelt 2004's equalize_valences).
void Remesher::equalize_valences() {
  for (EH e : mesh_.edges())
    if (!mesh_.status(e).deleted() && flip_improves(e)) mesh_.flip(e);
}

// Moves each free vertex towards the area-weighted centroid of its one-ring's triangles, in
// its tangent plane, then onto the input surface; a move that would turn one of its
// triangles over or thin it (keeps_shape), or land on the region's border, is skipped.
void Remesher::relax_tangentially() {
  for (VH v : mesh_.vertices()) {
    if (mesh_.status(v).deleted() || !is_free(v)) continue;
    const Vec3 p = point(v);
    Vec3 normal = Vec3::Zero(), centroid = Vec3::Zero();
    double area = 0.0;
    for (FH f : mesh_.vf_range(v)) {
      auto fv = mesh_.cfv_iter(f);
      const Vec3 a = point(*fv), b = point(*++fv), c = point(*++fv);
      const Vec3 n = (b - a).cross(c - a);
      normal += n;
      area += 0.5 * n.norm();
      centroid += 0.5 * n.norm() * (a + b + c) / 3.0;
    }
    if (!(area > 0.0) || !(normal.norm() > 0.0)) continue;
    normal.normalize();
    centroid /= area;
    const Vec3 target = centroid - normal * normal.dot(centroid - p);
    const SurfacePoint s = projector_->closest(target);
    bool folds = s.on_border;  // a free vertex stays off the region's border
    for (HH g : mesh_.voh_range(v)) {
      if (!mesh_.face_handle(g).is_valid()) continue;
      const Vec3 pa = point(mesh_.to_vertex_handle(g));
      const Vec3 pb = point(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(g)));
      if (!keeps_shape(p, pa, pb, s.position, pa, pb)) folds = true;
    }
    if (!folds) place(v, s);
  }
}

// The output arrays (RemeshedRegion's row layout) from the mesh after garbage collection.
RemeshedRegion Remesher::result() {
  mesh_.garbage_collection();
  const int n = int(V_.rows());
  std::vector<int> row(mesh_.n_vertices(), -1);
  std::vector<bool> taken(n, false);
  int n_new = 0;
  for (VH v : mesh_.vertices()) {
    const int g = mesh_.property(global_, v);
    if (g >= 0) row[v.idx()] = g, taken[g] = true;  // fixed, or a free vertex that survived
    else ++n_new;
  }
  // New free vertices take the free rows left over in increasing order, then appended rows.
  std::vector<int> spare;
  for (int i = 0; i < n; ++i)
    if (free_[i] && !taken[i]) spare.push_back(i);
  RemeshedRegion out;
  const int rows = n + std::max(0, n_new - int(spare.size()));
  int next_spare = 0, next_append = n;
  for (VH v : mesh_.vertices())
    if (row[v.idx()] < 0)
      row[v.idx()] = next_spare < int(spare.size()) ? spare[next_spare++] : next_append++;
  out.unreferenced.assign(spare.begin() + next_spare, spare.end());
  out.vertices = Positions::Zero(rows, 3);
  out.vertices.topRows(n) = V_;
  out.free.assign(rows, false);
  out.origin_face.assign(rows, -1);
  out.origin_barycentric = Positions::Zero(rows, 3);
  out.target_edge_length = L_;
  for (VH v : mesh_.vertices()) {
    if (!is_free(v)) continue;
    const int r = row[v.idx()];
    out.vertices.row(r) = point(v);
    out.free[r] = true;
    out.origin_face[r] = mesh_.property(origin_face_, v);
    const std::array<double, 3>& b = mesh_.property(origin_bary_, v);
    out.origin_barycentric.row(r) << b[0], b[1], b[2];
  }
  std::vector<int> kept;
  for (Eigen::Index f = 0; f < F_.rows(); ++f)
    if (!(free_[F_(f, 0)] || free_[F_(f, 1)] || free_[F_(f, 2)])) kept.push_back(int(f));
  out.faces.resize(Eigen::Index(kept.size() + mesh_.n_faces()), 3);
  for (std::size_t t = 0; t < kept.size(); ++t) out.faces.row(Eigen::Index(t)) = F_.row(kept[t]);
  Eigen::Index t = Eigen::Index(kept.size());
  for (FH f : mesh_.faces()) {
    int k = 0;
    for (VH v : mesh_.fv_range(f)) out.faces(t, k++) = row[v.idx()];
    ++t;
  }
  return out;
}

}  // namespace

RemeshedRegion remesh_region(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                             const RemeshOptions& options) {
  check_input(V, F, free, options);
  Remesher remesher(V, F, free, options);
  remesher.run(options.iterations);
  return remesher.result();
}

}  // namespace geofair
