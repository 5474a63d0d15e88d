"""Check Live Fair Drag (mesh.geometric_fairing_live) inside Blender, run as a script (its execute:
the offset in a few frames); raises (non-zero exit) on failure.

    blender --background --factory-startup --python-exit-code 1 \\
        --python tests/blender/check_live.py -- build/addon
    python3 tests/blender/check_live.py -- build/addon

On a UV sphere (64 segments, 32 rings, with a second UV map, a colour attribute and a vertex
group): the region the faces within 50° of +x, the handle the Pin group's vertices within 10°
of +x, slid by 0.15 along the sphere's tangent (+y). The result is the Fair operator's cold fair
of the same input within the tolerance and stays near the sphere; only the positions of the
region and the handle change (every other layer byte-identical); one undo restores every byte.
Without a handle, or a region: a clear error and the mesh untouched. Then the frame times on a
region of about 2,000 free vertices (a 128×64 UV sphere's 70° cap).
"""

import sys

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import numpy as np
from mathutils import Euler

from geofair_dev.blender import (
    disable_addon,
    edit_state,
    enable_addon,
    parse_args,
    positions,
    select_faces,
    select_vertices,
)

AXIS = np.array([1.0, 0.0, 0.0])
OFFSET = (0.0, 0.15, 0.0)
# The attribute types compared byte for byte: property, width, dtype.
ATTRIBUTE_DATA = {
    "FLOAT": ("value", 1, np.float32),
    "INT": ("value", 1, np.int32),
    "BOOLEAN": ("value", 1, bool),
    "FLOAT_VECTOR": ("vector", 3, np.float32),
    "FLOAT2": ("vector", 2, np.float32),
    "FLOAT_COLOR": ("color", 4, np.float32),
    "BYTE_COLOR": ("color", 4, np.float32),
}


def angle_to_axis(points):
    unit = points / np.linalg.norm(points, axis=-1, keepdims=True)
    return np.degrees(np.arccos(np.clip(unit @ AXIS, -1.0, 1.0)))


def live(**properties):
    """Run the operator as a script would, with an undo push; return (result, error text)."""
    try:
        return bpy.ops.mesh.geometric_fairing_live("EXEC_DEFAULT", True, **properties), ""
    except RuntimeError as error:  # an operator that reports an ERROR raises in scripts
        return {"CANCELLED"}, str(error).strip()


def add_sphere(segments, rings, region_deg, handle_deg):
    """A UV sphere in Edit Mode with its region selected and the handle in vertex group 'Handle'."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=1.0)
    obj = bpy.context.active_object
    mesh = obj.data
    rng = np.random.default_rng(3)
    second = mesh.uv_layers.new(name="Second")
    second.data.foreach_set("uv", rng.uniform(0, 1, 2 * len(mesh.loops)).astype(np.float32))
    paint = mesh.color_attributes.new("Paint", "FLOAT_COLOR", "POINT")
    paint.data.foreach_set("color", rng.uniform(0, 1, 4 * len(mesh.vertices)).astype(np.float32))
    obj.vertex_groups.new(name="Weights").add(list(range(0, len(mesh.vertices), 3)), 0.5, "REPLACE")
    handle = np.flatnonzero(angle_to_axis(positions(obj).astype(np.float64)) < handle_deg)
    obj.vertex_groups.new(name="Handle").add(handle.tolist(), 1.0, "REPLACE")
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(obj, lambda c: angle_to_axis(c) < region_deg)
    bpy.ops.ed.undo_push(message="selected the region")
    return obj, handle


def attributes(obj):
    """Every attribute but the positions, and the vertex groups' weights, as bytes (Object Mode)."""
    bpy.ops.object.mode_set(mode="OBJECT")
    mesh, data = obj.data, {}
    for attribute in mesh.attributes:
        if attribute.name == "position" or attribute.data_type not in ATTRIBUTE_DATA:
            continue
        name, width, dtype = ATTRIBUTE_DATA[attribute.data_type]
        values = np.empty(len(attribute.data) * width, dtype=dtype)
        attribute.data.foreach_get(name, values)
        data[attribute.name] = values.tobytes()
    data["groups"] = repr([[(g.group, g.weight) for g in v.groups] for v in mesh.vertices])
    bpy.ops.object.mode_set(mode="EDIT")
    return data


def expect_refused(obj, message, **properties):
    before = edit_state(obj)
    result, error = live(**properties)
    assert result == {"CANCELLED"} and message in error, (result, error)
    assert edit_state(obj) == before, "a refused drag changed the mesh"
    print(f"ok: {properties} -> CANCELLED ({error}); mesh untouched")


