"""One fairing run on a Blender mesh, runs on several objects, and :func:`fair_object` for scripts.

A :class:`FairingRun` reads the mesh and finds the region when it is made,
solves (in the calling thread or a worker thread) and writes the new positions
only in :meth:`FairingRun.finish`: a run that is cancelled or fails (also inside
the compiled solver) never touches the mesh. A :class:`FairingBatch` solves the
runs of several objects (multi-object Edit Mode) one after another. The
operator (modal, Esc to cancel) and :func:`fair_object` (``blender
--background`` pipelines) share them.

A run whose solve stops unconverged writes nothing either, unless
``keep_unconverged`` is set: :meth:`FairingRun.finish` returns its report with
``discarded`` set, the operator reports it as an error and :func:`fair_object`
raises :class:`NotConvergedError`.

Hidden faces take no part unless ``use_hidden`` is set: the mesh ends at them
as at an open border (see :func:`region.find_region`), so a hidden face's
vertices never move, and those next to the region are fixed boundary vertices
(G1: with normals from the visible faces).

With ``boundary="g0"`` (positions only) no boundary normal is estimated or
checked: the library reads none, and a region that reaches the open mesh border
needs none there either.
"""

import difflib
import math
import threading
import time
import types
from dataclasses import dataclass, field

import bpy
import numpy as np

from . import carry, mesh_edit, mesh_io, metrics, native, overlays, properties, region


@dataclass
class FairingOptions:
    """Options of a run: ``geofair.fair``'s by its names and values (the library checks them), defaults
    from ``geofair.defaults()``, then the add-on's own.

    ``time_limit`` None (or 0) is automatic (the library's). The options no property holds
    (``properties.SCRIPT_OPTION_NAMES``: ``normal_weighting``, ``damping``, ``cg_iterations``,
    ``tuning``) are None unless a script gives them: None is not passed, so the library's default
    applies. The upper-case values earlier versions of the add-on took ("UNIFORM", "CONFORMAL",
    "INTRINSIC", "BILAPLACIAN", "AUTO", "NEWTON", "PAPER") are still accepted: a string value is
    taken in lower case (so is "G0" for ``boundary``).
    """

    inner_fairness: str = properties.DEFAULTS["inner_fairness"]
    outer_fairness: str = properties.DEFAULTS["outer_fairness"]
    boundary: str = properties.DEFAULTS["boundary"]
    tolerance: float = properties.DEFAULTS["tolerance"]
    max_iterations: int = properties.DEFAULTS["max_iterations"]
    levels: int = properties.DEFAULTS["levels"]
    iteration: str = properties.DEFAULTS["iteration"]
    time_limit: float | None = properties.DEFAULTS["time_limit"]
    normal_weighting: str | None = None
    damping: float | None = None
    cg_iterations: int | None = None
    tuning: dict | None = None
    remesh: str = "off"
    region_group: str = ""
    pin_group: str = ""
    use_hidden: bool = False
    keep_unconverged: bool = False

    def __post_init__(self):
        for name in ("inner_fairness", "outer_fairness", "boundary", "iteration", "remesh"):
            if isinstance(getattr(self, name), str):
                setattr(self, name, getattr(self, name).lower())
        if isinstance(self.remesh, bool):  # geofair.fair's own values
            self.remesh = "always" if self.remesh else "off"
        if self.remesh not in properties.REMESH_VALUES:
            raise ValueError(
                f"remesh must be one of {', '.join(repr(v) for v in properties.REMESH_VALUES)}, got {self.remesh!r}"
            )

    def library_options(self):
        """The keyword arguments of ``geofair.fair`` these options give (``remesh`` only when it is not off,
        a script's option only when given, so that the default run is the library's default call)."""
        options = {name: getattr(self, name) for name in properties.LIBRARY_OPTION_NAMES}
        for name in properties.SCRIPT_OPTION_NAMES:
            if getattr(self, name) is not None:
                options[name] = getattr(self, name)
        if self.remesh != "off":
            options["remesh"] = properties.REMESH_VALUES[self.remesh]
        return options


