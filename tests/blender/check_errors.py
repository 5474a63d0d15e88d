"""Check bad input and solver failures of the Geometric Fairing operator; raises (non-zero exit) on failure.

Runs in Blender 3.4+ and in the ``bpy`` module from PyPI (see dev/geofair_dev/blender.py).

- Bad input, each with its exact report, ``{'CANCELLED'}`` and the mesh (positions,
  UVs, selection) byte-identical: nothing selected; only vertices; only edges; the
  whole closed mesh selected; a whole closed part (a sphere beside a grid) selected.
- An unconverged solve (Max Iterations 1): ``{'CANCELLED'}`` with the residual and the
  tolerance in the error, the mesh byte-identical and no undo step; with *Keep Unconverged
  Result* ticked the mesh changes and a warning gives the residual. ``fair_object`` raises
  ``NotConvergedError`` unless ``keep_unconverged=True``.
- A converged result that flips triangles over (the count simulated by a module whose
  ``fair`` reports it): written, with a warning, and the count in the panel's figures.
- A failure inside the compiled solver, simulated by replacing the loaded module's
  ``fair`` with one that raises (RuntimeError, ValueError, and an unexpected
  MemoryError), and a real one (a NaN vertex that the native code rejects): the
  operator reports it and cancels, the mesh is unchanged, Edit Mode still works,
  the next run succeeds, and undo/redo return exactly to the states before and after
  it (the failed run added no undo step).
"""

import contextlib
import ctypes
import os
import re
import sys
import tempfile
import types

import bpy  # first: the bpy module from PyPI makes bmesh importable

# isort: split
import bmesh
import numpy as np

from geofair_dev.blender import (
    FailingModule,
    add_subdivided_suzanne,
    disable_addon,
    edit_state,
    enable_addon,
    parse_args,
    run_fairing,
    select_faces,
)

BROW = np.array([0.4, -0.7, 0.72])
NOTHING = "Error: Geometric Fairing: No face is selected: select the faces to fair"
ONLY_VERTICES_OR_EDGES = (
    "Error: Geometric Fairing: No face is selected, only vertices or edges: select the faces to fair "
    "(in Face Select mode, or all vertices of each face)"
)
WHOLE_MESH = (
    "Error: Geometric Fairing: The whole mesh is selected and it has no open border: fairing needs "
    "unselected faces around the selection to hold it in place"
)
WHOLE_PART = (
    "Error: Geometric Fairing: The selection covers a whole closed part of the mesh: fairing needs "
    "unselected faces around the selection"
)


def expect(obj, what, expected, **properties):
    """The operator cancels with exactly ``expected`` and leaves ``obj`` byte-identical."""
    before = edit_state(obj)
    result, error = run_fairing(**properties)
    assert result == {"CANCELLED"}, f"{what}: expected CANCELLED, got {result}"
    assert error == expected, f"{what}: report\n  {error!r}\nexpected\n  {expected!r}"
    assert edit_state(obj) == before, f"{what}: the mesh changed"
    last = bpy.context.window_manager.geometric_fairing.last_run
    assert last.status == "ERROR" and f"Error: Geometric Fairing: {last.message}" == expected, last.message
    print(f"ok: {what} -> CANCELLED, mesh unchanged: {error}")


def select_elements(obj, mode, indices):
    """Select exactly the vertices or edges ``indices`` in select mode ``mode`` ('VERT' or 'EDGE')."""
    bpy.context.tool_settings.mesh_select_mode = (mode == "VERT", mode == "EDGE", False)
    bm = bmesh.from_edit_mesh(obj.data)
    for element in (*bm.verts, *bm.edges, *bm.faces):
        element.select = False
    elements = bm.verts if mode == "VERT" else bm.edges
    elements.ensure_lookup_table()
    for i in indices:
        elements[i].select_set(True)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)
    assert not any(f.select for f in bm.faces), "the chosen elements select a face"
    assert sum(e.select for e in elements) == len(indices)


