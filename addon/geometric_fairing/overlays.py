"""Zebra stripes and mean-curvature colours in the 3D View, each removable leaving nothing behind.

- Zebra (reflection lines): Solid shading lit by a matcap of horizontal light
  bands (:func:`display.zebra_matcap`), loaded as a studio light from a
  temporary PNG. It shows on every object in that 3D View. No material, node
  group or image is made; the studio light and its file are removed when the
  last view turns zebra off.
- Live Fair Drag's radius: a circle drawn in the view while the drag runs
  (:func:`draw_circle_2d`, from the operator's draw handler).
- Mean curvature: H from ``geofair.mean_curvature`` as a float colour attribute
  (point domain) of the active mesh, blue–white–red symmetric around 0, shown
  with Solid shading coloured by attribute. Removed on toggling off. On at most
  one mesh at a time.

Turning either on records the settings it changes; turning it off restores them
exactly, in either order with the other toggle: the view's shading type and
colour type (shared, restored when the last toggle that changed them is off),
the lighting with its studio light and hidden matcap choice, the mesh's active
and render colour attributes. A file is never saved with either on: they are
taken off before saving and put back after.
"""

import math
import os
import shutil
import tempfile

import bmesh
import bpy
import gpu
from gpu_extras.batch import batch_for_shader

from . import display, mesh_io, native

ZEBRA_LIGHT = "geofair_zebra.png"
ZEBRA_STRIPES = 16
CURVATURE_ATTRIBUTE = "Mean Curvature (geofair)"

# View-space settings shared by both toggles: space pointer -> {setting: [original value, set of owners]}.
_overrides = {}
# Zebra: space pointer -> (light, studio light if the light was Studio, matcap); Blender keeps the matcap choice apart.
_zebra = {}
# Curvature: mesh name -> (active colour attribute, render colour attribute) before it was turned on. By name:
# global undo reallocates meshes.
_curvature = {}
_zebra_file = None  # the matcap PNG while the studio light is loaded


def draw_circle_2d(centre, radius, colour=(1.0, 1.0, 1.0, 0.7), segments=64):
    """A circle of ``radius`` pixels around ``centre`` (region pixels), in a POST_PIXEL draw handler."""
    try:
        shader = gpu.shader.from_builtin("UNIFORM_COLOR")
    except ValueError:  # Blender before 4.0 names it by dimension
        shader = gpu.shader.from_builtin("2D_UNIFORM_COLOR")
    points = [
        (
            centre[0] + radius * math.cos(2 * math.pi * k / segments),
            centre[1] + radius * math.sin(2 * math.pi * k / segments),
        )
        for k in range(segments + 1)
    ]
    batch = batch_for_shader(shader, "LINE_STRIP", {"pos": points})
    gpu.state.blend_set("ALPHA")
    shader.bind()
    shader.uniform_float("color", colour)
    batch.draw(shader)
    gpu.state.blend_set("NONE")


# -- finding views and meshes by pointer (never keep Blender structs across calls) -------------------------------


def view3d_spaces():
    """Every 3D View space of every screen."""
    for screen in bpy.data.screens:
        for area in screen.areas:
            for space in area.spaces:
                if space.type == "VIEW_3D":
                    yield space


def _space(key):
    return next((space for space in view3d_spaces() if space.as_pointer() == key), None)


def _mesh(key):
    return bpy.data.meshes.get(key)


def _override(key, shading, owner, name, value):
    record = _overrides.setdefault(key, {})
    if name not in record:
        record[name] = [getattr(shading, name), set()]
    record[name][1].add(owner)
    setattr(shading, name, value)


def _release(key, shading, owner):
    record = _overrides.get(key, {})
    for name in list(record):
        original, owners = record[name]
        owners.discard(owner)
        if not owners:
            if shading is not None:
                setattr(shading, name, original)
            del record[name]
    if not record:
        _overrides.pop(key, None)


# -- zebra -------------------------------------------------------------------------------------------------------


def zebra_enabled(space):
    """Whether zebra stripes are on in the 3D View ``space``."""
    return space is not None and space.as_pointer() in _zebra


