"""UV conformal distortion (the add-on's bpy-free metrics module) against values computed by hand."""

import importlib.util
import pathlib

import numpy as np
import pytest

_METRICS_PY = pathlib.Path(__file__).resolve().parents[1] / "addon" / "geometric_fairing" / "metrics.py"
_spec = importlib.util.spec_from_file_location("geofair_metrics", _METRICS_PY)
metrics = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(metrics)

RIGHT_UV = np.array([[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]])  # the unit right triangle in UV
TRIANGLE = np.array([[0, 1, 2]])


def distortion(points, uv=RIGHT_UV):
    """σ1/σ2 of the one triangle with 3D corners ``points`` and UV corners ``uv``."""
    return metrics.uv_conformal_distortion(np.asarray(points, dtype=float), TRIANGLE, uv)[0]


def test_identity_is_conformal():
    assert distortion([[0, 0, 0], [1, 0, 0], [0, 1, 0]]) == pytest.approx(1.0, abs=1e-15)


def test_right_triangle_stretched_along_u():
    # J = diag(2, 1): σ1 = 2, σ2 = 1.
    assert distortion([[0, 0, 0], [2, 0, 0], [0, 1, 0]]) == pytest.approx(2.0, rel=1e-15)
    # Stretched by 3 along v instead, and lying in the x = 0 plane: J maps u to +z, v to 3·y.
    assert distortion([[0, 0, 0], [0, 0, 1], [0, 3, 0]]) == pytest.approx(3.0, rel=1e-15)


@pytest.mark.parametrize("angle", [0.3, 1.0, 2.5, -0.7])
@pytest.mark.parametrize("scale", [1.0, 0.01, 250.0])
def test_rotation_and_uniform_scale_are_conformal(angle, scale):
    # The right triangle rotated in a tilted plane and scaled: a similarity, distortion 1.
    c, s = np.cos(angle), np.sin(angle)
    plane = np.array([[1, 0, 0], [0, np.cos(0.4), np.sin(0.4)]])  # orthonormal rows
    corners = scale * (RIGHT_UV[0] @ np.array([[c, s], [-s, c]])) @ plane + [5, -2, 1]
    assert distortion(corners) == pytest.approx(1.0, abs=1e-12)


def test_mirror_is_conformal():
    # A UV map that flips the triangle keeps angles: σ1/σ2 = 1 (orientation is not measured).
    assert distortion([[0, 0, 0], [0, 1, 0], [1, 0, 0]]) == pytest.approx(1.0, abs=1e-15)


def test_shear():
    # J = [[1, 1], [0, 1]]: JᵀJ = [[1, 1], [1, 2]], eigenvalues (3 ± √5)/2, so
    # σ1/σ2 = sqrt((3 + √5)/(3 - √5)) = (3 + √5)/2 = 2.618..., the golden ratio squared.
    assert distortion([[0, 0, 0], [1, 0, 0], [1, 1, 0]]) == pytest.approx((3 + np.sqrt(5)) / 2, rel=1e-14)


def test_equilateral_uv_on_right_isosceles_triangle():
    # UV: equilateral (1, 0), (1/2, √3/2); 3D: the unit right triangle. J = E U⁻¹ with
    # U = [[1, 1/2], [0, √3/2]], E = I: U⁻¹ = [[1, -1/√3], [0, 2/√3]], JᵀJ = [[1, -1/√3], [-1/√3, 5/3]],
    # trace 8/3, det 4/3: λ = (8/3 ± √(64/9 - 16/3))/2 = (4 ± √4)/3 → 2 and 2/3, σ1/σ2 = √3.
    uv = np.array([[[0.0, 0.0], [1.0, 0.0], [0.5, np.sqrt(3) / 2]]])
    assert distortion([[0, 0, 0], [1, 0, 0], [0, 1, 0]], uv) == pytest.approx(np.sqrt(3), rel=1e-14)


def test_inverse_map_has_the_same_ratio():
    rng = np.random.default_rng(3)
    for _ in range(20):
        flat = rng.normal(size=(3, 2))
        uv = rng.normal(size=(1, 3, 2))
        forward = distortion(np.c_[flat, np.zeros(3)], uv)
        backward = distortion(np.c_[uv[0], np.zeros(3)], flat[None])
        assert forward == pytest.approx(backward, rel=1e-9)
        # And it equals σ1/σ2 from numpy's SVD of J = E U⁻¹.
        e = np.stack([flat[1] - flat[0], flat[2] - flat[0]], axis=1)
        u = np.stack([uv[0, 1] - uv[0, 0], uv[0, 2] - uv[0, 0]], axis=1)
        sigma = np.linalg.svd(e @ np.linalg.inv(u), compute_uv=False)
        assert forward == pytest.approx(sigma[0] / sigma[1], rel=1e-9)


def test_degenerate_triangles_are_infinite():
    collapsed_uv = np.array([[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]])
    assert distortion([[0, 0, 0], [1, 0, 0], [0, 1, 0]], collapsed_uv) == np.inf
    assert distortion([[0, 0, 0], [1, 0, 0], [2, 0, 0]]) == np.inf  # a 3D triangle on a line


def test_summary_mean_and_max():
    # Three triangles with distortion 1, 2 and 3: mean 2, max 3.
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0], [0, 3, 0]], dtype=float)
    triangles = np.array([[0, 1, 2], [0, 3, 2], [0, 1, 4]])
    uv = np.repeat(RIGHT_UV, 3, axis=0)
    per_triangle = metrics.uv_conformal_distortion(vertices, triangles, uv)
    np.testing.assert_allclose(per_triangle, [1.0, 2.0, 3.0], rtol=1e-15)
    summary = metrics.uv_distortion(vertices, triangles, uv)
    assert summary == metrics.Distortion(mean=pytest.approx(2.0), max=pytest.approx(3.0), triangles=3)
    empty = metrics.summarize([])
    assert empty.triangles == 0 and np.isnan(empty.mean)


def test_mismatched_uvs_are_rejected():
    with pytest.raises(ValueError, match="2 triangles but UVs for 1"):
        metrics.uv_conformal_distortion(np.eye(3), [[0, 1, 2], [0, 2, 1]], RIGHT_UV)
