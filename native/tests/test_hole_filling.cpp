// fill_holes' combinatorial steps (hole_filling_internal.h): the boundary loops, which of
// them are holes, Liepa's triangulation of a loop and the split of its edges across the
// hole; the working scale (mesh_scale.h).
#include "geofair/hole_filling.h"
#include "hole_filling_internal.h"
#include "mesh_scale.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

TEST(HolesToFill, LeavesTheOuterBorderOfASheetOpen) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  const auto loops = boundary_loops(m.V, m.F);
  ASSERT_EQ(loops.size(), 2u);
  const size_t inner = loops[0].size() < loops[1].size() ? 0 : 1;
  const HoleChoice choice = holes_to_fill(m.V, m.F);
  ASSERT_EQ(choice.holes.size(), 1u);
  EXPECT_EQ(choice.holes[0], loops[inner]);
  ASSERT_EQ(choice.left_open.size(), 1u);
  EXPECT_EQ(choice.left_open[0].loop, loops[1 - inner]);
  EXPECT_NE(choice.left_open[0].reason.find("an outer border"), std::string::npos);
  // The rule's options: every loop, or none longer than the inner one's edges less one.
  EXPECT_EQ(holes_to_fill(m.V, m.F, HoleRule{false, 0}).holes, loops);
  const int shorter = int(loops[inner].size()) - 1;
  const HoleChoice none = holes_to_fill(m.V, m.F, HoleRule{false, shorter});
  EXPECT_TRUE(none.holes.empty());
  ASSERT_EQ(none.left_open.size(), 2u);
  EXPECT_NE(none.left_open[inner].reason.find("more edges than max_hole_edges"), std::string::npos);
  EXPECT_THROW(holes_to_fill(m.V, m.F, HoleRule{true, -1}), InvalidInputError);
  // The same at any scale.
  for (double scale : {1e-100, 1e100})
    EXPECT_EQ(holes_to_fill(m.V * scale, m.F).holes, choice.holes) << scale;
}

TEST(HolesToFill, FillsTheHolesOfAClosedSurface) {
  // A pillow: the dome z = 2 (1 − x²)(1 − y²) over the grid with a hole, closed by the flat
  // grid with another hole below it, mirrored (x → −x: it faces down, and its diagonals
  // differ from the dome's), which shares the dome's border vertices.
  testing::Mesh dome = grid_with_hole(10, 0.45);
  for (int v = 0; v < dome.V.rows(); ++v)
    dome.V(v, 2) = 2.0 * (1.0 - dome.V(v, 0) * dome.V(v, 0)) * (1.0 - dome.V(v, 1) * dome.V(v, 1));
  const testing::Mesh floor = grid_with_hole(10, 0.45, -0.5, 0.5);
  const int n = int(dome.V.rows());
  testing::Mesh m{Positions(2 * n, 3), Triangles(dome.F.rows() + floor.F.rows(), 3)};
  m.V.topRows(n) = dome.V;
  m.V.bottomRows(n) = floor.V;
  m.V.bottomRows(n).col(0) *= -1.0;
  m.F.topRows(dome.F.rows()) = dome.F;
  for (int f = 0; f < floor.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int v = floor.F(f, c), i = v % 11, j = v / 11;
      const bool border = i == 0 || j == 0 || i == 10 || j == 10;
      m.F(dome.F.rows() + f, c) = border ? j * 11 + (10 - i) : n + v;
    }
  const auto loops = boundary_loops(m.V, m.F);
  ASSERT_EQ(loops.size(), 2u);
  const HoleChoice choice = holes_to_fill(m.V, m.F);
  EXPECT_EQ(choice.holes, loops);
  EXPECT_TRUE(choice.left_open.empty());
}

TEST(TriangulateLoop, PlanarHoleIsFilledFlatAndOrientedLikeTheMesh) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  auto loops = hole_filling::holes_to_fill(m.V, m.F, {});
  ASSERT_EQ(loops.size(), 1u);  // the inner loop: the grid's border is an outer border
  const auto& loop = loops[0];
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
  const auto& loop = loops.at(0);
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
  // A sheet's own border is a hole only where the rule says so.
  const testing::Mesh sheet = testing::planar_grid(2);
  EXPECT_THROW(hole_filling::holes_to_fill(sheet.V, sheet.F, {}), InvalidInputError);
  auto loops = hole_filling::holes_to_fill(sheet.V, sheet.F, {}, HoleRule{false, 0});
  EXPECT_EQ(loops.size(), 1u);
}

