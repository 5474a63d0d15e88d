"""Live fairing: per-frame times of geofair.LiveFairing.update along a scripted drag, beside a
cold geofair.fair of the same frames.

The scenes are the constructions of bench/speed.py's sphere caps, undisturbed
(geofair_dev.scenes: ``irregular`` and ``regular`` 60° caps of the unit sphere,
``sphere_cap(n_free=n, irregular=..., seed=1, boundary_rings=2)``; ``random`` and
``icosphere`` caps above z = 0.3 of whole sphere meshes, ``flattened_sphere_cap(n, kind,
seed=1)``'s exact positions, the rest of the sphere fixed). The handle is the cap's free
vertices within --handle degrees (default 8) of +z; the region is the rest of the cap's
free vertices. The G1 normals are the sphere's, turned with the handle (a handle of random
points can have a vertex without a triangle of its own, where the library's estimate needs
one).

The drag, in frames (each an update() of the handle's new positions and G1 normals, a rigid
handle turning its normals with it):

- ``slide``: the handle rotated about the sphere's centre (the x axis) by --slide degrees
  in --slide-frames steps (default 20° in 20 frames): along the sphere, so every frame's
  exact answer is the sphere; "radial" is the largest | |q| - 1 | over the free vertices;
- ``lift``: then the handle moved along +z by 0.015 per frame, 10 frames (0.15 in all);
- ``tilt``: then the handle turned about the x axis through its own centre by 2° per frame,
  10 frames.

Per frame (with --frames): the wall time of update(), how it was solved (warm Newton steps,
or "cold" where it fell back to the cold path), the residual, folded edges and for slide
frames the radial error. Per scene, a summary row: free vertices, the median, 95th
percentile and largest frame time (ms), the median CPU time of a frame (ms, all threads:
below the wall time where other processes take the cores), the median Newton steps, frames that fell back to
the cold path, frames that did not converge, the largest fold count, the largest radial
error of the slide; then a cold geofair.fair of every --cold-every-th frame's same input (and
the last): its median time (s), the ratio of that median to the warm frames' median, and the
largest distance between update()'s and fair()'s vertices over the region's diameter L
where fair() converged without new folds, and "cold bad": the cold solves that did not (of
those run). Below, the anchor for speed, a prefactorized linear bi-Laplacian (Botsch &
Kobbelt 2004; SciPy's splu of L D⁻¹ L's free block, the rest mesh's cotangent Laplacian and
lumped areas): its median time a frame and the largest radial error of its slide (it does
not keep the sphere). A long slide can fold the cold solve from the frame's input while the warm
frame, started from the last one, does not fold.

    PYTHONPATH=build/python python3 bench/live.py [n_free ...] [--caps irregular,regular,random,icosphere]
        [--handle DEG] [--slide DEG] [--slide-frames N] [--inner uniform|conformal]
        [--cold-every K] [--remesh off|if_needed] [--frames] [--time-limit SECONDS|addon]

With --time-limit each update gets that bound (update's time_limit; "addon": the add-on's
rule, 4 times the constructor's time and at least 1 s): a frame whose warm start leaves no
time returns unconverged without the cold path (it counts in "fail", not in "cold").

With --remesh if_needed (LiveFairing's remesh option) the "cold" column counts the frames
that remeshed too, the radial error is over each frame's own free vertices, the comparison
with the cold fair skips the frames on a remeshed mesh (from the first remesh on), and a line
under the summary gives the remeshes.

Defaults: sizes 2000 and 13000, all four constructions. The machine may be shared (the
times are wall times): rerun when a figure matters.
"""

import argparse
import json
import os
import time

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

import geofair
from geofair_dev import scenes
from geofair_dev.caps import FLATTENED


def rotation_x(degrees):
    a = np.radians(degrees)
    return np.array([[1.0, 0.0, 0.0], [0.0, np.cos(a), -np.sin(a)], [0.0, np.sin(a), np.cos(a)]])


def handle_scene(n, kind, handle_deg):
    """(vertices, faces, free, handle, normals): the cap on the unit sphere (its exact
    positions, also of the free vertices), its central handle, and the sphere's normals (the
    G1 normals of the fixed vertices)."""
    if kind in FLATTENED:
        s, _ = scenes.flattened_sphere_cap(n, kind, seed=1)
    else:
        s = scenes.sphere_cap(n_free=n, irregular=kind == "irregular", seed=1, boundary_rings=2)
    v = s.vertices.copy()
    unit = v / np.linalg.norm(v, axis=1)[:, None]
    handle = s.free & (np.degrees(np.arccos(np.clip(unit[:, 2], -1.0, 1.0))) < handle_deg)
    return v, s.faces, s.free & ~handle, handle, unit


