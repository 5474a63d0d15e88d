"""Check what fairing changes in a mesh: positions where they must, nothing else; hidden faces; shape keys.

Runs in Blender 3.4+ and in the ``bpy`` module from PyPI (see dev/geofair_dev/blender.py).

- Layers: on Suzanne with shape keys, a modifier stack, custom split normals, two UV
  maps, colour attributes (point float, corner byte), a face attribute, a vertex group,
  seams and sharp edges, fairing in Edit Mode (operator) and in Object Mode
  (fair_object) changes the active shape key at the free vertices only; every other
  layer read with foreach_get in Object Mode is byte-identical afterwards.
- Shape keys: fairing in Edit Mode and in Object Mode give byte-identical shape keys and
  positions, with the basis active and with another key active (keys relative to the
  active key move by the same offset, as Blender does on leaving Edit Mode).
- Hidden faces: by default a hidden face takes no part: its vertices never move, and the
  result is the one of the same mesh with those faces deleted. With Use Hidden Faces
  they take part (as boundary, or inside a region group).
"""

import sys

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import bmesh
import numpy as np

from geofair_dev.blender import (
    add_subdivided_suzanne,
    disable_addon,
    enable_addon,
    face_centres,
    parse_args,
    select_faces,
)

BROW = np.array([0.4, -0.7, 0.72])
# Before 4.1 custom normals need auto smooth, and their stored data is no attribute: Python cannot read it.
# There the corner normals they give are compared where the geometry did not change; from 4.1 on the stored
# data (the custom_normal attribute) is compared byte for byte as well, over the whole mesh.
LEGACY = bpy.app.version < (4, 1, 0)
CUSTOM_NORMALS_NOTE = "" if LEGACY else " (custom_normal data included)"
# foreach_get key, width and dtype of each attribute data type.
ATTRIBUTE_ACCESS = {
    "FLOAT": ("value", 1, np.float32),
    "INT": ("value", 1, np.int32),
    "INT8": ("value", 1, np.int32),
    "BOOLEAN": ("value", 1, bool),
    "FLOAT2": ("vector", 2, np.float32),
    "FLOAT_VECTOR": ("vector", 3, np.float32),
    "FLOAT_COLOR": ("color", 4, np.float32),
    "BYTE_COLOR": ("color", 4, np.float32),
    "INT32_2D": ("value", 2, np.int32),
    "INT16_2D": ("value", 2, np.int32),
    "QUATERNION": ("value", 4, np.float32),
}


def fair(**properties):
    try:
        return bpy.ops.mesh.geometric_fairing("EXEC_DEFAULT", True, **properties), ""
    except RuntimeError as error:
        return {"CANCELLED"}, str(error).strip()


def get(collection, attribute, dtype, width=1):
    values = np.empty(len(collection) * width, dtype=dtype)
    collection.foreach_get(attribute, values)
    return values


def near_brow(centre):
    return np.linalg.norm(centre - BROW) < 0.25


# -- what is compared ------------------------------------------------------------------------------------------------


