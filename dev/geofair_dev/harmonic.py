"""Discrete harmonic maps with a fixed boundary, solved with scipy: the reference for
where conformal inner fairness (Schneider & Kobbelt 2001, section 7.3) must put the
vertices once the surface is known.

A Laplacian ``L`` is an (n, n) scipy sparse matrix with the conventions of
``geofair.cotangent_laplacian``: L[i, j] >= 0 the weight of edge (i, j) (for the mesh's own
cotangent weights possibly negative), L[i, i] = -sum_j L[i, j]. The map sends free vertex i
to the weighted mean of its neighbours, sum_j L[i, j] (p_j - p_i) = 0, with the other
vertices fixed.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["region_faces", "clamped", "planar_harmonic_map", "cylinder_harmonic_map"]


def region_faces(faces: np.ndarray, free: np.ndarray) -> np.ndarray:
    """The triangles with at least one free vertex: the fairing region with its G1
    boundary ring, (m, 3) int64."""
    return faces[np.asarray(free)[faces].any(axis=1)]


def clamped(L) -> sp.csr_matrix:
    """L with negative off-diagonal weights set to 0 and the diagonal made -(row sum)
    again: the weights geofair used before the intrinsic Delaunay triangulation."""
    L = sp.coo_matrix(L)
    off = L.row != L.col
    W = sp.csr_matrix((np.maximum(L.data[off], 0.0), (L.row[off], L.col[off])), shape=L.shape)
    return (W - sp.diags(np.asarray(W.sum(axis=1)).ravel())).tocsr()


def planar_harmonic_map(L, positions: np.ndarray, free: np.ndarray) -> np.ndarray:
    """Solves L[F, F] p_F = -L[F, B] p_B for the free rows F of `positions` (n, d), all
    other rows B fixed (rows of vertices outside the region have no weights and drop
    out). Returns the (n, d) positions: the harmonic map onto the plane of the fixed
    vertices when they lie in a plane."""
    L = sp.csr_matrix(L)
    F, B = np.flatnonzero(free), np.flatnonzero(~np.asarray(free))
    p = np.array(positions, float)
    p[F] = spla.spsolve(L[F][:, F].tocsc(), -(L[F][:, B] @ p[B])).reshape(len(F), -1)
    return p


def cylinder_harmonic_map(L, angle: np.ndarray, height: np.ndarray, free: np.ndarray):
    """Harmonic map onto the unit cylinder x = cos u, y = sin u: the tangential part of
    sum_j L[i, j] (q_j - q_i) vanishes at every free vertex i, i.e.
    sum_j L[i, j] sin(u_j - u_i) = 0 (the direction of growing u) and
    sum_j L[i, j] (z_j - z_i) = 0 (along the axis). The second is linear; the first is
    solved by Newton's method from the linear map of the angles. Returns (u, z), (n,)."""
    L = sp.csr_matrix(L)
    free = np.asarray(free)
    z = planar_harmonic_map(L, np.asarray(height, float)[:, None], free)[:, 0]
    u = planar_harmonic_map(L, np.asarray(angle, float)[:, None], free)[:, 0]
    F = np.flatnonzero(free)
    W = sp.coo_matrix(L)
    keep = W.row != W.col
    rows, cols, w = W.row[keep], W.col[keep], W.data[keep]
    for _ in range(50):
        d = u[cols] - u[rows]
        g = np.bincount(rows, w * np.sin(d), minlength=len(u))
        C = sp.csr_matrix((w * np.cos(d), (rows, cols)), shape=L.shape)
        J = C - sp.diags(np.asarray(C.sum(axis=1)).ravel())
        step = spla.spsolve(J[F][:, F].tocsc(), -g[F])
        u[F] += step
        if np.abs(step).max() < 1e-14:
            break
    return u, z
