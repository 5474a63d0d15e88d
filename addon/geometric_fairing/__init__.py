"""Geometric Fairing: intrinsic mesh fairing (Schneider & Kobbelt 2001) of selected faces.

A legacy add-on (``bl_info``, Blender 3.4 to 4.1) and an extension
(``blender_manifest.toml``, Blender 4.2+) from the same folder: only relative
imports, and the compiled module ``geofair`` is found inside the package (legacy zip)
or installed from the extension's wheel (see ``native.py``).

For scripts: :func:`fair_object` (see ``examples/fair_object.py``) and :func:`fill_holes`.
"""

bl_info = {
    "name": "Geometric Fairing",
    "author": "geofair",
    "version": (0, 0, 0),  # the build writes pyproject.toml's version here (cmake/stamp_version.cmake)
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Fairing (Edit Mode); Edit Mode > Mesh > Geometric Fairing",
    "description": "Fair the selected faces: intrinsic fairing Δ_B H = 0 with a G1 (or G0) boundary",
    "category": "Mesh",
}

import bpy  # noqa: E402

from . import operators, overlays, properties, ui  # noqa: E402
from .fairing import FairingOptions, FairingReport, NotConvergedError, fair_object  # noqa: E402
from .holes import fill_holes  # noqa: E402

__all__ = [
    "FairingOptions",
    "FairingReport",
    "NotConvergedError",
    "fair_object",
    "fill_holes",
    "register",
    "unregister",
]


def register():
    """Register properties, operators, panels, the menu entry and the file handlers."""
    properties.register()
    for cls in operators.CLASSES:
        bpy.utils.register_class(cls)
    ui.register()
    overlays.register()


def unregister():
    """Turn zebra and curvature off everywhere and unregister everything."""
    overlays.unregister()
    ui.unregister()
    for cls in reversed(operators.CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
