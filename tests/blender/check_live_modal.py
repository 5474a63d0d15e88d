"""Check Live Fair Drag's modal drag in a real Blender window: the mouse moves the handle, Esc
restores every byte, a click confirms with one undo step and leaves the offset for redo.

Needs a display (Xvfb) and Blender's event simulation, as check_modal.py:

    xvfb-run -a -s "-screen 0 1280x800x24" blender --factory-startup --enable-event-simulate \\
        --python tests/blender/check_live_modal.py -- build/addon
"""

import sys
import traceback

import bpy
from mathutils import Vector

# isort: split
import numpy as np

from geofair_dev.blender import (
    TimerSteps,
    edit_state,
    enable_addon,
    finish,
    parse_args,
    positions,
    select_faces,
    select_vertices,
    wait_until,
    window_view3d,
)

AXIS = np.array([1.0, 0.0, 0.0])


def angle_to_axis(points):
    unit = points / np.linalg.norm(points, axis=-1, keepdims=True)
    return np.degrees(np.arccos(np.clip(unit @ AXIS, -1.0, 1.0)))


def invoke_live(sidebar=False):
    """Invoke as the Mesh menu does (in the main region) or as the sidebar's button (its UI region)."""
    window, area, region = window_view3d()
    if sidebar:
        region = next(r for r in area.regions if r.type == "UI")
    with bpy.context.temp_override(window=window, area=area, region=region):
        return bpy.ops.mesh.geometric_fairing_live("INVOKE_DEFAULT", pin_group="Handle")


def mouse(dx, dy, event_type="MOUSEMOVE", value="NOTHING"):
    """Simulate an event at the 3D View's centre moved by (dx, dy) pixels."""
    window, _, region = window_view3d()
    x, y = region.x + region.width // 2 + dx, region.y + region.height // 2 + dy
    window.event_simulate(type=event_type, value=value, x=x, y=y)


def drag_a_little():
    for step in range(1, 6):
        mouse(0, 3 * step)
        yield 0.2


def escape_restores(obj, before, what):
    """Press Esc; the mesh must be ``before`` byte for byte."""
    mouse(0, 40, "ESC", "PRESS")
    mouse(0, 40, "ESC", "RELEASE")
    yield 0.3
    assert edit_state(obj) == before, f"{what} did not restore every byte"
    print(f"ok: {what} restored the mesh byte for byte")


def key(event_type, times=1):
    for _ in range(times):
        mouse(0, 15, event_type, "PRESS")
        mouse(0, 15, event_type, "RELEASE")


def rotate_and_scale(addon):
    """R turns the handle with the mouse about its centre, then 1 0 typed makes it 10° about the view's
    axis; S and 1 . 2 typed scale it by 1.2 about its centre, the rotation and the move kept."""
    live = addon.live
    moved = addon.operators.last_drag().move
    key("R")
    yield 0.3
    for step in range(1, 4):  # a quarter circle around the view's centre
        angle = np.radians(15.0 * step)
        mouse(int(-40 * np.sin(angle)), int(40 * np.cos(angle)))
        yield 0.2
    _, turned = live.axis_angle(addon.operators.last_drag().move.rotation)
    assert turned > 0.0, "R did not turn the handle"
    key("ONE"), key("ZERO")
    yield 0.3
    move = addon.operators.last_drag().move
    axis, turned = live.axis_angle(move.rotation @ moved.rotation.T)
    assert np.isclose(np.degrees(turned), 10.0), np.degrees(turned)
    _, _, region = window_view3d()
    into_screen = -np.array(region.data.view_rotation @ Vector((0.0, 0.0, 1.0)))
    assert np.allclose(axis, into_screen, atol=1e-5), (axis, into_screen)  # Blender's typed R (object = world)
    print(f"ok: R turns the handle with the mouse, 10 typed: {np.degrees(turned):.3f}° about the axis into the screen")
    key("S")
    key("ONE"), key("PERIOD"), key("TWO")
    yield 0.3
    scaled = addon.operators.last_drag().move
    assert np.isclose(scaled.scale, 1.2) and np.allclose(scaled.rotation, move.rotation), scaled
    drag = addon.operators.last_drag()
    handle = drag.base[drag.handle]
    centre = drag.centre + move.offset  # the scaling is about the centre where R left it
    spread = np.linalg.norm(scaled.points(handle, drag.centre) - centre, axis=1)
    before = np.linalg.norm(move.points(handle, drag.centre) - centre, axis=1)
    assert np.allclose(spread, 1.2 * before), "S did not scale about the handle's centre"
    print(f"ok: S with 1.2 typed scales the handle about its centre; {drag.frames[-1].status()}")


