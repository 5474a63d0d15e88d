"""geofair.remesh_region, the isotropic remesh of a region (Botsch & Kobbelt 2004), and
fair(remesh=...): the row layout (fixed rows bit-identical, free rows reused, extras
appended), an oriented manifold region behind the same border, edge lengths near the
target, positions reproduced from origin_face/origin_barycentric, valences towards 6."""

import math

import numpy as np
import pytest

import geofair
from geofair_dev import scenes


def pole_cap(k=48, polar_angle=60.0, rings=3):
    """The unit sphere's cap within `polar_angle` degrees of +z as a fan of k thin triangles around one
    free vertex at the pole (valence k, triangles 7.7 times longer than wide for k = 48),
    with `rings` rings of k fixed vertices from there outwards (a strip of fixed triangles
    between them). Returns (vertices on the sphere, faces oriented outward, free)."""
    theta0 = math.radians(polar_angle)
    step = 2 * math.pi * math.sin(theta0) / k
    rows = [np.array([[0.0, 0.0, 1.0]])]
    for j in range(rings):
        t, phi = theta0 + j * step, 2 * math.pi * (np.arange(k) + 0.5 * (j % 2)) / k
        rows.append(np.column_stack([np.sin(t) * np.cos(phi), np.sin(t) * np.sin(phi), np.full(k, np.cos(t))]))
    v = np.concatenate(rows)
    f = [[0, 1 + i, 1 + (i + 1) % k] for i in range(k)]
    for j in range(rings - 1):
        a, b = 1 + j * k, 1 + (j + 1) * k
        for i in range(k):
            i1 = (i + 1) % k
            if j % 2 == 0:
                f += [[a + i, b + i, a + i1], [a + i1, b + i, b + i1]]
            else:
                f += [[a + i, b + i, b + i1], [a + i, b + i1, a + i1]]
    f = np.array(f, dtype=np.int32)
    outward = (np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]) * v[f].mean(axis=1)).sum(axis=1) > 0
    f[~outward] = f[~outward][:, ::-1]
    free = np.zeros(len(v), bool)
    free[0] = True
    return v, f, free


def random_cap(n_free=2000, seed=1):
    """The flattened random-sample cap of tests/test_flattened_caps.py on the exact sphere:
    irregular (valences 3 to 11), (vertices, faces, free, exact normals)."""
    s, _ = scenes.flattened_sphere_cap(n_free, "random", seed=seed)
    return s.vertices, s.faces.astype(np.int32), s.free, s.normals


def half_edges(faces):
    return np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])


def border_half_edges(faces):
    """The half-edges of `faces` whose opposite is in no face, as a set of (a, b)."""
    h = {tuple(e) for e in half_edges(faces).tolist()}
    return {(a, b) for a, b in h if (b, a) not in h}


def region(faces, free):
    return faces[free[faces].any(axis=1)]


def target_length(v, f, free):
    b = np.array(sorted(border_half_edges(region(f, free))))
    return np.linalg.norm(v[b[:, 0]] - v[b[:, 1]], axis=1).mean()


def interior_edge_lengths(r):
    """Lengths of the new region's edges that are not on its border."""
    new = region(r.faces, r.free)
    border = {tuple(sorted(e)) for e in border_half_edges(new)}
    e = [x for x in scenes.edges(new).tolist() if tuple(x) not in border]
    e = np.array(e)
    return np.linalg.norm(r.vertices[e[:, 0]] - r.vertices[e[:, 1]], axis=1)


def free_valences(r):
    return scenes.valences(r.faces, len(r.vertices))[r.free]


CASES = {"random cap": random_cap, "pole": lambda: pole_cap() + (None,)}


@pytest.mark.parametrize("case", CASES)
def test_fixed_rows_faces_outside_and_region_border_kept(case):
    v, f, free, _ = CASES[case]()
    r = geofair.remesh_region(v, f, free)
    n = len(v)
    assert r.vertices.dtype == np.float64 and r.faces.dtype == np.int32
    assert np.array_equal(r.vertices[:n][~free], v[~free])  # bit-identical, same rows
    assert not r.free[:n][~free].any()
    # Faces without a free vertex first, unchanged and in order; the new region behind the
    # same border, traversed the same way.
    outside = f[~free[f].any(axis=1)]
    assert np.array_equal(r.faces[: len(outside)], outside)
    new = r.faces[len(outside) :]
    assert r.free[new].any(axis=1).all()
    assert border_half_edges(new) == border_half_edges(region(f, free))


@pytest.mark.parametrize("case", CASES)
def test_new_region_is_an_oriented_manifold(case):
    v, f, free, _ = CASES[case]()
    r = geofair.remesh_region(v, f, free)
    new = region(r.faces, r.free)
    h = half_edges(new)
    # Each half-edge once: every edge in at most two faces, oppositely oriented.
    assert len(np.unique(h, axis=0)) == len(h)
    # Each edge with a free vertex in exactly two faces: free vertices are surrounded.
    interior = h[r.free[h].any(axis=1)]
    opposite = {tuple(e) for e in h.tolist()}
    assert all((b, a) in opposite for a, b in interior.tolist())
    # Each free vertex's triangles form one closed fan: as many faces as neighbours, and
    # the mesh's Euler characteristic of the region (a disk) stays 1.
    counts = np.bincount(new.ravel(), minlength=len(r.vertices))
    assert np.array_equal(counts[r.free], free_valences(r))
    used = np.unique(new)
    assert len(used) - len(scenes.edges(new)) + len(new) == 1