def layers(obj):
    """Every layer of ``obj``'s mesh read in Object Mode, as bytes (or reprs), by name."""
    assert obj.mode == "OBJECT"
    mesh = obj.data
    data = {"co": get(mesh.vertices, "co", np.float32, 3).tobytes()}
    if mesh.shape_keys is not None:
        for key in mesh.shape_keys.key_blocks:
            data[f"shape key {key.name}"] = get(key.data, "co", np.float32, 3).tobytes()
            data[f"shape key {key.name} settings"] = (key.relative_key.name, key.value, key.mute, key.vertex_group)
    for layer in mesh.uv_layers:
        data[f"uv {layer.name}"] = get(layer.data, "uv", np.float32, 2).tobytes()
    for attribute in mesh.attributes:  # 4.x: also custom_normal, UV maps, selection; 3.4: generic ones only
        if attribute.name == "position" or attribute.data_type not in ATTRIBUTE_ACCESS:
            continue
        key, width, dtype = ATTRIBUTE_ACCESS[attribute.data_type]
        data[f"attribute {attribute.name}"] = get(attribute.data, key, dtype, width).tobytes()
    for attribute in mesh.color_attributes:
        data[f"colour {attribute.name}"] = get(attribute.data, "color", np.float32, 4).tobytes()
    for name, collection, attribute, dtype, width in (
        ("edge vertices", mesh.edges, "vertices", np.int32, 2),
        ("corner vertices", mesh.loops, "vertex_index", np.int32, 1),
        ("face loop starts", mesh.polygons, "loop_start", np.int32, 1),
        ("vertex select", mesh.vertices, "select", bool, 1),
        ("face select", mesh.polygons, "select", bool, 1),
        ("vertex hide", mesh.vertices, "hide", bool, 1),
        ("face hide", mesh.polygons, "hide", bool, 1),
        ("seams", mesh.edges, "use_seam", bool, 1),
        ("sharp edges", mesh.edges, "use_edge_sharp", bool, 1),
        ("smooth faces", mesh.polygons, "use_smooth", bool, 1),
    ):
        data[name] = get(collection, attribute, dtype, width).tobytes()
    data["has custom normals"] = mesh.has_custom_normals
    data["vertex groups"] = [
        (group.name, [(v.index, e.weight) for v in mesh.vertices for e in v.groups if e.group == group.index])
        for group in obj.vertex_groups
    ]
    data["modifiers"] = [
        [(prop.identifier, repr(getattr(modifier, prop.identifier))) for prop in modifier.bl_rna.properties]
        for modifier in obj.modifiers
    ]
    data["active"] = (
        obj.active_shape_key_index,
        mesh.uv_layers.active.name if mesh.uv_layers.active else None,
        mesh.color_attributes.active_color_name,
    )
    return data


def corner_normals(obj):
    """``(L, 3)`` float32 normals of the face corners (custom split normals where set)."""
    mesh = obj.data
    if LEGACY:
        mesh.calc_normals_split()
        return get(mesh.loops, "normal", np.float32, 3).reshape(-1, 3)
    return get(mesh.corner_normals, "vector", np.float32, 3).reshape(-1, 3)