def region_diagonal(points):
    return float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))


def check_drag(addon, obj, handle):
    """The drag's result against the sphere, the Fair operator's cold fair, the layers; undo."""
    before, layers = edit_state(obj), attributes(obj)
    start = positions(obj).astype(np.float64)
    result, error = live(pin_group="Handle", offset=OFFSET)
    assert result == {"FINISHED"}, (result, error)
    drag = addon.operators.last_drag()
    after = positions(obj).astype(np.float64)
    free = drag.free
    moved = np.any(after != start, axis=1)
    assert np.isfinite(after).all() and not moved[~(free | drag.handle)].any(), "a fixed vertex moved"
    assert np.array_equal(np.flatnonzero(drag.handle), handle), "the handle is not the Pin group"
    target = start.copy()
    assert np.allclose(drag.offset, OFFSET) and drag.offset.dtype == np.float64  # the property's float32
    target[handle] += drag.offset
    assert np.array_equal(after[handle], target[handle].astype(np.float32)), "the handle is not translated"
    radial = np.abs(np.linalg.norm(after[free], axis=1) - 1.0).max()
    print(f"ok: {drag.summary()}; {moved.sum()} vertices moved, radial error {radial:.2e}")
    assert radial < 0.05, radial
    state = edit_state(obj)
    assert all(state[key] == before[key] for key in before if key != "co"), "a layer or the selection changed"
    assert attributes(obj) == layers, "an attribute or a vertex group changed"
    print("ok: UV maps, colours, vertex groups, selection and hiding byte-identical")
    bpy.ops.ed.undo()
    assert edit_state(obj) == before, "one undo did not restore every byte"
    print("ok: one undo restored the mesh byte for byte")
    # A cold geofair.fair of the same input: the region, triangles, normals and options of the drag
    # (the Fair operator's after moving the handle differs by 3e-4: Blender splits the stretched
    # quads next to the handle along their other diagonal, and Live Fair Drag keeps its triangles).
    run = addon.fairing.FairingRun(obj, addon.fairing.default_options(bpy.context, pin_group="Handle"))
    assert np.array_equal(run.region.free, free) and np.array_equal(run.mesh.vertices, start)
    options = run.options.library_options()
    cold = addon.native.geofair.fair(
        target, run.mesh.triangles, free, boundary_normals=drag.normals, polygon_ids=run.polygon_ids, **options
    )
    assert cold.converged, cold.message
    distance = np.abs(cold.vertices - after).max() / region_diagonal(target[free])
    print(f"ok: Live Fair Drag vs a cold geofair.fair of the same input: max |Δ| / L = {distance:.1e}")
    assert distance < 1e-4, distance
    result, error = live(pin_group="Handle", offset=OFFSET, details=True)
    assert result == {"FINISHED"}, (result, error)
    print(f"ok: Keep Details: {addon.operators.last_drag().summary()}")
    bpy.ops.ed.undo()


def check_turn_and_scale(addon, obj, handle):
    """Rotation and Scale (the redo panel's): the handle turned and scaled about its centre, its G1
    normals turned with it; the result is the cold geofair.fair of that input."""
    before = edit_state(obj)
    start = positions(obj).astype(np.float64)
    euler = (0.0, 0.0, np.radians(12.0))
    result, error = live(pin_group="Handle", rotation=euler, scale=1.15)
    assert result == {"FINISHED"}, (result, error)
    drag = addon.operators.last_drag()
    rotation = np.array(Euler(euler).to_matrix())
    target = start.copy()
    target[handle] = drag.centre + 1.15 * (start[handle] - drag.centre) @ rotation.T
    after = positions(obj).astype(np.float64)
    assert np.allclose(after[handle], target[handle], atol=1e-6), "the handle is not turned and scaled"
    normals = np.array(drag.normals, dtype=np.float64)
    normals[handle] = normals[handle] @ rotation.T
    run = addon.fairing.FairingRun(obj, addon.fairing.default_options(bpy.context, pin_group="Handle"))
    options = run.options.library_options()
    cold = addon.native.geofair.fair(
        target, run.mesh.triangles, drag.free, boundary_normals=normals, polygon_ids=run.polygon_ids, **options
    )
    assert cold.converged, cold.message
    distance = np.abs(cold.vertices - after).max() / region_diagonal(target[drag.free])
    print(f"ok: turned by 12° and scaled by 1.15: {drag.summary()}; vs a cold fair max |Δ| / L = {distance:.1e}")
    assert distance < 1e-4, distance
    bpy.ops.ed.undo()
    assert edit_state(obj) == before, "one undo did not restore every byte"


