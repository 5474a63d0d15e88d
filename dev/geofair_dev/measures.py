"""Distances between triangle meshes, for comparing faired shapes (numpy and scipy only).

- ``point_mesh_distance``: exact Euclidean distance from points to a triangle mesh
  (the closest point on any triangle: face, edge or corner).
- ``hausdorff``: the symmetric Hausdorff distance between two meshes, measured from the
  vertices (optionally also edge midpoints and face centroids) of each to the triangles
  of the other: max(max_a d(a, B), max_b d(b, A)).
  Vertex sampling makes it a lower bound of the surface-to-surface distance, exact when
  the farthest points are vertices (e.g. meshes that agree up to a rigid motion of
  corresponding vertices, and every example in the tests).
- ``symmetry_error``: how far a mesh is from being mapped onto itself by a set of
  orthogonal maps: max over the maps G of hausdorff(G(mesh), mesh).

All lengths are in mesh units; ``bounding_box_diagonal`` gives the usual normalization.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

__all__ = ["bounding_box_diagonal", "point_mesh_distance", "hausdorff", "symmetry_error"]


def bounding_box_diagonal(vertices: np.ndarray) -> float:
    """Length of the diagonal of the axis-aligned bounding box of (n, 3) `vertices`."""
    v = np.asarray(vertices, float)
    return float(np.linalg.norm(v.max(axis=0) - v.min(axis=0)))


def _closest_on_triangles(p, a, b, c):
    """Closest points to p on triangles (a, b, c), all (k, 3): Ericson, Real-Time
    Collision Detection, 5.1.5, vectorized over k pairs."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v_in, w_in = vb / denom, vc / denom
        out = a + v_in[:, None] * ab + w_in[:, None] * ac  # inside the face
        # edges: ab, ac, bc
        t_ab = d1 / (d1 - d3)
        t_ac = d2 / (d2 - d6)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
    edge_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
    edge_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
    edge_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
    out = np.where(edge_bc[:, None], b + t_bc[:, None] * (c - b), out)
    out = np.where(edge_ac[:, None], a + t_ac[:, None] * ac, out)
    out = np.where(edge_ab[:, None], a + t_ab[:, None] * ab, out)
    out = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, out)
    out = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, out)
    out = np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, out)
    return out


def point_mesh_distance(points: np.ndarray, vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Distance from each of `points` (k, 3) to the triangle mesh (`vertices` (n, 3),
    `faces` (m, 3) int), (k,) float64, exact up to rounding.

    How: the nearest point on the mesh lies no farther than the nearest triangle
    centroid, so only triangles whose centroid is within that distance plus the largest
    centroid-to-corner distance can hold it; those candidates are found with a k-d tree
    and measured exactly.  Raises ValueError for an empty mesh or bad shapes.
    """
    points = np.asarray(points, float).reshape(-1, 3)
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3 or len(f) == 0:
        raise ValueError("point_mesh_distance: need (n, 3) vertices and a non-empty (m, 3) faces array")
    tri = v[f]
    centroid = tri.mean(axis=1)
    reach = float(np.linalg.norm(tri - centroid[:, None], axis=2).max())
    tree = cKDTree(centroid)
    nearest, _ = tree.query(points)
    candidates = tree.query_ball_point(points, nearest + reach * (1 + 1e-12) + 1e-300)
    counts = np.fromiter((len(c) for c in candidates), np.int64, len(points))
    owner = np.repeat(np.arange(len(points)), counts)
    cand = np.fromiter((i for c in candidates for i in c), np.int64, int(counts.sum()))
    out = np.full(len(points), np.inf)
    for start in range(0, len(owner), 1 << 20):  # bounded memory
        o, t = owner[start : start + (1 << 20)], cand[start : start + (1 << 20)]
        p = points[o]
        q = _closest_on_triangles(p, tri[t, 0], tri[t, 1], tri[t, 2])
        np.minimum.at(out, o, np.linalg.norm(p - q, axis=1))
    return out


def _samples(v, f, dense):
    f = np.asarray(f)
    points = v[np.unique(f)]
    if not dense:
        return points
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    return np.concatenate([points, v[e].mean(axis=1), v[f].mean(axis=1)])


def hausdorff(vertices_a, faces_a, vertices_b, faces_b, dense: bool = False) -> float:
    """Symmetric Hausdorff distance between meshes A and B, sample points of each to the
    triangles of the other (mesh units).  Samples: the vertices used by a face; with
    ``dense`` also the edge midpoints and face centroids, which catches a surface that
    bulges between vertices lying on the other mesh."""
    va, vb = np.asarray(vertices_a, float), np.asarray(vertices_b, float)
    ab = point_mesh_distance(_samples(va, faces_a, dense), vb, faces_b).max()
    ba = point_mesh_distance(_samples(vb, faces_b, dense), va, faces_a).max()
    return float(max(ab, ba))


def symmetry_error(vertices, faces, maps) -> float:
    """max over the orthogonal 3x3 `maps` (g, 3, 3) of hausdorff(G(mesh), mesh), in mesh
    units: 0 for a mesh that every map sends onto itself (about the origin)."""
    v = np.asarray(vertices, float)
    return max(hausdorff(v @ np.asarray(g, float).T, faces, v, faces) for g in maps)
