"""The G1 boundary normals estimated from the surface around the region.

geofair.boundary_normals (and fair() without boundary_normals) fits a least-squares
quadric through the fixed vertices within two rings of each G1 boundary vertex (region.h,
estimate_boundary_normals): error O(h²) on a smooth surface, where the one-sided
area-weighted normal of the surrounding triangles (method="area", the estimate of earlier
releases) is O(h). Measured here against the exact normals of sphere, cylinder and torus
patches (three rings of fixed vertices around the region) and of Blender's UV sphere.
"""

import re

import numpy as np
import pytest

import geofair
from geofair_dev import scenes
from geofair_dev.scenes import uv_sphere


def mean_edge(vertices, faces):
    e = scenes.edges(faces)
    return float(np.linalg.norm(vertices[e[:, 0]] - vertices[e[:, 1]], axis=1).mean())


def max_error(vertices, faces, free, exact, method):
    """Max |n - exact| over the G1 boundary (checking that its rows are unit vectors, the others zero)."""
    normals = geofair.boundary_normals(vertices, faces, free, method=method)
    g1 = np.zeros(len(vertices), dtype=bool)
    g1[faces[free[faces].any(axis=1)].ravel()] = True
    g1 &= ~free
    np.testing.assert_allclose(np.linalg.norm(normals[g1], axis=1), 1.0, rtol=0, atol=1e-14)
    assert not normals[~g1].any(), "rows of vertices off the G1 boundary are zero"
    return float(np.linalg.norm(normals[g1] - exact[g1], axis=1).max())


def orders(errors, sizes):
    return [np.log(errors[k] / errors[k + 1]) / np.log(sizes[k] / sizes[k + 1]) for k in range(len(errors) - 1)]


# Max error of the quadric estimate and of the one-sided area estimate at 500, 2000 and 8000
# free vertices (edge length halving), as measured when this test was written.
PATCHES = {
    "sphere_cap(regular)": (scenes.sphere_cap, False, [5.08e-4, 6.71e-5, 8.66e-6], [3.99e-2, 2.04e-2, 1.04e-2]),
    "sphere_cap(irregular)": (scenes.sphere_cap, True, [3.42e-4, 5.01e-5, 6.95e-6], [3.47e-2, 1.82e-2, 9.43e-3]),
    "cylinder_patch(irregular)": (
        scenes.cylinder_patch,
        True,
        [6.01e-4, 8.12e-5, 1.07e-5],
        [4.63e-2, 2.38e-2, 1.21e-2],
    ),
    # The torus's graph over its tangent plane has cubic terms (its curvature varies), which
    # the sphere's and the cylinder's lack: there the quadric's error falls like h³, here h².
    "torus_patch(regular)": (scenes.torus_patch, False, [1.96e-3, 4.44e-4, 1.10e-4], [6.70e-2, 3.42e-2, 1.70e-2]),
    "torus_patch(irregular)": (scenes.torus_patch, True, [3.06e-3, 6.83e-4, 1.50e-4], [7.08e-2, 3.60e-2, 1.83e-2]),
}


@pytest.mark.parametrize("name", PATCHES)
def test_quadric_estimate_is_second_order_on_patches(name):
    make, irregular, quadric_expected, area_expected = PATCHES[name]
    quadric, area, sizes = [], [], []
    for n_free in (500, 2000, 8000):
        s = make(n_free=n_free, irregular=irregular, boundary_rings=3)
        quadric.append(max_error(s.vertices, s.faces, s.free, s.normals, "quadric"))
        area.append(max_error(s.vertices, s.faces, s.free, s.normals, "area"))
        sizes.append(mean_edge(s.vertices, s.faces))
    print(name, "quadric", quadric, orders(quadric, sizes), "area", area, orders(area, sizes))
    assert min(orders(quadric, sizes)) > 1.7
    assert quadric == pytest.approx(quadric_expected, rel=0.02)
    # For contrast: the one-sided estimate is first order, and 20 to 1000 times worse.
    assert all(0.8 < order < 1.2 for order in orders(area, sizes))
    assert area == pytest.approx(area_expected, rel=0.02)


