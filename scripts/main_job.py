"""Main job: fair Suzanne's brow with the Geometric Fairing add-on and show the result.

    blender --background --factory-startup --python-exit-code 1 \\
        --python scripts/main_job.py -- --addon build/addon --out out

Builds Blender's Suzanne subdivided twice (Subdivision Surface modifier,
applied), selects the faces around her left brow, runs the operator and writes

    out/suzanne_faired.blend   the scene: faired Suzanne, a hidden copy of the original
    out/suzanne_faired.obj     the faired mesh
    out/before_after.png       Workbench renders before | after, faired region tinted
"""

import argparse
import pathlib
import sys
import time

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import bmesh
import numpy as np
from mathutils import Vector

from geofair_dev import paths
from geofair_dev.blender import add_subdivided_suzanne

REGION_CENTRE, REGION_RADIUS = np.array([0.45, -0.72, 0.62]), 0.3  # Suzanne's left brow
RESOLUTION = (640, 560)


def parse_args():
    """Options after ``--`` on the command line."""
    parser = argparse.ArgumentParser(prog="main_job.py")
    parser.add_argument(
        "--addon",
        type=pathlib.Path,
        default=pathlib.Path("build/addon"),
        help="folder that holds the geometric_fairing add-on",
    )
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("out"), help="output folder")
    # Suzanne carries a UV map, so the texture-preserving inner fairness by default.
    # The library's values (geofair.fair's), which the operator takes as they are; upper case works too.
    inner, outer = ("uniform", "conformal", "conformal_intrinsic"), ("intrinsic", "bilaplacian")
    parser.add_argument("--inner-fairness", type=str.lower, default="conformal", choices=inner)
    parser.add_argument("--outer-fairness", type=str.lower, default="intrinsic", choices=outer)
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else [])


def enable_addon(folder):
    """Import and register the add-on from ``folder`` (works in Blender 3.4 and 4.5); return it."""
    geometric_fairing = paths.import_addon(folder)
    geometric_fairing.register()
    print(f"add-on: {pathlib.Path(geometric_fairing.__file__).parent}")
    return geometric_fairing


def add_suzanne():
    """Blender's Suzanne with a Subdivision Surface modifier (level 2) applied, smooth shaded."""
    obj = add_subdivided_suzanne()
    obj.name = "Suzanne"
    bpy.ops.object.shade_smooth()
    return obj


def tint_region(obj):
    """Give the faces whose centre lies within the brow sphere a second material; return their mask."""
    mesh = obj.data
    centres = np.empty(3 * len(mesh.polygons), dtype=np.float32)
    mesh.polygons.foreach_get("center", centres)
    inside = np.linalg.norm(centres.reshape(-1, 3) - REGION_CENTRE, axis=1) < REGION_RADIUS
    for name, colour in (("Skin", (0.8, 0.8, 0.8, 1.0)), ("Faired region", (0.95, 0.55, 0.25, 1.0))):
        material = bpy.data.materials.new(name)
        material.diffuse_color = colour
        mesh.materials.append(material)
    mesh.polygons.foreach_set("material_index", inside.astype(np.int32))
    return inside


def select_faces(obj, mask):
    """Enter Edit Mode and select exactly the faces in ``mask``."""
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bm = bmesh.from_edit_mesh(obj.data)
    for element in (*bm.verts, *bm.edges, *bm.faces):
        element.select = False
    bm.faces.ensure_lookup_table()
    for index in np.flatnonzero(mask).tolist():
        bm.faces[index].select_set(True)
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)


def look_at(obj, target):
    """Turn a camera (or light) so that it looks at ``target``."""
    obj.rotation_euler = (Vector(target) - obj.location).to_track_quat("-Z", "Y").to_euler()


def setup_render(scene, out_path):
    """A 3/4 view of Suzanne's left side, Workbench with studio light and material colours."""
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.location = (2.4, -3.0, 1.5)
    camera.data.lens = 50
    look_at(camera, (0.3, -0.2, 0.25))

    # A caption at the top of the frame, 3 units in front of the camera, facing it.
    label = bpy.data.objects.new("Label", bpy.data.curves.new("Label", "FONT"))
    scene.collection.objects.link(label)
    label.parent = camera
    label.location = (0.0, 0.78, -3.0)
    label.data.align_x = "CENTER"
    label.data.size = 0.14

    scene.world = bpy.data.worlds.new("World")
    scene.world.color = (0.02, 0.02, 0.02)
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.display.shading.light = "STUDIO"
    scene.display.shading.color_type = "MATERIAL"
    scene.display.shading.show_cavity = True
    scene.display.render_aa = "8"
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = str(out_path)
    return label


