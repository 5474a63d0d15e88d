"""Tests of the add-on's bpy-free carrying of layers onto new triangles (carry.py) and of choosing holes
(region.py), on hand-made meshes with stand-in library results (geofair_dev.fake_library: the fields of
``geofair.fair(..., remesh=True)`` and ``geofair.fill_holes``).

In Blender: tests/blender/check_remesh.py.
"""

import numpy as np
import pytest

from geofair_dev import paths
from geofair_dev.fake_library import centroid_remesh, fan_fill

carry = paths.source_module(paths.ADDON_SOURCE / "carry.py")
region = paths.source_module(paths.ADDON_SOURCE / "region.py")


def grid(nx, ny, skip=()):
    """A triangulated (nx × ny) grid in z = 0 without the quads ``skip``; vertex (x, y) is x + y (nx + 1)."""
    xs, ys = np.meshgrid(np.arange(nx + 1), np.arange(ny + 1))
    vertices = np.stack([xs.ravel(), ys.ravel(), np.zeros(xs.size)], axis=1).astype(float)

    def v(x, y):
        return x + y * (nx + 1)

    triangles = []
    for y in range(ny):
        for x in range(nx):
            if (x, y) not in skip:
                triangles += [[v(x, y), v(x + 1, y), v(x + 1, y + 1)], [v(x, y), v(x + 1, y + 1), v(x, y + 1)]]
    return vertices, np.array(triangles)


def linear_uv(points):
    return np.stack([0.1 + 0.05 * points[..., 0], 0.2 + 0.03 * points[..., 1] + 0.01 * points[..., 0]], axis=-1)


def test_corner_faces_follow_the_polygons_corner_ranges():
    # Polygons stored out of order: 1 corner range before 0.
    face = carry.corner_faces([4, 0], [3, 4], 7)
    assert face.tolist() == [1, 1, 1, 1, 0, 0, 0]


def test_remeshed_region_corners_interpolate_the_uv_map_exactly():
    vertices, triangles = grid(4, 4)
    free = np.zeros(len(vertices), dtype=bool)
    free[[6, 7, 8, 11, 12, 13, 16, 17, 18]] = True
    corner_uvs = linear_uv(vertices[triangles])  # (T, 3, 2), a UV map without seams
    result = centroid_remesh(vertices, triangles, free)
    new = carry.new_region_faces(triangles, free, result.faces)
    assert len(new) == 3 * np.count_nonzero(free[triangles].any(axis=1))
    new_faces = result.faces[new]
    region_rows = np.flatnonzero(free[triangles].any(axis=1))
    fixed = np.setdiff1d(np.unique(new_faces), np.flatnonzero(result.free))
    candidates = carry.corner_candidates(triangles[region_rows], corner_uvs[region_rows], fixed)
    uvs = carry.interpolate_corners(
        new_faces, result.free, triangles, corner_uvs, result.origin_face, result.origin_barycentric, candidates, {}
    )
    expected = linear_uv(result.vertices[new_faces])
    assert np.abs(uvs - expected).max() < 1e-12
    assert carry.flipped_uv_triangles(uvs, corner_uvs[region_rows]) == 0
    assert carry.split_vertices(triangles[region_rows], corner_uvs[region_rows], np.flatnonzero(free)) == 0
    points = carry.interpolate_points(
        vertices[:, :2], triangles, result.origin_face, result.origin_barycentric, np.flatnonzero(result.free)
    )
    assert np.abs(points - result.vertices[result.free][:, :2]).max() < 1e-12


