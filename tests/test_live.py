"""geofair.LiveFairing: a region prepared once and faired again as its fixed vertices move
(a handle dragged through the surface; Schneider & Kobbelt 2001, section 8). Each frame is
the surface of a cold geofair.fair of the same input; a handle dragged along a sphere keeps
the sphere; a failed frame or bad input leaves the last converged frame."""

import re

import numpy as np
import pytest

import geofair
from geofair_dev import scenes


def rotation_x(degrees):
    a = np.radians(degrees)
    return np.array([[1.0, 0.0, 0.0], [0.0, np.cos(a), -np.sin(a)], [0.0, np.sin(a), np.cos(a)]])


@pytest.fixture(scope="module")
def handle_scene():
    """An irregular unit sphere (3,000 vertices): the handle is the 8° cap around +z, the
    region the 50° cap around it (about 520 free vertices), the rest of the sphere fixed."""
    s = scenes.sphere(n_vertices=3000, irregular=True, seed=1)
    polar = np.degrees(np.arccos(np.clip(s.vertices[:, 2], -1.0, 1.0)))
    handle = polar < 8.0
    free = (polar < 50.0) & ~handle
    return s.vertices, s.faces, free, handle


def region_diagonal(vertices, faces, free):
    """The bounding-box diagonal of the free vertices and their neighbours (fair's L)."""
    used = np.unique(faces[free[faces].any(axis=1)])
    p = vertices[used]
    return float(np.linalg.norm(p.max(axis=0) - p.min(axis=0)))


def lifted(vertices, handle, lift):
    w = vertices.copy()
    w[handle, 2] += lift
    return w


def check_frame(result, w, free):
    assert np.all(np.isfinite(result.vertices))
    assert np.array_equal(result.vertices[~free], w[~free])


@pytest.mark.parametrize("inner", ["uniform", "conformal"])
def test_update_is_the_cold_fair_of_its_input(handle_scene, inner):
    # The handle pulled out along +z in steps of about an edge length: every frame warm
    # (no cold path), and the last one the surface of a cold fair of the same input within
    # the tolerance (positions in units of the region's diameter L).
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free, inner_fairness=inner)
    assert live.result.converged and live.frames == 0
    for k in range(1, 6):
        w = lifted(v, handle, 0.04 * k)
        r = live.update(w)
        check_frame(r, w, free)
        assert r.converged and "cold path" not in r.message, r.message
    assert live.frames == 5 and live.cold_frames == 0
    assert r is not live.result and np.array_equal(r.vertices, live.result.vertices)
    cold = geofair.fair(w, f, free, inner_fairness=inner)
    assert cold.converged
    L = region_diagonal(w, f, free)
    assert np.abs(r.vertices - cold.vertices).max() <= 1e-4 * L
    # The surface moved with the handle: the free vertices next to it rose.
    assert r.vertices[free, 2].max() > v[free, 2].max() + 0.1
    held = live.result  # a copy: the next frame does not change it
    live.update(lifted(v, handle, 0.24))
    assert np.array_equal(held.vertices, r.vertices)
    assert not np.array_equal(live.result.vertices, r.vertices)


def test_update_of_free_rows_is_not_read(handle_scene):
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free)
    w = lifted(v, handle, 0.04)
    a = live.update(w)
    live = geofair.LiveFairing(v, f, free)
    w_nan = w.copy()
    w_nan[free] = np.nan
    b = live.update(w_nan)
    assert np.array_equal(a.vertices, b.vertices)


