"""geofair.defaults(): the one source of fair's option defaults (FairingOptions in types.h)."""

import re

import numpy as np
import pytest

import geofair
from geofair_dev import scenes


def signature_defaults():
    """The defaults in fair's signature line, as Python values."""
    line = geofair.fair.__doc__.splitlines()[0]
    return {m[0]: eval(m[1]) for m in re.findall(r"(\w+): [^=,]+ = ('[^']*'|[-+.\deE]+|None)", line)}  # noqa: S307


def test_signature_uses_the_library_defaults():
    defaults = geofair.defaults()
    signature = signature_defaults()
    for name in (
        "inner_fairness",
        "outer_fairness",
        "normal_weighting",
        "tolerance",
        "max_iterations",
        "damping",
        "cg_iterations",
        "levels",
        "iteration",
        "boundary",
        "time_limit",
    ):
        assert signature[name] == defaults[name], name


def test_docstring_states_the_automatic_time_limit():
    d = geofair.defaults()
    text = " ".join(geofair.fair.__doc__.split())
    assert f"{d['time_limit_base']:g} s plus {d['time_limit_per_free_vertex'] * 1e3:g} ms per free vertex" in text


def test_defaults_are_a_fresh_dict():
    first = geofair.defaults()
    first["tolerance"] = 1.0
    assert geofair.defaults()["tolerance"] != 1.0


def test_defaults_fair_a_mesh():
    """Every default is accepted by fair itself (as keyword arguments)."""
    scene = scenes.sphere_cap(n_free=300, irregular=True, seed=13)
    options = {k: v for k, v in geofair.defaults().items() if not k.startswith("time_limit_")}
    result = geofair.fair(scene.vertices, scene.faces, scene.free, boundary_normals=scene.normals, **options)
    assert result.converged
    assert np.array_equal(result.vertices[~scene.free], scene.vertices[~scene.free])


def test_docstring_figures_are_filled_in():
    # fair's docstring takes its figures from the library's constants: no placeholder is left.
    assert "{" not in geofair.fair.__doc__ and "}" not in geofair.fair.__doc__


def test_tuning_defaults_name_every_field_once():
    tuning = geofair.defaults()["tuning"]
    assert len(tuning) == 55
    assert tuning["newton.patience"] == 20 and isinstance(tuning["newton.patience"], int)
    assert tuning["schedule.time_limit_base"] == geofair.defaults()["time_limit_base"]
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
        ([("newton.patience", 3)], "tuning must be a dict or None, got list"),
    ]
    for tuning, message in cases:
        with pytest.raises(ValueError) as error:
            geofair.fair(*args, boundary_normals=scene.normals, tuning=tuning)
        assert message in str(error.value)
