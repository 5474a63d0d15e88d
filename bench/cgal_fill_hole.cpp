// CGAL's hole filling, Polygon_mesh_processing::triangulate_refine_and_fair_hole, as the
// linear reference of bench/holes.py.
//
//   cgal_fill_hole IN OUT
//
// IN is a little-endian binary file written by geofair_dev.cgal_fill_hole:
//   int32 #V, int32 #F, int32 #L, float64 V[#V][3], int32 F[#F][3], int32 loop[#L]
// where loop lists the vertices of one boundary loop of the mesh (any start, either
// direction). OUT receives int32 #V', int32 #F', float64 V'[#V'][3], int32 F'[#F'][3]: the
// mesh after filling, the input's #V vertices and #F faces first (unchanged), the new ones
// after. Standard output gets one JSON line: {"seconds": wall time of
// triangulate_refine_and_fair_hole() alone, "triangulate_seconds", "refine_seconds",
// "fair_seconds": its phases (from the hole-filling visitor), "peak_mib": peak resident set
// of the process, "success": fair()'s return value, "new_vertices", "new_faces"}.
//
// CGAL 5.5's defaults: the hole is triangulated (a 2D constrained Delaunay triangulation of
// the boundary projected on its least-squares plane when that is near planar, else the
// minimum-weight triangulation over the 3D Delaunay search space), refined (Liepa's
// refinement, density_control_factor sqrt(2), the new vertices' edge lengths interpolated
// from the boundary's) and faired: fair() with fairing_continuity 1, the bilaplacian
// Δ²x = 0 with cotangent weights, tangent continuity through the fixed ring around the hole,
// Eigen's SparseLU.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <tuple>
#include <vector>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Clock = std::chrono::steady_clock;

namespace {

// Wall time of the phases of triangulate_refine_and_fair_hole. CGAL copies or references the
// visitor depending on the call; the times live behind a pointer so either works.
struct Phases {
  Clock::time_point start, refine_start, fair_start, end;
};

struct TimingVisitor : CGAL::Polygon_mesh_processing::Hole_filling::Default_visitor {
  Phases* phases;
  explicit TimingVisitor(Phases* p) : phases(p) {}
  void start_refine_phase() const { phases->refine_start = Clock::now(); }
  void start_fair_phase() const { phases->fair_start = Clock::now(); }
  void end_fair_phase() const { phases->end = Clock::now(); }
};

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: cgal_fill_hole IN OUT\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::int32_t header[3];
  if (!in.read(reinterpret_cast<char*>(header), sizeof header) || header[0] < 0 ||
      header[1] < 0 || header[2] < 3) {
    std::cerr << "cgal_fill_hole: cannot read the header of " << argv[1] << "\n";
    return 2;
  }
  const std::int32_t nv = header[0], nf = header[1], nl = header[2];
  std::vector<double> V(3 * std::size_t(nv));
  std::vector<std::int32_t> F(3 * std::size_t(nf)), loop(nl);
  in.read(reinterpret_cast<char*>(V.data()), V.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(F.data()), F.size() * sizeof(std::int32_t));
  in.read(reinterpret_cast<char*>(loop.data()), loop.size() * sizeof(std::int32_t));
  if (!in) {
    std::cerr << "cgal_fill_hole: " << argv[1] << " is truncated\n";
    return 2;
  }

