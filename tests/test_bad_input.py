"""Bad input and hard meshes: geofair answers with a faired mesh or a clear ValueError or
RuntimeError, never a crash, NaN, or a changed fixed vertex."""

import inspect
import time

import numpy as np
import pytest

import geofair
from geofair_dev import scenes


@pytest.fixture(scope="module")
def cap():
    return scenes.sphere_cap(n_free=200, irregular=True, seed=1)


def fair(v, f, free, **kw):
    return geofair.fair(v, f, free, max_iterations=kw.pop("max_iterations", 3000), **kw)


def check_result(r, v, free):
    assert np.all(np.isfinite(r.vertices)) and np.isfinite(r.residual)
    assert np.array_equal(r.vertices[~free], v[~free])


def test_arrays_converted_without_surprises(cap):
    ref = fair(cap.vertices, cap.faces, cap.free, boundary_normals=cap.normals)
    # Fortran order, int32 faces, uint faces: the same result.
    for v, f in (
        (np.asfortranarray(cap.vertices), cap.faces),
        (cap.vertices, cap.faces.astype(np.int32)),
        (cap.vertices, cap.faces.astype(np.uint32)),
    ):
        r = fair(v, f, cap.free, boundary_normals=cap.normals)
        assert np.array_equal(r.vertices, ref.vertices)


@pytest.mark.parametrize(
    "mutate, message",
    [
        (lambda v, f, m, n: (v.astype(np.float32), f, m, n), "vertices must have dtype float64"),
        (lambda v, f, m, n: (v[:, :2].copy(), f, m, n), r"vertices must have shape \(n, 3\)"),
        (lambda v, f, m, n: (v, f.astype(float), m, n), "faces must have an integer dtype"),
        (lambda v, f, m, n: (v, f.ravel(), m, n), r"faces must have shape \(m, 3\)"),
        (lambda v, f, m, n: (v, f, m[:-1], n), r"free must have shape"),
        (lambda v, f, m, n: (v, f, m.astype(np.uint8), n), "free must have dtype bool"),
        (lambda v, f, m, n: (v, f, m, n[:-1]), "boundary_normals"),
        (lambda v, f, m, n: (v.tolist(), f, m, n), "vertices must be a numpy array"),
    ],
)
def test_wrong_shapes_and_dtypes(cap, mutate, message):
    v, f, m, n = mutate(cap.vertices, cap.faces, cap.free, cap.normals)
    with pytest.raises(ValueError, match=message):
        geofair.fair(v, f, m, boundary_normals=n)


def test_indices_out_of_range(cap):
    # One wording for every function and every index, too large, negative or beyond int32.
    n = len(cap.vertices)
    calls = {
        "fair": lambda f: geofair.fair(cap.vertices, f, cap.free, boundary_normals=cap.normals),
        "fill_holes": lambda f: geofair.fill_holes(cap.vertices, f),
        "mean_curvature": lambda f: geofair.mean_curvature(cap.vertices, f),
        "boundary_normals": lambda f: geofair.boundary_normals(cap.vertices, f, cap.free),
        "cotangent_laplacian": lambda f: geofair.cotangent_laplacian(cap.vertices, f),
        "remesh_region": lambda f: geofair.remesh_region(cap.vertices, f, cap.free),
    }
    for index in (n, -1, 2**40):
        f = cap.faces.astype(np.int64)
        f[7, 1] = index
        for name, call in calls.items():
            with pytest.raises(geofair.InvalidInputError) as error:
                call(f)
            assert str(error.value) == f"{name}: triangle 7 has vertex index {index}, out of range [0, {n})"


MODULE_FUNCTIONS = [
    name for name in dir(geofair) if callable(getattr(geofair, name)) and not isinstance(getattr(geofair, name), type)
]


def test_every_module_function_has_a_signature():
    assert len(MODULE_FUNCTIONS) == 15, MODULE_FUNCTIONS
    for name in MODULE_FUNCTIONS:
        signature = inspect.signature(getattr(geofair, name))
        assert all(p.kind is not p.VAR_KEYWORD for p in signature.parameters.values()), name


