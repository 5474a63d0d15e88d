"""Operators: Geometric Fairing (modal with progress and Esc, or blocking), zebra and curvature toggles.

The fairing operator is thin: :class:`fairing.FairingRun` reads the mesh,
solves and writes; here options are resolved, the run is driven and errors
become reports. Invoked from the UI it solves in a worker thread (the solver
releases the GIL) while a timer shows progress; Esc cancels and the mesh stays
as it was, since a run writes nothing before it finishes. Run from a script,
the redo panel or in background mode it solves in place.
"""

import math

import bpy
from bpy.props import EnumProperty

from . import fairing, overlays
from .properties import OPTION_NAMES, FairingProperties

PROGRESS_STEPS = 1000
# Events a running fairing lets through: looking around changes nothing.
NAVIGATION_EVENTS = {
    "MIDDLEMOUSE",
    "WHEELUPMOUSE",
    "WHEELDOWNMOUSE",
    "TRACKPADPAN",
    "TRACKPADZOOM",
    "MOUSEROTATE",
    "MOUSEMOVE",
    "INBETWEEN_MOUSEMOVE",
}
TOGGLE_ITEMS = (
    ("TOGGLE", "Toggle", "Turn on if off, off if on"),
    ("ON", "On", "Turn on"),
    ("OFF", "Off", "Turn off"),
)


_running = None  # the FairingRun of the modal operator while it solves


def running():
    """The run the modal operator is solving, or None (for scripts and tests driving the UI)."""
    return _running


def cancel_running():
    """Cancel the modal operator's run as Esc does; return whether one was running.

    The operator notices at its next timer event and ends with the mesh as it was.
    """
    if _running is None:
        return False
    _running.request_cancel()
    return True


def progress_fraction(first_residual, residual, tolerance):
    """Progress in [0, 1] of a run from its first residual towards the tolerance, on a log scale."""
    if not (first_residual > tolerance > 0.0 and residual > 0.0) or math.isnan(residual):
        return 0.0
    fraction = math.log(first_residual / residual) / math.log(first_residual / tolerance)
    return min(max(fraction, 0.0), 1.0)


class MESH_OT_geometric_fairing(FairingProperties, bpy.types.Operator):
    """Fair the selected faces: smooth surface with G1 continuity to the unselected faces"""

    bl_idname = "mesh.geometric_fairing"
    bl_label = "Geometric Fairing"
    bl_options = {"REGISTER", "UNDO"}

    _run = None
    _timer = None
    _first_residual = None

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        if obj is not None and obj.type == "MESH" and obj.mode == "EDIT":
            return True
        cls.poll_message_set("Needs a mesh object in Edit Mode")
        return False

    def resolve_options(self, context):
        """Options given to the operator; the others from the panel (which follows the preferences)."""
        settings = context.scene.geometric_fairing
        for name in OPTION_NAMES:
            if not self.properties.is_property_set(name):
                setattr(self, name, getattr(settings, name))
        return fairing.FairingOptions(**{name: getattr(self, name) for name in OPTION_NAMES})

    def prepare(self, context):
        """Read the mesh and find the region; None (after a report) if that fails."""
        options = self.resolve_options(context)
        obj = context.active_object
        try:
            return fairing.FairingRun(obj, options)  # RuntimeError without the compiled module
        except (ValueError, RuntimeError) as error:  # RegionError is a ValueError
            fairing.store_last_run(context.window_manager, options, error=error, object_name=obj.name)
            self.report({"ERROR"}, f"Geometric Fairing: {error}")
            return None

    def execute(self, context):
        run = self.prepare(context)
        if run is None:
            return {"CANCELLED"}
        wm = context.window_manager
        wm.progress_begin(0, PROGRESS_STEPS)
        run.user_progress = lambda iteration, residual: wm.progress_update(self.progress_value(residual))
        try:
            run.solve()
        finally:
            wm.progress_end()
        return self.finish(context, run)

    def invoke(self, context, event):
        if bpy.app.background or context.window is None:
            return self.execute(context)
        run = self.prepare(context)
        if run is None:
            return {"CANCELLED"}
        global _running
        self._run = _running = run
        run.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        wm.progress_begin(0, PROGRESS_STEPS)
        self.show_status(context)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        run = self._run
        if event.type == "ESC" and event.value == "PRESS":
            run.request_cancel()
        if run.done:
            self.end_modal(context)
            return self.finish(context, run)
        if event.type == "TIMER":
            context.window_manager.progress_update(self.progress_value(run.residual))
            self.show_status(context)
        if event.type in NAVIGATION_EVENTS:
            return {"PASS_THROUGH"}
        return {"RUNNING_MODAL"}

    def cancel(self, context):
        """Blender ends the modal operator (file loaded, window closed): stop the solve, leave the mesh."""
        if self._run is not None:
            self._run.request_cancel()
            self._run.wait()
        self.end_modal(context)

    def end_modal(self, context):
        global _running
        _running = None
        wm = context.window_manager
        if self._timer is not None:
            wm.event_timer_remove(self._timer)
            self._timer = None
        wm.progress_end()
        context.workspace.status_text_set(None)

    def progress_value(self, residual):
        if self._first_residual is None and residual == residual:  # not NaN
            self._first_residual = residual
        fraction = progress_fraction(self._first_residual or 0.0, residual, self.tolerance)
        return round(fraction * PROGRESS_STEPS)

    def show_status(self, context):
        run = self._run
        if run.cancel_requested:
            text = "Geometric Fairing: cancelling…"
        else:
            text = (
                f"Geometric Fairing: {int(run.region.free.sum())} vertices, iteration {run.iteration}, "
                f"residual {run.residual:.3g} (tolerance {self.tolerance:g}) — Esc to cancel"
            )
        context.workspace.status_text_set(text)

    def finish(self, context, run):
        """Write the result (unless cancelled), keep the figures for the panel, report."""
        obj = run.obj
        try:
            report = run.finish()
        except (ValueError, RuntimeError) as error:
            fairing.store_last_run(context.window_manager, run.options, error=error, object_name=obj.name)
            self.report({"ERROR"}, f"Geometric Fairing: {error}")
            return {"CANCELLED"}
        fairing.store_last_run(context.window_manager, run.options, report)
        if report.cancelled:
            self.report({"INFO"}, f"Geometric Fairing: {report.summary()}")
            return {"CANCELLED"}
        try:
            overlays.refresh_curvature(obj, context)
        except RuntimeError as error:
            self.report({"WARNING"}, f"Geometric Fairing: curvature colours not updated: {error}")
        if report.converged:
            self.report({"INFO"}, f"Geometric Fairing: {report.summary()}")
        else:
            self.report({"WARNING"}, f"Geometric Fairing: {report.summary()} (tolerance {run.options.tolerance:g})")
        return {"FINISHED"}


