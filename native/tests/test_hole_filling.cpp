// fill_holes' combinatorial steps (hole_filling_internal.h): the boundary loops, Liepa's
// triangulation of a loop and the split of its edges across the hole.
#include "geofair/hole_filling.h"
#include "hole_filling_internal.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <vector>

namespace geofair {
namespace {

// The planar grid with the faces whose centroid lies within radius r of (cx, cy) removed.
testing::Mesh grid_with_hole(int n, double r, double cx = 0.0, double cy = 0.0) {
  testing::Mesh g = testing::planar_grid(n);
  std::vector<int> keep;
  for (int f = 0; f < g.F.rows(); ++f) {
    const Vec3 c = (g.V.row(g.F(f, 0)) + g.V.row(g.F(f, 1)) + g.V.row(g.F(f, 2))) / 3.0;
    if (std::hypot(c.x() - cx, c.y() - cy) > r) keep.push_back(f);
  }
  testing::Mesh m{g.V, Triangles(int(keep.size()), 3)};
  for (size_t k = 0; k < keep.size(); ++k) m.F.row(int(k)) = g.F.row(keep[k]);
  return m;
}

std::map<std::pair<int, int>, int> directed(const Triangles& F) {
  std::map<std::pair<int, int>, int> e;
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) e[{F(f, c), F(f, (c + 1) % 3)}] = F(f, (c + 2) % 3);
  return e;
}

TEST(DirectedEdges, AgreeWithAMapOfTheTriangles) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  const hole_filling::DirectedEdges edges(m.F);
  const auto reference = directed(m.F);
  const int n = int(m.V.rows());
  std::set<std::pair<int, int>> border;
  edges.for_each_border_edge([&](int a, int b) { border.insert({a, b}); });
  for (int a = 0; a < n; ++a) {
    std::set<int> at;
    edges.for_each_triangle_at(a, [&](int t) { at.insert(t); });
    std::set<int> expected;
    for (int f = 0; f < m.F.rows(); ++f)
      if (m.F(f, 0) == a || m.F(f, 1) == a || m.F(f, 2) == a) expected.insert(f);
    EXPECT_EQ(at, expected) << "vertex " << a;
    for (int b = 0; b < n; ++b) {
      const auto it = reference.find({a, b});
      EXPECT_EQ(edges.third(a, b), it == reference.end() ? -1 : it->second);
      EXPECT_EQ(edges.has(a, b), it != reference.end());
      const bool is_border = it != reference.end() && !reference.count({b, a});
      EXPECT_EQ(border.count({a, b}) == 1, is_border);
    }
  }
  EXPECT_EQ(edges.third(-1, 0), -1);
  EXPECT_EQ(edges.third(n, 0), -1);
}

TEST(BoundaryLoops, GridWithHoleHasOuterAndInnerLoop) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  const auto loops = boundary_loops(m.V, m.F);
  ASSERT_EQ(loops.size(), 2u);
  const auto edges = directed(m.F);
  for (const auto& loop : loops)
    for (size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      // Loop direction is the missing face's: the mesh has b -> a and not a -> b.
      EXPECT_TRUE(edges.count({b, a}));
      EXPECT_FALSE(edges.count({a, b}));
    }
}

TEST(TriangulateLoop, PlanarHoleIsFilledFlatAndOrientedLikeTheMesh) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  auto loops = hole_filling::holes_to_fill(m.V, m.F, {});
  // The inner loop is the shorter one.
  const auto& loop = loops[0].size() < loops[1].size() ? loops[0] : loops[1];
  const Triangles T = hole_filling::triangulate_loop(m.V, loop, hole_filling::DirectedEdges(m.F));
  ASSERT_EQ(T.rows(), Eigen::Index(loop.size() - 2));
  // Every triangle lies in z = 0 and faces +z like the grid, and the patch with the mesh
  // uses every loop edge once in each direction (a manifold, consistently oriented fill).
  auto edges = directed(m.F);
  for (int t = 0; t < T.rows(); ++t) {
    const Vec3 n = (m.V.row(T(t, 1)) - m.V.row(T(t, 0)))
                       .cross(m.V.row(T(t, 2)) - m.V.row(T(t, 0)))
                       .transpose();
    EXPECT_GT(n.z(), 0.0);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(m.V(T(t, c), 2), 0.0);
      EXPECT_TRUE(edges.emplace(std::make_pair(T(t, c), T(t, (c + 1) % 3)), t).second);
    }
  }
  for (int t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(edges.count({T(t, (c + 1) % 3), T(t, c)}));
}

