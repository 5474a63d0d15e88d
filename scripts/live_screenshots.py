"""A picture sequence of Live Fair Drag in a real Blender window: a handle dragged over a sphere.

    xvfb-run -a -s "-screen 0 1600x1000x24" blender --factory-startup --enable-event-simulate \\
        --python scripts/live_screenshots.py -- --addon build/addon --out docs/images

Enables the add-on, adds a UV sphere (64 segments, 32 rings) in Edit Mode with the faces
within 50° of an axis selected (the region) and the vertices within 10° of it in the vertex
group "Handle", turns zebra stripes on, starts Live Fair Drag (the operator of the Mesh
menu, pin group "Handle") and moves the mouse upwards in steps by simulated events, as a
modeller drags with G; after each step it waits for the frame and takes the 3D View (its
header shows the operator's status line). Esc then restores the mesh. Writes

    <out>/live_drag.png   the 3D View at the start and after three steps of the drag

Steps run from timers; Blender exits with status 1 if one fails.
"""

import argparse
import pathlib
import sys
import traceback

import bpy

# isort: split
import numpy as np
from mathutils import Vector

from geofair_dev.blender import (
    TimerSteps,
    enable_addon,
    finish,
    positions,
    select_faces,
    side_by_side,
    wait_until,
    window_view3d,
)

AXIS = np.array([0.8, -0.55, 0.25]) / np.linalg.norm([0.8, -0.55, 0.25])
STEPS = (0, 60, 120, 180)  # the mouse's offsets upwards, pixels


def parse_args():
    parser = argparse.ArgumentParser(prog="live_screenshots.py")
    parser.add_argument("--addon", type=pathlib.Path, default=pathlib.Path("build/addon"))
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("docs/images"))
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else [])


def angle_to_axis(points):
    unit = points / np.linalg.norm(points, axis=-1, keepdims=True)
    return np.degrees(np.arccos(np.clip(unit @ AXIS, -1.0, 1.0)))


def sphere():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=1.0)
    obj = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    handle = np.flatnonzero(angle_to_axis(positions(obj).astype(np.float64)) < 10.0)
    obj.vertex_groups.new(name="Handle").add(handle.tolist(), 1.0, "REPLACE")
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(obj, lambda c: angle_to_axis(c) < 50.0)
    bpy.ops.ed.undo_push(message="selected the region")
    return obj


def look_at_handle(space):
    """A 3/4 view of the handle from the side, so that a drag upwards shows the region's bend."""
    r3d = space.region_3d
    r3d.view_perspective = "PERSP"
    direction = Vector((0.75, -0.8, 0.5))
    r3d.view_rotation = direction.to_track_quat("Z", "Y")
    r3d.view_location = Vector(tuple(0.5 * AXIS))
    r3d.view_distance = 2.3
    space.lens = 50
    space.overlay.show_overlays = False
    space.show_gizmo = False
    space.show_region_toolbar = False
    space.show_region_tool_header = False
    space.show_region_ui = False


def mouse(dy, event_type="MOUSEMOVE", value="NOTHING"):
    """Simulate an event at the 3D View's centre moved up by dy pixels."""
    window, _, region = window_view3d()
    x, y = region.x + region.width // 2, region.y + region.height // 2 + dy
    window.event_simulate(type=event_type, value=value, x=x, y=y)


def screenshot(path):
    window, area, region = window_view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.screen.screenshot_area(filepath=str(path))


def steps(addon, obj, out):
    window, area, region = window_view3d()
    look_at_handle(area.spaces.active)
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.view3d.geometric_fairing_zebra(action="ON")
    mouse(0)
    yield 1.0
    with bpy.context.temp_override(window=window, area=area, region=region):
        started = bpy.ops.mesh.geometric_fairing_live("INVOKE_DEFAULT", pin_group="Handle")
    assert started == {"RUNNING_MODAL"}, started
    yield 0.5
    shots = []
    for k, dy in enumerate(STEPS):
        if dy:
            drag = addon.operators.last_drag()
            frames = len(drag.frames)
            for y in np.linspace(STEPS[k - 1], dy, 6)[1:]:  # the mouse moves, not jumps
                mouse(int(round(y)))
                yield 0.05
            yield from wait_until(lambda d=drag, n=frames: len(d.frames) > n, "a frame of the drag")
            yield 0.8  # the frame's redraw
            print(f"step {k}: {drag.frames[-1].status()}")
        path = out / f"_live_{k}.png"
        screenshot(path)
        shots.append(path)
    mouse(STEPS[-1], "ESC", "PRESS")
    mouse(STEPS[-1], "ESC", "RELEASE")
    yield 0.3
    side_by_side(shots, out / "live_drag.png", shrink=0.6, crop=0.55)
    print(f"wrote {out / 'live_drag.png'}")


def main():
    args = parse_args()
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    bpy.context.preferences.view.show_splash = False
    addon = enable_addon(args.addon.resolve())
    obj = sphere()
    bpy.app.timers.register(TimerSteps(steps(addon, obj, out), "live_screenshots"), first_interval=1.0)


try:
    main()
except Exception:
    traceback.print_exc()
    finish(1)
