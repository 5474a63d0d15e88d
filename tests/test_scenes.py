"""Tests of the analytic test scenes in scenes.py (numpy/scipy only, no geofair)."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from geofair_dev import scenes
from geofair_dev.scenes import border_mask, edges, face_normals, triangle_angles, valences

PATCHES = {
    "sphere_cap": scenes.sphere_cap,
    "cylinder_patch": scenes.cylinder_patch,
    "catenoid_patch": scenes.catenoid_patch,
    "plane_disk": scenes.plane_disk,
}
N_FREE = 1000


@functools.cache
def patch(kind: str, irregular: bool, rings: int = 1, seed: int = 0, n_free: int = N_FREE):
    return PATCHES[kind](n_free=n_free, irregular=irregular, seed=seed, boundary_rings=rings)


@functools.cache
def closed(kind: str, irregular: bool, seed: int = 0):
    make = {"sphere": scenes.sphere, "cylinder_tube": scenes.cylinder_tube}[kind]
    return make(n_vertices=1500, irregular=irregular, seed=seed)


ALL_PATCHES = [(k, irr, rings) for k in PATCHES for irr in (False, True) for rings in (1, 2)]
ALL_CLOSED = [(k, irr) for k in ("sphere", "cylinder_tube") for irr in (False, True)]


def all_scenes():
    return [patch(*p) for p in ALL_PATCHES] + [closed(*c) for c in ALL_CLOSED]


def gradient_normal(scene):
    """Unit gradient of the implicit function of each surface (outward), (n, 3)."""
    p = scene.vertices
    x, y, z = p.T
    if scene.name.startswith("sphere"):
        g = p.copy()
    elif scene.name.startswith("cylinder"):
        g = np.column_stack([x, y, 0 * z])
    elif scene.name.startswith("catenoid"):  # x^2 + y^2 - cosh(z)^2, a = 1
        g = np.column_stack([x, y, -np.cosh(z) * np.sinh(z)])
    else:
        g = np.tile([0.0, 0.0, 1.0], (len(p), 1))
    return g / np.linalg.norm(g, axis=1, keepdims=True)


def cotan_mean_curvature(v, f, n):
    """H_i = -<3/(4A) sum_j (cot a_j + cot b_j)(q_j - q_i), n_i>, eq. (5) projected (H = 1/r on
    a sphere with outward normals)."""
    lap, area = np.zeros_like(v), np.zeros(len(v))
    for k in range(3):
        i, j, o = f[:, k], f[:, (k + 1) % 3], f[:, (k + 2) % 3]
        a, b = v[i] - v[o], v[j] - v[o]
        cot = np.einsum("ij,ij->i", a, b) / np.linalg.norm(np.cross(a, b), axis=1)
        np.add.at(lap, i, cot[:, None] * (v[j] - v[i]))
        np.add.at(lap, j, cot[:, None] * (v[i] - v[j]))
    a = 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1)
    for k in range(3):
        np.add.at(area, f[:, k], a)
    return -3 / (4 * area) * np.einsum("ij,ij->i", lap, n)


# ------------------------------------------------------------------------------------
# Geometry


@pytest.mark.parametrize("scene", all_scenes(), ids=lambda s: s.name)
def test_vertices_on_surface_and_exact_normals(scene):
    v, n = scene.vertices, scene.normals
    assert v.dtype == n.dtype == np.float64 and v.shape == n.shape == (len(v), 3)
    assert np.abs(scene.distance(v)).max() < 1e-12
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, rtol=0, atol=1e-14)
    assert np.allclose(n, gradient_normal(scene), rtol=0, atol=1e-12)


@pytest.mark.parametrize("scene", all_scenes(), ids=lambda s: s.name)
def test_distance_is_signed_outward(scene):
    eps = 1e-3
    d = scene.distance(scene.vertices + eps * scene.normals)
    assert np.allclose(d, eps, rtol=0.01, atol=0)
    assert np.allclose(scene.distance(scene.vertices - eps * scene.normals), -eps, rtol=0.01)


@pytest.mark.parametrize("scene", all_scenes(), ids=lambda s: s.name)
def test_faces_oriented_along_normals(scene):
    fn = face_normals(scene.vertices, scene.faces)
    dots = np.einsum("ij,ikj->ik", fn, scene.normals[scene.faces])
    assert dots.min() > 0.5


@pytest.mark.parametrize(
    "scene", [patch("sphere_cap", False), closed("sphere", False), closed("sphere", True),
              closed("cylinder_tube", False), patch("catenoid_patch", False),
              patch("plane_disk", True)], ids=lambda s: s.name)  # fmt: skip
def test_mean_curvature_matches_cotan_estimate(scene):
    """Also fixes the sign convention: H = -1/r on a sphere with outward normals."""
    interior = scene.free & ~border_mask(scene.faces, len(scene.vertices))
    h = cotan_mean_curvature(scene.vertices, scene.faces, scene.normals)[interior]
    assert abs(np.median(h) - scene.mean_curvature) < 0.03 * max(1.0, abs(scene.mean_curvature))


# ------------------------------------------------------------------------------------
# Topology and the free region


def check_mesh(scene, euler):
    """Valid, manifold, consistently oriented, connected, Euler characteristic `euler`;
    returns the border edges (b, 2)."""
    n, f = len(scene.vertices), scene.faces
    assert f.dtype == np.int64 and f.ndim == 2 and f.shape[1] == 3
    assert f.min() >= 0 and f.max() < n
    assert (np.bincount(f.ravel(), minlength=n) > 0).all(), "unreferenced vertex"
    assert len(np.unique(np.sort(f, axis=1), axis=0)) == len(f), "duplicate face"
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    ed, per_edge = np.unique(e, axis=0, return_counts=True)
    assert per_edge.max() <= 2, "non-manifold edge"
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    assert len(np.unique(directed, axis=0)) == len(directed), "inconsistent orientation"
    assert n - len(ed) + len(f) == euler
    adj = coo_matrix((np.ones(len(ed)), (ed[:, 0], ed[:, 1])), shape=(n, n))
    assert connected_components(adj, directed=False)[0] == 1
    border = ed[per_edge == 1]
    # Each border vertex has exactly two border edges: the border is a union of loops.
    assert (np.bincount(border.ravel(), minlength=n)[np.unique(border)] == 2).all()
    return border


@pytest.mark.parametrize("p", ALL_PATCHES, ids=str)
def test_patch_is_a_disk_with_interior_free_vertices(p):
    s = patch(*p)
    n = len(s.vertices)
    check_mesh(s, euler=1)  # connected, chi = 1, manifold: a disk
    assert s.free.dtype == bool and s.free.shape == (n,)
    on_border = border_mask(s.faces, n)
    assert not (on_border & s.free).any(), "a free vertex lies on the mesh border"
    bd = s.boundary_distance(s.vertices)
    assert (bd[s.free] < -1e-9).all()
    assert (bd[~s.free] > -1e-12).all()
    ed = edges(s.faces)
    touching = ed[s.free[ed[:, 0]] != s.free[ed[:, 1]]]
    fixed_next_to_free = np.unique(touching[~s.free[touching]])
    assert np.abs(bd[fixed_next_to_free]).max() < 1e-12
    rings = p[2]
    if rings == 1:
        assert np.array_equal(on_border, ~s.free)
    else:
        assert (bd[on_border] > 1e-3).all(), "outer ring lies outside the boundary curve"


@pytest.mark.parametrize("irregular", [False, True])
@pytest.mark.parametrize("rings", [1, 2])
def test_cap_boundary_is_on_the_circle(irregular, rings):
    s = scenes.sphere_cap(opening_angle=60, n_free=500, irregular=irregular, boundary_rings=rings)
    ed = edges(s.faces)
    touching = np.unique(ed[s.free[ed[:, 0]] != s.free[ed[:, 1]]])
    g1 = touching[~s.free[touching]]
    assert np.abs(s.vertices[g1, 2] - 0.5).max() < 1e-12  # cos 60 deg
    assert s.vertices[s.free, 2].min() > 0.5
    if rings == 1:
        assert np.array_equal(np.sort(g1), np.nonzero(~s.free)[0])
    else:  # the fixed vertices not adjacent to free ones are strictly outside the circle
        others = np.setdiff1d(np.nonzero(~s.free)[0], g1)
        assert len(others) > 0 and s.vertices[others, 2].max() < 0.5 - 1e-3


@pytest.mark.parametrize("irregular", [False, True])
def test_tube_is_an_annulus_with_exact_end_circles(irregular):
    s = closed("cylinder_tube", irregular)
    border = check_mesh(s, euler=0)
    z = s.vertices[:, 2]
    on_border = border_mask(s.faces, len(z))
    assert np.array_equal(on_border, ~s.free)
    assert np.array_equal(np.abs(z[on_border]), np.ones(on_border.sum()))  # height 2
    assert (np.abs(z[s.free]) < 1).all()
    # two loops: no border edge joins the two end circles
    assert (z[border[:, 0]] == z[border[:, 1]]).all()


@pytest.mark.parametrize("irregular", [False, True])
def test_sphere_is_closed(irregular):
    s = closed("sphere", irregular)
    check_mesh(s, euler=2)
    assert not border_mask(s.faces, len(s.vertices)).any()
    assert s.free.all()


def test_sphere_vertex_counts():
    assert len(scenes.sphere(n_vertices=642).vertices) == 642  # frequency 8
    assert len(scenes.sphere(n_vertices=1000).vertices) == 10 * 10**2 + 2
    assert len(scenes.sphere(n_vertices=1000, irregular=True).vertices) == 1000


@pytest.mark.parametrize("kind", PATCHES)
@pytest.mark.parametrize("irregular", [False, True])
@pytest.mark.parametrize("n_free", [150, 2500])
def test_n_free_is_honoured(kind, irregular, n_free):
    s = PATCHES[kind](n_free=n_free, irregular=irregular, seed=1)
    assert abs(s.n_free - n_free) <= 0.15 * n_free


# ------------------------------------------------------------------------------------
# Mesh quality


@pytest.mark.parametrize("scene", all_scenes(), ids=lambda s: s.name)
def test_triangle_quality_and_valences(scene):
    angles = triangle_angles(scene.vertices, scene.faces)
    interior = scene.free & ~border_mask(scene.faces, len(scene.vertices))
    val = valences(scene.faces, len(scene.vertices))[interior]
    if "irregular" in scene.name:
        assert angles.min() > 15.0
        assert val.min() <= 5 and val.max() >= 7
        assert 0.2 < np.mean(val != 6) < 0.8
    else:
        assert angles.min() > 30.0
        if scene.name.startswith("sphere("):  # the 12 icosahedron corners have valence 5
            assert np.count_nonzero(val == 5) == 12 and np.count_nonzero(val != 6) == 12
        else:
            assert (val == 6).all()


@pytest.mark.parametrize("kind", PATCHES)
def test_regular_and_irregular_differ(kind):
    a, b = patch(kind, False), patch(kind, True)
    assert a.vertices.shape != b.vertices.shape or not np.array_equal(a.vertices, b.vertices)
    max_a = valences(a.faces, len(a.vertices))[a.free].max()
    max_b = valences(b.faces, len(b.vertices))[b.free].max()
    assert max_a == 6 < max_b


# ------------------------------------------------------------------------------------
# Reproducibility and disturbed()


@pytest.mark.parametrize("make", [*PATCHES.values(), scenes.sphere, scenes.cylinder_tube])
def test_seeds_are_reproducible(make):
    n = {"n_free": 300} if make in PATCHES.values() else {"n_vertices": 300}
    a, b, c = (make(irregular=True, seed=s, **n) for s in (5, 5, 6))
    for field in ("vertices", "faces", "free", "normals"):
        assert np.array_equal(getattr(a, field), getattr(b, field))
    assert a.vertices.shape != c.vertices.shape or not np.array_equal(a.vertices, c.vertices)


@pytest.mark.parametrize("scene", all_scenes(), ids=lambda s: s.name)
def test_disturbed_moves_only_free_vertices(scene):
    before = scene.vertices.copy()
    d = scene.disturbed(seed=3, amplitude=0.1)
    assert d.shape == before.shape and d.dtype == np.float64
    assert np.array_equal(scene.vertices, before), "disturbed() modified the scene"
    assert d[~scene.free].tobytes() == before[~scene.free].tobytes()
    moved = np.linalg.norm(d - before, axis=1)[scene.free]
    assert moved.min() > 0 and moved.max() <= 0.1 * 1.3 * scene.size + 1e-12
    # moved along the normals only
    cross = np.cross(d - before, scene.normals)[scene.free]
    assert np.abs(cross).max() < 1e-12
    assert np.array_equal(d, scene.disturbed(seed=3, amplitude=0.1))
    assert not np.array_equal(d, scene.disturbed(seed=4, amplitude=0.1))
    assert np.array_equal(scene.disturbed(amplitude=0.0), before)


def test_disturbed_bulges_outward_for_positive_amplitude():
    s = patch("sphere_cap", False)
    d = s.disturbed(seed=0, amplitude=0.1, noise=0.0)
    assert (s.distance(d)[s.free] > 0).all()
    flat = s.disturbed(seed=0, amplitude=-0.1, noise=0.0)
    assert (s.distance(flat)[s.free] < 0).all()


def test_invalid_rings():
    with pytest.raises(ValueError):
        scenes.plane_disk(boundary_rings=0)


def test_catenoid_is_parametrized_as_documented():
    s = patch("catenoid_patch", False)
    phi = np.degrees(np.arctan2(s.vertices[:, 1], s.vertices[:, 0]))
    assert math.isclose(phi.max(), 60.0) and math.isclose(phi.min(), -60.0)
    assert s.vertices[:, 2].max() == 1.0 and s.vertices[:, 2].min() == -1.0
    assert s.mean_curvature == 0.0


# ------------------------------------------------------------------------------------
# Torus patch


@functools.cache
def torus(irregular: bool):
    return scenes.torus_patch(n_free=1000, irregular=irregular, seed=3)


@pytest.mark.parametrize("irregular", [False, True])
def test_torus_patch_is_on_the_torus_with_exact_normals(irregular):
    s = torus(irregular)
    p = s.vertices
    rho = np.hypot(p[:, 0], p[:, 1])
    assert np.abs(np.hypot(rho - 2.0, p[:, 2]) - 1.0).max() < 1e-14  # R = 2, r = 1
    assert np.abs(s.distance(p)).max() < 1e-14
    core = np.column_stack([2.0 * p[:, 0] / rho, 2.0 * p[:, 1] / rho, np.zeros(len(p))])
    assert np.abs((p - core) - s.normals).max() < 1e-14  # r = 1: the normal is p - core
    assert (np.einsum("ij,ikj->ik", face_normals(p, s.faces), s.normals[s.faces]) > 0).all()
    # a point pushed along the normal by d has signed distance d
    assert np.allclose(s.distance(p + 0.1 * s.normals), 0.1)
    assert math.isnan(s.mean_curvature)


@pytest.mark.parametrize("irregular", [False, True])
def test_torus_patch_region_is_as_documented(irregular):
    s = torus(irregular)
    p = s.vertices
    phi = np.degrees(np.arctan2(p[:, 1], p[:, 0]))
    theta = np.degrees(np.arctan2(p[:, 2], np.hypot(p[:, 0], p[:, 1]) - 2.0))
    fixed = ~s.free
    assert math.isclose(phi.max(), 45.0) and math.isclose(phi.min(), -45.0)
    assert math.isclose(theta.max(), 135.0) and math.isclose(theta.min(), 45.0)
    assert (np.abs(phi[s.free]) < 45.0).all() and ((theta[s.free] > 45.0) & (theta[s.free] < 135.0)).all()
    assert np.abs(s.boundary_distance(p[fixed])).max() < 1e-12
    assert (s.boundary_distance(p[s.free]) < 0).all()
    assert abs(s.n_free - 1000) < 100
    assert not (border_mask(s.faces, len(p)) & s.free).any()
    if irregular:
        assert triangle_angles(p, s.faces).min() >= scenes.MIN_ANGLE_DEG
        assert len(np.unique(valences(s.faces, len(p))[s.free])) >= 4


def test_torus_patch_conformal_coordinates():
    # uv are conformal: the triangles' angles on the surface are those in the (u, v) plane
    s = torus(True)
    flat = np.column_stack([s.uv, np.zeros(len(s.uv))])
    assert np.abs(triangle_angles(s.vertices, s.faces) - triangle_angles(flat, s.faces)).max() < 3.0


def test_torus_patch_invalid():
    with pytest.raises(ValueError):
        scenes.torus_patch(major_radius=1.0, minor_radius=1.0)
    with pytest.raises(ValueError):
        scenes.torus_patch(theta_range=(0.0, 200.0))