def test_a_fixed_corner_on_a_seam_takes_the_value_of_its_side():
    vertices, triangles = grid(4, 2)
    free = np.zeros(len(vertices), dtype=bool)
    free[[6, 7, 8]] = True  # the middle row inside
    corner_uvs = linear_uv(vertices[triangles])
    right = vertices[triangles][..., 0].mean(axis=1) > 2.0
    corner_uvs[right] += [1.0, 0.0]  # a seam along x = 2: the right half is a separate island
    result = centroid_remesh(vertices, triangles, free)
    new_faces = result.faces[carry.new_region_faces(triangles, free, result.faces)]
    region_rows = np.flatnonzero(free[triangles].any(axis=1))
    fixed = np.setdiff1d(np.unique(new_faces), np.flatnonzero(result.free))
    candidates = carry.corner_candidates(triangles[region_rows], corner_uvs[region_rows], fixed)
    assert len(candidates[2]) == 2 and len(candidates[0]) == 1  # vertex (2, 0) is on the seam
    uvs = carry.interpolate_corners(
        new_faces, result.free, triangles, corner_uvs, result.origin_face, result.origin_barycentric, candidates, {}
    )
    at_seam = np.argwhere(new_faces == 2)
    for f, k in at_seam:
        centre = result.vertices[new_faces[f]].mean(axis=0)
        side = 1.0 if centre[0] > 2.0 else 0.0
        assert np.allclose(uvs[f, k], linear_uv(vertices[2]) + [side, 0.0]), (f, uvs[f, k])
    assert carry.split_vertices(triangles[region_rows], corner_uvs[region_rows], np.flatnonzero(free)) == 1


def test_a_result_that_lost_an_outside_triangle_is_refused():
    vertices, triangles = grid(3, 3)
    free = np.zeros(len(vertices), dtype=bool)
    free[5] = True
    result = centroid_remesh(vertices, triangles, free)
    with pytest.raises(carry.CarryError, match="lost triangles outside the region"):
        carry.new_region_faces(triangles, free, result.faces[1:])


def test_check_remeshed_refuses_nan_and_bad_origins():
    vertices, triangles = grid(3, 3)
    free = np.zeros(len(vertices), dtype=bool)
    free[5] = True
    r = centroid_remesh(vertices, triangles, free)
    carry.check_remeshed(r.vertices, r.faces, r.free, r.origin_face, r.origin_barycentric, len(triangles))
    bad = r.vertices.copy()
    bad[5, 0] = np.nan
    with pytest.raises(carry.CarryError, match="invalid positions"):
        carry.check_remeshed(bad, r.faces, r.free, r.origin_face, r.origin_barycentric, len(triangles))
    origin = r.origin_face.copy()
    origin[5] = len(triangles)
    with pytest.raises(carry.CarryError, match="origin"):
        carry.check_remeshed(r.vertices, r.faces, r.free, origin, r.origin_barycentric, len(triangles))
    faces = r.faces.copy()
    faces[-1] = [0, 0, 1]
    with pytest.raises(carry.CarryError, match="degenerate"):
        carry.check_remeshed(r.vertices, faces, r.free, r.origin_face, r.origin_barycentric, len(triangles))


def test_harmonic_fill_reproduces_a_linear_map_over_a_planar_hole():
    hole = {(1, 1), (2, 1), (1, 2), (2, 2)}
    vertices, triangles = grid(4, 4, skip=hole)
    loops = region.mesh_holes(triangles, len(vertices))
    assert [len(loop) for loop in loops] == [16, 8]
    result = fan_fill(vertices, triangles, [loops[1]])
    new_faces = result.faces[len(triangles) :]
    known = np.zeros(len(result.vertices), dtype=bool)
    known[: len(vertices)] = True
    values = np.zeros((len(result.vertices), 2))
    values[: len(vertices)] = linear_uv(vertices)
    filled = carry.harmonic_fill(result.vertices, new_faces, known, values)
    assert np.abs(filled[len(vertices) :] - linear_uv(result.vertices[len(vertices) :])).max() < 1e-9
    assert np.array_equal(filled[: len(vertices)], values[: len(vertices)])