@dataclass(frozen=True)
class FairingReport:
    """Figures of a run.

    Attributes:
        object_name: the mesh object.
        free_vertices: vertices that could move.
        pinned_vertices: vertices inside the region kept fixed by the pin group.
        border_fixed_vertices: vertices inside the region kept fixed on the open mesh border
            (with ``boundary="g0"`` boundary vertices like any other: :meth:`summary` does not
            mention them).
        hidden_fixed_vertices: vertices inside the region kept fixed because they belong to a
            hidden face too (without ``use_hidden``).
        converged: the residual fell below the tolerance.
        cancelled: stopped by Esc or by a progress callback; the mesh is unchanged.
        discarded: not converged, and the options did not ask to keep an unconverged
            result (``keep_unconverged``); the mesh is unchanged.
        tolerance: the tolerance of the run.
        iterations: fairing iterations (all levels), or Newton steps.
        residual: the last normalized residual of Δ_B H = 0 (dimensionless).
        seconds: wall time of the solve.
        uv_before, uv_after: :class:`metrics.Distortion` of the active UV map over the
            triangles with a free vertex, before and after (None without a UV map;
            ``uv_after`` is None when the mesh was not changed).
        iterations_per_level, vertices_per_level: per multigrid level, coarsest first.
        iteration: the solver that produced the result, "newton" or "paper" (``iteration="auto"``
            picks one; "" when nothing was solved).
        folds: edges with a free vertex whose two triangles face apart in the solver's
            result (``geofair.FairingResult.folds``), also where that result was not written;
            new_folds: those of them that did not in the mesh before.
        timings: wall time in seconds of the steps of the run: ``read`` (mesh to numpy),
            ``region``, ``uv`` (UV distortion before and after, with ``uv_read``, reading
            the UVs), ``solve``, ``write``.
        message: the library's account of how the solve ended (``geofair.FairingResult.message``).
        stop_reason: why the solve ended, as a value (``geofair.FairingResult.stop_reason``:
            "converged", "max_iterations", "time_limit", "no_progress", "cancelled", "diverged").
        boundary: the boundary condition of the run, "g1" or "g0".
        remesh: the Remesh option of the run ("off", "if_needed", "always").
        remeshed: the region's triangles were replaced (``geofair.FairingResult.remeshed``);
            in the mesh too when ``changed``.
        triangles_added, faces_removed: new faces written and old faces deleted (remeshed).
        uv_flips: new triangles whose active-UV orientation is opposite to the old region's.
        notes: what could not be carried over to new faces (UV seams, custom normals), one
            sentence each.
        holes: holes filled (Fill Holes; ``free_vertices`` are then the new vertices).
        hole_fills: Fill Holes: what was done with each hole (:func:`region.hole_records`:
            method, converged, folds, removed faces, why left open).
    """

    object_name: str
    free_vertices: int
    pinned_vertices: int
    border_fixed_vertices: int
    converged: bool
    cancelled: bool
    iterations: int
    residual: float
    seconds: float
    uv_before: metrics.Distortion | None = None
    uv_after: metrics.Distortion | None = None
    iterations_per_level: list = field(default_factory=list)
    vertices_per_level: list = field(default_factory=list)
    hidden_fixed_vertices: int = 0
    iteration: str = ""
    timings: dict = field(default_factory=dict)
    discarded: bool = False
    tolerance: float = float("nan")
    folds: int = 0
    new_folds: int = 0
    message: str = ""
    stop_reason: str = ""
    boundary: str = "g1"
    remesh: str = "off"
    remeshed: bool = False
    triangles_added: int = 0
    faces_removed: int = 0
    uv_flips: int = 0
    notes: tuple = ()
    holes: int = 0
    hole_fills: tuple = ()

    @classmethod
    def of_result(cls, result, options, **fields):
        """The report of a run whose library result is ``result`` (``geofair.FairingResult``)
        with ``options`` (:class:`FairingOptions`): the solver's figures from the result, the
        tolerance and boundary from the options, the rest from ``fields``."""
        return cls(
            converged=bool(result.converged),
            iterations=int(result.iterations),
            residual=float(result.residual),
            iterations_per_level=list(result.iterations_per_level),
            vertices_per_level=list(result.vertices_per_level),
            iteration=str(result.iteration),
            folds=int(getattr(result, "folds", 0)),
            new_folds=int(getattr(result, "new_folds", 0)),
            message=str(getattr(result, "message", "")),
            stop_reason=str(getattr(result, "stop_reason", "")),
            tolerance=float(options.tolerance),
            boundary=options.boundary,
            **fields,
        )

    @property
    def stopped_at_time_limit(self):
        """The library's words where an unconverged solve stopped at its time limit, the given or the automatic
        one ("stopped at the time limit of 1.0e-02 s"), else ""."""
        if self.converged or self.stop_reason not in ("time_limit", "no_progress"):
            return ""
        return self.message.split(" (", 1)[0]

    @property
    def changed(self):
        """Whether the mesh was changed (neither cancelled nor discarded)."""
        return not self.cancelled and not self.discarded

    def summary(self):
        """One line for reports and logs."""
        if self.hole_fills:
            text = region.fill_text(self.hole_fills) + f"; {self.free_vertices} new vertices"
            if self.changed:
                text += f", {self.triangles_added} new triangles"
        elif self.holes:
            text = f"{self.holes} hole{'s' if self.holes > 1 else ''}, {self.free_vertices} new vertices"
            if self.changed:
                text += f", {self.triangles_added} new triangles"
        else:
            text = f"{self.free_vertices} vertices"
        if self.pinned_vertices:
            text += f" ({self.pinned_vertices} pinned)"
        text += f", {self.iterations} iterations, residual {self.residual:.3g}, {self.seconds:.2f} s"
        if self.border_fixed_vertices and self.boundary != "g0":  # G0 needs nothing from the faces around
            text += f"; {self.border_fixed_vertices} vertices on the open mesh border kept fixed"
        if self.hidden_fixed_vertices:
            text += f"; {self.hidden_fixed_vertices} vertices of hidden faces kept fixed"
        if self.uv_before is not None:
            text += f"; UV distortion mean {self.uv_before.mean:.4f}"
            if self.uv_after is not None:
                text += f" → {self.uv_after.mean:.4f}"
        if self.cancelled:
            return text + ", cancelled: mesh unchanged"
        stopped = f" ({self.stopped_at_time_limit})" if self.stopped_at_time_limit else ""
        if self.discarded:
            return text + f", NOT converged{stopped}: mesh unchanged"
        if self.hole_fills:  # fill_text said how each hole ended
            return "; ".join([text, *self.notes])
        text += ", converged" if self.converged else f", NOT converged{stopped}, result kept"
        if self.folds:
            but = ", but " if self.converged else ", "
            text += f"{but}{self.folds} edge{'s' if self.folds > 1 else ''} folded over (triangles flipped)"
        if self.remeshed and self.changed and not self.holes:
            text += f"; remeshed: {self.faces_removed} faces replaced by {self.triangles_added} triangles"
            if self.uv_flips:
                text += f", {self.uv_flips} flipped in the UV map"
        for note in self.notes:
            text += f"; {note}"
        return text