def test_drag_along_the_sphere_keeps_the_sphere(handle_scene):
    # Rotations about the centre: the sphere solves Δ_B H = 0 with the handle's positions and
    # its (turned) tangent planes, so every frame lies on it up to the discretization error.
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free)
    for k in range(1, 9):  # 2° per frame, 16° in all: the handle moves about an edge a frame
        w = v.copy()
        w[handle] = v[handle] @ rotation_x(2.0 * k).T
        r = live.update(w)
        check_frame(r, w, free)
        assert r.converged and r.folds == 0, r.message
        # A steady rotation repeats in the span of the last two frames' moves: from the third
        # frame on the secant start is that close (two steps each from the last frame's alone).
        assert k < 3 or r.newton_iterations <= 1, (k, r.message)
        radial = np.abs(np.linalg.norm(r.vertices[free], axis=1) - 1.0).max()
        assert radial < 1e-4, (k, radial)
    assert live.cold_frames == 0
    # The handle's neighbourhood moved with it (not left where it was).
    assert np.abs(r.vertices[free] - v[free]).max() > 0.1


def test_steady_translation_takes_one_step_a_frame(handle_scene):
    # A translation moves the handle along a line: the secant start interpolates the free
    # vertices' response quadratically through the last three frames, one Newton step a
    # frame from the third frame on (two from the last frame's response alone). A step back
    # is the frame before, exactly: no step.
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free)
    frames = []
    for k in range(1, 9):  # 0.02 a frame, about a third of an edge
        w = lifted(v, handle, 0.02 * k)
        r = live.update(w)
        check_frame(r, w, free)
        assert r.converged and "cold path" not in r.message, r.message
        assert k < 3 or (r.newton_iterations <= 1 and "harmonic" not in r.message), (k, r.message)
        frames.append(r)
    cold = geofair.fair(w, f, free)
    assert cold.converged
    L = region_diagonal(w, f, free)
    assert np.abs(r.vertices - cold.vertices).max() <= 1e-4 * L
    back = live.update(lifted(v, handle, 0.02 * 7))
    assert back.converged and back.newton_iterations == 0, back.message
    assert np.abs(back.vertices - frames[-2].vertices).max() <= 1e-4 * L


def test_drag_past_the_triangles_remeshes_and_keeps_the_sphere(handle_scene):
    # 30° along the sphere, 2° a frame: the triangles between the handle and the region's
    # border squeeze until the warm start folds or fails (about 20°); with remesh="if_needed"
    # the region is remeshed from the last frame's surface once its smallest angle has
    # fallen to a third (or a frame folds or fails) and the drag goes on, every frame on the sphere
    # without a folded edge. The fixed vertices keep their rows.
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free, remesh="if_needed")
    fixed = ~free
    warm_remeshes = degenerated = 0
    for k in range(1, 16):
        w = v.copy()
        w[handle] = v[handle] @ rotation_x(2.0 * k).T
        r = live.update(w)
        assert r.converged and r.folds == 0, (k, r.message)
        assert np.array_equal(r.vertices[: len(v)][fixed], w[fixed])
        radial = np.abs(np.linalg.norm(r.vertices[r.free], axis=1) - 1.0).max()
        assert radial < 1e-4, (k, radial)
        if r.remeshed:
            # Solved warm on the remesh (or by the cold fair of a remesh where that fails):
            # the surface of a cold fair of the same mesh and fixed positions.
            warm_remeshes += "solved warm on the new mesh" in r.message
            degenerated += "triangles degenerated" in r.message
            cold = geofair.fair(r.vertices, r.faces, r.free)
            assert cold.converged and np.abs(cold.vertices - r.vertices).max() < 1e-5, (k, r.message)
    assert live.remeshes >= 1 and live.frames == 15 and warm_remeshes >= 1 and degenerated >= 1
    assert not (r.faces.shape == f.shape and np.array_equal(r.faces, f))
    # The remeshed mesh: its free vertices are the region's (none of the fixed rows), every
    # face of the input without a free vertex is kept, and the rows in no face are listed.
    assert not np.any(r.free[: len(v)] & fixed)
    outside = f[~free[f].any(axis=1)]
    assert {tuple(t) for t in outside} <= {tuple(t) for t in r.faces}
    in_faces = np.zeros(len(r.vertices), dtype=bool)
    in_faces[r.faces] = True
    assert np.array_equal(np.sort(r.unreferenced), np.flatnonzero(~in_faces))
    # The same frame again, its free rows NaN (the caller's free rows are not read, also
    # where the remesh left them in no face): the same surface, every row finite.
    w_nan = w.copy()
    w_nan[free] = np.nan
    again = live.update(w_nan)
    assert again.converged and np.all(np.isfinite(again.vertices)), again.message
    assert np.array_equal(again.vertices[: len(v)][fixed], w[fixed])
    assert np.array_equal(again.unreferenced, r.unreferenced)
    assert np.abs(again.vertices - r.vertices).max() < 1e-5
    # Normals given for the input's rows (the sphere's: the estimate's within its error).
    exact = live.update(w, boundary_normals=w / np.linalg.norm(w, axis=1)[:, None])
    assert exact.converged and np.abs(exact.vertices - r.vertices).max() < 1e-3, exact.message
    # The live mesh's own row count is taken as well; another one is refused.
    live.update(np.vstack([w, r.vertices[len(v) :]]))
    with pytest.raises(geofair.InvalidInputError, match="rows"):
        live.update(w[:-1])


