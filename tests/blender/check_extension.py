"""Install the extension zip into a fresh user folder and fair the UV sphere's cap with the operator.

    python3 tests/blender/check_extension.py -- EXTENSION.zip OUT.npz   (bpy 4.5 or 5.0 module)

- installs the zip with Blender's ``extension install-file -r user_default -e`` (the handler
  that ``blender --command extension`` runs), which installs the wheel it lists;
- the enabled add-on ``bl_ext.user_default.geometric_fairing`` loads ``geofair`` from that
  wheel, inside the user folder (not from build/python, not bundled in the add-on);
- a UV sphere (64 segments, 32 rings), in Edit Mode the faces with a vertex above z = 0.25
  selected, faired by ``mesh.geometric_fairing``; the region the add-on fairs (positions,
  triangles, free vertices, boundary normals, options) and the positions before and after
  go to OUT.npz, where tests/test_extension.py compares them with the build tree's module;
- disables and removes the extension.

The user folders must be redirected to a temporary folder by the caller (environment
BLENDER_USER_RESOURCES, BLENDER_USER_SCRIPTS, BLENDER_USER_CONFIG); the script refuses otherwise.
"""

import dataclasses
import json
import os
import pathlib
import sys

import bpy

# isort: split
import addon_utils
import bmesh
import numpy as np
from bl_pkg import bl_extension_cli

MODULE = "bl_ext.user_default.geometric_fairing"


def arguments():
    args = sys.argv[sys.argv.index("--") + 1 :]
    return pathlib.Path(args[0]).resolve(), pathlib.Path(args[1]).resolve()


def user_folder():
    folder = pathlib.Path(os.environ.get("BLENDER_USER_RESOURCES", ""))
    scripts = pathlib.Path(bpy.utils.user_resource("SCRIPTS"))
    assert str(folder) not in ("", ".") and folder in (scripts, *scripts.parents), (
        f"redirect the user folders first (user scripts: {scripts})"
    )
    return folder


def extension(*args):
    """What ``blender --command extension *args`` does; raises on a non-zero exit."""
    code = bl_extension_cli.cli_extension_handler([str(a) for a in args])
    assert code == 0, f"extension {' '.join(map(str, args))} exited {code}"


def positions(obj):
    co = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3).astype(np.float64)


def uv_sphere_with_cap_selected():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=1.0)
    obj = bpy.context.active_object
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bm = bmesh.from_edit_mesh(obj.data)
    for element in (*bm.verts, *bm.edges, *bm.faces):
        element.select = False
    for face in bm.faces:
        if any(v.co.z > 0.25 for v in face.verts):
            face.select_set(True)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)
    return obj


def main():
    archive, out = arguments()
    folder = user_folder()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, extension {archive.name}")
    extension("install-file", "-r", "user_default", "-e", archive)
    # -e enabled it: registered and in the preferences.
    assert bpy.context.preferences.addons.get(MODULE) is not None, [a.module for a in bpy.context.preferences.addons]
    assert addon_utils.check(MODULE) == (True, True), addon_utils.check(MODULE)
    addon = sys.modules[MODULE]
    assert folder in pathlib.Path(addon.__file__).parents, addon.__file__
    geofair = addon.native.geofair
    assert geofair is not None, addon.native.IMPORT_ERROR
    module_file = pathlib.Path(geofair.__file__)
    assert folder in module_file.parents and "site-packages" in module_file.parts, f"geofair from {module_file}"
    assert not list(pathlib.Path(addon.__file__).parent.glob("geofair*")), "the extension bundles no module"
    print(f"ok: {MODULE} enabled, geofair {geofair.__version__} from its wheel: {module_file}")

    obj = uv_sphere_with_cap_selected()
    options = addon.fairing.FairingOptions()  # the preferences' defaults, passed to the operator explicitly
    run = addon.fairing.FairingRun(obj, options)  # what the operator fairs: read only, nothing solved
    mesh, fairing_region = run.mesh, run.region
    bpy.ops.object.mode_set(mode="OBJECT")
    before = positions(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    # The operator's properties (OPTION_NAMES); the options only scripts pass are not among them.
    given = {
        name: addon.properties.property_value(name, getattr(options, name))
        for name in addon.properties.OPTION_NAMES
        if name not in ("use_hidden", "region_group", "pin_group")
    }
    assert bpy.ops.mesh.geometric_fairing("EXEC_DEFAULT", **given) == {"FINISHED"}
    bpy.ops.object.mode_set(mode="OBJECT")
    after = positions(obj)
    np.savez(
        out,
        before=before,
        after=after,
        vertices=mesh.vertices,
        triangles=mesh.triangles[run.present_triangles],
        polygon_ids=mesh.triangle_face[run.present_triangles],
        free=fairing_region.free,
        boundary_normals=run.boundary_normals,
        options=json.dumps(dataclasses.asdict(options)),
        module=str(module_file),
        blender=bpy.app.version_string,
    )
    moved = np.linalg.norm(after - before, axis=1)
    print(f"ok: the operator faired {int(fairing_region.free.sum())} free vertices, moved up to {moved.max():.4f}")

    addon_utils.disable(MODULE, default_set=True)
    extension("remove", "user_default.geometric_fairing")
    assert not (folder / "extensions" / "user_default" / "geometric_fairing").exists()
    print("check_extension: all checks passed")


main()
