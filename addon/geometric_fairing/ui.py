"""The Fairing tab of the 3D View sidebar (Edit Mode) and the Mesh menu entry."""

import bpy

from . import native, overlays, properties
from .operators import (
    MESH_OT_geometric_fairing,
    MESH_OT_geometric_fairing_curvature,
    MESH_OT_geometric_fairing_fill_holes,
    MESH_OT_geometric_fairing_live,
    VIEW3D_OT_geometric_fairing_zebra,
)


def draw_menu_entry(self, context):
    """Append the operators to a menu: Fair, Live Fair Drag and Fill Holes next to it."""
    self.layout.separator()
    self.layout.operator(MESH_OT_geometric_fairing.bl_idname)
    self.layout.operator(MESH_OT_geometric_fairing_live.bl_idname)
    self.layout.operator(MESH_OT_geometric_fairing_fill_holes.bl_idname)


class FairingPanel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Fairing"
    bl_context = "mesh_edit"


class VIEW3D_PT_geometric_fairing(FairingPanel, bpy.types.Panel):
    """Options and the Fair button"""

    bl_label = "Geometric Fairing"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.geometric_fairing
        obj = context.active_object

        column = layout.column()
        column.prop(settings, "inner_fairness", text="Inner")
        column.prop(settings, "outer_fairness", text="Outer")
        column.prop(settings, "boundary")
        column.prop(settings, "remesh")
        column = layout.column()
        column.prop_search(settings, "region_group", obj, "vertex_groups", text="Region", icon="GROUP_VERTEX")
        if not settings.region_group:
            column.label(text="Region: the selected faces", icon="INFO")
        column.prop_search(settings, "pin_group", obj, "vertex_groups", text="Pin", icon="PINNED")
        column.prop(settings, "use_hidden")

        if native.geofair is None:
            box = layout.box()
            box.alert = True
            box.label(text="The compiled module cannot be loaded", icon="ERROR")
            for line in _wrap(native.IMPORT_ERROR, 48):
                box.label(text=line)
        row = layout.row()
        row.scale_y = 1.4
        row.operator(MESH_OT_geometric_fairing.bl_idname, text="Fair", icon="MOD_SMOOTH")
        column = layout.column(align=True)
        row = column.row(align=True)
        row.operator(MESH_OT_geometric_fairing_live.bl_idname, text="Live Fair Drag", icon="VIEW_PAN")
        row.prop(settings, "live_details", text="", icon="MOD_DISPLACE")
        column.prop(settings, "live_radius")
        column.label(text=_handle_text(settings), icon="PINNED")
        row = layout.row()
        row.operator(MESH_OT_geometric_fairing_fill_holes.bl_idname, text="Fill Holes", icon="MOD_TRIANGULATE")
        layout.label(text="Esc cancels: mesh unchanged")


class VIEW3D_PT_geometric_fairing_advanced(FairingPanel, bpy.types.Panel):
    """The solver's stopping rules and method (properties.ADVANCED_OPTION_NAMES), closed by default"""

    bl_label = "Advanced"
    bl_parent_id = "VIEW3D_PT_geometric_fairing"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        properties.draw_advanced_options(layout.column(), context.scene.geometric_fairing)


