"""Geometric Fairing: intrinsic mesh fairing (Schneider & Kobbelt 2001) of selected faces."""

bl_info = {
    "name": "Geometric Fairing",
    "author": "geofair",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Edit Mode > Mesh > Geometric Fairing",
    "description": "Fair the selected faces: intrinsic fairing Δ_B H = 0 with a G1 boundary",
    "category": "Mesh",
}

import bpy  # noqa: E402

from . import operators, ui  # noqa: E402


def register():
    """Register the operator and its menu entry."""
    bpy.utils.register_class(operators.MESH_OT_geometric_fairing)
    ui.register()


def unregister():
    """Unregister the menu entry and the operator."""
    ui.unregister()
    bpy.utils.unregister_class(operators.MESH_OT_geometric_fairing)
