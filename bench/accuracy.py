"""Accuracy of fairing on the analytic scenes: linear bilaplacian fairing, the paper's
settings and geofair's defaults.

Sphere cap (unit sphere, 60 degrees), cylinder patch (unit radius) and catenoid patch
(a = 1), regular and irregular meshes, free vertices disturbed along the normals, exact G1
normals: the max distance of the free vertices to the analytic surface (mesh units; the
radial error on the sphere and the cylinder). Torus patch (R = 2, r = 1; its faired shape
is not known in closed form): the Hausdorff distance between the results on a regular and
an irregular mesh, relative to the bounding-box diagonal.

Settings: "bilaplacian" = outer_fairness="bilaplacian"; "paper" = normal_weighting="area"
(Schneider & Kobbelt 2001, section 6), everything else default; "defaults" = geofair.fair's
defaults (normal_weighting="quadric"). All with uniform inner fairness, tolerance 1e-4.

Flattened caps (scenes.flattened_sphere_cap: random samples of the unit sphere or an
icosphere, the cap above z = 0.3 pressed onto that plane, not disturbed): the max radial
error; exact G1 normals for the random caps, the library's for the icosphere caps.

    PYTHONPATH=build/python python3 bench/accuracy.py [--quick] [--only patches|flattened|torus]

--quick: a quarter of the vertices; --only: those rows alone.
"""

import argparse
import time

import numpy as np

import geofair
from geofair_dev import measures, scenes

SETTINGS = {
    "bilaplacian": dict(outer_fairness="bilaplacian"),
    "paper": dict(normal_weighting="area"),
    "defaults": {},
}
PATCHES = [
    ("sphere cap", scenes.sphere_cap, 2000),
    ("cylinder", scenes.cylinder_patch, 5000),
    ("catenoid", scenes.catenoid_patch, 5000),
]
FLATTENED = [
    ("random", 2000, 1),
    ("random", 7000, 1),
    ("random", 7000, 2),
    ("random", 13000, 2),
    ("icosphere", 13000, 1),
]


def fair(scene, settings, start=None, normals=True):
    v = scene.disturbed(seed=2, amplitude=0.1) if start is None else start
    t = time.perf_counter()
    normals = scene.normals if normals else None
    r = geofair.fair(v, scene.faces, scene.free, boundary_normals=normals, max_iterations=50000, **settings)
    return r, time.perf_counter() - t


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--only", choices=("patches", "flattened", "torus"), help="print only these rows")
    args = parser.parse_args()
    scale = 0.25 if args.quick else 1.0
    print("| scene | mesh | free | " + " | ".join(SETTINGS) + " | iterations (paper, defaults) | time [s] |")
    print("|---|---|---:|" + "---:|" * len(SETTINGS) + "---|---:|")
    for name, make, n in PATCHES if args.only in (None, "patches") else []:
        for irregular in (False, True):
            s = make(n_free=round(n * scale), irregular=irregular, seed=1)
            cells, iterations, total = [], [], 0.0
            for key, settings in SETTINGS.items():
                r, t = fair(s, settings)
                total += t
                cells.append(f"{np.abs(s.distance(r.vertices[s.free])).max():.1e}")
                if key != "bilaplacian":
                    iterations.append(f"{r.iterations}" + ("" if r.converged else " (not converged)"))
            mesh = "irregular" if irregular else "regular"
            row = [name, mesh, str(s.n_free), *cells, ", ".join(iterations), f"{total:.0f}"]
            print("| " + " | ".join(row) + " |", flush=True)
    for construction, n, seed in FLATTENED if args.only in (None, "flattened") else []:
        s, start = scenes.flattened_sphere_cap(round(n * scale), construction, seed=seed)
        cells, iterations, total = [], [], 0.0
        for key, settings in SETTINGS.items():
            r, t = fair(s, settings, start=start, normals=construction == "random")
            total += t
            cells.append(f"{np.abs(s.distance(r.vertices[s.free])).max():.1e}")
            if key != "bilaplacian":
                iterations.append(f"{r.iterations}" + ("" if r.converged else " (not converged)"))
        name = f"flattened cap, seed {seed}"
        row = [name, construction, str(s.n_free), *cells, ", ".join(iterations), f"{total:.0f}"]
        print("| " + " | ".join(row) + " |", flush=True)
    if args.only in ("patches", "flattened"):
        return
    pair = [scenes.torus_patch(n_free=round(10000 * scale), irregular=irr, seed=1) for irr in (False, True)]
    cells, iterations, total = [], [], 0.0
    for key, settings in SETTINGS.items():
        results = []
        for s in pair:
            r, t = fair(s, settings)
            total += t
            results.append(r)
            if key != "bilaplacian":
                iterations.append(f"{r.iterations}" + ("" if r.converged else " (not converged)"))
        v = pair[0].vertices
        diag = np.linalg.norm(v.max(axis=0) - v.min(axis=0))
        d = measures.hausdorff(results[0].vertices, pair[0].faces, results[1].vertices, pair[1].faces, dense=True)
        cells.append(f"{d / diag:.1e}")
    print(
        f"| torus, regular vs irregular (Hausdorff / diagonal) | both | {pair[0].n_free}, {pair[1].n_free} | "
        + " | ".join(cells)
        + f" | {', '.join(iterations)} | {total:.0f} |",
        flush=True,
    )


if __name__ == "__main__":
    main()
