"""Menu entry of Geometric Fairing in the Edit Mode Mesh menu."""

import bpy

from .operators import MESH_OT_geometric_fairing


def draw_menu_entry(self, context):
    """Append the operator to a menu."""
    self.layout.separator()
    self.layout.operator(MESH_OT_geometric_fairing.bl_idname)


def register():
    """Add the menu entry."""
    bpy.types.VIEW3D_MT_edit_mesh.append(draw_menu_entry)


def unregister():
    """Remove the menu entry."""
    bpy.types.VIEW3D_MT_edit_mesh.remove(draw_menu_entry)
