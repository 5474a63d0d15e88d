"""The ``geofair`` command line: fill the holes of mesh files, or fair a region of one.

    geofair fill IN [IN ...] (-o OUT | --output-dir DIR) [--rim keep|trim] [--boundary g1|g0]
        [--edge-length L] [--max-hole-edges N] [--all-borders] [fair options] [--jobs N]
        [--report FILE.json] [--quiet]
    geofair fair IN --region FILE -o OUT [--remesh] [--boundary g1|g0] [fair options]
    python -m geofair ...   (the same, from the installed wheel)

Files: OBJ, PLY, OFF and STL, read and written by OpenMesh's IO (``geofair.read_mesh`` and
``geofair.write_mesh``): polygons are split into triangles; PLY and OFF vertex colours and
OBJ and PLY texture coordinates are kept, and interpolated onto the new vertices (harmonic
interpolation from the hole's loop). An output is written under a temporary name and renamed
at the end: a failure never leaves a partial file. With several inputs each is done on its
own (``--jobs N`` at once, each in its own process); a file that fails is reported and the
others are still written. Exit status: 0 when every file was written, 1 when one failed, 2
for a usage error. ``--report`` writes a JSON report: per file its status, the error, and
for fill one record per hole (loop vertex, method, converged, folded edges, removed faces).
"""

import argparse
import concurrent.futures
import json
import os
import sys
import time

import numpy as np

import geofair

# The fairing keywords of geofair.fair and geofair.fill_holes the command line passes on.
FAIR_OPTIONS = ("boundary", "inner_fairness", "outer_fairness", "iteration", "tolerance", "time_limit")


def _positive_length(text):
    """An argparse type: a finite length > 0 (a usage error otherwise)."""
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not (0.0 < value < float("inf")):
        raise argparse.ArgumentTypeError(f"must be a positive length, got {text!r}")
    return value


def _add_fair_options(parser):
    parser.add_argument("--boundary", choices=("g1", "g0"), default=None, help="boundary condition (default g1)")
    parser.add_argument(
        "--inner-fairness",
        dest="inner_fairness",
        choices=("uniform", "conformal", "conformal_intrinsic"),
        default=None,
        help="inner fairness (default uniform; see geofair.fair)",
    )
    parser.add_argument(
        "--outer-fairness",
        dest="outer_fairness",
        choices=("intrinsic", "bilaplacian"),
        default=None,
        help="outer fairness (default intrinsic; see geofair.fair)",
    )
    parser.add_argument(
        "--iteration", choices=("auto", "newton", "paper"), default=None, help="solver (default auto; see geofair.fair)"
    )
    parser.add_argument("--tolerance", type=float, default=None, help="residual tolerance (dimensionless)")
    parser.add_argument(
        "--time-limit", dest="time_limit", type=float, default=None, help="seconds per file (default automatic)"
    )
    parser.add_argument("--report", default=None, help="write a JSON report to this file")
    parser.add_argument("--jobs", type=int, default=1, help="files done at once, each in its own process")
    parser.add_argument("--quiet", action="store_true", help="print nothing but errors")