def short_number(x):
    """``x`` with at most two significant digits, in scientific notation unless in [1, 10): 3.2e-1, 1e-4, 3.6, 1.2e2."""
    if not math.isfinite(x) or x == 0.0:
        return f"{x:g}"
    mantissa, exponent = f"{x:.1e}".split("e")
    mantissa = mantissa.rstrip("0").rstrip(".")
    return mantissa if int(exponent) == 0 else f"{mantissa}e{int(exponent)}"


CONFORMAL_HINT = "Conformal inner fairness converges on more meshes."
KEEP_UNCONVERGED_HINT = "Pass keep_unconverged=True to apply it anyway."
REMESH_HINT = "Remesh 'If Needed' may help (it changes the triangles)."
REMESH_SCRIPT_HINT = "Passing remesh='if_needed' may help (it changes the triangles)."
TIME_LIMIT_HINT = "A longer Time Limit (0: automatic) lets it go on."
TIME_LIMIT_SCRIPT_HINT = "A longer time_limit (None: automatic) lets it go on."


def unconverged_hint(
    options,
    report,
    keep_hint=KEEP_UNCONVERGED_HINT,
    remesh=None,
    remesh_hint=REMESH_SCRIPT_HINT,
    time_limit_hint=TIME_LIMIT_SCRIPT_HINT,
):
    """What to try after the unconverged run ``report`` of ``options`` that was not kept: where it stopped at the
    time limit the user gave, a longer one; else Conformal after Uniform (uniform inner fairness can degenerate the
    triangles of an irregular region, docs/REAL_MESHES.md) and remeshing if it was off (``remesh``, by default
    ``options.remesh``); then ``keep_hint``."""
    if report.stop_reason == "time_limit" and options.time_limit:
        return f"{time_limit_hint} {keep_hint}"
    hints = [CONFORMAL_HINT] if options.inner_fairness == "uniform" else []
    if (options.remesh if remesh is None else remesh) == "off":
        hints.append(remesh_hint)
    return " ".join([*hints, keep_hint])


class SolverFailedError(RuntimeError):
    """The solver failed (a RuntimeError from ``geofair.fair``) with Remesh off: its message and the hint to remesh."""


class NotConvergedError(RuntimeError):
    """The solve stopped before the residual reached the tolerance, and the result was not kept.

    Attributes:
        report: the run's :class:`FairingReport` (``discarded`` set; the mesh is unchanged).
    """

    def __init__(self, report, hint=KEEP_UNCONVERGED_HINT):
        self.report = report
        stopped = f"; {report.stopped_at_time_limit}" if report.stopped_at_time_limit else ""
        super().__init__(
            f"Fairing did not converge (residual {short_number(report.residual)}, tolerance "
            f"{short_number(report.tolerance)}{stopped}): the mesh is unchanged. {hint}"
        )


# FairingRun's polygon_ids by default: each face of the mesh is a polygon.
_FACES = object()

# The result of a run that never got to solve (cancelled first): nothing to write.
_NOT_SOLVED = types.SimpleNamespace(
    converged=False, iterations=0, residual=float("nan"), iterations_per_level=[], vertices_per_level=[], iteration=""
)