def _zebra_light():
    """The zebra matcap studio light, loaded (from a new temporary PNG) if needed."""
    global _zebra_file
    lights = bpy.context.preferences.studio_lights
    light = next((light for light in lights if light.name == ZEBRA_LIGHT and light.type == "MATCAP"), None)
    if light is None:
        folder = tempfile.mkdtemp(prefix="geofair-")
        _zebra_file = os.path.join(folder, ZEBRA_LIGHT)
        display.write_png(_zebra_file, display.zebra_matcap(stripes=ZEBRA_STRIPES))
        light = lights.load(_zebra_file, "MATCAP")
    return light


def _remove_zebra_light():
    global _zebra_file
    lights = bpy.context.preferences.studio_lights
    for light in [light for light in lights if light.name == ZEBRA_LIGHT and light.type == "MATCAP"]:
        lights.remove(light)
    if _zebra_file is not None:
        shutil.rmtree(os.path.dirname(_zebra_file), ignore_errors=True)
        _zebra_file = None


def zebra_on(space):
    """Show reflection lines in the 3D View ``space`` (Solid shading, zebra matcap)."""
    key = space.as_pointer()
    if key in _zebra:
        return
    light = _zebra_light()
    shading = space.shading
    _override(key, shading, "zebra", "type", "SOLID")
    previous_light = shading.light
    previous_studio = shading.studio_light if previous_light == "STUDIO" else None  # Flat has none
    shading.light = "MATCAP"
    _zebra[key] = (previous_light, previous_studio, shading.studio_light)
    shading.studio_light = light.name


def zebra_off(space):
    """Remove the reflection lines from ``space``, restoring its shading; unload the matcap if no view uses it."""
    key = space.as_pointer()
    _restore_zebra(key, space.shading)
    if not _zebra:
        _remove_zebra_light()


def _restore_zebra(key, shading):
    saved = _zebra.pop(key, None)
    if saved is None:
        return
    light, studio, matcap = saved
    if shading is not None:
        shading.light = "MATCAP"
        shading.studio_light = matcap  # Blender keeps the matcap choice even while another light is used
        shading.light = light
        if studio is not None:
            shading.studio_light = studio
    _release(key, shading, "zebra")


# -- mean curvature ----------------------------------------------------------------------------------------------


def curvature_enabled(mesh):
    """Whether ``mesh`` carries the mean-curvature colours."""
    return mesh is not None and CURVATURE_ATTRIBUTE in mesh.attributes


def _curvature_colors(obj, limit=None):
    if native.geofair is None:
        raise RuntimeError(native.IMPORT_ERROR)
    data = mesh_io.read(obj, uvs=False)
    h = native.geofair.mean_curvature(data.vertices, data.triangles)
    return display.curvature_colors(h, limit)


def _write_colors(obj, colors):
    mesh = obj.data
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(mesh)
        layers = bm.verts.layers.float_color
        layer = layers.get(CURVATURE_ATTRIBUTE) or layers.new(CURVATURE_ATTRIBUTE)
        for vertex, color in zip(bm.verts, colors.tolist(), strict=True):
            vertex[layer] = color
        bmesh.update_edit_mesh(mesh, loop_triangles=False, destructive=False)
    else:
        attribute = mesh.color_attributes.get(CURVATURE_ATTRIBUTE)
        if attribute is None:
            attribute = mesh.color_attributes.new(CURVATURE_ATTRIBUTE, "FLOAT_COLOR", "POINT")
        attribute.data.foreach_set("color", colors.ravel())
        mesh.update()


def curvature_on(obj, space, context=None):
    """Colour ``obj`` by its mean curvature and show the colours in the 3D View ``space``.

    Returns the colour range: H = ±limit (1/length) are full red and blue.
    Raises RuntimeError without the compiled module.
    """
    context = context or bpy.context
    mesh = obj.data
    for key in list(_curvature):  # one mesh at a time
        if key != mesh.name:
            curvature_off(_mesh(key))
    colors, limit = _curvature_colors(obj)
    if mesh.name not in _curvature:
        attributes = mesh.color_attributes
        _curvature[mesh.name] = (attributes.active_color_name, attributes.default_color_name)
    _write_colors(obj, colors)
    mesh.color_attributes.active_color = mesh.color_attributes[CURVATURE_ATTRIBUTE]
    if space is not None:
        key = space.as_pointer()
        _override(key, space.shading, "curvature", "type", "SOLID")
        _override(key, space.shading, "curvature", "color_type", "VERTEX")
    session = getattr(context.window_manager, "geometric_fairing", None)
    if session is not None:
        session.curvature_limit = limit
    return limit


