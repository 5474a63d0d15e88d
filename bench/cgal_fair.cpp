// CGAL's linear fairing, Polygon_mesh_processing::fair, as a reference for our benchmarks.
//
//   cgal_fair IN OUT
//
// IN is a little-endian binary file written by bench/cgal_fair.py:
//   int32 #V, int32 #F, int32 #free, float64 V[#V][3], int32 F[#F][3], int32 free[#free]
// OUT receives float64 V[#V][3], the vertex positions after fairing. Standard output gets
// one JSON line: {"seconds": wall time of fair() alone, "peak_mib": peak resident set of
// the process, "success": fair()'s return value}.
//
// fair() solves the linear system Δ^(k+1) x = 0 over the free vertices with k =
// fairing_continuity = 1 (the bilaplacian, tangent continuity through the fixed ring
// outside the region), cotangent weights with Voronoi areas, and Eigen's SparseLU:
// CGAL 5.5's defaults.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Surface_mesh.h>

#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <vector>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: cgal_fair IN OUT\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::int32_t header[3];
  if (!in.read(reinterpret_cast<char*>(header), sizeof header) || header[0] < 0 ||
      header[1] < 0 || header[2] < 0) {
    std::cerr << "cgal_fair: cannot read the header of " << argv[1] << "\n";
    return 2;
  }
  std::vector<double> V(3 * std::size_t(header[0]));
  std::vector<std::int32_t> F(3 * std::size_t(header[1])), free(header[2]);
  in.read(reinterpret_cast<char*>(V.data()), V.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(F.data()), F.size() * sizeof(std::int32_t));
  in.read(reinterpret_cast<char*>(free.data()), free.size() * sizeof(std::int32_t));
  if (!in) {
    std::cerr << "cgal_fair: " << argv[1] << " is truncated\n";
    return 2;
  }

  Mesh mesh;
  std::vector<Mesh::Vertex_index> vi(header[0]);
  for (std::int32_t i = 0; i < header[0]; ++i)
    vi[i] = mesh.add_vertex(Kernel::Point_3(V[3 * i], V[3 * i + 1], V[3 * i + 2]));
  for (std::int32_t f = 0; f < header[1]; ++f)
    if (mesh.add_face(vi[F[3 * f]], vi[F[3 * f + 1]], vi[F[3 * f + 2]]) == Mesh::null_face()) {
      std::cerr << "cgal_fair: face " << f << " is not manifold\n";
      return 2;
    }
  std::vector<Mesh::Vertex_index> region;
  region.reserve(free.size());
  for (std::int32_t i : free) {
    if (i < 0 || i >= header[0]) {
      std::cerr << "cgal_fair: free vertex index out of range\n";
      return 2;
    }
    region.push_back(vi[i]);
  }

  const auto start = std::chrono::steady_clock::now();
  const bool success = CGAL::Polygon_mesh_processing::fair(
      mesh, region, CGAL::parameters::fairing_continuity(1));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  for (std::int32_t i = 0; i < header[0]; ++i) {
    const auto& p = mesh.point(vi[i]);
    V[3 * i] = p.x();
    V[3 * i + 1] = p.y();
    V[3 * i + 2] = p.z();
  }
  std::ofstream out(argv[2], std::ios::binary);
  out.write(reinterpret_cast<const char*>(V.data()), V.size() * sizeof(double));
  if (!out) {
    std::cerr << "cgal_fair: cannot write " << argv[2] << "\n";
    return 2;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);  // ru_maxrss is in KiB on Linux
  std::printf("{\"seconds\": %.6f, \"peak_mib\": %.1f, \"success\": %s}\n", seconds,
              usage.ru_maxrss / 1024.0, success ? "true" : "false");
  return success ? 0 : 1;
}