class _WorkerThread:
    """``solve()`` in a worker thread (the solver releases the GIL): start, poll, wait."""

    _thread = None

    def start(self):
        """Run :meth:`solve` in a worker thread; poll :attr:`done`."""
        self._thread = threading.Thread(target=self.solve, name="geometric-fairing", daemon=True)
        self._thread.start()

    @property
    def done(self):
        """Whether the worker thread (if any) has finished."""
        return self._thread is None or not self._thread.is_alive()

    def wait(self, timeout=None):
        """Wait for the worker thread; return :attr:`done`."""
        if self._thread is not None:
            self._thread.join(timeout)
        return self.done


def _pinned(obj, options, mesh, pin_selected, pin_group=True):
    """``(n,)`` bool vertices of the Pin group (non-zero weight; not with ``pin_group`` False), and the
    selected ones with ``pin_selected``; None when neither applies."""
    pinned = None
    if options.pin_group and pin_group:
        pinned = mesh_io.vertex_group_weights(obj, options.pin_group) > 0.0
    if pin_selected:
        pinned = mesh.vertex_selected if pinned is None else pinned | mesh.vertex_selected
    return pinned


def _region_faces(obj, options, mesh, faces, present, pin_selected, handle_radius):
    """``(faces, pin_selected)``: the faces to fair (FairingRun's ``faces``, ``handle_radius`` and
    ``options.region_group`` rules) and whether the selected vertices are pinned."""
    if handle_radius is not None:
        if not mesh.vertex_selected.any():
            raise region.NothingSelectedError("No vertex is selected: select the handle's vertices")
        near = region.surface_distances(mesh.vertices, mesh.triangles, mesh.vertex_selected, handle_radius)
        faces = region.polygons_inside(near <= handle_radius, mesh.loop_start, mesh.loop_total, mesh.corner_verts)
        faces &= present
        if not faces.any():
            raise region.NothingSelectedError(f"No face lies within the radius {handle_radius:.4g} of the handle")
        return faces, True
    if faces is None and options.region_group:
        if obj.vertex_groups.get(options.region_group) is None:
            raise region.NothingSelectedError(f"'{obj.name}' has no vertex group '{options.region_group}'")
        inside = mesh_io.vertex_group_weights(obj, options.region_group) > 0.0
        faces = region.polygons_inside(inside, mesh.loop_start, mesh.loop_total, mesh.corner_verts) & present
        if not faces.any():
            raise region.NothingSelectedError(f"Vertex group '{options.region_group}' encloses no face")
    elif faces is None:
        faces = mesh.face_selected & present
        region.require_selected_faces(faces, mesh.vertex_selected)
    return faces, pin_selected


