"""geofair.defaults(): the one source of fair's option defaults (FairingOptions in types.h)."""

import re

import numpy as np

import geofair
import scenes


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