  Mesh mesh;
  std::vector<Mesh::Vertex_index> vi(nv);
  for (std::int32_t i = 0; i < nv; ++i)
    vi[i] = mesh.add_vertex(Kernel::Point_3(V[3 * i], V[3 * i + 1], V[3 * i + 2]));
  for (std::int32_t f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k)
      if (F[3 * f + k] < 0 || F[3 * f + k] >= nv) {
        std::cerr << "cgal_fill_hole: face " << f << " has a vertex index out of range\n";
        return 2;
      }
    if (mesh.add_face(vi[F[3 * f]], vi[F[3 * f + 1]], vi[F[3 * f + 2]]) == Mesh::null_face()) {
      std::cerr << "cgal_fill_hole: face " << f << " is not manifold\n";
      return 2;
    }
  }
  for (std::int32_t i : loop)
    if (i < 0 || i >= nv) {
      std::cerr << "cgal_fill_hole: loop vertex index out of range\n";
      return 2;
    }

  // The border halfedge of the loop: between its first two vertices, on the hole's side.
  Mesh::Halfedge_index border;
  const Mesh::Halfedge_index h = mesh.halfedge(vi[loop[0]], vi[loop[1]]);
  if (h != Mesh::null_halfedge()) {
    if (mesh.is_border(h))
      border = h;
    else if (mesh.is_border(mesh.opposite(h)))
      border = mesh.opposite(h);
  }
  if (border == Mesh::null_halfedge()) {
    std::cerr << "cgal_fill_hole: loop[0]-loop[1] is not a border edge\n";
    return 2;
  }
  std::int32_t cycle = 0;
  for (Mesh::Halfedge_index g : CGAL::halfedges_around_face(border, mesh)) {
    (void)g;
    ++cycle;
  }
  if (cycle != nl) {
    std::cerr << "cgal_fill_hole: the border cycle has " << cycle << " edges, the loop " << nl
              << "\n";
    return 2;
  }

  Phases phases;
  std::vector<Mesh::Face_index> new_faces;
  std::vector<Mesh::Vertex_index> new_vertices;
  phases.start = Clock::now();
  phases.refine_start = phases.fair_start = phases.end = phases.start;
  const auto result = CGAL::Polygon_mesh_processing::triangulate_refine_and_fair_hole(
      mesh, border, std::back_inserter(new_faces), std::back_inserter(new_vertices),
      CGAL::parameters::visitor(TimingVisitor(&phases)));
  const auto stop = Clock::now();
  const bool success = std::get<0>(result);

  // Surface_mesh appends new elements; nothing is removed by the hole filling, so the
  // input's indices stay the first ones.
  if (mesh.has_garbage()) {
    std::cerr << "cgal_fill_hole: the mesh has removed elements after filling\n";
    return 2;
  }
  const std::int32_t nv_out = std::int32_t(mesh.number_of_vertices());
  const std::int32_t nf_out = std::int32_t(mesh.number_of_faces());
  std::vector<double> V_out(3 * std::size_t(nv_out));
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    const std::size_t i = std::size_t(v);
    V_out[3 * i] = p.x();
    V_out[3 * i + 1] = p.y();
    V_out[3 * i + 2] = p.z();
  }
  std::vector<std::int32_t> F_out;
  F_out.reserve(3 * std::size_t(nf_out));
  for (Mesh::Face_index f : mesh.faces())
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      F_out.push_back(std::int32_t(std::size_t(v)));
  if (F_out.size() != 3 * std::size_t(nf_out)) {
    std::cerr << "cgal_fill_hole: the result is not a triangle mesh\n";
    return 2;
  }

  std::ofstream out(argv[2], std::ios::binary);
  const std::int32_t out_header[2] = {nv_out, nf_out};
  out.write(reinterpret_cast<const char*>(out_header), sizeof out_header);
  out.write(reinterpret_cast<const char*>(V_out.data()), V_out.size() * sizeof(double));
  out.write(reinterpret_cast<const char*>(F_out.data()), F_out.size() * sizeof(std::int32_t));
  if (!out) {
    std::cerr << "cgal_fill_hole: cannot write " << argv[2] << "\n";
    return 2;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);  // ru_maxrss is in KiB on Linux
  std::printf(
      "{\"seconds\": %.6f, \"triangulate_seconds\": %.6f, \"refine_seconds\": %.6f, "
      "\"fair_seconds\": %.6f, \"peak_mib\": %.1f, \"success\": %s, \"new_vertices\": %d, "
      "\"new_faces\": %d}\n",
      seconds_between(phases.start, stop), seconds_between(phases.start, phases.refine_start),
      seconds_between(phases.refine_start, phases.fair_start),
      seconds_between(phases.fair_start, phases.end), usage.ru_maxrss / 1024.0,
      success ? "true" : "false", nv_out - nv, nf_out - nf);
  return success ? 0 : 1;
}