def check_bad_selections(obj):
    select_faces(obj, lambda c: False)
    expect(obj, "nothing selected", NOTHING)

    bm = bmesh.from_edit_mesh(obj.data)
    far_apart = [0, len(bm.verts) // 2, len(bm.verts) - 1]
    select_elements(obj, "VERT", far_apart)
    expect(obj, "only vertices selected", ONLY_VERTICES_OR_EDGES)
    # Edges in a row along one face loop: a chain of edges selects no face.
    bm.edges.ensure_lookup_table()
    start = bm.edges[100]
    chain = [start.index, start.link_loops[0].link_loop_next.edge.index]
    select_elements(obj, "EDGE", chain)
    expect(obj, "only edges selected", ONLY_VERTICES_OR_EDGES)
    # Vertices of faces selected in Vertex Select mode do select the faces: that is a face selection.
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)

    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, location=(4, 0, 0))
    sphere = bpy.context.active_object
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(sphere, lambda c: True)
    expect(sphere, "the whole closed mesh selected", WHOLE_MESH)

    # A grid and the sphere in one mesh, all selected: the sphere is a closed part with no boundary.
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=10, y_subdivisions=10, size=2, location=(4, 0, -2))
    bpy.context.view_layer.objects.active = sphere
    sphere.select_set(True)
    bpy.ops.object.join()
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(sphere, lambda c: True)
    expect(sphere, "a whole closed part selected", WHOLE_PART)
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.data.objects.remove(sphere)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bpy.ops.object.mode_set(mode="EDIT")


def edit_mode_works(obj):
    """Edit Mode is usable after an error: selecting, the BMesh, and leaving and entering it again."""
    assert obj.mode == "EDIT" and bpy.context.active_object == obj
    co = edit_state(obj)["co"]
    assert bpy.ops.mesh.select_all(action="SELECT") == {"FINISHED"}
    assert all(f.select for f in bmesh.from_edit_mesh(obj.data).faces)
    assert bpy.ops.mesh.select_all(action="DESELECT") == {"FINISHED"}
    bm = bmesh.from_edit_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    assert len(bm.verts) == len(obj.data.vertices) and not any(f.select for f in bm.faces)
    assert bpy.ops.object.mode_set(mode="OBJECT") == {"FINISHED"}
    assert bpy.ops.object.mode_set(mode="EDIT") == {"FINISHED"} and obj.mode == "EDIT"
    assert edit_state(obj)["co"] == co


def check_solver_failure(addon, obj, error, expected):
    """A solver that raises ``error``: a clean report, mesh and undo history untouched, the next run works."""
    select_faces(obj, lambda c: np.linalg.norm(c - BROW) < 0.25)
    bpy.ops.ed.undo_push(message="selected the brow")
    before = edit_state(obj)

    real = addon.native.geofair
    failing = addon.native.geofair = FailingModule(real, error)
    try:
        result, report = run_fairing(inner_fairness="conformal")
    finally:
        addon.native.geofair = real
    assert failing.calls == 1, "the solver was not called"
    assert result == {"CANCELLED"} and report == expected, (result, report)
    assert edit_state(obj) == before, "a failed solve changed the mesh"
    last = bpy.context.window_manager.geometric_fairing.last_run
    assert last.status == "ERROR" and last.object_name == obj.name, (last.status, last.object_name)
    assert addon.operators.running() is None
    print(f"ok: solver raising {type(error).__name__} -> CANCELLED, mesh unchanged: {report}")

    edit_mode_works(obj)
    select_faces(obj, lambda c: np.linalg.norm(c - BROW) < 0.25)
    bpy.ops.ed.undo_push(message="selected the brow again")
    assert edit_state(obj) == before
    print("ok: Edit Mode works after the error (select all/none, BMesh, leaving and entering)")

    # The failed run added no undo step: one undo after a successful run goes back to the state before it.
    result, report = run_fairing(inner_fairness="conformal")
    assert result == {"FINISHED"}, report
    after = edit_state(obj)
    assert after["co"] != before["co"], "the run after the error changed nothing"
    bpy.ops.ed.undo()
    assert edit_state(obj) == before, "undo did not return exactly to the state before the run"
    bpy.ops.ed.redo()
    assert edit_state(obj) == after, "redo did not return exactly to the faired mesh"
    bpy.ops.ed.undo()
    assert edit_state(obj) == before
    print("ok: the next run succeeds; undo and redo return exactly to the states before and after it")

    # An error right after a successful run: the mesh stays as faired, and undo then goes back past the run.
    result, report = run_fairing(inner_fairness="conformal")
    assert result == {"FINISHED"} and edit_state(obj)["co"] == after["co"], report
    failing = addon.native.geofair = FailingModule(real, error)
    try:
        result, report = run_fairing(inner_fairness="conformal")
    finally:
        addon.native.geofair = real
    assert result == {"CANCELLED"} and report == expected and edit_state(obj)["co"] == after["co"]
    bpy.ops.ed.undo()
    assert edit_state(obj) == before, "undo after the error did not return exactly to the state before the last run"
    print("ok: an error after a run leaves the faired mesh; undo returns exactly to the state before that run")


