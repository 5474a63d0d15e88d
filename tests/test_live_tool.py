"""The add-on's Live Fair Drag without bpy (addon/geometric_fairing/live.py): the region and handle
as the Fair operator finds them (region.py, the handle its pinned vertices), the handle translated
in frames; each shown frame is the cold geofair.fair of its input, an unconverged frame keeps the
last good positions, and a region without a handle is refused. In Blender:
tests/blender/check_live.py."""

import importlib.util
import pathlib

import numpy as np
import pytest

import geofair
from geofair_dev import scenes

_ADDON = pathlib.Path(__file__).resolve().parents[1] / "addon" / "geometric_fairing"


def _load(name):
    spec = importlib.util.spec_from_file_location(f"geofair_{name}", _ADDON / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


live = _load("live")
region = _load("region")


@pytest.fixture(scope="module")
def sphere_region():
    """An irregular unit sphere (3,000 vertices); the selected triangles those within 50° of +z, the
    Pin group the vertices within 8° of it: (vertices, triangles, Region, boundary normals)."""
    s = scenes.sphere(n_vertices=3000, irregular=True, seed=1)
    polar = np.degrees(np.arccos(np.clip(s.vertices[:, 2], -1.0, 1.0)))
    selected = (polar[s.faces] < 50.0).all(axis=1)
    r = region.find_region(s.vertices, s.faces, selected, pinned=polar < 8.0)
    normals = region.boundary_normals(r, s.vertices, s.faces, geofair.boundary_normals)
    return s.vertices, s.faces, r, normals


def make_drag(sphere_region, details=False, step=None, **options):
    v, f, r, normals = sphere_region
    return live.LiveDrag(geofair, v, f, r.free, r.pinned, normals, None, options, details, step)


def region_diagonal(vertices, faces, free):
    used = np.unique(faces[free[faces].any(axis=1)])
    p = vertices[used]
    return float(np.linalg.norm(p.max(axis=0) - p.min(axis=0)))


def test_drag_is_the_cold_fair_of_its_input(sphere_region):
    # The handle slid along the sphere's tangent (+y) by 0.15 in 5 frames: every frame warm, and
    # the last the cold fair of the same input (the Fair operator's) within the tolerance.
    v, f, r, normals = sphere_region
    drag = make_drag(sphere_region)
    assert drag.handle_count == np.count_nonzero(r.pinned) > 0 and drag.free_count == np.count_nonzero(r.free)
    offset = np.array([0.0, 0.15, 0.0])
    frame = drag.drag(offset, 5)
    assert frame.converged and not frame.cold and frame.steps >= 1, frame.message
    assert "Newton step" in frame.status() and "NOT" not in frame.status()
    assert len(drag.frames) == 5 and np.array_equal(drag.offset, offset)
    target = v.copy()
    target[r.pinned] += offset
    assert np.array_equal(drag.positions[~r.free], target[~r.free])  # fixed rows as given
    cold = geofair.fair(target, f, r.free, boundary_normals=normals)
    assert cold.converged
    error = np.abs(drag.positions - cold.vertices).max() / region_diagonal(target, f, r.free)
    assert error < 1e-4, error
    # The region follows the handle and stays near the sphere: a translated handle keeps its tangent
    # planes (they do not turn as along the sphere), so the region bulges a little (measured 0.031).
    radial = np.abs(np.linalg.norm(drag.positions[r.free], axis=1) - 1.0).max()
    assert radial < 0.05, radial
    assert (drag.positions[r.free, 1] - v[r.free, 1]).max() > 0.1  # next to the handle, nearly its 0.15
    assert "5 frames" in drag.summary()


def test_unconverged_frame_keeps_the_last_good_positions(sphere_region):
    drag = make_drag(sphere_region, step=10.0, time_limit=0.5)  # no sub-steps
    good = drag.frame([0.0, 0.05, 0.0])
    assert good.converged
    kept = drag.positions.copy()
    # Pulled out by three radii: no fair surface (a tube that pinches); the cold path fails too.
    bad = drag.frame([0.0, 0.0, 3.0])
    assert not bad.converged and bad.cold and "NOT converged" in bad.status() and "cold path" in bad.status()
    assert np.array_equal(drag.positions, kept) and np.array_equal(drag.offset, [0.0, 0.05, 0.0])
    assert np.isfinite(drag.positions).all()
    assert "1 not converged" in drag.summary()


def test_a_frame_past_its_time_limit_keeps_the_last_good_positions(sphere_region):
    # Without a Time Limit a frame is bounded by the preparation's time (a viewport that
    # freezes for the cold path's seconds past a fold point is worse than a frame not taken).
    drag = make_drag(sphere_region, step=10.0)
    rule = max(live.FRAME_SECONDS_MIN, live.FRAME_PREPARE_FACTOR * drag.prepare_seconds)
    assert drag.frame_time_limit == rule and live.FRAME_PREPARE_FACTOR > 1.0
    assert make_drag(sphere_region, time_limit=7.5).frame_time_limit == 7.5  # the user's Time Limit
    good = drag.frame([0.0, 0.05, 0.0])
    assert good.converged
    kept = drag.positions.copy()
    drag.frame_time_limit = 1e-6  # the warm start stops at once, and no cold path runs
    bad = drag.frame([0.0, 0.0, 3.0])
    assert not bad.converged and not bad.cold and "NOT converged (time limit)" in bad.status(), bad.status()
    assert np.array_equal(drag.positions, kept) and np.array_equal(drag.offset, [0.0, 0.05, 0.0])
    drag.frame_time_limit = 60.0
    assert drag.frame([0.0, 0.08, 0.0]).converged


def test_non_finite_offset_is_an_unconverged_frame(sphere_region):
    drag = make_drag(sphere_region)
    kept = drag.positions.copy()
    frame = drag.frame([np.nan, 0.0, 0.0])
    assert not frame.converged and "non-finite" in frame.message
    assert np.array_equal(drag.positions, kept)


def test_details_keep_the_input_at_rest(sphere_region):
    v, f, r, _ = sphere_region
    drag = make_drag(sphere_region, details=True)
    assert np.array_equal(drag.positions, v)  # nothing moves before the handle does
    frame = drag.frame([0.0, 0.05, 0.0])
    assert frame.converged, frame.message


def test_no_handle_is_refused(sphere_region):
    v, f, r, normals = sphere_region
    with pytest.raises(live.NoHandleError, match="No handle: put vertices inside the region into the Pin"):
        live.LiveDrag(geofair, v, f, r.free, np.zeros(len(v), dtype=bool), normals, None, {}, False)


def test_a_long_jump_is_split_into_warm_steps(sphere_region):
    # A jump of the mouse by 0.3 (several edges) in one frame: split into sub-steps of at most the
    # mean edge length at the handle, each warm, instead of one cold-path solve.
    drag = make_drag(sphere_region)
    assert 0.0 < drag.step < 0.2
    frame = drag.frame([0.0, 0.3, 0.0])
    assert frame.converged and not frame.cold, frame.message
    assert frame.substeps == int(np.ceil(0.3 / drag.step)) > 1 and "sub-steps" in frame.status()
    assert np.array_equal(drag.offset, [0.0, 0.3, 0.0])


def test_a_handle_turned_along_the_sphere_keeps_the_region_on_it(sphere_region):
    # The handle rotated by 20° about the x axis through the sphere's centre (a rotation about its
    # own centre c and the offset R c - c): with its G1 normals (the sphere's) turned by the same
    # rotation, every boundary datum lies on the unit sphere, the exact answer of every frame.
    v, f, r, _ = sphere_region
    exact = (v, f, r, v / np.linalg.norm(v, axis=1, keepdims=True))
    drag = make_drag(exact)
    rest = np.abs(np.linalg.norm(drag.positions[r.free], axis=1) - 1.0).max()
    rotation = live.rotation_matrix([1.0, 0.0, 0.0], np.radians(20.0))
    move = live.HandleMove(offset=rotation @ drag.centre - drag.centre, rotation=rotation)
    frame = drag.drag(move, 4)
    assert frame.converged and not frame.cold and frame.substeps > 1, frame.message
    assert all(f.converged for f in drag.frames)
    assert np.allclose(drag.positions[r.pinned], v[r.pinned] @ rotation.T, atol=1e-12)
    radial = np.abs(np.linalg.norm(drag.positions[r.free], axis=1) - 1.0).max()
    assert rest < 1e-5 and radial < 1e-4, (rest, radial)  # measured 8.0e-7 and 2.7e-6
    # Translated by the same offset without turning, the handle bends the region off the sphere.
    still = make_drag(exact)
    assert still.drag(live.HandleMove(offset=move.offset), 4).converged
    assert np.abs(np.linalg.norm(still.positions[r.free], axis=1) - 1.0).max() > 100 * radial


def test_a_scaled_handle_is_the_cold_fair_of_its_input(sphere_region):
    v, f, r, normals = sphere_region
    drag = make_drag(sphere_region)
    frame = drag.frame(live.HandleMove(scale=1.4))
    assert frame.converged and not frame.cold, frame.message
    target = v.copy()
    target[r.pinned] = drag.centre + 1.4 * (v[r.pinned] - drag.centre)
    assert np.array_equal(drag.positions[~r.free], target[~r.free])
    cold = geofair.fair(target, f, r.free, boundary_normals=normals)  # a scaling keeps the normals
    assert cold.converged
    error = np.abs(drag.positions - cold.vertices).max() / region_diagonal(target, f, r.free)
    assert error < 1e-6, error  # measured 2.5e-8


def test_handle_moves_compose_and_interpolate():
    rng = np.random.default_rng(5)
    for angle in (0.0, 1e-7, 0.4, 2.0, np.pi - 1e-4, np.pi - 5e-10, np.pi):
        axis = rng.normal(size=3)
        rotation = live.rotation_matrix(axis, angle)
        assert np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-14) and np.isclose(np.linalg.det(rotation), 1.0)
        back_axis, back_angle = live.axis_angle(rotation)
        assert abs(back_angle - angle) <= 1e-12 * max(angle, 1e-3), (angle, back_angle)
        assert np.allclose(live.rotation_matrix(back_axis, back_angle), rotation, rtol=0.0, atol=1e-12), angle
    a = live.HandleMove(rng.normal(size=3), live.rotation_matrix(rng.normal(size=3), 1.1), 0.7)
    b = live.HandleMove(rng.normal(size=3), live.rotation_matrix(rng.normal(size=3), 2.5), 1.9)
    points, centre = rng.normal(size=(6, 3)), rng.normal(size=3)
    assert np.allclose(a.then(b).points(points, centre), b.points(a.points(points, centre), centre))
    end = a.toward(b, 1.0)
    assert np.allclose(end.points(points, centre), b.points(points, centre))
    half = a.toward(b, 0.5)  # halfway: half the turn and the geometric mean of the scales
    assert np.isclose(half.scale, np.sqrt(0.7 * 1.9))
    _, turn = live.axis_angle(b.rotation @ a.rotation.T)
    _, half_turn = live.axis_angle(half.rotation @ a.rotation.T)
    assert np.isclose(half_turn, turn / 2)


