// Discrete mean curvature by Moreton & Séquin with the spiral samples of section 6.2.
//
// Schneider & Kobbelt 2001, section 6: eqs. (8)-(11); singularity handling, section 6.2.
// Sign convention: H > 0 where the surface bends away from its normal, so H = 1/r on a
// sphere of radius r with outward normals, 1/(2r) on a cylinder, 0 on a plane and on
// minimal surfaces. Units: 1/length.
#pragma once

#include "region.h"
#include "geofair/types.h"

#include <Eigen/Core>

#include <cmath>

namespace geofair {

/// Exported by geofair/building_blocks.h, which documents it and gives the defaults.
Eigen::VectorXd mean_curvature(const Positions& V, const Triangles& F, const Positions* normals,
                               NormalWeighting weighting);

/// Unit normal of vertex i from the triangles of its one-ring, weighted as requested.
/// Returns the zero vector if the triangles are degenerate (no defined normal).
///
/// Quadric (beyond the paper): starting from Max's normal n0, the heights ⟨q_j − q_i, n0⟩
/// of the ring neighbours are fitted by a x + b y + (L x² + 2M xy + N y²)/2 in tangent
/// coordinates (each equation scaled by 2/|q_j − q_i|² like the rows of eqs. (8)–(10)), and
/// the normal is that of the fitted plane, (n0 − a b_x − b b_y)/|…|. Taylor's theorem makes
/// its error O(h²) on any smooth surface and ring shape, where weighted face normals are
/// O(h) off by irregular rings; κ of eq. (8) divides the normal's error by |q_j − q_i|, so
/// only an O(h²) normal gives a consistent H. Below valence 5 the vertices across the ring
/// edges join the samples (five unknowns); falls back to n0 where fewer than five samples
/// remain or the fitted plane tilts by 45° or more (a degenerate ring).
Vec3 vertex_normal(const OneRings& rings, const Positions& X, int i, NormalWeighting weighting);

/// The extra sample p_j between the ring neighbours a = q_j and b = q_{j+1} (section 6.2).
///
/// E is the plane through a and b that contains `plane_direction` (the sum of the unit
/// normals of the two triangles at edge ab). The tangents at a and b are E ∩ (tangent
/// plane), oriented towards b - a; each defines a circle in E through a and b, and p is the
/// midpoint of the two circles' intersections with the perpendicular bisector of ab that
/// lie closer to ab (approximating a spiral through a, b; Marciniak & Putz 1984).
/// Falls back to (a+b)/2 only where E is undefined (plane_direction parallel to b - a).
Vec3 spiral_sample(const Vec3& a, const Vec3& normal_a, const Vec3& b, const Vec3& normal_b,
                   const Vec3& plane_direction);

/// Result of the Moreton–Séquin estimate at one vertex.
struct CurvatureEstimate {
  double H = 0.0;      ///< mean curvature, eq. (10), 1/length
  double dH_dt = 0.0;  ///< derivative of H when the vertex moves by t along its normal,
                       ///< with |q_j - q_i| held fixed (section 7.2), 1/length²
};

/// Moreton–Séquin mean curvature of vertex i placed at `p` with unit normal `n`, from its
/// ring neighbours in `X` plus, if `spiral`, the section 6.2 samples between neighbours
/// that share a triangle (needs unit vertex normals `N` of the neighbours and, for the
/// second triangle at each ring edge, `across`).
///
/// Each sample q gives a row (t_x², t_x t_y, t_y²) and the normal curvature
/// κ = 2⟨p - q, n⟩ / |q - p|² (eq. (8), sign as above); the 3×3 normal equations (11) are
/// solved with a relative Tikhonov term of 1e-12·trace so that the rank-deficient case of
/// Lemma 1 stays continuous.
CurvatureEstimate moreton_sequin(const OneRings& rings, const Positions& X, const Positions& N,
                                 int i, const Vec3& p, const Vec3& n, bool spiral);

/// True where section 6.2 applies: valence 3 or 4, or a vertex on the mesh border (whose
/// one-sided neighbourhood alone does not determine the curvature tensor well).
inline bool needs_spiral_samples(const OneRings& rings, int i) {
  return rings.valence(i) <= 4 || !rings.closed(i);
}


}  // namespace geofair
