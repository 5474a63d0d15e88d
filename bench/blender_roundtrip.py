"""Time of the Blender round trip of the add-on against the native solve, on a region of about 100,000 vertices.

    blender --background --factory-startup --python-exit-code 1 \\
        --python bench/blender_roundtrip.py -- --addon build/addon [--subdivisions 4] \\
        [--outer bilaplacian|intrinsic] [--max-iterations N]

(or ``python3 bench/blender_roundtrip.py -- --addon build/addon`` with the ``bpy`` module).

Suzanne subdivided ``--subdivisions`` times (4: 126,000 vertices), in Edit Mode, with
the faces of her head above the chin selected (her eyes, separate closed parts, left
out). Prints, for one :class:`FairingRun` as the operator makes it: reading the mesh
(``update_from_editmode`` and ``foreach_get``), building the region, the UV distortion
figures, the native solve and writing the positions back into the BMesh; then the
add-on's overhead as a share of the solve, and the same for the operator run end to end
(its time minus the solve it reports). For reference, in the same process: reading the
positions and UVs element by element from the BMesh, as the add-on did before.

Not part of the test run; it never fails on time.
"""

import argparse
import importlib
import pathlib
import sys
import time

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import bmesh
import numpy as np


def parse_args():
    parser = argparse.ArgumentParser(prog="blender_roundtrip.py")
    parser.add_argument("--addon", type=pathlib.Path, required=True, help="folder holding geometric_fairing")
    parser.add_argument("--subdivisions", type=int, default=4)
    parser.add_argument("--outer", default="BILAPLACIAN", choices=["BILAPLACIAN", "INTRINSIC"], type=str.upper)
    parser.add_argument("--max-iterations", type=int, default=3, help="iterations of intrinsic fairing")
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else [])


def suzanne(subdivisions):
    bpy.ops.mesh.primitive_monkey_add()
    obj = bpy.context.active_object
    modifier = obj.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels = subdivisions
    bpy.ops.object.modifier_apply(modifier=modifier.name)
    return obj


def select_head(obj, addon):
    """Select the faces of the largest part (the head, not the eyes) above the chin, in Object Mode."""
    mesh = obj.data
    corners = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", corners)
    starts = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_start", starts)
    totals = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_total", totals)
    following = np.arange(len(corners)) + 1
    ends = starts + totals
    following[ends - 1] = starts  # the next corner around each face
    part = addon.region.connected_parts(len(mesh.vertices), np.stack([corners, corners[following]], axis=1))
    head = np.bincount(part).argmax()
    centres = np.empty(3 * len(mesh.polygons))
    mesh.polygons.foreach_get("center", centres)
    return (part[corners[starts]] == head) & (centres.reshape(-1, 3)[:, 2] > -0.45)


def select(obj, selected):
    """In Edit Mode (Face Select), select exactly the faces ``selected``."""
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bm = bmesh.from_edit_mesh(obj.data)
    for element in (*bm.verts, *bm.edges):
        element.select = False
    for face, chosen in zip(bm.faces, selected.tolist(), strict=True):
        face.select = chosen
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)


def reference_read(obj):
    """The add-on's former Edit Mode reading: positions and UVs element by element from the BMesh."""
    bm = bmesh.from_edit_mesh(obj.data)
    start = time.perf_counter()
    np.array([v.co[:] for v in bm.verts], dtype=np.float64)
    layer = bm.loops.layers.uv.active
    np.array([loop[layer].uv[:] for face in bm.faces for loop in face.loops], dtype=np.float64)
    return time.perf_counter() - start


def main():
    args = parse_args()
    sys.path.insert(0, str(args.addon.resolve()))
    addon = importlib.import_module("geometric_fairing")
    addon.register()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {args.addon}")
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    obj = suzanne(args.subdivisions)
    head = select_head(obj, addon)
    bpy.ops.object.mode_set(mode="EDIT")
    select(obj, head)
    print(f"Suzanne subdivided {args.subdivisions}x: {len(obj.data.vertices)} vertices, {head.sum()} faces selected")
    options = addon.FairingOptions(
        outer_fairness=args.outer, max_iterations=args.max_iterations, levels=1, tolerance=1e-12
    )

    start = time.perf_counter()
    run = addon.fairing.FairingRun(obj, options)
    prepared = time.perf_counter() - start
    run.solve()
    start = time.perf_counter()
    report = run.finish()
    finished = time.perf_counter() - start
    if run.error is not None:
        raise run.error
    t = report.timings
    overhead = prepared + finished
    print(f"free vertices {report.free_vertices}, outer {args.outer.lower()}, {report.iterations} iterations")
    print(f"{'step':<34}{'seconds':>9}{'of solve':>10}")
    for name, seconds in (
        ("read mesh (foreach_get)", t["read"]),
        ("region (selection -> free, normals)", t["region"]),
        ("UVs read (BMesh, region's corners)", t["uv_read"]),
        ("UV distortion before and after", t["uv"] - t["uv_read"]),
        ("write positions (BMesh)", t["write"]),
        ("add-on overhead, all steps", overhead),
        ("native solve", t["solve"]),
    ):
        print(f"{name:<34}{seconds:>9.3f}{seconds / t['solve']:>9.1%}")

    select(obj, head)
    start = time.perf_counter()
    result = bpy.ops.mesh.geometric_fairing(
        outer_fairness=args.outer, max_iterations=args.max_iterations, levels=1, tolerance=1e-12
    )
    total = time.perf_counter() - start
    solve = bpy.context.window_manager.geometric_fairing.last_run.seconds
    print(
        f"operator {result}: {total:.3f} s, solve {solve:.3f} s, everything else {total - solve:.3f} s "
        f"= {(total - solve) / solve:.1%} of the solve"
    )
    reference = reference_read(obj)
    print(
        f"reference: reading positions and UVs element by element from the BMesh {reference:.3f} s, "
        f"{reference / t['read']:.1f}x the add-on's read"
    )
    bpy.ops.object.mode_set(mode="OBJECT")
    addon.unregister()


main()
