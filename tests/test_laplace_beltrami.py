"""Cotangent Laplace–Beltrami operator and the Dirichlet matrix S (Schneider & Kobbelt 2001,
section 5, eqs. (5)-(7))."""

import numpy as np
import pytest
import scipy.sparse.linalg

import geofair
from geofair_dev import scenes

MESHES = [
    ("sphere", lambda irr: scenes.sphere(radius=1.5, n_vertices=400, irregular=irr, seed=1)),
    ("cap", lambda irr: scenes.sphere_cap(n_free=300, irregular=irr, seed=2)),
    ("catenoid", lambda irr: scenes.catenoid_patch(n_free=300, irregular=irr, seed=3)),
]


@pytest.fixture(
    params=[(name, irr) for name, _ in MESHES for irr in (False, True)],
    ids=lambda p: f"{p[0]}-{'irregular' if p[1] else 'regular'}",
)
def scene(request):
    name, irr = request.param
    return dict(MESHES)[name](irr)


def test_symmetric_with_constants_in_null_space(scene):
    L = geofair.cotangent_laplacian(scene.vertices, scene.faces)
    assert L.shape == (len(scene.vertices),) * 2
    assert abs(L - L.T).max() < 1e-12 * abs(L).max()
    assert np.abs(L @ np.ones(L.shape[0])).max() < 1e-12 * abs(L).max()
    # The weights are the cotangents of the opposite angles: on these meshes (no angle
    # above 90°) no edge weight is negative.
    off = L - scipy.sparse.diags(L.diagonal())
    assert off.data.min() > -1e-12 * abs(L).max()


@pytest.mark.parametrize("make", [scenes.sphere_cap, scenes.cylinder_patch, scenes.catenoid_patch])
@pytest.mark.parametrize("irregular", [False, True])
def test_dirichlet_matrix_positive_definite(make, irregular):
    scene = make(n_free=300, irregular=irregular, seed=5)
    L = geofair.cotangent_laplacian(scene.vertices, scene.faces)
    free = np.flatnonzero(scene.free)
    S = -L[free][:, free]
    smallest = scipy.sparse.linalg.eigsh(S.tocsc(), k=1, sigma=0, which="LM")[0][0]
    assert smallest > 0


def test_mean_curvature_normal_on_sphere():
    # eq. (5): H n = 3/(4A) Σ (cot α + cot β)(q_j - q_i), i.e. L @ X = -(4A/3) H n. With A the
    # plain 1-disk area (not a Voronoi area) this is consistent where the ring is regular;
    # the icosphere's twelve valence-5 vertices are off by several percent, as expected.
    s = scenes.sphere(radius=2.0, n_vertices=2500, irregular=False)
    L = geofair.cotangent_laplacian(s.vertices, s.faces)
    f = s.faces
    area = 0.5 * np.linalg.norm(
        np.cross(s.vertices[f[:, 1]] - s.vertices[f[:, 0]], s.vertices[f[:, 2]] - s.vertices[f[:, 0]]), axis=1
    )
    disk = np.zeros(len(s.vertices))
    for k in range(3):
        np.add.at(disk, f[:, k], area)
    Hn = -(3.0 / (4.0 * disk))[:, None] * (L @ s.vertices)
    H = np.einsum("ij,ij->i", Hn, s.normals)
    regular = scenes.valences(s.faces, len(s.vertices)) == 6
    assert regular.sum() == len(s.vertices) - 12
    assert np.abs(H[regular] - 0.5).max() < 2e-3


def test_scale_invariant_weights():
    s = scenes.sphere_cap(n_free=200, irregular=True, seed=4)
    L1 = geofair.cotangent_laplacian(s.vertices, s.faces)
    L2 = geofair.cotangent_laplacian(1e3 * s.vertices, s.faces)
    assert abs(L1 - L2).max() < 1e-9 * abs(L1).max()
