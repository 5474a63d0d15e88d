"""Speed of geofair.fair on disturbed sphere caps (irregular; --regular), with CGAL's linear fair beside it.

For each size (free vertices, default about 2k, 13k, 100k and 1M) prints: our wall time,
the iteration used ("newton": steps; "paper": iterations per level, coarsest first), final
residual, max radial error |‖q‖ − 1| over the free vertices (unit sphere), peak resident
memory, and the same input through CGAL's ``Polygon_mesh_processing::fair`` (continuity 1,
geofair_dev.cgal_fair) with its time, peak memory and max radial error, and the time ratio
ours/CGAL. Then the measured time exponent (least-squares slope of log time over log free
vertices) of both.

    PYTHONPATH=build/python python3 bench/speed.py [n_free ...]
        [--normal-weighting quadric|max|area|angle] [--inner uniform|conformal] [--no-cgal]
        [--iteration auto|newton|paper] [--phases] [--caps irregular|regular|random|icosphere]
        [--seeds 1,2,3] [--cache DIR] [--timeout SECONDS]
        [--module [LABEL=]this|FOLDER|WHEEL ...] [--rounds R] [--settle SECONDS]

``--module`` (repeatable) names the geofair to time: ``this`` (the default: whatever
``import geofair`` finds), a folder with the compiled module (``build/python``), or a wheel
file, installed with its dependencies into a venv of its own (geofair_dev.modules) as a user
would install it. With several modules and ``--rounds R`` the solves are interleaved (each
case: every module, then CGAL, R times) and each time is the median of the rounds, with
their range.

Scenes: ``geofair_dev.scenes.sphere_cap(n_free, irregular=True, seed=1, boundary_rings=2)``,
disturbed by ``disturbed(seed=2, amplitude=0.1)``; with ``--regular`` the same with
``irregular=False`` (concentric rings of 6k vertices, interior valence 6, so the free
vertex count is the nearest 1 + 3K(K - 1)); with ``--caps random`` or ``--caps icosphere``
``geofair_dev.scenes.flattened_sphere_cap(n_free, construction, seed=1)``: a whole sphere of
random samples or a geodesic icosphere, the cap above z = 0.3 pressed flat onto that plane
(a modeller's flattened selection), the rest of the sphere fixed; ``--seeds`` makes each size
with these seeds instead of 1 (geofair_dev.caps.load_scene); geofair gets the exact
normals on the random caps and estimates them on the icosphere caps. CGAL gets the whole mesh (its second,
outer fixed ring gives it tangent continuity); geofair the same vertices and free mask with
the exact sphere normals as G1 boundary normals. Generating the 1M-vertex irregular cap
takes about 5 minutes and 1 GiB (100k: 11 s), so scenes are cached as .npz files in
``--cache`` (default /tmp/geofair_bench_scenes) and reused (geofair_dev.caps).

Each solve (ours and CGAL's) runs in its own process, so its peak memory (VmHWM, which
includes the Python interpreter, numpy and the scene arrays for ours, about 40 MiB at 2k)
is its own; "solve MiB" is the part added by fair() itself. Times are wall times of the
fair() call alone (not the scene I/O), which starts ``--settle`` seconds (default 0.3,
geofair_dev.child.settle) after the child's imports and scene: numpy's OpenBLAS starts its
threads at ``import numpy`` and they spin for about 0.1 s on the second core that fair()
uses (in Blender numpy was imported at startup; ``--settle 0`` times a script that fairs at
once). The machine may be shared: rerun when a figure matters. A solve that fails (e.g.
geofair.SolverError) prints its error and a "failed" row; one that exceeds --timeout a
"timeout" row. With --phases each row is followed by the wall time of the solve's phases
(FairingResult.phase_seconds: the hierarchy, and per level the initial mesh, set-up,
inner-fairness relaxations, Newton steps and polishes, or the paper's iterations).
"""

import argparse
import json
import os
import subprocess
import time

import numpy as np

from geofair_dev import child as child_process
from geofair_dev import modules
from geofair_dev.caps import load_scene


