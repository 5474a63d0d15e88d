"""Accuracy and time of geofair.fair on disturbed irregular sphere caps.

Prints, for each size, the max radial error |‖q‖ − 1| over the free vertices (unit sphere)
and the wall time of the linear bilaplacian solution and of intrinsic fairing.

    PYTHONPATH=build/python python3 bench/sphere_cap.py [n_free ...] [--levels N]
        [--normal-weighting area|angle|max|quadric] [--inner uniform|conformal]

--normal-weighting defaults to area, the paper's choice (geofair.fair's default is quadric).
"""

import argparse
import time

import numpy as np

import geofair
from geofair_dev import scenes


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sizes", nargs="*", type=int, default=[2000, 20000])
    parser.add_argument("--levels", type=int, default=None)
    parser.add_argument("--normal-weighting", default="area")
    parser.add_argument("--inner", default="uniform")
    parser.add_argument("--max-iterations", type=int, default=200000)
    args = parser.parse_args()
    extra = {} if args.levels is None else {"levels": args.levels}
    print(
        f"{'free':>7} {'outer':>12} {'levels':>7} {'iterations':>18} {'residual':>10} "
        f"{'max radial error':>17} {'time [s]':>9}"
    )
    for n in args.sizes:
        s = scenes.sphere_cap(n_free=n, irregular=True, seed=1)
        v = s.disturbed(seed=2, amplitude=0.1)
        for outer in ("bilaplacian", "intrinsic"):
            t = time.perf_counter()
            r = geofair.fair(
                v,
                s.faces,
                s.free,
                boundary_normals=s.normals,
                outer_fairness=outer,
                inner_fairness=args.inner,
                normal_weighting=args.normal_weighting,
                max_iterations=args.max_iterations,
                **extra,
            )
            elapsed = time.perf_counter() - t
            err = np.abs(np.linalg.norm(r.vertices[s.free], axis=1) - 1.0).max()
            its = "/".join(map(str, getattr(r, "iterations_per_level", [r.iterations])))
            print(
                f"{s.n_free:>7} {outer:>12} {len(r.iterations_per_level):>7} {its:>18} "
                f"{r.residual:>10.2e} {err:>17.3e} {elapsed:>9.2f}",
                flush=True,
            )


if __name__ == "__main__":
    main()
