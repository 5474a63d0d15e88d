"""Tests of the add-on's bpy-free region module on small hand-made meshes.

Boundary normals come from the library (``geofair.boundary_normals``) except where the
add-on keeps a vertex's current normal: :func:`normals` assembles them as the add-on does.
"""

import importlib.util
import pathlib

import numpy as np
import pytest

import geofair
from geofair_dev import scenes

_REGION_PY = pathlib.Path(__file__).resolve().parents[1] / "addon" / "geometric_fairing" / "region.py"
_spec = importlib.util.spec_from_file_location("geofair_region", _REGION_PY)
region = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(region)


def grid(nx, ny):
    """Quad grid in the z = 0 plane: (nx+1)(ny+1) vertices, vertex (x, y) has index x + y (nx+1).

    Returns vertices, triangles, the polygon of each triangle and a function
    quad(x, y) giving the polygon index of the quad with lower-left corner (x, y).
    Quads are counter-clockwise seen from +z and fan-triangulated along the
    diagonal from (x, y) to (x+1, y+1).
    """
    xs, ys = np.meshgrid(np.arange(nx + 1), np.arange(ny + 1))
    vertices = np.stack([xs.ravel(), ys.ravel(), np.zeros(xs.size)], axis=1).astype(float)
    v = lambda x, y: x + y * (nx + 1)  # noqa: E731
    corners = [[v(x, y), v(x + 1, y), v(x + 1, y + 1), v(x, y + 1)] for y in range(ny) for x in range(nx)]
    starts = np.arange(len(corners)) * 4
    triangles, triangle_polygon = region.triangulate_polygons(starts, np.full(len(corners), 4), np.ravel(corners))
    return vertices, triangles, triangle_polygon, lambda x, y: x + y * nx


def normals(r, vertices, triangles, present=None):
    """The boundary normals the add-on passes to geofair.fair for region ``r``."""
    triangles = triangles if present is None else triangles[present]
    return region.boundary_normals(r, vertices, triangles, geofair.boundary_normals)


def vertex_mask(n, nx, points):
    mask = np.zeros(n, dtype=bool)
    for x, y in points:
        mask[x + y * (nx + 1)] = True
    return mask


def select_quads(triangle_polygon, quad, quads):
    return np.isin(triangle_polygon, [quad(x, y) for x, y in quads])


def signed_area_xy(vertices, loop):
    p = vertices[loop]
    q = np.roll(p, -1, axis=0)
    return 0.5 * np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1])


