// Progressive mesh by half-edge collapses with OpenMesh's decimater (section 7.4).
#include "progressive_mesh.h"

#include "inner_fairness.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace geofair {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};

// The collapse priority of ModFairingHierarchyT (smallest first) for a half-edge from p0 to
// p1: its squared length times `factor` (Mesh::priority_factor of the vertex at p0), as a
// float like the decimater's priorities. Mesh::Sweep compares with it, so both must compute
// it alike.
float length_priority(const OpenMesh::Vec3d& p0, const OpenMesh::Vec3d& p1, float factor) {
  return factor * float((p1 - p0).sqrnorm());
}

// The mesh the decimater works on. DecimaterT asks the mesh type whether a half-edge
// collapse keeps the mesh a manifold (is_collapse_ok) for every candidate it weighs; the
// library's TriConnectivity::is_collapse_ok is compiled into Debian's libOpenMeshCore with
// its assertions on, and there every status access compares type names and allocates a
// string: most of the decimation's time (docs/DESIGN_NOTES.md, "The decimation's speed").
// This type answers with the same
// conditions, its status accesses inlined here; so does find_halfedge, and valence reads a
// count kept per vertex: the decimater's legality check and the priority module ask for
// them too (each handle access inside the library checks its validity through a call).
struct Mesh : OpenMesh::TriMesh_ArrayKernelT<DoubleTraits> {
  using TriMesh_ArrayKernelT::find_halfedge;
  using TriMesh_ArrayKernelT::valence;
  // The valences, counted once (start_decimation) and updated at each collapse
  // (before_collapse).
  unsigned int valence(VertexHandle v) const { return valences[v.idx()]; }
  std::vector<unsigned int> valences;
  // Once the mesh is built: its valences, and a ring mark per vertex for the sweeps.
  void start_decimation() {
    valences.assign(n_vertices(), 0);
    for (const VertexHandle v : vertices())
      for (auto it = cvoh_iter(v); it.is_valid(); ++it) ++valences[v.idx()];
    sweep.ring_stamp.assign(n_vertices(), 0);
  }
  // Before the collapse of v0 into v1 with apexes vl, vr (invalid on the border): v1 takes
  // v0's neighbours but v1 and the apexes (its own already: the link condition), and each
  // apex loses v0.
  void before_collapse(VertexHandle v0, VertexHandle v1, VertexHandle vl, VertexHandle vr) {
    const unsigned int apexes = unsigned(vl.is_valid()) + unsigned(vr.is_valid());
    valences[v1.idx()] += valences[v0.idx()] - 2 - apexes;
    if (vl.is_valid()) --valences[vl.idx()];
    if (vr.is_valid()) --valences[vr.idx()];
  }
  HalfedgeHandle find_halfedge(VertexHandle from, VertexHandle to) const {
    for (const HalfedgeHandle h : voh_range(from))
      if (to_vertex_handle(h) == to) return h;
    return HalfedgeHandle();
  }

  // Collapsing v0 (from) into v1 (to) is refused if the edge or a vertex is deleted, if a
  // triangle of the edge has its other two edges on the border, if the edge has the same or
  // no apex on both sides, if v0 and v1 share a neighbour other than the apexes (the link
  // condition), or if both lie on the border while the edge does not; and skipped (refused)
  // if it cannot be the decimater's choice (see Sweep).
  bool is_collapse_ok(HalfedgeHandle v0v1) {
    const VertexHandle v0 = from_vertex_handle(v0v1);
    if (v0v1 == halfedge_handle(v0) || v0 != sweep.from) {
      sweep.start(v0, priority_factor(v0));
      for (const VertexHandle a : vv_range(v0)) sweep.mark(a.idx());
    } else if (length_priority(point(v0), point(to_vertex_handle(v0v1)), sweep.factor) > sweep.best)
      return false;
    return keeps_manifold(v0v1);
  }