class VIEW3D_PT_geometric_fairing_last_run(FairingPanel, bpy.types.Panel):
    """Figures of the last run"""

    bl_label = "Last Run"
    bl_parent_id = "VIEW3D_PT_geometric_fairing"

    def draw(self, context):
        layout = self.layout
        last = context.window_manager.geometric_fairing.last_run
        if last.status == "NONE":
            layout.label(text="No run yet")
            return
        icon = {"CONVERGED": "CHECKMARK", "NOT_CONVERGED": "ERROR", "CANCELLED": "CANCEL", "ERROR": "ERROR"}
        status = layout.row()
        status.alert = last.status in ("ERROR", "NOT_CONVERGED")
        status.label(text=f"{last.object_name}: {_status_text(last)}", icon=icon[last.status])
        if last.status in ("ERROR", "NOT_CONVERGED"):  # not converged: whether the result was kept, and why not
            for line in _wrap(last.message, 48):
                layout.label(text=line)
            if last.status == "ERROR":
                return
        if last.not_faired:
            box = layout.box()
            box.alert = True
            for line in _wrap(f"Not faired: {last.not_faired}", 48):
                box.label(text=line)
        figures = [
            (figure.label, figure.text(getattr(last, figure.name)))
            for figure in properties.RUN_FIGURES
            if figure.shown(getattr(last, figure.name))
        ]
        figures += [
            ("Tolerance", f"{last.tolerance:.2g}"),
            ("Inner", _item_name(properties.INNER_FAIRNESS_ITEMS, last.inner_fairness)),
            ("Outer", _item_name(properties.OUTER_FAIRNESS_ITEMS, last.outer_fairness)),
            ("Boundary", _item_name(properties.BOUNDARY_ITEMS, last.boundary)),
        ]
        if last.has_uv:
            after = "unchanged" if last.status == "CANCELLED" else f"{last.uv_after_mean:.3f} / {last.uv_after_max:.2f}"
            figures += [
                ("UV σ1/σ2 before", f"{last.uv_before_mean:.3f} / {last.uv_before_max:.2f}"),
                ("UV σ1/σ2 after", after),
            ]
        column = layout.column(align=True)
        for name, value in figures:
            row = column.split(factor=0.55, align=True)
            row.label(text=name)
            row.label(text=value)
        if last.has_uv:
            layout.label(text=f"UV: mean / max, {last.uv_triangles} triangles")


class VIEW3D_PT_geometric_fairing_inspect(FairingPanel, bpy.types.Panel):
    """Zebra stripes and mean-curvature colours"""

    bl_label = "Inspect"
    bl_parent_id = "VIEW3D_PT_geometric_fairing"

    def draw(self, context):
        layout = self.layout
        space = context.space_data
        obj = context.active_object
        column = layout.column(align=True)
        zebra = overlays.zebra_enabled(space)
        column.operator(
            VIEW3D_OT_geometric_fairing_zebra.bl_idname,
            text="Zebra Stripes",
            icon="HIDE_OFF" if zebra else "HIDE_ON",
            depress=zebra,
        )
        curvature = obj is not None and overlays.curvature_enabled(obj.data)
        column.operator(
            MESH_OT_geometric_fairing_curvature.bl_idname,
            text="Mean Curvature",
            icon="HIDE_OFF" if curvature else "HIDE_ON",
            depress=curvature,
        )
        if curvature:
            limit = context.window_manager.geometric_fairing.curvature_limit
            layout.label(text=f"Blue −{limit:.3g}  White 0  Red +{limit:.3g} (1/length)")


def _handle_text(settings):
    """Which vertices Live Fair Drag moves, in the panel's words."""
    if settings.live_radius > 0.0:
        return "Handle: the selection, region within Radius"
    if settings.region_group:
        return "Handle: Pin group and selection in Region"
    if settings.pin_group:
        return "Handle: Pin group inside the selection"
    return "Handle: set a Pin group (no handle yet)"


def _status_text(last):
    return {
        "CONVERGED": "converged",
        "NOT_CONVERGED": "NOT converged",
        "CANCELLED": "cancelled, mesh unchanged",
        "ERROR": "failed, mesh unchanged",
    }[last.status]


def _item_name(items, identifier):
    """The name an enum's ``items`` give ``identifier`` (the library's value), or the value itself."""
    return next((name for key, name, _ in items if key == identifier), identifier)


def _wrap(text, width):
    """Split ``text`` into lines of at most about ``width`` characters, for labels."""
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    return [*lines, line] if line else lines


CLASSES = (
    VIEW3D_PT_geometric_fairing,
    VIEW3D_PT_geometric_fairing_advanced,
    VIEW3D_PT_geometric_fairing_last_run,
    VIEW3D_PT_geometric_fairing_inspect,
)


def register():
    """Register the panels and add the menu entry."""
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_edit_mesh.append(draw_menu_entry)


def unregister():
    """Remove the menu entry and unregister the panels."""
    bpy.types.VIEW3D_MT_edit_mesh.remove(draw_menu_entry)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
