"""Check the panel's zebra and mean-curvature toggles: on shows them, off leaves nothing behind.

Runs in Blender 3.4+ and in the ``bpy`` module from PyPI (see dev/geofair_dev/blender.py). Compares,
before and after each on/off sequence: the data-blocks (materials, node groups,
images, textures), the object's material slots and active material, the mesh's
attributes with the active and render colour attributes, every shading setting
of the 3D View (including the matcap Blender keeps aside while another light is
used) and of the scene, and the loaded studio lights.
"""

import pathlib
import sys
import tempfile

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import numpy as np

from geofair_dev.blender import (
    add_subdivided_suzanne,
    disable_addon,
    enable_addon,
    in_view3d,
    parse_args,
    select_faces,
    view3d_space,
)

DATA_BLOCKS = ("materials", "node_groups", "images", "textures", "worlds")
ATTRIBUTE = "Mean Curvature (geofair)"
ZEBRA = "geofair_zebra.png"


def rna_values(struct):
    """Every readable non-pointer property of an RNA struct, by name."""
    values = {}
    for prop in struct.bl_rna.properties:
        if prop.identifier == "rna_type" or prop.type in ("POINTER", "COLLECTION"):
            continue
        if prop.identifier == "studio_light":
            continue  # its meaning depends on type and light (and reading it may warn): see hidden_choices()
        if prop.identifier == "wireframe_color_type" and isinstance(struct.id_data, bpy.types.Scene):
            continue  # unused by the scene's shading, and 4.5 warns reading its unset value
        value = getattr(struct, prop.identifier)
        values[prop.identifier] = tuple(value) if hasattr(value, "__len__") and not isinstance(value, str) else value
    return values


def hidden_choices(shading):
    """The studio light, matcap and world light Blender remembers apart (switches to each and back)."""
    kind, light, choices = shading.type, shading.light, {}
    shading.type = "SOLID"  # studio_light means the world light in the other types
    for lighting in ("STUDIO", "MATCAP"):
        shading.light = lighting
        choices[lighting] = shading.studio_light
    shading.light = light
    shading.type = "MATERIAL"
    choices["WORLD"] = shading.studio_light
    shading.type = kind
    return choices


def state(obj):
    """Everything a toggle may touch."""
    _, space = view3d_space()
    mesh = obj.data
    return {
        "data": {name: sorted(block.name for block in getattr(bpy.data, name)) for name in DATA_BLOCKS},
        "slots": [(slot.material.name if slot.material else None, slot.link) for slot in obj.material_slots],
        "active_material": (obj.active_material_index, obj.active_material.name if obj.active_material else None),
        "attributes": sorted((a.name, a.domain, a.data_type) for a in mesh.attributes),
        "colors": (mesh.color_attributes.active_color_name, mesh.color_attributes.default_color_name),
        "view_shading": rna_values(space.shading),
        "hidden_choices": hidden_choices(space.shading),
        "scene_shading": rna_values(bpy.context.scene.display.shading),
        "studio_lights": sorted((light.name, light.type) for light in bpy.context.preferences.studio_lights),
    }


def assert_same(before, after, what):
    for key in before:
        if before[key] != after[key]:
            difference = before[key]
            if isinstance(difference, dict):
                difference = {k: (v, after[key].get(k)) for k, v in difference.items() if after[key].get(k) != v}
            raise AssertionError(f"{what}: {key} changed: {difference}")
    print(f"ok: {what}: nothing left behind")


def zebra(action):
    with in_view3d():
        assert bpy.ops.view3d.geometric_fairing_zebra(action=action) == {"FINISHED"}


def curvature(action):
    with in_view3d():
        assert bpy.ops.mesh.geometric_fairing_curvature(action=action) == {"FINISHED"}


def zebra_is_on():
    _, space = view3d_space()
    shading = space.shading
    return shading.type == "SOLID" and shading.light == "MATCAP" and shading.studio_light == ZEBRA


def curvature_colors(obj):
    """``(n, 4)`` colours of the curvature attribute (Object Mode)."""
    attribute = obj.data.color_attributes[ATTRIBUTE]
    assert (attribute.domain, attribute.data_type) == ("POINT", "FLOAT_COLOR"), attribute
    colors = np.empty(4 * len(obj.data.vertices), dtype=np.float32)
    attribute.data.foreach_get("color", colors)
    return colors.reshape(-1, 4)


def check_sequences(obj, addon, label):
    """Each toggle alone and both interleaved, in the current mode: nothing left behind."""
    before = state(obj)
    zebra("ON")
    assert zebra_is_on(), "zebra on: not lit by the zebra matcap"
    assert addon.overlays.zebra_enabled(view3d_space()[1])
    assert (ZEBRA, "MATCAP") in state(obj)["studio_lights"]
    zebra("TOGGLE")
    assert not zebra_is_on()
    assert_same(before, state(obj), f"{label}: zebra on, off")

    curvature("ON")
    mesh = obj.data
    assert ATTRIBUTE in mesh.attributes and mesh.color_attributes.active_color_name == ATTRIBUTE
    assert view3d_space()[1].shading.color_type == "VERTEX"
    assert bpy.context.window_manager.geometric_fairing.curvature_limit > 0
    curvature("TOGGLE")
    assert ATTRIBUTE not in mesh.attributes
    assert_same(before, state(obj), f"{label}: curvature on, off")

    zebra("ON")
    curvature("ON")
    assert zebra_is_on() and view3d_space()[1].shading.color_type == "VERTEX"
    zebra("OFF")
    assert view3d_space()[1].shading.type == "SOLID", "curvature still needs Solid shading"
    curvature("OFF")
    assert_same(before, state(obj), f"{label}: zebra on, curvature on, zebra off, curvature off")

    curvature("ON")
    zebra("ON")
    curvature("OFF")
    assert zebra_is_on()
    zebra("OFF")
    assert_same(before, state(obj), f"{label}: curvature on, zebra on, curvature off, zebra off")


