"""Live Fair Drag without bpy (numpy only): a handle dragged through a region, refaired per frame.

The region is the Fair operator's (selected faces or a Region vertex group); the
handle is the region's pinned vertices: the Pin vertex group's inside the region,
and, when a Region vertex group gives the region, the selected vertices inside it
too (``fairing.FairingRun``'s ``pin_selected``). The handle moves as a whole: translated,
rotated and uniformly scaled about its centre (:class:`HandleMove`; its G1 tangent planes turn
with the rotation); each frame is ``geofair.LiveFairing.update`` from the last converged
frame (docs/LIVE.md), in sub-steps that move no handle vertex by more than the mean edge
length at the handle: the warm start holds for about an edge a step, a longer jump of the
mouse would fall back to the slow cold path. A frame that does not converge, or gives a
non-finite position, leaves the last good positions shown.

Conventions: ``V  #V×3 float64`` positions in object space, ``T  #T×3 int`` triangles.
"""

import math
import time
from dataclasses import dataclass, field

import numpy as np

HANDLE_RULE = (
    "the handle is the Pin vertex group's vertices inside the region (with a Region vertex group, the selected "
    "vertices inside it too)"
)
RADIUS_RULE = "the handle is the selected vertices, the region the faces within the radius of it along the surface"
NO_HANDLE = (
    "No handle: put vertices inside the region into the Pin vertex group (or give the region by a Region vertex "
    "group and select the handle's vertices inside it)"
)


class NoHandleError(ValueError):
    """The region holds no handle (no pinned vertex inside it)."""


def rotation_matrix(axis, angle):
    """``(3, 3)`` rotation by ``angle`` radians about ``axis`` (right-handed; a zero axis: the identity)."""
    axis = np.asarray(axis, dtype=np.float64).reshape(3)
    length = float(np.linalg.norm(axis))
    if not length > 0.0:
        return np.eye(3)
    x, y, z = axis / length
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)


def axis_angle(rotation):
    """``(axis (3,), angle)`` of a rotation matrix, the angle in [0, π] radians."""
    r = np.asarray(rotation, dtype=np.float64)
    w = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])  # 2 sin(angle) axis
    angle = math.atan2(float(np.linalg.norm(w)) / 2.0, (float(np.trace(r)) - 1.0) / 2.0)
    if angle == 0.0:
        return np.array([1.0, 0.0, 0.0]), 0.0
    if angle < math.pi - 1e-3:
        return w / np.linalg.norm(w), angle
    # Near a half turn w is tiny: the axis from the symmetric part (R + Rᵀ)/2 = cos·I + (1 - cos) a aᵀ,
    # the largest column of a aᵀ, signed along w.
    cos = (float(np.trace(r)) - 1.0) / 2.0
    outer = ((r + r.T) / 2.0 - cos * np.eye(3)) / (1.0 - cos)
    axis = outer[:, int(np.argmax(np.linalg.norm(outer, axis=0)))]
    axis = axis / np.linalg.norm(axis)
    return (-axis if axis @ w < 0.0 else axis), angle


@dataclass(frozen=True, eq=False)
class HandleMove:
    """The handle's move about its centre c (object space): p ↦ c + scale · rotation (p − c) + offset.

    Attributes:
        offset: ``(3,)`` translation (mesh units).
        rotation: ``(3, 3)`` rotation matrix; the handle's G1 normals turn with it.
        scale: uniform scale factor (> 0), which keeps the normals.
    """

    offset: np.ndarray = field(default_factory=lambda: np.zeros(3))
    rotation: np.ndarray = field(default_factory=lambda: np.eye(3))
    scale: float = 1.0

    def points(self, points, centre):
        """``(k, 3)`` points moved."""
        return centre + self.scale * (points - centre) @ self.rotation.T + self.offset

    def then(self, other):
        """This move followed by ``other`` (both about the same centre)."""
        return HandleMove(
            other.scale * (other.rotation @ self.offset) + other.offset,
            other.rotation @ self.rotation,
            other.scale * self.scale,
        )

    def toward(self, other, fraction):
        """The move a ``fraction`` of the way from this one to ``other``: the offset and the log of
        the scale linear, the rotation about the axis of the rotation between them."""
        axis, angle = axis_angle(other.rotation @ self.rotation.T)
        return HandleMove(
            self.offset + fraction * (other.offset - self.offset),
            rotation_matrix(axis, fraction * angle) @ self.rotation,
            self.scale * (other.scale / self.scale) ** fraction,
        )


