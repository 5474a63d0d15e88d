"""Real-mesh benchmark: geofair.fair on regions of real meshes, Blender primitives and the paper's scenes.

For each case and inner fairness prints one row: the case name, free vertices, the
region's topology (disc, annulus or other), inner fairness, "inval" (seeds drawn before
this one whose region was invalid input: redrawn), the outcome (yes = converged, no = not
converged, timeout, error, invalid), new folds (edges with a free endpoint whose two
triangles' normals have a negative dot product after fairing but not before), the wall
time of the fair() call alone, the final residual, the iteration used ("newton" or "paper"
with the result's iteration count; "+Nn": Newton steps), and for sphere caps the max
radial error | |q| - 1 | over the free vertices; then the error message or the result's
``reason`` where there is one. Fixed vertices must come back bit-identical: a violation is
printed as "!!! FIXED VERTICES CHANGED". At the end, per inner fairness: cases, converged
without new folds (count and %, and by the region's topology: disc, annulus, other; see
region_topology), not converged, converged with new folds, timeouts, errors, median and
max time of the finished solves per size class (free vertices <= 150, <= 1,500, <= 15,000,
more) and how many cases of at most 10,000 free vertices took more than 10 s (timeouts
included).

    PYTHONPATH=build/python python3 bench/realmesh.py [--quick] [--large] [--only SUBSTRING[,SUBSTRING...]]
        [--inner uniform,conformal] [--timeout SECONDS] [--cache DIR] [--json FILE]
        [--remesh off|always|if_needed] [--compare-remesh] [--tuning JSON]

--remesh MODE passes ``remesh`` to geofair.fair (off: False, the default and today's
behaviour, the keyword not passed at all; always: True; if_needed: "if_needed"). With a mode
other than off each row gets a column "remesh" (off: not asked, kept: the connectivity was
kept, yes: the result was remeshed); new folds of a remeshed result are its folded edges
with a free endpoint (its triangles are not the input's), and the radial error is taken
over its free vertices. The summary then says, per inner fairness, in how many cases the
result was remeshed. --compare-remesh runs each case with remesh off and with MODE (after
each other, the same input) and the summary also lists the cases that converge without new
folds with the connectivity kept but not with MODE (lost), and the reverse (gained).

--tuning JSON passes overrides of the solvers' tuning to every solve (``tuning=``, e.g.
'{"schedule.newton_min_base_free": 800}'): a tuning is measured on this corpus before it is
changed.

The corpus: geofair_dev.corpus (dev/geofair_dev/corpus.py), which describes its cases:
regions of CGAL's demo meshes (``cgal/...``), Blender's primitives (``blender/...``, made
through the ``bpy`` module; skipped with a note without it), the paper's scenes
(``paper/...``) and regular sphere caps (``regular/...``).

--quick: 18 cases of at most about 1,000 free vertices. Every solve runs
``geofair.fair`` with the defaults (only ``inner_fairness`` set) in its own process
with a timeout (--timeout, default 60 s), timed from 0.3 s after its imports and input
(geofair_dev.child.settle); the inputs are cached in --cache
(default /tmp/geofair_realmesh_cases) and reused. A solve whose process cannot import
geofair (the module being rebuilt) waits and retries; a "#" line marks where the module
file changed during the run (each JSON row carries its time as "build").
"""

import argparse
import importlib.util
import json
import os
import sys
import time

import numpy as np

from geofair_dev import child as child_process
from geofair_dev.corpus import DEFAULT_CACHE, case_file, corpus, new_folds, region_topology

SIZE_CLASSES = ((150, "<=150"), (1500, "<=1.5k"), (15000, "<=15k"), (None, ">15k"))

# --------------------------------------------------------------------------------------
# Running


def child(args):
    """Runs one solve; writes the result's vertices to --result, prints a JSON line."""
    import geofair

    with np.load(args.child) as d:
        v, f, free, bn, polygons = d["vertices"], d["faces"], d["free"], d["boundary_normals"], d["polygon_ids"]
    bn = bn if len(bn) else None
    polygons = polygons if len(polygons) else None
    remesh = {"off": {}, "always": {"remesh": True}, "if_needed": {"remesh": "if_needed"}}[args.remesh]
    if args.tuning:
        remesh["tuning"] = json.loads(args.tuning)
    out, r = child_process.solve(
        lambda: geofair.fair(v, f, free, boundary_normals=bn, polygon_ids=polygons, inner_fairness=args.inner, **remesh)
    )
    if r is not None:
        np.save(args.result, np.asarray(r.vertices))
        out["status"] = "yes" if getattr(r, "converged", None) else "no"
        if args.remesh != "off":
            out["remeshed"] = bool(getattr(r, "remeshed", False))
            if out["remeshed"]:  # the result's own triangles and free mask
                np.savez(args.result + ".mesh.npz", faces=np.asarray(r.faces), free=np.asarray(r.free))
        for attr in ("converged", "residual", "iteration", "iterations", "newton_iterations", "reason"):
            out[attr] = child_process.scalar(getattr(r, attr, None))
    child_process.report(out)