def test_failed_warm_remesh_goes_back_to_the_old_mesh_and_remeshes_cold(handle_scene):
    # With one Newton step a frame, the warm start of each frame of the drag fails, and so
    # does the warm start on its remesh: the live mesh goes back to the old one, and the
    # remesh's cold fair gives the frame, the surface of a cold fair of its own mesh.
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free, remesh="if_needed", max_warm_steps=1)
    for k in range(1, 4):
        w = v.copy()
        w[handle] = v[handle] @ rotation_x(3.0 * k).T
        r = live.update(w)
        assert r.converged and r.remeshed and r.folds == 0, (k, r.message)
        assert "the warm solve on the remesh did not converge" in r.message, r.message
        assert np.array_equal(r.vertices[: len(v)][~free], w[~free])
        cold = geofair.fair(r.vertices, r.faces, r.free)
        assert cold.converged and np.abs(cold.vertices - r.vertices).max() < 1e-5, (k, r.message)
        radial = np.abs(np.linalg.norm(r.vertices[r.free], axis=1) - 1.0).max()
        assert radial < 1e-4, (k, radial)
    assert live.frames == 3 and live.remeshes == 3 and live.cold_frames == 0


def test_remesh_before_the_fold_waits_for_a_frame_with_time(handle_scene):
    # The drag of the test above, 2° a frame: the first frame that remeshes because the
    # last one's triangles degenerated, given no time, is returned unsolved (the last
    # converged frame) and keeps its remesh for the next frame; so does a frame that raises
    # (bad normals). The frame after is then the frame of a drag without the pause, bit for
    # bit.
    v, f, free, handle = handle_scene

    def frame(k):
        w = v.copy()
        w[handle] = v[handle] @ rotation_x(2.0 * k).T
        return w

    live = geofair.LiveFairing(v, f, free, remesh="if_needed")
    for k in range(1, 16):
        r = live.update(frame(k))
        if "triangles degenerated" in r.message:
            break
    assert r.converged and r.remeshed, (k, r.message)
    paused = geofair.LiveFairing(v, f, free, remesh="if_needed")
    for j in range(1, k):
        last = paused.update(frame(j))
    stopped = paused.update(frame(k), time_limit=1e-300)  # a deadline already passed
    assert not stopped.converged and stopped.stop_reason == "time_limit", stopped.message
    assert "waits for a frame with time" in stopped.message, stopped.message
    assert paused.remeshes == live.remeshes - 1
    assert np.array_equal(stopped.vertices[free], last.vertices[free])
    with pytest.raises(geofair.InvalidInputError, match="normal"):
        paused.update(frame(k), boundary_normals=np.zeros_like(v))
    again = paused.update(frame(k))
    assert again.message == r.message and np.array_equal(again.vertices, r.vertices)
    assert np.array_equal(again.faces, r.faces) and paused.remeshes == live.remeshes


