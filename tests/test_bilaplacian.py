"""The linear initial mesh (section 7.4, bilaplacian.h) against an independent direct solve.

``outer_fairness="bilaplacian"`` returns the solution of Δ(Δf)(q_i) = 0 at every free
vertex, with Δf(q_j) = Σ_k λ_jk f_k − f_j and, at a G1 boundary vertex b, the normal part
n_b n_bᵀ Δf(q_b) of its one-sided umbrella. The library solves it by conjugate gradients on
the symmetric form, preconditioned by the Cholesky factors of its scalar part; here the
same equations are assembled from their definition with numpy and solved by scipy's sparse
LU, for uniform and for (clamped) cotangent weights.
"""

import numpy as np
import pytest
import scipy.sparse
import scipy.sparse.linalg

import geofair
from geofair_dev import scenes


def region_weights(vertices, faces, free, inner):
    """λ per region vertex as {j: λ_ij} over the triangles with a free vertex."""
    region = faces[free[faces].any(axis=1)]
    w = {}
    for tri in region:
        for c in range(3):
            i, j, k = tri[c], tri[(c + 1) % 3], tri[(c + 2) % 3]
            # The angle at k lies opposite the edge ij.
            a, b = vertices[i] - vertices[k], vertices[j] - vertices[k]
            cot = a.dot(b) / np.linalg.norm(np.cross(a, b))
            for p, q in ((i, j), (j, i)):
                w.setdefault(p, {}).setdefault(q, 0.0)
                w[p][q] = w[p][q] + cot if inner == "conformal" else 1.0
    lam = {}
    for i, row in w.items():
        clamped = {j: max(x, 0.0) for j, x in row.items()}
        total = sum(clamped.values())
        lam[i] = {j: x / total for j, x in clamped.items()} if total > 0 else {j: 1 / len(row) for j in row}
    return lam


def reference_bilaplacian(vertices, faces, free, normals, inner):
    lam = region_weights(vertices, faces, free, inner)
    free_ids = np.flatnonzero(free)
    index = {v: i for i, v in enumerate(free_ids)}
    nf = len(free_ids)
    rows, cols, vals = [], [], []
    rhs = np.zeros(3 * nf)

    def add_laplacian(row, weight, j):
        # weight · Δf(q_j) into the equations of free vertex `row`.
        P = np.eye(3) if free[j] else np.outer(normals[j], normals[j])
        terms = [(j, -1.0)] + list(lam[j].items())
        for k, c in terms:
            if free[k]:
                for a in range(3):
                    for b in range(3):
                        rows.append(3 * row + a)
                        cols.append(3 * index[k] + b)
                        vals.append(weight * c * P[a, b])
            else:
                rhs[3 * row : 3 * row + 3] -= weight * c * (P @ vertices[k])

    for row, i in enumerate(free_ids):
        add_laplacian(row, -1.0, i)
        for j, c in lam[i].items():
            add_laplacian(row, c, j)
    K = scipy.sparse.csc_matrix((vals, (rows, cols)), shape=(3 * nf, 3 * nf))
    f = scipy.sparse.linalg.spsolve(K, rhs).reshape(nf, 3)
    out = vertices.copy()
    out[free_ids] = f
    return out


@pytest.mark.parametrize("inner", ["uniform", "conformal"])
@pytest.mark.parametrize("scene", [scenes.sphere_cap, scenes.cylinder_patch])
def test_linear_solution_matches_a_direct_solve(scene, inner):
    s = scene(n_free=600, irregular=True, seed=5, boundary_rings=1)
    v = s.disturbed(seed=6, amplitude=0.1)
    expected = reference_bilaplacian(v, s.faces, s.free, s.normals, inner)
    r = geofair.fair(v, s.faces, s.free, boundary_normals=s.normals, inner_fairness=inner, outer_fairness="bilaplacian")
    # The boundary normals enter: the linear G1 solution is not the free-boundary one.
    assert np.abs(expected - v).max() > 1e-2 * s.size
    assert np.array_equal(r.vertices[~s.free], v[~s.free])
    assert np.abs(r.vertices - expected).max() < 1e-10 * s.size