def test_typed_and_mouse_turns_follow_blenders_conventions():
    # Seen from below (the view's axis towards the viewer is -Z): the mouse turning counter-clockwise
    # turns the handle counter-clockwise as seen, about -Z; a typed angle about the axis into the
    # screen (+Z here), or about the global axis as it is.
    still, view, to_object = live.HandleMove(), np.array([0.0, 0.0, -1.0]), np.eye(3)
    cases = [
        (dict(angle=0.3, axis=None, typed=None), [0.0, 0.0, -1.0], 0.3),
        (dict(angle=0.3, axis=2, typed=None), [0.0, 0.0, -1.0], 0.3),
        (dict(angle=0.0, axis=None, typed=10.0), [0.0, 0.0, 1.0], np.radians(10.0)),
        (dict(angle=0.0, axis=2, typed=10.0), [0.0, 0.0, 1.0], np.radians(10.0)),
        (dict(angle=0.0, axis=0, typed=-30.0), [-1.0, 0.0, 0.0], np.radians(30.0)),
    ]
    for options, axis, angle in cases:
        move = live.mode_move("ROTATE", still, to_object, np.zeros(3), view_axis=view, factor=1.0, **options)
        assert np.allclose(move.rotation, live.rotation_matrix(axis, angle), atol=1e-15), options
        assert np.allclose(move.offset, 0.0) and move.scale == 1.0
    # About the centre where an earlier move left it: that centre stays put.
    moved = live.HandleMove(offset=np.array([0.3, -0.2, 0.5]))
    turned = live.mode_move("ROTATE", moved, to_object, np.zeros(3), 0.7, view, 1.0)
    scaled = live.mode_move("SCALE", moved, to_object, np.zeros(3), 0.0, view, 1.7)
    centre = np.array([1.0, 2.0, 3.0])
    for move in (turned, scaled):
        assert np.allclose(move.points(centre[None], centre), centre + moved.offset)
    assert live.mode_move("SCALE", still, to_object, np.zeros(3), 0.0, view, factor=-2.0).scale == 2.0
    shifted = live.mode_move("TRANSLATE", still, 2.0 * np.eye(3), np.array([1.0, 2.0, 3.0]), 0.0, view, 1.0, axis=1)
    assert np.array_equal(shifted.offset, [0.0, 4.0, 0.0])  # along global Y only, in object units
    assert live.typed_value(live.typed_text(live.typed_text("1", "PERIOD"), "FIVE")) == 1.5
    assert live.typed_text("2", "MINUS") == "-2" and live.typed_value("-") is None


def test_a_long_move_goes_on_over_several_frames_and_turns_in_small_steps(sphere_region):
    # Cut short after 2 updates a frame, a jump of 0.3 takes several frames and ends exactly there;
    # a turn of 20° of the handle in place takes at least 20/5 updates (live.MAX_TURN).
    drag = make_drag(sphere_region)
    target = live.HandleMove(offset=np.array([0.0, 0.3, 0.0]))
    frames = [drag.frame(target, max_substeps=2)]
    while not frames[-1].reached:
        assert frames[-1].converged and frames[-1].substeps == 2 and "on the way" in frames[-1].status()
        frames.append(drag.frame(target, max_substeps=2))
    assert len(frames) >= 2 and frames[-1].converged
    assert np.array_equal(drag.offset, [0.0, 0.3, 0.0])
    spin = make_drag(sphere_region)
    frame = spin.frame(live.HandleMove(rotation=live.rotation_matrix([0.0, 0.0, 1.0], np.radians(20.0))))
    assert frame.converged and frame.reached and frame.substeps >= 4, frame
