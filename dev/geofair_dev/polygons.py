"""Blender's UV sphere (geofair_dev.scenes.uv_sphere) with its quads split into triangles in
different ways, and its cap above z = 0.25 flattened and faired (tests/test_polygons.py,
bench/quad_splits.py)."""

import numpy as np

import geofair
from geofair_dev.scenes import uv_sphere

SEGMENTS, RINGS = 64, 32


def tessellated_uv_sphere(split):
    """The UV sphere with each quad (a, b, c, d) split along a–c where split[k] is True, else
    along b–d; (vertices, faces, polygon_ids) with one id per pole triangle and per quad."""
    vertices, faces = uv_sphere(SEGMENTS, RINGS)
    quads = faces[SEGMENTS:-SEGMENTS].reshape(-1, 2, 3)  # uv_sphere splits along a–c
    a, b, c, d = quads[:, 0, 0], quads[:, 0, 1], quads[:, 0, 2], quads[:, 1, 2]
    split = np.asarray(split, bool)[:, None]
    first = np.where(split, np.stack([a, b, c], 1), np.stack([a, b, d], 1))
    second = np.where(split, np.stack([a, c, d], 1), np.stack([b, c, d], 1))
    tris = np.stack([first, second], 1).reshape(-1, 3)
    faces = np.vstack([faces[:SEGMENTS], tris, faces[-SEGMENTS:]])
    n_quads = len(quads)
    polygon_ids = np.concatenate(
        [np.arange(SEGMENTS), np.repeat(SEGMENTS + np.arange(n_quads), 2), SEGMENTS + n_quads + np.arange(SEGMENTS)]
    )
    return vertices, faces, polygon_ids


def splits():
    n = SEGMENTS * (RINGS - 2)
    k = np.arange(n)
    return {
        "a-c": np.ones(n, bool),
        "b-d": np.zeros(n, bool),
        "checkerboard": (k + k // SEGMENTS) % 2 == 0,
        "random": np.random.default_rng(0).random(n) < 0.5,
    }


def fair_flattened_cap(split, polygons, inner_fairness="uniform"):
    """fair()'s result, with or without the polygon ids, and the free mask."""
    vertices, faces, polygon_ids = tessellated_uv_sphere(split)
    free = vertices[:, 2] > 0.25
    flat = vertices.copy()
    flat[free, 2] = 0.25
    polygon_ids = polygon_ids if polygons else None
    r = geofair.fair(flat, faces, free, inner_fairness=inner_fairness, polygon_ids=polygon_ids)
    return r, free