def build_id():
    """Modification time of the geofair module that a child would import (without importing it)."""
    spec = importlib.util.find_spec("geofair")
    origin = spec.origin if spec else None
    return time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(os.path.getmtime(origin))) if origin else "none"


def _fair_has_remesh():
    try:
        import geofair
    except ImportError:
        return True  # unknown: the solves will say
    return "remesh" in (geofair.fair.__doc__ or "")


def run_solve(path, inner, args, remesh="off"):
    """Runs one solve in a child process (geofair_dev.child.run); (dict, result vertices or
    None); with remesh other than off a remeshed result's faces and free mask are in
    dict["mesh"]."""
    result = os.path.join(args.cache, f"result_{os.getpid()}.npy")
    for stale in (result, result + ".mesh.npz"):
        if os.path.exists(stale):
            os.remove(stale)
    cmd = [sys.executable, os.path.abspath(__file__), "--child", path, "--inner", inner, "--result", result]
    if remesh != "off":
        cmd += ["--remesh", remesh]
    if args.tuning:
        cmd += ["--tuning", args.tuning]
    out = child_process.run(cmd, args.timeout)
    after = np.load(result) if out["status"] in ("yes", "no") else None
    if after is not None:
        os.remove(result)
    if out.get("remeshed") and after is not None:
        with np.load(result + ".mesh.npz") as d:
            out["mesh"] = {"faces": d["faces"], "free": d["free"].astype(bool)}
        os.remove(result + ".mesh.npz")
    return out, after


def fixed_changed(before, after, free):
    """Number of fixed vertices whose coordinates are not bit-identical (a remeshed result
    keeps the fixed rows' indices; its extra rows are not compared)."""
    after = after[: len(before)]
    a, b = np.ascontiguousarray(before[~free]), np.ascontiguousarray(after[~free])
    return int((a.view(np.uint64) != b.view(np.uint64)).any(axis=1).sum())


def make_row(desc, meta, inner, n_free, out, before, after, faces, free, remesh=None):
    row = {"case": desc["name"], "free": n_free, "inner": inner, "invalid": meta.get("invalid", 0)}
    if remesh is not None:
        row["remesh"] = remesh
    row["topology"], row["euler"], row["loops"] = region_topology(faces, free)
    mesh = out.pop("mesh", None)
    row.update(out)
    if after is not None:
        if mesh is None:
            row["new_folds"] = new_folds(before, after, faces, free)
        else:  # other triangles than the input's: every folded edge with a free endpoint counts
            row["new_folds"] = new_folds(None, after, mesh["faces"], mesh["free"])
        row["fixed_changed"] = fixed_changed(before, after, free)
        if meta.get("sphere"):
            result_free = free if mesh is None else mesh["free"]
            row["radial_error"] = float(np.abs(np.linalg.norm(after[result_free], axis=1) - 1.0).max())
    return row


def _fmt(x, spec, width):
    return f"{x:>{width}{spec}}" if isinstance(x, (int, float)) else " " * width


HEADER = (
    f"{'case':<30} {'free':>6} {'region':<7} {'inner':<9} {'inval':>5} {'conv':<7} {'folds':>5} {'time [s]':>8} "
    f"{'residual':>8} {'iteration':<20} {'radial':>8}  note"
)


HEADER_REMESH = HEADER.replace(" note", " remesh  note")


def format_row(row, remesh_column=False):
    it = ""
    if row.get("iteration") is not None:
        it = f"{row['iteration']} {row.get('iterations', '')}"
        if row.get("newton_iterations"):
            it += f" +{row['newton_iterations']}n"
    note = row.get("message") or row.get("reason") or ""
    if row.get("fixed_changed"):
        note = f"!!! FIXED VERTICES CHANGED: {row['fixed_changed']} !!! " + note
    remesh = ""
    if remesh_column:
        remesh = "off" if row.get("remesh", "off") == "off" else ""
        if not remesh and "remeshed" in row:
            remesh = "yes" if row["remeshed"] else "kept"
        remesh = f" {remesh:<6}"
    return (
        f"{row['case']:<30} {row['free']:>6} {row.get('topology', ''):<7} {row['inner']:<9} "
        f"{row['invalid']:>5} {row['status']:<7} "
        f"{_fmt(row.get('new_folds'), 'd', 5)} {_fmt(row.get('seconds'), '.2f', 8)} "
        f"{_fmt(row.get('residual'), '.1e', 8)} {it:<20} {_fmt(row.get('radial_error'), '.1e', 8)}{remesh}  {note}"
    ).rstrip()


