"""Check the Geometric Fairing operator with several objects in Edit Mode; raises (non-zero exit) on failure.

Runs in Blender 3.4+ and in the ``bpy`` module from PyPI (see dev/geofair_dev/blender.py).

- Two Suzannes in Edit Mode, each with a selected region: both are faired, each only
  inside its region, and one undo restores both exactly.
- One with a region, one with nothing selected: the first is faired, the other skipped.
- One with a region, one that cannot be faired (a whole closed sphere selected), or
  whose solve fails: the first is faired, the other is left exactly as it was, and the
  warning names it and says why.
- Neither can be faired: an error naming both, nothing changed.
- Two objects sharing one mesh (linked duplicates) fair it once.
"""

import sys

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import numpy as np

from geofair_dev.blender import (
    FailingModule,
    add_subdivided_suzanne,
    disable_addon,
    enable_addon,
    parse_args,
    select_faces,
)
from geofair_dev.blender import edit_state as state
from geofair_dev.blender import run_fairing as fair

BROW = np.array([0.4, -0.7, 0.72])
WHOLE_MESH = (
    "The whole mesh is selected and it has no open border: fairing needs unselected faces around the selection "
    "to hold it in place"
)


def brow(obj):
    """The brow in ``obj``'s own coordinates (the objects stand apart)."""
    return lambda centre: np.linalg.norm(centre - BROW) < 0.25


def edit(*objects, shared=False):
    """Put ``objects`` into Edit Mode together, the first one active (``shared``: they share one mesh)."""
    if bpy.context.object is not None and bpy.context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    for obj in bpy.context.view_layer.objects:
        obj.select_set(obj in objects)
    bpy.context.view_layer.objects.active = objects[0]
    bpy.ops.object.mode_set(mode="EDIT")
    in_mode = {obj.name for obj in bpy.context.objects_in_mode_unique_data}
    assert in_mode == ({objects[0].name} if shared else {obj.name for obj in objects}), in_mode


def moved(before, after):
    old, new = (np.frombuffer(data["co"], np.float32).reshape(-1, 3) for data in (before, after))
    return np.any(old != new, axis=1)


def last_run():
    return bpy.context.window_manager.geometric_fairing.last_run


def check_both_faired(left, right):
    edit(left, right)
    select_faces(left, brow(left))
    select_faces(right, brow(right))
    bpy.ops.ed.undo_push(message="selected both brows")
    before = {obj.name: state(obj) for obj in (left, right)}
    result, error = fair(inner_fairness="conformal")
    assert result == {"FINISHED"}, error
    after = {obj.name: state(obj) for obj in (left, right)}
    counts = []
    for obj in (left, right):
        changed = moved(before[obj.name], after[obj.name])
        assert changed.sum() > 50, f"{obj.name}: {changed.sum()} vertices moved"
        # Only positions change, and only inside the region (the faces selected in that object).
        assert {k: v for k, v in before[obj.name].items() if k != "co"} == {
            k: v for k, v in after[obj.name].items() if k != "co"
        }
        counts.append(int(changed.sum()))
    last = last_run()
    assert last.status == "CONVERGED" and last.object_name == f"{left.name}, {right.name}", last.object_name
    assert last.free_vertices == sum(counts) and not last.not_faired, (last.free_vertices, counts)
    assert last.message.startswith(f"{left.name}: ") and f"; {right.name}: " in last.message, last.message
    print(f"ok: two objects in Edit Mode, both faired ({counts[0]} + {counts[1]} vertices): {last.message}")
    bpy.ops.ed.undo()
    for obj in (left, right):
        assert state(obj) == before[obj.name], f"undo did not restore {obj.name}"
    print("ok: one undo restores both objects exactly")


def check_one_without_selection(left, right):
    edit(left, right)
    select_faces(left, brow(left))
    select_faces(right, lambda c: False)
    bpy.ops.ed.undo_push(message="one selection")
    before = {obj.name: state(obj) for obj in (left, right)}
    result, error = fair(inner_fairness="conformal")
    assert result == {"FINISHED"}, error
    assert moved(before[left.name], state(left)).sum() > 50
    assert state(right) == before[right.name], "the object with nothing selected changed"
    last = last_run()
    assert last.object_name == left.name and not last.not_faired and last.message.startswith(f"{left.name}: ")
    print(f"ok: the object with nothing selected is skipped: {last.message}")
    bpy.ops.ed.undo()


