"""geofair's shipped stubs (native/python/stubs/geofair/__init__.pyi) are what pybind11-stubgen
makes from the built module (scripts/make_stubs.py): regenerate them after changing the bindings.
tests/test_wheel.py checks them against the installed wheel with mypy's stubtest."""

import importlib.util
import os
import subprocess
import sys

import pytest

from geofair_dev.paths import BUILD, REPO


def test_stubs_are_those_of_the_built_module(tmp_path):
    if importlib.util.find_spec("pybind11_stubgen") is None:
        if os.environ.get("CI"):
            pytest.fail("pybind11-stubgen is not installed (scripts/setup.sh installs it)")
        pytest.skip("pybind11-stubgen is not installed")
    out = tmp_path / "geofair.pyi"
    env = dict(os.environ, PYTHONPATH=str(BUILD / "python"))
    subprocess.run([sys.executable, REPO / "scripts" / "make_stubs.py", out], check=True, env=env, cwd=tmp_path)
    shipped = REPO / "native" / "python" / "stubs" / "geofair" / "__init__.pyi"
    assert out.read_text() == shipped.read_text(), (
        "the stubs differ from the built module's: PYTHONPATH=build/python python3 scripts/make_stubs.py"
    )
    assert "def fair(" in shipped.read_text() and "class FairingResult" in shipped.read_text()
