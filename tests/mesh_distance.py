"""Distances between triangle meshes (numpy and scipy.spatial only), for comparing faired
results on different meshes of one region."""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

__all__ = ["point_to_mesh_distance", "hausdorff_distance"]


def _closest_on_segment(p, a, b):
    ab = b - a
    t = np.einsum("...i,...i->...", p - a, ab) / np.maximum(np.einsum("...i,...i->...", ab, ab), 1e-300)
    return a + np.clip(t, 0.0, 1.0)[..., None] * ab


def point_to_mesh_distance(points: np.ndarray, vertices: np.ndarray, faces: np.ndarray, candidates: int = 16):
    """Unsigned distance from each point to the triangle mesh (vertices, faces).

    points (k, 3), vertices (n, 3) float64, faces (m, 3) int. Exact over the `candidates`
    triangles whose centroids are nearest to each point, which is the exact distance when
    the nearest triangle is among them (true for points near a mesh of well-shaped
    triangles, as here). Returns (k,) float64.
    """
    points = np.asarray(points, float)
    tri = vertices[faces]  # (m, 3, 3)
    k = min(candidates, len(faces))
    _, idx = cKDTree(tri.mean(axis=1)).query(points, k=k)
    idx = idx.reshape(len(points), k)
    a, b, c = (tri[idx, j] for j in range(3))  # (k_pts, k, 3)
    p = points[:, None, :]
    n = np.cross(b - a, c - a)
    nn = np.einsum("...i,...i->...", n, n)
    # projection onto the plane, inside the triangle when all three edge tests agree
    proj = p - (np.einsum("...i,...i->...", p - a, n) / np.maximum(nn, 1e-300))[..., None] * n
    inside = np.ones(idx.shape, bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("...i,...i->...", np.cross(v - u, proj - u), n) >= 0
    best = np.where(inside, np.linalg.norm(p - proj, axis=-1), np.inf)
    for u, v in ((a, b), (b, c), (c, a)):
        best = np.minimum(best, np.linalg.norm(p - _closest_on_segment(p, u, v), axis=-1))
    return best.min(axis=1)


def hausdorff_distance(va, fa, vb, fb) -> float:
    """Symmetric Hausdorff distance between two triangle meshes, sampled at the vertices,
    edge midpoints and face centroids of each (to the exact nearest point of the other)."""

    def samples(v, f):
        e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
        return np.concatenate([v[np.unique(f)], v[e].mean(axis=1), v[f].mean(axis=1)])

    return max(
        point_to_mesh_distance(samples(va, fa), vb, fb).max(),
        point_to_mesh_distance(samples(vb, fb), va, fa).max(),
    )