  // Region-local ids from n_free on are G1 boundary vertices; `rules` are those of
  // build_progressive_mesh, read here and by the priority module.
  int n_free = 0;
  Decimation rules;
  int min_boundary_loop = HierarchyTuning{}.min_boundary_loop;  // build_progressive_mesh sets it
  bool is_g1(VertexHandle v) const { return v.idx() >= n_free; }
  // The factor of the priorities of collapses from v0 (length_priority): 1e-4 for a free
  // vertex of valence below 5 if low valences go first, else 1.
  float priority_factor(VertexHandle v0) const {
    return rules.low_valence_first && !is_g1(v0) && valence(v0) < 5 ? 1e-4f : 1.0f;
  }

  // DecimaterT::heap_vertex(v) weighs every half-edge out of v in turn, starting at
  // halfedge_handle(v): legality first (keeps_manifold), then the priority, and keeps the
  // smallest priority. With the priority the squared edge length (ModFairingHierarchyT), a
  // half-edge longer than the shortest legal one found so far in the same sweep cannot be
  // chosen, so its checks are skipped. `best` is the smallest priority of the sweep of
  // `from` so far (set by the priority module); a sweep starts at halfedge_handle(from),
  // and a collapse ends it. The decimater's second check of the half-edge it chose, after
  // popping it from the heap, is never skipped: if no other sweep came in between, its
  // length equals `best`, and only longer ones are skipped. The hierarchy is the same as
  // with every candidate weighed (docs/DESIGN_NOTES.md, "The decimation's speed").
  // The sweep also keeps what every candidate of `from` reads and the collapses leave
  // unchanged until one is made: the one-ring of `from` (marked, for the link condition) and
  // its triangles with their normals (faces, for the priority module).
  struct Face {
    FaceHandle handle;
    VertexHandle vertex[3];
    OpenMesh::Vec3d point[3], normal;
  };
  struct Sweep {
    VertexHandle from;
    float best = FLT_MAX, factor = 1.0f;  // factor: priority_factor(from)
    std::vector<Face> faces;
    bool faces_known = false;
    void start(VertexHandle v, float f = 1.0f) {
      from = v, best = FLT_MAX, factor = f;
      ++stamp, faces.clear(), faces_known = false;
    }
    // The ring of `from`: the vertices whose ring_stamp is this sweep's stamp.
    void mark(int vertex) { ring_stamp[vertex] = stamp; }
    bool in_ring(int vertex) const { return ring_stamp[vertex] == stamp; }
    std::vector<std::uint64_t> ring_stamp;  // per vertex (start_decimation)
    std::uint64_t stamp = 1;
  } sweep;

 private:
  bool keeps_manifold(HalfedgeHandle v0v1) {
    if (status(edge_handle(v0v1)).deleted()) return false;
    const HalfedgeHandle v1v0 = opposite_halfedge_handle(v0v1);
    const VertexHandle v0 = to_vertex_handle(v1v0), v1 = to_vertex_handle(v0v1);
    if (status(v0).deleted() || status(v1).deleted()) return false;
    // The apex of the triangle left of h, invalid on the border; false if its other two
    // edges both lie on the border.
    auto apex = [&](HalfedgeHandle h, VertexHandle& v) {
      if (is_boundary(h)) return true;
      const HalfedgeHandle h1 = next_halfedge_handle(h), h2 = next_halfedge_handle(h1);
      v = to_vertex_handle(h1);
      return !(is_boundary(opposite_halfedge_handle(h1)) &&
               is_boundary(opposite_halfedge_handle(h2)));
    };
    VertexHandle vl, vr;
    if (!apex(v0v1, vl) || !apex(v1v0, vr) || vl == vr) return false;
    // The link condition: no common neighbour of v0 (its ring, kept by the sweep) and v1
    // but the apexes.
    for (const VertexHandle b : vv_range(v1)) {
      if (b == vl || b == vr) continue;
      if (sweep.in_ring(b.idx())) return false;
    }
    return !(is_boundary(v0) && is_boundary(v1) && !is_boundary(v0v1) && !is_boundary(v1v0));
  }
};

