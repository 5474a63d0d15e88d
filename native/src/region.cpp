// One-rings from OpenMesh's half-edge structure, and extraction of the fairing region.
#include "geofair/region.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <cmath>
#include <string>

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

}  // namespace

bool OneRings::closed(int i) const {
  if (valence(i) == 0) return false;
  for (int k = offset[i]; k < offset[i + 1]; ++k)
    if (!has_face[k]) return false;
  return true;
}

OneRings build_one_rings(int n_vertices, const Triangles& triangles, const char* caller,
                         const std::vector<int>* triangle_ids) {
  silence_openmesh();
  auto name = [&](Eigen::Index f) { return triangle_ids ? (*triangle_ids)[f] : int(f); };
  Mesh mesh;
  mesh.reserve(n_vertices, 3 * triangles.rows() / 2 + 3, triangles.rows());
  for (int v = 0; v < n_vertices; ++v) mesh.add_vertex(Mesh::Point(0, 0, 0));
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const int a = triangles(f, 0), b = triangles(f, 1), c = triangles(f, 2);
    if (a < 0 || b < 0 || c < 0 || a >= n_vertices || b >= n_vertices || c >= n_vertices)
      throw InvalidInputError(prefix(caller) + "triangle " + std::to_string(name(f)) +
                              " has a vertex index out of range [0, " +
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

  OneRings r;
  r.offset.assign(n_vertices + 1, 0);
  r.ring.reserve(6 * n_vertices);
  r.has_face.reserve(6 * n_vertices);
  r.across.reserve(6 * n_vertices);
  std::vector<FanEdge> fan;
  std::vector<std::uint8_t> used;
  for (int v = 0; v < n_vertices; ++v) {
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
    r.offset[v] = int(r.ring.size());
    // Open fans first: they start at a neighbour that no fan edge leads to.
    for (std::size_t k = 0; k < fan.size(); ++k) {
      bool is_start = true;
      for (const auto& g : fan)
        if (g.to == fan[k].from) is_start = false;
      if (is_start && !used[k]) emit_chain(int(k));
    }
    for (std::size_t k = 0; k < fan.size(); ++k)
      if (!used[k]) emit_chain(int(k));
    r.offset[v + 1] = int(r.ring.size());
  }
  return r;
}

FairingRegion extract_region(const Positions& V, const Triangles& F, const std::vector<bool>& free,
                             const Positions* boundary_normals) {
  const char* fn = "fair";
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
  for (int i = 0; i < region.n; ++i)
    if (!V.row(region.global[i]).allFinite())
      throw InvalidInputError(prefix(fn) + "vertex " + std::to_string(region.global[i]) +
                              " has a non-finite coordinate");

  region.triangles.resize(Eigen::Index(region_triangles.size()), 3);
  for (std::size_t t = 0; t < region_triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) region.triangles(Eigen::Index(t), c) = local[F(region_triangles[t], c)];
  region.rings = build_one_rings(region.n, region.triangles, fn, &region_triangles);
  for (int i = 0; i < region.n_free; ++i)
    if (!region.rings.closed(i))
      throw InvalidInputError(prefix(fn) + "free vertex " + std::to_string(region.global[i]) +
                              " lies on the mesh border (its triangles do not close around "
                              "it); fix it or give it as a G1 boundary vertex");

  // G1 boundary normals: prescribed, or from the surrounding surface.
  const int nb = region.n - region.n_free;
  region.g1_normals.resize(nb, 3);
  if (boundary_normals) {
    if (boundary_normals->rows() != nv)
      throw InvalidInputError(prefix(fn) + "boundary_normals has " +
                              std::to_string(boundary_normals->rows()) + " rows for " +
                              std::to_string(nv) + " vertices");
    for (int b = 0; b < nb; ++b) region.g1_normals.row(b) = boundary_normals->row(region.global[region.n_free + b]);
  } else {
    region.g1_normals.setZero();
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
      if (free[a] || free[b] || free[c]) continue;
      if (local[a] < 0 && local[b] < 0 && local[c] < 0) continue;
      const Vec3 pa = V.row(a), pb = V.row(b), pc = V.row(c);
      const Vec3 cr = (pb - pa).cross(pc - pa);
      for (int v : {a, b, c})
        if (local[v] >= region.n_free) region.g1_normals.row(local[v] - region.n_free) += cr;
    }
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
    } else if (!(len > 0.0)) {
      throw InvalidInputError(prefix(fn) + "G1 boundary vertex " + std::to_string(v) +
                              " has no surrounding triangle without a free vertex to take its "
                              "normal from (the free region reaches the mesh border); pass "
                              "boundary_normals");
    }
    region.g1_normals.row(b) = n / len;
  }
  return region;
}

}  // namespace geofair