def test_remesh_of_a_small_handle_with_given_normals():
    # A 4-vertex handle: its vertices have no triangle without a free vertex, so their
    # normals must come from boundary_normals, in the remesh's steps too (a remesh that
    # estimated them failed, and the drag fell to the cold path and did not converge). The
    # free rows are NaN: a remesh reads the last frame's, not the caller's.
    s = scenes.sphere(n_vertices=3000, irregular=True, seed=1)
    v, f = s.vertices, s.faces
    polar = np.degrees(np.arccos(np.clip(v[:, 2], -1.0, 1.0)))
    handle = polar < 4.0
    free = (polar < 50.0) & ~handle
    live = geofair.LiveFairing(v, f, free, boundary_normals=v, remesh="if_needed")
    for k in range(1, 16):
        w = v.copy()
        w[handle] = v[handle] @ rotation_x(2.0 * k).T
        normals = w.copy()  # the unit sphere's
        w[free] = np.nan  # not read, in remeshed frames neither
        r = live.update(w, boundary_normals=normals)
        assert r.converged and r.folds == 0 and "remeshing failed" not in r.message, (k, r.message)
        assert np.all(np.isfinite(r.vertices))
        radial = np.abs(np.linalg.norm(r.vertices[r.free], axis=1) - 1.0).max()
        assert radial < 1e-4, (k, radial)
    assert live.remeshes >= 1 and live.cold_frames == 0


def test_failed_frame_leaves_the_last_converged_frame(handle_scene):
    v, f, free, handle = handle_scene
    # A time limit for the failing frame's cold path, with room for the good frames on a
    # loaded machine (two test workers on two cores).
    live = geofair.LiveFairing(v, f, free, time_limit=2.0)
    good = lifted(v, handle, 0.04)
    first = live.update(good)
    assert first.converged
    # Pulled out by three radii: a tube far longer than its circumference has no fair
    # solution (it pinches); the warm start fails, and so does the cold path.
    failed = live.update(lifted(v, handle, 3.0))
    assert not failed.converged
    assert "cold path" in failed.message and "did not converge" in failed.message
    check_frame(failed, lifted(v, handle, 3.0), free)
    assert live.frames == 2 and live.cold_frames == 1
    assert np.array_equal(live.result.vertices, first.vertices)
    # The next frame starts from the last converged one, warm.
    again = live.update(lifted(v, handle, 0.08))
    assert again.converged and "cold path" not in again.message, again.message


def test_warm_start_failing_from_both_predictors_counts_the_steps_of_each(handle_scene):
    """A jump against the drag: Newton converges within max_warm_steps neither from the secant
    predictor (the last frame's step continued) nor from the harmonic one; the cold path's
    message counts the steps of both starts."""
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free, max_warm_steps=3)
    for degrees in (6.0, -18.0):
        w = v.copy()
        w[handle] = v[handle] @ rotation_x(degrees).T
        result = live.update(w)
    assert result.converged and live.cold_frames == 1, result.message
    steps = re.search(
        r"after (\d+) Newton steps? from the secant predictor and (\d+) Newton steps? from the harmonic one",
        result.message,
    )
    assert steps and 1 <= int(steps[1]) <= 3 and 1 <= int(steps[2]) <= 3, result.message


