"""Intrinsic Delaunay triangulation by edge flips and its cotangent Laplacian (Bobenko &
Springborn 2007): non-negative weights, same surface, equal to the mesh's cotangent
Laplacian where the mesh is already Delaunay."""

import numpy as np
import pytest
from scipy.spatial import Delaunay

import geofair
from geofair_dev import scenes


def off_diagonal(L):
    L = L.tocoo()
    keep = L.row != L.col
    return L.data[keep]


def planar(points, faces):
    """Lift 2D points to z = 0 and orient the faces counter-clockwise."""
    p = np.column_stack([points, np.zeros(len(points))])
    f = np.asarray(faces, np.int64).copy()
    z = np.cross(p[f[:, 1]] - p[f[:, 0]], p[f[:, 2]] - p[f[:, 0]])[:, 2]
    f[z < 0] = f[z < 0][:, ::-1]
    return p, f


def squashed_disk(seed, squash=5.0, n=300):
    """Random points in the unit disk plus 40 on its circle, Delaunay-triangulated after
    stretching y by `squash`: in the plane, a mesh of needles and obtuse triangles."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    r, a = np.sqrt(rng.uniform(0, 0.8, n)), rng.uniform(0, 2 * np.pi, n)
    pts = np.concatenate([np.column_stack([r * np.cos(a), r * np.sin(a)]), np.column_stack([np.cos(t), np.sin(t)])])
    return pts, Delaunay(pts * [1.0, squash]).simplices


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_flat_mesh_gives_the_delaunay_triangulation_laplacian(seed):
    # On a flat mesh with a convex border the intrinsic Delaunay triangulation is the
    # Delaunay triangulation of the points; its cotangent Laplacian is unique even where
    # points are cocircular.
    pts, bad = squashed_disk(seed)
    v, f = planar(pts, bad)
    assert (off_diagonal(geofair.cotangent_laplacian(v, f)) < -0.1).sum() > 100  # many negative weights
    triangles, lengths, flips = geofair.intrinsic_delaunay(v, f)
    assert flips > 100 and triangles.shape == f.shape
    L = geofair.intrinsic_delaunay_laplacian(v, f)
    _, good = planar(pts, Delaunay(pts).simplices)
    reference = geofair.cotangent_laplacian(v, good)
    assert abs(L - reference).max() < 1e-9 * abs(reference).max()
    # The triangles are the Delaunay triangles, with their Euclidean edge lengths.
    same = {tuple(sorted(t)) for t in triangles} == {tuple(sorted(t)) for t in good}
    assert same
    i, j = triangles, np.roll(triangles, -1, axis=1)
    assert np.allclose(lengths, np.linalg.norm(v[j] - v[i], axis=2), rtol=1e-12)


def test_weights_non_negative_and_laplacian_properties_on_a_curved_obtuse_mesh():
    s = scenes.sphere_cap(n_free=600, irregular=True, seed=3)
    v = s.disturbed(seed=4, amplitude=0.1, noise=1.0)  # rough: many obtuse angles
    assert (off_diagonal(geofair.cotangent_laplacian(v, s.faces)) < 0).sum() > 50
    L = geofair.intrinsic_delaunay_laplacian(v, s.faces)
    scale = np.abs(off_diagonal(L)).max()
    assert off_diagonal(L).min() > -1e-12 * scale
    assert abs(L - L.T).max() < 1e-12 * scale
    assert np.abs(L @ np.ones(len(v))).max() < 1e-12 * scale
    # The metric is kept: the total area of the intrinsic triangles is the mesh's area.
    _, lengths, flips = geofair.intrinsic_delaunay(v, s.faces)
    a, b, c = lengths.T
    p = (a + b + c) / 2
    heron = np.sqrt(np.maximum(p * (p - a) * (p - b) * (p - c), 0)).sum()
    q = v[s.faces]
    area = 0.5 * np.linalg.norm(np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 0]), axis=1)
    assert flips > 0 and heron == pytest.approx(area.sum(), rel=1e-12)


@pytest.mark.parametrize("make", [scenes.sphere_cap, scenes.catenoid_patch])
def test_delaunay_mesh_is_unchanged(make):
    s = make(n_free=500, irregular=True, seed=5)  # the scenes' meshes are Delaunay
    triangles, _, flips = geofair.intrinsic_delaunay(s.vertices, s.faces)
    assert flips == 0 and np.array_equal(triangles, s.faces)
    L0 = geofair.cotangent_laplacian(s.vertices, s.faces)
    assert abs(geofair.intrinsic_delaunay_laplacian(s.vertices, s.faces) - L0).max() < 1e-12 * abs(L0).max()


def test_scale_invariant_weights():
    pts, f = squashed_disk(7)
    v, f = planar(pts, f)
    L1 = geofair.intrinsic_delaunay_laplacian(v, f)
    L2 = geofair.intrinsic_delaunay_laplacian(1e4 * v, f)
    assert abs(L1 - L2).max() < 1e-9 * abs(L1).max()


def test_bad_input():
    v = np.zeros((3, 3))
    with pytest.raises(ValueError, match="out of range"):
        geofair.intrinsic_delaunay_laplacian(v, np.array([[0, 1, 3]]))
    v[1, 0] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        geofair.intrinsic_delaunay(v, np.array([[0, 1, 2]]))