def drag(v, handle, normals, slide_deg, slide_frames):
    """The frames: (phase, vertices, G1 normals) in order; a rigid handle turns its normals."""
    frames = []
    for k in range(1, slide_frames + 1):
        w, n = v.copy(), normals.copy()
        R = rotation_x(slide_deg * k / slide_frames)
        w[handle], n[handle] = v[handle] @ R.T, normals[handle] @ R.T
        frames.append(("slide", w, n))
    _, slid, slid_normals = frames[-1]
    for k in range(1, 11):
        w = slid.copy()
        w[handle, 2] += 0.015 * k
        frames.append(("lift", w, slid_normals))
    _, lifted, lifted_normals = frames[-1]
    centre = lifted[handle].mean(axis=0)
    for k in range(1, 11):
        w, n = lifted.copy(), lifted_normals.copy()
        R = rotation_x(2.0 * k)
        w[handle] = centre + (lifted[handle] - centre) @ R.T
        n[handle] = lifted_normals[handle] @ R.T
        frames.append(("tilt", w, n))
    return frames


class LinearBilaplacian:
    """The anchor for speed (Botsch & Kobbelt 2004): Δ²x = 0 at the free vertices with the
    cotangent Laplacian and lumped areas of the rest mesh, K = L D⁻¹ L, its free block
    factorized once (SciPy's splu); a frame is one back substitution with the fixed rows."""

    def __init__(self, vertices, faces, free):
        L = geofair.cotangent_laplacian(vertices, faces).tocsc()
        e1 = vertices[faces[:, 1]] - vertices[faces[:, 0]]
        e2 = vertices[faces[:, 2]] - vertices[faces[:, 0]]
        area = 0.5 * np.linalg.norm(np.cross(e1, e2), axis=1)
        lumped = np.bincount(faces.ravel(), np.repeat(area / 3.0, 3), minlength=len(vertices))
        K = (L @ scipy.sparse.diags(1.0 / np.maximum(lumped, 1e-300)) @ L).tocsc()
        self.free = free
        self.K_fb = K[free][:, ~free]
        self.lu = scipy.sparse.linalg.splu(K[free][:, free].tocsc())

    def solve(self, vertices):
        out = vertices.copy()
        out[self.free] = self.lu.solve(-(self.K_fb @ vertices[~self.free]))
        return out


def region_diagonal(vertices, faces, free):
    used = np.unique(faces[free[faces].any(axis=1)])
    p = vertices[used]
    return float(np.linalg.norm(p.max(axis=0) - p.min(axis=0)))


def newton_steps(result):
    """The Newton steps of a warm frame; None where the frame ran the cold path or remeshed."""
    if "cold path" in result.message or result.remeshed:
        return None
    return result.newton_iterations


