"""Operators: Geometric Fairing (modal with progress and Esc, or blocking), zebra and curvature toggles.

The fairing operator is thin: :class:`fairing.FairingRun` reads a mesh,
solves and writes; here options are resolved, the runs are driven and errors
become reports. Invoked from the UI it solves in a worker thread (the solver
releases the GIL) while a timer shows progress; Esc cancels and the meshes stay
as they were, since a run writes nothing before it finishes. Run from a script,
the redo panel or in background mode it solves in place.

Several objects in Edit Mode (multi-object editing): every one with selected
faces is faired, each on its own, with one undo step for all. An object with
nothing selected is skipped. An object that cannot be faired (its selection
has no boundary, or the solver fails on it) is left as it was while the
others are still faired; the report names it and says why, as a warning.
Only when no object could be faired does the operator cancel with an error.

Errors never leave a half-written mesh: a run writes only after its solve
succeeded, and a cancelled operator adds no undo step, so undo after an error
goes back to the step before it. A solve that stops unconverged counts as an
error (the mesh is left as it was, the report gives the residual and the
tolerance) unless *Keep Unconverged Result* is ticked: then it is written with
a warning.
"""

import time

import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty, IntProperty
from bpy_extras import view3d_utils
from mathutils import Euler, Matrix, Vector

from . import fairing, holes, live, mesh_io, native, overlays, properties
from .properties import OPTION_NAMES, FairingProperties, SolverProperties, option_values
from .region import NothingSelectedError

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


UNCONVERGED_HINT = "Tick 'Keep Unconverged Result' to apply it anyway."


_running = None  # the FairingBatch of the modal operator while it solves


def running():
    """The :class:`fairing.FairingBatch` the modal operator is solving, or None (for scripts and tests driving the UI).

    It has ``iteration``, ``residual`` (of the run being solved), ``done``,
    ``cancel_requested``, ``request_cancel()`` and ``runs``.
    """
    return _running


def cancel_running():
    """Cancel the modal operator's run as Esc does; return whether one was running.

    The operator notices at its next timer event and ends with the mesh as it was.
    """
    if _running is None:
        return False
    _running.request_cancel()
    return True


progress_fraction = fairing.progress_fraction


def edit_mode_meshes(context):
    """The mesh objects in Edit Mode, one per mesh data (multi-object editing), the active one first."""
    active = context.active_object
    objects = [obj for obj in getattr(context, "objects_in_mode_unique_data", None) or [] if obj.type == "MESH"]
    if not objects and active is not None:
        objects = [active]
    objects.sort(key=lambda obj: obj != active)
    return objects