// 4√3·area / (a² + b² + c²): 1 for an equilateral triangle, 0 for a degenerate one.
double triangle_quality(const OpenMesh::Vec3d& a, const OpenMesh::Vec3d& b,
                        const OpenMesh::Vec3d& c, OpenMesh::Vec3d& normal) {
  normal = (b - a) % (c - a);
  const double edges = (b - a).sqrnorm() + (c - b).sqrnorm() + (a - c).sqrnorm();
  return edges > 0.0 ? 2.0 * std::sqrt(3.0) * normal.norm() / edges : 0.0;
}

// Priority module: shortest half-edge first, distorted or flipped triangles refused.
template <class MeshT>
class ModFairingHierarchyT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModFairingHierarchyT, MeshT, FairingHierarchy);

  explicit ModFairingHierarchyT(MeshT& mesh) : Base(mesh, false), mesh_(mesh) {}

  float collapse_priority(const CollapseInfo& ci) override {
    const Decimation& rules = mesh_.rules;
    // A G1 boundary vertex (locked unless the boundary is coarsened) collapses only while
    // its border loop keeps min_boundary_loop vertices; a fixed vertex inside the region
    // (closed fan) never. The decimater itself collapses a vertex on the border only into
    // a neighbour on the border along a border edge (free vertices are never on it).
    if (mesh_.is_g1(ci.v0) && !(mesh_.is_boundary(ci.v0) && long_loop(ci.v0)))
      return float(Base::ILLEGAL_COLLAPSE);
    // Valences after the collapse: vl and vr lose an edge, v1 takes over v0's. G1 boundary
    // vertices keep whatever fan the region gives them.
    for (auto v : {ci.vl, ci.vr})
      if (v.is_valid() && !mesh_.is_g1(v) && int(mesh_.valence(v)) - 1 < rules.min_valence)
        return float(Base::ILLEGAL_COLLAPSE);
    if (!mesh_.is_g1(ci.v1) &&
        int(mesh_.valence(ci.v1) + mesh_.valence(ci.v0)) - 4 > rules.max_valence)
      return float(Base::ILLEGAL_COLLAPSE);
    for (const auto& face : faces_of(ci.v0)) {
      if (face.handle == ci.fl || face.handle == ci.fr) continue;  // these two disappear
      OpenMesh::Vec3d q[3];
      for (int k = 0; k < 3; ++k) q[k] = face.vertex[k] == ci.v0 ? ci.p1 : face.point[k];
      OpenMesh::Vec3d n_new;
      if (triangle_quality(q[0], q[1], q[2], n_new) < rules.min_quality)
        return float(Base::ILLEGAL_COLLAPSE);
      const OpenMesh::Vec3d& n_old = face.normal;
      if ((n_old | n_new) < 0.5 * n_old.norm() * n_new.norm()) return float(Base::ILLEGAL_COLLAPSE);
    }
    const float priority = length_priority(
        ci.p0, ci.p1, ci.v0 == mesh_.sweep.from ? mesh_.sweep.factor : mesh_.priority_factor(ci.v0));
    if (ci.v0 == mesh_.sweep.from) mesh_.sweep.best = std::min(mesh_.sweep.best, priority);
    return priority;
  }

  // Records the collapsed vertex with its one-ring before the collapse.
  void preprocess_collapse(const CollapseInfo& ci) override {
    mesh_.sweep.start(typename MeshT::VertexHandle());  // a collapse ends the sweep
    mesh_.before_collapse(ci.v0, ci.v1, ci.vl, ci.vr);
    collapses.vertex.push_back(ci.v0.idx());
    for (auto v : mesh_.vv_range(ci.v0)) collapses.ring.push_back(v.idx());
    collapses.offset.push_back(int(collapses.ring.size()));
  }

  VertexSplits collapses;  // in collapse order

 private:
  // The triangles of v0 with their corners and normals: the sweep's where it sweeps v0 (made
  // at its first candidate), else made now into `scratch_`.
  const std::vector<typename MeshT::Face>& faces_of(typename MeshT::VertexHandle v0) {
    const bool swept = v0 == mesh_.sweep.from;
    auto& faces = swept ? mesh_.sweep.faces : scratch_;
    if (swept && mesh_.sweep.faces_known) return faces;
    faces.clear();
    for (auto f : mesh_.vf_range(v0)) {
      typename MeshT::Face face;
      face.handle = f;
      int k = 0;
      for (auto v : mesh_.fv_range(f)) {
        face.vertex[k] = v;
        face.point[k] = mesh_.point(v);
        ++k;
      }
      triangle_quality(face.point[0], face.point[1], face.point[2], face.normal);
      faces.push_back(face);
    }
    if (swept) mesh_.sweep.faces_known = true;
    return faces;
  }
  std::vector<typename MeshT::Face> scratch_;

  // True if the border loop through border vertex v has more than min_boundary_loop vertices.
  bool long_loop(typename MeshT::VertexHandle v) const {
    auto h = mesh_.halfedge_handle(v);  // the border half-edge out of v
    for (int k = 0; k < mesh_.min_boundary_loop; ++k) {
      h = mesh_.next_halfedge_handle(h);
      if (mesh_.from_vertex_handle(h) == v) return false;
    }
    return true;
  }
  MeshT& mesh_;
};

