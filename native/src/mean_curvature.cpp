// Moreton–Séquin mean curvature (Schneider & Kobbelt 2001, section 6).
#include "mean_curvature.h"

#include "common.h"
#include "small_ldlt.h"

#include <Eigen/Dense>

#include <cmath>
#include <string>

namespace geofair {
namespace {

// Accumulates the normal equations (11) of the least-squares fit (9), (10).
struct NormalEquations {
  Vec3 p, n, bx, by;
  // The symmetric AtA, entries (0,0) (0,1) (0,2) (1,1) (1,2) (2,2), accumulated as scalars.
  double a00 = 0.0, a01 = 0.0, a02 = 0.0, a11 = 0.0, a12 = 0.0, a22 = 0.0;
  Vec3 Atb = Vec3::Zero();  // right-hand side from κ_j, eq. (8)
  Vec3 Atc = Vec3::Zero();  // right-hand side from dκ_j/dt = 2/|q_j - p|², section 7.2

  NormalEquations(const Vec3& p_, const Vec3& n_) : p(p_), n(n_) { tangent_basis(n, bx, by); }

  void add(const Vec3& q) {
    const Vec3 d = q - p;
    const double dd = d.squaredNorm();
    const double dn = d.dot(n);
    const double tx = d.dot(bx), ty = d.dot(by);
    const double tt = tx * tx + ty * ty;
    if (!(tt > 1e-24 * dd) || !(dd > 0.0)) return;  // sample on the normal line: no direction
    const double inv = 1.0 / tt;
    const double r0 = tx * tx * inv, r1 = tx * ty * inv, r2 = ty * ty * inv;
    a00 += r0 * r0, a01 += r0 * r1, a02 += r0 * r2;
    a11 += r1 * r1, a12 += r1 * r2, a22 += r2 * r2;
    const double inv_dd = 1.0 / dd;
    const Vec3 row(r0, r1, r2);
    Atb += row * (-2.0 * dn * inv_dd);
    Atc += row * (2.0 * inv_dd);
  }