class FairingRun(_WorkerThread):
    """A fairing run on the mesh of ``obj`` (Edit Mode or Object Mode).

    Args:
        obj: a mesh object.
        options: :class:`FairingOptions`.
        faces: ``(P,)`` bool mask of the faces to fair, or None: the faces of
            ``options.region_group`` if set, else the selected faces.
        progress: optional ``callable(iteration, residual)``, called about every
            0.1 s from the thread that solves; returning False cancels.
        boundary_normals: ``(V, 3)`` float unit normals over the mesh's vertices, read at
            the G1 boundary vertices (``geofair.fair``'s), or None: estimated from the
            faces around (and at pinned vertices, their own normal).
        polygon_ids: ``(P,)`` integer array, the polygon each face of the mesh belongs to
            (uniform inner fairness runs over the polygons' edges); None: each triangle
            of the tessellation is a polygon (its diagonals count as edges). Default: each
            face is a polygon.
        pin_selected: the selected vertices are pinned too (Live Fair Drag's handle when a
            Region vertex group or a radius gives the region).
        handle_radius: the region is the faces within this distance (mesh units, along the
            edges) of the selected vertices (Live Fair Drag's radius), which are pinned (the
            Pin group is not used); None: ``faces``.

    Raises:
        ValueError: no usable region (:class:`region.RegionError`), a missing
            vertex group, a wrong mask or polygon_ids.
        RuntimeError: the compiled module cannot be loaded.
    """

    remesh_hint = REMESH_SCRIPT_HINT  # added to a solver failure with Remesh off (the operator's: REMESH_HINT)

    def __init__(
        self,
        obj,
        options,
        faces=None,
        progress=None,
        boundary_normals=None,
        polygon_ids=_FACES,
        pin_selected=False,
        handle_radius=None,
    ):
        if native.geofair is None:
            raise RuntimeError(native.IMPORT_ERROR)
        if obj is None or obj.type != "MESH":
            raise ValueError("fairing needs a mesh object")
        mesh = self._read(obj, options, progress)
        clock = time.perf_counter()
        present = np.ones(len(mesh.loop_start), dtype=bool) if options.use_hidden else ~mesh.face_hidden
        faces, pin_selected = _region_faces(obj, options, mesh, faces, present, pin_selected, handle_radius)
        faces = np.asarray(faces, dtype=bool)
        if faces.shape != (len(mesh.loop_start),):
            raise ValueError(f"the face mask must have one entry per face ({len(mesh.loop_start)}), not {faces.shape}")
        pinned = _pinned(obj, options, mesh, pin_selected, pin_group=handle_radius is None)
        self.present_triangles = present[mesh.triangle_face]
        self.region = region.find_region(
            mesh.vertices, mesh.triangles, faces[mesh.triangle_face], pinned, present=self.present_triangles
        )
        if options.remesh != "off" and mesh_edit.has_shape_keys(obj):
            raise ValueError(
                f"Remesh needs a mesh without shape keys ('{obj.name}' has some: the new vertices would have no "
                "shape-key positions): use Remesh Off"
            )
        self.boundary_normals = None  # G0: positions only, the library reads no normals
        if options.boundary != "g0" and boundary_normals is not None:
            self.boundary_normals = np.asarray(boundary_normals, dtype=np.float64)
        elif options.boundary != "g0":
            self.boundary_normals = region.boundary_normals(
                self.region, mesh.vertices, mesh.triangles[self.present_triangles], native.geofair.boundary_normals
            )
        # Uniform inner fairness over the polygons' edges, not the tessellation's diagonals.
        self.polygon_ids = mesh.triangle_face[self.present_triangles]
        if polygon_ids is None:
            self.polygon_ids = None
        elif polygon_ids is not _FACES:
            polygon_ids = np.asarray(polygon_ids)
            if polygon_ids.shape != (len(mesh.loop_start),) or polygon_ids.dtype.kind not in "iu":
                raise ValueError(
                    f"polygon_ids must be an integer array with one entry per face ({len(mesh.loop_start)}), "
                    f"not {polygon_ids.dtype} {polygon_ids.shape}"
                )
            self.polygon_ids = polygon_ids[self.polygon_ids]
        self.changed_triangles = region.region_triangles(mesh.triangles, self.region.free)
        self.timings["region"] = time.perf_counter() - clock
        clock = time.perf_counter()
        mesh.corner_uvs = mesh_io.read_uvs(obj, mesh)
        self.timings["uv_read"] = time.perf_counter() - clock
        self.uv_before = self._uv_distortion(mesh.vertices)
        self.timings["uv"] = time.perf_counter() - clock
        self._reset_run()

    def _read(self, obj, options, progress):
        """Keep the object, its mode, the options and the progress callback; read and return its mesh."""
        self.obj = obj
        self.object_name = obj.name
        self.mode = obj.mode
        self.options = options
        self.user_progress = progress
        self.timings = {}
        clock = time.perf_counter()
        self.mesh = mesh_io.read(obj, uvs=False)
        self.timings["read"] = time.perf_counter() - clock
        return self.mesh

    def _reset_run(self):
        """The figures and the state of a run that has not solved yet."""
        self.iteration = 0
        self.residual = float("nan")
        self.first_residual = float("nan")
        self.seconds = 0.0
        self.result = None
        self.error = None
        self._cancel = threading.Event()
        self._thread = None

    # -- solving -----------------------------------------------------------------------------

    def _solve_with(self, call):
        """``call()``'s result, or the exception it raised, kept for :meth:`finish` (which runs in
        Blender's thread); its seconds in ``seconds`` and the "solve" timing."""
        start = time.perf_counter()
        try:
            self.result = call()
        except Exception as error:
            self.error = error
        self.seconds = time.perf_counter() - start
        self.timings["solve"] = self.seconds

    def solve(self):
        """Solve in this thread; the result or the error is kept for :meth:`finish`."""
        mesh = self.mesh
        self._solve_with(
            lambda: native.geofair.fair(
                mesh.vertices,
                mesh.triangles[self.present_triangles],
                self.region.free,
                boundary_normals=self.boundary_normals,
                polygon_ids=self.polygon_ids,
                progress=self._progress,
                **self.options.library_options(),
            )
        )

    def request_cancel(self):
        """Ask the solver to stop at its next progress call (within about 0.1 s and one iteration)."""
        self._cancel.set()

    @property
    def cancel_requested(self):
        return self._cancel.is_set()

    def _progress(self, iteration, residual):
        self.iteration, self.residual = int(iteration), float(residual)
        if self.first_residual != self.first_residual and residual == residual:  # the first that is not NaN
            self.first_residual = float(residual)
        if self.user_progress is not None and self.user_progress(iteration, residual) is False:
            self._cancel.set()
        return not self._cancel.is_set()

    # -- result ------------------------------------------------------------------------------

    def finish(self):
        """Write the result into the mesh unless cancelled or discarded; return the :class:`FairingReport`.

        Call in Blender's main thread after :meth:`solve` (or when :attr:`done`). An
        unconverged result is written only with ``options.keep_unconverged``;
        otherwise the report has ``discarded`` set and the mesh is unchanged.

        Raises:
            ValueError, RuntimeError: the solver failed (the mesh is unchanged),
                or the mesh changed under the run.
        """
        if not self.done:
            raise RuntimeError("finish: the run is still going")
        cancelled = self._cancel.is_set()  # even if it converged meanwhile: the user asked for the mesh as it was
        if self.error is not None and not cancelled:
            if type(self.error) is RuntimeError and self.options.remesh == "off":
                raise SolverFailedError(f"{self.error} {self.remesh_hint}") from self.error
            raise self.error
        result = self.result
        uv_after = None
        if result is None:  # cancelled before it was solved (a later object of a batch), or failed meanwhile
            cancelled = True
            result = _NOT_SOLVED
        discarded = not cancelled and not result.converged and not self.options.keep_unconverged
        remeshed = bool(getattr(result, "remeshed", False))
        written = mesh_edit.Written()
        if not cancelled and not discarded:
            positions = np.asarray(result.vertices, dtype=np.float64)
            free = np.flatnonzero(self.region.free)
            if not remeshed and (positions.shape != self.mesh.vertices.shape or not np.isfinite(positions[free]).all()):
                raise RuntimeError("the solver returned invalid positions; mesh unchanged")
            try:
                unchanged = self.obj.mode == self.mode and mesh_io.vertex_count(self.obj) == len(self.mesh.vertices)
            except ReferenceError:  # the object was deleted
                unchanged = False
            if not unchanged:
                raise RuntimeError("the mesh changed during the run; result discarded")
            clock = time.perf_counter()
            if remeshed:  # the region's triangles were replaced: carry the layers over (mesh_edit)
                try:
                    written = mesh_edit.replace_region(
                        self.obj, self.mesh, np.flatnonzero(self.present_triangles), self.region.free, result
                    )
                except carry.CarryError as error:
                    raise RuntimeError(str(error)) from error
            else:
                mesh_io.write_positions(self.obj, positions, free)
            self.timings["write"] = time.perf_counter() - clock
            clock = time.perf_counter()
            if remeshed:
                if written.metric_uvs is not None:
                    uv_after = metrics.uv_distortion(
                        written.metric_vertices, written.metric_triangles, written.metric_uvs
                    )
            else:
                uv_after = self._uv_distortion(positions)
            self.timings["uv"] += time.perf_counter() - clock
        return FairingReport.of_result(
            result,
            self.options,
            object_name=self.object_name,
            free_vertices=int(np.count_nonzero(result.free if remeshed else self.region.free)),
            pinned_vertices=int(np.count_nonzero(self.region.pinned)),
            border_fixed_vertices=int(np.count_nonzero(self.region.border_fixed)),
            hidden_fixed_vertices=int(np.count_nonzero(self.region.hidden_fixed)),
            cancelled=cancelled,
            seconds=self.seconds,
            uv_before=self.uv_before,
            uv_after=uv_after,
            timings=dict(self.timings),
            discarded=discarded,
            remesh=self.options.remesh,
            remeshed=remeshed,
            triangles_added=written.triangles_added,
            faces_removed=written.faces_removed,
            uv_flips=written.uv_flips,
            notes=tuple(written.notes),
        )

    def _uv_distortion(self, positions):
        uv = self.mesh.corner_uvs
        if uv is None:
            return None
        keep = self.changed_triangles
        return metrics.uv_distortion(positions, self.mesh.triangles[keep], uv[self.mesh.triangle_corners[keep]])


