"""Uniform inner fairness on a quad mesh, split into triangles four ways: with and without
geofair.fair's polygon_ids (the polygon each triangle came from).

Mesh: Blender's UV sphere (geofair_dev.scenes.uv_sphere: 64 segments, 32 rings, radius 1),
its quads split along a–c, along b–d, in a checkerboard, or at random (seed 0), as
geofair_dev.polygons builds them (also for tests/test_polygons.py); the cap above z = 0.25 flattened onto that plane and
faired with the defaults (uniform inner fairness, the library's boundary normals). Per
split and umbrella: converged, the max distance of the free vertices from the unit sphere,
the max distance of each free vertex from where the a–c split puts it (with the same
umbrella), time.

    PYTHONPATH=build/python python3 bench/quad_splits.py [--inner conformal]

--inner conformal: the same with conformal inner fairness (which does not read the
polygons: both umbrella rows are the same solve).
"""

import argparse
import time

import numpy as np

from geofair_dev.polygons import fair_flattened_cap, splits


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--inner", default="uniform", choices=("uniform", "conformal"))
    inner = parser.parse_args().inner
    print(f"# inner fairness {inner}")
    print(f"{'split':14s} {'umbrella':9s} {'converged':9s} {'radial':>8s} {'vs a-c':>8s} {'time [s]':>8s}")
    for polygons in (False, True):
        reference = None
        for name, split in splits().items():
            t = time.perf_counter()
            r, free = fair_flattened_cap(split, polygons, inner)
            seconds = time.perf_counter() - t
            x = r.vertices[free]
            radial = np.abs(np.linalg.norm(x, axis=1) - 1.0).max()
            moved = "" if reference is None else f"{np.linalg.norm(x - reference, axis=1).max():.1e}"
            reference = x if reference is None else reference
            umbrella = "polygons" if polygons else "triangles"
            print(f"{name:14s} {umbrella:9s} {r.converged!s:9s} {radial:8.1e} {moved:>8s} {seconds:8.2f}", flush=True)


if __name__ == "__main__":
    main()
