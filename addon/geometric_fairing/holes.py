"""Filling holes of a Blender mesh with ``geofair.fill_holes``: which holes, the run, the write.

A hole is a boundary loop of the mesh (a closed chain of edges with one face each). The
holes filled are those whose whole boundary loop is selected; with nothing selected in
the mesh (a script), or with ``all_holes``, every hole by the library's rule
(``geofair.holes_to_fill``): every boundary loop but the outer border of each open part of
the mesh, which the report names as left open. A :class:`FillRun` reads the mesh
when it is made, solves (in the calling thread or a worker thread, like
:class:`fairing.FairingRun`, whose progress and cancelling it shares) and writes only in
:meth:`FillRun.finish`: the new vertices and faces, with UVs, colours and vertex groups
interpolated harmonically from around each hole (:func:`mesh_edit.add_fill`). Every hole gets
a fill: the library tries its fills in turn and keeps the best (``geofair.FillResult.holes``
says which), so a fill that did not converge is written too and the report says so. With
*Clean Rim* (``clean_rim``, off by default: it deletes the user's faces) the library may remove
the faces of a ragged rim (teeth, spikes, faces that fold against the fill) where the fill of
the hole as it is folds or does not converge, and fill the larger hole; the report names them
(face indices before the fill).
"""

import time
import types

import numpy as np

from . import carry, fairing, mesh_edit, mesh_io, native, properties, region


class FillRun(fairing.FairingRun):
    """Filling the holes of the mesh of ``obj`` (Edit Mode or Object Mode).

    Args:
        obj: a mesh object.
        options: :class:`fairing.FairingOptions` (its library options are used; region,
            pins, hidden faces and remesh are not).
        all_holes: fill every hole whatever is selected (outer borders of open parts stay open).
        target_edge_length: the fill's edge length (object units); 0 or None: that of each hole's boundary.
        progress: optional ``callable(iteration, residual)``; returning False cancels.
        clean_rim: let the library remove the faces of a ragged rim where the fill of the hole as
            it is folds or does not converge (``geofair.fill_holes(rim="trim")``).

    Raises:
        ValueError: no hole to fill (:class:`region.RegionError`).
        RuntimeError: the compiled module cannot be loaded, or has no ``fill_holes``.
    """

    def __init__(self, obj, options, all_holes=False, target_edge_length=0.0, progress=None, clean_rim=False):
        if native.geofair is None:
            raise RuntimeError(native.IMPORT_ERROR)
        if not hasattr(native.geofair, "holes_to_fill"):
            raise RuntimeError("this build of the compiled module 'geofair' has no holes_to_fill: update the add-on")
        if obj is None or obj.type != "MESH":
            raise ValueError("filling holes needs a mesh object")
        if mesh_edit.has_shape_keys(obj):
            raise ValueError(
                f"Fill Holes needs a mesh without shape keys ('{obj.name}' has some: the new vertices would have no "
                "shape-key positions)"
            )
        self.target_edge_length = float(target_edge_length or 0.0)  # None as geofair's: automatic
        if not (0.0 <= self.target_edge_length < float("inf")):
            raise ValueError(f"target_edge_length must be 0, None or a positive length, got {target_edge_length!r}")
        self.clean_rim = bool(clean_rim)
        mesh = self._read(obj, options, progress)
        n = len(mesh.vertices)
        self.left_open = []  # (loop, reason) of the boundary loops the library's rule leaves open
        if all_holes or not mesh.vertex_selected.any():
            self.loops, self.left_open = region.every_hole(native.geofair, mesh.vertices, mesh.triangles, obj.name)
        else:
            loops = region.mesh_holes(mesh.triangles, n)
            self.loops = region.choose_holes(loops, n, mesh_io.edge_selection(obj), obj.name)
        # What the shared progress and status read: the boundary vertices stand for the region.
        self.region = types.SimpleNamespace(free=np.zeros(sum(len(loop) for loop in self.loops), dtype=bool))
        self._reset_run()

    @property
    def holes(self):
        return len(self.loops)

    def solve(self):
        """Solve in this thread; the result or the error is kept for :meth:`finish`."""
        options = self.options.library_options()
        options.pop("remesh", None)
        if self.target_edge_length > 0.0:
            options["target_edge_length"] = self.target_edge_length
        if self.clean_rim:
            options["rim"] = "trim"
        loops = [loop.tolist() for loop in self.loops]
        self._solve_with(
            lambda: native.geofair.fill_holes(
                self.mesh.vertices, self.mesh.triangles, loops, progress=self._progress, **options
            )
        )

    def finish(self):
        """Write the fill unless cancelled or discarded; return the :class:`fairing.FairingReport`.

        Raises:
            ValueError, RuntimeError: the solver failed (the mesh is unchanged), or the
                mesh changed under the run.
        """
        if not self.done:
            raise RuntimeError("finish: the run is still going")
        cancelled = self._cancel.is_set()
        if self.error is not None and not cancelled:
            raise self.error
        result = self.result
        if result is None:
            cancelled = True
            result = fairing._NOT_SOLVED
        # Every hole's best fill is written (converged or not: fill_holes tried the others).
        records = region.hole_records(getattr(result, "holes", None) or (), self.mesh.triangle_face)
        if getattr(result, "holes", None) is not None:
            discarded = not cancelled and not any(r["filled"] for r in records)
        else:  # a module without per-hole records: as for fairing
            discarded = not cancelled and not result.converged and not self.options.keep_unconverged
        written = mesh_edit.Written()
        uv_after = None
        if not cancelled and not discarded:
            try:
                unchanged = self.obj.mode == self.mode and mesh_io.vertex_count(self.obj) == len(self.mesh.vertices)
            except ReferenceError:
                unchanged = False
            if not unchanged:
                raise RuntimeError("the mesh changed during the run; result discarded")
            clock = time.perf_counter()
            try:
                written = mesh_edit.add_fill(self.obj, self.mesh, result)
            except carry.CarryError as error:
                raise RuntimeError(str(error)) from error
            self.timings["write"] = time.perf_counter() - clock
            if written.metric_uvs is not None:
                uv_after = fairing.metrics.uv_distortion(
                    written.metric_vertices, written.metric_triangles, written.metric_uvs
                )
        new_vertices = int(np.count_nonzero(np.asarray(getattr(result, "free", []), dtype=bool)))
        return fairing.FairingReport.of_result(
            result,
            self.options,
            object_name=self.object_name,
            free_vertices=new_vertices,
            pinned_vertices=0,
            border_fixed_vertices=0,
            cancelled=cancelled,
            seconds=self.seconds,
            uv_after=uv_after,
            timings=dict(self.timings),
            discarded=discarded,
            remeshed=written.triangles_added > 0,
            triangles_added=written.triangles_added,
            notes=(*written.notes, *([region.left_open_text(self.left_open)] if self.left_open else [])),
            holes=self.holes,
            hole_fills=tuple(records),
            faces_removed=written.faces_removed,
        )