class FairingBatch(_WorkerThread):
    """The runs of several objects (multi-object Edit Mode), solved one after another.

    Solving, cancelling and waiting work as for one :class:`FairingRun`; a
    failure of one run (also inside the compiled solver) is kept by that run
    and does not stop the others. :meth:`finish` writes each run that
    succeeded and returns the reports and the errors per object (the report
    of a run whose unconverged result was discarded, and not written, too).

    Args:
        runs: list of :class:`FairingRun`, each on another mesh.
    """

    def __init__(self, runs):
        self.runs = list(runs)
        self.index = 0
        self.written = []  # the runs whose result finish() wrote
        self._cancel = threading.Event()
        self._thread = None

    @property
    def current(self):
        """The run being solved (the last one once all are done)."""
        return self.runs[min(self.index, len(self.runs) - 1)]

    @property
    def iteration(self):
        return self.current.iteration

    @property
    def residual(self):
        return self.current.residual

    @property
    def free_vertices(self):
        return int(sum(np.count_nonzero(run.region.free) for run in self.runs))

    def solve(self):
        """Solve every run in this thread, in order, until all are done or cancelled."""
        for index, run in enumerate(self.runs):
            if self._cancel.is_set():
                break
            self.index = index
            run.solve()

    def request_cancel(self):
        """Cancel every run: the one solving stops at its next progress call, the others never start."""
        self._cancel.set()
        for run in self.runs:
            run.request_cancel()

    @property
    def cancel_requested(self):
        return self._cancel.is_set()

    def progress(self, tolerance):
        """Progress in [0, 1] over all runs: each run's share on a log scale of its residual."""
        run = self.current
        fraction = progress_fraction(run.first_residual, run.residual, tolerance)
        return (min(self.index, len(self.runs) - 1) + fraction) / len(self.runs)

    def finish(self):
        """Write each run's result unless cancelled; return ``(reports, errors)``.

        ``reports`` is a list of :class:`FairingReport`, ``errors`` a list of
        ``(object name, exception)`` of the runs that failed (their meshes are
        unchanged).
        """
        reports, errors = [], []
        self.written = []
        for run in self.runs:
            try:
                report = run.finish()
            except Exception as error:  # noqa: BLE001 (anything from the solver: that object is left as it was)
                errors.append((run.object_name, error))
                continue
            reports.append(report)
            if report.changed:
                self.written.append(run)
        return reports, errors