def vm_hwm_mib():
    """Peak resident set of this process so far, MiB (Linux /proc)."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


CAPS = {
    "irregular": "disturbed irregular caps (sphere_cap(irregular=True), 60°, exact G1 normals)",
    "regular": "disturbed regular caps (sphere_cap, interior valence 6, exact G1 normals)",
    "random": "flattened caps of random sphere samples (flattened_sphere_cap, exact G1 normals)",
    "icosphere": "flattened icosphere caps (flattened_sphere_cap, the library's G1 normals)",
}


def radial_error(vertices, free):
    return float(np.abs(np.linalg.norm(vertices[free], axis=1) - 1.0).max())


def child(args):
    """Runs one of our solves; prints a JSON line."""
    import geofair

    v, f, free, normals = load_scene(args.cache, args.child, args.caps, args.seed)
    child_process.settle(args.settle)
    before = vm_hwm_mib()
    t = time.perf_counter()
    r = geofair.fair(
        v,
        f,
        free,
        boundary_normals=normals,
        normal_weighting=args.normal_weighting,
        inner_fairness=args.inner,
        max_iterations=args.max_iterations,
        iteration=args.iteration,
    )
    seconds = time.perf_counter() - t
    peak = vm_hwm_mib()
    print(
        json.dumps(
            {
                "n_free": int(free.sum()),
                "seconds": seconds,
                "iterations": list(r.iterations_per_level),
                "iteration": r.iteration,
                "newton_iterations": r.newton_iterations,
                "vertices": list(r.vertices_per_level),
                "residual": r.residual,
                "converged": r.converged,
                "error": radial_error(r.vertices, free),
                "peak_mib": peak,
                "solve_mib": peak - before,
                "phases": [[name, t] for name, t in r.phase_seconds],
            }
        )
    )


def run_ours(args, n, seed, spec):
    """One solve of the module ``spec`` (geofair_dev.modules) in a child process: its JSON report."""
    python, env = modules.command(spec)
    cmd = [python, os.path.abspath(__file__), "--child", str(n), "--seed", str(seed)]
    cmd += ["--cache", args.cache]
    cmd += ["--normal-weighting", args.normal_weighting, "--inner", args.inner]
    cmd += ["--max-iterations", str(args.max_iterations), "--iteration", args.iteration]
    cmd += ["--caps", args.caps, "--settle", str(args.settle)]
    try:
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout, env=env)
    except subprocess.TimeoutExpired:
        return None
    if run.returncode != 0:
        # A failed solve is a row of the table (the error's last line), not the end of it.
        lines = run.stderr.strip().splitlines()
        return {"failed": lines[-1] if lines else f"exit status {run.returncode}"}
    return json.loads(run.stdout.strip().splitlines()[-1])


def slope(ns, ts):
    """Least-squares exponent p of t ~ n^p."""
    ok = [(n, t) for n, t in zip(ns, ts, strict=True) if t and t > 0]
    if len(ok) < 2:
        return float("nan")
    x, y = np.log([n for n, _ in ok]), np.log([t for _, t in ok])
    return float(np.polyfit(x, y, 1)[0])


def span(values):
    """Median of the values, with their range when there are several: '0.512 (0.50-0.53)'."""
    values = sorted(values)
    median = float(np.median(values))
    return f"{median:.3f}" if len(values) == 1 else f"{median:.3f} ({values[0]:.3f}-{values[-1]:.3f})"


def describe(r):
    """The solve's path, residual and error: 'newton 3/1/2, 2.5e-08, err 9.0e-08, 127 MiB'."""
    its = r["iteration"] + " " + "/".join(map(str, r["iterations"]))
    if r["iteration"] == "paper" and r["newton_iterations"]:
        its = f"newton {r['newton_iterations']}, " + its
    mark = "" if r["converged"] else " NOT CONVERGED"
    return f"{its}, residual {r['residual']:.1e}{mark}, err {r['error']:.1e}, peak {r['peak_mib']:.0f} MiB"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sizes", nargs="*", type=int, default=[2000, 13000, 100000, 1000000])
    parser.add_argument("--normal-weighting", default="quadric", help="default: the library's")
    parser.add_argument("--inner", default="uniform")
    parser.add_argument("--max-iterations", type=int, default=20000)
    parser.add_argument("--iteration", default="auto", help="auto (default), newton or paper")
    parser.add_argument("--no-cgal", action="store_true")
    parser.add_argument("--phases", action="store_true", help="print the time of each phase")
    parser.add_argument("--caps", default="irregular", choices=sorted(CAPS), help="the caps' construction")
    parser.add_argument("--regular", action="store_true", help="the same as --caps regular")
    parser.add_argument("--seeds", default="1", help="comma-separated seeds of the caps (default 1)")
    parser.add_argument(
        "--module",
        action="append",
        metavar="[LABEL=]SPEC",
        help="a geofair to time: 'this' (default: what import geofair finds), a folder with the compiled "
        "module (build/python), or a wheel (installed into a venv of its own); repeat to compare, "
        "the solves interleaved",
    )
    parser.add_argument("--rounds", type=int, default=1, help="interleaved rounds; times are their median")
    parser.add_argument("--cache", default="/tmp/geofair_bench_scenes")
    parser.add_argument(
        "--settle",
        type=float,
        default=child_process.SETTLE_SECONDS,
        help="seconds between a child's imports and scene and its timed fair() (>= 0)",
    )
    parser.add_argument("--timeout", type=float, default=900.0, help="per solve, seconds")
    parser.add_argument("--child", type=int, default=None, help=argparse.SUPPRESS)
    parser.add_argument("--seed", type=int, default=1, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.regular:
        args.caps = "regular"
    if args.child is not None:
        child(args)
        return

    from geofair_dev import cgal_fair

    use_cgal = not args.no_cgal and cgal_fair.available()
    specs = [modules.parse(m) for m in (args.module or ["this"])]
    print(
        f"# {CAPS[args.caps]}; geofair.fair: iteration={args.iteration}, "
        f"normal_weighting={args.normal_weighting}, "
        f"inner_fairness={args.inner}, "
        f"default tolerance and levels; {os.cpu_count()} cores, load average "
        f"{os.getloadavg()[0]:.1f}; {args.rounds} round(s), each solve in its own process"
    )
    for label, spec in specs:
        print(f"# {label}: {spec}")
    cases = [(n, seed) for n in args.sizes for seed in (int(s) for s in args.seeds.split(",") if s.strip())]
    times = {(case, label): [] for case in cases for label, _ in specs + [("CGAL", None)]}
    last, n_free, cgal_err = {}, {}, {}
    for _ in range(args.rounds):
        for case in cases:
            n, seed = case
            v, f, free, _ = load_scene(args.cache, n, args.caps, seed)  # generated outside the timed children
            n_free[case] = int(free.sum())
            for label, spec in specs:
                r = run_ours(args, n, seed, spec)
                last[case, label] = r
                if r and "failed" not in r:
                    times[case, label].append(r["seconds"])
            if use_cgal:
                c = cgal_fair.cgal_fair(v, f, free)
                last[case, "CGAL"] = c
                cgal_err[case] = radial_error(c.vertices, free)
                if c.success:
                    times[case, "CGAL"].append(c.seconds)
            del v, f, free
    labels = [label for label, _ in specs]
    first = labels[0]
    for case in cases:
        n, seed = case
        print(f"{n_free[case]:>9,} free (seed {seed})")
        cgal = times[case, "CGAL"]
        for label in labels + (["CGAL"] if use_cgal else []):
            r, ts = last.get((case, label)), times[case, label]
            if label == "CGAL":
                c = r
                detail = f"err {cgal_err[case]:.1e}, peak {c.peak_mib:.0f} MiB" + ("" if c.success else " (failed)")
            elif r is None:
                print(f"    {label:>24}: timeout")
                continue
            elif "failed" in r:
                print(f"    {label:>24}: failed: {r['failed']}")
                continue
            else:
                detail = describe(r)
            ratios = []
            if ts and label != first and times[case, first]:
                ratios.append(f"{np.median(ts) / np.median(times[case, first]):.2f}x {first}")
            if ts and label != "CGAL" and cgal:
                ratios.append(f"{np.median(ts) / np.median(cgal):.2f}x CGAL")
            print(f"    {label:>24}: {span(ts) if ts else '-':>22} s  {', '.join(ratios):<28} {detail}")
            if args.phases and label != "CGAL":
                print("    " + " " * 26 + "phases [s]: " + ", ".join(f"{p} {t:.3f}" for p, t in r["phases"]))
    for label in labels + (["CGAL"] if use_cgal else []):
        ns = [n_free[c] for c in cases if times[c, label]]
        ts = [float(np.median(times[c, label])) for c in cases if times[c, label]]
        print(f"time exponent (log-log slope over the sizes), {label}: {slope(ns, ts):.2f}")


if __name__ == "__main__":
    main()