def fill_holes(
    obj, *, all_holes=False, target_edge_length=0.0, clean_rim=False, progress=None, context=None, **options
):
    """Fill holes of a mesh object from a script (Object or Edit Mode): the selected ones, or every hole.

    With nothing selected, or ``all_holes``, every boundary loop is filled but the outer border of each open
    part of the mesh (``geofair.holes_to_fill``'s rule); the report's ``notes`` name the loops left open.

    Args:
        obj: a mesh object.
        all_holes: every hole, whatever is selected (with nothing selected: every hole too).
        target_edge_length: the fill's edge length (object units); 0 or None: that of each hole's boundary.
        clean_rim: let the library remove the faces of a ragged rim first where the fill of the
            hole as it is folds or does not converge (the report's ``hole_fills`` name them).
        progress: optional ``callable(iteration, residual)``; returning False cancels.
        context: ``bpy.context`` by default (its scene's panel settings are the defaults).
        **options: ``geofair.fill_holes``'s fairing options (``inner_fairness``, ``boundary``,
            ``normal_weighting``, ``tolerance``, ``time_limit``, ``tuning``, ...); ``keep_unconverged`` is
            accepted and not read (every hole's best fill is written).

    Returns:
        :class:`fairing.FairingReport` (``holes``, ``hole_fills`` what each hole got,
        ``free_vertices`` the new vertices, ``triangles_added``, ``faces_removed``, ``notes``).
        Every hole gets its best fill, converged or not (``converged`` says whether all did).

    Raises:
        TypeError: an unknown option.
        ValueError: no hole to fill (none, or only outer borders; :class:`region.RegionError`), bad input.
        fairing.NotConvergedError: no hole could be filled (mesh unchanged).
        RuntimeError: the solver failed, or the compiled module is missing.
    """
    import bpy

    context = context or bpy.context
    if "rim" in options:  # geofair.fill_holes' keyword: the add-on's is the Clean Rim option's
        raise TypeError("fill_holes: unknown option 'rim'; pass clean_rim=True for geofair's rim='trim'")
    names = (*properties.LIBRARY_OPTION_NAMES, *properties.SCRIPT_OPTION_NAMES)
    fairing.check_option_names("fill_holes", options, names)
    run_options = fairing.default_options(context, **options)
    run = FillRun(
        obj,
        run_options,
        all_holes=all_holes,
        target_edge_length=target_edge_length,
        progress=progress,
        clean_rim=clean_rim,
    )
    run.solve()
    report = run.finish()
    if report.discarded:
        raise fairing.NotConvergedError(report, "No hole could be filled; the report's hole_fills say why.")
    return report
