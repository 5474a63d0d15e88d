// One-rings from OpenMesh's half-edge structure, and extraction of the fairing region.
#include "region.h"

#include "common.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>

namespace geofair {
namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

std::string prefix(const char* caller) { return std::string(caller) + ": "; }

// OpenMesh reports failed add_face calls on its error stream; we turn them into
// exceptions instead, so keep the stream quiet.
void silence_openmesh() {
  static const bool silenced = [] {
    omerr().disable();
    omlog().disable();
    return true;
  }();
  (void)silenced;
}

struct FanEdge {
  int from, to, across;
};

// Fewest samples, and largest condition number of the column-equilibrated normal equations,
// with which the quadric fit of a boundary normal is trusted (estimate_boundary_normals).
constexpr int kMinQuadricSamples = 6;
constexpr double kMaxQuadricCondition = 1e6;

// Normal of the tangent plane of the least-squares paraboloid z = a x + b y + c x² + d xy + e y²
// through the origin, in the frame of the unit normal n, fitted to the offsets d (samples
// minus the vertex, in units of their rms distance), each equation weighted by 1/|d|².
// False where the fit is ill-conditioned or tilts the plane by 45° or more.
bool fit_tangent_plane(const std::vector<Vec3>& offsets, const Vec3& n, Vec3& out) {
  Vec3 bx, by;
  tangent_basis(n, bx, by);
  using Vec5 = Eigen::Matrix<double, 5, 1>;
  using Mat5 = Eigen::Matrix<double, 5, 5>;
  Mat5 M = Mat5::Zero();
  Vec5 rhs = Vec5::Zero();
  for (const Vec3& d : offsets) {
    const double dd = d.squaredNorm();
    const double w = 1.0 / dd;
    const double x = d.dot(bx), y = d.dot(by), z = d.dot(n);
    Vec5 row;
    row << x, y, x * x, x * y, y * y;
    row *= w;
    M.noalias() += row * row.transpose();
    rhs += row * (w * z);
  }
  // Equilibrate the columns, then judge the conditioning by the eigenvalues.
  const Vec5 diag = M.diagonal();
  if (!(diag.minCoeff() > 0.0) || !diag.allFinite()) return false;
  const Vec5 s = diag.cwiseSqrt().cwiseInverse();
  const Mat5 Ms = s.asDiagonal() * M * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Mat5> eigen(Ms, Eigen::EigenvaluesOnly);
  const Vec5 lambda = eigen.eigenvalues();  // ascending
  if (!(lambda(0) > lambda(4) / kMaxQuadricCondition)) return false;
  const Vec5 c = s.asDiagonal() * Ms.ldlt().solve(s.asDiagonal() * rhs);
  const double a = c(0), b = c(1);
  if (!(a * a + b * b < 1.0)) return false;
  out = (n - a * bx - b * by).normalized();
  return out.allFinite();
}

}  // namespace

bool OneRings::closed(int i) const {
  if (valence(i) == 0) return false;
  for (int k = offset[i]; k < offset[i + 1]; ++k)
    if (!has_face[k]) return false;
  return true;
}

namespace {

// The triangles as an OpenMesh half-edge mesh, checked (indices, repeated vertices, a
// consistently oriented manifold); triangle_ids name the triangles in errors.
void build_mesh(Mesh& mesh, int n_vertices, const Triangles& triangles, const char* caller,
                const std::vector<int>* triangle_ids) {
  silence_openmesh();
  auto name = [&](Eigen::Index f) { return triangle_ids ? (*triangle_ids)[f] : int(f); };
  mesh.reserve(n_vertices, 3 * triangles.rows() / 2 + 3, triangles.rows());
  for (int v = 0; v < n_vertices; ++v) mesh.add_vertex(Mesh::Point(0, 0, 0));
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const int a = triangles(f, 0), b = triangles(f, 1), c = triangles(f, 2);
    for (const int v : {a, b, c})
      if (v < 0 || v >= n_vertices)
        throw InvalidInputError(prefix(caller) + "triangle " + std::to_string(name(f)) +
                                " has vertex index " + std::to_string(v) + ", out of range [0, " +
                                std::to_string(n_vertices) + ")");
    if (a == b || b == c || a == c)
      throw InvalidInputError(prefix(caller) + "triangle " + std::to_string(name(f)) +
                              " repeats a vertex");
    const auto fh = mesh.add_face(mesh.vertex_handle(a), mesh.vertex_handle(b),
                                  mesh.vertex_handle(c));
    if (!fh.is_valid())
      throw InvalidInputError(prefix(caller) + "triangle " + std::to_string(name(f)) +
                              " makes an edge non-manifold or is oriented against its "
                              "neighbour (faces must form a consistently oriented manifold)");
  }

}