def checks(addon, obj):
    yield 0.5
    mouse(0, 0)
    yield 0.2
    before, handle = edit_state(obj), positions(obj)
    assert invoke_live() == {"RUNNING_MODAL"}
    yield from drag_a_little()
    drag = addon.operators.last_drag()
    assert drag.frames and np.any(positions(obj) != handle), "the drag moved nothing"
    print(f"ok: dragging: {drag.summary()}; last frame: {drag.frames[-1].status()}")
    yield from escape_restores(obj, before, "Esc")

    mouse(0, 0)
    yield 0.2
    assert invoke_live(sidebar=True) == {"RUNNING_MODAL"}
    yield from drag_a_little()
    mouse(0, 15, "Z", "PRESS")  # along global Z only (the sphere's object space is the world's)
    mouse(0, 15, "Z", "RELEASE")
    yield 0.3
    along_z = addon.operators.last_drag().offset
    assert along_z[0] == along_z[1] == 0.0 and along_z[2] > 0.0, along_z
    print(f"ok: Z: the handle moves along Z only, offset {np.round(along_z, 4)}")
    yield from rotate_and_scale(addon)
    mouse(0, 40, "LEFTMOUSE", "PRESS")
    mouse(0, 40, "LEFTMOUSE", "RELEASE")
    yield 0.3
    drag = addon.operators.last_drag()
    moved = edit_state(obj)
    assert moved["co"] != before["co"] and np.linalg.norm(drag.offset) > 0, "the click kept nothing"
    assert all(moved[key] == before[key] for key in before if key != "co"), "a layer changed"
    last = bpy.context.window_manager.operators[-1]
    assert last.bl_idname == "MESH_OT_geometric_fairing_live", last.bl_idname
    props = last.properties
    assert np.allclose(props.offset, drag.offset), (props.offset[:], drag.offset)
    assert np.allclose(np.array(props.rotation.to_matrix()), drag.move.rotation, atol=1e-6)
    assert np.isclose(props.scale, drag.move.scale), (props.scale, drag.move.scale)
    print(f"ok: from the sidebar, click confirmed: {drag.summary()}; offset {np.round(drag.offset, 4)}, "
          f"rotation {np.round(np.degrees(props.rotation[:]), 2)}°, scale {props.scale:.3f} for redo")  # fmt: skip
    window, area, region = window_view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.ed.undo()
    assert edit_state(obj) == before, "one undo did not restore every byte"
    print("ok: one undo restored the mesh byte for byte")
    yield from radius_by_wheel(addon, obj)
    print("check_live_modal: all checks passed")


def radius_by_wheel(addon, obj):
    """With a radius the selected vertices are the handle; the wheel (down: larger, as Proportional
    Editing's) prepares a larger region and keeps the move; Esc restores every byte."""
    handle = np.flatnonzero(angle_to_axis(positions(obj).astype(np.float64)) < 10.0)
    select_vertices(obj, handle)
    bpy.ops.ed.undo_push(message="selected the handle")
    before = edit_state(obj)
    mouse(0, 0)
    yield 0.2
    window, area, region = window_view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        started = bpy.ops.mesh.geometric_fairing_live("INVOKE_DEFAULT", pin_group="", radius=0.6)
    assert started == {"RUNNING_MODAL"}, started
    yield from drag_a_little()
    small = addon.operators.last_drag()
    assert np.array_equal(np.flatnonzero(small.handle), handle), "the handle is not the selection"
    mouse(0, 15, "WHEELDOWNMOUSE", "PRESS")  # two steps in quick succession: one new region
    mouse(0, 15, "WHEELDOWNMOUSE", "PRESS")
    yield 0.3
    yield from wait_until(lambda: addon.operators.last_drag() is not small, "the wheel's new region")
    large = addon.operators.last_drag()
    assert large is not small and large.free_count > small.free_count, (small.summary(), large.summary())
    assert np.allclose(large.offset, small.offset), "the move was not kept"
    print(f"ok: the wheel grows the radius: {small.free_count} -> {large.free_count} free vertices, move kept")
    print(f"    the drag before: {small.summary()}; after: {large.summary()}")
    yield from escape_restores(obj, before, "Esc after resizing")


def main():
    folder, _ = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    assert not bpy.app.background, "check_live_modal needs a window (run it under xvfb-run without --background)"
    addon = enable_addon(folder)
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=1.0)
    obj = bpy.context.active_object
    handle = np.flatnonzero(angle_to_axis(positions(obj).astype(np.float64)) < 10.0)
    obj.vertex_groups.new(name="Handle").add(handle.tolist(), 1.0, "REPLACE")
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(obj, lambda c: angle_to_axis(c) < 50.0)
    bpy.ops.ed.undo_push(message="selected the region")
    bpy.app.timers.register(TimerSteps(checks(addon, obj), "check_live_modal"), first_interval=0.5)


try:
    main()
except Exception:
    traceback.print_exc()
    finish(1)
