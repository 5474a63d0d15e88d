"""Check the modal Geometric Fairing operator in a real Blender window: progress, Esc cancels, a run finishes.

Needs a display (Xvfb) and Blender's event simulation, which replaces real input by
``Window.event_simulate``:

    xvfb-run -a -s "-screen 0 1280x800x24" blender --factory-startup --enable-event-simulate \\
        --python tests/blender/check_modal.py -- build/addon

Steps run from timers while Blender's event loop runs; the script ends Blender with
exit status 0 when every check passed and 1 otherwise (a timer cannot use
--python-exit-code).
"""

import sys
import traceback

import bpy

# isort: split
import numpy as np

from geofair_dev.blender import (
    FailingModule,
    TimerSteps,
    add_subdivided_suzanne,
    enable_addon,
    finish,
    parse_args,
    positions,
    select_faces,
    wait_until,
    window_view3d,
)

BROW = np.array([0.4, -0.7, 0.72])


def invoke_fairing(**properties):
    """Invoke the operator as the Fair button does (INVOKE_DEFAULT in the 3D View)."""
    window, area, region = window_view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        return bpy.ops.mesh.geometric_fairing("INVOKE_DEFAULT", **properties)


def press(event_type):
    """Simulate a key press and release over the 3D View."""
    window, area, region = window_view3d()
    x, y = region.x + region.width // 2, region.y + region.height // 2
    window.event_simulate(type=event_type, value="PRESS", x=x, y=y)
    window.event_simulate(type=event_type, value="RELEASE", x=x, y=y)


def checks(addon, obj):
    last = bpy.context.window_manager.geometric_fairing.last_run
    operators = addon.operators
    yield 0.5  # let the window draw once

    # A run that would take minutes: Esc cancels it, the mesh stays as it was.
    before = positions(obj)
    result = invoke_fairing(inner_fairness="conformal", tolerance=1e-15, max_iterations=10**7)
    assert result == {"RUNNING_MODAL"}, result
    run = operators.running()
    assert run is not None, "no run is going"
    yield from wait_until(lambda: run.iteration > 0, "the first iterations")
    yield 0.3
    assert not run.done and np.array_equal(positions(obj), before), "the mesh changed while solving"
    iterations = run.iteration
    print(f"ok: modal run going, iteration {iterations}, residual {run.residual:.3g}; pressing Esc")
    press("ESC")
    yield from wait_until(lambda: operators.running() is None, "the run to stop after Esc")
    assert run.cancel_requested and last.status == "CANCELLED", last.status
    assert np.array_equal(positions(obj), before), "Esc left the mesh changed"
    print(f"ok: Esc cancelled the run after {last.iterations} iterations; mesh unchanged ({last.message})")

    # The same through the plain function (what a script driving the UI can call).
    assert invoke_fairing(inner_fairness="conformal", tolerance=1e-15, max_iterations=10**7) == {"RUNNING_MODAL"}
    yield from wait_until(lambda: operators.running().iteration > 0, "the first iterations")
    assert operators.cancel_running()
    yield from wait_until(lambda: operators.running() is None, "the run to stop after cancel_running()")
    assert last.status == "CANCELLED" and np.array_equal(positions(obj), before)
    assert not operators.cancel_running()
    print("ok: cancel_running() cancelled the run; mesh unchanged")

    # A run to the end writes the mesh, with one undo step.
    assert invoke_fairing(inner_fairness="conformal") == {"RUNNING_MODAL"}
    yield from wait_until(lambda: operators.running() is None, "the run to finish")
    assert last.status == "CONVERGED", (last.status, last.message)
    after = positions(obj)
    assert np.any(after != before), "a finished run did not change the mesh"
    print(f"ok: modal run finished: {last.message}")
    window, area, region = window_view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.ed.undo()
    assert np.array_equal(positions(obj), before), "undo did not restore the mesh"
    print("ok: undo restored the mesh")

    # The solver fails in the worker thread (simulated): a clean error, the mesh as it was, no
    # run left behind, and the next run works. Only here: the bpy module has no window for
    # the modal path (it runs the operator's execute, checked in check_errors.py).
    real = addon.native.geofair
    addon.native.geofair = FailingModule(real, RuntimeError("fair: the iteration diverged (simulated)"))
    try:
        assert invoke_fairing(inner_fairness="conformal") == {"RUNNING_MODAL"}
        yield from wait_until(lambda: operators.running() is None, "the failing run to end")
    finally:
        addon.native.geofair = real
    expected = "fair: the iteration diverged (simulated) Remesh 'If Needed' may help (it changes the triangles)."
    assert last.status == "ERROR" and last.message == expected, last.message
    assert np.array_equal(positions(obj), before), "a failed modal run changed the mesh"
    assert obj.mode == "EDIT"
    print(f"ok: a solver error in the modal run -> {last.status}: {last.message}; mesh unchanged")
    assert invoke_fairing(inner_fairness="conformal") == {"RUNNING_MODAL"}
    yield from wait_until(lambda: operators.running() is None, "the run after the error to finish")
    assert last.status == "CONVERGED" and np.array_equal(positions(obj), after), last.message
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.ed.undo()
    assert np.array_equal(positions(obj), before), "undo after the error did not restore the mesh"
    print("ok: the next modal run works, and undo restores the mesh exactly")

    # Fill Holes runs the same way: Suzanne's holes (around the eyes) filled in the worker thread;
    # Esc cancels a long one, a run to the end adds one undo step.
    obj.update_from_editmode()
    faces = len(obj.data.polygons)
    with bpy.context.temp_override(window=window, area=area, region=region):
        result = bpy.ops.mesh.geometric_fairing_fill_holes(
            "INVOKE_DEFAULT", all_holes=True, tolerance=1e-15, max_iterations=10**7, iteration="paper"
        )
    assert result == {"RUNNING_MODAL"}, result
    run = operators.running()
    yield from wait_until(lambda: run.iteration > 0, "the fill's first iterations")
    press("ESC")
    yield from wait_until(lambda: operators.running() is None, "the fill to stop after Esc")
    obj.update_from_editmode()
    assert last.status == "CANCELLED" and len(obj.data.polygons) == faces, (last.status, last.message)
    assert np.array_equal(positions(obj), before), "Esc left the fill in the mesh"
    print(f"ok: Esc cancelled Fill Holes; mesh unchanged ({last.message})")
    with bpy.context.temp_override(window=window, area=area, region=region):
        assert bpy.ops.mesh.geometric_fairing_fill_holes("INVOKE_DEFAULT", all_holes=True) == {"RUNNING_MODAL"}
    yield from wait_until(lambda: operators.running() is None, "the fill to finish")
    assert last.status == "CONVERGED", (last.status, last.message)
    obj.update_from_editmode()
    assert len(obj.data.polygons) > faces, "Fill Holes added no face"
    print(f"ok: modal Fill Holes: {last.message}")
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.ed.undo()
    obj.update_from_editmode()
    assert len(obj.data.polygons) == faces and np.array_equal(positions(obj), before), "undo did not remove the fill"
    print("ok: undo removed the fill")
    print("check_modal: all checks passed")


def main():
    folder, _ = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    assert not bpy.app.background, "check_modal needs a window (run it under xvfb-run without --background)"
    addon = enable_addon(folder)
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    obj = add_subdivided_suzanne()
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(obj, lambda c: np.linalg.norm(c - BROW) < 0.25)
    bpy.ops.ed.undo_push(message="selected the brow")
    bpy.app.timers.register(TimerSteps(checks(addon, obj), "check_modal"), first_interval=0.5)


try:
    main()
except Exception:
    traceback.print_exc()
    finish(1)
