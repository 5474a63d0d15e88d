"""CGAL's hole filling, ``Polygon_mesh_processing::triangulate_refine_and_fair_hole``, from Python.

Runs ``build/bench/cgal_fill_hole`` (bench/cgal_fill_hole.cpp, built by CMake when
libcgal-dev is installed) in a subprocess, so its peak memory is its own:

    from geofair_dev.cgal_fill_hole import cgal_fill_hole
    result = cgal_fill_hole(vertices, faces, loop)   # result.vertices, .faces, .seconds, ...

CGAL triangulates the hole, refines the triangulation (Liepa's refinement, the edge lengths
interpolated from the boundary's) and fairs the new vertices with ``fair()`` (continuity 1:
the linear bilaplacian Δ²x = 0, cotangent weights, tangent continuity through the fixed
ring around the hole). The input's vertices and faces come back first and unchanged, the
new ones after, as ``geofair.fill_holes`` returns them.
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
from dataclasses import dataclass

import numpy as np

from geofair_dev.paths import BUILD

EXECUTABLE = str(BUILD / "bench" / "cgal_fill_hole")


@dataclass
class CgalFillResult:
    vertices: np.ndarray  # (n + k, 3) float64: the input's n rows, then the k new vertices
    faces: np.ndarray  # (m + l, 3) int64: the input's m faces, then the l new ones
    seconds: float  # wall time of triangulate_refine_and_fair_hole() alone (no I/O)
    phase_seconds: dict  # {"triangulate", "refine", "fair"}: its phases, seconds
    peak_mib: float  # peak resident set of the cgal_fill_hole process, MiB
    success: bool  # fair()'s return value (False: the linear solve failed)
    new_vertices: int  # k
    new_faces: int  # l


def available() -> bool:
    return os.access(EXECUTABLE, os.X_OK)


def cgal_fill_hole(vertices: np.ndarray, faces: np.ndarray, loop, timeout: float | None = None) -> CgalFillResult:
    """Fill the hole bounded by ``loop`` with CGAL's ``triangulate_refine_and_fair_hole``.

    vertices (n, 3) float, faces (m, 3) int (a manifold triangle mesh), loop: the vertex
    indices of one of its boundary loops in order (any start, either direction).
    Raises FileNotFoundError when the executable was not built, RuntimeError when it fails
    (bad input, not a boundary loop), subprocess.TimeoutExpired after ``timeout`` seconds.
    """
    if not available():
        raise FileNotFoundError(f"{EXECUTABLE} is not built (is libcgal-dev installed?)")
    vertices = np.ascontiguousarray(vertices, dtype="<f8")
    faces = np.ascontiguousarray(faces, dtype="<i4")
    loop = np.ascontiguousarray(loop, dtype="<i4")
    with tempfile.TemporaryDirectory(prefix="cgal_fill_hole_") as tmp:
        src, dst = os.path.join(tmp, "in.bin"), os.path.join(tmp, "out.bin")
        with open(src, "wb") as f:
            np.array([len(vertices), len(faces), len(loop)], dtype="<i4").tofile(f)
            vertices.tofile(f)
            faces.tofile(f)
            loop.tofile(f)
        run = subprocess.run([EXECUTABLE, src, dst], capture_output=True, text=True, timeout=timeout)
        if run.returncode not in (0, 1) or not run.stdout.strip():
            raise RuntimeError(f"cgal_fill_hole failed ({run.returncode}): {run.stderr.strip()}")
        report = json.loads(run.stdout.strip().splitlines()[-1])
        with open(dst, "rb") as f:
            nv, nf = np.fromfile(f, dtype="<i4", count=2)
            v = np.fromfile(f, dtype="<f8", count=3 * nv).reshape(-1, 3)
            fa = np.fromfile(f, dtype="<i4", count=3 * nf).reshape(-1, 3).astype(np.int64)
    phases = {k: report[f"{k}_seconds"] for k in ("triangulate", "refine", "fair")}
    return CgalFillResult(v, fa, report["seconds"], phases, report["peak_mib"], report["success"],
                          report["new_vertices"], report["new_faces"])  # fmt: skip