// Appends the ring of vertex v to r (r.offset[v] set), counter-clockwise, one chain per fan;
// `fan` and `used`: work space.
void append_ring(const Mesh& mesh, int v, OneRings& r, std::vector<FanEdge>& fan,
                 std::vector<std::uint8_t>& used) {
  // Every triangle (v, w, u) at v contributes the fan edge w -> u; chaining the fan
  // edges orders the ring counter-clockwise, with one chain per fan.
  fan.clear();
  for (auto h : mesh.voh_range(mesh.vertex_handle(v))) {
    if (h.is_boundary()) continue;
    const auto e = h.next();  // w -> u
    const auto o = e.opp();
    fan.push_back({e.from().idx(), e.to().idx(), o.is_boundary() ? -1 : o.next().to().idx()});
  }
  used.assign(fan.size(), 0);
  auto find_from = [&](int w) {
    for (std::size_t k = 0; k < fan.size(); ++k)
      if (!used[k] && fan[k].from == w) return int(k);
    return -1;
  };
  auto push = [&](int w, int face, int across) {
    r.ring.push_back(w);
    r.has_face.push_back(std::uint8_t(face));
    r.across.push_back(across);
  };
  auto emit_chain = [&](int k) {
    const std::size_t chain_start = r.ring.size();
    const int first = fan[k].from;
    for (;;) {
      used[k] = 1;
      push(fan[k].from, 1, fan[k].across);
      const int nk = find_from(fan[k].to);
      if (nk >= 0) {
        k = nk;
        continue;
      }
      if (fan[k].to != first)
        push(fan[k].to, 0, -1);  // open fan: its last neighbour has no triangle after it
      else if (chain_start != std::size_t(r.offset[v]))
        r.has_face.back() = 0;  // a second closed fan cannot wrap to the ring's start
      return;
    }
  };
  // Open fans first: they start at a neighbour that no fan edge leads to.
  for (std::size_t k = 0; k < fan.size(); ++k) {
    bool is_start = true;
    for (const auto& g : fan)
      if (g.to == fan[k].from) is_start = false;
    if (is_start && !used[k]) emit_chain(int(k));
  }
  for (std::size_t k = 0; k < fan.size(); ++k)
    if (!used[k]) emit_chain(int(k));
}

}  // namespace

OneRings build_one_rings(int n_vertices, const Triangles& triangles, const char* caller,
                         const std::vector<int>* triangle_ids) {
  Mesh mesh;
  build_mesh(mesh, n_vertices, triangles, caller, triangle_ids);
  OneRings r;
  r.offset.assign(n_vertices + 1, 0);
  r.ring.reserve(6 * n_vertices);
  r.has_face.reserve(6 * n_vertices);
  r.across.reserve(6 * n_vertices);
  std::vector<FanEdge> fan;
  std::vector<std::uint8_t> used;
  for (int v = 0; v < n_vertices; ++v) {
    r.offset[v] = int(r.ring.size());
    append_ring(mesh, v, r, fan, used);
    r.offset[v + 1] = int(r.ring.size());
  }
  return r;
}

void check_triangles(int n_vertices, const Triangles& triangles, const char* caller) {
  Mesh mesh;
  build_mesh(mesh, n_vertices, triangles, caller, nullptr);
}