def decorate(obj):
    """Give ``obj`` modifiers, custom normals, a second UV map, colour and face attributes, a group, edge flags."""
    mesh = obj.data
    rng = np.random.default_rng(7)
    n, corners = len(mesh.vertices), len(mesh.loops)
    subdivision = obj.modifiers.new("Smooth more", "SUBSURF")
    subdivision.levels = 1
    displace = obj.modifiers.new("Bumps", "DISPLACE")
    displace.strength = 0.05
    obj.modifiers.new("Mirror", "MIRROR").use_axis[1] = True
    second = mesh.uv_layers.new(name="Second")
    second.data.foreach_set("uv", rng.uniform(0, 1, 2 * corners).astype(np.float32))
    paint = mesh.color_attributes.new("Paint", "FLOAT_COLOR", "POINT")
    paint.data.foreach_set("color", rng.uniform(0, 1, 4 * n).astype(np.float32))
    corner_colours = mesh.color_attributes.new("Bytes", "BYTE_COLOR", "CORNER")
    corner_colours.data.foreach_set("color", rng.uniform(0, 1, 4 * corners).astype(np.float32))
    mesh.color_attributes.active_color = paint
    weight = mesh.attributes.new("Face weight", "FLOAT", "FACE")
    weight.data.foreach_set("value", rng.uniform(0, 1, len(mesh.polygons)).astype(np.float32))
    group = obj.vertex_groups.new(name="Weights")
    for i in range(0, n, 3):
        group.add([i], float(rng.uniform(0.1, 1)), "REPLACE")
    mesh.edges.foreach_set("use_seam", rng.uniform(size=len(mesh.edges)) < 0.1)
    mesh.edges.foreach_set("use_edge_sharp", rng.uniform(size=len(mesh.edges)) < 0.1)
    if LEGACY:
        mesh.use_auto_smooth = True
    mesh.polygons.foreach_set("use_smooth", np.ones(len(mesh.polygons), dtype=bool))
    normals = rng.normal(size=(corners, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    mesh.normals_split_custom_set(normals.tolist())
    assert mesh.has_custom_normals


def add_shape_keys(obj, relative_to=None):
    """Basis and keys A, B, C, smooth deformations; ``relative_to`` maps a key to the key it is relative to."""
    obj.shape_key_add(name="Basis")
    base = get(obj.data.vertices, "co", np.float64, 3).reshape(-1, 3)
    x, y, z = base.T
    shapes = {
        "A": base + np.stack([0 * x, 0 * y, 0.08 * np.sin(3 * x)], axis=1),
        "B": base * [1.05, 1.0, 0.97],
        "C": base + np.stack([0.05 * z, 0 * y, -0.05 * x], axis=1),
    }
    for name, co in shapes.items():
        key = obj.shape_key_add(name=name, from_mix=False)
        key.data.foreach_set("co", co.astype(np.float32).ravel())
    for name, other in (relative_to or {}).items():
        obj.data.shape_keys.key_blocks[name].relative_key = obj.data.shape_keys.key_blocks[other]


# -- checks ------------------------------------------------------------------------------------------------------


def compare(before, after, changed, what):
    """Every layer but ``changed`` byte-identical; return the layers that differ."""
    differ = sorted(name for name in before if before[name] != after[name])
    unexpected = [name for name in differ if name not in changed]
    assert not unexpected, f"{what}: {unexpected} changed"
    assert set(after) == set(before), f"{what}: layers added or removed: {set(after) ^ set(before)}"
    return differ


def check_layers(addon):
    """Only the active shape key changes, at the free vertices; every other layer is byte-identical."""
    obj = add_subdivided_suzanne()
    decorate(obj)
    add_shape_keys(obj)
    obj.active_shape_key_index = 1  # "A"
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(obj, near_brow)
    bpy.ops.object.mode_set(mode="OBJECT")
    before = layers(obj)
    normals_before = corner_normals(obj)

    for mode in ("EDIT", "OBJECT"):
        if mode == "EDIT":
            bpy.ops.object.mode_set(mode="EDIT")
            result, error = fair(inner_fairness="conformal")
            assert result == {"FINISHED"}, error
            bpy.ops.object.mode_set(mode="OBJECT")
            free = bpy.context.window_manager.geometric_fairing.last_run.free_vertices
        else:
            free = addon.fair_object(obj, inner_fairness="conformal").free_vertices
        after = layers(obj)
        differ = compare(before, after, {"shape key A"}, f"{mode.title()} Mode")
        assert differ == ["shape key A"], differ
        old, new = (np.frombuffer(d["shape key A"], np.float32).reshape(-1, 3) for d in (before, after))
        moved = np.flatnonzero(np.any(old != new, axis=1))
        assert len(moved) == free > 50, (len(moved), free)
        # The mesh's own positions (the basis) did not move: its corner normals are the same bytes.
        assert corner_normals(obj).tobytes() == normals_before.tobytes(), "corner normals changed"
        print(
            f"ok: {mode.title()} Mode: shape key A changed at {len(moved)} free vertices only; "
            f"{len(before) - 1} other layers byte-identical{CUSTOM_NORMALS_NOTE}"
        )
        # Back to the original for the other mode.
        obj.data.shape_keys.key_blocks["A"].data.foreach_set("co", old.ravel())
        obj.data.update()
        assert layers(obj) == before
    bpy.data.objects.remove(obj)


def check_layers_without_shape_keys(addon):
    """Without shape keys the mesh positions change at the free vertices only, with custom normals etc. kept."""
    obj = add_subdivided_suzanne()
    decorate(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(obj, near_brow)
    bpy.ops.object.mode_set(mode="OBJECT")
    before = layers(obj)
    normals_before = corner_normals(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    result, error = fair(inner_fairness="conformal", remesh="off")  # the default, given
    assert result == {"FINISHED"}, error
    bpy.ops.object.mode_set(mode="OBJECT")
    after = layers(obj)
    differ = compare(before, after, {"co", "attribute position"}, "no shape keys")
    assert differ == ["co"], differ
    # Corner normals (custom) are the same bytes wherever no face around the corner's vertex changed.
    old, new = (np.frombuffer(d["co"], np.float32).reshape(-1, 3) for d in (before, after))
    moved = np.any(old != new, axis=1)
    corners = get(obj.data.loops, "vertex_index", np.int32)
    face_of_corner = np.repeat(np.arange(len(obj.data.polygons)), get(obj.data.polygons, "loop_total", np.int32))
    changed_faces = np.unique(face_of_corner[moved[corners]])
    affected = np.zeros(len(old), dtype=bool)
    affected[corners[np.isin(face_of_corner, changed_faces)]] = True
    keep = ~affected[corners]
    assert corner_normals(obj)[keep].tobytes() == normals_before[keep].tobytes(), "corner normals changed far away"
    print(
        f"ok: without shape keys only the positions changed, at {moved.sum()} vertices; {len(before) - 1} other "
        f"layers byte-identical{CUSTOM_NORMALS_NOTE}; corner normals identical at the {keep.sum()} corners "
        "away from the changed faces"
    )
    bpy.data.objects.remove(obj)


def duplicate(obj, name):
    copy = obj.copy()
    copy.data = obj.data.copy()
    copy.name = name
    bpy.context.collection.objects.link(copy)
    return copy


def check_shape_keys_edit_equals_object_mode(addon):
    """Edit Mode (operator) and Object Mode (fair_object) store the same bytes in every key and the mesh."""
    original = add_subdivided_suzanne()
    add_shape_keys(original, relative_to={"B": "A"})  # A and C relative to the basis, B to A
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(original, near_brow)
    bpy.ops.object.mode_set(mode="OBJECT")
    mask = get(original.data.polygons, "select", bool)
    # With the basis active, B (relative to A, relative to the basis) moves too from Blender 4.0 on.
    with_basis = {"Basis", "A", "C", "co"} | ({"B"} if bpy.app.version >= (4, 0, 0) else set())
    for active, moves in ((0, with_basis), (1, {"A", "B"})):
        in_edit = duplicate(original, "Edited")
        in_object = duplicate(original, "Scripted")
        for obj in (in_edit, in_object):
            obj.active_shape_key_index = active
        before = layers(in_edit)
        for obj in bpy.context.selected_objects:
            obj.select_set(False)
        bpy.context.view_layer.objects.active = in_edit
        in_edit.select_set(True)
        bpy.ops.object.mode_set(mode="EDIT")
        result, error = fair(inner_fairness="conformal")
        assert result == {"FINISHED"}, error
        bpy.ops.object.mode_set(mode="OBJECT")
        addon.fair_object(in_object, region=mask, inner_fairness="conformal")
        edited, scripted = layers(in_edit), layers(in_object)
        assert edited == scripted, [name for name in edited if edited[name] != scripted[name]]
        differ = compare(before, edited, {f"shape key {name}" for name in moves} | {"co", "attribute position"}, "")
        expected = sorted(f"shape key {name}" if name != "co" else name for name in moves)
        assert differ == expected, (differ, expected)
        name = in_edit.data.shape_keys.key_blocks[active].name
        print(f"ok: active key {name}: Edit Mode and Object Mode store identical bytes; changed: {', '.join(differ)}")
        bpy.data.objects.remove(in_edit)
        bpy.data.objects.remove(in_object)
    bpy.data.objects.remove(original)


def check_hidden_faces(addon):
    obj = add_subdivided_suzanne()
    centres = face_centres(obj)
    region = np.array([near_brow(c) for c in centres])
    middle = centres[region][np.argmin(np.linalg.norm(centres[region] - BROW, axis=1))]
    # Hidden: a patch in the middle of the region, and faces just outside it on one side.
    hide = (np.linalg.norm(centres - middle, axis=1) < 0.06) | (
        (np.linalg.norm(centres - BROW, axis=1) > 0.25)
        & (np.linalg.norm(centres - BROW, axis=1) < 0.32)
        & (centres[:, 0] > BROW[0])
    )
    assert 4 <= np.count_nonzero(hide & region) and 4 <= np.count_nonzero(hide & ~region), np.count_nonzero(hide)
    bpy.ops.object.mode_set(mode="EDIT")
    bm = bmesh.from_edit_mesh(obj.data)
    bm.faces.ensure_lookup_table()
    select_faces(obj, lambda c: False)
    for i in np.flatnonzero(hide):
        bm.faces[i].select_set(True)
    bmesh.update_edit_mesh(obj.data)
    bpy.ops.mesh.hide(unselected=False)
    bm = bmesh.from_edit_mesh(obj.data)
    bm.faces.ensure_lookup_table()
    assert np.array_equal([f.hide for f in bm.faces], hide)
    for face in bm.faces:  # the region without the hidden faces (Blender never selects a hidden face)
        face.select_set(bool(region[face.index]) and not face.hide)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data)
    hidden_vertices = np.unique([v.index for f in bm.faces if f.hide for v in f.verts])
    bpy.ops.ed.undo_push(message="hid faces")

    def positions():
        if obj.mode == "EDIT":
            obj.update_from_editmode()
        return get(obj.data.vertices, "co", np.float32, 3).reshape(-1, 3)

    def restore():
        bpy.ops.object.mode_set(mode="OBJECT")
        obj.data.vertices.foreach_set("co", before.ravel())
        obj.data.update()
        bpy.ops.object.mode_set(mode="EDIT")
        assert positions().tobytes() == before.tobytes()

    before = positions()
    result, error = fair(inner_fairness="conformal")
    assert result == {"FINISHED"}, error
    default = positions()
    last = bpy.context.window_manager.geometric_fairing.last_run
    assert default[hidden_vertices].tobytes() == before[hidden_vertices].tobytes(), "a hidden vertex moved"
    moved = np.flatnonzero(np.any(default != before, axis=1))
    assert len(moved) == last.free_vertices > 30 and "vertices of hidden faces kept fixed" in last.message
    print(f"ok: hidden faces: {len(hidden_vertices)} vertices of hidden faces unchanged, {len(moved)} moved")

    # The same as fairing the mesh with the hidden faces deleted.
    bpy.ops.ed.undo()
    bpy.ops.object.mode_set(mode="OBJECT")
    without = duplicate(obj, "Without hidden faces")
    bm = bmesh.new()
    bm.from_mesh(without.data)
    bmesh.ops.delete(bm, geom=[f for f in bm.faces if f.hide], context="FACES_ONLY")
    bm.to_mesh(without.data)
    bm.free()
    assert len(without.data.vertices) == len(before)
    selected = get(without.data.polygons, "select", bool)
    addon.fair_object(without, region=selected, inner_fairness="conformal")
    reference = get(without.data.vertices, "co", np.float32, 3).reshape(-1, 3)
    difference = np.abs(reference - default).max()
    assert difference < 1e-6, difference
    print(f"ok: the result equals fairing the mesh with the hidden faces deleted (max difference {difference:.1e})")
    bpy.data.objects.remove(without)

    # Object Mode (fair_object) leaves hidden faces out too.
    report = addon.fair_object(obj, inner_fairness="conformal")
    scripted = positions()
    assert report.hidden_fixed_vertices > 0 and scripted[hidden_vertices].tobytes() == before[hidden_vertices].tobytes()
    assert np.abs(scripted - default).max() < 1e-6
    obj.data.vertices.foreach_set("co", before.ravel())
    obj.data.update()
    print("ok: fair_object leaves hidden faces out too")

    # Use Hidden Faces: the hidden faces are unselected faces around the region now, so their
    # vertices still stay, but their normals shape the result.
    bpy.ops.object.mode_set(mode="EDIT")
    result, error = fair(inner_fairness="conformal", use_hidden=True)
    assert result == {"FINISHED"}, error
    used = positions()
    assert used[hidden_vertices].tobytes() == before[hidden_vertices].tobytes()
    assert np.abs(used - default).max() > 1e-4, "Use Hidden Faces changed nothing"
    print(f"ok: Use Hidden Faces: hidden faces shape the boundary (max difference {np.abs(used - default).max():.3g})")
    restore()

    # A region group over hidden faces: they move only with Use Hidden Faces.
    bpy.ops.object.mode_set(mode="OBJECT")
    inside = np.unique(get(obj.data.loops, "vertex_index", np.int32).reshape(-1, 4)[region])
    obj.vertex_groups.new(name="Patch").add(inside.tolist(), 1.0, "REPLACE")
    bpy.ops.object.mode_set(mode="EDIT")
    result, error = fair(inner_fairness="conformal", region_group="Patch")
    assert result == {"FINISHED"}, error
    assert positions()[hidden_vertices].tobytes() == before[hidden_vertices].tobytes()
    restore()
    result, error = fair(inner_fairness="conformal", region_group="Patch", use_hidden=True)
    assert result == {"FINISHED"}, error
    hidden_moved = np.any(positions()[hidden_vertices] != before[hidden_vertices], axis=1)
    assert hidden_moved.sum() >= 4, hidden_moved.sum()
    print(f"ok: region group over hidden faces: they stay by default; with Use Hidden Faces {hidden_moved.sum()} move")
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.data.objects.remove(obj)


def main():
    folder, _ = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon = enable_addon(folder)
    check_layers(addon)
    check_layers_without_shape_keys(addon)
    check_shape_keys_edit_equals_object_mode(addon)
    check_hidden_faces(addon)
    disable_addon()
    print("check_mesh_data: all checks passed")


main()