def test_harmonic_fill_of_many_new_vertices_converges():
    # A finer fill: the 1-to-3 split of the fan, twice (interior vertices connected to interior ones).
    vertices, triangles = grid(6, 6, skip={(x, y) for x in range(1, 5) for y in range(1, 5)})
    loops = region.mesh_holes(triangles, len(vertices))
    fill = fan_fill(vertices, triangles, [loops[1]])
    n = len(vertices)
    free = np.zeros(len(fill.vertices), dtype=bool)
    free[n:] = True
    finer = centroid_remesh(fill.vertices, fill.faces, free)
    finer = centroid_remesh(finer.vertices, finer.faces, finer.free)
    new_faces = finer.faces[np.asarray(finer.free)[finer.faces].any(axis=1)]
    known = ~np.asarray(finer.free)
    values = np.zeros((len(finer.vertices), 2))
    values[known] = linear_uv(finer.vertices[known])
    filled = carry.harmonic_fill(finer.vertices, new_faces, known, values)
    inside = np.asarray(finer.free)
    assert np.isfinite(filled).all()
    low, high = values[known].min(axis=0), values[known].max(axis=0)
    assert (filled[inside] >= low - 1e-12).all() and (filled[inside] <= high + 1e-12).all()  # maximum principle


def test_boundary_corner_values_count_jumps_at_a_seam():
    vertices, triangles = grid(4, 4, skip={(1, 1), (2, 1), (1, 2), (2, 2)})
    loop = region.mesh_holes(triangles, len(vertices))[1]
    corner_uvs = linear_uv(vertices[triangles])
    values, jumps = carry.boundary_corner_values(triangles, corner_uvs, loop, len(vertices))
    assert jumps == 0 and np.allclose(values, linear_uv(vertices[loop]))
    corner_uvs[vertices[triangles][..., 0].mean(axis=1) > 2.0] += [1.0, 0.0]
    _, jumps = carry.boundary_corner_values(triangles, corner_uvs, loop, len(vertices))
    assert jumps == 2  # where the seam x = 2 meets the hole, at (2, 1) and (2, 3)


def test_choose_holes():
    vertices, triangles = grid(4, 4, skip={(1, 1), (2, 1), (1, 2), (2, 2)})
    n = len(vertices)
    loops = region.mesh_holes(triangles, n)
    inner = loops[1]
    edges = np.stack([inner, np.roll(inner, -1)], axis=1)
    assert [len(loop) for loop in region.choose_holes(loops, n, edges)] == [8]
    with pytest.raises(region.RegionError, match="close no hole"):
        region.choose_holes(loops, n, edges[:3])
    with pytest.raises(region.NothingSelectedError, match="No hole is selected"):
        region.choose_holes(loops, n, np.array([[0, 6]]))  # an inner edge, no boundary one
    closed = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    with pytest.raises(region.NothingSelectedError, match="'Tet' has no hole"):
        region.choose_holes(region.mesh_holes(closed, 4), 4, np.zeros((0, 2)), name="Tet")


def test_every_hole_is_the_librarys_rule():
    # Nothing selected: the library's holes (geofair.holes_to_fill), here the grid's hole and not its border.
    geofair = pytest.importorskip("geofair")
    vertices, triangles = grid(4, 4, skip={(1, 1), (2, 1), (1, 2), (2, 2)})
    outer, inner = region.mesh_holes(triangles, len(vertices))
    holes, left_open = region.every_hole(geofair, vertices, triangles, "Grid")
    assert [sorted(loop.tolist()) for loop in holes] == [sorted(inner.tolist())]
    ((loop, reason),) = left_open
    assert sorted(loop.tolist()) == sorted(outer.tolist()) and reason.startswith("an outer border")
    text = region.left_open_text(left_open)
    assert text.startswith(f"the loop of 16 edges at vertex {loop[0]} is left open, an outer border: it spans")
    plain, plain_triangles = grid(2, 2)
    with pytest.raises(region.NothingSelectedError, match=r"'Plane' has no hole to fill: the loop of 8 edges"):
        region.every_hole(geofair, plain, plain_triangles, "Plane")
    closed = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    tet = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    with pytest.raises(region.NothingSelectedError, match="'Tet' has no hole: every edge has two faces"):
        region.every_hole(geofair, tet, closed, "Tet")
