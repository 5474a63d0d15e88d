"""Uniform inner fairness on triangulated polygon meshes (geofair.fair's polygon_ids).

Blender's meshes are mostly quads, which the add-on hands to the library as Blender's
tessellation into triangles. The uniform umbrella over the triangles counts each quad's
diagonal as an edge, so the vertex distribution, and with it what converges, depends on
which diagonal split each quad. With polygon_ids the umbrella runs over the quads' edges:
the result is the same for every split. Known answer: Blender's UV sphere (64 segments, 32
rings), whose cap above z = 0.25 is flattened and faired back onto the unit sphere."""

import numpy as np
import pytest

import geofair
from geofair_dev.polygons import fair_flattened_cap, splits, tessellated_uv_sphere


def test_uniform_fairing_of_quads_does_not_depend_on_their_split():
    results = {}
    for name, split in splits().items():
        r, free = fair_flattened_cap(split, polygons=True)
        assert r.converged, (name, r.message)
        # The library's boundary normals (the sphere's own normals give 2e-5): measured 6.9e-4 to 7.5e-4.
        assert np.abs(np.linalg.norm(r.vertices[free], axis=1) - 1.0).max() < 1e-3, name
        results[name] = r.vertices[free]
    for name in ("b-d", "checkerboard", "random"):
        # Measured 3e-6 (b-d), 6e-5 (checkerboard), 1e-5 (random): the discretization error of
        # the surface, which still sees the diagonals.
        assert np.linalg.norm(results[name] - results["a-c"], axis=1).max() < 2e-4, name


def test_without_polygon_ids_the_split_moves_the_vertices():
    # For contrast, the umbrella over the triangles: the two uniform splits converge, but the
    # vertices of one lie up to 0.41 from those of the other.
    first, free = fair_flattened_cap(splits()["a-c"], polygons=False)
    second, _ = fair_flattened_cap(splits()["b-d"], polygons=False)
    assert first.converged and second.converged
    assert np.linalg.norm(first.vertices[free] - second.vertices[free], axis=1).max() > 0.1


def test_polygon_ids_are_checked():
    vertices, faces, polygon_ids = tessellated_uv_sphere(splits()["a-c"])
    free = vertices[:, 2] > 0.25
    with pytest.raises(ValueError, match=rf"polygon_ids must have shape \({len(faces)},\)"):
        geofair.fair(vertices, faces, free, polygon_ids=polygon_ids[:-1])
    with pytest.raises(ValueError, match="polygon_ids must have an integer dtype"):
        geofair.fair(vertices, faces, free, polygon_ids=polygon_ids.astype(float))
    with pytest.raises(ValueError, match="out of range"):
        geofair.fair(vertices, faces, free, polygon_ids=polygon_ids.astype(np.int64) + 2**40)


def test_one_polygon_for_every_triangle_keeps_the_triangle_umbrella():
    # Bogus ids (all triangles one "polygon") leave every interior edge a diagonal: each free
    # vertex then keeps its whole ring, the same weights as without polygon_ids.
    vertices, faces, _ = tessellated_uv_sphere(splits()["a-c"])
    free = vertices[:, 2] > 0.25
    flat = vertices.copy()
    flat[free, 2] = 0.25
    same = geofair.fair(flat, faces, free, polygon_ids=np.zeros(len(faces), np.int32), max_iterations=3)
    plain = geofair.fair(flat, faces, free, max_iterations=3)
    np.testing.assert_array_equal(same.vertices, plain.vertices)


def random_split_grid(n=10, jitter=0.3, seed=1):
    """A planar grid of n×n unit-spaced quads, each split along a random diagonal, its
    interior vertices jittered; (vertices, faces, free, polygon_ids, the regular grid)."""
    rng = np.random.default_rng(seed)
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="xy")
    grid = np.column_stack([i.ravel(), j.ravel(), np.zeros(i.size)]).astype(float)
    free = ((i > 0) & (i < n) & (j > 0) & (j < n)).ravel()
    vertices = grid.copy()
    vertices[free, :2] += jitter * rng.uniform(-1, 1, (free.sum(), 2))
    faces, polygon_ids = [], []
    for q, (x, y) in enumerate((x, y) for y in range(n) for x in range(n)):
        a, b, c, d = y * (n + 1) + x, y * (n + 1) + x + 1, (y + 1) * (n + 1) + x + 1, (y + 1) * (n + 1) + x
        faces += [[a, b, c], [a, c, d]] if rng.random() < 0.5 else [[a, b, d], [b, c, d]]
        polygon_ids += [q, q]
    return vertices, np.array(faces), free, np.array(polygon_ids), grid


def test_relax_inner_fairness_over_polygons_reaches_the_regular_grid():
    # On a plane the uniform fixed point of the quads' umbrella is the regular grid; the
    # triangles' umbrella of a random split pulls vertices towards the diagonals' ends.
    vertices, faces, free, polygon_ids, grid = random_split_grid()
    normals = np.tile([0.0, 0.0, 1.0], (len(vertices), 1))

    def relaxed(**kw):
        x = vertices
        for _ in range(30):
            x, _ = geofair.relax_inner_fairness(x, faces, free, normals, tangent_planes="fixed", **kw)
        return x

    assert np.abs(relaxed(polygon_ids=polygon_ids) - grid).max() < 1e-9
    assert np.abs(relaxed() - grid).max() > 0.05