def test_quadric_estimate_on_uv_spheres():
    # The cap above z = 0.25 of Blender's UV sphere at three resolutions.
    quadric, area, sizes = [], [], []
    for segments in (32, 64, 128):
        vertices, faces = uv_sphere(segments, segments // 2)
        free = vertices[:, 2] > 0.25
        quadric.append(max_error(vertices, faces, free, vertices, "quadric"))
        area.append(max_error(vertices, faces, free, vertices, "area"))
        sizes.append(mean_edge(vertices, faces))
    assert min(orders(quadric, sizes)) > 1.7
    assert quadric == pytest.approx([6.76e-3, 8.35e-4, 1.04e-4], rel=0.02)
    assert area == pytest.approx([1.04e-1, 5.17e-2, 2.58e-2], rel=0.02)


def test_flattened_uv_sphere_cap_is_faired_back_onto_the_sphere():
    """Issue 23: the cap above z = 0.25 of the UV sphere (64 segments, 32 rings), flattened
    to z = 0.25 and faired without boundary normals, comes back onto the unit sphere."""
    vertices, faces = uv_sphere(64, 32)
    free = vertices[:, 2] > 0.25
    flat = vertices.copy()
    flat[free, 2] = 0.25

    def radial_error(**kw):
        r = geofair.fair(flat, faces, free, **kw)
        assert r.converged, r
        return np.abs(np.linalg.norm(r.vertices[free], axis=1) - 1.0).max()

    new = radial_error()  # boundary_normals=None: the quadric estimate
    assert new < 1e-3  # measured 7.1e-4
    assert radial_error(boundary_normals=vertices.copy()) < 5e-5  # exact normals: 2.3e-5
    # The one-sided normals of earlier releases leave the cap 4.1e-2 off the sphere.
    one_sided = geofair.boundary_normals(flat, faces, free, method="area")
    assert radial_error(boundary_normals=one_sided) > 3e-2
    # The estimate does not read the free vertices' positions (the flattened cap).
    estimate = geofair.boundary_normals(vertices, faces, free)
    np.testing.assert_array_equal(geofair.boundary_normals(flat, faces, free), estimate)


def test_estimate_is_oriented_like_the_faces_and_scale_invariant():
    s = scenes.sphere_cap(n_free=500, irregular=True, boundary_rings=3)
    normals = geofair.boundary_normals(s.vertices, s.faces, s.free)
    flipped = geofair.boundary_normals(s.vertices, s.faces[:, ::-1].copy(), s.free)
    np.testing.assert_allclose(flipped, -normals, rtol=0, atol=1e-12)
    g1 = np.linalg.norm(normals, axis=1) > 0
    assert (np.einsum("ij,ij->i", normals[g1], s.normals[g1]) > 0.999).all()
    for scale in (1e-4, 1e4):
        scaled = geofair.boundary_normals(scale * s.vertices, s.faces, s.free)
        np.testing.assert_allclose(scaled, normals, rtol=0, atol=1e-11)


def test_two_straight_rows_fall_back_to_the_area_estimate():
    # Two rings of fixed vertices on a regular cylinder: along the straight sides every
    # sample lies on two lines parallel to the axis (y and y² cannot be told apart), the fit
    # is ill-conditioned and the area estimate is taken; along the curved sides it is not.
    s = scenes.cylinder_patch(n_free=2000, boundary_rings=2)
    quadric = geofair.boundary_normals(s.vertices, s.faces, s.free)
    area = geofair.boundary_normals(s.vertices, s.faces, s.free, method="area")
    g1 = np.linalg.norm(quadric, axis=1) > 0
    same = (quadric[g1] == area[g1]).all(axis=1)
    assert 0.8 * g1.sum() < same.sum() < g1.sum()
    error = np.linalg.norm(quadric[g1] - s.normals[g1], axis=1)
    assert error.max() <= np.linalg.norm(area[g1] - s.normals[g1], axis=1).max()


def test_no_surrounding_triangle_gives_zero_rows():
    # One ring of fixed vertices: no triangle without a free vertex, so no estimate; fair()
    # then needs boundary_normals.
    s = scenes.sphere_cap(n_free=200, boundary_rings=1)
    assert not geofair.boundary_normals(s.vertices, s.faces, s.free).any()
    with pytest.raises(ValueError, match="pass boundary_normals"):
        geofair.fair(s.vertices, s.faces, s.free)
    # Given normals are not checked where there is no estimate to check them against.
    r = geofair.fair(s.vertices, s.faces, s.free, boundary_normals=-s.normals, max_iterations=1)
    assert np.isfinite(r.vertices).all()


def test_inverted_normal_is_rejected():
    s = scenes.sphere_cap(n_free=500, boundary_rings=3)
    g1 = np.flatnonzero(np.linalg.norm(geofair.boundary_normals(s.vertices, s.faces, s.free), axis=1))
    v = int(g1[len(g1) // 2])
    normals = s.normals.copy()
    normals[v] *= -1
    message = (
        f"fair: boundary_normals[{v}] points against the surface's orientation (dot product -1.00 with the "
        "normal of its surrounding triangles); flip it or the faces"
    )
    with pytest.raises(ValueError, match=re.escape(message)):
        geofair.fair(s.vertices, s.faces, s.free, boundary_normals=normals)
    # Faces flipped against exact normals: the first G1 boundary vertex is named.
    with pytest.raises(ValueError, match=r"boundary_normals\[\d+\] points against the surface's orientation"):
        geofair.fair(s.vertices, s.faces[:, ::-1].copy(), s.free, boundary_normals=s.normals)
    # A normal tilted by 80° from the surface's is the caller's choice.
    tangent = np.cross(s.normals[v], [0.0, 0.0, 1.0])
    tangent /= np.linalg.norm(tangent)
    normals[v] = np.cos(np.radians(80)) * s.normals[v] + np.sin(np.radians(80)) * tangent
    r = geofair.fair(s.vertices, s.faces, s.free, boundary_normals=normals, max_iterations=1)
    assert np.isfinite(r.vertices).all()


def test_bad_input():
    s = scenes.sphere_cap(n_free=200, boundary_rings=3)
    with pytest.raises(ValueError, match="method must be one of 'quadric', 'area', got 'cubic'"):
        geofair.boundary_normals(s.vertices, s.faces, s.free, method="cubic")
    with pytest.raises(ValueError, match="free must have shape"):
        geofair.boundary_normals(s.vertices, s.faces, s.free[:-1])
    with pytest.raises(ValueError, match="vertices must have dtype float64"):
        geofair.boundary_normals(s.vertices.astype(np.float32), s.faces, s.free)
    bad = s.faces.copy()
    bad[3, 1] = len(s.vertices)
    with pytest.raises(ValueError, match=r"boundary_normals: triangle 3 has vertex index \d+, out of range"):
        geofair.boundary_normals(s.vertices, bad, s.free)
    v = s.vertices.copy()
    outside = np.flatnonzero(~s.free & (s.boundary_distance(s.vertices) > 1e-9))
    v[outside] = np.nan
    with pytest.raises(ValueError, match="boundary_normals: the normal of G1 boundary vertex \\d+ is not finite"):
        geofair.boundary_normals(v, s.faces, s.free)