def run(n, kind, args):
    v, f, free, handle, normals = handle_scene(n, kind, args.handle)
    t = time.perf_counter()
    tuning = {"tuning": json.loads(args.tuning)} if args.tuning else {}
    live = geofair.LiveFairing(
        v, f, free, boundary_normals=normals, inner_fairness=args.inner, remesh=args.remesh, **tuning
    )
    prepare = time.perf_counter() - t
    limit = args.time_limit
    if limit == "addon":  # the add-on's bound (addon/geometric_fairing/live.py)
        limit = max(1.0, 4.0 * prepare)
    limit = None if limit is None else float(limit)
    print(
        f"# {kind} n={n}: {int(free.sum())} free, {int(handle.sum())} handle vertices; "
        f"constructor {prepare:.2f} s ({'converged' if live.result.converged else 'NOT converged'})"
        + ("" if limit is None else f"; each update's time limit {limit:.2f} s"),
        flush=True,
    )
    frames = drag(v, handle, normals, args.slide, args.slide_frames)
    times, cpu, steps, radial, folds, cold_paths, failed, results = [], [], [], [], [], 0, 0, []
    phases = {}
    for i, (phase, w, n_w) in enumerate(frames):
        t, c = time.perf_counter(), time.process_time()
        r = live.update(w, boundary_normals=n_w, time_limit=limit)
        dt = time.perf_counter() - t
        times.append(dt)
        cpu.append(time.process_time() - c)
        results.append(r)
        s = newton_steps(r)
        if s is None:
            cold_paths += 1
        else:
            steps.append(s)
            for name, seconds in r.phase_seconds:
                phases.setdefault(name, []).append(seconds * 1000)
        failed += not r.converged
        folds.append(r.folds)
        rad = np.abs(np.linalg.norm(r.vertices[r.free], axis=1) - 1.0).max() if phase == "slide" else None
        if rad is not None:
            radial.append(rad)
        if args.frames:
            how = f"{s} steps" if s is not None else ("remesh" if r.remeshed else "cold")
            rad_text = f" radial {rad:.1e}" if rad is not None else ""
            print(
                f"  {i + 1:3d} {phase:5s} {dt * 1000:7.1f} ms  {how:9s} residual {r.residual:.1e} "
                f"folds {r.folds}{rad_text}{'' if r.converged else '  NOT CONVERGED'}",
                flush=True,
            )
    linear = LinearBilaplacian(v, f, free)
    linear_times, linear_radial = [], 0.0
    for phase, w, _ in frames:
        t = time.perf_counter()
        x = linear.solve(w)
        linear_times.append(time.perf_counter() - t)
        if phase == "slide":
            linear_radial = max(linear_radial, float(np.abs(np.linalg.norm(x[free], axis=1) - 1.0).max()))
    cold_times, distance, cold_bad = [], 0.0, 0
    # Every --cold-every-th frame and the last (0: the last alone).
    every = set(range(args.cold_every - 1, len(frames), args.cold_every)) if args.cold_every > 0 else set()
    picks = sorted(every | {len(frames) - 1})
    for i in picks:
        _, w, n_w = frames[i]
        t = time.perf_counter()
        c = geofair.fair(w, f, free, boundary_normals=n_w, inner_fairness=args.inner, **tuning)
        cold_times.append(time.perf_counter() - t)
        cold_bad += not c.converged or c.new_folds > 0
        # A remeshed frame's mesh is not the cold fair's (no row-wise comparison).
        same_mesh = len(results[i].vertices) == len(c.vertices) and np.array_equal(results[i].faces, c.faces)
        if c.converged and c.new_folds == 0 and results[i].converged and same_mesh:
            L = region_diagonal(w, f, free)
            distance = max(distance, float(np.abs(c.vertices - results[i].vertices).max()) / L)
    ms = np.array(times) * 1000
    warm_median = float(np.median(ms))
    cold_median = float(np.median(cold_times))
    print(
        f"{kind:9s} {int(free.sum()):6d} {warm_median:8.1f} {np.percentile(ms, 95):8.1f} {ms.max():8.1f} "
        f"{np.median(cpu) * 1000:8.1f} "
        f"{np.median(steps) if steps else float('nan'):5.1f} {cold_paths:4d} {failed:4d} {max(folds):5d} "
        f"{max(radial):9.1e} {cold_median:7.2f} {cold_median * 1000 / warm_median:7.1f} {distance:9.1e} "
        f"{cold_bad}/{len(picks)}",
        flush=True,
    )
    if args.remesh != "off":
        print(f"  remeshes: {live.remeshes} (frames that replaced the region's triangles)")
    print("  warm phases, median ms: " + ", ".join(f"{k} {np.median(t):.1f}" for k, t in phases.items()))
    print(
        f"  linear bi-Laplacian (prefactorized): median {np.median(linear_times) * 1000:.1f} ms a frame, "
        f"slide radial error {linear_radial:.1e}"
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sizes", nargs="*", type=int, default=[2000, 13000])
    parser.add_argument("--caps", default="irregular,regular,random,icosphere")
    parser.add_argument("--handle", type=float, default=8.0, help="handle radius, degrees")
    parser.add_argument("--slide", type=float, default=20.0, help="slide along the sphere, degrees")
    parser.add_argument("--slide-frames", type=int, default=20)
    parser.add_argument("--inner", default="uniform")
    parser.add_argument("--remesh", default="off", choices=["off", "if_needed"], help="LiveFairing's remesh option")
    parser.add_argument(
        "--cold-every", type=int, default=5, help="a cold fair of every K-th frame's input and the last (0: the last)"
    )
    parser.add_argument("--frames", action="store_true", help="a row per frame")
    parser.add_argument("--tuning", default=None, help="LiveFairing's tuning, JSON (geofair.defaults()['tuning'])")
    parser.add_argument(
        "--time-limit",
        default=None,
        help="seconds an update may take (update's time_limit), or 'addon': 4 x the constructor's time, >= 1 s",
    )
    args = parser.parse_args()
    if args.cold_every < 0:
        parser.error("--cold-every must be >= 0")
    with open("/proc/loadavg") as f:
        load = f.read().split()[0]
    print(f"# load average {load} on {os.cpu_count()} cores")
    print(
        f"# {args.slide_frames} slide frames ({args.slide}° along the sphere), 10 lift, 10 tilt; "
        f"handle {args.handle}°, inner fairness {args.inner}"
    )
    header = "cap          free   med ms   p95 ms   max ms  cpu med steps cold fail folds    radial"
    header += "  cold s   ratio     |Δ|/L cold bad"
    print(header)
    for n in args.sizes:
        for kind in args.caps.split(","):
            run(n, kind, args)


if __name__ == "__main__":
    main()