void check_indices(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                   const char* fn) {
  const int nv = int(V.rows());
  if (int(free.size()) != nv)
    throw InvalidInputError(prefix(fn) + "free has " + std::to_string(free.size()) +
                            " entries for " + std::to_string(nv) + " vertices");
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (F(f, c) < 0 || F(f, c) >= nv)
        throw InvalidInputError(prefix(fn) + "triangle " + std::to_string(f) +
                                " has vertex index " + std::to_string(F(f, c)) +
                                ", out of range [0, " + std::to_string(nv) + ")");
}

// Every vertex a triangle uses has finite coordinates, also far from the region (fair()
// returns its position).
void check_finite(const Positions& V, const Triangles& F, const char* fn) {
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (!V.row(F(f, c)).allFinite())
        throw InvalidInputError(prefix(fn) + "vertex " + std::to_string(F(f, c)) +
                                " has a non-finite coordinate");
}

namespace {

// Work space of quadric_normal.
struct QuadricSamples {
  explicit QuadricSamples(int nv) : stamp(nv, -1) {}
  std::vector<int> stamp;  // the vertex whose samples last took this one
  std::vector<int> first_ring;
  std::vector<Vec3> offsets;
};

// The quadric fit's normal at G1 boundary vertex v (estimate_boundary_normals), from the area
// normal n0 and the surrounding triangles `incident[start[w] .. start[w + 1])` of every
// vertex w; false where the fit is not trusted (n0 stays).
bool quadric_normal(const Positions& V, const Triangles& F, int v, const Vec3& n0,
                    const std::vector<int>& start, const std::vector<int>& incident,
                    QuadricSamples& samples, Vec3& normal) {
  std::vector<int>& stamp = samples.stamp;
  std::vector<int>& first_ring = samples.first_ring;
  std::vector<Vec3>& offsets = samples.offsets;
  const Vec3 q = V.row(v);
  // Samples: the vertices of the surrounding triangles at v, and of the triangles
  // without a free vertex at those.
  first_ring.clear();
  offsets.clear();
  stamp[v] = v;
  bool finite = true;
  auto take = [&](int w) {
    if (stamp[w] == v) return false;
    stamp[w] = v;
    const Vec3 d = V.row(w).transpose() - q;
    if (!d.allFinite()) finite = false;
    offsets.push_back(d);
    return true;
  };
  for (int k = start[v]; k < start[v + 1]; ++k)
    for (int c = 0; c < 3; ++c)
      if (take(F(incident[k], c))) first_ring.push_back(F(incident[k], c));
  for (int w : first_ring)
    for (int k = start[w]; k < start[w + 1]; ++k)
      for (int c = 0; c < 3; ++c) take(F(incident[k], c));
  if (!finite || int(offsets.size()) < kMinQuadricSamples) return false;
  double mean_dd = 0.0;
  for (const Vec3& d : offsets) mean_dd += d.squaredNorm();
  const double unit = std::sqrt(mean_dd / double(offsets.size()));
  if (!(unit > 0.0) || !std::isfinite(unit)) return false;
  bool coincident = false;
  for (Vec3& d : offsets) {
    d /= unit;
    if (!(d.squaredNorm() > 0.0)) coincident = true;
  }
  if (coincident) return false;
  // Fit in the frame of n0, then once more in the frame of the fitted normal.
  Vec3 n1, n2;
  if (!fit_tangent_plane(offsets, n0, n1) || !fit_tangent_plane(offsets, n1, n2)) return false;
  if (!(n2.dot(n0) > 0.0)) return false;
  normal = n2;
  return true;
}

}  // namespace

