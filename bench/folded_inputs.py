"""Fairing from disturbed and folded inputs: a sphere cap and a planar disc whose free vertices
were moved before fairing (noise along the normals, scrambled within the surface, crumpled,
flattened, a spike, collapsed towards the centre), faired by geofair.fair with the library's
boundary normals and each inner fairness.

Prints per input and inner fairness: the input's folded edges (against the undisturbed mesh),
converged, the result's folded edges (``FairingResult.folds``) and those not in the input
(``new_folds``), the largest distance of a free vertex from the surface, the time.

Usage: PYTHONPATH=build/python python3 bench/folded_inputs.py [--free N] [--inner uniform,conformal]
"""

import argparse
import time

import numpy as np

import geofair
from geofair_dev import scenes
from geofair_dev.corpus import new_folds


def disturbed(scene, rng):
    """(name, positions) of the disturbed inputs of ``scene``, at the scale of its median edge h."""
    v, faces = scene.vertices, scene.faces
    free = np.flatnonzero(scene.free)
    n = scene.normals[free]
    h = np.median(np.linalg.norm(v[faces[:, 0]] - v[faces[:, 1]], axis=1))

    def moved(offsets):
        w = v.copy()
        w[free] += offsets
        return w

    tangential = rng.normal(size=(len(free), 3))
    tangential -= (tangential * n).sum(axis=1)[:, None] * n
    flattened = v.copy()
    flattened[free, 2] = v[free, 2].min()
    spike = v.copy()
    top = free[np.argmax(v[free, 2])]
    spike[top] += 10 * h * scene.normals[top]
    return [
        ("normal noise 0.5h", moved(rng.uniform(-0.5, 0.5, len(free))[:, None] * h * n)),
        ("normal noise 2h", moved(rng.uniform(-2, 2, len(free))[:, None] * h * n)),
        ("scrambled in the surface 0.8h", moved(0.8 * h * tangential)),
        ("crumpled 1.5h", moved(1.5 * h * rng.normal(size=(len(free), 3)))),
        ("flattened", flattened),
        ("spike 10h", spike),
        ("collapsed towards the centre", moved(-0.8 * v[free])),
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--free", type=int, default=1000, help="free vertices of each scene")
    parser.add_argument("--inner", default="uniform,conformal,conformal_intrinsic")
    args = parser.parse_args()
    inners = args.inner.split(",")
    print("| scene | input | input folds | inner fairness | converged | folds | new | distance | time |")
    print("|---|---|---:|---|---|---:|---:|---:|---:|")
    for name, irregular, make, distance in [
        ("sphere cap, regular", False, scenes.sphere_cap, lambda p: np.abs(np.linalg.norm(p, axis=1) - 1)),
        ("sphere cap, irregular", True, scenes.sphere_cap, lambda p: np.abs(np.linalg.norm(p, axis=1) - 1)),
        ("planar disc, irregular", True, scenes.plane_disk, lambda p: np.abs(p[:, 2])),
    ]:
        scene = make(n_free=args.free, irregular=irregular, seed=1, boundary_rings=3)
        free = scene.free
        for label, start in disturbed(scene, np.random.default_rng(0)):
            folds_in = new_folds(scene.vertices, start, scene.faces, free)
            for inner in inners:
                clock = time.perf_counter()
                r = geofair.fair(start, scene.faces, free, inner_fairness=inner)
                seconds = time.perf_counter() - clock
                off = distance(np.asarray(r.vertices)[free]).max()
                print(
                    f"| {name} | {label} | {folds_in} | {inner} | {'yes' if r.converged else 'no'} | {r.folds} | "
                    f"{r.new_folds} | {off:.1e} | {seconds:.2f} s |",
                    flush=True,
                )


if __name__ == "__main__":
    main()
