"""Check the Geometric Fairing operator inside Blender; raises (non-zero exit) on failure.

Runs in Blender 3.4+ and in the ``bpy`` module from PyPI:

    blender --background --factory-startup --python-exit-code 1 \\
        --python tests/blender/check_operator.py -- build/addon
    python3 tests/blender/check_operator.py -- build/addon

The argument after ``--`` is the folder holding the ``geometric_fairing``
package (default: ``<repo>/build/addon``). With ``--no-native`` the compiled
module is made unimportable, and it checks instead that the add-on still
registers and that the operator cancels with a clear message.
"""

import importlib
import pathlib
import sys

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import bmesh
import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]


def parse_args():
    args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    no_native = "--no-native" in args
    folders = [a for a in args if a != "--no-native"]
    return pathlib.Path(folders[0] if folders else REPO / "build" / "addon").resolve(), no_native


def enable_addon(folder, no_native=False):
    """Import ``geometric_fairing`` from ``folder`` and register it (same on Blender 3.4 and 4.5)."""
    if not (folder / "geometric_fairing" / "__init__.py").is_file():
        raise FileNotFoundError(f"no geometric_fairing add-on in {folder}")
    if no_native:  # a None entry in sys.modules makes the import raise ImportError
        sys.modules["geometric_fairing.geofair"] = None
        sys.modules["geofair"] = None
    sys.path.insert(0, str(folder))
    addon = importlib.import_module("geometric_fairing")
    assert pathlib.Path(addon.__file__).parent == folder / "geometric_fairing", addon.__file__
    addon.register()
    return addon


def fair(**properties):
    """Run the operator as a script would, with an undo push; return (result, error message)."""
    try:
        return bpy.ops.mesh.geometric_fairing("EXEC_DEFAULT", True, **properties), ""
    except RuntimeError as error:  # an operator that reports an ERROR raises in scripts
        return {"CANCELLED"}, str(error)


def snapshot(obj):
    """Positions (float32), every UV layer (raw bytes) and the face selection of the edit mesh."""
    obj.update_from_editmode()
    mesh = obj.data
    positions = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get("co", positions)
    selected = np.empty(len(mesh.polygons), dtype=bool)
    mesh.polygons.foreach_get("select", selected)
    # In Edit Mode the mesh's UV layers read as empty: read the BMesh's (float32 as stored).
    bm = bmesh.from_edit_mesh(mesh)
    uvs = {}
    for name, layer in bm.loops.layers.uv.items():
        uv = np.array([loop[layer].uv[:] for face in bm.faces for loop in face.loops], dtype=np.float32)
        assert uv.shape == (len(mesh.loops), 2), uv.shape
        uvs[name] = uv.tobytes()
    return positions.reshape(-1, 3), uvs, selected


def object_mode_data(obj):
    """Positions and UV layers read with foreach_get in Object Mode (raw bytes)."""
    mesh = obj.data
    positions = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get("co", positions)
    uvs = []
    for layer in mesh.uv_layers:
        uv = np.empty(2 * len(mesh.loops), dtype=np.float32)
        layer.data.foreach_get("uv", uv)
        uvs.append(uv.tobytes())
    return positions.tobytes(), uvs


def add_subdivided_suzanne():
    bpy.ops.mesh.primitive_monkey_add()
    obj = bpy.context.active_object
    modifier = obj.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels = 2
    bpy.ops.object.modifier_apply(modifier=modifier.name)
    assert len(obj.data.uv_layers) == 1, "Suzanne comes with a UV map"
    return obj


def select_faces(obj, inside):
    """In Edit Mode, select exactly the faces whose centre satisfies ``inside(centre)``."""
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bm = bmesh.from_edit_mesh(obj.data)
    for element in (*bm.verts, *bm.edges, *bm.faces):
        element.select = False
    for face in bm.faces:
        if inside(np.array(face.calc_center_median())):
            face.select_set(True)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)


def expect_cancelled(obj, what, message):
    before = snapshot(obj)
    result, error = fair()
    assert result == {"CANCELLED"}, f"{what}: expected CANCELLED, got {result}"
    assert message in error, f"{what}: message {error!r} lacks {message!r}"
    after = snapshot(obj)
    assert np.array_equal(before[0], after[0]) and before[1] == after[1], f"{what}: mesh changed"
    print(f"ok: {what} -> CANCELLED ({error.strip()})")