@dataclass(frozen=True)
class Frame:
    """One frame of the drag.

    Attributes:
        move: the handle's :class:`HandleMove` asked for (object space).
        converged: the frame converged with finite positions and is shown.
        cold: it ran the cold path (geofair.fair's whole schedule).
        steps: Newton steps of a warm frame (0 on the cold path).
        seconds: wall time of the frame (all its sub-steps).
        message: the library's account of the last sub-step (or the error's text).
        substeps: updates the frame took (a jump longer than the step length is split).
        folds: edges of the region whose triangles flipped over in the last sub-step.
        reached: the frame got to ``move`` (not cut short by ``max_substeps``).
    """

    move: HandleMove
    converged: bool
    cold: bool
    steps: int
    seconds: float
    message: str
    substeps: int = 1
    folds: int = 0
    reached: bool = True

    def status(self):
        """The header's text of the frame."""
        how = "cold path" if self.cold else f"{self.steps} Newton step{'s' if self.steps != 1 else ''}"
        text = f"frame {self.seconds * 1e3:.0f} ms, {how}"
        if self.substeps > 1:
            text += f" ({self.substeps} sub-steps)"
        if self.folds:
            text += f", {self.folds} edge{'s' if self.folds != 1 else ''} folded over"
        if not self.converged:
            limit = " (time limit)" if "time limit" in self.message else ""
            text += f", NOT converged{limit}: last good positions kept"
        elif not self.reached:
            text += ", on the way"
        return text


MODES = ("TRANSLATE", "ROTATE", "SCALE")  # Blender's G, R and S
# Without a Time Limit, an update may take this many times the preparation (a cold fair of the
# region), and at least FRAME_SECONDS_MIN seconds.
FRAME_PREPARE_FACTOR = 4.0
FRAME_SECONDS_MIN = 1.0
MAX_TURN = math.radians(5.0)  # the largest turn of the handle's tangent planes in one update


def mode_move(mode, committed, to_object, translation, angle, view_axis, factor, axis=None, typed=None):
    """The handle's move: ``committed`` followed by one transform mode, as Blender's G, R and S take
    the mouse (or a typed value) in world space.

    Args:
        mode: one of :data:`MODES`.
        committed: the :class:`HandleMove` of the modes before (object space); rotations and
            scalings are about the handle's centre where ``committed`` put it.
        to_object: ``(3, 3)`` world-to-object linear map (the object's inverted matrix).
        translation: ``(3,)`` the mouse's move in the view plane through the handle (world units).
        angle: the mouse's turn about the handle's centre on screen (radians, counter-clockwise).
        view_axis: ``(3,)`` unit world direction towards the viewer: the mouse turns the handle
            about it (as seen, with a global axis flipped to face the viewer); a typed angle turns
            it about the opposite direction, into the screen, or about the global axis as it is
            (Blender's convention).
        factor: the mouse's distance from the handle's centre on screen over that at the mode's
            start (the scale).
        axis: 0, 1 or 2: along (G) or about (R) that global axis; None: the view's. Scaling is
            uniform.
        typed: a typed value that replaces the mouse's: the distance along ``axis`` (X without
            one; mesh units), the angle (degrees) or the scale factor; None: the mouse's.
    """
    unit = np.eye(3)
    to_object = np.asarray(to_object, dtype=np.float64)
    centre_offset = committed.offset  # the handle's centre has moved by it
    if mode == "TRANSLATE":
        world = np.asarray(translation, dtype=np.float64)
        if typed is not None:
            world = typed * unit[0 if axis is None else axis]
        elif axis is not None:
            world = world[axis] * unit[axis]
        step = HandleMove(offset=to_object @ world)
    elif mode == "ROTATE":
        # The mouse's turn about the axis towards the viewer (the handle follows the mouse); a typed
        # angle as Blender's: about the axis into the screen, or about the global axis unflipped.
        view = np.asarray(view_axis, dtype=np.float64)
        if typed is not None:
            world_axis, turn = (-view if axis is None else unit[axis]), math.radians(typed)
        elif axis is None:
            world_axis, turn = view, angle
        else:
            world_axis, turn = unit[axis] * (1.0 if unit[axis] @ view >= 0.0 else -1.0), angle
        rotation = rotation_matrix(to_object @ world_axis, turn)
        step = HandleMove(offset=centre_offset - rotation @ centre_offset, rotation=rotation)
    elif mode == "SCALE":
        scale = typed if typed is not None else factor
        scale = max(abs(float(scale)), 1e-3) if math.isfinite(scale) else 1.0  # no mirror, no collapse
        step = HandleMove(offset=centre_offset - scale * centre_offset, scale=scale)
    else:
        raise ValueError(f"unknown transform mode {mode!r}: expected one of {MODES}")
    return committed.then(step)