def customize(obj):
    """A state far from the factory settings: a material, a colour attribute, wireframe, flat light."""
    material = bpy.data.materials.new("Skin")
    obj.data.materials.append(material)
    paint = obj.data.color_attributes.new("Paint", "BYTE_COLOR", "CORNER")
    obj.data.color_attributes.active_color = paint
    obj.data.color_attributes.new("Second", "FLOAT_COLOR", "POINT")
    _, space = view3d_space()
    shading = space.shading
    shading.light = "MATCAP"
    shading.studio_light = "ceramic_dark.exr"
    shading.light = "STUDIO"
    shading.studio_light = "paint.sl"
    shading.light = "FLAT"
    shading.type = "WIREFRAME"
    shading.color_type = "OBJECT"


def check_sign_on_a_sphere(addon):
    """H > 0 on a sphere with outward normals: red, not blue; the range is about 1/r."""
    bpy.ops.mesh.primitive_uv_sphere_add(radius=2.0, location=(5, 0, 0), segments=48, ring_count=24)
    sphere = bpy.context.active_object
    before = state(sphere)
    curvature("ON")
    colors = curvature_colors(sphere)
    assert np.all(colors[:, 0] > colors[:, 2] + 0.3), "a sphere should be red (H > 0)"
    limit = bpy.context.window_manager.geometric_fairing.curvature_limit
    assert 0.45 < limit < 0.55, f"range {limit}, expected about 1/r = 0.5"
    curvature("OFF")
    assert_same(before, state(sphere), "sphere: curvature on, off")
    print(f"ok: a sphere of radius 2 is red, colour range ±{limit:.3f}")
    bpy.data.objects.remove(sphere)


def check_fairing_updates_colors(obj):
    bpy.ops.object.mode_set(mode="OBJECT")
    curvature("ON")
    colors = curvature_colors(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(obj, lambda c: np.linalg.norm(c - [0.4, -0.7, 0.72]) < 0.25)
    assert bpy.ops.mesh.geometric_fairing("EXEC_DEFAULT", inner_fairness="conformal") == {"FINISHED"}
    bpy.ops.object.mode_set(mode="OBJECT")
    changed = np.any(curvature_colors(obj) != colors, axis=1)
    assert changed.sum() > 50, f"only {changed.sum()} colours changed after fairing"
    print(f"ok: fairing recomputed the curvature colours ({changed.sum()} vertices changed)")
    curvature("OFF")
    bpy.ops.object.mode_set(mode="EDIT")


def check_save(obj, addon):
    """A file saved with both on holds neither; both are back on after saving."""
    bpy.ops.object.mode_set(mode="OBJECT")
    before = state(obj)
    name = obj.name
    zebra("ON")
    curvature("ON")
    with tempfile.TemporaryDirectory() as folder:
        path = str(pathlib.Path(folder) / "saved.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path, copy=True)
        assert zebra_is_on() and ATTRIBUTE in obj.data.attributes, "saving turned the views off"
        zebra("OFF")
        curvature("OFF")
        assert_same(before, state(obj), "after saving: zebra off, curvature off")
        bpy.ops.wm.open_mainfile(filepath=path)
    obj = bpy.data.objects[name]
    loaded = state(obj)
    for key in ("data", "slots", "active_material", "attributes", "colors", "studio_lights"):
        assert loaded[key] == before[key], f"saved file: {key} {loaded[key]} != {before[key]}"
    assert not zebra_is_on() and loaded["view_shading"]["light"] == before["view_shading"]["light"]
    print("ok: the saved file has no zebra and no curvature attribute")
    return obj


def main():
    folder, _ = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon = enable_addon(folder)
    obj = add_subdivided_suzanne()

    bpy.ops.object.mode_set(mode="EDIT")
    check_sequences(obj, addon, "Edit Mode, factory settings")
    bpy.ops.object.mode_set(mode="OBJECT")
    check_sequences(obj, addon, "Object Mode, factory settings")
    customize(obj)
    check_sequences(obj, addon, "Object Mode, custom settings")
    bpy.ops.object.mode_set(mode="EDIT")
    check_sequences(obj, addon, "Edit Mode, custom settings")

    before = state(obj)  # on in Edit Mode, off in Object Mode
    curvature("ON")
    bpy.ops.object.mode_set(mode="OBJECT")
    assert ATTRIBUTE in obj.data.attributes, "the colours did not survive leaving Edit Mode"
    curvature("OFF")
    bpy.ops.object.mode_set(mode="EDIT")
    assert_same(before, state(obj), "curvature on in Edit Mode, off in Object Mode")

    check_fairing_updates_colors(obj)
    bpy.ops.object.mode_set(mode="OBJECT")
    check_sign_on_a_sphere(addon)
    bpy.context.view_layer.objects.active = obj
    obj = check_save(obj, addon)

    before = state(obj)  # disabling the add-on turns everything off
    zebra("ON")
    curvature("ON")
    disable_addon()
    after = state(obj)
    assert after == before, "disabling the add-on left zebra or curvature behind"
    print("ok: disabling the add-on turned zebra and curvature off")
    print("check_inspect: all checks passed")


main()
