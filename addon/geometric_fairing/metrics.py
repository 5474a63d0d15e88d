"""Texture distortion of a UV map, without bpy (numpy only).

Inner fairness decides where the vertices sit on the faired surface; the
conformal (texture-preserving) choice keeps each triangle similar to its UV
image as far as it can. This module measures how far: the conformal distortion
σ1/σ2 of the linear map from each UV triangle to its 3D triangle.

Conventions: ``V  #V×3 float`` vertex positions (mesh units), ``T  #T×3 int``
triangles, ``UV  #T×3×2 float`` the UV coordinates of each triangle corner (UV
units; distortion is dimensionless, so neither unit matters).
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Distortion:
    """Summary of the conformal distortion over a set of triangles.

    Attributes:
        mean: mean of σ1/σ2 over the triangles (1 = conformal; ``inf`` if one
            triangle is degenerate in UV or in 3D).
        max: the largest σ1/σ2.
        triangles: number of triangles measured.
    """

    mean: float
    max: float
    triangles: int


def uv_conformal_distortion(vertices, triangles, corner_uvs):
    """Per-triangle conformal distortion σ1/σ2 of the map from the UV triangle to the 3D triangle.

    For a triangle with corners p0, p1, p2 (3D) and u0, u1, u2 (UV), the linear
    map is the ``3×2`` matrix J with ``J [u1 - u0, u2 - u0] = [p1 - p0, p2 - p0]``;
    σ1 ≥ σ2 are its singular values. σ1/σ2 = 1 exactly when the 3D triangle is
    similar to its UV image (a rotation, uniform scale or mirror: angles are
    kept); a stretch by k in one direction gives k. The inverse map, 3D to UV,
    has the same ratio. A triangle that is degenerate in UV or in 3D gives ``inf``.

    How: with ``U = [u1 - u0, u2 - u0]`` (2×2) and ``M = Eᵀ E`` the Gram matrix
    of the 3D edges ``E = [p1 - p0, p2 - p0]``, ``JᵀJ = U⁻ᵀ M U⁻¹``. The ratio
    does not change when J is scaled, so ``A = adj(U)ᵀ M adj(U)`` (= det(U)² JᵀJ)
    serves, with no division: σ1/σ2 = sqrt(λ1/λ2) = λ1 / sqrt(det A), λ1 the
    larger eigenvalue of A, from trace² - 4 det = (a00 - a11)² + 4 a01² so that
    near-conformal triangles lose no digits.

    Args:
        vertices: ``(n, 3)`` float positions.
        triangles: ``(T, 3)`` int triangles.
        corner_uvs: ``(T, 3, 2)`` float UV coordinates of each triangle corner.

    Returns:
        ``(T,)`` float64, each >= 1 (``inf`` for degenerate triangles).
    """
    p = np.asarray(vertices, dtype=np.float64)[np.asarray(triangles, dtype=np.int64).reshape(-1, 3)]
    uv = np.asarray(corner_uvs, dtype=np.float64).reshape(-1, 3, 2)
    if len(uv) != len(p):
        raise ValueError(f"uv_conformal_distortion: {len(p)} triangles but UVs for {len(uv)}")
    # Elementwise on (T,) arrays (a batched einsum over 2×2 matrices is several times slower).
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]  # E = [e1, e2]
    m00, m01, m11 = (e1 * e1).sum(axis=1), (e1 * e2).sum(axis=1), (e2 * e2).sum(axis=1)  # M = EᵀE
    # U = [[a, b], [c, d]] = [u1 - u0, u2 - u0]; adj(U) = [[d, -b], [-c, a]], columns x and y.
    x0, x1 = uv[:, 2, 1] - uv[:, 0, 1], uv[:, 0, 1] - uv[:, 1, 1]  # (d, -c)
    y0, y1 = uv[:, 0, 0] - uv[:, 2, 0], uv[:, 1, 0] - uv[:, 0, 0]  # (-b, a)
    mx0, mx1 = m00 * x0 + m01 * x1, m01 * x0 + m11 * x1  # M x
    a00 = x0 * mx0 + x1 * mx1  # A = adj(U)ᵀ M adj(U) = [[xᵀMx, xᵀMy], [yᵀMx, yᵀMy]]
    a01 = y0 * mx0 + y1 * mx1
    a11 = y0 * (m00 * y0 + m01 * y1) + y1 * (m01 * y0 + m11 * y1)
    trace = a00 + a11
    det = a00 * a11 - a01 * a01
    # trace² - 4 det of a symmetric 2×2 matrix, without the cancellation near conformal triangles.
    discriminant = (a00 - a11) ** 2 + 4.0 * a01 * a01
    largest = 0.5 * (trace + np.sqrt(np.maximum(discriminant, 0.0)))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = largest / np.sqrt(np.maximum(det, 0.0))
    # Rounding can put a conformal triangle a hair below 1; a degenerate one gives x/0 or 0/0.
    return np.where(det > 0.0, np.maximum(ratio, 1.0), np.inf)


def summarize(distortion):
    """Return the :class:`Distortion` (mean, max, count) of per-triangle values ``distortion``."""
    distortion = np.asarray(distortion, dtype=np.float64)
    if distortion.size == 0:
        return Distortion(mean=float("nan"), max=float("nan"), triangles=0)
    return Distortion(mean=float(distortion.mean()), max=float(distortion.max()), triangles=int(distortion.size))


def uv_distortion(vertices, triangles, corner_uvs):
    """Mean and maximum conformal distortion σ1/σ2 over ``triangles``: ``summarize(uv_conformal_distortion(...))``."""
    return summarize(uv_conformal_distortion(vertices, triangles, corner_uvs))
