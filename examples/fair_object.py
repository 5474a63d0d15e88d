"""Fair regions of a mesh from a script, in Object Mode, with ``geometric_fairing.fair_object``.

    blender --background --factory-startup --python-exit-code 1 \\
        --python examples/fair_object.py -- --addon build/addon [--out out/fair_object.blend]

(or ``python3 examples/fair_object.py -- --addon build/addon`` with the ``bpy``
module). ``--addon`` takes the add-on from a folder of the repository's build,
found by its development package (geofair_dev in dev/, which scripts/setup.sh
installs). Without ``--addon`` the add-on must be installed: a legacy add-on is
imported as ``geometric_fairing``, an extension as
``bl_ext.<repository>.geometric_fairing``.

The script builds Suzanne subdivided twice and fairs three regions, the three
ways to give one:

1. a vertex group ("Brow": the faces all of whose vertices have a non-zero weight),
2. a boolean array over the faces (the cheek), with a pin vertex group inside it,
3. the selected faces (region=None), with a progress callback that gives up
   after a time limit: a cancelled run leaves the mesh as it was.

``fair_object`` returns a FairingReport: free_vertices, iterations, residual,
converged, cancelled, seconds, uv_before/uv_after (conformal distortion of the
UV map: mean, max). It raises ValueError for a region that cannot be faired and
RuntimeError when the solver fails; the mesh is then unchanged too.
"""

import argparse
import importlib
import pathlib
import sys
import time

import bpy
import numpy as np


def parse_args():
    parser = argparse.ArgumentParser(prog="fair_object.py")
    parser.add_argument("--addon", type=pathlib.Path, help="folder that holds the geometric_fairing package")
    parser.add_argument("--out", type=pathlib.Path, help="save the scene to this .blend file")
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else [])


def import_addon(folder):
    """The geometric_fairing package: from ``folder``, or the installed legacy add-on or extension."""
    if folder is not None:  # the repository's build: its development package knows where (dev/)
        from geofair_dev.paths import import_addon

        return import_addon(folder)
    repositories = getattr(bpy.context.preferences, "extensions", None)  # Blender 4.2+
    names = ["geometric_fairing"] + [f"bl_ext.{repo.module}.geometric_fairing" for repo in repositories.repos or []]
    for name in names if repositories is not None else names[:1]:
        try:
            return importlib.import_module(name)
        except ImportError:
            continue
    raise SystemExit("geometric_fairing is not installed: pass --addon build/addon")


def suzanne():
    """Blender's Suzanne with a Subdivision Surface modifier (level 2) applied; she has a UV map."""
    bpy.ops.mesh.primitive_monkey_add()
    obj = bpy.context.active_object
    modifier = obj.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels = 2
    bpy.ops.object.modifier_apply(modifier=modifier.name)
    return obj


def positions(obj):
    co = np.empty(3 * len(obj.data.vertices))
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


def face_centres(obj):
    centres = np.empty(3 * len(obj.data.polygons))
    obj.data.polygons.foreach_get("center", centres)
    return centres.reshape(-1, 3)


def near(points, centre, radius):
    return np.linalg.norm(points - np.asarray(centre), axis=1) < radius


def print_report(title, report):
    uv = "-"
    if report.uv_before is not None:
        after = f"{report.uv_after.mean:.4f}" if report.uv_after is not None else "(unchanged)"
        uv = f"{report.uv_before.mean:.4f} -> {after}"
    state = "cancelled" if report.cancelled else ("converged" if report.converged else "NOT converged")
    print(
        f"{title:<34} {report.free_vertices:>5} {report.iterations:>6} {report.residual:>10.3g} "
        f"{report.seconds:>7.2f} {state:<13} {uv}"
    )


def main():
    args = parse_args()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    geometric_fairing = import_addon(args.addon)
    obj = suzanne()
    print(f"Blender {bpy.app.version_string}; {obj.name}: {len(obj.data.vertices)} vertices, Object Mode")
    print(f"{'region':<34} {'free':>5} {'iter.':>6} {'residual':>10} {'time/s':>7} {'state':<13} UV σ1/σ2 mean")

    # 1. A vertex group defines the region.
    brow = obj.vertex_groups.new(name="Brow")
    brow.add(np.flatnonzero(near(positions(obj), (0.4, -0.7, 0.72), 0.27)).tolist(), 1.0, "REPLACE")
    report = geometric_fairing.fair_object(obj, region="Brow", inner_fairness="conformal")
    print_report("vertex group 'Brow'", report)

    # 2. A boolean array over the faces, with pinned vertices inside the region.
    cheek = near(face_centres(obj), (0.55, -0.6, 0.0), 0.3)
    pins = obj.vertex_groups.new(name="Pins")  # a few vertices in the middle of the cheek keep their place
    middle = positions(obj)[np.argmin(np.linalg.norm(positions(obj) - (0.55, -0.6, 0.0), axis=1))]
    pins.add(np.flatnonzero(near(positions(obj), middle, 0.04)).tolist(), 1.0, "REPLACE")
    report = geometric_fairing.fair_object(obj, region=cheek, pin_group="Pins", inner_fairness="conformal")
    print_report(f"face mask, {report.pinned_vertices} pinned", report)

    # 3. The selected faces, with a time limit through the progress callback.
    obj.data.polygons.foreach_set("select", near(face_centres(obj), (0.0, -0.2, 0.85), 0.35))
    before = positions(obj)
    deadline = time.perf_counter() + 1e-9  # so short that the first progress call gives up

    def give_up_at_deadline(iteration, residual):
        return time.perf_counter() < deadline

    report = geometric_fairing.fair_object(obj, tolerance=1e-9, progress=give_up_at_deadline)
    print_report("selected faces, time limit", report)
    assert report.cancelled and np.array_equal(positions(obj), before), "a cancelled run changed the mesh"

    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        bpy.ops.wm.save_as_mainfile(filepath=str(args.out.resolve()))
        print(f"saved {args.out}")
    print("fair_object example: done")


main()