Positions estimate_boundary_normals(const Positions& V, const Triangles& F,
                                    const std::vector<bool>& free, BoundaryNormalEstimate method,
                                    const char* caller) {
  const int nv = int(V.rows());
  check_indices(V, F, free, caller);
  // G1 boundary: fixed vertices of triangles with a free vertex. Surrounding triangles:
  // those without a free vertex, as vertex -> triangle lists (CSR).
  std::vector<std::uint8_t> g1(nv, 0);
  std::vector<int> start(nv + 1, 0);
  auto has_free = [&](Eigen::Index f) { return free[F(f, 0)] || free[F(f, 1)] || free[F(f, 2)]; };
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (has_free(f)) {
      for (int c = 0; c < 3; ++c)
        if (!free[F(f, c)]) g1[F(f, c)] = 1;
    } else {
      for (int c = 0; c < 3; ++c) ++start[F(f, c) + 1];
    }
  }
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<int> incident(start[nv]);
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      if (!has_free(f))
        for (int c = 0; c < 3; ++c) incident[fill[F(f, c)]++] = int(f);
  }

  Positions normals = Positions::Zero(nv, 3);
  QuadricSamples samples(nv);
  for (int v = 0; v < nv; ++v) {
    if (!g1[v]) continue;
    Vec3 sum = Vec3::Zero();
    for (int k = start[v]; k < start[v + 1]; ++k) {
      const int f = incident[k];
      const Vec3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
      sum += (b - a).cross(c - a);
    }
    const double len = sum.norm();
    if (!std::isfinite(len)) {
      normals.row(v).setConstant(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    if (!(len > 0.0)) continue;  // no surrounding triangle, or only degenerate ones
    const Vec3 n0 = sum / len;
    normals.row(v) = n0;
    if (method == BoundaryNormalEstimate::Area) continue;
    Vec3 fitted;
    if (quadric_normal(V, F, v, n0, start, incident, samples, fitted)) normals.row(v) = fitted;
  }
  return normals;
}

namespace {

// region.polygon_diagonal: an edge of the region is a diagonal of a polygon where its two
// triangles of F (inside the region or not) carry the same polygon id. `local`: the caller's
// vertex -> region id, or -1.
void mark_polygon_diagonals(FairingRegion& region, const Triangles& F,
                            const std::vector<int>& polygon_ids, const std::vector<int>& local) {
  struct EdgeTriangles {
    int polygon, count;
    bool same;
  };
  std::unordered_map<std::uint64_t, EdgeTriangles> edges;
  edges.reserve(3 * std::size_t(region.triangles.rows()));
  auto key = [&](int a, int b) {
    return std::uint64_t(std::min(a, b)) * std::uint64_t(region.n) + std::uint64_t(std::max(a, b));
  };
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int a = local[F(t, c)], b = local[F(t, (c + 1) % 3)];
      if (a < 0 || b < 0) continue;
      const int polygon = polygon_ids[t];
      const auto it = edges.try_emplace(key(a, b), EdgeTriangles{polygon, 0, true}).first;
      it->second.same = it->second.same && it->second.polygon == polygon;
      ++it->second.count;
    }
  const OneRings& rings = region.rings;
  region.polygon_diagonal.assign(rings.ring.size(), 0);
  for (int i = 0; i < region.n; ++i)
    for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k) {
      const EdgeTriangles& e = edges.at(key(i, rings.ring[k]));
      region.polygon_diagonal[k] = e.count == 2 && e.same;
    }
}

// The region's vertices (free first, then the G1 boundary), triangles and one-rings, with
// the checks of each free vertex (in a triangle, not on the border); positions are checked
// before (check_finite).
FairingRegion region_mesh(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                          const std::vector<int>* polygon_ids, const char* fn) {
  const int nv = int(V.rows());
  // Region triangles: those with a free vertex. Their fixed vertices are the G1 boundary.
  std::vector<int> region_triangles;
  std::vector<std::uint8_t> in_region(nv, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (!(free[F(f, 0)] || free[F(f, 1)] || free[F(f, 2)])) continue;
    region_triangles.push_back(int(f));
    for (int c = 0; c < 3; ++c) in_region[F(f, c)] = 1;
  }
  FairingRegion region;
  std::vector<int> local(nv, -1);
  for (int v = 0; v < nv; ++v) {
    if (!free[v]) continue;
    if (!in_region[v])
      throw InvalidInputError(prefix(fn) + "free vertex " + std::to_string(v) +
                              " belongs to no triangle");
    local[v] = int(region.global.size());
    region.global.push_back(v);
  }
  region.n_free = int(region.global.size());
  if (region.n_free == 0) throw InvalidInputError(prefix(fn) + "no vertex is free");
  for (int v = 0; v < nv; ++v)
    if (in_region[v] && !free[v]) {
      local[v] = int(region.global.size());
      region.global.push_back(v);
    }
  region.n = int(region.global.size());
  if (region.n == region.n_free)
    throw InvalidInputError(prefix(fn) +
                            "every vertex of the region is free: a G1 boundary (fixed "
                            "vertices next to the free ones) is required");

  region.triangles.resize(Eigen::Index(region_triangles.size()), 3);
  for (std::size_t t = 0; t < region_triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) region.triangles(Eigen::Index(t), c) = local[F(region_triangles[t], c)];
  region.rings = build_one_rings(region.n, region.triangles, fn, &region_triangles);
  for (int i = 0; i < region.n_free; ++i)
    if (!region.rings.closed(i))
      throw InvalidInputError(prefix(fn) + "free vertex " + std::to_string(region.global[i]) +
                              " lies on the mesh border (its triangles do not close around "
                              "it); fix it or give it as a G1 boundary vertex");
  if (polygon_ids) mark_polygon_diagonals(region, F, *polygon_ids, local);
  return region;
}

