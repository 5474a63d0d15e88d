"""The add-on's own cost around the native solve (the Blender round trip) on sphere caps of 100,000 free vertices.

    blender --background --factory-startup --python-exit-code 1 \\
        --python bench/blender_roundtrip.py -- [n_free ...] [--addon build/addon]
        [--max-iterations 100] [--tolerance 1e-4] [--iteration auto|newton|paper]
        [--no-uv] [--profile] [--cache /tmp/geofair_bench_scenes]

or the same arguments with the ``bpy`` module from PyPI: ``python3 bench/blender_roundtrip.py
[n_free ...] [...]``.

Scene (default n_free 100000): ``geofair_dev.scenes.sphere_cap(n_free, irregular=True, seed=1,
boundary_rings=2)`` disturbed by ``disturbed(seed=2, amplitude=0.1)``, loaded from the .npz
cache of bench/speed.py (geofair_dev.caps; generated there if missing), as a mesh object with a UV map (the
x, y projection; ``--no-uv``: none) and the faces with a free vertex selected. The add-on
then finds the free vertices itself (those all of whose faces are selected: the scene's,
about 100k) and the boundary normals from the unselected faces.

Two paths, each on a fresh object:

- Edit Mode (BMesh): ``bpy.ops.mesh.geometric_fairing('EXEC_DEFAULT', True, ...)`` after one
  ``bpy.ops.ed.undo_push()``, as a user (or the redo panel) runs it; the time includes the
  undo step Blender pushes after the operator.
- Object Mode: ``geometric_fairing.fair_object(obj)`` (``foreach_get``/``foreach_set``), as
  a ``blender --background`` pipeline runs it.

For each it prints the wall time, the time inside ``geofair.fair`` (the solve: the module's
``fair`` is wrapped by this script, the add-on is not changed), and the add-on's overhead =
wall time − solve, in seconds and as a share of the solve, broken down from the add-on's
own step timings (``FairingReport.timings``) and wrappers around its functions.

The solve can be bounded by ``--max-iterations`` (per level; default 100). At 100k free
vertices ``iteration="auto"`` runs Newton's method, which converges within it (32 steps,
about 27-29 s on a 2-core machine); with ``--iteration paper`` the bound stops the paper's
iteration unconverged, and then the printed share of the solve is an upper bound on the
share of a converged one. The overhead does not depend on the solver (it is the same work on
the same mesh): the absolute seconds are the figure to compare. ``--profile`` adds a
cProfile of the Edit Mode operator, in a run of its own with a one-iteration solve.

Not part of the test run; it never fails on time. The machine may be shared: rerun when a
figure matters.
"""

import argparse
import cProfile
import os
import pathlib
import pstats
import sys
import time

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import numpy as np

from geofair_dev import blender as helpers  # enables the add-on as Preferences does
from geofair_dev import caps, paths  # caps: the scene cache of bench/speed.py


def parse_args():
    if "--" in sys.argv:
        argv = sys.argv[sys.argv.index("--") + 1 :]
    elif sys.argv and pathlib.Path(sys.argv[0]).resolve() == pathlib.Path(__file__).resolve():  # python3 this.py
        argv = sys.argv[1:]
    else:  # Blender's own arguments
        argv = []
    parser = argparse.ArgumentParser(prog="blender_roundtrip.py", description=__doc__.splitlines()[0])
    parser.add_argument("sizes", nargs="*", type=int, default=[100000], help="free vertices of the caps")
    parser.add_argument("--addon", type=pathlib.Path, default=paths.BUILT_ADDON)
    parser.add_argument("--max-iterations", type=int, default=100, help="bounds the solve (per level)")
    parser.add_argument("--tolerance", type=float, default=1e-4)
    parser.add_argument("--iteration", default=None, help="auto, newton or paper (default: the add-on's, auto)")
    parser.add_argument("--no-uv", action="store_true", help="no UV map (skips the UV distortion figures)")
    parser.add_argument("--profile", action="store_true", help="cProfile of the Edit Mode operator")
    parser.add_argument("--cache", default="/tmp/geofair_bench_scenes")
    return parser.parse_args(argv)


# -- timing the add-on from outside ----------------------------------------------------------


