"""Inner fairness by global tangential solves (geofair.relax_inner_fairness).

The solve that fair()'s Newton iteration repeats at every level and at convergence: on an
exact sphere cap and cylinder patch whose free vertices were slid along the surface, each
solve is followed by an exact lift back onto the surface, so the iteration below isolates
the linearization of the tangential condition. With turning tangent planes (Newton's
linearization) it converges quadratically; with fixed planes linearly, by a constant
factor per solve; both reach the same vertices.
"""

import numpy as np
import pytest

import geofair
from geofair_dev import scenes


def _surface(name):
    """(scene, onto, normals): exact projection onto the surface and its unit normals."""
    if name == "sphere":
        s = scenes.sphere_cap(n_free=1500, irregular=True, seed=3, opening_angle=60)

        def onto(X):
            return X / np.linalg.norm(X, axis=1)[:, None]

        return s, onto, onto
    s = scenes.cylinder_patch(n_free=1500, irregular=True, seed=3)

    def onto(X):
        Y = X.copy()
        Y[:, :2] /= np.hypot(X[:, 0], X[:, 1])[:, None]
        return Y

    def normals(X):
        N = onto(X)
        N[:, 2] = 0.0
        return N

    return s, onto, normals


def _slid(s, onto, normals):
    """The free vertices slid along the surface by a smooth field vanishing at the boundary."""
    X = s.vertices.copy()
    size = np.ptp(X, axis=0).max()
    fade = np.clip(-s.boundary_distance(X) / (0.3 * size), 0.0, 1.0)
    N = normals(X)
    c = np.array([0.3, 1.0, 0.6])
    t = c - (N @ c)[:, None] * N
    X[s.free] = onto(X + 0.1 * size * fade[:, None] * t)[s.free]
    return X


def _solves(s, onto, normals, X, planes, count):
    """`count` solves from X, each lifted onto the surface: the largest move of each, and X."""
    moves = []
    for _ in range(count):
        Y, scale = geofair.relax_inner_fairness(X, s.faces, s.free, normals(X), tangent_planes=planes)
        assert 0.0 < scale <= 1.0
        Y[s.free] = onto(Y)[s.free]
        moves.append(np.abs(Y - X).max())
        X = Y
    return np.array(moves), X


def _edge_length(s):
    e = np.vstack([s.faces[:, [0, 1]], s.faces[:, [1, 2]], s.faces[:, [2, 0]]])
    return np.linalg.norm(s.vertices[e[:, 0]] - s.vertices[e[:, 1]], axis=1).mean()


@pytest.mark.parametrize("name", ["sphere", "cylinder"])
def test_turning_tangent_planes_converge_quadratically_to_the_fixed_planes_vertices(name):
    s, onto, normals = _surface(name)
    X = _slid(s, onto, normals)
    h = _edge_length(s)
    turning, X_turning = _solves(s, onto, normals, X, "turning", 8)
    fixed, X_fixed = _solves(s, onto, normals, X, "fixed", 40)
    # The first solves are cut by the stretch limit; once a move is below 1e-2 edge lengths
    # the next is below its square (in edge lengths) with turning planes ...
    start = int(np.argmax(turning < 1e-2 * h))
    assert turning[start] < 1e-2 * h, turning / h
    assert turning[start + 1] / h <= (turning[start] / h) ** 2, turning / h
    assert turning[-1] < 1e-12 * h, turning / h
    # ... and only a constant factor smaller with fixed ones, ...
    ratios = fixed[1:] / fixed[:-1]
    linear = ratios[(fixed[:-1] < 0.05 * h) & (fixed[1:] > 1e-10 * h)]
    assert len(linear) >= 3 and np.all(linear > 0.05), ratios
    # ... to the same vertices.
    assert np.abs(X_turning - X_fixed).max() < 1e-9 * h
    # The fixed point is inner fairness: the uniform Laplacian of a free vertex is normal.
    n = normals(X_turning)
    for i in np.nonzero(s.free)[0][:200]:
        ring = np.unique(s.faces[np.any(s.faces == i, axis=1)])
        ring = ring[ring != i]
        L = X_turning[ring].mean(axis=0) - X_turning[i]
        assert np.linalg.norm(L - (L @ n[i]) * n[i]) < 1e-10 * h


def test_relax_inner_fairness_rejects_bad_input():
    s, onto, normals = _surface("sphere")
    with pytest.raises(ValueError, match="tangent_planes"):
        geofair.relax_inner_fairness(s.vertices, s.faces, s.free, s.normals, tangent_planes="x")
    with pytest.raises(ValueError, match="normals"):
        geofair.relax_inner_fairness(s.vertices, s.faces, s.free, s.normals[:-1])
    with pytest.raises(ValueError, match="normals"):
        geofair.relax_inner_fairness(s.vertices, s.faces, s.free, np.zeros_like(s.normals))