UNCONVERGED = re.compile(
    r"Error: Geometric Fairing: Fairing did not converge \(residual (\d(\.\d)?(e-?\d+)?), tolerance 1e-4\): the mesh "
    r"is unchanged\. Remesh 'If Needed' may help \(it changes the triangles\)\. Tick 'Keep Unconverged Result' to "
    r"apply it anyway\."
)


@contextlib.contextmanager
def printed():
    """Collect what is printed to the standard output (also by Blender's C code: its reports) in a ``with`` block.

    In background mode an operator's WARNING or INFO report is only printed ("Warning: ..."); yields a list
    that holds the text once the block ends.
    """
    libc = ctypes.CDLL(None)
    text = []
    sys.stdout.flush()
    libc.fflush(None)
    saved = os.dup(1)
    with tempfile.TemporaryFile() as file:
        os.dup2(file.fileno(), 1)
        try:
            yield text
        finally:
            sys.stdout.flush()
            libc.fflush(None)
            os.dup2(saved, 1)
            os.close(saved)
            file.seek(0)
            text.append(file.read().decode())
            print(text[0], end="")


def check_unconverged(addon, obj):
    """Max Iterations 1 stops unconverged: CANCELLED with the residual, mesh and undo history untouched."""
    select_faces(obj, lambda c: np.linalg.norm(c - BROW) < 0.25)
    bpy.ops.ed.undo_push(message="selected the brow (unconverged)")
    before = edit_state(obj)
    result, report = run_fairing(inner_fairness="conformal", max_iterations=1)
    match = UNCONVERGED.fullmatch(report)
    assert result == {"CANCELLED"} and match, (result, report)
    assert edit_state(obj) == before, "an unconverged run changed the mesh"
    last = bpy.context.window_manager.geometric_fairing.last_run
    assert last.status == "NOT_CONVERGED" and last.iterations >= 1, (last.status, last.iterations)
    assert f"Error: Geometric Fairing: {last.message}" == report, last.message
    assert abs(float(match.group(1)) / last.residual - 1) < 0.06 and last.residual > 1e-4, last.residual
    print(f"ok: an unconverged solve -> CANCELLED, mesh unchanged: {report}")

    # No undo step: after a run and an unconverged one, one undo goes back to the state before the run.
    result, report = run_fairing(inner_fairness="conformal")
    assert result == {"FINISHED"}, report
    after = edit_state(obj)
    assert after["co"] != before["co"]
    result, report = run_fairing(inner_fairness="conformal", max_iterations=1)
    assert result == {"CANCELLED"} and UNCONVERGED.fullmatch(report) and edit_state(obj) == after, report
    bpy.ops.ed.undo()
    assert edit_state(obj) == before, "undo after the unconverged run did not go back past the run before it"
    print("ok: the unconverged run added no undo step")

    # After an unconverged uniform run the report points to conformal inner fairness.
    result, report = run_fairing(inner_fairness="uniform", max_iterations=1)
    assert result == {"CANCELLED"} and edit_state(obj) == before, (result, report)
    assert report.endswith(
        "the mesh is unchanged. Conformal inner fairness converges on more meshes. Remesh 'If Needed' may help (it "
        "changes the triangles). Tick 'Keep Unconverged Result' to apply it anyway."
    ), report

    # Stopped at the Time Limit the user gave: the report points to a longer one, not to another setting.
    result, report = run_fairing(inner_fairness="uniform", time_limit=1e-6)
    assert result == {"CANCELLED"} and edit_state(obj) == before, (result, report)
    assert bpy.context.window_manager.geometric_fairing.last_run.status == "NOT_CONVERGED"
    assert report.endswith(
        "the mesh is unchanged. A longer Time Limit (0: automatic) lets it go on. Tick 'Keep Unconverged Result' to "
        "apply it anyway."
    ), report

    # Keep Unconverged Result: written, with a warning that gives the residual.
    with printed() as output:
        result, report = run_fairing(inner_fairness="conformal", max_iterations=1, keep_unconverged=True)
    assert result == {"FINISHED"} and report == "", (result, report)
    kept = edit_state(obj)
    assert kept["co"] != before["co"] and kept["co"] != after["co"], "the kept result is not the unconverged one"
    assert {k: v for k, v in kept.items() if k != "co"} == {k: v for k, v in before.items() if k != "co"}
    last = bpy.context.window_manager.geometric_fairing.last_run
    assert last.status == "NOT_CONVERGED" and "NOT converged, result kept" in last.message, last.message
    residual = addon.fairing.short_number(last.residual)
    expected = (
        f"Warning: Geometric Fairing: did not converge (residual {residual}, tolerance 1e-4), unconverged result "
        f"kept: {last.message}"
    )
    assert expected in output[0].splitlines(), (expected, output)
    print(f"ok: Keep Unconverged Result -> FINISHED, mesh changed, warning: {expected}")
    bpy.ops.ed.undo()
    assert edit_state(obj) == before
    rna = bpy.ops.mesh.geometric_fairing.get_rna_type().properties["keep_unconverged"]
    assert rna.name == "Keep Unconverged Result" and rna.default is False, (rna.name, rna.default)


