"""Blender-side helpers of the tests (tests/blender/check_*.py), benchmarks (bench/blender_*.py)
and scripts: enabling the add-on from a folder, Suzanne, selecting faces, reading positions.

They run inside Blender 3.4+ and the ``bpy`` module from PyPI. Each check script is run as

    blender --background --factory-startup --python-exit-code 1 --python tests/blender/<script>.py -- build/addon
    python3 tests/blender/<script>.py -- build/addon

and raises (non-zero exit) on failure; ``geofair_dev`` must import there (scripts/setup.sh
installs it for ``python3`` and for Debian's Python that Blender 3.4 runs; tests/test_blender.py
passes ``PYTHONPATH``: geofair_dev.paths).
"""

import importlib
import os
import pathlib
import sys
import time
import traceback

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import addon_utils
import bmesh
import numpy as np

from geofair_dev import paths


def parse_args():
    """``(addon folder, flags)`` from the arguments after ``--`` (default folder: ``paths.BUILT_ADDON``)."""
    args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    flags = {a for a in args if a.startswith("--")}
    folders = [a for a in args if not a.startswith("--")]
    return pathlib.Path(folders[0] if folders else paths.BUILT_ADDON).resolve(), flags


def enable_addon(folder, no_native=False):
    """Enable ``geometric_fairing`` from ``folder`` the way Preferences does (so its preferences exist)."""
    if not (folder / "geometric_fairing" / "__init__.py").is_file():
        raise FileNotFoundError(f"no geometric_fairing add-on in {folder}")
    if no_native:  # a None entry in sys.modules makes the import raise ImportError
        sys.modules["geometric_fairing.geofair"] = None
    paths.prepend(folder)
    addon = addon_utils.enable("geometric_fairing", default_set=True, handle_error=_raise)
    assert addon is not None, "addon_utils.enable failed"
    assert pathlib.Path(addon.__file__).parent == folder / "geometric_fairing", addon.__file__
    assert bpy.context.preferences.addons.get("geometric_fairing") is not None
    return importlib.import_module("geometric_fairing")


def disable_addon():
    """Leave Edit Mode and disable the add-on: the bpy module may hang at exit otherwise."""
    if bpy.context.object is not None and bpy.context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    addon_utils.disable("geometric_fairing", default_set=True, handle_error=_raise)


def _raise(error):
    raise error


def add_subdivided_suzanne():
    """Suzanne with a Subdivision Surface modifier (level 2) applied, active, in Object Mode;
    she comes with a UV map. The Suzanne of the checks, benchmarks, scripts and corpus."""
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


def select_vertices(obj, vertices):
    """In Edit Mode, vertex select mode with exactly ``vertices`` (indices) selected."""
    bpy.context.tool_settings.mesh_select_mode = (True, False, False)
    bm = bmesh.from_edit_mesh(obj.data)
    chosen = set(np.asarray(vertices).tolist())
    for vertex in bm.verts:
        vertex.select_set(vertex.index in chosen)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)


def face_centres(obj):
    """``(P, 3)`` face centres of ``obj``'s mesh (Object Mode)."""
    centres = np.empty(3 * len(obj.data.polygons))
    obj.data.polygons.foreach_get("center", centres)
    return centres.reshape(-1, 3)


def positions(obj):
    """``(n, 3)`` float32 positions as stored (the edit mesh's in Edit Mode)."""
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(obj.data)
        return np.array([v.co[:] for v in bm.verts], dtype=np.float32).reshape(-1, 3)
    co = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


def view3d_space():
    """The 3D View of the current screen (there is one in background mode too)."""
    for area in bpy.context.screen.areas:
        if area.type == "VIEW_3D":
            return area, area.spaces.active
    raise RuntimeError("no 3D View in the current screen")


def in_view3d():
    """A context override that makes the operators see the 3D View as ``context.space_data``."""
    area, space = view3d_space()
    region = next(r for r in area.regions if r.type == "WINDOW")
    return bpy.context.temp_override(area=area, region=region, space_data=space)


# Checks in a Blender window (xvfb-run, --enable-event-simulate): steps run from a timer while
# Blender's event loop runs, so they end Blender themselves.


def window_view3d():
    """(window, area, region): the first window's 3D View and its main region."""
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    return window, area, region