class _SolvingOperator:
    """What the Fair and Fill Holes operators share: runs on the meshes in Edit Mode solved in a worker
    thread with progress (Esc cancels) or in place, then written, reported and kept for the panel.

    A subclass gives ``label`` (the reports' prefix), :meth:`resolve_options`, :meth:`make_run`,
    :meth:`status_text` and :meth:`unconverged_hint`.
    """

    label = "Geometric Fairing"
    _batch = None
    _timer = None
    _failed = ()  # (object name, error) of the objects that could not be prepared
    _several = False  # several objects in Edit Mode: reports name the objects

    def prepare(self, context):
        """Read each mesh in Edit Mode and find its region; the batch, or None (after a report) if none can run."""
        options = self.resolve_options(context)
        objects = edit_mode_meshes(context)
        self._several = len(objects) > 1
        runs, failed = [], []
        for obj in objects:
            try:
                runs.append(self.make_run(obj, options))  # RuntimeError without the compiled module
            except Exception as error:  # noqa: BLE001 (reported by object name; the mesh was not touched)
                failed.append((obj.name, error))
        if not runs:
            message = self.failure_text(failed)
            fairing.store_last_runs(context.window_manager, options, [], failed, message)
            self.report({"ERROR"}, f"{self.label}: {message}")
            return None
        # Beside an object that has something to fair, one with nothing selected is simply skipped.
        self._failed = [(name, error) for name, error in failed if not isinstance(error, NothingSelectedError)]
        return fairing.FairingBatch(runs)

    def failure_text(self, failed):
        if not self._several:
            return fairing.error_text(failed[0][1])
        return "; ".join(f"{name}: {fairing.error_text(error)}" for name, error in failed)

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        if obj is not None and obj.type == "MESH" and obj.mode == "EDIT":
            return True
        cls.poll_message_set("Needs a mesh object in Edit Mode")
        return False

    def execute(self, context):
        batch = self._batch = self.prepare(context)
        if batch is None:
            return {"CANCELLED"}
        wm = context.window_manager
        wm.progress_begin(0, PROGRESS_STEPS)
        for run in batch.runs:
            run.user_progress = lambda iteration, residual: wm.progress_update(self.progress_value())
        try:
            batch.solve()
        finally:
            wm.progress_end()
        return self.finish(context, batch)

    def invoke(self, context, event):
        if bpy.app.background or context.window is None:
            return self.execute(context)
        batch = self.prepare(context)
        if batch is None:
            return {"CANCELLED"}
        global _running
        self._batch = _running = batch
        batch.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        wm.progress_begin(0, PROGRESS_STEPS)
        self.show_status(context)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        batch = self._batch
        if event.type == "ESC" and event.value == "PRESS":
            batch.request_cancel()
        if batch.done:
            self.end_modal(context)
            return self.finish(context, batch)
        if event.type == "TIMER":
            context.window_manager.progress_update(self.progress_value())
            self.show_status(context)
        if event.type in NAVIGATION_EVENTS:
            return {"PASS_THROUGH"}
        return {"RUNNING_MODAL"}

    def cancel(self, context):
        """Blender ends the modal operator (file loaded, window closed): stop the solve, leave the meshes."""
        if self._batch is not None:
            self._batch.request_cancel()
            self._batch.wait()
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

    def progress_value(self):
        return round(self._batch.progress(self.tolerance) * PROGRESS_STEPS)

    def show_status(self, context):
        batch = self._batch
        if batch.cancel_requested:
            text = f"{self.label}: cancelling…"
        else:
            run = batch.current
            which = f"{run.object_name} ({batch.index + 1}/{len(batch.runs)}): " if len(batch.runs) > 1 else ""
            text = (
                f"{self.label}: {which}{self.status_text(run)}, iteration {run.iteration}, "
                f"residual {run.residual:.3g} (tolerance {self.tolerance:g}) — Esc to cancel"
            )
        context.workspace.status_text_set(text)

    def finish(self, context, batch):
        """Write the results (unless cancelled), keep the figures for the panel, report."""
        reports, errors = batch.finish()
        options = batch.runs[0].options
        # An unconverged result that was not kept: that object is not faired, like one that failed.
        not_kept = [
            (report.object_name, fairing.NotConvergedError(report, self.unconverged_hint(options, report)))
            for report in reports
            if report.discarded
        ]
        reports = [report for report in reports if not report.discarded]
        errors = [*self._failed, *errors, *not_kept]
        wm = context.window_manager
        if not reports:
            message = self.failure_text(errors)
            fairing.store_last_runs(wm, options, [], errors, message)
            self.report({"ERROR"}, f"{self.label}: {message}")
            return {"CANCELLED"}
        if self._several:
            parts = [f"{report.object_name}: {report.summary()}" for report in reports]
            parts += [f"{name} {self.not_done}: {fairing.error_text(error)}" for name, error in errors]
            message = "; ".join(parts)
        else:
            message = reports[0].summary()
        fairing.store_last_runs(wm, options, reports, errors, message)
        if any(report.cancelled for report in reports):
            self.report({"INFO"}, f"{self.label}: {message}")
            return {"CANCELLED"}
        for run in batch.written:
            try:
                overlays.refresh_curvature(run.obj, context)
            except RuntimeError as error:
                self.report({"WARNING"}, f"{self.label}: curvature of {run.object_name} not updated: {error}")
        if errors:
            self.report({"WARNING"}, f"{self.label}: {message}")
        elif all(report.converged for report in reports):
            # A converged result that flips triangles over is written, with a warning (Ctrl+Z undoes it);
            # so is one with notes on what could not be carried over to new faces.
            warn = any(report.folds or report.notes for report in reports)
            self.report({"WARNING" if warn else "INFO"}, f"{self.label}: {message}")
        else:
            residual = max(report.residual for report in reports if not report.converged)
            self.report(
                {"WARNING"},
                f"{self.label}: did not converge (residual {fairing.short_number(residual)}, tolerance "
                f"{fairing.short_number(options.tolerance)}), unconverged result kept: {message}",
            )
        return {"FINISHED"}