@pytest.mark.parametrize("name", [f for f in MODULE_FUNCTIONS if f != "defaults"])
def test_unknown_keyword_is_named_with_the_nearest(cap, name):
    # A short TypeError naming the keyword and the nearest valid one, not pybind11's signature
    # and the repr of every input array.
    function = getattr(geofair, name)
    parameters = list(inspect.signature(function).parameters)
    misspelt = parameters[-1][:-1] + "x" + parameters[-1][-1]
    known = {"path": "mesh.ply", "vertices": cap.vertices, "faces": cap.faces}  # read_mesh, write_mesh: a path first
    with pytest.raises(TypeError) as error:
        function(*[known[p] for p in parameters[:3] if p in known], **{misspelt: 1})
    message = str(error.value)
    assert message.startswith(f"{name}() got an unexpected keyword argument '{misspelt}'"), message
    assert f"did you mean '{parameters[-1]}'?" in message and len(message.splitlines()) < 5, message


def test_argument_errors_are_short(cap):
    args = (cap.vertices, cap.faces, cap.free)
    unexpected = "fair() got an unexpected keyword argument"
    cases = [
        (lambda: geofair.fair(*args, tolerence=1e-3), f"{unexpected} 'tolerence'; did you mean 'tolerance'?"),
        (lambda: geofair.fair(*args, xyz=1), f"{unexpected} 'xyz' (its arguments: vertices, faces, free, remesh,"),
        (lambda: geofair.fair(*args, tolerance="1e-3"), "fair(): tolerance must be a number, got str '1e-3'"),
        (lambda: geofair.fair(*args, max_iterations=2.5), "fair(): max_iterations must be an int, got float 2.5"),
        (lambda: geofair.fair(*args, inner_fairness=None), "fair(): inner_fairness must be a str, got None"),
        (lambda: geofair.fair(*args, "g0"), "fair() takes 3 positional arguments but 4 were given (the others are"),
        (lambda: geofair.fair(*args[:2]), "fair() missing required argument 'free'"),
        (lambda: geofair.fair(*args, faces=cap.faces), "fair() got multiple values for argument 'faces'"),
        (lambda: geofair.defaults(1), "defaults() takes 0 positional arguments but 1 were given"),
    ]
    for call, expected in cases:
        with pytest.raises(TypeError) as error:
            call()
        assert str(error.value).startswith(expected), str(error.value)
        assert len(str(error.value)) < 400, str(error.value)


def test_arguments_convert_as_before(cap):
    # By keyword or position, numpy scalars and Python ints for numbers: the same result.
    reference = geofair.fair(cap.vertices, cap.faces, cap.free, boundary_normals=cap.normals, tolerance=1e-4)
    for kw in (
        dict(tolerance=np.float64(1e-4), max_iterations=np.int64(20000), levels=np.int32(0)),
        dict(damping=0.9, cg_iterations=10, time_limit=None),
    ):
        r = geofair.fair(vertices=cap.vertices, faces=cap.faces, free=cap.free, boundary_normals=cap.normals, **kw)
        assert np.array_equal(r.vertices, reference.vertices)


def test_non_finite_input(cap):
    v = cap.vertices.copy()
    i = int(np.flatnonzero(cap.free)[5])
    v[i, 2] = np.nan
    with pytest.raises(ValueError, match=f"vertex {i} has a non-finite coordinate"):
        geofair.fair(v, cap.faces, cap.free, boundary_normals=cap.normals)
    n = cap.normals.copy()
    b = int(np.flatnonzero(~cap.free)[3])
    n[b] = [np.inf, 0, 0]
    with pytest.raises(ValueError, match=f"vertex {b} is not finite"):
        geofair.fair(cap.vertices, cap.faces, cap.free, boundary_normals=n)


@pytest.mark.parametrize("normals", ["given", "estimated"])
def test_non_finite_vertex_outside_the_region(normals):
    # A fixed vertex two rings away from the free ones: not read by the solve, but returned.
    s = scenes.sphere_cap(n_free=300, boundary_rings=3)
    near = np.zeros(len(s.vertices), bool)
    near[s.faces[s.free[s.faces].any(axis=1)].ravel()] = True
    i = int(np.flatnonzero(~near)[0])
    v = s.vertices.copy()
    v[i, 0] = np.inf
    bn = s.normals if normals == "given" else None
    with pytest.raises(geofair.InvalidInputError, match=f"vertex {i} has a non-finite coordinate"):
        geofair.fair(v, s.faces, s.free, boundary_normals=bn)