class Clock:
    """Seconds spent in wrapped functions, by name, and the last value one of them returned."""

    def __init__(self):
        self.seconds = {}
        self.returned = {}

    def wrap(self, owner, name, label):
        function = getattr(owner, name)

        def timed(*args, **kwargs):
            start = time.perf_counter()
            try:
                value = function(*args, **kwargs)
            finally:
                self.seconds[label] = self.seconds.get(label, 0.0) + time.perf_counter() - start
            self.returned[label] = value
            return value

        setattr(owner, name, timed)
        return lambda: setattr(owner, name, function)

    def get(self, label):
        return self.seconds.get(label, 0.0)


def instrument(addon, clock):
    """Wrap the solve and the add-on's steps; return a function that undoes it."""
    fairing = addon.fairing
    undo = [
        clock.wrap(addon.native.geofair, "fair", "solve"),
        clock.wrap(fairing.FairingRun, "__init__", "prepare"),
        clock.wrap(fairing.FairingRun, "finish", "finish"),
        clock.wrap(fairing, "store_last_runs", "last runs"),  # the operator's (calls store_last_run)
        clock.wrap(fairing, "store_last_run", "last run"),  # fair_object's
        clock.wrap(addon.overlays, "refresh_curvature", "curvature"),
    ]
    # Blender calls a registered class's execute with as many arguments as its code declares.
    operator = addon.operators.MESH_OT_geometric_fairing
    execute = operator.execute

    def timed_execute(self, context):
        start = time.perf_counter()
        try:
            return execute(self, context)
        finally:
            clock.seconds["execute"] = clock.get("execute") + time.perf_counter() - start

    operator.execute = timed_execute
    undo.append(lambda: setattr(operator, "execute", execute))
    return lambda: [restore() for restore in reversed(undo)]


# -- the scene -------------------------------------------------------------------------------


