"""The CGAL reference of the benchmarks (geofair_dev.cgal_fair) measures what it claims.

CGAL's ``fair`` with continuity 1 solves the linear bilaplacian system Δ²x = 0, so it
reproduces a plane exactly and leaves the fixed vertices alone. Skipped when the
executable is not built, except in CI.
"""

import numpy as np
import pytest

from geofair_dev import cgal_fair, scenes
from geofair_dev.testing import require_built


@pytest.fixture(autouse=True)
def _needs_cgal():
    require_built(cgal_fair)


def test_plane_is_reproduced_and_fixed_vertices_are_untouched():
    s = scenes.plane_disk(n_free=500, irregular=True, seed=3, boundary_rings=2)
    v = s.disturbed(seed=4, amplitude=0.1)
    r = cgal_fair.cgal_fair(v, s.faces, s.free)
    assert r.success
    assert np.abs(r.vertices[s.free, 2]).max() < 1e-9  # back on z = 0
    assert np.array_equal(r.vertices[~s.free], v[~s.free])
    assert r.seconds > 0.0 and r.peak_mib > 0.0