  CurvatureEstimate solve() const {
    Eigen::Matrix3d M;
    M << a00, a01, a02, a01, a11, a12, a02, a12, a22;
    const double reg = 1e-12 * M.trace();
    if (!(reg > 0.0)) return {};
    M.diagonal().array() += reg;
    // H = (x0 + x2)/2 = g·Atb / 2 with g = M⁻¹ (1, 0, 1), M symmetric positive definite:
    // g = adj(M) (1, 0, 1) / det M, the cofactors written out (3×3, no factorization).
    const double c00 = M(1, 1) * M(2, 2) - M(1, 2) * M(1, 2);
    const double c01 = M(0, 2) * M(1, 2) - M(0, 1) * M(2, 2);
    const double c02 = M(0, 1) * M(1, 2) - M(0, 2) * M(1, 1);
    const double c12 = M(0, 2) * M(0, 1) - M(0, 0) * M(1, 2);
    const double c22 = M(0, 0) * M(1, 1) - M(0, 1) * M(0, 1);
    const double det = M(0, 0) * c00 + M(0, 1) * c01 + M(0, 2) * c02;
    if (!(det > 0.0)) return {};
    const Vec3 g = Vec3(c00 + c02, c01 + c12, c02 + c22) / det;
    return {0.5 * g.dot(Atb), 0.5 * g.dot(Atc)};
  }
};

// Tangent plane of the least-squares paraboloid through q_i and its ring neighbours (and
// the flaps' far corners below valence 5):
// in the frame of the first guess n0, the height z_j = ⟨q_j - q_i, n0⟩ of neighbour j at
// tangent coordinates (x_j, y_j) is fitted by z = a x + b y + (L x² + 2M xy + N y²)/2, each
// equation scaled by 2/|q_j - q_i|² as the Moreton–Séquin rows (8)-(10) are; the normal is
// (n0 - a bx - b by)/|…|. Taylor's theorem makes the tilt error O(h²) on any smooth surface
// and any ring shape (the weighted normals are O(h) on irregular rings), so the curvature
// fit of eq. (11) in that plane is consistent. Returns n0 where fewer than five samples
// leave the fit undetermined or the fit tilts the plane by 45° or more.
Vec3 fitted_normal(const OneRings& rings, const Positions& X, int i, const Vec3& n0) {
  // Samples: the ring neighbours; below valence 5 (too few for five unknowns) also the
  // vertices across the ring edges (the far corners of the flaps).
  const int begin = rings.offset[i], end = rings.offset[i + 1];
  const bool flaps = end - begin < 5;
  const Vec3 q = X.row(i);
  auto for_each_sample = [&](auto&& f) {
    for (int k = begin; k < end; ++k) f(Vec3(X.row(rings.ring[k]).transpose() - q));
    if (flaps)
      for (int k = begin; k < end; ++k)
        if (rings.has_face[k] && rings.across[k] >= 0)
          f(Vec3(X.row(rings.across[k]).transpose() - q));
  };
  int count = 0;
  double mean_dd = 0.0;
  for_each_sample([&](const Vec3& d) { ++count, mean_dd += d.squaredNorm(); });
  if (count < 5) return n0;
  // Lengths in units of the samples' rms distance, so that the slopes and curvatures of
  // the fit are of one order and the relative Tikhonov term does not depend on the scale.
  const double unit = std::sqrt(mean_dd / count);
  if (!(unit > 0.0) || !std::isfinite(unit)) return n0;
  Vec3 bx, by;
  tangent_basis(n0, bx, by);
  Eigen::Matrix<double, 5, 5> AtA = Eigen::Matrix<double, 5, 5>::Zero();
  Eigen::Matrix<double, 5, 1> Atz = Eigen::Matrix<double, 5, 1>::Zero();
  for_each_sample([&](const Vec3& sample) {
    const Vec3 d = sample / unit;
    const double dd = d.squaredNorm();
    if (!(dd > 0.0)) return;
    const double x = d.dot(bx), y = d.dot(by), w = 2.0 / dd;
    const double row[5] = {w * x, w * y, 0.5 * w * x * x, w * x * y, 0.5 * w * y * y};
    // The lower triangle alone: what the LDLT and the trace read.
    for (int c = 0; c < 5; ++c)
      for (int r = c; r < 5; ++r) AtA(r, c) += row[r] * row[c];
    const double z = w * d.dot(n0);
    for (int r = 0; r < 5; ++r) Atz(r) += row[r] * z;
  });
  const double reg = 1e-12 * AtA.trace();
  if (!(reg > 0.0)) return n0;
  AtA.diagonal().array() += reg;
  const Eigen::Matrix<double, 5, 1> c = solve_small_ldlt<5>(AtA, Atz);
  const double a = c(0), b = c(1);
  if (!(a * a + b * b < 1.0)) return n0;
  return (n0 - a * bx - b * by).normalized();
}

}  // namespace

Vec3 vertex_normal(const OneRings& rings, const Positions& X, int i, NormalWeighting weighting) {
  const Vec3 q = X.row(i);
  Vec3 sum = Vec3::Zero();
  for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k) {
    if (!rings.has_face[k]) continue;
    const Vec3 e1 = X.row(rings.ring[k]).transpose() - q;
    const Vec3 e2 = X.row(rings.ring[rings.next_slot(i, k)]).transpose() - q;
    const Vec3 c = e1.cross(e2);
    switch (weighting) {
      case NormalWeighting::Area:
        sum += c;
        break;
      case NormalWeighting::Angle: {
        const double cn = c.norm();
        if (cn > 0.0) sum += std::atan2(cn, e1.dot(e2)) / cn * c;
        break;
      }
      case NormalWeighting::Max:
      case NormalWeighting::Quadric: {
        const double w = e1.squaredNorm() * e2.squaredNorm();
        if (w > 0.0) sum += c / w;
        break;
      }
    }
  }
  const double len = sum.norm();
  if (!(len > 0.0) || !std::isfinite(len)) return Vec3::Zero();
  if (weighting == NormalWeighting::Quadric) return fitted_normal(rings, X, i, sum / len);
  return sum / len;
}

