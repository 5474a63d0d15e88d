"""Tests of the paper's design scenes (paper_scenes.py): exact boundary circles and
normals, mesh validity, and the symmetry of the boundary data (numpy/scipy only)."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from geofair_dev import paper_scenes
from geofair_dev.scenes import border_mask, edges, face_normals, triangle_angles


@functools.cache
def scene(kind: str, size: str):
    if kind == "blend":
        return paper_scenes.cylinder_blend() if size == "fine" else paper_scenes.cylinder_blend(82, 12)
    return paper_scenes.tetrathing(13308 if size == "fine" else 500)


ALL = [("blend", "fine"), ("blend", "coarse"), ("tetrathing", "coarse"), ("tetrathing", "fine")]


@pytest.mark.parametrize("kind,size", ALL)
def test_circle_samples_lie_exactly_on_their_circles(kind, size):
    sc = scene(kind, size)
    boundary = np.unique(sc.faces[sc.free[sc.faces].any(axis=1)])
    boundary = boundary[~sc.free[boundary]]
    assert (sc.on_circle[boundary] >= 0).all()  # every G1 boundary vertex is a circle sample
    for k, c in enumerate(sc.circles):
        p = sc.vertices[sc.on_circle == k] - c.centre
        assert len(p) >= 8
        np.testing.assert_allclose(p @ c.axis, 0.0, atol=1e-14)  # in the circle's plane
        np.testing.assert_allclose(np.linalg.norm(p, axis=1), c.radius, rtol=1e-14)
        # equally spaced: every sample's nearest other sample is one chord away
        n = len(p)
        chord = 2 * c.radius * np.sin(np.pi / n)
        gaps = np.linalg.norm(p[:, None] - p[None], axis=2) + np.eye(n) * 1e9
        np.testing.assert_allclose(gaps.min(axis=1), chord, rtol=1e-12)


@pytest.mark.parametrize("kind,size", ALL)
def test_normals_are_exact(kind, size):
    sc = scene(kind, size)
    np.testing.assert_allclose(np.linalg.norm(sc.normals, axis=1), 1.0, rtol=1e-14)
    for k, c in enumerate(sc.circles):  # G1 data: radial from the cylinder axis
        rim = sc.on_circle == k
        radial = sc.vertices[rim] - c.centre
        np.testing.assert_allclose(sc.normals[rim], radial / c.radius, atol=1e-14)
    if kind == "blend":  # stubs: radial from their cylinder's axis, outward
        stub = ~sc.free & (sc.on_circle < 0)
        for c in sc.circles:
            p = sc.vertices[stub] - c.centre
            on_this = np.abs(np.linalg.norm(p - np.outer(p @ c.axis, c.axis), axis=1) - c.radius) < 1e-12
            on_this &= p @ c.axis > 0
            radial = p[on_this] - np.outer(p[on_this] @ c.axis, c.axis)
            np.testing.assert_allclose(sc.normals[stub][on_this], radial / c.radius, atol=1e-14)
        assert stub.sum() > 0
    # free vertices: radial from their junction's sphere centre, on that sphere
    centres = np.zeros((1, 3)) if kind == "blend" else paper_scenes.TETRAHEDRON
    c0 = sc.circles[0]
    R = np.hypot(np.linalg.norm(c0.centre - centres[0]), c0.radius)
    p = sc.vertices[sc.free]
    d = np.linalg.norm(p[:, None] - centres[None], axis=2)
    nearest = centres[d.argmin(axis=1)]
    np.testing.assert_allclose(d.min(axis=1), R, rtol=1e-13)
    np.testing.assert_allclose(sc.normals[sc.free], (p - nearest) / R, atol=1e-13)


@pytest.mark.parametrize("kind,size", ALL)
def test_mesh_is_valid(kind, size):
    sc = scene(kind, size)
    n = len(sc.vertices)
    # oriented along the normals (outward), no slivers, every vertex used
    agree = np.einsum("ij,ikj->ik", face_normals(sc.vertices, sc.faces), sc.normals[sc.faces])
    assert (agree > 0).all()
    assert triangle_angles(sc.vertices, sc.faces).min() >= paper_scenes.MIN_ANGLE_DEG
    assert np.bincount(sc.faces.ravel(), minlength=n).all()
    # manifold and consistently oriented: every directed edge once
    directed = np.concatenate([sc.faces[:, [0, 1]], sc.faces[:, [1, 2]], sc.faces[:, [2, 0]]])
    assert len(np.unique(directed, axis=0)) == len(directed)
    chi = n - len(edges(sc.faces)) + len(sc.faces)
    border = border_mask(sc.faces, n)
    assert not (border & sc.free).any()
    if kind == "blend":  # a pair of pants with stubs: three open ends
        assert chi == -1
        assert border.sum() == 3 * len(sc.vertices[sc.on_circle == 0])
    else:  # closed genus 3
        assert chi == -4 and not border.any()
        # four junctions of free vertices, each bounded by three circles
        e = edges(sc.faces)
        e = e[sc.free[e].all(axis=1)]
        g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
        count, label = connected_components(g, directed=False)
        assert len(np.unique(label[sc.free])) == 4
    assert (sc.free[sc.faces].any(axis=1) | (kind == "blend")).all()  # no face across a gap


@pytest.mark.parametrize(
    "kind,size,expected,tolerance",
    [("blend", "fine", 920, 15), ("blend", "coarse", 118, 4), ("tetrathing", "coarse", 500, 15),
     ("tetrathing", "fine", 13308, 60)],
)  # fmt: skip
def test_sizes_match_the_paper(kind, size, expected, tolerance):
    sc = scene(kind, size)
    assert abs(sc.region_vertices - expected) <= tolerance


@pytest.mark.parametrize("kind,size", ALL)
def test_symmetries_map_the_boundary_data_onto_themselves(kind, size):
    sc = scene(kind, size)
    rim = sc.on_circle >= 0
    p, q = sc.vertices[rim], sc.normals[rim]
    assert len(sc.symmetries) == (12 if kind == "blend" else 24)
    for g in sc.symmetries:
        np.testing.assert_allclose(g @ g.T, np.eye(3), atol=1e-15)
        gp, gq = p @ g.T, q @ g.T
        d = np.linalg.norm(gp[:, None] - p[None], axis=2)
        match = d.argmin(axis=1)
        np.testing.assert_allclose(d.min(axis=1), 0.0, atol=1e-13)  # samples onto samples
        np.testing.assert_allclose(gq, q[match], atol=1e-13)  # normals onto normals
        assert len(np.unique(match)) == len(p)


def test_the_start_meshes_are_not_symmetric():
    """The symmetry lives in the boundary data only; the irregular patch and the jittered
    lattice break it in the mesh (so a symmetric result is the solver's doing)."""
    sc = scene("blend", "fine")
    free = sc.vertices[sc.free]
    tree = cKDTree(free)
    worst = min(tree.query(free @ g.T)[0].max() for g in sc.symmetries[1:])
    assert worst > 0.05  # some vertex lands at least that far from every vertex, for every G


def test_tetrahedral_group():
    full, rotations = paper_scenes.tetrahedral_group(), paper_scenes.tetrahedral_group(reflections=False)
    assert full.shape == (24, 3, 3) and rotations.shape == (12, 3, 3)
    np.testing.assert_array_equal(full[0], np.eye(3))
    keys = {m.tobytes() for m in full}
    assert len(keys) == 24
    for a in full:  # a group: closed under products
        for b in full:
            assert (a @ b).tobytes() in keys
        # maps the tetrahedron onto itself
        image = paper_scenes.TETRAHEDRON @ a.T
        assert {tuple(x) for x in image} == {tuple(x) for x in paper_scenes.TETRAHEDRON}
    assert np.allclose(np.linalg.det(rotations), 1.0)


def test_bad_parameters_raise():
    with pytest.raises(ValueError, match="overlap"):
        paper_scenes.cylinder_blend(distance=0.5)
    with pytest.raises(ValueError, match="overlap"):
        paper_scenes.tetrathing(500, radius=0.9)
