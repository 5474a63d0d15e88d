"""geofair.defaults(): the one source of fair's option defaults (FairingOptions in types.h)."""

import inspect

import numpy as np
import pytest

import geofair
from geofair_dev import scenes


def keyword_defaults(function):
    """The keyword-only parameters of ``function`` and their defaults, from inspect.signature."""
    parameters = inspect.signature(function).parameters.values()
    return {p.name: p.default for p in parameters if p.kind is inspect.Parameter.KEYWORD_ONLY}


def test_defaults_are_exactly_fairs_keyword_arguments():
    # The same names in the same order, the same values; tuning=None means the tuning spelled out.
    defaults = geofair.defaults()
    signature = keyword_defaults(geofair.fair)
    assert list(defaults) == list(signature)
    assert signature.pop("tuning") is None and isinstance(defaults.pop("tuning"), dict)
    for name, value in signature.items():
        assert defaults[name] == value and type(defaults[name]) is type(value), name
    positional = [p.name for p in inspect.signature(geofair.fair).parameters.values() if p.default is p.empty]
    assert positional == ["vertices", "faces", "free"]


def test_default_call_converges():
    # fair(V, F, free, **geofair.defaults()) is fair's default call: a sphere cap with fixed rings
    # around (its G1 normals estimated from them) converges, to the same bits as fair(V, F, free).
    scene = scenes.sphere_cap(n_free=150, irregular=True, seed=13, boundary_rings=3)
    args = (scene.vertices, scene.faces, scene.free)
    result = geofair.fair(*args, **geofair.defaults())
    assert result.converged and result.stop_reason == "converged", result.message
    assert np.array_equal(result.vertices, geofair.fair(*args).vertices)
    assert np.array_equal(result.vertices[~scene.free], scene.vertices[~scene.free])


def test_docstring_states_the_automatic_time_limit():
    tuning = geofair.defaults()["tuning"]
    text = " ".join(geofair.fair.__doc__.split())
    base, per_vertex = tuning["schedule.time_limit_base"], tuning["schedule.time_limit_per_free_vertex"]
    assert f"{base:g} s plus {per_vertex * 1e3:g} ms per free vertex" in text


def test_defaults_are_a_fresh_dict():
    first = geofair.defaults()
    first["tolerance"] = 1.0
    assert geofair.defaults()["tolerance"] != 1.0


def test_defaults_fair_a_mesh():
    """Every default is accepted by fair itself (as keyword arguments)."""
    scene = scenes.sphere_cap(n_free=300, irregular=True, seed=13)
    options = dict(geofair.defaults(), boundary_normals=scene.normals)
    result = geofair.fair(scene.vertices, scene.faces, scene.free, **options)
    assert result.converged
    assert np.array_equal(result.vertices[~scene.free], scene.vertices[~scene.free])


def test_docstring_figures_are_filled_in():
    # fair's docstring takes its figures from the library's constants: no placeholder is left.
    assert "{" not in geofair.fair.__doc__ and "}" not in geofair.fair.__doc__


def test_tuning_defaults_name_every_field_once():
    tuning = geofair.defaults()["tuning"]
    assert len(tuning) == 63
    assert tuning["newton.patience"] == 20 and isinstance(tuning["newton.patience"], int)
    assert not any(name.startswith("time_limit_") for name in geofair.defaults())  # only in the tuning
    assert {name.split(".")[0] for name in tuning} == {
        "paper", "newton", "tangential", "multigrid", "hierarchy", "bilaplacian", "schedule"
    }  # fmt: skip


def test_tuning_override_reaches_the_solver():
    # An automatic time limit of 0 s stops the solve at once, unconverged.
    scene = scenes.sphere_cap(n_free=300, irregular=True, seed=13)
    args = (scene.vertices, scene.faces, scene.free)
    zero = {"schedule.time_limit_base": 0.0, "schedule.time_limit_per_free_vertex": 0}
    result = geofair.fair(*args, boundary_normals=scene.normals, tuning=zero)
    assert not result.converged and "time limit of 0.0e+00 s" in result.message
    assert geofair.fair(*args, boundary_normals=scene.normals, tuning={}).converged
    numpy_values = {"newton.patience": np.int64(20), "newton.max_step": np.float64(4.0)}
    assert geofair.fair(*args, boundary_normals=scene.normals, tuning=numpy_values).converged


def test_tuning_errors_name_the_field():
    scene = scenes.sphere_cap(n_free=300, irregular=True, seed=13)
    args = (scene.vertices, scene.faces, scene.free)
    cases = [
        ({"newton.patiense": 3}, 'unknown tuning field "newton.patiense"'),
        ({"newton.patience": 2.5}, 'tuning["newton.patience"] must be an int'),
        ({"newton.patience": 10**30}, 'tuning["newton.patience"] must be an int'),
        ({"newton.max_step": "x"}, 'tuning["newton.max_step"] must be a number'),
        ({"newton.patience": 0}, "tuning.newton.patience must be in [1, inf), got 0"),
        ({"tangential.max_stretch": 1.0}, "tuning.tangential.max_stretch must be in (0, 1), got 1"),
        # A range bounded by another field: the tightest GMRES tolerance by the ordinary one.
        (
            {"newton.krylov_tolerance_min": 2e-3},
            "krylov_tolerance_min must be in (0, 0.001] (bounded by newton.krylov_tolerance), got 0.002",
        ),
        ([("newton.patience", 3)], "tuning must be a dict or None, got list"),
    ]
    for tuning, message in cases:
        with pytest.raises(ValueError) as error:
            geofair.fair(*args, boundary_normals=scene.normals, tuning=tuning)
        assert message in str(error.value)
    raised = {"newton.krylov_tolerance": 1e-2, "newton.krylov_tolerance_min": 2e-3}
    assert geofair.fair(*args, boundary_normals=scene.normals, tuning=raised).converged
    equal = {"newton.krylov_tolerance_min": 1e-3}  # the closed upper end: the rule off
    assert geofair.fair(*args, boundary_normals=scene.normals, tuning=equal).converged
