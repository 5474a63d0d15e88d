"""Test setup: ``import geofair`` loads the compiled module of ``$GEOFAIR_BUILD`` (default
build/python), through geofair_dev.paths; the scenes, measures and corpus come from the
development package geofair_dev (dev/, on sys.path by pytest.ini's ``pythonpath``).

With GEOFAIR_TEST_INSTALLED=1 the tests run against the installed ``geofair`` (the wheel in
a virtual environment, tests/test_wheel.py) and build/python stays off sys.path.
"""

from geofair_dev import paths

paths.use_build_module()