class FoldingModule:
    """Stands in for the loaded ``geofair`` module: the real ``fair``, its result reporting ``folds`` flipped edges."""

    def __init__(self, real, folds):
        self.real, self.folds = real, folds

    def fair(self, *args, **kwargs):
        return FoldedResult(self.real.fair(*args, **kwargs), self.folds)

    def __getattr__(self, name):
        return getattr(self.real, name)


class FoldedResult:
    """A ``geofair.FairingResult`` whose ``folds`` and ``new_folds`` read ``folds``."""

    def __init__(self, result, folds):
        self.result, self.folds, self.new_folds = result, folds, folds

    def __getattr__(self, name):
        return getattr(self.result, name)


def check_converged_with_folds(addon, obj):
    """A converged result that flips triangles over is written, with a warning and the count in the panel."""
    select_faces(obj, lambda c: np.linalg.norm(c - BROW) < 0.25)
    bpy.ops.ed.undo_push(message="selected the brow (folds)")
    before = edit_state(obj)
    result, report = run_fairing(inner_fairness="conformal")
    last = bpy.context.window_manager.geometric_fairing.last_run
    assert result == {"FINISHED"} and last.status == "CONVERGED" and last.folds == 0, (result, report)
    assert "folded" not in last.message, last.message
    bpy.ops.ed.undo()
    assert edit_state(obj) == before

    real = addon.native.geofair
    addon.native.geofair = FoldingModule(real, 3)
    try:
        with printed() as output:
            result, report = run_fairing(inner_fairness="conformal")
    finally:
        addon.native.geofair = real
    assert result == {"FINISHED"} and report == "", (result, report)
    assert edit_state(obj)["co"] != before["co"], "the converged result was not written"
    assert last.status == "CONVERGED" and last.folds == 3, (last.status, last.folds)
    assert last.message.endswith(", converged, but 3 edges folded over (triangles flipped)"), last.message
    expected = f"Warning: Geometric Fairing: {last.message}"
    assert expected in output[0].splitlines(), (expected, output)
    print(f"ok: a converged result with folds -> FINISHED, written, warning: {expected}")
    bpy.ops.ed.undo()
    assert edit_state(obj) == before


def check_fair_object_unconverged(addon, obj):
    """fair_object raises NotConvergedError (mesh unchanged) unless keep_unconverged=True."""
    bpy.ops.object.mode_set(mode="OBJECT")
    co = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    try:
        addon.fair_object(obj, inner_fairness="conformal", max_iterations=1)
    except addon.NotConvergedError as error:
        assert isinstance(error, RuntimeError) and error.report.discarded and not error.report.changed
        assert str(error).startswith("Fairing did not converge (residual ") and str(error).endswith(
            "tolerance 1e-4): the mesh is unchanged. Passing remesh='if_needed' may help (it changes the triangles). "
            "Pass keep_unconverged=True to apply it anyway."
        ), error
    else:
        raise AssertionError("fair_object did not raise NotConvergedError")
    try:
        addon.fair_object(obj, inner_fairness="uniform", max_iterations=1)
    except addon.NotConvergedError as error:
        assert str(error).endswith(
            "the mesh is unchanged. Conformal inner fairness converges on more meshes. Passing remesh='if_needed' may "
            "help (it changes the triangles). Pass keep_unconverged=True to apply it anyway."
        ), error
    else:
        raise AssertionError("fair_object did not raise NotConvergedError")
    try:
        addon.fair_object(obj, inner_fairness="uniform", time_limit=1e-6)
    except addon.NotConvergedError as error:
        assert error.report.stop_reason == "time_limit", error.report.stop_reason
        assert str(error).endswith(
            "the mesh is unchanged. A longer time_limit (None: automatic) lets it go on. Pass keep_unconverged=True "
            "to apply it anyway."
        ), error
    else:
        raise AssertionError("fair_object did not raise NotConvergedError")
    after = np.empty_like(co)
    obj.data.vertices.foreach_get("co", after)
    assert after.tobytes() == co.tobytes()
    assert bpy.context.window_manager.geometric_fairing.last_run.status == "NOT_CONVERGED"
    report = addon.fair_object(obj, inner_fairness="conformal", max_iterations=1, keep_unconverged=True)
    assert not report.converged and report.changed, report
    obj.data.vertices.foreach_get("co", after)
    assert after.tobytes() != co.tobytes()
    obj.data.vertices.foreach_set("co", co)
    obj.data.update()
    print("ok: fair_object raises NotConvergedError, mesh unchanged; keep_unconverged=True writes the result")
    bpy.ops.object.mode_set(mode="EDIT")