Triangles snapshot(const Mesh& mesh) {
  Triangles T(Eigen::Index(mesh.n_faces()), 3);
  Eigen::Index t = 0;
  for (auto f : mesh.faces()) {
    int k = 0;
    for (auto v : f.vertices()) T(t, k++) = v.idx();
    ++t;
  }
  T.conservativeResize(t, 3);
  return T;
}

}  // namespace

int default_levels(int n_free) {
  if (n_free <= 1000) return 1;
  int levels = 1;
  for (double n = n_free; n > 250.0; n /= 4.0) ++levels;
  return levels;
}

Positions hierarchy_positions(const FairingRegion& region, const Positions& X_input,
                              const InnerFairnessWeights* lambda, int sweeps) {
  Positions X = X_input;
  const OneRings& r = region.rings;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    Positions Y = X;
    for (int i = 0; i < region.n_free; ++i) {
      Vec3 c = Vec3::Zero();
      if (lambda)
        c = weighted_centroid(*lambda, X, i);
      else
        for (int k = r.offset[i]; k < r.offset[i + 1]; ++k)
          c += (1.0 / r.valence(i)) * X.row(r.ring[k]).transpose();
      Y.row(i) = 0.5 * (X.row(i) + c.transpose());
    }
    X.swap(Y);
  }
  return X;
}

