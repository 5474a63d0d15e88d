"""CGAL's linear ``Polygon_mesh_processing::fair`` as a reference, from Python.

Runs ``build/bench/cgal_fair`` (bench/cgal_fair.cpp, built by CMake when libcgal-dev is
installed) in a subprocess, so its peak memory is its own:

    from geofair_dev.cgal_fair import cgal_fair
    result = cgal_fair(vertices, faces, free)   # result.vertices, .seconds, .peak_mib

CGAL solves Δ²x = 0 (``fairing_continuity(1)``) over the free vertices with cotangent
weights and Eigen's SparseLU; tangent continuity comes from the fixed vertices outside the
region, so give it a mesh with at least two fixed rings (``boundary_rings=2`` in
geofair_dev.scenes).
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
from dataclasses import dataclass

import numpy as np

from geofair_dev.paths import BUILD

EXECUTABLE = str(BUILD / "bench" / "cgal_fair")


@dataclass
class CgalResult:
    vertices: np.ndarray  # (#V, 3) float64, the faired positions (fixed vertices unchanged)
    seconds: float  # wall time of fair() alone (no I/O, no mesh construction)
    peak_mib: float  # peak resident set of the cgal_fair process, MiB
    success: bool  # fair()'s return value (False: the solver failed)


def available() -> bool:
    return os.access(EXECUTABLE, os.X_OK)


def cgal_fair(vertices: np.ndarray, faces: np.ndarray, free: np.ndarray) -> CgalResult:
    """Fair ``vertices[free]`` with CGAL's ``fair`` (continuity 1).

    vertices (#V, 3) float, faces (#F, 3) int (a manifold triangle mesh), free: (#V,) bool
    mask or (#free,) int indices, as ``geofair.fair`` takes it.
    Raises FileNotFoundError when the executable was not built, RuntimeError when it fails.
    """
    if not available():
        raise FileNotFoundError(f"{EXECUTABLE} is not built (is libcgal-dev installed?)")
    vertices = np.ascontiguousarray(vertices, dtype="<f8")
    faces = np.ascontiguousarray(faces, dtype="<i4")
    free = np.asarray(free)
    free = np.ascontiguousarray(np.flatnonzero(free) if free.dtype == bool else free, dtype="<i4")
    with tempfile.TemporaryDirectory(prefix="cgal_fair_") as tmp:
        src, dst = os.path.join(tmp, "in.bin"), os.path.join(tmp, "out.bin")
        with open(src, "wb") as f:
            np.array([len(vertices), len(faces), len(free)], dtype="<i4").tofile(f)
            vertices.tofile(f)
            faces.tofile(f)
            free.tofile(f)
        run = subprocess.run([EXECUTABLE, src, dst], capture_output=True, text=True)
        if run.returncode not in (0, 1) or not run.stdout.strip():
            raise RuntimeError(f"cgal_fair failed ({run.returncode}): {run.stderr.strip()}")
        report = json.loads(run.stdout.strip().splitlines()[-1])
        out = np.fromfile(dst, dtype="<f8").reshape(-1, 3)
    return CgalResult(out, report["seconds"], report["peak_mib"], report["success"])