def octahedron():
    """Closed octahedron, outward oriented: equator 0..3, top 4, bottom 5."""
    vertices = np.array([[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
    top = [[i, (i + 1) % 4, 4] for i in range(4)]
    bottom = [[(i + 1) % 4, i, 5] for i in range(4)]
    return vertices, np.array(top + bottom)


def test_fan_triangulation_of_quads_and_ngons():
    # A triangle, a quad and a convex pentagon (regular, radius 1).
    angles = 2 * np.pi * np.arange(5) / 5
    pentagon = np.stack([np.cos(angles), np.sin(angles), np.zeros(5)], axis=1)
    vertices = np.vstack([[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0], [2, 0, 0], [2, 3, 0], [0, 3, 0]], pentagon])
    starts, totals = np.array([0, 3, 7]), np.array([3, 4, 5])
    triangles, triangle_polygon = region.triangulate_polygons(starts, totals, np.arange(12))

    assert triangles.shape == (1 + 2 + 3, 3)
    np.testing.assert_array_equal(triangle_polygon, [0, 1, 1, 2, 2, 2])
    np.testing.assert_array_equal(triangles[1:3], [[3, 4, 5], [3, 5, 6]])
    area = np.linalg.norm(region.face_cross_products(vertices, triangles), axis=1) / 2
    polygon_area = np.bincount(triangle_polygon, weights=area)
    np.testing.assert_allclose(polygon_area, [0.5, 6.0, 2.5 * np.sin(2 * np.pi / 5)], rtol=1e-14)
    # Orientation is kept: every triangle faces +z like its polygon.
    assert np.all(region.face_cross_products(vertices, triangles)[:, 2] > 0)


def test_triangulation_rejects_degenerate_polygon():
    with pytest.raises(ValueError, match="at least 3"):
        region.triangulate_polygons([0], [2], [0, 1])


def test_square_selection_in_grid():
    nx = ny = 6
    vertices, triangles, triangle_polygon, quad = grid(nx, ny)
    n = len(vertices)
    selected = select_quads(triangle_polygon, quad, [(x, y) for x in range(1, 5) for y in range(1, 5)])
    # Lift the inner vertices: boundary normals come from the unselected (flat) faces only.
    inner = [(x, y) for x in range(2, 5) for y in range(2, 5)]
    vertices[vertex_mask(n, nx, inner), 2] = 1.0

    r = region.find_region(vertices, triangles, selected)

    np.testing.assert_array_equal(r.free, vertex_mask(n, nx, inner))
    ring = [(x, y) for x in range(1, 6) for y in range(1, 6) if x in (1, 5) or y in (1, 5)]
    # Corners (5, 1) and (1, 5) share no triangle with a free vertex (the diagonals run from
    # (x, y) to (x+1, y+1)), so they are not part of the G1 boundary.
    expected_boundary = vertex_mask(n, nx, [p for p in ring if p not in ((5, 1), (1, 5))])
    np.testing.assert_array_equal(r.boundary, expected_boundary)
    assert not r.keeps_normal.any() and not r.current_normals.any()
    n_boundary = normals(r, vertices, triangles)
    np.testing.assert_array_equal(n_boundary[r.boundary], np.tile([0.0, 0.0, 1.0], (14, 1)))
    np.testing.assert_array_equal(n_boundary[~r.boundary], 0.0)
    assert not r.border_fixed.any()

    assert len(r.loops) == 1
    loop = r.loops[0]
    assert len(loop) == 14 and set(loop.tolist()) == set(np.flatnonzero(expected_boundary).tolist())
    # Consecutive loop vertices are joined by mesh edges, and the loop turns counter-clockwise.
    assert np.all(np.abs(vertices[loop] - vertices[np.roll(loop, -1)])[:, :2].max(axis=1) == 1)
    assert signed_area_xy(vertices, loop) > 0


def test_selection_touching_open_border():
    nx, ny = 4, 4
    vertices, triangles, triangle_polygon, quad = grid(nx, ny)
    n = len(vertices)
    selected = select_quads(triangle_polygon, quad, [(0, 1), (1, 1), (0, 2), (1, 2)])
    vertices[vertex_mask(n, nx, [(1, 2)]), 2] = 1.0  # lift the free vertex

    r = region.find_region(vertices, triangles, selected)

    np.testing.assert_array_equal(r.free, vertex_mask(n, nx, [(1, 2)]))
    # (0, 2) has only selected faces but lies on the open border: kept fixed.
    np.testing.assert_array_equal(r.border_fixed, vertex_mask(n, nx, [(0, 2)]))
    assert r.boundary[2 * (nx + 1)]
    # Its normal falls back to the selected faces at it: cross products, by hand,
    # (-1, 0, 1) + (-1, 1, 1) + (0, 0, 1) of its three triangles.
    np.testing.assert_array_equal(r.keeps_normal, r.border_fixed)
    n_boundary = normals(r, vertices, triangles)
    np.testing.assert_allclose(n_boundary[2 * (nx + 1)], np.array([-2, 1, 3]) / np.sqrt(14), rtol=1e-15)
    # The other boundary vertices see flat unselected faces: the library's estimate.
    others = r.boundary & ~r.border_fixed
    np.testing.assert_array_equal(n_boundary[others], np.tile([0.0, 0.0, 1.0], (others.sum(), 1)))
    assert len(r.loops) == 1 and 2 * (nx + 1) in r.loops[0]


def test_whole_open_grid_selected_fixes_the_border():
    nx, ny = 3, 3
    vertices, triangles, _, _ = grid(nx, ny)
    r = region.find_region(vertices, triangles, np.ones(len(triangles), dtype=bool))
    interior = [(x, y) for x in (1, 2) for y in (1, 2)]
    np.testing.assert_array_equal(r.free, vertex_mask(len(vertices), nx, interior))
    assert r.border_fixed.sum() == 12
    n_boundary = normals(r, vertices, triangles)
    np.testing.assert_array_equal(n_boundary[r.boundary], np.tile([0.0, 0.0, 1.0], (r.boundary.sum(), 1)))


def test_two_disjoint_selections():
    nx, ny = 9, 4
    vertices, triangles, triangle_polygon, quad = grid(nx, ny)
    n = len(vertices)
    blocks = [(x, y) for x in (1, 2) for y in (1, 2)] + [(x, y) for x in (6, 7) for y in (1, 2)]
    r = region.find_region(vertices, triangles, select_quads(triangle_polygon, quad, blocks))

    np.testing.assert_array_equal(r.free, vertex_mask(n, nx, [(2, 2), (7, 2)]))
    assert len(r.loops) == 2
    left, right = sorted(r.loops, key=lambda loop: vertices[loop, 0].mean())
    assert vertices[left, 0].max() <= 3 and vertices[right, 0].min() >= 6
    assert set(left.tolist()) | set(right.tolist()) == set(np.flatnonzero(r.boundary).tolist())
    assert all(signed_area_xy(vertices, loop) > 0 for loop in r.loops)


def test_annulus_has_two_boundary_loops():
    nx = ny = 7
    vertices, triangles, triangle_polygon, quad = grid(nx, ny)
    n = len(vertices)
    ring = [(x, y) for x in range(1, 6) for y in range(1, 6) if (x, y) != (3, 3)]
    r = region.find_region(vertices, triangles, select_quads(triangle_polygon, quad, ring))

    hole = [(3, 3), (4, 3), (4, 4), (3, 4)]
    free = [(x, y) for x in range(2, 6) for y in range(2, 6) if (x, y) not in hole]
    np.testing.assert_array_equal(r.free, vertex_mask(n, nx, free))
    assert len(r.loops) == 2
    outer, inner = r.loops
    assert signed_area_xy(vertices, outer) > 0
    # The inner loop runs around the hole, clockwise.
    assert set(inner.tolist()) == set(np.flatnonzero(vertex_mask(n, nx, hole)).tolist())
    assert signed_area_xy(vertices, inner) == -1.0


def test_octahedron_normals_come_from_unselected_faces():
    vertices, triangles = octahedron()
    selected = np.array([True] * 4 + [False] * 4)  # the four faces around the top
    r = region.find_region(vertices, triangles, selected)

    np.testing.assert_array_equal(r.free, [False] * 4 + [True, False])
    np.testing.assert_array_equal(r.boundary, [True] * 4 + [False, False])
    equator = vertices[:4]
    # Bisector of the two lower faces: the library's quadric fit has too few samples (four) and
    # falls back to the area-weighted normal of the surrounding triangles.
    expected = (equator + [0, 0, -1]) / np.sqrt(2)
    np.testing.assert_allclose(normals(r, vertices, triangles)[:4], expected, rtol=0, atol=1e-15)
    assert len(r.loops) == 1
    loop = r.loops[0]
    assert np.array_equal(np.roll(loop, -int(np.argmin(loop))), [0, 1, 2, 3])


@pytest.mark.parametrize(
    "selected, message",
    [
        ([False] * 8, region.NO_FACE_SELECTED),
        ([True] + [False] * 7, "No vertex lies inside"),
        ([True] * 8, region.WHOLE_MESH_SELECTED),
    ],
)
def test_invalid_selections(selected, message):
    vertices, triangles = octahedron()
    with pytest.raises(region.RegionError) as error:
        region.find_region(vertices, triangles, np.array(selected))
    assert message in str(error.value)
    assert isinstance(error.value, region.NothingSelectedError) == (message == region.NO_FACE_SELECTED)


def test_no_face_selected_says_whether_vertices_or_edges_are():
    with pytest.raises(region.NothingSelectedError) as error:
        region.require_selected_faces(np.zeros(4, dtype=bool), np.zeros(6, dtype=bool))
    assert str(error.value) == region.NO_FACE_SELECTED == "No face is selected: select the faces to fair"
    with pytest.raises(region.NothingSelectedError) as error:
        region.require_selected_faces(np.zeros(4, dtype=bool), np.array([0, 1, 0, 0, 0, 1], dtype=bool))
    assert str(error.value) == region.ONLY_VERTICES_OR_EDGES
    assert str(error.value).startswith("No face is selected, only vertices or edges")
    region.require_selected_faces(np.array([0, 0, 1, 0], dtype=bool), None)  # a face: no error


def test_hidden_faces_are_absent():
    # An 8x8 grid with the inner 6x6 quads selected, and the quad at (3, 3) hidden (absent).
    nx = ny = 8
    vertices, triangles, triangle_polygon, quad = grid(nx, ny)
    n = len(vertices)
    rng = np.random.default_rng(3)
    vertices[:, 2] = rng.uniform(-0.2, 0.2, n)
    block = [(x, y) for x in range(1, 7) for y in range(1, 7)]
    hidden = select_quads(triangle_polygon, quad, [(3, 3)])
    selected = select_quads(triangle_polygon, quad, block) & ~hidden  # Blender never selects a hidden face

    r = region.find_region(vertices, triangles, selected, present=~hidden)

    hidden_corners = [(3, 3), (4, 3), (4, 4), (3, 4)]
    np.testing.assert_array_equal(r.hidden_fixed, vertex_mask(n, nx, hidden_corners))
    inner = [(x, y) for x in range(2, 7) for y in range(2, 7)]
    np.testing.assert_array_equal(r.free, vertex_mask(n, nx, [p for p in inner if p not in hidden_corners]))
    assert not r.border_fixed.any()
    # The hidden quad's corners are boundary vertices with the normal of the visible faces at
    # them: all selected, so the area-weighted normal of their selected present triangles.
    present_triangles = triangles[~hidden]
    cross = region.face_cross_products(vertices, present_triangles)
    n_boundary = normals(r, vertices, triangles, present=~hidden)
    np.testing.assert_array_equal(r.keeps_normal, r.hidden_fixed)
    for x, y in hidden_corners:
        i = x + y * (nx + 1)
        assert r.boundary[i]
        expected = cross[(present_triangles == i).any(axis=1)].sum(axis=0)
        np.testing.assert_allclose(n_boundary[i], expected / np.linalg.norm(expected), rtol=1e-13)
    # Two loops: the outer one and one around the hidden quad.
    assert len(r.loops) == 2 and set(r.loops[1].tolist()) == set(np.flatnonzero(r.hidden_fixed).tolist())

    # With the hidden quad present (and unselected) the same vertices are boundary with normals
    # of the unselected quad: they differ, so hidden faces really take no part above.
    shown = region.find_region(vertices, triangles, selected)
    np.testing.assert_array_equal(shown.free, r.free)
    assert not shown.hidden_fixed.any()
    i = 3 + 3 * (nx + 1)
    assert not np.allclose(normals(shown, vertices, triangles)[i], n_boundary[i])


def test_closed_mesh_with_hidden_faces_selected_elsewhere():
    # The whole visible octahedron selected, its bottom face hidden: the mesh now ends at the
    # hidden face, whose vertices hold the rest in place.
    vertices, triangles = octahedron()
    hidden = np.array([False] * 7 + [True])
    r = region.find_region(vertices, triangles, ~hidden, present=~hidden)
    np.testing.assert_array_equal(r.hidden_fixed, np.isin(np.arange(6), triangles[7]))
    np.testing.assert_array_equal(r.free, ~np.isin(np.arange(6), triangles[7]))
    with pytest.raises(region.NothingSelectedError, match="No face is selected"):
        region.find_region(vertices, triangles, hidden, present=~hidden)  # only a hidden face "selected"
    with pytest.raises(ValueError, match="present must have one entry per triangle"):
        region.find_region(vertices, triangles, ~hidden, present=np.ones(3, dtype=bool))


@pytest.mark.parametrize("seed", range(5))
def test_connected_parts_match_a_flood_fill(seed):
    rng = np.random.default_rng(seed)
    n = 200
    edges = rng.integers(0, n, size=(150, 2))
    label = region.connected_parts(n, edges)
    # Reference: a flood fill over an adjacency list.
    neighbours = [[] for _ in range(n)]
    for a, b in edges.tolist():
        neighbours[a].append(b)
        neighbours[b].append(a)
    expected = np.full(n, -1)
    for start in range(n):
        if expected[start] >= 0:
            continue
        stack = [start]
        expected[start] = start
        while stack:
            for w in neighbours[stack.pop()]:
                if expected[w] < 0:
                    expected[w] = start
                    stack.append(w)
    np.testing.assert_array_equal(label, expected)


def test_connected_parts_of_a_long_path():
    # A path numbered so that every hook goes the wrong way: still one part, in a few passes.
    n = 100000
    order = np.random.default_rng(0).permutation(n)
    label = region.connected_parts(n, np.stack([order[:-1], order[1:]], axis=1))
    assert (label == 0).all()


def test_closed_part_fully_selected_next_to_valid_selection():
    vertices, triangles = octahedron()
    vertices = np.vstack([vertices, vertices + [5, 0, 0]])
    triangles = np.vstack([triangles, triangles + 6])
    selected = np.array([True] * 4 + [False] * 4 + [True] * 8)
    with pytest.raises(region.RegionError) as error:
        region.find_region(vertices, triangles, selected)
    assert str(error.value) == region.WHOLE_CLOSED_PART
    # Everything selected, but an open grid beside the octahedron: not "the whole mesh has no border".
    grid_vertices, grid_triangles, _, _ = grid(3, 3)
    vertices = np.vstack([vertices, grid_vertices + [0, 0, 5]])
    triangles = np.vstack([triangles, grid_triangles + 12])
    with pytest.raises(region.RegionError) as error:
        region.find_region(vertices, triangles, np.ones(len(triangles), dtype=bool))
    assert str(error.value) == region.WHOLE_CLOSED_PART


def test_region_error_is_a_value_error():
    assert issubclass(region.RegionError, ValueError)


def test_pinned_vertex_inside_the_region():
    nx = ny = 6
    vertices, triangles, triangle_polygon, quad = grid(nx, ny)
    n = len(vertices)
    selected = select_quads(triangle_polygon, quad, [(x, y) for x in range(1, 5) for y in range(1, 5)])
    inner = [(x, y) for x in range(2, 5) for y in range(2, 5)]
    vertices[vertex_mask(n, nx, [(3, 3)]), 2] = 0.5  # the pinned vertex sits on a bump
    # Pins: the centre (inside), a rim vertex (already fixed) and one outside the region.
    pinned = vertex_mask(n, nx, [(3, 3), (1, 3), (0, 0)])

    r = region.find_region(vertices, triangles, selected, pinned=pinned)

    np.testing.assert_array_equal(r.pinned, vertex_mask(n, nx, [(3, 3)]))
    np.testing.assert_array_equal(r.free, vertex_mask(n, nx, [p for p in inner if p != (3, 3)]))
    centre = 3 + 3 * (nx + 1)
    assert r.boundary[centre] and not r.free[centre]
    # Its normal is its own current vertex normal: the area-weighted normal of its six triangles, by
    # hand: the bump of height h = 0.5 over unit quads cut along (x, y)-(x+1, y+1) gives cross products
    # summing to (0, 0, 6) in z and cancelling in x and y (the ring is point-symmetric about the vertex).
    assert r.keeps_normal[centre]
    np.testing.assert_allclose(normals(r, vertices, triangles)[centre], [0.0, 0.0, 1.0], atol=1e-15)
    # Loops outline the triangles that touch a free vertex: a lone pin lies inside that outline.
    assert len(r.loops) == 1 and centre not in r.loops[0]


def test_pinned_normal_on_a_slope():
    # Pin the centre of a tilted plane z = 0.5 x: its normal is the plane's, (-0.5, 0, 1)/|.|.
    nx = ny = 4
    vertices, triangles, triangle_polygon, quad = grid(nx, ny)
    vertices[:, 2] = 0.5 * vertices[:, 0]
    selected = select_quads(triangle_polygon, quad, [(x, y) for x in range(4) for y in range(4)])
    r = region.find_region(vertices, triangles, selected, pinned=vertex_mask(len(vertices), nx, [(2, 2)]))
    n_boundary = normals(r, vertices, triangles)
    np.testing.assert_allclose(n_boundary[2 + 2 * (nx + 1)], np.array([-0.5, 0, 1]) / np.sqrt(1.25))


def test_normals_are_the_library_estimate_where_there_is_an_unselected_face():
    # A sphere cap (three rings of fixed vertices around it), its free region's triangles
    # selected: every boundary vertex has unselected faces, and the add-on passes the
    # library's estimate unchanged; the one-sided normal of the unselected faces (what the
    # add-on computed before) is 50 times further from the sphere's.
    s = scenes.sphere_cap(n_free=2000, irregular=True, boundary_rings=3)
    r = region.find_region(s.vertices, s.faces, s.free[s.faces].any(axis=1))
    np.testing.assert_array_equal(r.free, s.free)
    assert not r.keeps_normal.any()
    n_boundary = normals(r, s.vertices, s.faces)
    np.testing.assert_array_equal(n_boundary, geofair.boundary_normals(s.vertices, s.faces, s.free))
    error = np.linalg.norm(n_boundary[r.boundary] - s.normals[r.boundary], axis=1).max()
    one_sided = geofair.boundary_normals(s.vertices, s.faces, s.free, method="area")
    assert error < 1e-4 < 1e-2 < np.linalg.norm(one_sided[r.boundary] - s.normals[r.boundary], axis=1).max()


def test_degenerate_boundary_normal_is_an_error():
    # The unselected faces around the selection collapsed onto one point: no usable normal.
    nx = ny = 4
    vertices, triangles, triangle_polygon, quad = grid(nx, ny)
    selected = select_quads(triangle_polygon, quad, [(x, y) for x in (1, 2) for y in (1, 2)])
    r = region.find_region(vertices, triangles, selected)
    outside = ~r.free & ~r.boundary
    vertices[outside | r.boundary] = 0.0
    with pytest.raises(region.RegionError, match="boundary vertices have no usable normal"):
        normals(r, vertices, triangles)


def test_everything_pinned_is_an_error():
    vertices, triangles = octahedron()
    selected = np.array([True] * 4 + [False] * 4)
    with pytest.raises(region.RegionError, match="Every vertex inside the selection is pinned"):
        region.find_region(vertices, triangles, selected, pinned=np.array([False] * 4 + [True, False]))
    with pytest.raises(ValueError, match="one entry per vertex"):
        region.find_region(vertices, triangles, selected, pinned=np.ones(3, dtype=bool))


def test_region_triangles_touch_a_free_vertex():
    vertices, triangles = octahedron()
    free = np.array([False] * 4 + [True, False])
    np.testing.assert_array_equal(region.region_triangles(triangles, free), [True] * 4 + [False] * 4)


def test_polygons_inside_a_vertex_set():
    # A triangle, a quad and a pentagon sharing vertices; corners listed in polygon order.
    loop_start, loop_total = np.array([0, 3, 7]), np.array([3, 4, 5])
    corner_verts = np.array([0, 1, 2, 1, 3, 4, 2, 4, 5, 6, 7, 3])
    inside = np.zeros(8, dtype=bool)
    inside[[0, 1, 2, 3, 4]] = True
    np.testing.assert_array_equal(region.polygons_inside(inside, loop_start, loop_total, corner_verts), [1, 1, 0])
    inside[:] = True
    assert region.polygons_inside(inside, loop_start, loop_total, corner_verts).all()
    # Polygons need not be stored in corner order.
    np.testing.assert_array_equal(
        region.polygons_inside(np.arange(8) >= 3, [7, 0, 3], [5, 3, 4], corner_verts), [True, False, False]
    )


def test_fill_report_names_each_holes_method_and_the_removed_faces():
    """The add-on's Fill Holes report (region.hole_records, fill_text, hole_lines) from the library's
    per-hole records: methods counted, the removed triangles named as their polygons."""

    class Hole:
        def __init__(self, method, removed=(), folds=0, converged=True, reason=""):
            self.method, self.filled, self.folds, self.converged = method, method != "none", folds, converged
            self.removed_faces, self.reason, self.loop = np.array(removed, dtype=np.int32), reason, np.array([7, 8, 9])

    holes = [
        Hole("intrinsic"),
        Hole("intrinsic"),
        Hole("intrinsic_trimmed", removed=[4, 5, 9]),
        Hole("linear", folds=2, converged=True),
        Hole("none", reason="cannot be filled: it would take about 3e+06 new vertices"),
    ]
    triangle_face = np.array([0, 0, 1, 1, 2, 2, 3, 3, 4, 4])  # quads: two triangles each
    records = region.hole_records(holes, triangle_face)
    assert records[2]["removed_faces"] == [2, 4]
    text = region.fill_text(records)
    assert text.startswith("4 holes filled: 2 intrinsic, 1 after cleaning its rim (2 faces removed: 2, 4), 1 linear")
    assert "; 2 folded edges" in text and "not converged" not in text
    assert "the hole at vertex 7 is not filled: cannot be filled" in text
    lines = region.hole_lines(records)
    assert (
        len(lines) == 5
        and lines[2] == "hole at vertex 7: after cleaning its rim, converged, 0 folded edges, faces removed: 2, 4"
    )


def test_surface_distances_follow_the_edges_up_to_the_limit():
    # A unit-spaced grid of right triangles (diagonals from (i, j) to (i+1, j+1)): from the corner
    # (0, 0) the shortest edge path to (i, j) takes min(i, j) diagonals and |i - j| unit edges.
    n = 8
    x, y = np.meshgrid(np.arange(n, dtype=float), np.arange(n, dtype=float), indexing="ij")
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    index = np.arange(n * n).reshape(n, n)
    a, b, c, d = index[:-1, :-1].ravel(), index[1:, :-1].ravel(), index[1:, 1:].ravel(), index[:-1, 1:].ravel()
    triangles = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    sources = np.zeros(n * n, dtype=bool)
    sources[index[0, 0]] = True
    i, j = x.ravel(), y.ravel()
    exact = np.minimum(i, j) * np.sqrt(2.0) + np.abs(i - j)
    distance = region.surface_distances(vertices, triangles, sources, limit=5.0)
    inside = exact <= 5.0
    assert np.allclose(distance[inside], exact[inside])
    assert np.isinf(distance[~inside]).all() and (~inside).any()
    # Two sources: each vertex is as far as the nearer one.
    sources[index[-1, -1]] = True
    both = region.surface_distances(vertices, triangles, sources, limit=100.0)
    far = np.minimum(n - 1 - i, n - 1 - j) * np.sqrt(2.0) + np.abs(i - j)
    assert np.allclose(both, np.minimum(exact, far))