class MESH_OT_geometric_fairing(FairingProperties, _SolvingOperator, bpy.types.Operator):
    """Fair the selected faces: a smooth surface meeting the unselected faces with G1 continuity, or G0 (Boundary)"""

    bl_idname = "mesh.geometric_fairing"
    bl_label = "Geometric Fairing"
    bl_options = {"REGISTER", "UNDO"}

    label = "Geometric Fairing"
    not_done = "not faired"

    def resolve_options(self, context):
        """Options given to the operator; the others from the panel (which follows the preferences)."""
        self.inherit_panel(context.scene.geometric_fairing, OPTION_NAMES)
        return fairing.FairingOptions(**option_values(self), keep_unconverged=self.keep_unconverged)

    def make_run(self, obj, options):
        run = fairing.FairingRun(obj, options)
        run.remesh_hint = fairing.REMESH_HINT
        return run

    def status_text(self, run):
        return f"{int(run.region.free.sum())} vertices"

    def unconverged_hint(self, options, report):
        return fairing.unconverged_hint(
            options, report, UNCONVERGED_HINT, remesh_hint=fairing.REMESH_HINT, time_limit_hint=fairing.TIME_LIMIT_HINT
        )


class MESH_OT_geometric_fairing_fill_holes(SolverProperties, _SolvingOperator, bpy.types.Operator):
    """Fill the holes whose whole boundary loop is selected (nothing selected: every hole, not an open mesh's outer
    border) with a faired surface meeting the faces around with G1 continuity, or G0 (Boundary); every hole gets its
    best fill (Clean Rim: where a fill folds or does not converge, a ragged rim's faces may be removed and the hole
    filled again); UVs interpolated from around each hole"""

    bl_idname = "mesh.geometric_fairing_fill_holes"
    bl_label = "Fill Holes (Geometric Fairing)"
    bl_options = {"REGISTER", "UNDO"}

    label = "Fill Holes"
    not_done = "not filled"

    all_holes: BoolProperty(
        name="All Holes",
        description=(
            "Fill every hole of the mesh, whatever is selected (with nothing selected: every hole too); "
            "the outer border of an open mesh stays open (to fill it, turn this off and select the border)"
        ),
        default=False,
        options={"SKIP_SAVE"},
    )
    edge_length: FloatProperty(
        name="Edge Length",
        description="Edge length of the fill's triangles, in the object's own units (before its scale); 0: the mean "
        "length of each hole's boundary edges",
        default=0.0,
        min=0.0,
        subtype="DISTANCE",
        options={"SKIP_SAVE"},
    )
    clean_rim: BoolProperty(
        name="Clean Rim",
        description=(
            "Where a hole's fill folds or does not converge, remove the ragged faces of its rim first (teeth with "
            "two boundary edges, spikes narrower than 90°, faces that fold against the fill) and fill the larger "
            "hole; the report names the faces removed. Off by default: it deletes faces of yours"
        ),
        default=False,
        options={"SKIP_SAVE"},
    )
    # Not in the redo panel: every hole's best fill is written, converged or not (read only
    # with a compiled module older than fill_holes' per-hole records).
    keep_unconverged: properties._keep_unconverged(options={"SKIP_SAVE", "HIDDEN"})

    def resolve_options(self, context):
        """Options given to the operator; the others from the panel (which follows the preferences)."""
        self.inherit_panel(context.scene.geometric_fairing, properties.LIBRARY_OPTION_NAMES)
        values = option_values(self, properties.LIBRARY_OPTION_NAMES)
        return fairing.FairingOptions(**values, keep_unconverged=self.keep_unconverged)

    def make_run(self, obj, options):
        return holes.FillRun(
            obj, options, all_holes=self.all_holes, target_edge_length=self.edge_length, clean_rim=self.clean_rim
        )

    def status_text(self, run):
        return f"{run.holes} hole{'s' if run.holes > 1 else ''}"

    def unconverged_hint(self, options, report):
        return fairing.unconverged_hint(
            options, report, UNCONVERGED_HINT, remesh="always", time_limit_hint=fairing.TIME_LIMIT_HINT
        )


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