def size_class(n):
    for i, (limit, _) in enumerate(SIZE_CLASSES):
        if limit is None or n <= limit:
            return i
    return len(SIZE_CLASSES) - 1


def _good(r):
    """Converged without new folds, fixed vertices untouched."""
    return r["status"] == "yes" and r.get("new_folds") == 0 and not r.get("fixed_changed")


def summary(rows, inners, timeout, modes=("off",)):
    lines = []
    for inner, mode in [(inner, mode) for inner in inners for mode in modes]:
        rs = [r for r in rows if r["inner"] == inner and r.get("remesh", "off") == mode]
        if not rs:
            continue
        label = inner if tuple(modes) == ("off",) else f"{inner}, remesh {mode}"
        total = len(rs)
        good = sum(_good(r) for r in rs)
        folded = sum(r["status"] == "yes" and bool(r.get("new_folds")) for r in rs)
        count = {s: sum(r["status"] == s for r in rs) for s in ("no", "timeout", "error", "invalid")}
        fixed = sum(bool(r.get("fixed_changed")) for r in rs)
        slow = sum((r["status"] == "timeout" and timeout > 10) or (r.get("seconds") or 0) > 10
                   for r in rs if r["free"] <= 10000)  # fmt: skip
        lines.append(
            f"{label}: {total} cases, converged without new folds {good} ({100 * good / total:.0f} %), "
            f"not converged {count['no']}, converged with new folds {folded}, timeouts {count['timeout']}, "
            f"errors {count['error']}, invalid input {count['invalid']}"
            + (f", !!! FIXED VERTICES CHANGED in {fixed}" if fixed else "")
        )
        by_kind = []
        for kind in ("disc", "annulus", "other"):
            ks = [r for r in rs if r.get("topology") == kind]
            if ks:
                ok = sum(r["status"] == "yes" and r.get("new_folds") == 0 and not r.get("fixed_changed") for r in ks)
                by_kind.append(f"{kind} {ok} of {len(ks)}")
        parts = ["regions by topology, converged without new folds: " + ", ".join(by_kind)] if by_kind else []
        for i, (_, label) in enumerate(SIZE_CLASSES):
            ts = [r["seconds"] for r in rs if size_class(r["free"]) == i and r["status"] in ("yes", "no")]
            n = sum(size_class(r["free"]) == i for r in rs)
            if n:
                t = f"median {np.median(ts):.2f} s, max {max(ts):.2f} s" if ts else "none finished"
                parts.append(f"{label} free: {n} cases, {len(ts)} finished, {t}")
        lines += ["    " + p for p in parts]
        lines.append(f"    cases <= 10,000 free taking > 10 s (timeouts included): {slow}")
        if mode != "off":
            remeshed = sum(bool(r.get("remeshed")) for r in rs)
            finished = sum("remeshed" in r for r in rs)
            lines.append(f"    remeshed: {remeshed} of {total} cases ({finished} finished)")
    if len(modes) == 2:
        off, mode = modes
        for inner in inners:
            by = {(r["case"], r.get("remesh", "off")): r for r in rows if r["inner"] == inner}
            cases = [c for c, m in by if m == off and (c, mode) in by]
            lost = [c for c in cases if _good(by[c, off]) and not _good(by[c, mode])]
            gained = [c for c in cases if _good(by[c, mode]) and not _good(by[c, off])]
            lines.append(
                f"{inner}: {len(cases)} cases run both ways; converged without new folds with the connectivity "
                f"kept but not with remesh {mode} (lost): {len(lost)}" + (f" ({', '.join(lost)})" if lost else "")
            )
            lines.append(
                f"    with remesh {mode} but not with the connectivity kept (gained): {len(gained)}"
                + (f" ({', '.join(gained)})" if gained else "")
            )
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a small subset (<= ~1,000 free vertices)")
    parser.add_argument("--large", action="store_true", help="add icosphere 7 and the 100k regular cap")
    parser.add_argument("--only", default=None, help="the cases whose name contains any of these (comma-separated)")
    parser.add_argument("--timeout", type=float, default=60.0, help="per solve, seconds")
    parser.add_argument("--inner", default="uniform,conformal", help="inner fairness, comma-separated")
    parser.add_argument("--cache", default=DEFAULT_CACHE)
    parser.add_argument("--json", default=None, help="write all rows to this file")
    parser.add_argument("--remesh", default="off", choices=("off", "always", "if_needed"),
                        help="geofair.fair's remesh: off (False, the default), always (True), if_needed")  # fmt: skip
    parser.add_argument("--compare-remesh", action="store_true",
                        help="run every case with remesh off and with --remesh's mode")  # fmt: skip
    parser.add_argument("--tuning", default=None, help="overrides of geofair.fair's tuning (JSON)")
    parser.add_argument("--child", default=None, help=argparse.SUPPRESS)
    parser.add_argument("--result", default=None, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        child(args)
        return
    if args.compare_remesh and args.remesh == "off":
        parser.error("--compare-remesh needs --remesh always or --remesh if_needed")
    modes = ("off", args.remesh) if args.compare_remesh else (args.remesh,)
    remesh_column = modes != ("off",)
    inners = [s.strip() for s in args.inner.split(",") if s.strip()]
    descs, notes = corpus(args.quick, args.large, args.cache)
    if args.only:
        descs = [d for d in descs if any(part in d["name"] for part in args.only.split(","))]
    threads = os.environ.get("OMP_NUM_THREADS")
    print(
        f"# geofair.fair defaults, inner fairness {', '.join(inners)}; timeout {args.timeout:.0f} s; "
        f"{len(descs)} cases; {os.cpu_count()} cores" + (f", OMP_NUM_THREADS={threads}" if threads else "")
        + f", load average {os.getloadavg()[0]:.1f}"
    )  # fmt: skip
    for note in notes:
        print(f"# {note}")
    if remesh_column:
        print(f"# remesh: {' and '.join(modes)}")
        if not _fair_has_remesh():
            print("# geofair.fair has no remesh keyword in this build: the remeshing rows will be errors")
    print(HEADER_REMESH if remesh_column else HEADER, flush=True)
    rows = []
    start = time.perf_counter()
    build = build_id()
    print(f"# geofair module built {build}", flush=True)
    for desc in descs:
        import_waits = 0
        while True:
            try:
                path = case_file(desc, args.cache)
            except (ValueError, RuntimeError) as error:
                print(f"# {desc['name']}: not built: {error}", flush=True)
                break
            except ImportError as error:  # geofair, maybe being rebuilt
                import_waits += 1
                if import_waits > child_process.IMPORT_RETRIES:
                    raise
                print(f"# {desc['name']}: {error}; retrying in {child_process.IMPORT_WAIT} s", flush=True)
                sys.modules.pop("geofair", None)
                time.sleep(child_process.IMPORT_WAIT)
                continue
            with np.load(path) as d:
                v, f, free = d["vertices"], d["faces"], d["free"]
                meta = json.loads(str(d["meta"]))
            redraw = None
            case_rows = []
            for inner, mode in [(inner, mode) for inner in inners for mode in modes]:
                if build_id() != build:
                    build = build_id()
                    print(f"# the geofair module changed (rebuilt {build}): rows below use it", flush=True)
                out, after = run_solve(path, inner, args, mode)
                out["build"] = build
                if out["status"] == "invalid" and desc["kind"] == "disc":
                    redraw = out["message"]
                    break
                row = make_row(desc, meta, inner, int(free.sum()), out, v, after, f, free,
                               mode if remesh_column else None)  # fmt: skip
                row["seed_vertex"] = meta.get("seed_vertex")
                case_rows.append(row)
                print(format_row(row, remesh_column), flush=True)
            if redraw is None:
                rows += case_rows
                break
            if case_rows:
                print(f"# {desc['name']}: the rows above are superseded (seed redrawn)", flush=True)
            print(f"# {desc['name']}: seed {meta.get('seed_vertex')} invalid input ({redraw}): redrawn", flush=True)
            desc = dict(desc, attempt=meta["invalid"] + 1)
    print(f"# {len(rows)} solves in {time.perf_counter() - start:.0f} s")
    print("\n".join(summary(rows, inners, args.timeout, modes)))
    if args.json:
        with open(args.json, "w") as out:
            json.dump({"args": vars(args), "notes": notes, "rows": rows}, out, indent=1)


if __name__ == "__main__":
    main()