def finish(code):
    """Ends Blender at once with exit status ``code`` (a timer cannot use --python-exit-code)."""
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


class TimerSteps:
    """A generator's steps driven by ``bpy.app.timers``: ``yield seconds`` waits; its end exits
    Blender with status 0; an exception prints the traceback and "``name``: FAILED" and exits with 1."""

    def __init__(self, generator, name):
        self.generator, self.name = generator, name

    def __call__(self):
        try:
            return next(self.generator)
        except StopIteration:
            finish(0)
        except Exception:
            traceback.print_exc()
            print(f"{self.name}: FAILED")
            finish(1)


def wait_until(condition, what, timeout=60.0):
    """Timer steps (``yield from``) until ``condition()`` holds; AssertionError naming ``what``
    after ``timeout`` seconds."""
    start = time.perf_counter()
    while not condition():
        if time.perf_counter() - start > timeout:
            raise AssertionError(f"timed out waiting for {what}")
        yield 0.05


def run_fairing(**properties):
    """Run the operator as a script would, with an undo push; return (result, error text)."""
    try:
        return bpy.ops.mesh.geometric_fairing("EXEC_DEFAULT", True, **properties), ""
    except RuntimeError as error:  # an operator that reports an ERROR raises in scripts
        return {"CANCELLED"}, str(error).strip()


def edit_state(obj):
    """Everything the checks compare, as bytes: positions, every UV layer, selection and hiding of the edit mesh."""
    obj.update_from_editmode()
    mesh = obj.data
    data = {}
    for name, collection, attribute, dtype, width in (
        ("co", mesh.vertices, "co", np.float32, 3),
        ("vertex select", mesh.vertices, "select", bool, 1),
        ("edge select", mesh.edges, "select", bool, 1),
        ("face select", mesh.polygons, "select", bool, 1),
        ("face hide", mesh.polygons, "hide", bool, 1),
    ):
        values = np.empty(len(collection) * width, dtype=dtype)
        collection.foreach_get(attribute, values)
        data[name] = values.tobytes()
    bm = bmesh.from_edit_mesh(mesh)
    for name, layer in bm.loops.layers.uv.items():  # in Edit Mode the mesh's UV layers read as empty
        data[f"uv {name}"] = np.array([loop[layer].uv[:] for f in bm.faces for loop in f.loops], np.float32).tobytes()
    return data


class FailingModule:
    """Stands in for the loaded ``geofair`` module: ``fair`` raises ``error``; everything else is the real one's."""

    def __init__(self, real, error):
        self.real, self.error, self.calls = real, error, 0

    def fair(self, *args, **kwargs):
        self.calls += 1
        raise self.error

    def __getattr__(self, name):
        return getattr(self.real, name)


def side_by_side(paths, out, shrink=0.75, crop=1.0):
    """Put screenshots (PNG files) side by side, white gaps between, each cut to the middle
    ``crop`` of its width, scaled by ``shrink`` (a lighter file, still sharp), and save the
    strip as PNG at ``out``; the inputs are deleted."""
    images = [bpy.data.images.load(str(path)) for path in paths]
    pixels = []
    for image in images:
        data = np.empty(len(image.pixels), dtype=np.float32)
        image.pixels.foreach_get(data)
        data = data.reshape(image.size[1], image.size[0], 4)
        keep = int(round(crop * data.shape[1]))
        start = (data.shape[1] - keep) // 2
        pixels.append(data[:, start : start + keep])
    height = min(p.shape[0] for p in pixels)
    gap = np.ones((height, 12, 4), dtype=np.float32)
    parts = [pixels[0][:height]]
    for p in pixels[1:]:
        parts += [gap, p[:height]]
    combined = np.concatenate(parts, axis=1)
    result = bpy.data.images.new(pathlib.Path(out).stem, combined.shape[1], combined.shape[0], alpha=True)
    result.pixels.foreach_set(combined.ravel())
    result.scale(int(combined.shape[1] * shrink), int(combined.shape[0] * shrink))
    result.filepath_raw = str(out)
    result.file_format = "PNG"
    result.save()
    for image in (*images, result):
        bpy.data.images.remove(image)
    for path in paths:
        pathlib.Path(path).unlink()