TEST(HolesToFill, AcceptsALoopInEitherDirectionAndOrientsIt) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  auto loops = hole_filling::holes_to_fill(m.V, m.F, {});
  const auto& loop = loops.at(0);
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
  const auto loops = boundary_loops(m.V, m.F);
  ASSERT_EQ(loops.size(), 1u);
  ASSERT_GT(int(loops[0].size()), hole_filling::kMaxLiepaLoop);
  const Triangles T = hole_filling::triangulate_loop(m.V, loops[0], hole_filling::DirectedEdges(m.F));
  EXPECT_EQ(T.rows(), 0);
  const auto fan = hole_filling::split_inner_edges(m.V, T, loops[0]);
  ASSERT_EQ(fan.new_vertices.rows(), 1);
  EXPECT_NEAR(fan.new_vertices.row(0).norm(), 0.0, 1e-12);  // the square's centre
  EXPECT_EQ(fan.faces.rows(), Eigen::Index(loops[0].size()));
}

TEST(WorkingScale, IsOneInTheBandAndAPowerOfTwoNearTheEdgeLengthOutside) {
  const testing::Mesh m = grid_with_hole(10, 0.45);  // edges 0.2 to 0.28 long
  for (double scale : {1.0, 1e-8, 1e8}) EXPECT_EQ(working_scale(m.V * scale, m.F, "t"), 1.0);
  for (double scale : {1e-100, 1e100, 1e-150, 1e150}) {
    const double s = working_scale(m.V * scale, m.F, "t");
    EXPECT_EQ(std::frexp(s, new int), 0.5) << scale;  // a power of two
    const double relative = s / (0.23 * scale);
    EXPECT_GT(relative, 0.5) << scale;
    EXPECT_LT(relative, 2.0) << scale;
  }
}

// A deadline already passed, as an explicit time limit spent: the hole still gets the
// linear fill (one linear solve, not stopped by the deadline), no other attempt.
TEST(FillHoles, ADeadlinePassedGivesTheLinearFill) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  FairingOptions options;
  const FillResult in_time = fill_holes(m.V, m.F, {}, options);
  ASSERT_EQ(in_time.holes.size(), 2u);  // the hole, then the sheet's border left open
  EXPECT_EQ(in_time.holes[0].method, FillMethod::Intrinsic);
  options.deadline = FairingOptions::Deadline{std::chrono::steady_clock::now(), 0.0};
  const FillResult r = fill_holes(m.V, m.F, {}, options);
  ASSERT_EQ(r.holes.size(), 2u);
  EXPECT_EQ(r.holes[0].method, FillMethod::Linear);
  EXPECT_TRUE(r.holes[0].converged) << r.message;
  EXPECT_EQ(r.holes[0].attempts.size(), 1u);
  EXPECT_EQ(r.holes[1].method, FillMethod::None);
}

// The hole in the middle of grid_with_hole: the mesh, the hole's loop (the shorter of its two
// loops) and the vertices of the outer border.
struct GridHole {
  testing::Mesh mesh;
  std::vector<int> loop;
  std::vector<bool> outer;
};

GridHole grid_hole() {
  GridHole g{grid_with_hole(12, 0.35), {}, {}};
  auto loops = boundary_loops(g.mesh.V, g.mesh.F);
  std::sort(loops.begin(), loops.end(),
            [](const auto& a, const auto& b) { return a.size() < b.size(); });
  g.loop = loops[0];
  g.outer.assign(size_t(g.mesh.V.rows()), false);
  for (int v : loops[1]) g.outer[size_t(v)] = true;
  return g;
}

// F without the rows `removed` (sorted).
Triangles without(const Triangles& F, const std::vector<int>& removed) {
  Triangles out(F.rows() - Eigen::Index(removed.size()), 3);
  Eigen::Index k = 0;
  for (int f = 0; f < F.rows(); ++f)
    if (!std::binary_search(removed.begin(), removed.end(), f)) out.row(k++) = F.row(f);
  return out;
}