# Keys of the live drag: confirm, cancel (as G's).
CONFIRM_EVENTS = {"LEFTMOUSE", "RET", "NUMPAD_ENTER", "SPACE"}
CANCEL_EVENTS = {"RIGHTMOUSE", "ESC"}
LIVE_HINT = (
    "G/R/S move, rotate, scale; X/Y/Z global axis; type a value; wheel: radius; LMB/Enter confirm, RMB/Esc cancel"
)
AXIS_EVENTS = {"X": 0, "Y": 1, "Z": 2}
MODE_EVENTS = {"G": "TRANSLATE", "R": "ROTATE", "S": "SCALE"}
# The radius's factor per wheel step or key, as Proportional Editing's size.
MAX_SUBSTEPS = 12  # updates a frame makes before it yields to the next event
RESIZE_DELAY = 0.15  # seconds the radius's wheel steps gather before the new region is prepared
RADIUS_EVENTS = {"WHEELUPMOUSE": 1 / 1.1, "PAGE_UP": 1.1, "WHEELDOWNMOUSE": 1.1, "PAGE_DOWN": 1 / 1.1}

_last_drag = None  # the live.LiveDrag of the last Live Fair Drag


def last_drag():
    """The :class:`live.LiveDrag` of the last Live Fair Drag (its ``frames``, ``prepare_seconds``), or None."""
    return _last_drag


def view_region(context):
    """The main region of the 3D View the operator runs in (the sidebar's button: its area's), or None."""
    area = context.area
    if area is None or area.type != "VIEW_3D":
        return None
    if context.region is not None and context.region.type == "WINDOW":
        return context.region
    return next((region for region in area.regions if region.type == "WINDOW"), None)