// region.g1_normals: the prescribed unit normals (checked against the surface's
// orientation if asked) or the estimate from the surrounding surface.
void set_g1_normals(FairingRegion& region, const Positions& V, const Triangles& F,
                    const std::vector<bool>& free, const Positions* boundary_normals,
                    bool check_orientation, const char* fn) {
  const int nv = int(V.rows());
  const int nb = region.n - region.n_free;
  region.g1_normals.resize(nb, 3);
  if (boundary_normals && boundary_normals->rows() != nv)
    throw InvalidInputError(prefix(fn) + "boundary_normals has " +
                            std::to_string(boundary_normals->rows()) + " rows for " +
                            std::to_string(nv) + " vertices");
  Positions estimate;
  if (!boundary_normals || check_orientation)
    estimate = estimate_boundary_normals(V, F, free, BoundaryNormalEstimate::Quadric, fn);
  for (int b = 0; b < nb; ++b) {
    const int v = region.global[region.n_free + b];
    if (boundary_normals)
      region.g1_normals.row(b) = boundary_normals->row(v);
    else
      region.g1_normals.row(b) = estimate.row(v);
  }
  for (int b = 0; b < nb; ++b) {
    const int v = region.global[region.n_free + b];
    const Vec3 n = region.g1_normals.row(b);
    const double len = n.norm();
    if (!n.allFinite())
      throw InvalidInputError(prefix(fn) + "the normal of G1 boundary vertex " + std::to_string(v) +
                              " is not finite");
    if (boundary_normals) {
      if (std::abs(len - 1.0) > 1e-6)
        throw InvalidInputError(prefix(fn) + "boundary_normals[" + std::to_string(v) +
                                "] is not a unit vector (length " + std::to_string(len) + ")");
      if (check_orientation) {
        const Vec3 e = estimate.row(v);
        const double dot = n.dot(e) / len;
        if (e.allFinite() && e.squaredNorm() > 0.0 && dot < 0.0) {
          char text[32];
          std::snprintf(text, sizeof text, "%.2f", dot);
          throw InvalidInputError(prefix(fn) + "boundary_normals[" + std::to_string(v) +
                                  "] points against the surface's orientation (dot product " +
                                  text + " with the normal of its surrounding triangles); "
                                  "flip it or the faces");
        }
      }
    } else if (!(len > 0.0)) {
      throw InvalidInputError(prefix(fn) + "G1 boundary vertex " + std::to_string(v) +
                              " has no surrounding triangle without a free vertex to take its "
                              "normal from (the free region reaches the mesh border); pass "
                              "boundary_normals");
    }
    region.g1_normals.row(b) = n / len;
  }
}

// region.g1_normals with G0: the normalized sums of the cross products of each boundary
// vertex's region triangles (area-weighted, one-sided), at the input positions.
void set_g0_normals(FairingRegion& region, const Positions& V) {
  const int nf = region.n_free;
  region.g1_normals = Positions::Zero(region.n - nf, 3);
  for (Eigen::Index t = 0; t < region.triangles.rows(); ++t) {
    const Vec3 a = V.row(region.global[region.triangles(t, 0)]);
    const Vec3 b = V.row(region.global[region.triangles(t, 1)]);
    const Vec3 c = V.row(region.global[region.triangles(t, 2)]);
    const Vec3 cross = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k)
      if (region.triangles(t, k) >= nf) region.g1_normals.row(region.triangles(t, k) - nf) += cross;
  }
  for (int b = 0; b < region.n - nf; ++b) {
    const double len = region.g1_normals.row(b).norm();
    if (len > 0.0) region.g1_normals.row(b) /= len;
  }
}

}  // namespace

