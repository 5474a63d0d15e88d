"""Modelling scenarios: the add-on's fair_object with its defaults on selections a modeller makes on
Blender's primitives (subdivision surfaces, grids, poles of valence 32, n-gon caps, a torus,
Suzanne), run inside Blender:

    blender --background --factory-startup --python-exit-code 1 --python bench/blender_scenarios.py -- [build/addon]
    python3 bench/blender_scenarios.py -- [build/addon]      # the bpy module from PyPI

Prints one row per (scenario, inner fairness): how the run ended ("ok", or the exception
fair_object raised: NotConvergedError leaves the mesh unchanged, RegionError names what is
wrong with the selection), the selected faces, the vertices that moved, the seconds, and,
where the scenario has a known answer, the largest distance of the faired vertices from it
(the unit sphere). Every scenario starts from a fresh scene.
"""

import time

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import numpy as np

from geofair_dev.blender import add_subdivided_suzanne, disable_addon, enable_addon, face_centres, parse_args, positions


def fresh():
    bpy.ops.object.select_all(action="SELECT")
    bpy.ops.object.delete()


def subsurf(obj, levels):
    modifier = obj.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels = levels
    bpy.ops.object.modifier_apply(modifier=modifier.name)
    return obj


def subdivide(obj, cuts):
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.mesh.subdivide(number_cuts=cuts)
    bpy.ops.object.mode_set(mode="OBJECT")
    return obj


def set_positions(obj, co):
    obj.data.vertices.foreach_set("co", co.astype(np.float32).ravel())
    obj.data.update()
    return obj


def near(point, radius):
    return lambda c: np.linalg.norm(c - np.asarray(point), axis=1) < radius


def cube():
    bpy.ops.mesh.primitive_cube_add()
    return bpy.context.active_object


def rounded_box():
    return subsurf(cube(), 3)


def cube_grid():
    return subdivide(cube(), 9)


def cylinder(**kw):
    bpy.ops.mesh.primitive_cylinder_add(vertices=32, depth=2, **kw)
    return bpy.context.active_object


def trifan_cylinder():
    return cylinder(end_fill_type="TRIFAN")


def cut_cylinder():
    return subdivide(cylinder(), 4)


def above(z):
    return lambda c: c[:, 2] > z


def cone():
    bpy.ops.mesh.primitive_cone_add(vertices=32, depth=2)
    return subdivide(bpy.context.active_object, 6)


def bumped_grid():
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=60, y_subdivisions=60, size=2)
    obj = bpy.context.active_object
    co = positions(obj)
    co[:, 2] = 0.3 * np.exp(-((np.linalg.norm(co[:, :2], axis=1) / 0.2) ** 2))
    return set_positions(obj, co)


def uv_sphere():
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16)
    return bpy.context.active_object


def flattened_uv_sphere():
    obj = uv_sphere()
    co = positions(obj)
    co[co[:, 2] > 0.5, 2] = 0.5
    return set_positions(obj, co)


def torus():
    bpy.ops.mesh.primitive_torus_add()
    return bpy.context.active_object


def noisy_icosphere():
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=5)
    obj = bpy.context.active_object
    co = positions(obj) * (1 + 0.01 * np.random.default_rng(1).standard_normal(len(obj.data.vertices)))[:, None]
    return set_positions(obj, co)


# (name, mesh maker, selection by face centre, known answer: "sphere" or None)
SCENARIOS = [
    ("rounded box (cube, subsurf 3): corner", rounded_box, near((0.6, 0.6, 0.6), 0.6), None),
    ("rounded box: middle of a side", rounded_box, near((0, 0, 0.8), 0.5), None),
    ("rounded box: along an edge", rounded_box, near((0.7, 0, 0.7), 0.5), None),
    ("cube, 9 cuts: inside a face", cube_grid, lambda c: (c[:, 2] > 0.99) & (np.abs(c[:, :2]) < 0.7).all(1), None),
    ("cube, 9 cuts: around a corner (valence 3)", cube_grid, near((1, 1, 1), 0.9), None),
    ("cylinder: its n-gon cap", cylinder, above(0.99), None),
    ("cylinder, triangle-fan cap (valence 32)", trifan_cylinder, above(0.99), None),
    ("cylinder, 4 cuts: a band of the side (tube)", cut_cylinder, lambda c: np.abs(c[:, 2]) < 0.5, None),
    ("cone, 6 cuts: around the apex (valence 32)", cone, lambda c: c[:, 2] > 0.2, None),
    ("grid 60x60 with a bump: the bump", bumped_grid, lambda c: np.linalg.norm(c[:, :2], axis=1) < 0.5, None),
    ("UV sphere 32x16: cap at the pole", uv_sphere, lambda c: c[:, 2] > 0.5, "sphere"),
    ("UV sphere 32x16: pole cap flattened", flattened_uv_sphere, lambda c: c[:, 2] > 0.4, "sphere"),
    ("UV sphere 32x16: band at the equator", uv_sphere, lambda c: np.abs(c[:, 2]) < 0.3, "sphere"),
    ("UV sphere 32x16: patch on the side", uv_sphere, near((1, 0, 0), 0.6), "sphere"),
    ("Suzanne (subsurf 2): cheek", add_subdivided_suzanne, near((0.55, -0.55, -0.1), 0.25), None),
    ("Suzanne: top of the head", add_subdivided_suzanne, near((0, 0.1, 0.85), 0.35), None),
    ("Suzanne: chin", add_subdivided_suzanne, near((0, -0.75, -0.55), 0.25), None),
    ("Suzanne: nose", add_subdivided_suzanne, near((0, -0.9, -0.1), 0.2), None),
    ("torus: outer side", torus, near((1.25, 0, 0), 0.4), None),
    ("torus: inner side", torus, near((0.75, 0, 0), 0.3), None),
    ("icosphere 5 with 1% noise: patch", noisy_icosphere, near((0, 0, 1), 0.5), None),
]


def run(addon, make, select, answer, inner):
    fresh()
    obj = make()
    faces = select(face_centres(obj))
    before = positions(obj)
    start = time.perf_counter()
    try:
        addon.fair_object(obj, faces, inner_fairness=inner)
        status = "ok"
    except Exception as error:  # reported in the table: the point of the benchmark
        status = type(error).__name__
    seconds = time.perf_counter() - start
    after = positions(obj)
    moved = np.linalg.norm(after - before, axis=1) > 0
    error = ""
    if answer == "sphere" and moved.any():
        error = f"{np.abs(np.linalg.norm(after[moved], axis=1) - 1).max():.1e}"
    return status, int(faces.sum()), int(moved.sum()), seconds, error


def main():
    folder, _ = parse_args()
    addon = enable_addon(folder)
    print(f"Blender {bpy.app.version_string}; add-on from {folder}")
    print(f"{'scenario':46s} {'inner':9s} {'result':18s} {'faces':>6s} {'moved':>6s} {'s':>6s} {'off sphere':>10s}")
    for name, make, select, answer in SCENARIOS:
        for inner in ("uniform", "conformal"):
            status, faces, moved, seconds, error = run(addon, make, select, answer, inner)
            row = f"{name:46s} {inner:9s} {status:18s} {faces:6d} {moved:6d} {seconds:6.2f} {error:>10s}"
            print(row, flush=True)
    disable_addon()


main()
