"""Test setup: the compiled module from build/python and the scene generators.

With GEOFAIR_TEST_INSTALLED=1 the tests run against the installed ``geofair`` (the wheel in
a virtual environment, tests/test_wheel.py) and build/python stays off sys.path.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BUILD = os.environ.get("GEOFAIR_BUILD", os.path.join(ROOT, "build"))
INSTALLED = os.environ.get("GEOFAIR_TEST_INSTALLED") == "1"
for path in (HERE,) if INSTALLED else (HERE, os.path.join(BUILD, "python")):
    if path not in sys.path:
        sys.path.insert(0, path)
