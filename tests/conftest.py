"""Test setup: the compiled module from build/python and the scene generators."""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BUILD = os.environ.get("GEOFAIR_BUILD", os.path.join(ROOT, "build"))
for path in (HERE, os.path.join(BUILD, "python")):
    if path not in sys.path:
        sys.path.insert(0, path)
