"""Screenshots of the add-on in a real Blender window: the Fairing panel and zebra stripes before/after.

    xvfb-run -a -s "-screen 0 1600x1000x24" blender --factory-startup --enable-event-simulate \\
        --python scripts/screenshots.py -- --addon build/addon --out docs/images

Enables the add-on, builds Suzanne (subdivided twice) in Edit Mode with her left
brow selected, turns zebra stripes on, takes the 3D View before fairing, runs the
Fair button's operator (modal, in the window), takes the 3D View after, then
opens the sidebar's Fairing tab and takes the whole window. Writes

    <out>/panel.png               the window: panel with the last run's figures, zebra on
    <out>/zebra_before_after.png  the 3D View before | after, zebra stripes

Event simulation (``--enable-event-simulate``) is used to switch the sidebar to
the Fairing tab (Ctrl+Wheel over the sidebar): Blender 3.4 has no API for the
active tab. Steps run from timers; Blender exits with status 1 if one fails.
"""

import argparse
import os
import pathlib
import sys
import time
import traceback

import bpy

# isort: split
import bmesh
import numpy as np
from mathutils import Vector

from geofair_dev.blender import add_subdivided_suzanne, enable_addon, side_by_side

BROW = np.array([0.4, -0.7, 0.72])
TIMEOUT = 120.0


def parse_args():
    parser = argparse.ArgumentParser(prog="screenshots.py")
    parser.add_argument("--addon", type=pathlib.Path, default=pathlib.Path("build/addon"))
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("docs/images"))
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else [])


def suzanne():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    obj = add_subdivided_suzanne()
    bpy.ops.object.shade_smooth()
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bm = bmesh.from_edit_mesh(obj.data)
    for element in (*bm.verts, *bm.edges, *bm.faces):
        element.select = False
    for face in bm.faces:
        if np.linalg.norm(np.array(face.calc_center_median()) - BROW) < 0.25:
            face.select_set(True)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)
    return obj


def view3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == "VIEW_3D"), key=lambda a: a.width * a.height)
    region = next(r for r in area.regions if r.type == "WINDOW")
    return window, area, region


def override():
    window, area, region = view3d()
    return bpy.context.temp_override(window=window, area=area, region=region)


def look_at_brow(space):
    """A close 3/4 view of Suzanne's left brow, from the front left and a little above."""
    r3d = space.region_3d
    r3d.view_perspective = "PERSP"
    direction, target = Vector((0.5, -1.0, 0.55)), Vector((0.38, -0.68, 0.62))
    r3d.view_rotation = direction.to_track_quat("Z", "Y")
    r3d.view_location = target
    r3d.view_distance = 0.8
    space.lens = 50


def clean_view(space, clean):
    """Hide (or show again) everything in the 3D View but the mesh: overlays, gizmos, toolbar, sidebar."""
    space.overlay.show_overlays = not clean
    space.show_gizmo = not clean
    space.show_region_toolbar = not clean
    space.show_region_tool_header = not clean
    space.show_region_ui = not clean


def sidebar_to_fairing_tab(area):
    """Wheel over the sidebar's tab strip cycles its tabs: Item, Tool, View, then Fairing (registered last)."""
    window = bpy.context.window_manager.windows[0]
    sidebar = next(r for r in area.regions if r.type == "UI")
    # The tabs run down the right edge of the sidebar, from its top.
    x, y = sidebar.x + sidebar.width - 6, sidebar.y + sidebar.height - 40
    window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
    for _ in range(3):
        window.event_simulate(type="WHEELDOWNMOUSE", value="PRESS", x=x, y=y, ctrl=True)


def finish(code):
    sys.stdout.flush()
    os._exit(code)


def steps(addon, out):
    window, area, region = view3d()
    space = area.spaces.active
    clean_view(space, True)
    look_at_brow(space)
    with override():
        bpy.ops.view3d.geometric_fairing_zebra(action="ON")
    area.header_text_set("Before fairing: zebra stripes (reflection lines)")
    yield 1.0
    before = out / "_before.png"
    with override():
        bpy.ops.screen.screenshot_area(filepath=str(before))

    with override():
        assert bpy.ops.mesh.geometric_fairing("INVOKE_DEFAULT") == {"RUNNING_MODAL"}
    start = time.perf_counter()
    while addon.operators.running() is not None:
        assert time.perf_counter() - start < TIMEOUT, "the fairing run did not finish"
        yield 0.1
    last = bpy.context.window_manager.geometric_fairing.last_run
    assert last.status == "CONVERGED", (last.status, last.message)
    print(f"faired: {last.message}")
    area.header_text_set(f"After fairing: intrinsic (Δ_B H = 0), {last.inner_fairness} inner fairness, G1 boundary")
    yield 1.0
    after = out / "_after.png"
    with override():
        bpy.ops.screen.screenshot_area(filepath=str(after))
    side_by_side([before, after], out / "zebra_before_after.png")

    area.header_text_set(None)
    clean_view(space, False)
    yield 0.5
    sidebar_to_fairing_tab(area)
    yield 1.5
    with override():
        bpy.ops.screen.screenshot(filepath=str(out / "panel.png"))
    print(f"wrote {out / 'panel.png'} and {out / 'zebra_before_after.png'}")
    yield 0.2
    finish(0)


class Driver:
    def __init__(self, generator):
        self.generator = generator

    def __call__(self):
        try:
            return next(self.generator)
        except Exception:
            traceback.print_exc()
            finish(1)


def main():
    args = parse_args()
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    bpy.context.preferences.view.show_splash = False  # before Blender opens the splash, after this script
    addon = enable_addon(args.addon.resolve())
    settings = bpy.context.scene.geometric_fairing
    settings.inner_fairness = "conformal"  # Suzanne has a UV map: the texture-preserving mode
    suzanne()
    bpy.app.timers.register(Driver(steps(addon, out)), first_interval=1.0)


try:
    main()
except Exception:
    traceback.print_exc()
    finish(1)
