// Projection of moved vertices back onto a reference surface (surface_projection.h).
#include "surface_projection.h"
#include "common.h"
#include "region.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace geofair {
namespace {

// A hemisphere of radius 2 over a 24×24 grid of [-1, 1]², the vertices within 0.8 of the
// axis free; each free vertex is moved in its tangent plane by `move` grid spacings (a
// different direction per vertex), far across the mesh, and projected back.
double largest_distance_from_the_sphere(double move, double& linear_bound) {
  const double r = 2.0, h = 2.0 / 24;
  const testing::Mesh m = testing::onto_sphere(testing::planar_grid(24, 0.3), r);
  const Positions normals = testing::sphere_normals(m.V);
  const FairingRegion region = extract_region(m.V, m.F, testing::inside(m.V, 0.8), &normals);
  const Positions R = gather(m.V, region.global);
  const Positions NR = gather(normals, region.global);
  SurfaceProjection projection(region, R, NR);
  Positions X = R;
  double distance = 0.0;
  for (int i = 0; i < region.n_free; ++i) {
    const Vec3 n = NR.row(i).transpose();
    const Vec3 a = n.cross(Vec3::UnitZ()).normalized(), b = n.cross(a);
    const double angle = 2.399963 * i;  // the golden angle: directions all round
    X.row(i) += (move * h * (std::cos(angle) * a + std::sin(angle) * b)).transpose();
    projection.project(i, X);
    distance = std::max(distance, std::abs(X.row(i).norm() - r));
  }
  linear_bound = h * h / (8.0 * r);  // the flat triangles' distance at an edge's midpoint
  return distance;
}

// Phong tessellation with shape factor 1/2 is exact at edge midpoints and centroids of a
// sphere: what is left is of higher order than the flat triangles' h²/(8r).
TEST(SurfaceProjection, LongTangentialMovesComeBackOntoTheSphere) {
  // Before the projection a move of 6 spacings leaves the sphere by about (6h)²/(2r).
  double linear_bound = 0.0;
  const double distance = largest_distance_from_the_sphere(6.0, linear_bound);
  EXPECT_LT(distance, 0.05 * linear_bound);
}

TEST(SurfaceProjection, AShortMoveStaysWhereTheSphereIs) {
  double linear_bound = 0.0;
  const double distance = largest_distance_from_the_sphere(0.3, linear_bound);
  EXPECT_LT(distance, 0.05 * linear_bound);
}

}  // namespace
}  // namespace geofair
