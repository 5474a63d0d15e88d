"""Accuracy of the free-vertex normal weightings on the analytic scenes.

For each scene (sphere cap, cylinder patch, catenoid patch; regular and irregular; two
resolutions) prints the max distance of the faired free vertices to the analytic surface,
relative to the patch size, for linear bilaplacian fairing and for intrinsic fairing with
the area-weighted normals of the paper, angle-weighted normals, Max's (1999) weights and
the tangent plane of the quadric fit (the default). Single level (levels=1), uniform inner
fairness.

    PYTHONPATH=build/python python3 bench/normal_weighting.py [n_free ...]
"""

import sys
import time

import numpy as np

import geofair
from geofair_dev import scenes

SCENES = {"sphere cap": scenes.sphere_cap, "cylinder": scenes.cylinder_patch, "catenoid": scenes.catenoid_patch}
WEIGHTINGS = ("area", "angle", "max", "quadric")


def error(scene, vertices):
    return np.abs(scene.distance(vertices[scene.free])).max() / scene.size


def main():
    sizes = [int(a) for a in sys.argv[1:]] or [500, 2000]
    header = f"{'scene':<11} {'mesh':<9} {'free':>5} {'bilaplacian':>11} " + " ".join(f"{w:>9}" for w in WEIGHTINGS)
    print(header + f" {'time [s]':>9}")
    for name, make in SCENES.items():
        for irregular in (False, True):
            for n in sizes:
                s = make(n_free=n, irregular=irregular, seed=1)
                v = s.disturbed(seed=2, amplitude=0.1)
                t = time.perf_counter()
                kw = dict(boundary_normals=s.normals, max_iterations=50000, levels=1)
                linear = error(s, geofair.fair(v, s.faces, s.free, outer_fairness="bilaplacian", **kw).vertices)
                errs = [
                    error(s, geofair.fair(v, s.faces, s.free, normal_weighting=w, **kw).vertices) for w in WEIGHTINGS
                ]
                mesh = "irregular" if irregular else "regular"
                cells = " ".join(f"{e:>9.1e}" for e in errs)
                print(
                    f"{name:<11} {mesh:<9} {s.n_free:>5} {linear:>11.1e} {cells} {time.perf_counter() - t:>9.1f}",
                    flush=True,
                )


if __name__ == "__main__":
    main()
