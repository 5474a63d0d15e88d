"""What the tests share beside their fixtures (tests/conftest.py holds those).

- ``unavailable(reason)``: a test whose tool is missing (Blender, a bpy venv, a wheel, a
  reference executable) is skipped locally but fails where the environment variable CI is
  set, so that CI cannot pass by skipping.
- ``require_built(tool)``: ``unavailable`` unless a reference executable of build/bench
  (geofair_dev.cgal_fair, geofair_dev.cgal_fill_hole) is built.
"""

import os

import pytest


def unavailable(reason):
    """Skips the calling test, or fails it where CI is set (it never returns)."""
    if os.environ.get("CI"):
        pytest.fail(f"{reason} (CI is set, so this is not skipped)")
    pytest.skip(reason)


def require_built(tool):
    """``unavailable`` unless ``tool.available()``: a module with ``available()`` and
    ``EXECUTABLE``, such as geofair_dev.cgal_fair."""
    if not tool.available():
        unavailable(f"{tool.EXECUTABLE} is not built")
