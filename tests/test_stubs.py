"""geofair's shipped stubs (native/python/stubs/geofair/__init__.pyi) are what scripts/make_stubs.py
makes from the built module (pybind11-stubgen, then the functions' types): regenerate them after
changing the bindings. mypy's stubtest checks them against the built module here and against the
installed wheel in tests/test_wheel.py; every option typed ``typing.Literal[...]`` lists exactly
the values the function takes."""

import ast
import importlib.util
import inspect
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import geofair
from geofair_dev.paths import BUILD, REPO

SHIPPED = REPO / "native" / "python" / "stubs" / "geofair" / "__init__.pyi"


def require(module, installer):
    if importlib.util.find_spec(module) is None:
        if os.environ.get("CI"):
            pytest.fail(f"{module} is not installed ({installer} installs it)")
        pytest.skip(f"{module} is not installed")


def test_stubs_are_those_of_the_built_module(tmp_path):
    require("pybind11_stubgen", "scripts/setup.sh")
    out = tmp_path / "geofair.pyi"
    env = dict(os.environ, PYTHONPATH=str(BUILD / "python"))
    subprocess.run([sys.executable, REPO / "scripts" / "make_stubs.py", out], check=True, env=env, cwd=tmp_path)
    assert out.read_text() == SHIPPED.read_text(), (
        "the stubs differ from the built module's: PYTHONPATH=build/python python3 scripts/make_stubs.py"
    )
    assert "def fair(" in SHIPPED.read_text() and "class FairingResult" in SHIPPED.read_text()


def test_stubtest_finds_the_stubs_consistent_with_the_built_module(tmp_path):
    require("mypy", "scripts/setup.sh")
    (tmp_path / "mypy.ini").write_text("[mypy]\nignore_missing_imports = True\n")  # scipy has no stubs
    env = dict(os.environ, PYTHONPATH=str(BUILD / "python"), MYPYPATH=str(SHIPPED.parents[1]))
    command = [sys.executable, "-m", "mypy.stubtest", "--mypy-config-file", "mypy.ini"]
    command += ["--allowlist", str(REPO / "tests" / "stubtest_allowlist.txt"), "geofair"]
    completed = subprocess.run(command, cwd=tmp_path, env=env, capture_output=True, text=True)
    assert completed.returncode == 0 and "Success: no issues found" in completed.stdout, completed.stdout


def stub_functions():
    """{function name: {parameter name: annotation source}} of the shipped stubs."""
    tree = ast.parse(SHIPPED.read_text())
    functions = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            arguments = [*node.args.args, *node.args.kwonlyargs]
            functions[node.name] = {a.arg: ast.unparse(a.annotation) for a in arguments}
    return functions


def literal_values(annotation):
    """The strings of ``typing.Literal[...]`` in ``annotation``, or None."""
    found = re.search(r"typing\.Literal\[(.*?)\]", annotation)
    return None if found is None else [ast.literal_eval(v.strip()) for v in found.group(1).split(",")]


def fan():
    """Valid positional arguments by name: a fan of 6 triangles around a free centre."""
    angles = np.linspace(0.0, 2.0 * np.pi, 7)[:-1]
    vertices = np.vstack([[0.0, 0.0, 0.1], np.stack([np.cos(angles), np.sin(angles), np.zeros(6)], axis=1)])
    faces = np.array([[0, 1 + i, 1 + (i + 1) % 6] for i in range(6)])
    normals = np.tile([0.0, 0.0, 1.0], (7, 1))
    return {"vertices": vertices, "faces": faces, "free": np.arange(7) == 0, "normals": normals}


def test_every_option_literal_is_what_the_function_takes():
    literals = 0
    for name, parameters in stub_functions().items():
        function = getattr(geofair, name)
        required = [p for p, q in inspect.signature(function).parameters.items() if q.default is q.empty]
        if any(p not in fan() for p in required):  # read_mesh, write_mesh: files, and no option literal
            assert not any(literal_values(a) for a in parameters.values()), name
            continue
        args = [fan()[p] for p in required]
        for option, annotation in parameters.items():
            values = literal_values(annotation)
            if values is None:
                continue
            literals += 1
            # Each value is taken (an error, if any, is not about the option) ...
            for value in values:
                kwargs = {"boundary": "g0"} if "boundary" in parameters else {}  # no normals needed
                try:
                    function(*args, **{**kwargs, option: value})
                except ValueError as error:
                    assert f"{option} must be" not in str(error), (name, option, value, error)
            # ... and the message rejecting another lists exactly these, in this order.
            with pytest.raises(ValueError, match=f"{option} must be") as error:
                function(*args, **{option: "no such value"})
            listed = str(error.value).split(f"{option} must be", 1)[1].rsplit(", got", 1)[0]
            assert re.findall(r"'([^']*)'", listed) == values, (name, option, listed)
    assert literals == 16  # fair: 6, fill_holes: 6, relax_inner_fairness: 2, mean_curvature, boundary_normals
