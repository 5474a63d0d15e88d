"""One version, pyproject.toml's: the module, the built add-on's bl_info and blender_manifest.toml."""

import ast
import os
import tomllib

import pytest

import geofair
from geofair_dev.paths import BUILD, REPO

VERSION = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]


def test_the_module_has_pyprojects_version():
    assert geofair.__version__ == VERSION


def test_the_built_addon_has_pyprojects_version():
    addon = BUILD / "addon" / "geometric_fairing"
    if not (addon / "blender_manifest.toml").is_file():
        if os.environ.get("CI"):
            pytest.fail(f"no built add-on in {addon}")
        pytest.skip(f"no built add-on in {addon}")
    assert tomllib.loads((addon / "blender_manifest.toml").read_text())["version"] == VERSION
    # Blender 3.4 reads bl_info without running the file, as a literal: so does this test.
    tree = ast.parse((addon / "__init__.py").read_text())
    (bl_info,) = [n.value for n in tree.body if isinstance(n, ast.Assign) and n.targets[0].id == "bl_info"]
    assert ast.literal_eval(bl_info)["version"] == tuple(int(x) for x in VERSION.split(".")[:3])
