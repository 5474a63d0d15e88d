"""Live Fair Drag without bpy (numpy only): a handle dragged through a region, refaired per frame.

The region is the Fair operator's (selected faces or a Region vertex group); the
handle is the region's pinned vertices: the Pin vertex group's inside the region,
and, when a Region vertex group gives the region, the selected vertices inside it
too (``fairing.FairingRun``'s ``pin_selected``). The handle is translated rigidly
(its tangent planes do not turn); each frame is ``geofair.LiveFairing.update`` from
the last converged frame (docs/LIVE.md), in sub-steps of at most the mean edge
length at the handle: the warm start holds for about an edge a step, a longer jump
of the mouse would fall back to the slow cold path. A frame that does not
converge, or gives a non-finite position, leaves the last good positions shown.

Conventions: ``V  #V×3 float64`` positions in object space, ``T  #T×3 int`` triangles.
"""

import math
import time
from dataclasses import dataclass

import numpy as np

HANDLE_RULE = (
    "the handle is the Pin vertex group's vertices inside the region (with a Region vertex group, the selected "
    "vertices inside it too)"
)
NO_HANDLE = (
    "No handle: put vertices inside the region into the Pin vertex group (or give the region by a Region vertex "
    "group and select the handle's vertices inside it)"
)


class NoHandleError(ValueError):
    """The region holds no handle (no pinned vertex inside it)."""


@dataclass(frozen=True)
class Frame:
    """One frame of the drag.

    Attributes:
        offset: ``(3,)`` the handle's translation asked for (object space).
        converged: the frame converged with finite positions and is shown.
        cold: it ran the cold path (geofair.fair's whole schedule).
        steps: Newton steps of a warm frame (0 on the cold path).
        seconds: wall time of the frame (all its sub-steps).
        message: the library's account of the last sub-step (or the error's text).
        substeps: updates the frame took (a jump longer than the step length is split).
        folds: edges of the region whose triangles flipped over in the last sub-step.
    """

    offset: np.ndarray
    converged: bool
    cold: bool
    steps: int
    seconds: float
    message: str
    substeps: int = 1
    folds: int = 0

    def status(self):
        """The header's text of the frame."""
        how = "cold path" if self.cold else f"{self.steps} Newton step{'s' if self.steps != 1 else ''}"
        text = f"frame {self.seconds * 1e3:.0f} ms, {how}"
        if self.substeps > 1:
            text += f" ({self.substeps} sub-steps)"
        if self.folds:
            text += f", {self.folds} edge{'s' if self.folds != 1 else ''} folded over"
        if not self.converged:
            text += ", NOT converged: last good positions kept"
        return text


class LiveDrag:
    """A handle of a region translated rigidly, the region refaired per frame (``geofair.LiveFairing``).

    Args:
        library: the ``geofair`` module.
        vertices: ``(n, 3)`` float64 positions.
        triangles: ``(T, 3)`` int triangles that take part.
        free: ``(n,)`` bool free vertices of the region.
        handle: ``(n,)`` bool fixed vertices inside the region that move with the drag.
        boundary_normals: ``(n, 3)`` G1 normals (those of a translated handle do not turn),
            or None (G0).
        polygon_ids: ``(T,)`` polygon of each triangle, or None.
        options: keyword options of ``geofair.fair`` (remesh off).
        details: keep the region's details over its faired base (``LiveFairing(details=True)``).
        step: the longest move of the handle per update (mesh units); None: the mean length
            of the edges at the handle.

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
        start = self.live.result
        if not start.converged:
            raise RuntimeError(f"the region's fairing at the start did not converge: {start.message}")
        self.positions = np.array(start.vertices, dtype=np.float64)  # the last good frame
        self.offset = np.zeros(3)
        self.frames = []

    @property
    def handle_count(self):
        return int(np.count_nonzero(self.handle))

    @property
    def free_count(self):
        return int(np.count_nonzero(self.free))

    def frame(self, offset):
        """Translate the handle by ``offset`` (object space) and refair, from the last good offset in
        sub-steps of at most :attr:`step`; return the :class:`Frame`.

        An unconverged sub-step (or one raising, or with a non-finite position) ends the frame
        and leaves :attr:`positions` and :attr:`offset` at the last good one.
        """
        offset = np.asarray(offset, dtype=np.float64).reshape(3)
        start, clock = self.offset, time.perf_counter()
        distance = float(np.linalg.norm(offset - start))
        count = max(1, math.ceil(distance / self.step)) if np.isfinite(distance) and self.step > 0 else 1
        steps = 0
        for k in range(1, count + 1):
            sub = self._update(offset if k == count else start + (offset - start) * (k / count))
            steps += sub.steps
            if not sub.converged:
                break
        seconds = time.perf_counter() - clock
        frame = Frame(offset, sub.converged, sub.cold, steps, seconds, sub.message, k, sub.folds)
        self.frames.append(frame)
        return frame

    def _update(self, offset):
        """One LiveFairing update with the handle at ``offset``; the last good frame kept where it fails."""
        target = self.base.copy()
        target[self.handle] += offset
        clock = time.perf_counter()
        try:
            result = self.live.update(target, boundary_normals=self.normals)
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
            self.positions, self.offset = positions, offset
        return Frame(offset, converged, cold, steps, seconds, message, 1, folds)

    def drag(self, offset, frames):
        """Reach ``offset`` in ``frames`` equal steps (a script's drag); return the last :class:`Frame`."""
        frames = max(int(frames), 1)
        offset = np.asarray(offset, dtype=np.float64)
        last = None
        for k in range(1, frames + 1):
            last = self.frame(offset * (k / frames))
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