def render_pixels(scene, label, text, show, hide):
    """Render with only ``show`` visible and return the image as (h, w, 4) float32."""
    label.data.body = text
    show.hide_render, hide.hide_render = False, True
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(scene.render.filepath)
    pixels = np.empty(len(image.pixels), dtype=np.float32)
    image.pixels.foreach_get(pixels)
    shape = (image.size[1], image.size[0], 4)
    bpy.data.images.remove(image)
    return pixels.reshape(shape)


def save_png(pixels, path):
    """Write (h, w, 4) float32 RGBA pixels, bottom row first as Blender stores them, to a PNG."""
    image = bpy.data.images.new("before_after", pixels.shape[1], pixels.shape[0], alpha=True)
    image.pixels.foreach_set(pixels.ravel())
    image.filepath_raw = str(path)
    image.file_format = "PNG"
    image.save()
    bpy.data.images.remove(image)


def uv_distortion(obj, face_mask, metrics):
    """Mean and maximum conformal distortion σ1/σ2 of the UV map over the faces in ``face_mask``."""
    mesh = obj.data  # in Object Mode: in Edit Mode the mesh's UV layers read as empty
    mesh.calc_loop_triangles()
    count = len(mesh.loop_triangles)
    triangles, corners = np.empty(3 * count, dtype=np.int32), np.empty(3 * count, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", triangles)
    mesh.loop_triangles.foreach_get("loops", corners)
    face = np.empty(count, dtype=np.int32)
    mesh.loop_triangles.foreach_get("polygon_index", face)
    uv = np.empty(2 * len(mesh.loops), dtype=np.float32)
    mesh.uv_layers.active.data.foreach_get("uv", uv)
    keep = face_mask[face]
    distortion = metrics.uv_distortion(
        positions(obj), triangles.reshape(-1, 3)[keep], uv.reshape(-1, 2)[corners.reshape(-1, 3)[keep]]
    )
    return distortion.mean, distortion.max


def positions(obj):
    """Vertex positions of ``obj`` (its edit mesh in Edit Mode) as (n, 3) float32."""
    obj.update_from_editmode()
    co = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


def main():
    args = parse_args()
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}")
    addon = enable_addon(args.addon)

    suzanne = add_suzanne()
    brow = tint_region(suzanne)
    before = suzanne.copy()
    before.data = suzanne.data.copy()
    before.name = "Suzanne (before)"
    bpy.context.scene.collection.objects.link(before)
    before.hide_set(True)
    uv_before = uv_distortion(suzanne, brow, addon.metrics)
    select_faces(suzanne, brow)
    original = positions(suzanne)

    print(
        f"fairing {brow.sum()} selected faces of {len(suzanne.data.polygons)} "
        f"({args.inner_fairness} inner, {args.outer_fairness} outer fairness)"
    )
    start = time.perf_counter()
    result = bpy.ops.mesh.geometric_fairing(
        "EXEC_DEFAULT", True, inner_fairness=args.inner_fairness, outer_fairness=args.outer_fairness
    )
    print(f"operator returned {result} after {time.perf_counter() - start:.2f} s (report above)")
    if result != {"FINISHED"}:
        raise RuntimeError(f"Geometric Fairing failed: {result}")
    faired = positions(suzanne)
    moved = np.linalg.norm(faired - original, axis=1)
    print(f"{np.count_nonzero(moved)} vertices moved, at most {moved.max():.4f} (Suzanne is 2.7 wide)")
    bpy.ops.object.mode_set(mode="OBJECT")
    uv_after = uv_distortion(suzanne, brow, addon.metrics)
    print(
        "UV conformal distortion σ1/σ2 in the region (mean, max): "
        f"before {uv_before[0]:.3f}, {uv_before[1]:.3f}; after {uv_after[0]:.3f}, {uv_after[1]:.3f}"
    )

    scene = bpy.context.scene
    label = setup_render(scene, out / "render.png")
    start = time.perf_counter()
    left = render_pixels(scene, label, "before", before, suzanne)
    right = render_pixels(scene, label, "after", suzanne, before)
    (out / "render.png").unlink()
    save_png(np.concatenate([left, right], axis=1), out / "before_after.png")
    print(f"rendered {out / 'before_after.png'} in {time.perf_counter() - start:.1f} s")

    bpy.ops.object.select_all(action="DESELECT")
    suzanne.select_set(True)
    bpy.context.view_layer.objects.active = suzanne
    bpy.ops.wm.obj_export(
        filepath=str(out / "suzanne_faired.obj"), export_selected_objects=True, export_materials=False
    )
    bpy.ops.wm.save_as_mainfile(filepath=str(out / "suzanne_faired.blend"))
    print(f"wrote {out / 'suzanne_faired.obj'} and {out / 'suzanne_faired.blend'}")
    addon.unregister()  # the bpy module from PyPI hangs at exit while the operator is registered


main()