def build_parser():
    parser = argparse.ArgumentParser(
        prog="geofair", description="Intrinsic mesh fairing (Schneider & Kobbelt 2001) of mesh files."
    )
    parser.add_argument("--version", action="version", version=f"geofair {geofair.__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    fill = commands.add_parser("fill", help="fill the holes of mesh files")
    fill.add_argument("inputs", nargs="+", metavar="IN", help="OBJ, PLY, OFF or STL files")
    fill.add_argument("-o", "--output", default=None, help="the output file (one input)")
    fill.add_argument("--output-dir", default=None, help="folder for the outputs (same names as the inputs)")
    fill.add_argument("--rim", choices=("keep", "trim"), default="keep", help="trim: may remove a ragged rim's faces")
    fill.add_argument(
        "--edge-length",
        type=_positive_length,
        default=None,
        help="edge length of the fill (mesh units, > 0; default: the mean length of each hole's loop edges)",
    )
    fill.add_argument("--max-hole-edges", type=int, default=None, help="leave loops of more edges open")
    fill.add_argument("--all-borders", action="store_true", help="fill the outer borders of open meshes too")
    _add_fair_options(fill)
    fair = commands.add_parser("fair", help="fair a region of a mesh file")
    fair.add_argument("inputs", nargs=1, metavar="IN", help="OBJ, PLY, OFF or STL file")
    fair.add_argument("-o", "--output", required=True, help="the output file")
    fair.add_argument(
        "--region",
        required=True,
        help="the free vertices: a text file of vertex indices (whitespace or comma separated), or a .npy "
        "array of vertex indices, a vertex mask (n,) or a face mask (m,) of the file's faces",
    )
    fair.add_argument("--remesh", action="store_true", help="remesh the region before fairing")
    fair.description = (
        "Fair the region's free vertices (geofair.fair). The file's polygons are passed as polygon_ids, so "
        "uniform inner fairness runs over a quad file's polygon edges (geofair.fair's default, polygon_ids=None, "
        "over the triangles' edges)."
    )
    _add_fair_options(fair)
    return parser


class FileError(Exception):
    """A problem with one file, for the report (the message names the file)."""


def _options(args):
    return {name: getattr(args, name) for name in FAIR_OPTIONS if getattr(args, name, None) is not None}


def harmonic_values(vertices, faces, known, values, sweeps=500):
    """``values`` (n, k) at the rows ``known`` (n,) bool, the others interpolated over the graph of
    ``faces`` by Jacobi sweeps of the uniform Laplacian, started from the mean of the known ones."""
    values = np.asarray(values, float).copy()
    unknown = ~known
    if not unknown.any():
        return values
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    edges = edges[unknown[edges[:, 0]] | unknown[edges[:, 1]]]
    values[unknown] = values[known].mean(axis=0) if known.any() else 0.0
    degree = np.zeros(len(values))
    np.add.at(degree, edges[:, 0], 1.0)
    np.add.at(degree, edges[:, 1], 1.0)
    for _ in range(sweeps):
        total = np.zeros_like(values)
        np.add.at(total, edges[:, 0], values[edges[:, 1]])
        np.add.at(total, edges[:, 1], values[edges[:, 0]])
        values[unknown] = total[unknown] / np.maximum(degree[unknown, None], 1.0)
    return values


def _carried(mesh, vertices, faces):
    """The file's colours and texture coordinates for the result's rows (new rows interpolated)."""
    n = len(mesh["vertices"])
    known = np.zeros(len(vertices), bool)
    known[:n] = True
    out = {}
    for name in ("colors", "texcoords"):
        values = mesh.get(name)
        if values is None:
            continue
        padded = np.zeros((len(vertices), values.shape[1]))
        padded[:n] = values
        filled = harmonic_values(vertices, faces, known, padded)
        out[name] = np.clip(np.rint(filled), 0, 255).astype(np.uint8) if name == "colors" else filled
    return out


def _compact(vertices, faces, drop, carried):
    """The mesh without the rows ``drop`` (in no face), faces renumbered."""
    if len(drop) == 0:
        return vertices, faces, carried
    keep = np.ones(len(vertices), bool)
    keep[drop] = False
    index = np.cumsum(keep) - 1
    return vertices[keep], index[faces], {k: v[keep] for k, v in carried.items()}


FORMATS = (".obj", ".ply", ".off", ".stl")


def _check_format(path):
    if os.path.splitext(path)[1].lower() not in FORMATS:
        raise FileError(f"{path}: unknown mesh format (expected .obj, .ply, .off or .stl)")


def _read(path):
    try:
        return geofair.read_mesh(path)
    except ValueError as error:
        raise FileError(str(error).replace("read_mesh: ", "")) from error


def _write(path, vertices, faces, carried):
    try:
        geofair.write_mesh(path, vertices, faces, **carried)
    except (ValueError, OSError) as error:
        raise FileError(str(error).replace("write_mesh: ", "")) from error


def hole_report(hole):
    """One hole of a geofair.FillResult as a JSON-ready dict."""
    return {
        "vertex": int(hole.loop[0]) if len(hole.loop) else None,
        "loop_vertices": len(hole.loop),
        "method": hole.method,
        "filled": bool(hole.filled),
        "converged": bool(hole.converged),
        "folds": int(hole.folds),
        "new_vertices": int(hole.new_vertices),
        "new_faces": int(hole.new_faces),
        "removed_faces": [int(f) for f in hole.removed_faces],
        "reason": hole.reason,
        "attempts": [{k: a[k] for k in ("method", "converged", "folds", "seconds", "message")} for a in hole.attempts],
    }


def hole_line(hole):
    """One line per hole for the terminal."""
    if not hole["filled"]:
        return f"  hole at vertex {hole['vertex']}: left open, {hole['reason']}"
    line = f"  hole at vertex {hole['vertex']} ({hole['loop_vertices']} edges): {hole['method']}"
    line += ", converged" if hole["converged"] else ", not converged"
    line += f", {hole['folds']} folded edge{'s' if hole['folds'] != 1 else ''}, {hole['new_vertices']} new vertices"
    if hole["removed_faces"]:
        line += f", removed faces {', '.join(map(str, hole['removed_faces']))}"
    return line


def fill_file(job):
    """Fill the holes of one file; a report dict (status "ok" or "error")."""
    source, target, settings = job
    start = time.perf_counter()
    report = {"input": source, "output": target, "command": "fill"}
    try:
        _check_format(target)
        mesh = _read(source)
        options = dict(settings["options"])
        try:
            r = geofair.fill_holes(
                mesh["vertices"],
                mesh["faces"],
                rim=settings["rim"],
                target_edge_length=settings["edge_length"],
                max_hole_edges=settings["max_hole_edges"],
                keep_outer_borders=not settings["all_borders"],
                progress=settings.get("progress"),
                **options,
            )
        except (ValueError, RuntimeError) as error:
            raise FileError(f"{source}: {error}") from error
        vertices, faces = np.asarray(r.vertices), np.asarray(r.faces)
        carried = _carried(mesh, vertices, faces)
        vertices, faces, carried = _compact(vertices, faces, np.asarray(r.unreferenced, np.int64), carried)
        _write(target, vertices, faces, carried)
        report.update(
            status="ok",
            message=r.message,
            converged=bool(r.converged),
            folds=int(r.folds),
            vertices=[len(mesh["vertices"]), len(vertices)],
            faces=[len(mesh["faces"]), len(faces)],
            removed_faces=[int(f) for f in r.removed_faces],
            carried=sorted(carried),
            holes=[hole_report(h) for h in r.holes],
        )
    except FileError as error:
        report.update(status="error", error=str(error))
    report["seconds"] = round(time.perf_counter() - start, 3)
    return report


def read_region(path, n_vertices, faces):
    """The free vertices (n,) bool from a region file (see the fair command's --region)."""
    try:
        if path.endswith(".npy"):
            data = np.load(path, allow_pickle=False)
        else:
            with open(path) as file:
                text = file.read().replace(",", " ")
            data = np.array([int(token) for token in text.split()], dtype=np.int64)
    except (OSError, ValueError) as error:
        raise FileError(f"{path}: cannot be read as a region ({error})") from error
    data = np.asarray(data)
    if data.dtype == bool:
        if len(data) == n_vertices:
            return data
        if len(data) == len(faces):  # a face mask: the vertices whose every face is in it
            outside = np.zeros(n_vertices, bool)
            outside[faces[~data].ravel()] = True
            free = np.zeros(n_vertices, bool)
            free[faces[data].ravel()] = True
            return free & ~outside
        raise FileError(f"{path}: a mask of {len(data)} entries fits neither the {n_vertices} vertices nor the "
                        f"{len(faces)} faces")  # fmt: skip
    if data.ndim != 1 or not np.issubdtype(data.dtype, np.integer):
        raise FileError(f"{path}: expected vertex indices or a boolean mask")
    if len(data) and (data.min() < 0 or data.max() >= n_vertices):
        raise FileError(f"{path}: a vertex index is out of range (the mesh has {n_vertices} vertices)")
    free = np.zeros(n_vertices, bool)
    free[data] = True
    return free


def fair_file(job):
    """Fair the region of one file; a report dict."""
    source, target, settings = job
    start = time.perf_counter()
    report = {"input": source, "output": target, "command": "fair"}
    try:
        _check_format(target)
        mesh = _read(source)
        free = read_region(settings["region"], len(mesh["vertices"]), mesh["faces"])
        try:
            r = geofair.fair(
                mesh["vertices"],
                mesh["faces"],
                free,
                remesh=settings["remesh"],
                polygon_ids=mesh["polygon"],
                progress=settings.get("progress"),
                **settings["options"],
            )
        except (ValueError, RuntimeError) as error:
            raise FileError(f"{source}: {error}") from error
        if not r.converged:
            raise FileError(f"{source}: {r.message}; nothing written")
        vertices, faces = np.asarray(r.vertices), np.asarray(r.faces)
        carried = _carried(mesh, vertices, faces) if len(vertices) > len(mesh["vertices"]) else {}
        if len(vertices) == len(mesh["vertices"]):
            carried = {k: mesh[k] for k in ("colors", "texcoords") if mesh.get(k) is not None}
        vertices, faces, carried = _compact(vertices, faces, np.asarray(r.unreferenced, np.int64), carried)
        _write(target, vertices, faces, carried)
        report.update(status="ok", message=r.message, converged=True, folds=int(r.folds),
                      free_vertices=int(free.sum()), vertices=[len(mesh["vertices"]), len(vertices)])  # fmt: skip
    except FileError as error:
        report.update(status="error", error=str(error))
    report["seconds"] = round(time.perf_counter() - start, 3)
    return report


def _progress_line(name):
    """A progress callback that redraws one status line on a terminal."""
    if not sys.stderr.isatty():
        return None
    last = [0.0]

    def progress(iteration, residual):
        now = time.perf_counter()
        if now - last[0] > 0.2:
            last[0] = now
            print(f"\r{name}: iteration {iteration}, residual {residual:.2e}   ", end="", file=sys.stderr, flush=True)
        return True

    return progress


def _targets(parser, args):
    if args.output and len(args.inputs) > 1:
        parser.error("-o/--output takes one input; give --output-dir for several")
    if args.output:
        return [args.output]
    if not args.output_dir:
        parser.error("give -o OUT (one input) or --output-dir DIR")
    targets = [os.path.join(args.output_dir, os.path.basename(path)) for path in args.inputs]
    twice = sorted({t for t in targets if targets.count(t) > 1})
    if twice:
        parser.error(f"inputs of the same name would overwrite each other in --output-dir: {', '.join(twice)}")
    os.makedirs(args.output_dir, exist_ok=True)
    return targets


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error("--jobs must be at least 1")
    if args.command == "fill":
        targets = _targets(parser, args)
        settings = {"rim": args.rim, "edge_length": args.edge_length, "max_hole_edges": args.max_hole_edges,
                    "all_borders": args.all_borders, "options": _options(args)}  # fmt: skip
        work = fill_file
    else:
        targets = [args.output]
        settings = {"region": args.region, "remesh": args.remesh, "options": _options(args)}
        work = fair_file
    jobs = [(source, target, dict(settings)) for source, target in zip(args.inputs, targets, strict=True)]
    reports = []
    total = len(jobs)

    def done(report):
        reports.append(report)
        if sys.stderr.isatty():
            print("\r", end="", file=sys.stderr)
        if report["status"] == "error":
            print(f"geofair {args.command}: error: {report['error']}", file=sys.stderr)
        elif not args.quiet:
            print(f"[{len(reports)}/{total}] {report['input']} -> {report['output']}: {report['message']} "
                  f"({report['seconds']:.2f} s)")  # fmt: skip
            for hole in report.get("holes", []):
                print(hole_line(hole))

    if args.jobs == 1 or total == 1:
        for job in jobs:
            if not args.quiet:
                job[2]["progress"] = _progress_line(os.path.basename(job[0]))
            done(work(job))
    else:
        with concurrent.futures.ProcessPoolExecutor(max_workers=args.jobs) as pool:
            for report in pool.map(work, jobs):
                done(report)
    if args.report:
        temporary = f"{args.report}.partial"
        with open(temporary, "w") as file:
            json.dump({"command": args.command, "files": reports}, file, indent=1)
        os.replace(temporary, args.report)
    return 1 if any(r["status"] == "error" for r in reports) else 0


if __name__ == "__main__":
    sys.exit(main())