def cap_object(cache, n, uv):
    """The disturbed cap with about ``n`` free vertices as a mesh object, faces with a free vertex selected."""
    vertices, faces, free, _ = caps.load_scene(cache, n)
    mesh = bpy.data.meshes.new(f"cap{n}")
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", vertices.astype(np.float32).ravel())
    mesh.loops.add(faces.size)
    mesh.loops.foreach_set("vertex_index", faces.astype(np.int32).ravel())
    mesh.polygons.add(len(faces))
    mesh.polygons.foreach_set("loop_start", np.arange(0, faces.size, 3, dtype=np.int32))
    if bpy.app.version < (4, 0, 0):
        mesh.polygons.foreach_set("loop_total", np.full(len(faces), 3, dtype=np.int32))
    mesh.update(calc_edges=True)
    if mesh.validate():
        raise RuntimeError("the cap mesh was invalid")
    if uv:
        layer = mesh.uv_layers.new(name="UVMap")
        layer.data.foreach_set("uv", vertices[faces.ravel(), :2].astype(np.float32).ravel())
    selected = free[faces].any(axis=1)
    chosen = np.zeros(len(vertices), dtype=bool)
    chosen[faces[selected].ravel()] = True
    mesh.polygons.foreach_set("select", selected)
    mesh.vertices.foreach_set("select", chosen)
    edges = np.empty(2 * len(mesh.edges), dtype=np.int32)
    mesh.edges.foreach_get("vertices", edges)
    mesh.edges.foreach_set("select", chosen[edges.reshape(-1, 2)].all(axis=1))
    obj = bpy.data.objects.new(mesh.name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj, int(free.sum())


def remove(obj):
    if obj.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    mesh = obj.data
    bpy.data.objects.remove(obj)
    bpy.data.meshes.remove(mesh)


# -- the runs --------------------------------------------------------------------------------


def options(args):
    # The result is written (and the write timed) also where the bounded solve stops unconverged.
    given = {"max_iterations": args.max_iterations, "tolerance": args.tolerance, "keep_unconverged": True}
    if args.iteration is not None:
        given["iteration"] = args.iteration.upper()
    return given


def edit_mode_run(addon, obj, args):
    """The operator in Edit Mode as a user runs it; ``(wall seconds, Clock)``."""
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bpy.ops.ed.undo_push(message="before fairing")
    clock = Clock()
    restore = instrument(addon, clock)
    try:
        start = time.perf_counter()
        result = bpy.ops.mesh.geometric_fairing("EXEC_DEFAULT", True, **options(args))
        wall = time.perf_counter() - start
    finally:
        restore()
    if result != {"FINISHED"}:
        raise RuntimeError(f"the operator returned {result}: {bpy.context.window_manager.geometric_fairing.last_run}")
    # The undo step alone, for reference: what Blender's undo push costs on this mesh in Edit Mode.
    start = time.perf_counter()
    bpy.ops.ed.undo_push(message="reference")
    clock.seconds["undo push alone"] = time.perf_counter() - start
    return wall, clock


def profile_edit_mode(addon, args, n):
    """cProfile of the operator in Edit Mode with a one-iteration solve (a run apart: profiling slows Python)."""
    obj, _ = cap_object(args.cache, n, uv=not args.no_uv)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bpy.ops.ed.undo_push(message="before fairing")
    profile = cProfile.Profile()
    profile.enable()
    bpy.ops.mesh.geometric_fairing("EXEC_DEFAULT", True, **dict(options(args), max_iterations=1))
    profile.disable()
    print(f"\ncProfile of the operator in Edit Mode, max_iterations=1, cap of {len(obj.data.vertices)} vertices:")
    pstats.Stats(profile).sort_stats("tottime").print_stats(20)
    remove(obj)


def object_mode_run(addon, obj, args):
    """``fair_object`` in Object Mode (foreach_get/foreach_set); ``(wall seconds, Clock)``."""
    clock = Clock()
    restore = instrument(addon, clock)
    try:
        start = time.perf_counter()
        report = addon.fair_object(obj, **options(args))
        wall = time.perf_counter() - start
    finally:
        restore()
    clock.returned["finish"] = report
    return wall, clock


def print_breakdown(title, wall, clock, edit):
    report = clock.returned["finish"]
    t = report.timings
    solve = clock.get("solve")
    result = clock.returned["solve"]
    print(
        f"{title}: {report.free_vertices} free vertices; bounded solve: iteration {result.iteration}, "
        f"{report.iterations} iterations (per level {'/'.join(map(str, report.iterations_per_level))}), "
        f"residual {report.residual:.3g}, {'converged' if report.converged else 'NOT converged'}"
    )
    uv_figures = t["uv"] - t["uv_read"]
    rows = [
        ("read mesh (foreach_get)" + (" after update_from_editmode" if edit else ""), t["read"]),
        ("region (selection -> free, boundary normals)", t["region"]),
        ("UVs read (foreach_get" + (" of a to_mesh copy)" if edit else ")"), t["uv_read"]),
        ("UV distortion before and after", uv_figures),
        ("write positions" + (" (BMesh, normals, update_edit_mesh)" if edit else " (foreach_set)"), t["write"]),
        ("panel figures, curvature colours", clock.get("last runs" if edit else "last run") + clock.get("curvature")),
    ]
    accounted = sum(seconds for _, seconds in rows)
    inside = clock.get("execute") if edit else wall
    rows.append(("other Python of the add-on (options, report)", inside - solve - accounted))
    if edit:
        rows.append(("operator call outside execute (undo push)", wall - clock.get("execute")))
    overhead = wall - solve
    print(f"  {'step':<52}{'seconds':>9}{'of solve':>10}")
    for name, seconds in rows:
        print(f"  {name:<52}{seconds:>9.3f}{seconds / solve:>10.1%}")
    print(f"  {'add-on overhead = wall time - solve':<52}{overhead:>9.3f}{overhead / solve:>10.1%}")
    print(f"  {'native solve (geofair.fair, bounded)':<52}{solve:>9.3f}")
    print(f"  {'wall time':<52}{wall:>9.3f}")
    if edit:
        print(f"  (reference: bpy.ops.ed.undo_push() alone after the run: {clock.get('undo push alone'):.3f} s)")


def main():
    args = parse_args()
    addon = helpers.enable_addon(args.addon.resolve())
    print(
        f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {args.addon}; "
        f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}"
    )
    print(
        f"solve bounded by max_iterations={args.max_iterations} per level, tolerance {args.tolerance:g}, "
        f"iteration {args.iteration or 'auto (the default)'}: where the solve stops unconverged, the overhead's "
        f"share of a converged solve is smaller than the share printed"
    )
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for n in args.sizes:
        if args.profile:
            profile_edit_mode(addon, args, n)
        for edit in (True, False):
            obj, scene_free = cap_object(args.cache, n, uv=not args.no_uv)
            vertices = len(obj.data.vertices)
            if edit:
                wall, clock = edit_mode_run(addon, obj, args)
                title = "Edit Mode, bpy.ops.mesh.geometric_fairing"
            else:
                wall, clock = object_mode_run(addon, obj, args)
                title = "Object Mode, fair_object"
            uv = "no UV map" if args.no_uv else "UV map"
            print(f"\ncap of {vertices} vertices ({scene_free} free in the scene), {uv}")
            print_breakdown(title, wall, clock, edit)
            remove(obj)
    helpers.disable_addon()


main()