TEST(SplitInnerEdges, EveryTriangleGetsAVertexOffTheLoop) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  auto loops = hole_filling::holes_to_fill(m.V, m.F, {});
  const auto& loop = loops[0].size() < loops[1].size() ? loops[0] : loops[1];
  const Triangles T = hole_filling::triangulate_loop(m.V, loop, hole_filling::DirectedEdges(m.F));
  const auto split = hole_filling::split_inner_edges(m.V, T, loop);
  const std::set<int> on_loop(loop.begin(), loop.end());
  // The edges across the hole: #triangles - 1 for a triangulated disc (n - 3).
  EXPECT_EQ(split.new_vertices.rows(), Eigen::Index(loop.size() - 3));
  for (int t = 0; t < split.faces.rows(); ++t) {
    int off_loop = 0;
    for (int c = 0; c < 3; ++c) off_loop += !on_loop.count(split.faces(t, c));
    EXPECT_GE(off_loop, 1);
  }
}

TEST(HolesToFill, RejectsALoopThatIsNotABoundary) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  // Three interior vertices of the grid, far from the hole.
  const std::vector<std::vector<int>> bad{{12, 13, 24}};
  EXPECT_THROW(hole_filling::holes_to_fill(m.V, m.F, bad), InvalidInputError);
  const testing::Mesh closed = testing::planar_grid(2);
  auto loops = hole_filling::holes_to_fill(closed.V, closed.F, {});
  EXPECT_EQ(loops.size(), 1u);  // the grid's own border is a hole
}

TEST(HolesToFill, AcceptsALoopInEitherDirectionAndOrientsIt) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  auto loops = hole_filling::holes_to_fill(m.V, m.F, {});
  const auto& loop = loops[0].size() < loops[1].size() ? loops[0] : loops[1];
  std::vector<int> reversed(loop.rbegin(), loop.rend());
  const auto given = hole_filling::holes_to_fill(m.V, m.F, {reversed});
  ASSERT_EQ(given.size(), 1u);
  EXPECT_EQ(std::set<int>(given[0].begin(), given[0].end()), std::set<int>(loop.begin(), loop.end()));
  const auto edges = directed(m.F);
  EXPECT_TRUE(edges.count({given[0][1], given[0][0]}));
}

TEST(SplitInnerEdges, AThreeVertexHoleGetsItsCentroid) {
  const testing::Mesh m = testing::hexagon_fan();
  const std::vector<int> loop{1, 2, 3};  // any triangle: no edge across it
  Triangles T(1, 3);
  T << 1, 2, 3;
  const auto split = hole_filling::split_inner_edges(m.V, T, loop);
  ASSERT_EQ(split.new_vertices.rows(), 1);
  EXPECT_NEAR((split.new_vertices.row(0) - (m.V.row(1) + m.V.row(2) + m.V.row(3)) / 3.0).norm(),
              0.0, 1e-15);
  ASSERT_EQ(split.faces.rows(), 3);
  for (int t = 0; t < 3; ++t) {
    EXPECT_EQ(split.faces(t, 2), int(m.V.rows()));  // each triangle uses the centroid
    for (int c = 0; c < 3; ++c) EXPECT_GE(split.faces(t, c), 1);
  }
}

TEST(SplitInnerEdges, ALongLoopGetsACentroidFan) {
  // The border of a 250×250 grid: 1000 vertices, above kMaxLiepaLoop.
  const testing::Mesh m = testing::planar_grid(250);
  const auto loops = hole_filling::holes_to_fill(m.V, m.F, {});
  ASSERT_EQ(loops.size(), 1u);
  ASSERT_GT(int(loops[0].size()), hole_filling::kMaxLiepaLoop);
  const Triangles T = hole_filling::triangulate_loop(m.V, loops[0], hole_filling::DirectedEdges(m.F));
  EXPECT_EQ(T.rows(), 0);
  const auto fan = hole_filling::split_inner_edges(m.V, T, loops[0]);
  ASSERT_EQ(fan.new_vertices.rows(), 1);
  EXPECT_NEAR(fan.new_vertices.row(0).norm(), 0.0, 1e-12);  // the square's centre
  EXPECT_EQ(fan.faces.rows(), Eigen::Index(loops[0].size()));
}

}  // namespace
}  // namespace geofair
