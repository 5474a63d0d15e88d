"""Accuracy targets of geofair.fair with its defaults (quadric-fit normals, multigrid) on
irregular meshes of the analytic scenes, and mesh independence on a torus patch whose
faired shape is not known in closed form. The figures for every scene and setting are
printed by bench/accuracy.py (README, "Accuracy")."""

import numpy as np
import pytest

import geofair
from geofair_dev import measures, scenes


def fair(scene, **kw):
    # Accuracy, not speed: no wall-clock limit (the default one depends on the machine's load).
    v = scene.disturbed(seed=5, amplitude=0.1)
    kw.setdefault("time_limit", float("inf"))
    return geofair.fair(v, scene.faces, scene.free, boundary_normals=scene.normals, **kw)


def radial_error(scene, result):
    return np.abs(scene.distance(result.vertices[scene.free])).max()  # mesh units


def test_irregular_sphere_cap_within_1e4_and_far_better_than_the_paper_normals():
    s = scenes.sphere_cap(n_free=2000, irregular=True, seed=21)  # unit sphere, 60° cap
    r = fair(s)
    assert r.converged
    assert radial_error(s, r) <= 1e-4
    # The paper's area-weighted normals are inconsistent on this mesh (README: ~1e-3).
    paper = fair(s, normal_weighting="area")
    assert paper.converged and radial_error(s, paper) > 10 * radial_error(s, r)


@pytest.mark.parametrize("make", [scenes.cylinder_patch, scenes.catenoid_patch], ids=["cylinder", "catenoid"])
def test_irregular_cylinder_and_catenoid_patches_within_3e4(make):
    s = make(n_free=5000, irregular=True, seed=22)  # radius / waist 1
    r = fair(s)
    assert r.converged
    assert radial_error(s, r) <= 3e-4


def test_torus_patch_is_the_same_on_a_regular_and_an_irregular_mesh():
    # Δ_B H = 0 is intrinsic: the faired shape must not depend on the mesh. Hausdorff
    # distance of the two results relative to the bounding-box diagonal.
    meshes = [scenes.torus_patch(n_free=10000, irregular=irr, seed=23) for irr in (False, True)]
    results = [fair(s) for s in meshes]
    assert all(r.converged for r in results)
    v = meshes[0].vertices
    diag = np.linalg.norm(v.max(axis=0) - v.min(axis=0))
    d = measures.hausdorff(results[0].vertices, meshes[0].faces, results[1].vertices, meshes[1].faces, dense=True)
    assert d <= 5e-4 * diag
    # ... while the disturbance was far larger (the comparison can fail)
    start = measures.point_mesh_distance(meshes[1].disturbed(seed=5, amplitude=0.1), v, meshes[0].faces)
    assert start.max() > 50 * d
