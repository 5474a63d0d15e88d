"""Where things are in the repository, and the one place that puts folders on ``sys.path``.

- ``REPO``: the repository; ``BUILD``: the CMake build whose products the tests, benchmarks
  and scripts use, ``$GEOFAIR_BUILD`` or ``<repo>/build`` (``build-portable`` for the
  portable build: scripts/run_tests.sh); ``MODULE_FOLDER``: its ``geofair`` module
  (``BUILD/python``); ``BUILT_ADDON``: its add-on folder (``BUILD/addon``, holding
  ``geometric_fairing/`` with the compiled module); ``ADDON_SOURCE``: the add-on's sources.
- ``use_build_module()``: ``import geofair`` finds ``BUILD/python`` first (tests/conftest.py,
  scripts/results.py), unless ``GEOFAIR_TEST_INSTALLED=1`` asks for the installed wheel.
- ``import_addon(folder)``: the ``geometric_fairing`` package from a folder that holds it.
- ``source_module(path)``: a single file of the sources (an add-on module without bpy, a
  script) imported by its path, without putting its folder on ``sys.path``.
- ``subprocess_env()``: the environment for a Python or Blender started from here, in which
  ``geofair_dev`` imports (``PYTHONPATH`` holds ``dev/``).

How ``geofair_dev`` itself becomes importable: ``python3 -m pip install -e dev/``
(scripts/setup.sh) for ``python3``, and for Debian's Blender 3.4 (which runs
``/usr/bin/python3``'s environment) a ``.pth`` file that scripts/setup.sh writes there;
pytest.ini's ``pythonpath = dev`` for pytest; ``subprocess_env()`` for what the tests start.
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import pathlib
import sys

REPO = pathlib.Path(__file__).resolve().parents[2]
DEV = REPO / "dev"
BUILD = pathlib.Path(os.environ.get("GEOFAIR_BUILD") or REPO / "build").resolve()
MODULE_FOLDER = BUILD / "python"
BUILT_ADDON = BUILD / "addon"
ADDON_SOURCE = REPO / "addon" / "geometric_fairing"


def prepend(folder):
    """Put ``folder`` first on ``sys.path`` (once): every other helper goes through here."""
    folder = str(pathlib.Path(folder).resolve())
    if folder in sys.path:
        sys.path.remove(folder)
    sys.path.insert(0, folder)


def use_build_module():
    """``import geofair`` loads ``BUILD/python``'s module; with ``GEOFAIR_TEST_INSTALLED=1``
    (tests/test_wheel.py) the installed one, and ``BUILD/python`` stays off ``sys.path``."""
    if os.environ.get("GEOFAIR_TEST_INSTALLED") != "1":
        prepend(MODULE_FOLDER)


def import_addon(folder):
    """The ``geometric_fairing`` package from ``folder`` (e.g. build/addon), imported, not registered."""
    folder = pathlib.Path(folder).resolve()
    if not (folder / "geometric_fairing" / "__init__.py").is_file():
        raise FileNotFoundError(f"no geometric_fairing add-on in {folder}")
    prepend(folder)
    return importlib.import_module("geometric_fairing")


def source_module(path, name=None):
    """The module of one Python file (e.g. ``ADDON_SOURCE / "metrics.py"``), imported by its path."""
    path = pathlib.Path(path)
    spec = importlib.util.spec_from_file_location(name or path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def subprocess_env(**extra):
    """``os.environ`` with ``dev/`` first on ``PYTHONPATH`` (and ``extra``): a Python, the bpy
    module or Debian's Blender started with it imports ``geofair_dev``."""
    path = os.environ.get("PYTHONPATH")
    return dict(os.environ, PYTHONPATH=os.pathsep.join([str(DEV), *([path] if path else [])]), **extra)