def test_frame_time_limit_stops_the_warm_start_and_skips_the_cold_path(handle_scene):
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free)
    first = live.update(lifted(v, handle, 0.04), time_limit=60.0)
    assert first.converged
    unlimited = geofair.LiveFairing(v, f, free).update(lifted(v, handle, 0.04))
    assert np.array_equal(first.vertices, unlimited.vertices)  # a limit not reached changes nothing
    # The failing pull (above): its warm start stops at the frame's time limit, and no cold
    # path runs.
    w = lifted(v, handle, 3.0)
    failed = live.update(w, time_limit=1e-6)
    assert not failed.converged and failed.stop_reason == "time_limit"
    assert np.isfinite(failed.residual) and failed.residual > 1.0  # of the returned positions
    assert "stopped at the time limit" in failed.message and "cold path" not in failed.message, failed.message
    check_frame(failed, w, free)
    assert np.array_equal(failed.vertices[free], first.vertices[free])  # the last converged frame's
    assert live.frames == 2 and live.cold_frames == 0
    assert np.array_equal(live.result.vertices, first.vertices)
    for bad in (-1.0, np.nan, "1 s"):
        with pytest.raises(geofair.InvalidInputError, match="time_limit"):
            live.update(lifted(v, handle, 0.08), time_limit=bad)
    assert live.frames == 2
    again = live.update(lifted(v, handle, 0.08), time_limit=60.0)
    assert again.converged and "cold path" not in again.message, again.message


def test_frame_time_limit_not_reached_leaves_the_cold_path_as_it_was(handle_scene):
    # One Newton step may not reach the lifted frame: the cold path runs, under a time limit
    # it does not reach, and gives what it gives without one (fair's automatic limit stays).
    v, f, free, handle = handle_scene
    w = lifted(v, handle, 0.3)
    frames = [geofair.LiveFairing(v, f, free, max_warm_steps=1).update(w, time_limit=t) for t in (None, 600.0)]
    assert "cold path" in frames[0].message and frames[0].converged, frames[0].message
    assert np.array_equal(frames[0].vertices, frames[1].vertices) and frames[0].message == frames[1].message


def test_frame_time_limit_with_details_keeps_the_last_frame(handle_scene):
    v, f, free, handle = handle_scene
    rng = np.random.default_rng(3)
    bumpy = v + 0.01 * rng.standard_normal(v.shape) * free[:, None]  # details that fold triangles
    live = geofair.LiveFairing(bumpy, f, free, details=True)
    first = live.update(lifted(bumpy, handle, 0.04))
    assert first.converged
    failed = live.update(lifted(bumpy, handle, 3.0), time_limit=1e-6)
    assert not failed.converged and failed.stop_reason == "time_limit"
    assert np.array_equal(failed.vertices[free], first.vertices[free])
    # Folds of the base, as a warm frame counts them, not of the base with the details.
    assert failed.folds == first.folds == 0, failed.message


def nan_in_handle(w, handle):
    w[np.flatnonzero(handle)[0], 1] = np.nan
    return w


def inf_in_surroundings(w, handle):
    w[np.flatnonzero(~handle)[-1], 0] = np.inf
    return w


@pytest.mark.parametrize(
    "change, words",
    [
        (nan_in_handle, "non-finite"),
        (inf_in_surroundings, "non-finite"),
        (lambda w, handle: w[:-1], "rows"),
        (lambda w, handle: w[:, :2], "shape"),
        (lambda w, handle: w.astype(np.float32), "float64"),
        (lambda w, handle: w.tolist(), "numpy array"),
    ],
)
def test_bad_update_raises_and_leaves_the_state(handle_scene, change, words):
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free)
    before = live.update(lifted(v, handle, 0.04))
    with pytest.raises(geofair.InvalidInputError, match=words):
        live.update(change(lifted(v, handle, 0.08), handle))
    assert live.frames == 1 and np.array_equal(live.result.vertices, before.vertices)
    after = live.update(lifted(v, handle, 0.08))
    assert after.converged and "cold path" not in after.message


def test_bad_boundary_normals_raise(handle_scene):
    v, f, free, handle = handle_scene
    live = geofair.LiveFairing(v, f, free)
    w = lifted(v, handle, 0.04)
    with pytest.raises(geofair.InvalidInputError, match="boundary_normals"):
        live.update(w, boundary_normals=np.zeros((len(v) - 1, 3)))
    with pytest.raises(geofair.InvalidInputError):
        live.update(w, boundary_normals=-w)  # flipped against the surface's orientation
    assert live.frames == 0
    # The exact normals of the sphere, turned with the handle, give the estimate's surface.
    r = live.update(w, boundary_normals=w / np.linalg.norm(w, axis=1)[:, None])
    assert r.converged