def test_non_finite_vertex_in_no_triangle_is_returned_as_it_is(cap):
    v = np.vstack([cap.vertices, [np.nan, np.nan, np.nan]])
    free = np.append(cap.free, False)
    r = geofair.fair(v, cap.faces, free, boundary_normals=np.vstack([cap.normals, [0, 0, 1]]))
    assert r.converged and np.isnan(r.vertices[-1]).all()
    assert np.isfinite(r.vertices[:-1]).all()


def test_zero_or_non_unit_normals(cap):
    b = int(np.flatnonzero(~cap.free)[0])
    for scale, message in ((0.0, "length 0"), (1.01, "not a unit vector")):
        n = cap.normals.copy()
        n[b] *= scale
        with pytest.raises(ValueError, match=message):
            geofair.fair(cap.vertices, cap.faces, cap.free, boundary_normals=n)
    # Rows of vertices that are not G1 boundary vertices are ignored, whatever they hold.
    n = cap.normals.copy()
    n[cap.free] = np.nan
    check_result(fair(cap.vertices, cap.faces, cap.free, boundary_normals=n), cap.vertices, cap.free)


def test_no_free_vertex_and_no_boundary(cap):
    with pytest.raises(ValueError, match="no vertex is free"):
        geofair.fair(cap.vertices, cap.faces, np.zeros_like(cap.free))
    s = scenes.sphere(n_vertices=200)
    with pytest.raises(ValueError, match="G1 boundary"):
        geofair.fair(s.vertices, s.faces, np.ones(len(s.vertices), bool))


def test_region_reaching_the_border_needs_normals(cap):
    with pytest.raises(ValueError, match="pass boundary_normals"):
        geofair.fair(cap.vertices, cap.faces, cap.free)
    wide = scenes.sphere_cap(n_free=200, irregular=True, seed=1, boundary_rings=2)
    check_result(fair(wide.vertices, wide.faces, wide.free), wide.vertices, wide.free)


def test_degenerate_triangles_inside_the_region(cap):
    # Two free vertices on top of each other, and a collinear (zero-area) triangle: the
    # cotangent of a vanishing angle is capped at 1e12 instead of inf, and the bilaplacian
    # initial mesh replaces the free positions, so the result is a faired mesh.
    inside = cap.faces[cap.free[cap.faces].all(axis=1)]
    v = cap.vertices.copy()
    a, b, c = inside[0]
    v[b] = v[a]
    d, e, g = inside[10]
    v[g] = 0.5 * (v[d] + v[e])
    r = fair(v, cap.faces, cap.free, boundary_normals=cap.normals)
    check_result(r, v, cap.free)
    assert r.converged
    assert np.abs(np.linalg.norm(r.vertices[cap.free], axis=1) - 1).max() < 5e-3


def test_repeated_vertex_and_non_manifold_edge(cap):
    f = cap.faces.copy()
    f[3] = [f[3, 0], f[3, 0], f[3, 1]]
    with pytest.raises(ValueError, match="triangle 3 repeats a vertex"):
        geofair.fair(cap.vertices, f, cap.free, boundary_normals=cap.normals)
    k = int(np.flatnonzero(cap.free[cap.faces].all(axis=1))[0])
    f = np.vstack([cap.faces, cap.faces[k]])  # the same triangle twice: a non-manifold edge
    with pytest.raises(ValueError, match="non-manifold"):
        geofair.fair(cap.vertices, f, cap.free, boundary_normals=cap.normals)


def test_inconsistent_orientation(cap):
    f = cap.faces.copy()
    k = int(np.flatnonzero(cap.free[f].all(axis=1))[4])
    f[k] = f[k, ::-1]
    with pytest.raises(ValueError, match="oriented"):
        geofair.fair(cap.vertices, f, cap.free, boundary_normals=cap.normals)