def progress_fraction(first_residual, residual, tolerance):
    """Progress in [0, 1] of a run from its first residual towards the tolerance, on a log scale."""
    if not (first_residual > tolerance > 0.0 and residual > 0.0) or math.isnan(residual):
        return 0.0
    fraction = math.log(first_residual / residual) / math.log(first_residual / tolerance)
    return min(max(fraction, 0.0), 1.0)


def error_text(error):
    """The text of an error for a report: the message, with the type for unexpected ones."""
    if isinstance(error, (ValueError, RuntimeError)):
        return str(error)
    return f"{type(error).__name__}: {error}"


def options_from_settings(settings, **given):
    """:class:`FairingOptions` from the panel's ``settings`` (scene.geometric_fairing), overridden by ``given``."""
    values = properties.option_values(settings)
    values.update(given)
    return FairingOptions(**values)


def default_options(context, **given):
    """Options a script gets: the scene's panel settings when registered, else the preferences' defaults."""
    settings = getattr(context.scene, "geometric_fairing", None)
    if settings is not None:
        return options_from_settings(settings, **given)
    return FairingOptions(**given)


def check_option_names(function, options, names):
    """Raise a TypeError naming the first of ``options`` that is not in ``names`` (nor ``keep_unconverged``,
    nor one of ``properties.MESH_ARGUMENT_NAMES`` for fair_object), with the nearest valid name."""
    valid = (*names, "keep_unconverged", *(properties.MESH_ARGUMENT_NAMES if function == "fair_object" else ()))
    for name in options:
        if name not in valid:
            close = difflib.get_close_matches(name, valid, n=1)
            hint = f"; did you mean {close[0]!r}?" if close else f" (its options: {', '.join(valid)})"
            raise TypeError(f"{function}: unknown option {name!r}{hint}")


def fair_object(obj, region=None, *, progress=None, context=None, **options):
    """Fair a region of a mesh object, from a script, in Object Mode or Edit Mode.

    For ``blender --background`` pipelines: no operator, no context override,
    no undo step. The mesh is changed only if the run is neither cancelled nor
    failing. See ``examples/fair_object.py``.

    Args:
        obj: a mesh object.
        region: what to fair: the name of a vertex group (the faces all of
            whose vertices have a non-zero weight in it), a ``(P,)`` bool array
            over the mesh's faces, or None for the selected faces.
        progress: optional ``callable(iteration, residual)``, called about every
            0.1 s; returning False cancels the run and leaves the mesh unchanged.
        context: ``bpy.context`` by default; only its scene is read, for the
            defaults of options not given.
        **options: every keyword argument of ``geofair.fair``, by its names and values
            (``help(geofair.fair)``), passed through: ``inner_fairness`` ("uniform",
            "conformal" or "conformal_intrinsic"), ``outer_fairness`` ("intrinsic" or
            "bilaplacian"), ``boundary`` ("g1": positions and the tangent planes of the
            surface around, the default; "g0": positions only, the minimal surface spanned by
            the boundary, no normals needed), ``normal_weighting``, ``tolerance``,
            ``max_iterations``, ``damping``, ``cg_iterations``, ``levels``, ``iteration``
            ("auto", "newton" or "paper": the solver), ``time_limit`` (seconds; None or 0:
            automatic), ``tuning``; ``boundary_normals`` (``(V, 3)`` over the mesh's
            vertices; default: estimated from the faces around) and ``polygon_ids``
            (``(P,)``, the polygon each face of the mesh belongs to; default: each face its
            own; None: the triangles' edges, diagonals included). The upper-case values of
            earlier versions ("CONFORMAL") still work. The add-on's: ``pin_group`` (vertex group name),
            ``use_hidden`` (False: hidden faces take no part, their vertices never move),
            ``remesh`` ("off", the default: only positions change; "if_needed" or "always":
            the region's triangles may be replaced, with UVs, colours and vertex groups
            interpolated onto the new ones, see :class:`FairingReport` ``remeshed`` and
            ``notes``; ``geofair.fair``'s False and True work too).
            Not given: the Fairing panel's settings, which follow the add-on
            preferences (the library's defaults for the options the panel does not
            show). ``keep_unconverged`` (default False): write the result
            even if the solve stops unconverged.

    Returns:
        :class:`FairingReport` (also shown in the panel as the last run).

    Raises:
        TypeError: an unknown option.
        ValueError: no usable region, a missing vertex group, an option value
            ``geofair.fair`` rejects (its message names the values it takes).
        NotConvergedError: (a RuntimeError) the solve stopped unconverged and
            ``keep_unconverged`` is not set; the mesh is unchanged, the figures
            are in its ``report``.
        RuntimeError: the solver failed, or the compiled module is missing.
    """
    context = context or bpy.context
    check_option_names("fair_object", options, (*properties.OPTION_NAMES, *properties.SCRIPT_OPTION_NAMES))
    mesh_arguments = {name: options.pop(name) for name in ("boundary_normals", "polygon_ids") if name in options}
    faces = None
    if isinstance(region, str):
        options["region_group"] = region
    elif region is not None:
        faces = np.asarray(region, dtype=bool)
        options["region_group"] = ""
    else:
        options.setdefault("region_group", "")  # not the panel's: region=None means the selected faces
    run_options = default_options(context, **options)
    try:
        run = FairingRun(obj, run_options, faces=faces, progress=progress, **mesh_arguments)
        run.solve()
        report = run.finish()
        if report.discarded:
            raise NotConvergedError(report, unconverged_hint(run_options, report))
    except (ValueError, RuntimeError) as error:
        store_last_run(context.window_manager, run_options, error=error, object_name=getattr(obj, "name", ""))
        raise
    store_last_run(context.window_manager, run_options, report)
    if report.changed:
        overlays.refresh_curvature(obj, context)
    return report