Vec3 spiral_sample(const Vec3& a, const Vec3& normal_a, const Vec3& b, const Vec3& normal_b,
                   const Vec3& plane_direction) {
  const Vec3 mid = 0.5 * (a + b);
  const Vec3 d = b - a;
  const double len = d.norm();
  if (!(len > 0.0)) return mid;
  const Vec3 ex = d / len;
  Vec3 m = d.cross(plane_direction);  // normal of the plane E_j
  const double mn = m.norm();
  if (!(mn > 1e-12 * len * plane_direction.norm())) return mid;
  m /= mn;
  const Vec3 ey = m.cross(ex);  // in E_j, perpendicular to ab
  // Height above ab at the bisector of the arc through a and b tangent to t at a (or at b,
  // with the opposite sign): h·tan(θ/2) = h·sinθ/(1 + cosθ), θ the angle of t to ab.
  auto arc_height = [&](const Vec3& normal) {
    Vec3 t = normal.cross(m);
    const double tn = t.norm();
    if (!(tn > 0.0)) return 0.0;
    t /= tn;
    if (t.dot(ex) < 0.0) t = -t;  // the direction with the smaller angle to b - a
    return 0.5 * len * t.dot(ey) / (1.0 + t.dot(ex));
  };
  const double y = 0.5 * (arc_height(normal_a) - arc_height(normal_b));
  return mid + y * ey;
}

CurvatureEstimate moreton_sequin(const OneRings& rings, const Positions& X, const Positions& N,
                                 int i, const Vec3& p, const Vec3& n, bool spiral) {
  NormalEquations eq(p, n);
  for (int k = rings.offset[i]; k < rings.offset[i + 1]; ++k) {
    const int j = rings.ring[k];
    const Vec3 qj = X.row(j);
    eq.add(qj);
    if (!spiral || !rings.has_face[k]) continue;
    const int j1 = rings.ring[rings.next_slot(i, k)];
    const Vec3 qj1 = X.row(j1);
    Vec3 plane_direction = (qj - p).cross(qj1 - p).normalized();
    if (rings.across[k] >= 0) {
      const Vec3 x = X.row(rings.across[k]);
      plane_direction += (qj - qj1).cross(x - qj1).normalized();
    }
    eq.add(spiral_sample(qj, N.row(j), qj1, N.row(j1), plane_direction));
  }
  return eq.solve();
}

Eigen::VectorXd mean_curvature(const Positions& V, const Triangles& F, const Positions* normals,
                               NormalWeighting weighting) {
  const char* fn = "mean_curvature";
  const int nv = int(V.rows());
  if (!V.allFinite()) {
    for (int v = 0; v < nv; ++v)
      if (!V.row(v).allFinite())
        throw InvalidInputError(std::string(fn) + ": vertex " + std::to_string(v) +
                                " has a non-finite coordinate");
  }
  const OneRings rings = build_one_rings(nv, F, fn);
  Positions N(nv, 3);
  if (normals) {
    if (normals->rows() != nv)
      throw InvalidInputError(std::string(fn) + ": normals has " + std::to_string(normals->rows()) +
                              " rows for " + std::to_string(nv) + " vertices");
    for (int v = 0; v < nv; ++v) {
      const double len = normals->row(v).norm();
      if (!std::isfinite(len) || std::abs(len - 1.0) > 1e-6)
        throw InvalidInputError(std::string(fn) + ": normals[" + std::to_string(v) +
                                "] is not a finite unit vector");
      N.row(v) = normals->row(v) / len;
    }
  } else {
    for (int v = 0; v < nv; ++v) N.row(v) = vertex_normal(rings, V, v, weighting);
  }
  Eigen::VectorXd H = Eigen::VectorXd::Zero(nv);
  for (int v = 0; v < nv; ++v) {
    if (rings.valence(v) == 0) continue;
    const Vec3 n = N.row(v);
    if (n.squaredNorm() == 0.0) continue;
    H(v) = moreton_sequin(rings, V, N, v, V.row(v), n, needs_spiral_samples(rings, v)).H;
  }
  return H;
}

}  // namespace geofair
