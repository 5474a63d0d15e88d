"""The add-on's options are geofair.fair's: its names, and as enum identifiers every value it takes.

Read from addon/geometric_fairing/properties.py without bpy (its literal tuples); the
in-Blender side (the operator, the panel, fair_object) is tests/blender/check_operator.py
and check_scripting.py.
"""

import ast
import inspect
import pathlib
import re
import types

import numpy as np
import pytest

import geofair

PROPERTIES_PY = pathlib.Path(__file__).resolve().parents[1] / "addon" / "geometric_fairing" / "properties.py"


def literal(name):
    """The value of the module-level assignment ``name = <literal>`` in properties.py."""
    for node in ast.parse(PROPERTIES_PY.read_text()).body:
        if isinstance(node, ast.Assign) and [getattr(t, "id", None) for t in node.targets] == [name]:
            return ast.literal_eval(node.value)
    raise LookupError(name)


def definitions(*names):
    """The module-level assignments and functions ``names`` of properties.py, run without bpy."""
    nodes = [
        node
        for node in ast.parse(PROPERTIES_PY.read_text()).body
        if (isinstance(node, ast.FunctionDef) and node.name in names)
        or (isinstance(node, ast.Assign) and [getattr(t, "id", None) for t in node.targets][0] in names)
    ]
    namespace = {}
    exec(compile(ast.Module(body=nodes, type_ignores=[]), str(PROPERTIES_PY), "exec"), namespace)  # noqa: S102
    return types.SimpleNamespace(**{name: namespace[name] for name in names})


def accepted_values(option):
    """The values geofair.fair takes for ``option``, from the message with which it rejects another."""
    vertices = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    with pytest.raises(ValueError, match=f"{option} must be one of") as error:
        geofair.fair(vertices, np.array([[0, 1, 2]]), np.zeros(3, dtype=bool), **{option: "no such value"})
    return re.findall(r"'([a-z0-9_]+)'", str(error.value).split(", got")[0])


@pytest.mark.parametrize(
    ("option", "items"),
    [
        ("inner_fairness", "INNER_FAIRNESS_ITEMS"),
        ("outer_fairness", "OUTER_FAIRNESS_ITEMS"),
        ("boundary", "BOUNDARY_ITEMS"),
        ("iteration", "ITERATION_ITEMS"),
    ],
)
def test_enum_identifiers_are_every_value_the_library_takes(option, items):
    # In the library's order: a .blend file stores an enum by its item's number, so items are only appended.
    assert [identifier for identifier, _, _ in literal(items)] == accepted_values(option)


def fair_keywords():
    parameters = inspect.signature(geofair.fair).parameters.values()
    return [p.name for p in parameters if p.kind is inspect.Parameter.KEYWORD_ONLY]


def test_option_names_are_the_librarys():
    names = literal("LIBRARY_OPTION_NAMES")
    assert set(names) <= set(fair_keywords()), set(names) - set(fair_keywords())
    assert set(names) <= set(geofair.defaults()), set(names) - set(geofair.defaults())
    assert "time_limit" in names and geofair.defaults()["time_limit"] is None  # the property's 0


def test_fair_object_takes_every_keyword_of_fair():
    # The panel's options, remesh (mapped), the options only scripts give, and the arguments
    # fair_object takes per element of the object (boundary_normals, polygon_ids) or itself (progress).
    names = [
        *literal("LIBRARY_OPTION_NAMES"),
        "remesh",
        *literal("SCRIPT_OPTION_NAMES"),
        *literal("MESH_ARGUMENT_NAMES"),
    ]
    assert sorted(names) == sorted(fair_keywords())


def test_time_limit_zero_is_automatic_in_the_library_and_the_addon():
    # The Time Limit property holds 0 for automatic; the library takes 0 as None, the automatic limit.
    mapping = definitions("LIBRARY_OPTION_NAMES", "OPTION_NAMES", "property_value", "option_values")
    assert mapping.property_value("time_limit", None) == 0.0
    assert mapping.property_value("time_limit", 2.5) == 2.5
    panel = types.SimpleNamespace(**dict(dict.fromkeys(mapping.OPTION_NAMES, "x"), time_limit=0.0))
    assert mapping.option_values(panel)["time_limit"] is None
    panel.time_limit = 2.5
    assert mapping.option_values(panel)["time_limit"] == 2.5
    angles = np.linspace(0.0, 2.0 * np.pi, 7)[:-1]
    vertices = np.vstack([[0.0, 0.0, 0.3], np.stack([np.cos(angles), np.sin(angles), np.zeros(6)], axis=1)])
    faces = np.array([[0, 1 + i, 1 + (i + 1) % 6] for i in range(6)])
    free = np.arange(7) == 0
    automatic = geofair.fair(vertices, faces, free, boundary="g0")
    for value in (0, 0.0, mapping.property_value("time_limit", None)):
        result = geofair.fair(vertices, faces, free, boundary="g0", time_limit=value)
        assert result.converged and result.stop_reason == "converged"
        assert np.array_equal(result.vertices, automatic.vertices)


def test_remesh_items_are_off_if_needed_always():
    assert [identifier for identifier, _, _ in literal("REMESH_ITEMS")] == ["off", "if_needed", "always"]
    assert literal("REMESH_VALUES") == {"off": False, "if_needed": "if_needed", "always": True}


def test_remesh_values_are_taken_by_the_library():
    # A fan of 6 triangles around a free centre: every Remesh value solves.
    angles = np.linspace(0.0, 2.0 * np.pi, 7)[:-1]
    vertices = np.vstack([[0.0, 0.0, 0.1], np.stack([np.cos(angles), np.sin(angles), np.zeros(6)], axis=1)])
    faces = np.array([[0, 1 + i, 1 + (i + 1) % 6] for i in range(6)])
    free = np.zeros(7, dtype=bool)
    free[0] = True
    for value in literal("REMESH_VALUES").values():
        result = geofair.fair(vertices, faces, free, boundary="g0", remesh=value)
        assert result.faces.shape[1] == 3 and len(result.free) == len(result.vertices)


def test_live_fair_drag_options_are_live_fairings():
    # Live Fair Drag passes the panel's library options to geofair.LiveFairing, and Keep Details as
    # its details; not Remesh: LiveFairing's remesh="if_needed" changes triangles, and the add-on's
    # drag changes positions only (the library's default, off).
    mapping = definitions("LIBRARY_OPTION_NAMES", "LIVE_OPTION_NAMES")
    keywords = inspect.signature(geofair.LiveFairing).parameters
    assert set(mapping.LIBRARY_OPTION_NAMES) <= set(keywords) and "details" in keywords
    assert keywords["remesh"].default is False and "remesh" not in mapping.LIVE_OPTION_NAMES
    assert set(mapping.LIVE_OPTION_NAMES) - set(mapping.LIBRARY_OPTION_NAMES) == {
        "region_group",
        "pin_group",
        "use_hidden",
    }