@pytest.mark.parametrize("case", CASES)
def test_row_layout(case):
    v, f, free, _ = CASES[case]()
    r = geofair.remesh_region(v, f, free)
    n, n_fixed, n_new = len(v), int((~free).sum()), int(r.free.sum())
    assert len(r.vertices) == max(n, n_fixed + n_new)
    assert len(r.free) == len(r.origin_face) == len(r.origin_barycentric) == len(r.vertices)
    # Unreferenced rows: input free rows in no face, not free; the others are all used.
    assert free[r.unreferenced].all() and not r.free[r.unreferenced].any()
    assert not np.isin(r.unreferenced, r.faces).any()
    # Faces use fixed rows and new free rows only, and every new free row.
    used = np.unique(r.faces)
    assert np.isin(used, np.flatnonzero(~free)).sum() + r.free[used].sum() == len(used)
    assert r.free[used].sum() == n_new
    assert len(r.unreferenced) + n_new >= int(free.sum())


def test_edge_lengths_near_the_target():
    v, f, free, _ = random_cap()
    L = target_length(v, f, free)
    lengths = interior_edge_lengths(geofair.remesh_region(v, f, free)) / L
    before = interior_edge_lengths(geofair.remesh_region(v, f, free, iterations=0)) / L
    inside = ((lengths >= 0.8) & (lengths <= 4 / 3)).mean()
    # Measured: 90.6% of the interior edges within [4/5 L, 4/3 L] (the input's: 57%), 0.1%
    # longer (the relaxation after the splits stretches a few, to 1.48 L), the rest shorter
    # where a collapse would have made an edge longer than 4/3 L or flipped a triangle (no
    # edge below 0.57 L; the input's shortest: 0.10 L).
    assert inside >= 0.88
    assert inside > ((before >= 0.8) & (before <= 4 / 3)).mean() + 0.25
    assert (lengths > 4 / 3).mean() <= 0.01
    assert lengths.max() <= 1.6 and lengths.min() >= 0.5


def test_target_edge_length_option():
    v, f, free, _ = random_cap()
    L = 2 * target_length(v, f, free)
    r = geofair.remesh_region(v, f, free, target_edge_length=L)
    lengths = interior_edge_lengths(r) / L
    assert np.median(lengths) == pytest.approx(1.0, abs=0.15)
    assert r.free.sum() < free.sum() / 2.5  # twice the edge length: about a quarter the vertices


@pytest.mark.parametrize("case", CASES)
def test_origin_reproduces_positions_on_the_input_surface(case):
    v, f, free, _ = CASES[case]()
    r = geofair.remesh_region(v, f, free)
    i = np.flatnonzero(r.free)
    b = r.origin_barycentric[i]
    assert (r.origin_face[i] >= 0).all() and (r.origin_face[i] < len(f)).all()
    assert free[f[r.origin_face[i]]].any(axis=1).all()  # faces of the input region
    assert np.abs(b.sum(axis=1) - 1).max() <= 1e-12 and (b >= 0).all()
    p = (b[:, :, None] * v[f[r.origin_face[i]]]).sum(axis=1)
    assert np.abs(p - r.vertices[i]).max() <= 1e-12
    others = np.flatnonzero(~r.free)
    assert (r.origin_face[others] == -1).all() and not r.origin_barycentric[others].any()


def test_no_iterations_returns_the_input_region():
    v, f, free, _ = random_cap()
    r = geofair.remesh_region(v, f, free, iterations=0)
    assert np.array_equal(r.vertices, v) and np.array_equal(r.free, free)
    assert len(r.unreferenced) == 0
    assert {tuple(x) for x in r.faces.tolist()} == {tuple(x) for x in f.tolist()}


def test_valences_of_a_pole_become_regular():
    v, f, free = pole_cap()
    r = geofair.remesh_region(v, f, free)
    val = free_valences(r)
    # The pole had valence 48. Measured: 246 free vertices, all of valence 5, 6 or 7; 85% of
    # the interior edges within [4/5 L, 4/3 L], none longer (the fan's: 8.8 L).
    assert val.min() >= 5 and val.max() <= 7
    lengths = interior_edge_lengths(r) / target_length(v, f, free)
    assert ((lengths >= 0.8) & (lengths <= 4 / 3)).mean() >= 0.8
    assert lengths.max() <= 4 / 3


def test_valences_of_an_irregular_region_move_towards_six():
    v, f, free, _ = random_cap()
    before = scenes.valences(f, len(v))[free]
    after = free_valences(geofair.remesh_region(v, f, free))
    # Measured: |valence - 6| <= 1 at 82% of the input's free vertices (valences 4 to 11),
    # at all of them after (5 to 7).
    assert np.mean(np.abs(before - 6) <= 1) < 0.85
    assert np.all(np.abs(after - 6) <= 1)


def test_invalid_input_raises():
    v, f, free, _ = random_cap(300)
    with pytest.raises(ValueError, match="no vertex is free"):
        geofair.remesh_region(v, f, np.zeros(len(v), bool))
    with pytest.raises(ValueError, match="iterations"):
        geofair.remesh_region(v, f, free, iterations=-1)
    with pytest.raises(ValueError, match="target_edge_length"):
        geofair.remesh_region(v, f, free, target_edge_length=-1.0)
    flipped = f.copy()
    t = np.flatnonzero(free[f].any(axis=1))[0]
    flipped[t] = flipped[t, ::-1]
    with pytest.raises(ValueError, match="oriented"):
        geofair.remesh_region(v, flipped, free)
    # A free vertex on the mesh border: drop its first triangle.
    with pytest.raises(ValueError, match="mesh border"):
        geofair.remesh_region(v, np.delete(f, t, axis=0), free)
    bad = v.copy()
    bad[np.flatnonzero(free)[0]] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        geofair.remesh_region(bad, f, free)