ProgressiveMesh build_progressive_mesh(const FairingRegion& region, const Positions& X,
                                       int levels, const Decimation& rules,
                                       const HierarchyTuning& tuning) {
  Mesh mesh;
  mesh.n_free = region.n_free;
  mesh.rules = rules;
  mesh.min_boundary_loop = tuning.min_boundary_loop;
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_face_status();
  for (int i = 0; i < region.n; ++i) {
    const auto v = mesh.add_vertex(Mesh::Point(X(i, 0), X(i, 1), X(i, 2)));
    if (i >= region.n_free && !rules.coarsen_boundary) mesh.status(v).set_locked(true);
  }
  for (Eigen::Index t = 0; t < region.triangles.rows(); ++t)
    mesh.add_face(mesh.vertex_handle(region.triangles(t, 0)), mesh.vertex_handle(region.triangles(t, 1)),
                  mesh.vertex_handle(region.triangles(t, 2)));

  mesh.start_decimation();
  OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
  typename ModFairingHierarchyT<Mesh>::Handle module;
  decimater.add(module);
  decimater.initialize();
  VertexSplits& collapses = decimater.module(module).collapses;

  // Finest level first; decimate stage by stage towards the base mesh.
  std::vector<Triangles> fine_to_coarse{region.triangles};
  std::vector<VertexSplits> splits_fine_to_coarse;
  const int n_boundary = region.n - region.n_free;
  const double n_free_min = tuning.min_free_per_boundary * n_boundary;
  double previous = region.n_free;
  int free_present = region.n_free;  // free vertices not collapsed yet
  for (int level = levels - 2; level >= 0; --level) {
    const double shrink = std::pow(4.0, levels - 1 - level);
    std::size_t target;  // vertices of the level
    if (rules.coarsen_boundary) {
      target = std::size_t(std::max(1.0, std::round(region.n / shrink)));
    } else {
      double n_free = region.n_free / shrink;
      if (n_free < n_free_min) {
        // Clamp the coarsest level to the floor, if that still coarsens by 1.5×.
        if (previous < 1.5 * n_free_min) break;
        n_free = n_free_min;
        level = 0;
      }
      previous = n_free;
      target = std::size_t(n_boundary) + std::size_t(std::max(1.0, std::round(n_free)));
    }
    collapses = VertexSplits{};
    // decimate_to counts deleted vertices too, so ask for the number of collapses.
    const std::size_t present = region.n - std::accumulate(splits_fine_to_coarse.begin(), splits_fine_to_coarse.end(), std::size_t(0), [](std::size_t a, const VertexSplits& s) { return a + s.size(); });
    if (present <= target) break;
    decimater.decimate(present - target);
    if (collapses.size() == 0) break;  // nothing more can be collapsed
    // Replaying the vertex splits undoes the collapses in reverse order.
    VertexSplits splits;
    for (std::size_t c = collapses.size(); c-- > 0;) {
      splits.vertex.push_back(collapses.vertex[c]);
      splits.ring.insert(splits.ring.end(), collapses.ring.begin() + collapses.offset[c],
                         collapses.ring.begin() + collapses.offset[c + 1]);
      splits.offset.push_back(int(splits.ring.size()));
    }
    free_present -= int(std::count_if(collapses.vertex.begin(), collapses.vertex.end(),
                                      [&](int v) { return v < region.n_free; }));
    // With the boundary coarsened, too few free vertices may remain: no such level (and
    // none coarser).
    if (rules.coarsen_boundary && free_present < tuning.min_level_free) break;
    splits_fine_to_coarse.push_back(std::move(splits));
    fine_to_coarse.push_back(snapshot(mesh));
  }
  ProgressiveMesh pm;
  pm.triangles.assign(fine_to_coarse.rbegin(), fine_to_coarse.rend());
  pm.splits.emplace_back();
  pm.splits.insert(pm.splits.end(), splits_fine_to_coarse.rbegin(), splits_fine_to_coarse.rend());
  return pm;
}

FairingRegion level_region(const FairingRegion& region, const Triangles& triangles) {
  std::vector<int> local(region.n, -1);
  std::vector<std::uint8_t> present(region.n, 0);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c) present[triangles(t, c)] = 1;
  FairingRegion level;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = pass ? region.n_free : 0; i < (pass ? region.n : region.n_free); ++i)
      if (present[i]) {
        local[i] = int(level.global.size());
        level.global.push_back(i);
        if (!pass) level.n_free = int(level.global.size());
      }
  level.n = int(level.global.size());
  level.triangles.resize(triangles.rows(), 3);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c) level.triangles(t, c) = local[triangles(t, c)];
  level.rings = build_one_rings(level.n, level.triangles, "fair");
  level.boundary = region.boundary;
  level.g1_normals.resize(level.n - level.n_free, 3);
  for (int b = level.n_free; b < level.n; ++b)
    level.g1_normals.row(b - level.n_free) = region.g1_normals.row(level.global[b] - region.n_free);
  return level;
}

}  // namespace geofair
