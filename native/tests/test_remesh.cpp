// remesh_region's contract (fixed rows, the region's border, the row layout) and fair's
// remesh modes where the solve with the connectivity kept is cancelled or out of time.
#include "geofair/building_blocks.h"
#include "geofair/fairing.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace geofair {
namespace {

// The 20×20 grid on a sphere of radius 3, free within radius 0.8 of the pole.
struct Cap {
  testing::Mesh mesh = testing::onto_sphere(testing::planar_grid(20), 3.0);
  std::vector<bool> free = testing::inside(mesh.V, 0.8);
  Positions normals = testing::sphere_normals(mesh.V);
};

// The directed edges of the triangles with a free vertex that have no opposite in them.
std::set<std::pair<int, int>> border(const Triangles& F, const std::vector<bool>& free) {
  std::set<std::pair<int, int>> edges, out;
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    if (free[F(t, 0)] || free[F(t, 1)] || free[F(t, 2)])
      for (int k = 0; k < 3; ++k) edges.insert({F(t, k), F(t, (k + 1) % 3)});
  for (const auto& [a, b] : edges)
    if (!edges.count({b, a})) out.insert({a, b});
  return out;
}

TEST(RemeshRegion, KeepsFixedRowsAndTheRegionsBorder) {
  const Cap cap;
  RemeshOptions options;
  options.target_edge_length = 0.05;  // a third of the grid's spacing: many new vertices
  const RemeshedRegion r = remesh_region(cap.mesh.V, cap.mesh.F, cap.free, options);
  const Eigen::Index n = cap.mesh.V.rows();
  const long n_fixed = std::count(cap.free.begin(), cap.free.end(), false);
  const long n_new = std::count(r.free.begin(), r.free.end(), true);
  ASSERT_EQ(r.vertices.rows(), std::max<Eigen::Index>(n, n_fixed + n_new));
  for (Eigen::Index v = 0; v < n; ++v)
    if (!cap.free[v]) {
      EXPECT_TRUE(r.vertices.row(v) == cap.mesh.V.row(v)) << v;
      EXPECT_FALSE(r.free[v]);
    }
  EXPECT_EQ(border(r.faces, r.free), border(cap.mesh.F, cap.free));
  EXPECT_TRUE(r.unreferenced.empty());  // more new free vertices than old ones
  for (Eigen::Index v = 0; v < r.vertices.rows(); ++v) {
    ASSERT_EQ(r.origin_face[v] >= 0, bool(r.free[v])) << v;
    if (!r.free[v]) continue;
    Vec3 p = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      p += r.origin_barycentric(v, k) * Vec3(cap.mesh.V.row(cap.mesh.F(r.origin_face[v], k)));
    EXPECT_LE((p - Vec3(r.vertices.row(v))).norm(), 1e-12) << v;
  }
}

TEST(RemeshRegion, RejectsANonManifoldRegion) {
  const Cap cap;
  Eigen::Index t = 0;
  while (!cap.free[cap.mesh.F(t, 0)]) ++t;
  Triangles F(cap.mesh.F.rows() + 1, 3);
  F << cap.mesh.F, cap.mesh.F.row(t);  // a region triangle twice: its edges in 3 triangles
  try {
    remesh_region(cap.mesh.V, F, cap.free, {});
    FAIL() << "no exception";
  } catch (const InvalidInputError& error) {
    EXPECT_NE(std::string(error.what()).find("non-manifold"), std::string::npos) << error.what();
  }
}

// IfNeeded does not remesh a solve that was cancelled or that spent an explicit time limit.
TEST(FairRemesh, IfNeededStopsWhereTheFirstSolveWasCancelledOrOutOfTime) {
  const Cap cap;
  FairingOptions options;
  options.remesh = Remesh::IfNeeded;
  options.stop_requested = [] { return true; };
  FairingResult r = fair(cap.mesh.V, cap.mesh.F, cap.free, &cap.normals, options);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.stop_reason, StopReason::Cancelled);
  EXPECT_FALSE(r.remeshed);
  options.stop_requested = nullptr;
  options.time_limit = 0.0;
  r = fair(cap.mesh.V, cap.mesh.F, cap.free, &cap.normals, options);
  EXPECT_EQ(r.stop_reason, StopReason::TimeLimit);
  EXPECT_FALSE(r.remeshed);
  EXPECT_TRUE(r.faces == cap.mesh.F);
}

}  // namespace
}  // namespace geofair