// `loop` is, up to where it starts, one of the boundary loops of F without `removed`.
bool is_a_border_loop(const GridHole& g, const std::vector<int>& loop,
                      const std::vector<int>& removed) {
  for (const auto& other : boundary_loops(g.mesh.V, without(g.mesh.F, removed))) {
    if (other.size() != loop.size()) continue;
    const auto at = std::find(other.begin(), other.end(), loop[0]);
    if (at == other.end()) continue;
    std::vector<int> turned(at, other.end());
    turned.insert(turned.end(), other.begin(), at);
    if (turned == loop) return true;
  }
  return false;
}

TEST(TrimFaces, RemovesRimFacesWhileTheHoleStaysOneLoopAndRefusesOthers) {
  const GridHole g = grid_hole();
  const hole_filling::DirectedEdges edges(g.mesh.F);
  std::set<int> at_loop;  // the faces with a loop vertex
  for (int v : g.loop) edges.for_each_triangle_at(v, [&](int f) { at_loop.insert(f); });
  // A face away from the hole would open a second hole: refused.
  int far = -1;
  for (int f = 0; f < g.mesh.F.rows() && far < 0; ++f) {
    bool near = false;
    for (int c = 0; c < 3; ++c) near = near || std::abs(g.mesh.V(g.mesh.F(f, c), 0)) < 0.7;
    if (!near) far = f;
  }
  ASSERT_GE(far, 0);
  const hole_filling::TrimmedHole none{g.loop, {}};
  const auto refused = hole_filling::trim_faces(g.mesh.F, edges, g.loop, none, {far}, g.outer);
  EXPECT_TRUE(refused.removed.empty());
  EXPECT_EQ(refused.loop, g.loop);
  // The rim's faces: as many as keep one simple loop, at most the loop's size; the loop is
  // the border of what is left.
  const std::vector<int> rim(at_loop.begin(), at_loop.end());
  ASSERT_GT(rim.size(), g.loop.size());
  const auto grown = hole_filling::trim_faces(g.mesh.F, edges, g.loop, none, rim, g.outer);
  EXPECT_FALSE(grown.removed.empty());
  EXPECT_LE(grown.removed.size(), g.loop.size());
  EXPECT_TRUE(std::is_sorted(grown.removed.begin(), grown.removed.end()));
  for (int f : grown.removed) EXPECT_TRUE(at_loop.count(f)) << f;
  EXPECT_TRUE(is_a_border_loop(g, grown.loop, grown.removed));
  // trim_rim goes on from a trim: it keeps the faces removed and the loop stays a border.
  const std::vector<int> first = {edges.triangle(g.loop[1], g.loop[0]),
                                   edges.triangle(g.loop[4], g.loop[3])};  // on loop edges
  const auto start = hole_filling::trim_faces(g.mesh.F, edges, g.loop, none, first, g.outer);
  ASSERT_FALSE(start.removed.empty());
  const auto on = hole_filling::trim_rim(g.mesh.V, g.mesh.F, edges, g.loop, g.outer, &start);
  EXPECT_TRUE(std::includes(on.removed.begin(), on.removed.end(), start.removed.begin(),
                            start.removed.end()));
  EXPECT_LE(on.removed.size(), g.loop.size());
  EXPECT_TRUE(is_a_border_loop(g, on.loop, on.removed));
}

TEST(WorkingScale, NamesTheScaleWhereSquaredLengthsLeaveTheDoubles) {
  const testing::Mesh m = grid_with_hole(10, 0.45);
  auto message = [&](double scale) {
    try {
      working_scale(m.V * scale, m.F, "fill_holes");
    } catch (const InvalidInputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(1e200).find("fill_holes: a mesh of size 2.8e+200 is too large: squared "
                                "lengths overflow"),
            std::string::npos)
      << message(1e200);
  EXPECT_NE(message(1e-160).find("fill_holes: edge lengths of 2.3e-161 are too small: squared "
                                 "lengths underflow"),
            std::string::npos)
      << message(1e-160);
}

}  // namespace
}  // namespace geofair