def refresh_curvature(obj, context=None):
    """Recompute the colours of ``obj`` if it shows them (after fairing), keeping the colour range."""
    if obj is None or obj.type != "MESH" or not curvature_enabled(obj.data):
        return
    context = context or bpy.context
    session = getattr(context.window_manager, "geometric_fairing", None)
    limit = session.curvature_limit if session is not None and session.curvature_limit > 0 else None
    colors, _ = _curvature_colors(obj, limit)
    _write_colors(obj, colors)


def curvature_off(mesh):
    """Remove the colours from ``mesh`` and restore its colour attributes and every view's shading."""
    if mesh is not None:
        attribute = mesh.attributes.get(CURVATURE_ATTRIBUTE)
        if attribute is not None:
            mesh.attributes.remove(attribute)
        saved = _curvature.pop(mesh.name, None)
        if saved is not None:
            _restore_color_names(mesh, *saved)
    if not _curvature:
        for key in _views_with("curvature"):
            space = _space(key)
            _release(key, space.shading if space is not None else None, "curvature")


def _views_with(owner):
    """Pointers of the views whose shading ``owner`` ("zebra", "curvature") has changed."""
    return [key for key, record in _overrides.items() if any(owner in owners for _, owners in record.values())]


def _restore_color_names(mesh, active, render):
    attributes = mesh.color_attributes
    if active and active in attributes:
        attributes.active_color = attributes[active]
    if render and render in attributes:
        attributes.default_color_name = render


# -- everything off: unregister, loading and saving files ----------------------------------------------------------


def all_off():
    """Turn zebra and curvature off everywhere, restoring what they changed."""
    for key in list(_zebra):
        space = _space(key)
        _restore_zebra(key, space.shading if space is not None else None)
    for key in list(_curvature):
        curvature_off(_mesh(key))
    for key in list(_overrides):  # views that were closed meanwhile
        space = _space(key)
        for owner in ("zebra", "curvature"):
            _release(key, space.shading if space is not None else None, owner)
    _curvature.clear()
    _remove_zebra_light()


def forget():
    """Drop every record without touching Blender data (the file they belong to is being closed)."""
    _overrides.clear()
    _zebra.clear()
    _curvature.clear()
    _remove_zebra_light()


_suspended = None


@bpy.app.handlers.persistent
def _save_pre(*_args):
    global _suspended
    if _zebra or _curvature:
        _suspended = (list(_zebra), [(key, _views_with("curvature")) for key in _curvature])
        all_off()


@bpy.app.handlers.persistent
def _save_post(*_args):
    global _suspended
    if _suspended is None:
        return
    zebra, curvature = _suspended
    _suspended = None
    for key in zebra:
        space = _space(key)
        if space is not None:
            zebra_on(space)
    for key, views in curvature:
        mesh = _mesh(key)
        obj = next((o for o in bpy.data.objects if o.data == mesh), None) if mesh is not None else None
        if obj is None:
            continue
        spaces = [space for space in (_space(view) for view in views) if space is not None] or [None]
        for space in spaces:
            curvature_on(obj, space)


@bpy.app.handlers.persistent
def _load_pre(*_args):
    forget()


HANDLERS = ((bpy.app.handlers.save_pre, _save_pre), (bpy.app.handlers.save_post, _save_post))


def register():
    """Install the file handlers."""
    for handlers, handler in (*HANDLERS, (bpy.app.handlers.load_pre, _load_pre)):
        if handler not in handlers:
            handlers.append(handler)


def unregister():
    """Turn everything off and remove the handlers."""
    all_off()
    for handlers, handler in (*HANDLERS, (bpy.app.handlers.load_pre, _load_pre)):
        if handler in handlers:
            handlers.remove(handler)
