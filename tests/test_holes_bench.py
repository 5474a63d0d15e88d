"""The helpers of the hole-filling benchmark (geofair_dev.holes, bench/holes.py) and its
CGAL reference (geofair_dev.cgal_fill_hole) measure what they claim.

The CGAL tests are skipped when build/bench/cgal_fill_hole is not built, except in CI.
"""

import numpy as np
import pytest

from geofair_dev import cgal_fill_hole, holes, scenes


def grid(n=21, jitter=0.0, seed=0):
    """A planar n x n grid on z = 0, [0, 1]^2, each square split in two: (vertices, faces)."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n), indexing="xy")
    v = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    if jitter:
        inner = (v[:, 0] > 0) & (v[:, 0] < 1) & (v[:, 1] > 0) & (v[:, 1] < 1)
        v[inner, :2] += np.random.default_rng(seed).uniform(-jitter, jitter, (inner.sum(), 2)) / (n - 1)
    i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="xy")
    a = (j * n + i).ravel()
    b, c, d = a + 1, a + n + 1, a + n
    return v, np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def centre_vertex(v):
    return int(np.argmin(np.linalg.norm(v[:, :2] - 0.5, axis=1)))


# --------------------------------------------------------------------------------------
# Topology


def test_boundary_loops_of_a_triangle_and_a_grid():
    loops = holes.boundary_loops(np.array([[0, 1, 2]]))
    assert len(loops) == 1
    assert [int(x) for x in np.roll(loops[0], -int(np.argmin(loops[0])))] == [0, 1, 2]
    v, f = grid(5)
    (loop,) = holes.boundary_loops(f)
    assert len(loop) == 16  # the 4 x 4 squares' border
    assert set(loop.tolist()) == set(np.flatnonzero(scenes.border_mask(f, len(v))).tolist())
    assert holes.boundary_loops(scenes.sphere(n_vertices=642).faces) == []


def test_boundary_loops_agree_with_the_library():
    geofair = pytest.importorskip("geofair")
    if not hasattr(geofair, "boundary_loops"):
        pytest.skip("geofair.boundary_loops is not in this build")
    v, f = grid(21, jitter=0.3)
    hole, _ = holes.cut_disc(v, f, centre_vertex(v), radius=0.2)
    ours = holes.boundary_loops(hole.faces)
    theirs = geofair.boundary_loops(hole.vertices, hole.faces)
    assert len(ours) == len(theirs) == 2
    for loop in ours:  # the same cycle, run the other way (theirs: the missing face's direction)
        match = [t for t in theirs if set(t.tolist()) == set(loop.tolist())]
        assert len(match) == 1
        t = np.asarray(match[0])[::-1]
        k = int(np.flatnonzero(t == loop[0])[0])
        assert np.array_equal(np.roll(t, -k), loop)


def test_manifold_check_accepts_manifolds_and_rejects_the_rest():
    assert holes.manifold_problem(grid(6)[1]) is None
    assert holes.manifold_problem(scenes.sphere(n_vertices=642).faces) is None
    bowtie = np.array([[0, 1, 2], [0, 3, 4]])  # two triangles meeting at vertex 0 only
    assert "vertex 0" in holes.manifold_problem(bowtie)
    fin = np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]])  # edge 0-1 in three triangles
    assert holes.manifold_problem(fin) is not None
    flipped = np.array([[0, 1, 2], [0, 1, 3]])  # both triangles run 0 -> 1: inconsistent orientation
    assert "used twice in one direction" in holes.manifold_problem(flipped)
    assert "repeats a vertex" in holes.manifold_problem(np.array([[0, 1, 1]]))


def test_cut_disc_leaves_exactly_one_new_boundary_loop():
    s = scenes.sphere(n_vertices=2562, irregular=True, seed=2)
    hole, why = holes.cut_disc(s.vertices, s.faces, 0, count=100)
    assert why is None
    assert hole.removed >= 100
    assert len(hole.vertices) == len(s.vertices) - hole.removed
    loops = holes.boundary_loops(hole.faces)
    assert len(loops) == 1  # the sphere had none
    assert sorted(loops[0].tolist()) == sorted(hole.loop.tolist())
    assert holes.manifold_problem(hole.faces) is None
    # The cut-away triangles are a disc whose border is the loop, at the same positions.
    assert holes.euler_characteristic(hole.cut_faces) == 1
    (cut_loop,) = holes.boundary_loops(hole.cut_faces)
    a = np.sort(hole.cut_vertices[cut_loop], axis=0)
    b = np.sort(hole.vertices[hole.loop], axis=0)
    assert np.array_equal(a, b)
    # Cut plus cut-away is the whole sphere's area.
    area = lambda v, f: 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1).sum()  # noqa: E731
    total = area(s.vertices, s.faces)
    assert area(hole.vertices, hole.faces) + area(hole.cut_vertices, hole.cut_faces) == pytest.approx(total, rel=1e-12)


def test_cut_disc_in_a_grid_adds_one_loop_and_rejects_the_border():
    v, f = grid(21, jitter=0.3)
    hole, why = holes.cut_disc(v, f, centre_vertex(v), radius=0.2)
    assert why is None
    assert len(holes.boundary_loops(hole.faces)) == 2  # the grid's border and the hole
    assert np.linalg.norm(hole.vertices[hole.loop, :2] - 0.5, axis=1).max() < 0.2 + 2 / 20
    near_border = int(np.argmin(np.linalg.norm(v[:, :2] - [0.1, 0.5], axis=1)))
    hole, why = holes.cut_disc(v, f, near_border, radius=0.2)
    assert hole is None and "border" in why


def test_bfs_rings_cut_a_hexagon_out_of_a_grid():
    v, f = grid(11)
    seed = centre_vertex(v)
    hops = holes.hop_distance(f, seed)
    assert hops[seed] == 0 and hops[seed + 1] == 1 and hops[seed + 11 + 1] == 1  # the diagonal is an edge
    assert hops[seed - 11 - 1] == 1 and hops[seed + 11 - 1] == 2  # the other diagonal is not
    hole, why = holes.cut_disc(v, f, seed, radius=1, distance=hops)
    assert why is None and hole.removed == 7  # the seed and its six neighbours
    assert len(hole.loop) == 12  # the second ring
    assert len(holes.boundary_loops(hole.faces)) == 2


def test_neighbourhood_keeps_the_loop_and_is_manifold():
    s = scenes.sphere(n_vertices=2562, irregular=True, seed=2)
    hole, _ = holes.cut_disc(s.vertices, s.faces, 5, count=60)
    near = holes.neighbourhood(hole, 3)
    assert len(near.vertices) < len(hole.vertices)
    assert np.array_equal(near.vertices[near.loop], hole.vertices[hole.loop])
    assert holes.manifold_problem(near.faces) is None
    assert len(holes.boundary_loops(near.faces)) >= 2  # the hole and the surroundings' outer border


def test_loop_subdivision_keeps_a_plane_and_the_topology():
    v, f = grid(6, jitter=0.3)
    v2, f2 = holes.loop_subdivide(v, f)
    edges = len(scenes.edges(f))
    assert len(v2) == len(v) + edges and len(f2) == 4 * len(f)
    assert np.abs(v2[:, 2]).max() == 0.0
    assert holes.manifold_problem(f2) is None
    s = scenes.sphere(n_vertices=642)
    v3, f3 = holes.loop_subdivide(s.vertices, s.faces)
    assert holes.euler_characteristic(f3) == 2 and holes.manifold_problem(f3) is None
    r = np.linalg.norm(v3, axis=1)
    assert 0.99 < r.min() and r.max() <= 1.0 + 1e-12  # Loop's limit surface lies inside a convex mesh


# --------------------------------------------------------------------------------------
# Distances and checks


@pytest.mark.parametrize(
    ("point", "expected"),
    [
        ((0.2, 0.2, 3.0), 3.0),  # above the face
        ((0.25, 0.25, -0.5), 0.5),  # below it
        ((2.0, 0.0, 0.0), 1.0),  # beyond corner (1, 0, 0)
        ((-1.0, -1.0, 1.0), np.sqrt(3.0)),  # beyond the corner at the origin
        ((0.5, -1.0, 0.0), 1.0),  # beside edge (0,0)-(1,0)
        ((1.0, 1.0, 0.0), np.sqrt(0.5)),  # beside the hypotenuse, nearest (0.5, 0.5, 0)
        ((0.3, 0.3, 0.0), 0.0),  # on the face
    ],
)
def test_point_triangle_distance_by_hand(point, expected):
    d = holes.point_triangle_distance(point, (0, 0, 0), (1, 0, 0), (0, 1, 0))
    assert d.shape == (1,)
    assert d[0] == pytest.approx(expected, abs=1e-15)


def test_fill_distance_and_check_of_the_cut_triangles_put_back():
    v, f = grid(21, jitter=0.3)
    hole, _ = holes.cut_disc(v, f, centre_vertex(v), radius=0.2)
    # The cut-away triangles put back on the cut mesh's vertices (matched by position): the
    # original surface, at distance 0, closed, manifold, nothing folded.
    vo, fo = holes.cut_surface_put_back(hole)
    check = holes.check_fill(hole.vertices, hole.faces, hole.loop, vo, fo)
    assert check["input_kept"] and check["closed"] and check["manifold"] is None and check["folds"] == 0
    inner = len(np.unique(hole.cut_faces)) - len(hole.loop)  # the cut-away vertices off the loop
    assert check["new_vertices"] == inner and check["new_faces"] == len(hole.cut_faces)
    ref = (hole.cut_vertices, hole.cut_faces)
    assert max(holes.fill_distance(vo, fo, len(hole.faces), ref)) < 1e-15  # rounding of the samples alone
    lifted = vo.copy()
    lifted[len(hole.vertices) :, 2] = 0.01
    mean, worst = holes.fill_distance(lifted, fo, len(hole.faces), ref)
    assert worst == pytest.approx(0.01, abs=1e-15) and 0 < mean < 0.01  # samples on the loop's triangles are lower
    assert holes.fill_distance(lifted, fo, len(hole.faces), lambda p: p[:, 2])[1] == pytest.approx(0.01)
    # One triangle left out: not closed. One flipped: not manifold. One point pushed through: folds.
    assert not holes.check_fill(hole.vertices, hole.faces, hole.loop, vo, fo[:-1])["closed"]
    flipped = fo.copy()
    flipped[-1] = flipped[-1, ::-1]
    assert holes.check_fill(hole.vertices, hole.faces, hole.loop, vo, flipped)["manifold"] is not None
    pushed = vo.copy()
    pushed[len(hole.vertices), :2] += 0.3  # far beyond its neighbours: its fan overlaps itself
    assert holes.check_fill(hole.vertices, hole.faces, hole.loop, pushed, fo)["folds"] > 0
    moved = vo.copy()
    moved[0, 2] = 1e-300
    assert not holes.check_fill(hole.vertices, hole.faces, hole.loop, moved, fo)["input_kept"]


def test_cut_surface_folds_counts_the_folds_of_the_surface_cut_away():
    v, f = grid(21)
    centre = centre_vertex(v)
    folded = v.copy()
    folded[centre, :2] += 0.12  # beyond its neighbours: its fan overlaps itself
    for surface, expected_folds in ((v, False), (folded, True)):
        hole, _ = holes.cut_disc(surface, f, centre, count=40)
        assert (holes.cut_surface_folds(hole) > 0) == expected_folds


def test_folded_edges_counts_a_fold():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.0]])
    flat = np.array([[0, 1, 2], [1, 3, 2]])
    assert holes.folded_edges(v, flat, np.ones(2, bool)) == 0
    v[3] = (-0.5, -0.5, 0.0)  # the second triangle folded onto the first
    assert holes.folded_edges(v, flat, np.ones(2, bool)) == 1
    assert holes.folded_edges(v, flat, np.zeros(2, bool)) == 0  # not among the triangles asked about


# --------------------------------------------------------------------------------------
# CGAL's fill


def test_cgal_fill_of_a_planar_hole_lies_in_the_plane(needs_cgal):
    v, f = grid(31, jitter=0.3, seed=4)
    hole, why = holes.cut_disc(v, f, centre_vertex(v), radius=0.25)
    assert why is None
    r = cgal_fill_hole.cgal_fill_hole(hole.vertices, hole.faces, hole.loop)
    assert r.success and r.new_vertices > 0 and r.new_faces > 0
    assert len(r.vertices) == len(hole.vertices) + r.new_vertices
    assert np.abs(r.vertices[:, 2]).max() < 1e-12  # the bilaplacian reproduces the plane
    check = holes.check_fill(hole.vertices, hole.faces, hole.loop, r.vertices, r.faces)
    assert check["input_kept"] and check["closed"] and check["manifold"] is None and check["folds"] == 0
    mean, worst = holes.fill_distance(r.vertices, r.faces, len(hole.faces), (hole.cut_vertices, hole.cut_faces))
    assert worst < 1e-12
    assert r.seconds > 0 and r.peak_mib > 0
    assert r.seconds >= sum(r.phase_seconds.values()) - 1e-6


def test_cgal_fill_rejects_a_loop_that_is_not_a_boundary(needs_cgal):
    v, f = grid(11)
    with pytest.raises(RuntimeError, match="not a border edge"):
        cgal_fill_hole.cgal_fill_hole(v, f, [60, 61, 72])  # interior vertices


# --------------------------------------------------------------------------------------
# The benchmarks' summaries


def _bench(name):
    from geofair_dev import paths

    return paths.source_module(paths.REPO / "bench" / f"{name}.py", f"bench_{name}")


def test_holes_summary_counts_closer_fills_and_the_time_ratio():
    bench = _bench("holes")

    def row(case, method, mean, seconds, ok=True, kind="corpus"):
        return {"case": case, "kind": kind, "method": method, "status": "done", "ok": ok, "mean": mean,
                "max": 2 * mean, "seconds": seconds}  # fmt: skip

    rows = [row("a", "geofair", 1.0, 2.0), row("a", "cgal", 2.0, 1.0),  # ours closer, twice the time
            row("b", "geofair", 3.0, 3.0, ok=False), row("b", "cgal", 2.0, 1.0),  # CGAL closer
            row("c", "geofair", 1.0, 8.0), row("c", "cgal", 4.0, 1.0),  # ours closer
            {"case": "d", "kind": "corpus", "method": "geofair", "status": "timeout", "seconds": 120.0},
            row("d", "cgal", 1.0, 1.0)]  # fmt: skip
    text = "\n".join(bench.summary(rows, ["geofair", "cgal"]))
    assert "geofair: corpus holes filled (ok) 2 of 4 (timeout 1)" in text
    assert "cgal: corpus holes filled (ok) 4 of 4" in text
    assert "corpus holes filled by both: 3; geofair closer than cgal: mean distance 2 (67 %)" in text
    assert "of those filled ok by both (2): geofair closer (mean) on 2" in text
    assert "time ratio geofair/cgal over 3 holes: median 3.0, max 8.0" in text
    assert "folded edge" not in text  # no fold counts given
    # Fold counts: a hole whose cut-away surface folds is counted apart, a fill that is not
    # closed (or not manifold, or changed the input) not at all.
    for r, folds, cut_folds in zip(rows[:6:2], (0, 2, 0), (0, 0, 5), strict=True):
        r.update(folds=folds, cut_folds=cut_folds, closed=True, input_kept=True, manifold=None)
    line = "geofair: corpus fills (closed, manifold, input kept) without a folded edge: {}; where the cut-away "
    text = "\n".join(bench.summary(rows, ["geofair", "cgal"]))
    assert line.format("2 of 3") + "surface itself has none: 1 of 2" in text, text
    rows[4]["closed"] = False
    text = "\n".join(bench.summary(rows, ["geofair", "cgal"]))
    assert line.format("1 of 2") + "surface itself has none: 1 of 2" in text, text
    for r in rows:  # the same holes named as the benchmark names them: counted by size
        r["case"] = {"a": "cgal/elk/100/s0", "b": "cgal/elk/100/s1", "c": "cgal/bull/1000/s0"}.get(
            r["case"], "cgal/bull~1/10000/s0"
        )
    text = "\n".join(bench.summary(rows, ["geofair", "cgal"]))
    assert (
        "geofair: corpus holes ok by size (vertices removed, about): 100: 1 of 2, median 2.500 s; 1000: 1 of 1" in text
    )
    assert "10000: 0 of 1\n" in text  # a timeout: no time


def test_realmesh_summary_lists_cases_lost_and_gained_by_remeshing():
    bench = _bench("realmesh")

    def row(case, remesh, status, folds=0, remeshed=False):
        return {"case": case, "inner": "uniform", "remesh": remesh, "status": status, "new_folds": folds,
                "free": 100, "topology": "disc", "seconds": 1.0, "remeshed": remeshed}  # fmt: skip

    rows = [row("kept", "off", "yes"), row("kept", "if_needed", "yes"),
            row("lost", "off", "yes"), row("lost", "if_needed", "no", remeshed=True),
            row("gained", "off", "yes", folds=3), row("gained", "if_needed", "yes", remeshed=True)]  # fmt: skip
    for r in rows:
        if r["remesh"] == "off":
            del r["remeshed"]
    text = "\n".join(bench.summary(rows, ["uniform"], 60.0, ("off", "if_needed")))
    assert "uniform, remesh off: 3 cases, converged without new folds 2 (67 %)" in text
    assert "uniform, remesh if_needed: 3 cases, converged without new folds 2 (67 %)" in text
    assert "remeshed: 2 of 3 cases (3 finished)" in text
    assert "(lost): 1 (lost)" in text
    assert "(gained): 1 (gained)" in text
    # Remesh off alone: the summary as it always was (no remesh lines, the bare inner fairness).
    plain = bench.summary([r for r in rows if r["remesh"] == "off"], ["uniform"], 60.0)
    assert plain[0].startswith("uniform: 3 cases, converged without new folds 2 (67 %)")
    assert not any("remesh" in line for line in plain)