def fan(valence, height):
    """A vertex of the given valence in the middle of two rings of a flat disk."""
    ang = np.linspace(0, 2 * np.pi, valence, endpoint=False)
    ring = np.c_[np.cos(ang), np.sin(ang), np.zeros(valence)]
    v = np.vstack([[0, 0, height], ring, 2 * ring])
    f = [[0, 1 + i, 1 + (i + 1) % valence] for i in range(valence)]
    for i in range(valence):
        a, b = 1 + i, 1 + (i + 1) % valence
        f += [[a, a + valence, b + valence], [a, b + valence, b]]
    free = np.zeros(len(v), bool)
    free[0] = True
    return v, np.array(f), free


@pytest.mark.parametrize("valence", [3, 4, 20, 40])
def test_high_and_low_valence(valence):
    # A plane with a lifted centre vertex: fairing puts the vertex back into the plane.
    v, f, free = fan(valence, height=0.3)
    r = fair(v, f, free)
    check_result(r, v, free)
    assert r.converged and abs(r.vertices[0, 2]) < 1e-9


def test_scaled_mesh_gives_the_scaled_result():
    s = scenes.catenoid_patch(n_free=150, irregular=True, seed=3)
    v = s.disturbed(seed=1)
    ref = fair(v, s.faces, s.free, boundary_normals=s.normals, tolerance=1e-10, max_iterations=200)
    for scale in (1e-4, 1e4):
        r = fair(scale * v, s.faces, s.free, boundary_normals=s.normals, tolerance=1e-10, max_iterations=200)
        assert np.allclose(r.vertices / scale, ref.vertices, rtol=0, atol=1e-9 * s.size)


def test_several_boundary_loops():
    # An annulus of a cylinder: two boundary loops.
    s = scenes.cylinder_tube(radius=1.0, height=2.0, n_vertices=600, irregular=True, seed=2)
    v = s.disturbed(seed=1) if hasattr(s, "disturbed") else s.vertices
    r = fair(v, s.faces, s.free, boundary_normals=s.normals)
    check_result(r, v, s.free)
    assert r.converged
    assert np.abs(s.distance(r.vertices[s.free])).max() < 5e-3


def test_not_converged_is_reported(cap):
    r = geofair.fair(cap.disturbed(seed=2), cap.faces, cap.free, boundary_normals=cap.normals, max_iterations=3)
    assert not r.converged and r.iterations == 3


def random_mesh(rng):
    """A random or mutated small mesh: sometimes valid, often not."""
    base = scenes.sphere_cap(n_free=int(rng.integers(20, 80)), irregular=True, seed=int(rng.integers(1000)))
    v, f, free, n = base.disturbed(seed=int(rng.integers(1000))), base.faces.copy(), base.free.copy(), base.normals
    kind = rng.integers(6)
    if kind == 0:  # random faces
        f = rng.integers(0, len(v), size=f.shape)
    elif kind == 1:  # flip some triangles
        k = rng.integers(0, len(f), size=3)
        f[k] = f[k, ::-1]
    elif kind == 2:  # random free mask
        free = rng.random(len(v)) < 0.5
    elif kind == 3:  # collapse vertices
        k = rng.integers(0, len(v), size=5)
        v[k] = v[k[0]]
    elif kind == 4:  # huge displacements
        v = v + rng.normal(scale=10.0, size=v.shape) * free[:, None]
    return v, f, free, (n if rng.random() < 0.7 else None)


def test_random_and_mutated_meshes():
    rng = np.random.default_rng(20261121)
    start, outcomes = time.perf_counter(), {"result": 0, "ValueError": 0, "RuntimeError": 0}
    while time.perf_counter() - start < 20 and sum(outcomes.values()) < 300:
        v, f, free, n = random_mesh(rng)
        try:
            r = geofair.fair(
                v, f, free, boundary_normals=n, max_iterations=100, inner_fairness=rng.choice(["uniform", "conformal"])
            )
        except ValueError as e:
            assert str(e)
            outcomes["ValueError"] += 1
            continue
        except RuntimeError as e:
            assert str(e)
            outcomes["RuntimeError"] += 1
            continue
        check_result(r, v, free)
        outcomes["result"] += 1
    assert outcomes["result"] > 0 and outcomes["ValueError"] > 0