def check_one_failing(addon, left, sphere):
    edit(left, sphere)
    select_faces(left, brow(left))
    select_faces(sphere, lambda c: True)
    bpy.ops.ed.undo_push(message="brow and the whole sphere")
    before = {obj.name: state(obj) for obj in (left, sphere)}
    result, error = fair(inner_fairness="conformal")
    assert result == {"FINISHED"}, error  # a warning: the others were faired
    assert moved(before[left.name], state(left)).sum() > 50
    assert state(sphere) == before[sphere.name], "the object that cannot be faired changed"
    last = last_run()
    assert last.not_faired == f"{sphere.name}: {WHOLE_MESH}", last.not_faired
    assert last.message.endswith(f"; {sphere.name} not faired: {WHOLE_MESH}"), last.message
    assert last.object_name == left.name
    print(f"ok: one object cannot be faired, the other is: {last.message}")
    bpy.ops.ed.undo()
    assert state(left) == before[left.name]

    # Both cannot be faired: an error naming both, nothing changed.
    select_faces(left, lambda c: False)
    result, error = fair(inner_fairness="conformal")
    expected = (
        f"Error: Geometric Fairing: {left.name}: No face is selected: select the faces to fair; "
        f"{sphere.name}: {WHOLE_MESH}"
    )
    assert result == {"CANCELLED"} and error == expected, (result, error)
    assert last_run().status == "ERROR" and last_run().object_name == f"{left.name}, {sphere.name}"
    assert state(sphere) == before[sphere.name]
    print(f"ok: neither can be faired -> CANCELLED: {error}")

    # The solver fails on one object only: the other is faired, the failing one is named.
    select_faces(left, brow(left))
    select_faces(sphere, lambda c: c[2] > 0.5)  # a cap of the sphere: a valid region
    bpy.ops.ed.undo_push(message="brow and a cap")
    before = {obj.name: state(obj) for obj in (left, sphere)}
    sphere_vertices = len(sphere.data.vertices)
    real = addon.native.geofair

    class FailOnSphere(FailingModule):
        def fair(self, vertices, *args, **kwargs):
            if len(vertices) == sphere_vertices:
                return super().fair(vertices, *args, **kwargs)
            return self.real.fair(vertices, *args, **kwargs)

    addon.native.geofair = FailOnSphere(real, RuntimeError("fair: the iteration diverged (simulated)"))
    try:
        result, error = fair(inner_fairness="conformal")
    finally:
        addon.native.geofair = real
    assert result == {"FINISHED"}, error
    assert moved(before[left.name], state(left)).sum() > 50
    assert state(sphere) == before[sphere.name], "the object whose solve failed changed"
    hint = "Remesh 'If Needed' may help (it changes the triangles)."
    expected = f"{sphere.name}: fair: the iteration diverged (simulated) {hint}"
    assert last_run().not_faired == expected, last_run().not_faired
    print(f"ok: the solver fails on one object, the other is faired: {last_run().message}")
    bpy.ops.ed.undo()
    assert state(left) == before[left.name] and state(sphere) == before[sphere.name]
    print("ok: undo restores both")


def check_shared_mesh(left):
    """Linked duplicates share one mesh: it is faired once (objects_in_mode_unique_data)."""
    bpy.ops.object.mode_set(mode="OBJECT")
    twin = left.copy()  # same mesh data
    twin.location.x += 6
    bpy.context.collection.objects.link(twin)
    edit(left, twin, shared=True)
    select_faces(left, brow(left))
    bpy.ops.ed.undo_push(message="shared mesh")
    before = state(left)
    result, error = fair(inner_fairness="conformal")
    assert result == {"FINISHED"}, error
    count = int(moved(before, state(left)).sum())
    assert last_run().object_name == left.name and last_run().free_vertices == count, last_run().object_name
    print(f"ok: two objects sharing one mesh: faired once ({count} vertices)")
    bpy.ops.ed.undo()
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.data.objects.remove(twin)


def main():
    folder, _ = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon = enable_addon(folder)
    left = add_subdivided_suzanne()
    left.name = "Left"
    right = add_subdivided_suzanne()
    right.name = "Right"
    right.location.x = 3
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, location=(-3, 0, 0))
    sphere = bpy.context.active_object
    sphere.name = "Sphere"
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    check_both_faired(left, right)
    check_one_without_selection(left, right)
    check_one_failing(addon, left, sphere)
    check_shared_mesh(left)
    disable_addon()
    print("check_multi_object: all checks passed")


main()