def test_constructor_checks_its_input(handle_scene):
    v, f, free, _ = handle_scene
    with pytest.raises(geofair.InvalidInputError, match="max_warm_steps"):
        geofair.LiveFairing(v, f, free, max_warm_steps=0)
    with pytest.raises(geofair.InvalidInputError, match="free"):
        geofair.LiveFairing(v, f, free[:-1])
    with pytest.raises(geofair.InvalidInputError, match="tolerance"):
        geofair.LiveFairing(v, f, free, tolerance=-1.0)
    for remesh in ("always", True, "sometimes"):
        with pytest.raises(geofair.InvalidInputError, match="remesh must be False, 'off' or 'if_needed', got"):
            geofair.LiveFairing(v, f, free, remesh=remesh)
    with pytest.raises(geofair.InvalidInputError, match="details=True"):
        geofair.LiveFairing(v, f, free, remesh="if_needed", details=True)


def test_g0_handle_on_a_plane_is_the_cold_fair():
    # G0 (positions only): a handle lifted out of a flat disk; the frames are warm and the
    # last is the cold fair of its input.
    s = scenes.plane_disk(n_free=500, irregular=True, seed=3, boundary_rings=2)
    r2 = (s.vertices[:, :2] ** 2).sum(axis=1)
    handle = s.free & (r2 < (0.1 * r2[s.free].max()))
    free = s.free & ~handle
    live = geofair.LiveFairing(s.vertices, s.faces, free, boundary="g0")
    for k in range(1, 4):
        w = s.vertices.copy()
        w[handle, 2] += 0.02 * k * np.sqrt(r2[s.free].max())
        r = live.update(w)
        assert r.converged and "cold path" not in r.message, r.message
    cold = geofair.fair(w, s.faces, free, boundary="g0")
    assert cold.converged
    L = region_diagonal(w, s.faces, free)
    assert np.abs(r.vertices - cold.vertices).max() <= 1e-4 * L


def bumpy(vertices, free, amplitude=0.01):
    """The free vertices moved along the sphere's normal by small bumps (about 12 per
    half circle)."""
    x = vertices.copy()
    theta = np.arccos(np.clip(vertices[:, 2], -1.0, 1.0))
    phi = np.arctan2(vertices[:, 1], vertices[:, 0])
    bump = amplitude * np.sin(12.0 * theta) * np.sin(6.0 * phi)
    x[free] *= (1.0 + bump[free])[:, None]
    return x


def rms_radial(vertices, free):
    return float(np.sqrt(np.mean((np.linalg.norm(vertices[free], axis=1) - 1.0) ** 2)))


def test_details_ride_on_the_dragged_base(handle_scene):
    # The base of the bumpy region is the sphere; a slide along it keeps the base, and the
    # bumps come back in the base's frames: their RMS stays (within 5 %); without details
    # the region is the fair surface itself and they are gone.
    v, f, free, handle = handle_scene
    x = bumpy(v, free)
    before = rms_radial(x, free)
    assert before > 3e-3
    with_details = geofair.LiveFairing(x, f, free, details=True)
    without = geofair.LiveFairing(x, f, free)
    assert np.array_equal(with_details.result.vertices, x)  # the first frame is the input
    same = with_details.update(x)
    L = region_diagonal(x, f, free)
    assert same.converged and np.abs(same.vertices - x).max() <= 1e-4 * L
    for k in range(1, 6):
        w = x.copy()
        w[handle] = v[handle] @ rotation_x(2.0 * k).T
        r = with_details.update(w)
        check_frame(r, w, free)
        assert r.converged and "cold path" not in r.message, r.message
        assert abs(rms_radial(r.vertices, free) - before) <= 0.05 * before
        plain = without.update(w)
        assert plain.converged and rms_radial(plain.vertices, free) < 1e-4