FairingRegion extract_region(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                             const Positions* boundary_normals, bool check_orientation,
                             const std::vector<int>* polygon_ids,
                             BoundaryCondition boundary) {
  const char* fn = "fair";
  check_indices(V, F, free, fn);
  check_finite(V, F, fn);
  if (polygon_ids && Eigen::Index(polygon_ids->size()) != F.rows())
    throw InvalidInputError(prefix(fn) + "polygon_ids has " + std::to_string(polygon_ids->size()) +
                            " entries for " + std::to_string(F.rows()) + " triangles");
  FairingRegion region = region_mesh(V, F, free, polygon_ids, fn);
  region.boundary = boundary;
  if (boundary == BoundaryCondition::G0)
    set_g0_normals(region, V);
  else
    set_g1_normals(region, V, F, free, boundary_normals, check_orientation, fn);
  return region;
}

void set_boundary_normals(FairingRegion& region, const Positions& V, const Triangles& F,
                          const std::vector<bool>& free, const Positions* boundary_normals,
                          const char* caller) {
  if (region.boundary == BoundaryCondition::G0)
    set_g0_normals(region, V);
  else
    set_g1_normals(region, V, F, free, boundary_normals, true, caller);
}

FoldCount count_folds(const Positions& before, const Positions& after, const Triangles& F,
                      const std::vector<bool>& free) {
  // The edges with a free endpoint, bucketed by their smaller vertex (a counting sort, linear
  // in #F): entries (larger vertex, triangle), so that an edge's triangles share a bucket.
  const int n = int(before.rows());
  std::vector<int> start(std::size_t(n) + 1, 0);
  auto for_each_edge = [&](auto&& visit) {
    for (int f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = F(f, k), b = F(f, (k + 1) % 3);
        if (free[a] || free[b]) visit(std::min(a, b), std::max(a, b), f);
      }
  };
  for_each_edge([&](int a, int, int) { ++start[std::size_t(a) + 1]; });
  for (int v = 0; v < n; ++v) start[std::size_t(v) + 1] += start[std::size_t(v)];
  std::vector<std::pair<int, int>> slots(static_cast<std::size_t>(start.back()));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for_each_edge([&](int a, int b, int f) { slots[std::size_t(fill[std::size_t(a)]++)] = {b, f}; });
  auto normal = [&](const Positions& X, int f) -> Vec3 {
    const Vec3 p = X.row(F(f, 0)).transpose();
    return (Vec3(X.row(F(f, 1)).transpose()) - p).cross(Vec3(X.row(F(f, 2)).transpose()) - p);
  };
  FoldCount count;
  for (int v = 0; v < n; ++v) {
    const auto first = slots.begin() + start[std::size_t(v)];
    const auto last = slots.begin() + start[std::size_t(v) + 1];
    std::sort(first, last);  // a vertex's few edges: an edge's triangles become adjacent
    for (auto i = first; i != last;) {
      auto j = i;
      while (j != last && j->first == i->first) ++j;
      if (j - i == 2) {  // an edge of two triangles (a border edge has one; others are skipped)
        const int f = i->second, g = (i + 1)->second;
        if (normal(after, f).dot(normal(after, g)) < 0.0) {
          ++count.folds;
          count.new_folds += !(normal(before, f).dot(normal(before, g)) < 0.0);
        }
      }
      i = j;
    }
  }
  return count;
}

std::string fold_note(const FoldCount& folds) {
  if (folds.folds == 0) return "";
  return "; " + std::to_string(folds.folds) + (folds.folds == 1 ? " edge folds" : " edges fold") +
         " over (triangles flipped), " + std::to_string(folds.new_folds) +
         " of them not in the input";
}

}  // namespace geofair