class VIEW3D_OT_geometric_fairing_zebra(bpy.types.Operator):
    """Reflection lines (zebra stripes) in this 3D View, to judge G1 continuity at the boundary and smoothness"""

    bl_idname = "view3d.geometric_fairing_zebra"
    bl_label = "Zebra Stripes"
    bl_options = {"INTERNAL"}

    action: EnumProperty(name="Action", items=TOGGLE_ITEMS, default="TOGGLE", options={"SKIP_SAVE"})

    @classmethod
    def poll(cls, context):
        if context.space_data is not None and context.space_data.type == "VIEW_3D":
            return True
        cls.poll_message_set("Needs a 3D View")
        return False

    def execute(self, context):
        space = context.space_data
        on = not overlays.zebra_enabled(space) if self.action == "TOGGLE" else self.action == "ON"
        if on:
            overlays.zebra_on(space)
        else:
            overlays.zebra_off(space)
        return {"FINISHED"}


class MESH_OT_geometric_fairing_curvature(bpy.types.Operator):
    """Colour the active mesh by its mean curvature (blue concave, white flat, red convex)"""

    bl_idname = "mesh.geometric_fairing_curvature"
    bl_label = "Mean Curvature"
    bl_options = {"REGISTER", "UNDO", "INTERNAL"}

    action: EnumProperty(name="Action", items=TOGGLE_ITEMS, default="TOGGLE", options={"SKIP_SAVE"})

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        if obj is not None and obj.type == "MESH":
            return True
        cls.poll_message_set("Needs an active mesh object")
        return False

    def execute(self, context):
        obj = context.active_object
        space = context.space_data if context.space_data is not None and context.space_data.type == "VIEW_3D" else None
        enabled = overlays.curvature_enabled(obj.data)
        on = not enabled if self.action == "TOGGLE" else self.action == "ON"
        if not on:
            overlays.curvature_off(obj.data)
            return {"FINISHED"}
        try:
            limit = overlays.curvature_on(obj, space, context)
        except (ValueError, RuntimeError) as error:
            self.report({"ERROR"}, f"Mean curvature: {error}")
            return {"CANCELLED"}
        self.report({"INFO"}, f"Mean curvature: blue −{limit:.3g} … white 0 … red +{limit:.3g} (1/length)")
        return {"FINISHED"}


CLASSES = (MESH_OT_geometric_fairing, VIEW3D_OT_geometric_fairing_zebra, MESH_OT_geometric_fairing_curvature)