# Keys of a typed value (Blender's event types) and the characters they add.
TYPED_KEYS = {
    **{
        name: str(i)
        for i, name in enumerate(("ZERO", "ONE", "TWO", "THREE", "FOUR", "FIVE", "SIX", "SEVEN", "EIGHT", "NINE"))
    },
    **{f"NUMPAD_{i}": str(i) for i in range(10)},
    "PERIOD": ".",
    "NUMPAD_PERIOD": ".",
    "MINUS": "-",
    "NUMPAD_MINUS": "-",
}


def typed_text(text, key):
    """``text`` after the key ``key`` (a :data:`TYPED_KEYS` key or ``BACK_SPACE``): minus toggles the sign."""
    if key == "BACK_SPACE":
        return text[:-1]
    char = TYPED_KEYS[key]
    if char == "-":
        return text[1:] if text.startswith("-") else "-" + text
    return text + char


def typed_value(text):
    """The typed text's number, or None while it is not one (empty, ``-``, ``.``)."""
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


class LiveDrag:
    """A handle of a region moved as a whole, the region refaired per frame (``geofair.LiveFairing``).

    Args:
        library: the ``geofair`` module.
        vertices: ``(n, 3)`` float64 positions.
        triangles: ``(T, 3)`` int triangles that take part.
        free: ``(n,)`` bool free vertices of the region.
        handle: ``(n,)`` bool fixed vertices inside the region that move with the drag.
        boundary_normals: ``(n, 3)`` G1 normals (the handle's turn with its rotation), or None
            (G0).
        polygon_ids: ``(T,)`` polygon of each triangle, or None.
        options: keyword options of ``geofair.fair`` (remesh off); their ``time_limit`` bounds each
            update (:attr:`frame_time_limit`; None: :data:`FRAME_PREPARE_FACTOR` times the
            preparation's seconds, at least :data:`FRAME_SECONDS_MIN`).
        details: keep the region's details over its faired base (``LiveFairing(details=True)``).
        step: the longest move of a handle vertex per update (mesh units); None: the mean
            length of the edges at the handle.

    Raises:
        NoHandleError: ``handle`` is empty.
        ValueError, RuntimeError: as ``geofair.LiveFairing``; the cold fair at the
            start did not converge (RuntimeError).
    """

    def __init__(
        self, library, vertices, triangles, free, handle, boundary_normals, polygon_ids, options, details, step=None
    ):
        self.base = np.array(vertices, dtype=np.float64)
        self.handle = np.asarray(handle, dtype=bool)
        if not self.handle.any():
            raise NoHandleError(NO_HANDLE)
        self.free = np.asarray(free, dtype=bool)
        self.moving = np.flatnonzero(self.free | self.handle)  # the rows a frame writes
        self.normals = boundary_normals
        self.step = handle_edge_length(triangles, self.base, self.handle) if step is None else float(step)
        clock = time.perf_counter()
        self.live = library.LiveFairing(
            self.base,
            triangles,
            self.free,
            details=details,
            boundary_normals=boundary_normals,
            polygon_ids=polygon_ids,
            **options,
        )
        self.prepare_seconds = time.perf_counter() - clock
        # A frame's bound: past a point where the region's triangles fold the cold path can
        # take many seconds, which would freeze the viewport; the last good frame stays instead.
        limit = options.get("time_limit")
        self.frame_time_limit = limit or max(FRAME_SECONDS_MIN, FRAME_PREPARE_FACTOR * self.prepare_seconds)
        start = self.live.result
        if not start.converged:
            raise RuntimeError(f"the region's fairing at the start did not converge: {start.message}")
        self.positions = np.array(start.vertices, dtype=np.float64)  # the last good frame
        self.centre = self.base[self.handle].mean(axis=0)  # the handle's rotations and scalings are about it
        self.move = HandleMove()  # the last good frame's
        self.frames = []

    @property
    def offset(self):
        """``(3,)`` the last good frame's translation of the handle."""
        return self.move.offset

    @property
    def handle_count(self):
        return int(np.count_nonzero(self.handle))

    @property
    def free_count(self):
        return int(np.count_nonzero(self.free))

    def frame(self, move, max_substeps=math.inf):
        """Move the handle by ``move`` (a :class:`HandleMove`, or a ``(3,)`` translation; object space) and
        refair, from the last good move in sub-steps that move no handle vertex by more than :attr:`step`
        and turn it by at most :data:`MAX_TURN`; return the :class:`Frame`.

        An unconverged sub-step (or one raising, or with a non-finite position) ends the frame
        and leaves :attr:`positions` and :attr:`move` at the last good one. After ``max_substeps``
        sub-steps the frame ends on the way (``Frame.reached`` False; the next frame goes on from there).
        """
        if not isinstance(move, HandleMove):
            move = HandleMove(offset=np.asarray(move, dtype=np.float64).reshape(3))
        start, clock = self.move, time.perf_counter()
        handle = self.base[self.handle]
        moved = move.points(handle, self.centre) - start.points(handle, self.centre)
        distance = float(np.linalg.norm(moved, axis=1).max())
        _, turn = axis_angle(move.rotation @ start.rotation.T)
        count = 1
        if np.isfinite(distance) and self.step > 0:
            count = max(1, math.ceil(distance / self.step), math.ceil(turn / MAX_TURN))
        steps = 0
        for k in range(1, min(count, max_substeps) + 1):
            sub = self._update(move if k == count else start.toward(move, k / count))
            steps += sub.steps
            if not sub.converged:
                break
        seconds = time.perf_counter() - clock
        frame = Frame(move, sub.converged, sub.cold, steps, seconds, sub.message, k, sub.folds, k == count)
        self.frames.append(frame)
        return frame

    def _update(self, move):
        """One LiveFairing update with the handle moved by ``move``; the last good frame kept where it fails."""
        target = self.base.copy()
        target[self.handle] = move.points(self.base[self.handle], self.centre)
        normals = self.normals
        if normals is not None and not np.array_equal(move.rotation, np.eye(3)):
            normals = np.array(normals, dtype=np.float64)
            normals[self.handle] = normals[self.handle] @ move.rotation.T
        clock = time.perf_counter()
        try:
            result = self.live.update(target, boundary_normals=normals, time_limit=self.frame_time_limit)
            message, converged, steps = str(result.message), bool(result.converged), int(result.iterations)
            folds = int(getattr(result, "folds", 0))
            positions = np.asarray(result.vertices, dtype=np.float64)
            converged = converged and np.isfinite(positions[self.moving]).all()
        except (ValueError, RuntimeError) as error:
            message, converged, positions, steps, folds = str(error), False, None, 0, 0
        seconds = time.perf_counter() - clock
        cold = "cold path" in message
        steps = 0 if cold else steps
        if converged:
            self.positions, self.move = positions, move
        return Frame(move, converged, cold, steps, seconds, message, 1, folds)

    def drag(self, move, frames):
        """Reach ``move`` (a :class:`HandleMove` or a ``(3,)`` translation) in ``frames`` equal steps from
        the rest (a script's drag); return the last :class:`Frame`."""
        if not isinstance(move, HandleMove):
            move = HandleMove(offset=np.asarray(move, dtype=np.float64).reshape(3))
        frames = max(int(frames), 1)
        last = None
        for k in range(1, frames + 1):
            last = self.frame(move if k == frames else HandleMove().toward(move, k / frames))
        return last

    def summary(self):
        """One line on the frames so far: count, median time, cold and unconverged ones."""
        if not self.frames:
            return f"{self.free_count} free vertices, {self.handle_count} handle vertices, no frame"
        seconds = sorted(frame.seconds for frame in self.frames)
        median = seconds[len(seconds) // 2] * 1e3
        cold = sum(frame.cold for frame in self.frames)
        failed = sum(not frame.converged for frame in self.frames)
        text = (
            f"{self.free_count} free vertices, {self.handle_count} handle vertices; prepared in "
            f"{self.prepare_seconds:.2f} s; {len(self.frames)} frames, median {median:.0f} ms"
        )
        if cold:
            text += f", {cold} on the cold path"
        if failed:
            text += f", {failed} not converged"
        return text


def handle_edge_length(triangles, vertices, handle):
    """The mean length of the edges of the triangles at the handle (mesh units)."""
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    at = triangles[handle[triangles].any(axis=1)]
    edges = at[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    lengths = np.linalg.norm(vertices[edges[:, 0]] - vertices[edges[:, 1]], axis=1)
    return float(lengths.mean()) if len(lengths) else 0.0


def distance_text(offset):
    """The offset's length for the header, e.g. ``0.123``."""
    return f"{math.sqrt(float(np.dot(offset, offset))):.4g}"