def check_fairing(obj, **properties):
    """Fair the current selection, check the result, undo, and check the undo."""
    positions, uvs, selected = snapshot(obj)
    mesh = obj.data
    corners = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", corners)
    starts = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_start", starts)
    face_of_corner = np.repeat(np.arange(len(starts)), np.diff(np.append(starts, len(corners))))
    fixed = np.zeros(len(positions), dtype=bool)  # vertices of unselected faces never move
    fixed[corners[~selected[face_of_corner]]] = True
    inner = np.ones(len(positions), dtype=bool)  # vertices with all faces selected
    inner[corners[~selected[face_of_corner]]] = False
    bm = bmesh.from_edit_mesh(mesh)
    fixed |= np.array([v.is_boundary for v in bm.verts])  # the open mesh border stays put too

    bpy.ops.ed.undo_push(message="before fairing")
    result, error = fair(**properties)
    assert result == {"FINISHED"}, f"{properties}: {result} {error}"
    faired, faired_uvs, faired_selected = snapshot(obj)

    assert np.isfinite(faired).all(), "non-finite positions"
    assert np.array_equal(faired[fixed], positions[fixed]), "a vertex outside the selection or on the border moved"
    moved = np.any(faired != positions, axis=1)
    assert moved[inner].mean() > 0.5, f"only {moved[inner].sum()} of {inner.sum()} inner vertices moved"
    assert faired_uvs == uvs, "UV layers changed"
    assert np.array_equal(faired_selected, selected), "selection changed"
    shift = np.linalg.norm(faired - positions, axis=1).max()
    print(f"ok: {properties or 'defaults'}: {moved.sum()} vertices moved (max {shift:.4f}), UVs identical")

    bpy.ops.ed.undo()
    restored, restored_uvs, _ = snapshot(obj)
    assert np.array_equal(restored, positions), "undo did not restore the positions"
    assert restored_uvs == uvs, "undo changed the UV layers"
    print("ok: undo restored the mesh exactly")


def main():
    folder, no_native = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon = enable_addon(folder, no_native)
    assert addon.operators.MESH_OT_geometric_fairing.bl_idname == "mesh.geometric_fairing"
    assert addon.ui.draw_menu_entry in bpy.types.VIEW3D_MT_edit_mesh._dyn_ui_initialize()

    obj = add_subdivided_suzanne()
    assert not bpy.ops.mesh.geometric_fairing.poll(), "poll must fail in Object Mode"
    original = object_mode_data(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    assert bpy.ops.mesh.geometric_fairing.poll()

    # The left brow, clear of the open borders around the eyes.
    centre = np.array([0.4, -0.7, 0.72])
    select_faces(obj, lambda c: np.linalg.norm(c - centre) < 0.25)

    if no_native:
        assert addon.operators.geofair is None, "expected the add-on without its compiled module"
        expect_cancelled(obj, "no compiled module", "compiled module 'geofair' is missing")
        bpy.ops.object.mode_set(mode="OBJECT")  # the bpy module may hang at exit in Edit Mode
        addon.unregister()
        print("check_operator (no native module): all checks passed")
        return

    check_fairing(obj)
    check_fairing(obj, inner_fairness="CONFORMAL")
    check_fairing(obj, outer_fairness="BILAPLACIAN", tolerance=1e-5, max_iterations=500)
    # Brow and eye socket: reaches the open border around the eye, whose vertices stay fixed.
    select_faces(obj, lambda c: np.linalg.norm(c - [0.45, -0.7, 0.45]) < 0.3)
    check_fairing(obj)

    select_faces(obj, lambda c: False)
    expect_cancelled(obj, "nothing selected", "No face is selected")
    bpy.context.tool_settings.mesh_select_mode = (True, False, False)
    bm = bmesh.from_edit_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    bm.verts[0].select_set(True)
    bm.verts[1].select_set(True)
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)
    expect_cancelled(obj, "two vertices, no face selected", "No face is selected")
    nearest = min(np.linalg.norm(np.array(f.calc_center_median()) - centre) for f in bm.faces)
    select_faces(obj, lambda c: np.linalg.norm(c - centre) <= nearest)  # a single face
    expect_cancelled(obj, "a selection surrounding no vertex", "No vertex lies inside")

    bpy.ops.object.mode_set(mode="OBJECT")
    assert object_mode_data(obj) == original, "after undo and cancelled runs the mesh differs"
    print("ok: in Object Mode, positions and UVs read with foreach_get equal the original bytes")
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, location=(4, 0, 0))
    sphere = bpy.context.active_object
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(sphere, lambda c: True)
    expect_cancelled(sphere, "whole closed mesh selected", "whole closed part")

    bpy.ops.object.mode_set(mode="OBJECT")
    addon.unregister()
    print("check_operator: all checks passed")


main()