def check_refusals(obj, region_deg):
    expect_refused(obj, "No handle: put vertices inside the region into the Pin vertex group", pin_group="")
    expect_refused(obj, "has no vertex group 'Nothing'", pin_group="Nothing")
    bpy.ops.mesh.select_all(action="DESELECT")
    expect_refused(obj, "No face is selected", pin_group="Handle")
    select_faces(obj, lambda c: angle_to_axis(c) < region_deg)
    bpy.ops.ed.undo_push(message="selected the region again")


def check_region_group(addon, obj, handle):
    """With a Region vertex group, the selected vertices inside it are the handle."""
    bpy.ops.object.mode_set(mode="OBJECT")
    inside = np.flatnonzero(angle_to_axis(positions(obj).astype(np.float64)) < 50.0)
    obj.vertex_groups.new(name="Region").add(inside.tolist(), 1.0, "REPLACE")
    bpy.ops.object.mode_set(mode="EDIT")
    select_vertices(obj, handle)
    result, error = live(region_group="Region", pin_group="", offset=OFFSET)
    assert result == {"FINISHED"}, (result, error)
    drag = addon.operators.last_drag()
    assert np.array_equal(np.flatnonzero(drag.handle), handle), "not the selection in Region"
    print(f"ok: Region vertex group, the selected vertices the handle: {drag.summary()}")
    bpy.ops.ed.undo()


def check_radius(addon, obj, handle):
    """Radius: the selected vertices are the handle, the region the faces within the radius along the
    surface; nothing beyond it moves; one undo restores. Nothing selected: refused."""
    select_vertices(obj, handle)
    bpy.ops.ed.undo_push(message="selected the handle")
    before = edit_state(obj)
    start = positions(obj).astype(np.float64)
    result, error = live(pin_group="", radius=0.6, offset=OFFSET)
    assert result == {"FINISHED"}, (result, error)
    drag = addon.operators.last_drag()
    assert np.array_equal(np.flatnonzero(drag.handle), handle), "the handle is not the selection"
    angle = np.radians(angle_to_axis(start))
    # The handle's angular radius and the radius along the unit sphere; edge paths are longer than the
    # great circles, and a free vertex lies a ring of faces inside (rings 5.6° apart): measured 33.7°.
    reach = np.radians(10.0) + 0.6
    assert reach - np.radians(3 * 5.625) < angle[drag.free].max() <= reach, angle[drag.free].max()
    after = positions(obj).astype(np.float64)
    moved = np.any(after != start, axis=1)
    assert moved[drag.free].any() and not moved[~(drag.free | drag.handle)].any(), "a vertex beyond the radius moved"
    print(f"ok: Radius 0.6: {drag.summary()}; free vertices up to {np.degrees(angle[drag.free].max()):.1f}° from +x")
    bpy.ops.ed.undo()
    assert edit_state(obj) == before, "one undo did not restore every byte"
    result, error = live(pin_group="", radius=0.9, offset=OFFSET)
    assert result == {"FINISHED"}, (result, error)
    wider = addon.operators.last_drag()
    assert wider.free_count > drag.free_count and not wider.free[drag.free].sum() < drag.free_count
    print(f"ok: Radius 0.9: {wider.summary()}")
    bpy.ops.ed.undo()
    bpy.ops.mesh.select_all(action="DESELECT")
    expect_refused(obj, "No vertex is selected: select the handle's vertices", pin_group="", radius=0.6)
    bpy.ops.ed.undo()


def frame_times(addon):
    """About 2,000 free vertices: a 128×64 UV sphere's 70° cap, 10 frames of 0.02."""
    obj, _ = add_sphere(128, 64, 70.0, 10.0)
    result, error = live(pin_group="Handle", offset=(0.0, 0.2, 0.0), frames=10)
    assert result == {"FINISHED"}, (result, error)
    drag = addon.operators.last_drag()
    times = ", ".join(f"{frame.seconds * 1e3:.0f}" for frame in drag.frames)
    steps = [frame.steps for frame in drag.frames]
    print(f"ok: timing: {drag.summary()}; frame ms {times}; Newton steps {steps}")
    bpy.ops.object.mode_set(mode="OBJECT")


def main():
    folder, _ = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    addon = enable_addon(folder)
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    obj, handle = add_sphere(64, 32, 50.0, 10.0)
    check_refusals(obj, 50.0)
    check_drag(addon, obj, handle)
    check_turn_and_scale(addon, obj, handle)
    check_region_group(addon, obj, handle)
    check_radius(addon, obj, handle)
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.data.objects.remove(obj)
    frame_times(addon)
    disable_addon()
    print("check_live: all checks passed")


main()
