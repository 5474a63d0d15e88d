"""Tests of measures.py against known answers: point-triangle distances in every region
of a triangle, Hausdorff distances of shifted and rotated rectangles, symmetry errors."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial import cKDTree

from geofair_dev import scenes
from geofair_dev.measures import bounding_box_diagonal, hausdorff, point_mesh_distance, symmetry_error
from geofair_dev.paper_scenes import tetrahedral_group

TRIANGLE = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]])


@pytest.mark.parametrize(
    "point,expected",
    [
        ((0.5, 0.25, 0.3), 0.3),  # above the face
        ((0.5, 0.25, -0.7), 0.7),  # below the face
        ((-1.0, -1.0, 0.0), math.sqrt(2)),  # beyond corner 0
        ((3.0, -1.0, 1.0), math.sqrt(3)),  # beyond corner 1
        ((0.0, 2.0, 0.0), 1.0),  # beyond corner 2
        ((1.0, -0.5, 0.0), 0.5),  # beside edge 01
        ((-0.4, 0.5, 0.3), 0.5),  # beside edge 02
        ((2.0, 1.0, 0.0), 2 / math.sqrt(5)),  # beside the hypotenuse, in the plane: |x + 2y - 2| / sqrt(5)
        ((1.0, 0.5, 0.0), 0.0),  # on the hypotenuse
    ],
)
def test_point_triangle_distance_in_every_region(point, expected):
    d = point_mesh_distance(np.array([point]), TRIANGLE, np.array([[0, 1, 2]]))
    assert d[0] == pytest.approx(expected, abs=1e-15)


def test_point_mesh_distance_matches_brute_force():
    rng = np.random.default_rng(3)
    sc = scenes.sphere_cap(n_free=300, irregular=True)
    v, f = sc.vertices, sc.faces
    pts = rng.normal(size=(40, 3)) * 0.7 + [0, 0, 0.8]
    fast = point_mesh_distance(pts, v, f)
    # brute force: every triangle, closest point by a fine barycentric grid plus the edges
    k = 24
    a, b = np.meshgrid(np.linspace(0, 1, k + 1), np.linspace(0, 1, k + 1))
    keep = a + b <= 1
    w = np.column_stack([1 - a[keep] - b[keep], a[keep], b[keep]])
    samples = np.einsum("sk,tkd->tsd", w, v[f]).reshape(-1, 3)
    brute = cKDTree(samples).query(pts)[0]
    spacing = np.linalg.norm(v[f[:, 1]] - v[f[:, 0]], axis=1).max() / k
    assert (fast <= brute + 1e-12).all()  # exact: never above a sampled distance
    assert (brute - fast).max() < spacing  # and within the sampling resolution of it


def rectangle(a, b, n=8):
    """Grid mesh of [-a, a] x [-b, b] in the plane z = 0."""
    x, y = np.meshgrid(np.linspace(-a, a, n + 1), np.linspace(-b, b, n + 1), indexing="xy")
    v = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    return v, scenes._grid_faces(n, n)


def test_hausdorff_of_a_shifted_copy_is_the_shift():
    v, f = rectangle(1.0, 0.5)
    assert hausdorff(v, f, v + [0.0, 0.0, 0.3], f) == pytest.approx(0.3, abs=1e-15)
    assert hausdorff(v, f, v, f) == 0.0


def test_hausdorff_is_symmetric_and_takes_the_larger_side():
    big, fb = rectangle(1.0, 1.0)
    small, fs = rectangle(0.5, 0.5, n=4)
    # small lies inside big (distance 0 one way); big's corner is sqrt(0.5^2 + 0.5^2) from small
    assert hausdorff(big, fb, small, fs) == pytest.approx(math.sqrt(0.5), abs=1e-15)
    assert hausdorff(small, fs, big, fb) == pytest.approx(math.sqrt(0.5), abs=1e-15)
    assert point_mesh_distance(small, big, fb).max() == pytest.approx(0.0, abs=1e-15)


def test_dense_hausdorff_sees_the_surface_between_shared_vertices():
    # A non-planar quad split along either diagonal: the same four vertices, two surfaces.
    # The midpoint (1/2, 1/2, 0) of one diagonal is 1/(2√2) from both planes of the other
    # split (x + z = 1 and z = y), with its projections inside those triangles.
    v = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 1]])
    a, b = np.array([[0, 1, 2], [0, 2, 3]]), np.array([[0, 1, 3], [1, 2, 3]])
    assert hausdorff(v, a, v, b) == 0.0  # vertices only: blind to it
    assert hausdorff(v, a, v, b, dense=True) == pytest.approx(1 / (2 * math.sqrt(2)), abs=1e-15)


def test_symmetry_error_of_a_rectangle_under_a_quarter_turn():
    a, b = 1.0, 0.6
    v, f = rectangle(a, b)
    quarter = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    half = np.diag([-1.0, -1.0, 1.0])
    assert symmetry_error(v, f, [half]) == pytest.approx(0.0, abs=1e-15)
    assert symmetry_error(v, f, [half, quarter]) == pytest.approx(a - b, abs=1e-15)
    assert bounding_box_diagonal(v) == pytest.approx(2 * math.hypot(a, b))


def test_symmetry_error_of_an_icosphere_under_the_tetrahedral_group():
    """The geodesic icosphere has the pyritohedral symmetry, which contains T_d's rotations
    and the coordinate mirrors, but not the diagonal mirrors of T_d."""
    sc = scenes.sphere(n_vertices=642)
    group = tetrahedral_group()
    rotations = group[np.linalg.det(group) > 0]
    assert symmetry_error(sc.vertices, sc.faces, rotations) < 1e-14
    # a diagonal mirror (x <-> y) is no symmetry: vertices land between vertices
    assert symmetry_error(sc.vertices, sc.faces, group) > 1e-3
    # stretching along x breaks the rotations: (x, y, z) -> (y, z, x) moves the x-extreme
    stretched = sc.vertices * [1.1, 1.0, 1.0]
    assert symmetry_error(stretched, sc.faces, rotations) == pytest.approx(0.1, rel=0.1)


def test_point_mesh_distance_rejects_bad_input():
    with pytest.raises(ValueError):
        point_mesh_distance(np.zeros((1, 3)), TRIANGLE, np.zeros((0, 3), int))
    with pytest.raises(ValueError):
        point_mesh_distance(np.zeros((1, 3)), TRIANGLE[:, :2], np.array([[0, 1, 2]]))
