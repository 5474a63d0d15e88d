// The progressive mesh of the multigrid construction (Schneider & Kobbelt 2001, section
// 7.4; Hoppe 1996): nested levels, replayable vertex splits.
#include "progressive_mesh.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace geofair {
namespace {

std::set<int> vertices_of(const Triangles& F) {
  std::set<int> used(F.data(), F.data() + F.size());
  return used;
}

std::set<std::array<int, 3>> rotated_triangles(const Triangles& F) {
  std::set<std::array<int, 3>> out;
  for (int t = 0; t < F.rows(); ++t) {
    std::array<int, 3> tri{F(t, 0), F(t, 1), F(t, 2)};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    out.insert(tri);
  }
  return out;
}

// The 40×40 grid on a sphere of radius 3 (interior vertices jittered by `jitter` of the
// spacing), free within radius 0.8, with the sphere's G1 normals; X: the region's positions.
struct SphereRegion {
  testing::Mesh mesh;
  FairingRegion region;
  Positions X;

  explicit SphereRegion(double jitter)
      : mesh(testing::onto_sphere(testing::planar_grid(40, jitter), 3.0)) {
    const Positions N = testing::sphere_normals(mesh.V);
    region = extract_region(mesh.V, mesh.F, testing::inside(mesh.V, 0.8), &N);
    X.resize(region.n, 3);
    for (int i = 0; i < region.n; ++i) X.row(i) = mesh.V.row(region.global[i]);
  }
};

class ProgressiveMeshTest : public ::testing::TestWithParam<bool> {};

TEST_P(ProgressiveMeshTest, LevelsAreNestedAndSplitsAddTheMissingVertices) {
  const bool coarsen_boundary = GetParam();
  const SphereRegion sphere(0.2);
  const FairingRegion& region = sphere.region;
  const Positions& X = sphere.X;
  const ProgressiveMesh pm = build_progressive_mesh(
      region, X, 3, coarsen_boundary ? kNewtonDecimation : kPaperDecimation);
  ASSERT_EQ(pm.triangles.size(), 3u);
  ASSERT_EQ(pm.splits.size(), 3u);
  EXPECT_EQ(rotated_triangles(pm.triangles.back()), rotated_triangles(region.triangles));
  for (std::size_t l = 1; l < pm.triangles.size(); ++l) {
    const std::set<int> coarse = vertices_of(pm.triangles[l - 1]), fine = vertices_of(pm.triangles[l]);
    EXPECT_TRUE(std::includes(fine.begin(), fine.end(), coarse.begin(), coarse.end()));
    EXPECT_LT(coarse.size(), fine.size());
    // The splits re-insert exactly the vertices the coarser level lacks, each once, each
    // with a ring of vertices that exist when it is replayed.
    std::set<int> present = coarse;
    const VertexSplits& s = pm.splits[l];
    for (std::size_t k = 0; k < s.size(); ++k) {
      EXPECT_FALSE(present.count(s.vertex[k]));
      for (int r = s.offset[k]; r < s.offset[k + 1]; ++r) EXPECT_TRUE(present.count(s.ring[r]));
      present.insert(s.vertex[k]);
    }
    EXPECT_EQ(present, fine);
  }
  // Without boundary coarsening every level keeps the whole G1 boundary.
  if (!coarsen_boundary) {
    const std::set<int> base = vertices_of(pm.triangles.front());
    for (int b = region.n_free; b < region.n; ++b) EXPECT_TRUE(base.count(b)) << "boundary " << b;
  }
  // The coarsest level is a valid fairing region of its own.
  const FairingRegion base = level_region(region, pm.triangles.front());
  EXPECT_GT(base.n_free, 0);
  EXPECT_LT(base.n_free, region.n_free / 4);
}

TEST_P(ProgressiveMeshTest, CollapsesKeepTheTriangleQuality) {
  // Every triangle a collapse makes has quality 4√3·area / Σ edge² of at least the rules'
  // min_quality (the input's right triangles have 0.87), measured on the positions the
  // hierarchy was built on.
  const Decimation& rules = GetParam() ? kNewtonDecimation : kPaperDecimation;
  const SphereRegion sphere(0.0);
  const FairingRegion& region = sphere.region;
  const Positions& X = sphere.X;
  const ProgressiveMesh pm = build_progressive_mesh(region, X, 3, rules);
  ASSERT_EQ(pm.triangles.size(), 3u);
  const std::set<std::array<int, 3>> input = rotated_triangles(region.triangles);
  int made = 0;
  for (std::size_t l = 0; l + 1 < pm.triangles.size(); ++l)
    for (const std::array<int, 3>& t : rotated_triangles(pm.triangles[l])) {
      if (input.count(t)) continue;
      ++made;
      const Vec3 a = X.row(t[0]), b = X.row(t[1]), c = X.row(t[2]);
      const double edges = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
      const double quality = 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / edges;
      EXPECT_GE(quality, rules.min_quality) << "level " << l;
    }
  EXPECT_GT(made, 0);
}

INSTANTIATE_TEST_SUITE_P(BoundaryLockedAndCoarsened, ProgressiveMeshTest, ::testing::Bool());

}  // namespace
}  // namespace geofair
