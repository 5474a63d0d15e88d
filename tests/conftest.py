"""Test setup: ``import geofair`` loads the compiled module of ``$GEOFAIR_BUILD`` (default
build/python), through geofair_dev.paths; the scenes, measures and corpus come from the
development package geofair_dev (dev/, on sys.path by pytest.ini's ``pythonpath``).

With GEOFAIR_TEST_INSTALLED=1 the tests run against the installed ``geofair`` (the wheel in
a virtual environment, tests/test_wheel.py) and build/python stays off sys.path.
"""

import pytest

from geofair_dev import cgal_fill_hole, paths
from geofair_dev.testing import require_built

paths.use_build_module()


@pytest.fixture
def needs_cgal():
    """Skips a test that needs bench/cgal_fill_hole where it is not built; fails it in CI."""
    require_built(cgal_fill_hole)


# The files that take minutes go first: pytest-xdist gives each worker one file at a time
# (scripts/run_tests.sh), and one of these started last would end the run on one core.
LONG_FILES = ("test_wheel.py", "test_flattened_caps.py", "test_blender.py")


def pytest_collection_modifyitems(config, items):
    rank = {name: k for k, name in enumerate(LONG_FILES)}
    items.sort(key=lambda item: rank.get(item.path.name, len(LONG_FILES)))