def store_last_run(window_manager, options, report=None, error=None, object_name=""):
    """Keep the figures of a run (or its error) in ``window_manager.geometric_fairing.last_run`` for the panel."""
    session = getattr(window_manager, "geometric_fairing", None)
    if session is None:  # the add-on's classes are not registered
        return
    last = session.last_run
    last.inner_fairness = options.inner_fairness
    last.outer_fairness = options.outer_fairness
    last.boundary = options.boundary
    last.tolerance = options.tolerance
    last.not_faired = ""
    last.iteration = ""
    if isinstance(error, NotConvergedError):  # the figures of the run, with the reason it was not written
        store_last_run(window_manager, options, error.report)
        last.message = error_text(error)
        return
    if error is not None:
        last.status, last.message, last.object_name = "ERROR", error_text(error), object_name
        return
    last.object_name = report.object_name
    last.status = "CANCELLED" if report.cancelled else ("CONVERGED" if report.converged else "NOT_CONVERGED")
    last.message = report.summary()
    for figure in properties.RUN_FIGURES:
        setattr(last, figure.name, getattr(report, figure.name))
    last.has_uv = report.uv_before is not None
    if last.has_uv:
        last.uv_triangles = report.uv_before.triangles
        last.uv_before_mean, last.uv_before_max = report.uv_before.mean, report.uv_before.max
        after = report.uv_after or report.uv_before
        last.uv_after_mean, last.uv_after_max = after.mean, after.max


def store_last_runs(window_manager, options, reports, errors, message):
    """Keep the figures of the runs of several objects for the panel, added up; ``message`` is the report's line.

    One report and no error is stored as by :func:`store_last_run`. Objects
    that failed are listed in ``last_run.not_faired``.
    """
    session = getattr(window_manager, "geometric_fairing", None)
    if session is None:
        return
    if not reports:
        if len(errors) == 1:  # one object: its error as such (a NotConvergedError keeps its figures)
            store_last_run(window_manager, options, error=errors[0][1], object_name=errors[0][0])
            session.last_run.message = message
            return
        names = ", ".join(name for name, _ in errors)
        store_last_run(window_manager, options, error=RuntimeError(message), object_name=names)
        return
    if len(reports) == 1 and not errors:
        store_last_run(window_manager, options, reports[0])
        session.last_run.message = message
        return
    store_last_run(window_manager, options, reports[0])
    last = session.last_run
    last.object_name = ", ".join(report.object_name for report in reports)
    if any(report.cancelled for report in reports):
        last.status = "CANCELLED"
    else:
        last.status = "CONVERGED" if all(report.converged for report in reports) else "NOT_CONVERGED"
    last.message = message
    for figure in properties.RUN_FIGURES:
        setattr(last, figure.name, figure.combine(getattr(report, figure.name) for report in reports))
    last.has_uv = False  # one object's UV figures; they do not add up
    last.not_faired = "; ".join(f"{name}: {error_text(error)}" for name, error in errors)
