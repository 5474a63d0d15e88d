"""The Geometric Fairing operator: fairs the selected faces of the active mesh in Edit Mode."""

import pathlib
import sys
import time

import bmesh
import bpy
import numpy as np

from . import region
from .properties import FairingProperties


def _import_native():
    """Return ``(geofair, None)`` or ``(None, message)`` when the compiled module cannot be loaded."""
    errors = []
    try:
        from . import geofair  # the built add-on ships the module next to this file

        return geofair, None
    except ImportError as error:
        errors.append(f"in the add-on: {error}")
    try:
        import geofair  # development: PYTHONPATH=build/python

        return geofair, None
    except ImportError as error:
        errors.append(f"on sys.path: {error}")
    found = ", ".join(sorted(p.name for p in pathlib.Path(__file__).parent.glob("geofair*"))) or "none"
    return None, (
        "The compiled module 'geofair' is missing or was built for another Python version "
        f"(this Blender runs Python {sys.version.split()[0]}; module files in the add-on: {found}). "
        + "; ".join(errors)
    )


geofair, NATIVE_IMPORT_ERROR = _import_native()


def read_edit_mesh(obj):
    """Read the edit mesh of ``obj`` for fairing.

    Returns ``(bm, vertices, triangles, selected)``: the edit BMesh, ``(n, 3)``
    float64 positions, ``(T, 3)`` int32 triangles from Blender's own
    tessellation (``loop_triangles``, correct for concave n-gons) and ``(T,)``
    bool, whether the face of each triangle is selected.
    """
    obj.update_from_editmode()  # topology and selection of the edit mesh into obj.data
    mesh = obj.data
    mesh.calc_loop_triangles()
    triangles = np.empty(3 * len(mesh.loop_triangles), dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", triangles)
    triangle_face = np.empty(len(mesh.loop_triangles), dtype=np.int32)
    mesh.loop_triangles.foreach_get("polygon_index", triangle_face)
    face_selected = np.empty(len(mesh.polygons), dtype=bool)
    mesh.polygons.foreach_get("select", face_selected)

    # Positions from the BMesh itself, the data that is written back (and that
    # holds the active shape key's positions in Edit Mode).
    bm = bmesh.from_edit_mesh(mesh)
    bm.verts.ensure_lookup_table()
    vertices = np.array([v.co[:] for v in bm.verts], dtype=np.float64).reshape(-1, 3)
    return bm, vertices, triangles.reshape(-1, 3), face_selected[triangle_face]


def write_positions(obj, bm, positions, indices):
    """Move the BMesh vertices ``indices`` to ``positions[indices]`` and update the edit mesh."""
    verts = bm.verts
    for i, co in zip(indices.tolist(), positions[indices].tolist(), strict=True):
        verts[i].co = co
    bm.normal_update()
    bmesh.update_edit_mesh(obj.data, loop_triangles=True, destructive=False)


class MESH_OT_geometric_fairing(FairingProperties, bpy.types.Operator):
    """Fair the selected faces: smooth surface with G1 continuity to the unselected faces"""

    bl_idname = "mesh.geometric_fairing"
    bl_label = "Geometric Fairing"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        if obj is not None and obj.type == "MESH" and obj.mode == "EDIT":
            return True
        cls.poll_message_set("Needs a mesh object in Edit Mode")
        return False

    def execute(self, context):
        if geofair is None:
            self.report({"ERROR"}, NATIVE_IMPORT_ERROR)
            return {"CANCELLED"}
        obj = context.active_object
        bm, vertices, triangles, selected = read_edit_mesh(obj)
        try:
            fairing_region = region.find_region(vertices, triangles, selected)
            start = time.perf_counter()
            result = geofair.fair(
                vertices,
                triangles,
                fairing_region.free,
                boundary_normals=fairing_region.boundary_normals,
                inner_fairness=self.inner_fairness.lower(),
                outer_fairness=self.outer_fairness.lower(),
                tolerance=self.tolerance,
                max_iterations=self.max_iterations,
            )
            seconds = time.perf_counter() - start
        except (ValueError, RuntimeError) as error:  # RegionError is a ValueError
            self.report({"ERROR"}, f"Geometric Fairing: {error}")
            return {"CANCELLED"}

        positions = np.asarray(result.vertices, dtype=np.float64)
        free = np.flatnonzero(fairing_region.free)
        if positions.shape != vertices.shape or not np.isfinite(positions[free]).all():
            self.report({"ERROR"}, "Geometric Fairing: the solver returned invalid positions; mesh unchanged")
            return {"CANCELLED"}
        write_positions(obj, bm, positions, free)

        summary = (
            f"Geometric Fairing: {len(free)} vertices, {result.iterations} iterations, "
            f"residual {result.residual:.3g}, {seconds:.2f} s"
        )
        border = int(np.count_nonzero(fairing_region.border_fixed))
        if border:
            summary += f"; {border} vertices on the open mesh border kept fixed"
        if result.converged:
            self.report({"INFO"}, summary + ", converged")
        else:
            self.report({"WARNING"}, summary + f", NOT converged (tolerance {self.tolerance:g})")
        return {"FINISHED"}