class MESH_OT_geometric_fairing_live(SolverProperties, bpy.types.Operator):
    """Move, rotate or scale a handle (G, R, S), the region refaired as the mouse moves (Schneider & Kobbelt 2001,
    section 8). The region is Fair's (the selected faces, or the Region vertex group); the handle is the Pin vertex
    group's vertices inside it (with a Region vertex group, the selected vertices inside it too)"""

    bl_idname = "mesh.geometric_fairing_live"
    bl_label = "Live Fair Drag"
    bl_options = {"REGISTER", "UNDO", "BLOCKING"}

    label = "Live Fair Drag"

    region_group: properties._region_group(options={"SKIP_SAVE"})
    pin_group: properties._pin_group(options={"SKIP_SAVE"})
    use_hidden: properties._use_hidden(options={"SKIP_SAVE"})
    details: properties._live_details(options={"SKIP_SAVE"})
    radius: properties._live_radius(options={"SKIP_SAVE"})
    offset: FloatVectorProperty(
        name="Offset",
        description="Translation of the handle, object space",
        subtype="TRANSLATION",
        size=3,
        options={"SKIP_SAVE"},
    )
    rotation: FloatVectorProperty(
        name="Rotation",
        description="Rotation of the handle about its centre, object space; its tangent planes turn with it",
        subtype="EULER",
        size=3,
        options={"SKIP_SAVE"},
    )
    scale: FloatProperty(
        name="Scale",
        description="Uniform scale of the handle about its centre",
        default=1.0,
        min=1e-3,
        soft_max=10.0,
        options={"SKIP_SAVE"},
    )
    frames: IntProperty(
        name="Frames",
        description="Frames in which the move is reached without the mouse (scripts, redo): each refairs from the last",
        default=4,
        min=1,
        soft_max=50,
        options={"SKIP_SAVE"},
    )

    _drag = None  # live.LiveDrag while the mouse drags
    _obj = None
    _region = None  # the 3D View's main region: the mouse moves in its view
    _mode = "TRANSLATE"  # live.MODES: G, R or S
    _committed = None  # live.HandleMove of the modes before this one
    _centre = None  # the handle's centre (world) as the mode started: the view plane of G goes through it
    _start = None  # the mouse's point in that plane as the mode started (world)
    _start_2d = None  # the mouse on screen as the mode started, relative to the centre (pixels)
    _last_2d = None  # the last mouse move on screen, relative to the centre, and the turn so far (R)
    _angle = 0.0
    _to_object = None  # world to object space, for the moves
    _axis = None  # X/Y/Z: along or about that global axis (0, 1, 2), or None
    _typed = ""  # a value typed during the mode
    _mouse = None  # the last mouse move's world point
    _circle = None  # the draw handler of the radius's circle
    _timer = None  # while a frame cut short at MAX_SUBSTEPS goes on or wheel steps gather
    _continuing = False  # the last frame was cut short
    _resize_factor = 1.0  # the radius's factor of the wheel steps gathered
    _resize_at = 0.0  # the last wheel step's time (time.perf_counter)
    _view_axis = None  # towards the viewer as the mode started (world)

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        if obj is not None and obj.type == "MESH" and obj.mode == "EDIT":
            return True
        cls.poll_message_set("Needs a mesh object in Edit Mode")
        return False

    def resolve_options(self, context):
        """Options given to the operator; the others from the panel, as Fair's (Remesh stays off)."""
        settings = context.scene.geometric_fairing
        self.inherit_panel(settings, properties.LIVE_OPTION_NAMES)
        if not self.properties.is_property_set("details"):
            self.details = settings.live_details
        if not self.properties.is_property_set("radius"):
            self.radius = settings.live_radius
        return fairing.FairingOptions(**option_values(self, properties.LIVE_OPTION_NAMES))

    def prepare(self, context):
        """Read the active mesh, its region and handle, and prepare LiveFairing; the
        :class:`live.LiveDrag` (its ``base`` the positions as read), or None after a report."""
        options = self.resolve_options(context)
        obj = context.active_object
        try:
            run = fairing.FairingRun(
                obj, options, pin_selected=bool(options.region_group), handle_radius=self.radius or None
            )
            drag = live.LiveDrag(
                native.geofair,
                run.mesh.vertices,
                run.mesh.triangles[run.present_triangles],
                run.region.free,
                run.region.pinned,
                run.boundary_normals,
                run.polygon_ids,
                options.library_options(),
                self.details,
            )
        except Exception as error:  # noqa: BLE001 (reported; the mesh was not touched)
            self.report({"ERROR"}, f"{self.label}: {fairing.error_text(error)}")
            return None
        global _last_drag
        self._obj, _last_drag = obj, drag
        return drag

    def execute(self, context):
        drag = self.prepare(context)
        if drag is None:
            return {"CANCELLED"}
        rotation = np.array(Euler(self.rotation).to_matrix(), dtype=np.float64)
        frame = drag.drag(live.HandleMove(np.array(self.offset, dtype=np.float64), rotation, self.scale), self.frames)
        if not frame.converged:
            self.report({"ERROR"}, f"{self.label}: did not converge at the offset ({frame.message}); mesh unchanged")
            return {"CANCELLED"}
        mesh_io.write_positions(self._obj, drag.positions, drag.moving)
        self.report({"INFO"}, f"{self.label}: {drag.summary()}")
        return {"FINISHED"}

    def invoke(self, context, event):
        self._region = view_region(context)
        if bpy.app.background or context.window is None or self._region is None:
            return self.execute(context)
        drag = self._drag = self.prepare(context)
        if drag is None:
            return {"CANCELLED"}
        obj = self._obj
        mesh_io.write_positions(obj, drag.positions, drag.moving)  # the region faired at rest
        self._to_object = obj.matrix_world.inverted().to_3x3()
        self.start_mode("TRANSLATE", live.HandleMove(), event)
        rule = live.RADIUS_RULE if self.radius > 0.0 else live.HANDLE_RULE
        self.report({"INFO"}, f"{self.label}: prepared in {drag.prepare_seconds:.2f} s; {rule}")
        self.show(context, f"prepared in {drag.prepare_seconds * 1e3:.0f} ms")
        if self.radius > 0.0:
            self._circle = bpy.types.SpaceView3D.draw_handler_add(self.draw_circle, (), "WINDOW", "POST_PIXEL")
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def resize(self, context, factor):
        """The radius times ``factor``: the region prepared anew around the handle, the move so far applied
        to it; where the new region cannot be prepared the old one stays."""
        old, radius = self._drag, self.radius
        mesh_io.write_positions(self._obj, old.base, old.moving)  # the mesh as read, for the new region
        self.radius = radius * factor
        drag = self.prepare(context)
        if drag is None:
            global _last_drag
            self._drag, _last_drag, self.radius = old, old, radius
            mesh_io.write_positions(self._obj, old.positions, old.moving)
            self.show(context, f"radius {radius * factor:.4g} cannot be prepared, kept {radius:.4g}")
            return
        self._drag = drag
        frame = drag.frame(old.move, max_substeps=MAX_SUBSTEPS)  # a long move goes on from the timer
        self._continuing = frame.converged and not frame.reached
        self.sync_timer(context)
        mesh_io.write_positions(self._obj, drag.positions, drag.moving)
        self.show(
            context, f"radius {self.radius:.4g}: prepared in {drag.prepare_seconds * 1e3:.0f} ms, {frame.status()}"
        )

    def draw_circle(self):
        """The radius as a circle around the handle's centre in the view (POST_PIXEL), as Proportional Editing's."""
        try:
            region, drag = self._region, self._drag
            if drag is None or bpy.context.region != region:
                return
        except ReferenceError:  # the operator ended without end(): nothing to draw
            return
        world = self._obj.matrix_world
        centre = world @ Vector((drag.centre + drag.move.offset).tolist())
        right = region.data.view_rotation @ Vector((1.0, 0.0, 0.0))
        extent = (world.to_3x3() @ Vector((self.radius, 0.0, 0.0))).length
        middle = view3d_utils.location_3d_to_region_2d(region, region.data, centre)
        edge = view3d_utils.location_3d_to_region_2d(region, region.data, centre + extent * right)
        if middle is None or edge is None:
            return
        overlays.draw_circle_2d(middle, (edge - middle).length)

    def start_mode(self, mode, committed, event):
        """G, R or S from the handle as ``committed`` left it, the mouse where it is now."""
        self._mode, self._committed, self._axis, self._typed = mode, committed, None, ""
        centre = self._drag.centre + committed.offset
        self._centre = self._obj.matrix_world @ Vector(centre.tolist())
        self._start = self._mouse = self.mouse_point(event)
        self._start_2d = self._last_2d = self.mouse_2d(event)
        self._angle = 0.0
        self._view_axis = np.array(self._region.data.view_rotation @ Vector((0.0, 0.0, 1.0)))

    def mouse_point(self, event):
        """The mouse's point in the view plane through the handle's centre (world), also when the
        operator was started from the sidebar (window coordinates into the 3D View's main region)."""
        region = self._region
        mouse = (event.mouse_x - region.x, event.mouse_y - region.y)
        return view3d_utils.region_2d_to_location_3d(region, region.data, mouse, self._centre)

    def mouse_2d(self, event):
        """The mouse on screen relative to the handle's centre (pixels; (0, 0) if the centre is behind the view)."""
        region = self._region
        centre = view3d_utils.location_3d_to_region_2d(region, region.data, self._centre)
        mouse = Vector((event.mouse_x - region.x, event.mouse_y - region.y))
        return mouse - centre if centre is not None else Vector((0.0, 0.0))

    def modal(self, context, event):
        try:
            return self.handle_event(context, event)
        except Exception as error:  # noqa: BLE001 (every position back; reported, never a half-dragged mesh)
            self.cancel(context)
            self.report({"ERROR"}, f"{self.label}: {fairing.error_text(error)}; mesh restored")
            return {"CANCELLED"}

    def handle_event(self, context, event):
        if event.type == "TIMER":  # the timer of sync_timer (or another's: then nothing is due)
            if self._resize_factor != 1.0 and time.perf_counter() - self._resize_at >= RESIZE_DELAY:
                factor, self._resize_factor = self._resize_factor, 1.0
                self.resize(context, factor)
            elif self._continuing:
                self.drag_to(context)  # a frame cut short goes on
            self.sync_timer(context)
            return {"PASS_THROUGH"}
        if self.radius > 0.0 and event.type in RADIUS_EVENTS and event.value in {"PRESS", "NOTHING"}:
            # Wheel steps in quick succession make one new region (each is a cold fair).
            self._resize_factor *= RADIUS_EVENTS[event.type]
            self._resize_at = time.perf_counter()
            self.sync_timer(context)
            self.show(context, f"radius {self.radius * self._resize_factor:.4g}: preparing")
        elif event.type == "MOUSEMOVE":
            self._mouse = self.mouse_point(event)
            now = self.mouse_2d(event)
            if self._last_2d.length > 0.0 and now.length > 0.0:
                self._angle += self._last_2d.angle_signed(now, 0.0) * -1.0  # counter-clockwise positive
            self._last_2d = now
            self.drag_to(context)
        elif event.type in MODE_EVENTS and event.value == "PRESS":
            self.start_mode(MODE_EVENTS[event.type], self._drag.move, event)
            self.drag_to(context)
        elif event.type in AXIS_EVENTS and event.value == "PRESS":
            axis = AXIS_EVENTS[event.type]
            self._axis = None if self._axis == axis else axis
            self.drag_to(context)
        elif (event.type in live.TYPED_KEYS or event.type == "BACK_SPACE") and event.value == "PRESS":
            self._typed = live.typed_text(self._typed, event.type)
            self.drag_to(context)
        elif event.type in CONFIRM_EVENTS and event.value == "PRESS":
            return self.confirm(context)
        elif event.type in CANCEL_EVENTS and event.value == "PRESS":
            self.cancel(context)
            return {"CANCELLED"}
        elif event.type in NAVIGATION_EVENTS:
            return {"PASS_THROUGH"}
        return {"RUNNING_MODAL"}

    def drag_to(self, context):
        """One frame with the handle where the mouse (or the typed value) puts it; written if it converged."""
        if self._typed and live.typed_value(self._typed) is None:  # "-" or "." so far
            self.show(context, "type a number")
            return
        start = self._start_2d
        factor = self._last_2d.length / start.length if start.length >= 1.0 else 1.0
        move = live.mode_move(
            self._mode,
            self._committed,
            np.array(self._to_object),
            np.array(self._mouse - self._start),
            self._angle,
            self._view_axis,
            factor,
            self._axis,
            live.typed_value(self._typed) if self._typed else None,
        )
        frame = self._drag.frame(move, max_substeps=MAX_SUBSTEPS)
        if frame.converged:
            mesh_io.write_positions(self._obj, self._drag.positions, self._drag.moving)
        self.show(context, frame.status())
        # A frame cut short (a long typed move) goes on at the next timer event: the UI stays live.
        self._continuing = frame.converged and not frame.reached
        self.sync_timer(context)

    def sync_timer(self, context):
        """A timer while a frame cut short goes on or wheel steps gather, none otherwise."""
        due = self._continuing or self._resize_factor != 1.0
        if due and self._timer is None:
            self._timer = context.window_manager.event_timer_add(0.02, window=context.window)
        elif not due and self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None

    def show(self, context, text):
        move = self._drag.move
        what = f"offset {live.distance_text(move.offset)}"
        _, angle = live.axis_angle(move.rotation)
        if angle > 0.0:
            what += f", turned {np.degrees(angle):.1f}°"
        if move.scale != 1.0:
            what += f", scaled {move.scale:.3g}"
        mode = {"TRANSLATE": "Move", "ROTATE": "Rotate", "SCALE": "Scale"}[self._mode]
        if self._axis is not None and self._mode != "SCALE":  # scaling is uniform
            mode += f" {'along' if self._mode == 'TRANSLATE' else 'about'} {'XYZ'[self._axis]}"
        if self._typed:
            mode += f" [{self._typed}]"
        context.area.header_text_set(f"{self.label} ({mode}): {what}, {text} — {LIVE_HINT}")

    def confirm(self, context):
        """Keep the last good frame (one undo step); the offset it reached is the redo panel's."""
        drag = self._drag
        self.offset = drag.move.offset.tolist()
        self.rotation = Matrix(drag.move.rotation.tolist()).to_euler()
        self.scale = drag.move.scale
        self.end(context)
        try:
            overlays.refresh_curvature(self._obj, context)
        except RuntimeError as error:
            self.report({"WARNING"}, f"{self.label}: curvature not updated: {error}")
        self.report({"INFO"}, f"{self.label}: {drag.summary()}")
        return {"FINISHED"}

    def cancel(self, context):
        """Esc, RMB, or Blender ending the operator: every position back as it was, byte for byte."""
        drag = self._drag
        try:
            if drag is not None:
                mesh_io.write_positions(self._obj, drag.base, drag.moving)
        finally:
            self.end(context)

    def end(self, context):
        self._drag = None
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
        if self._circle is not None:
            bpy.types.SpaceView3D.draw_handler_remove(self._circle, "WINDOW")
            self._circle = None
        if context.area is not None:
            context.area.header_text_set(None)


CLASSES = (
    MESH_OT_geometric_fairing,
    MESH_OT_geometric_fairing_fill_holes,
    MESH_OT_geometric_fairing_live,
    VIEW3D_OT_geometric_fairing_zebra,
    MESH_OT_geometric_fairing_curvature,
)