def check_native_rejects(obj):
    """A real rejection by the compiled module: a free vertex whose position is NaN."""
    select_faces(obj, lambda c: np.linalg.norm(c - BROW) < 0.25)
    bm = bmesh.from_edit_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    inner = [v for v in bm.verts if v.link_faces and all(f.select for f in v.link_faces)]
    inner.sort(key=lambda v: np.linalg.norm(np.array(v.co) - BROW))  # the middle of the region
    vertex = inner[0].index
    original = inner[0].co.copy()
    inner[0].co = (float("nan"), 0.0, 0.0)
    bmesh.update_edit_mesh(obj.data, loop_triangles=True, destructive=False)
    bpy.ops.ed.undo_push(message="a NaN vertex")
    before = edit_state(obj)
    result, report = run_fairing(inner_fairness="conformal")
    assert result == {"CANCELLED"}, result
    assert report == f"Error: Geometric Fairing: fair: vertex {vertex} has a non-finite coordinate", report
    assert edit_state(obj) == before, "a rejected run changed the mesh"
    print(f"ok: the compiled module rejects a NaN vertex -> CANCELLED, mesh unchanged: {report}")
    bm = bmesh.from_edit_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    bm.verts[vertex].co = original
    bmesh.update_edit_mesh(obj.data, loop_triangles=True, destructive=False)
    bpy.ops.ed.undo_push(message="repaired the vertex")
    result, report = run_fairing(inner_fairness="conformal")
    assert result == {"FINISHED"}, report
    bpy.ops.ed.undo()
    print("ok: after repairing the vertex the run succeeds")


def check_fair_object_failure(addon, obj):
    """fair_object raises the solver's error and leaves the mesh unchanged (Object Mode)."""
    bpy.ops.object.mode_set(mode="OBJECT")
    co = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    real = addon.native.geofair
    addon.native.geofair = FailingModule(real, RuntimeError("fair: simulated failure"))
    try:
        addon.fair_object(obj)
    except RuntimeError as error:
        hint = "Passing remesh='if_needed' may help (it changes the triangles)."
        assert str(error) == f"fair: simulated failure {hint}", error
    else:
        raise AssertionError("fair_object did not raise")
    finally:
        addon.native.geofair = real
    after = np.empty_like(co)
    obj.data.vertices.foreach_get("co", after)
    assert after.tobytes() == co.tobytes()
    assert bpy.context.window_manager.geometric_fairing.last_run.status == "ERROR"
    report = addon.fair_object(obj, inner_fairness="conformal")
    assert report.converged
    print("ok: fair_object re-raises the solver's error, mesh unchanged; the next call works")
    bpy.ops.object.mode_set(mode="EDIT")


def main():
    folder, _ = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon = enable_addon(folder)
    obj = add_subdivided_suzanne()
    bpy.ops.object.mode_set(mode="EDIT")
    check_bad_selections(obj)
    check_unconverged(addon, obj)
    check_converged_with_folds(addon, obj)
    check_solver_failure(
        addon,
        obj,
        RuntimeError("fair: diverged (simulated)"),
        "Error: Geometric Fairing: fair: diverged (simulated) Remesh 'If Needed' may help (it changes the triangles).",
    )
    check_solver_failure(
        addon, obj, ValueError("fair: rejected (simulated)"), "Error: Geometric Fairing: fair: rejected (simulated)"
    )
    check_solver_failure(addon, obj, MemoryError("simulated"), "Error: Geometric Fairing: MemoryError: simulated")
    check_native_rejects(obj)
    check_fair_object_failure(addon, obj)
    check_fair_object_unconverged(addon, obj)
    assert isinstance(addon.native.geofair, types.ModuleType)
    disable_addon()
    print("check_errors: all checks passed")


main()
