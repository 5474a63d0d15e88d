// geofair::fair's stop requests (FairingOptions::stop_requested, deadline): the polls
// between the steps that report no progress, through which fair() keeps its time limit.
#include "geofair/fairing.h"
#include "region.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace geofair {
namespace {

// The 40×40 grid on a sphere of radius 3, free within radius 0.8 of the pole (about 800
// free vertices), pushed outward by a bump of 0.1: a start far from the sphere.
struct DisturbedCap {
  testing::Mesh mesh = testing::onto_sphere(testing::planar_grid(40, 0.2), 3.0);
  std::vector<bool> free = testing::inside(mesh.V, 0.8);
  Positions normals = testing::sphere_normals(mesh.V);
  Positions V = mesh.V;

  DisturbedCap() {
    for (int v = 0; v < V.rows(); ++v)
      if (free[v]) V.row(v) *= 1.0 + 0.1 * (1.0 - V.row(v).head<2>().squaredNorm() / 0.64) / 3.0;
  }
};

FairingOptions with_levels(int levels) {
  FairingOptions options;
  options.levels = levels;
  options.time_limit = std::numeric_limits<double>::infinity();
  return options;
}

class StopRequested : public ::testing::TestWithParam<int> {};

// L of the residual (fairing.h): the diagonal of the region's bounding box in V.
double region_diagonal(const Positions& V, const FairingRegion& region) {
  Positions X(region.n, 3);
  for (int i = 0; i < region.n; ++i) X.row(i) = V.row(region.global[i]);
  return (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
}

// Stopped at the first poll, before any level: the input itself, unconverged, with the
// residual of the input (that of a converged input is its converged residual, measured in
// the input's L).
TEST_P(StopRequested, AtTheFirstPollReturnsTheInputWithItsResidual) {
  const DisturbedCap cap;
  const FairingResult solved = fair(cap.V, cap.mesh.F, cap.free, &cap.normals, with_levels(GetParam()));
  ASSERT_TRUE(solved.converged) << solved.message;
  FairingOptions options = with_levels(GetParam());
  options.stop_requested = [] { return true; };
  const FairingResult stopped = fair(solved.vertices, cap.mesh.F, cap.free, &cap.normals, options);
  EXPECT_FALSE(stopped.converged);
  EXPECT_EQ(stopped.message.rfind("cancelled", 0), 0u) << stopped.message;
  EXPECT_TRUE(stopped.vertices == solved.vertices);
  const FairingRegion region = extract_region(cap.V, cap.mesh.F, cap.free, &cap.normals);
  const double expected = solved.residual * region_diagonal(solved.vertices, region) /
                          region_diagonal(cap.V, region);
  EXPECT_NEAR(stopped.residual, expected, 1e-9 * expected);
  EXPECT_LE(stopped.residual, options.tolerance);
}

// A stop requested at any poll of a run is honoured there: no later poll, an unconverged
// result with finite positions and the fixed vertices as they were.
TEST_P(StopRequested, AtEveryPollEndsTheRunThere) {
  const DisturbedCap cap;
  int polls = 0;
  FairingOptions counting = with_levels(GetParam());
  counting.stop_requested = [&polls] { return ++polls < 0; };
  const FairingResult full = fair(cap.V, cap.mesh.F, cap.free, &cap.normals, counting);
  ASSERT_TRUE(full.converged) << full.message;
  // The levels' starts and the relaxations before Newton's steps.
  ASSERT_GE(polls, 2 * GetParam());
  for (int stop_at = 1; stop_at <= polls; ++stop_at) {
    int seen = 0;
    FairingOptions options = with_levels(GetParam());
    options.stop_requested = [&seen, stop_at] { return ++seen >= stop_at; };
    const FairingResult r = fair(cap.V, cap.mesh.F, cap.free, &cap.normals, options);
    EXPECT_EQ(seen, stop_at) << "polled after the stop";
    EXPECT_FALSE(r.converged) << "stop at poll " << stop_at;
    EXPECT_TRUE(r.vertices.allFinite());
    EXPECT_TRUE(std::isfinite(r.residual));
    for (int v = 0; v < cap.V.rows(); ++v)
      if (!cap.free[v]) EXPECT_TRUE(r.vertices.row(v) == cap.V.row(v)) << "fixed vertex " << v;
  }
}

INSTANTIATE_TEST_SUITE_P(Levels, StopRequested, ::testing::Values(1, 2));

// FairingOptions::deadline: one already passed stops the solve at its first poll as a time
// limit (its seconds in the message), whatever time_limit is; one far ahead changes nothing.
TEST(Deadline, StopsAsATimeLimitAndOneNotReachedChangesNothing) {
  const DisturbedCap cap;
  FairingOptions options;  // the automatic time limit
  const FairingResult free_run = fair(cap.V, cap.mesh.F, cap.free, &cap.normals, options);
  ASSERT_TRUE(free_run.converged) << free_run.message;
  const auto now = std::chrono::steady_clock::now();
  options.deadline = FairingOptions::Deadline{now + std::chrono::hours(1), 3600.0};
  const FairingResult ahead = fair(cap.V, cap.mesh.F, cap.free, &cap.normals, options);
  EXPECT_TRUE(ahead.vertices == free_run.vertices);
  options.deadline = FairingOptions::Deadline{now, 0.25};
  for (const double time_limit : {-1.0, std::numeric_limits<double>::infinity()}) {
    options.time_limit = time_limit;
    const FairingResult stopped = fair(cap.V, cap.mesh.F, cap.free, &cap.normals, options);
    EXPECT_FALSE(stopped.converged);
    EXPECT_EQ(stopped.stop_reason, StopReason::TimeLimit);
    EXPECT_EQ(stopped.message.rfind("stopped at the time limit of 2.5e-01 s", 0), 0u)
        << stopped.message;
    EXPECT_TRUE(stopped.vertices == cap.V);
    // The caller's limit, not a failure of the method: no hint at another inner fairness.
    EXPECT_EQ(stopped.message.find("inner fairness"), std::string::npos) << stopped.message;
  }
  for (const double seconds : {-1.0, std::nan("")}) {
    options.deadline = FairingOptions::Deadline{now, seconds};
    EXPECT_THROW(fair(cap.V, cap.mesh.F, cap.free, &cap.normals, options), InvalidInputError);
  }
}

// The hexagon's centre moved outside it, across vertex 1: the two triangles at vertex 1 flip
// over, so the two edges between a flipped and an unflipped triangle are folds.
TEST(CountFolds, CountsEdgesBetweenAFlippedAndAnUnflippedTriangle) {
  const testing::Mesh m = testing::hexagon_fan();
  std::vector<bool> free(7, false);
  free[0] = true;
  Positions after = m.V;
  after.row(0) << 2.0, 0.0, 0.0;
  FoldCount count = count_folds(m.V, after, m.F, free);
  EXPECT_EQ(count.folds, 2);
  EXPECT_EQ(count.new_folds, 2);
  // Folds already in the input are not new; edges without a free vertex are not counted.
  count = count_folds(after, after, m.F, free);
  EXPECT_EQ(count.folds, 2);
  EXPECT_EQ(count.new_folds, 0);
  EXPECT_EQ(count_folds(m.V, after, m.F, std::vector<bool>(7, false)).folds, 0);
  // Raising or lowering the centre bends the fan without flipping a triangle.
  after.row(0) << 0.1, 0.0, -0.5;
  EXPECT_EQ(count_folds(m.V, after, m.F, free).folds, 0);
}

}  // namespace
}  // namespace geofair
