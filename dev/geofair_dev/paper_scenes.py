"""The paper's free-form design scenes: the cylinder blend (Figs. 1, 2) and the
tetrathing (Fig. 8) of Schneider & Kobbelt 2001.

Both are defined by boundary circles with G1 data only: the positions of the circle
samples and the unit normals of a cylinder through them (radial, perpendicular to the
circle's axis).  The free vertices between the circles form *junctions*: one sphere
through three circles with the three caps beyond the circles cut away (a pair of pants).
The sphere is only the start mesh M_0, which fixes the connectivity and the conformal
weights of section 7.3; the faired surface is decided by the circles and their normals.

- ``cylinder_blend``: three cylinders of radius r whose axes lie in the xy-plane at
  120 degrees, each circle at distance ``distance`` from the origin; one junction centred
  at the origin.  Short cylinder stubs outside the circles are fixed vertices (a second
  fixed ring for linear schemes such as CGAL's ``fair``, and the surrounding surface in
  pictures).  Optionally, like the paper's Fig. 1a, a rectangular patch of the sphere is
  meshed as a finer regular grid, which breaks the mesh's symmetry while the boundary
  data keep theirs.
- ``tetrathing``: a closed genus-3 surface, tubes along the six edges of a regular
  tetrahedron: the six circles sit at the edge midpoints (the points +-s e_x, +-s e_y,
  +-s e_z), perpendicular to their edges; each of the four tetrahedron vertices carries a
  junction of the three circles of its edges.  Every circle sample is a fixed vertex
  shared by two junctions, so ``geofair.fair`` needs ``boundary_normals``.

Meshing: free vertices are a Fibonacci lattice on the sphere (jittered by ``jitter``
spacings, seeded), minus the caps and a margin of 0.6 spacings around them, triangulated
with the exact circle samples by their convex hull (a Delaunay triangulation on the
sphere); the flat cap facets are dropped.  Points of slivers are relaxed towards their
neighbours until no triangle angle is below ``MIN_ANGLE_DEG`` (they stay on the sphere).
Circle samples are at angles 2 pi j / n from a direction chosen symmetrically, so the set
of samples is mapped onto itself by every symmetry of the configuration
(``PaperScene.symmetries``).

Normals: exact unit normals, outward (away from the solid), at every vertex: radial from
the cylinder axis at circle samples and stub vertices (the G1 data), radial from the
junction's sphere centre at free vertices (exact for M_0).

Only numpy and scipy.spatial are used.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial import ConvexHull

from geofair_dev.scenes import edges, face_normals, triangle_angles

__all__ = ["MIN_ANGLE_DEG", "Circle", "PaperScene", "cylinder_blend", "tetrathing", "tetrahedral_group"]

MIN_ANGLE_DEG = 15.0
"""Smallest triangle angle (degrees) of every mesh made here."""

_MARGIN = 0.6  # free lattice points keep this many spacings from the caps (and the patch)


@dataclass(frozen=True, eq=False)
class Circle:
    """A boundary circle: centre (3,), unit axis (3,) (the cylinder's direction), radius."""

    centre: np.ndarray
    axis: np.ndarray
    radius: float


@dataclass(eq=False)
class PaperScene:
    """A design scene of the paper, ready for ``geofair.fair``.

    Attributes:
        name: e.g. ``"cylinder_blend(920)"``.
        vertices: (n, 3) float64, the start mesh M_0 (free vertices on the junction
            spheres, circle samples exact).
        faces: (m, 3) int64, triangles oriented counter-clockwise seen from outside.
        free: (n,) bool, the vertices the fairing moves.
        normals: (n, 3) float64 exact outward unit normals (see the module docstring);
            the rows at circle samples are the G1 boundary normals.
        circles: the boundary circles.
        on_circle: (n,) int64, index into `circles` of a vertex that is a circle sample,
            -1 elsewhere.
        symmetries: (g, 3, 3) float64 orthogonal matrices that map the circles, their
            samples and normals onto themselves (the faired surface must keep them).
        region_vertices: number of vertices of the faired region: free vertices and
            circle samples (the paper's vertex count of the blend).
    """

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    free: np.ndarray
    normals: np.ndarray
    circles: list[Circle]
    on_circle: np.ndarray
    symmetries: np.ndarray
    region_vertices: int = field(init=False)

    def __post_init__(self):
        self.region_vertices = int(self.free.sum() + (self.on_circle >= 0).sum())

    @property
    def n_free(self) -> int:
        """Number of free vertices."""
        return int(self.free.sum())

    @property
    def region_faces(self) -> np.ndarray:
        """(k, 3) int64, the triangles with a free vertex (the faired surface)."""
        return self.faces[self.free[self.faces].any(axis=1)]


# --------------------------------------------------------------------------------------
# Symmetry groups


def tetrahedral_group(reflections: bool = True) -> np.ndarray:
    """The symmetries of the regular tetrahedron with vertices (1,1,1), (1,-1,-1),
    (-1,1,-1), (-1,-1,1): signed permutation matrices whose signs multiply to +1.

    Returns (24, 3, 3) float64 (T_d, with the 12 improper ones), or (12, 3, 3) (the
    rotation group T) with ``reflections=False``; the identity comes first.
    """
    out = []
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1.0, -1.0), repeat=3):
            if math.prod(signs) < 0:
                continue
            m = np.zeros((3, 3))
            m[range(3), perm] = signs
            if reflections or np.linalg.det(m) > 0:
                out.append(m)
    return np.array(out)


def _dihedral_group(axes_in_plane: int) -> np.ndarray:
    """D_kh about z with a mirror plane containing +y: the symmetries of k cylinders in
    the xy-plane at 360/k degrees, the first along +y.  (4k, 3, 3) float64."""
    k, out = axes_in_plane, []
    for i in range(k):
        c, s = math.cos(2 * math.pi * i / k), math.sin(2 * math.pi * i / k)
        rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        for mirror_x in (1.0, -1.0):
            for mirror_z in (1.0, -1.0):
                out.append(rot @ np.diag([mirror_x, 1.0, mirror_z]))
    return np.array(out)


# --------------------------------------------------------------------------------------
# Building blocks


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _circle_samples(circle: Circle, first: np.ndarray, n: int):
    """n samples at angles 2 pi j / n from the unit direction `first` (perpendicular to
    the axis), and their radial unit normals; (n, 3) each."""
    e1 = _unit(first - np.dot(first, circle.axis) * circle.axis)
    e2 = np.cross(circle.axis, e1)
    t = 2 * math.pi * np.arange(n) / n
    radial = np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2
    return circle.centre + circle.radius * radial, radial


def _fibonacci(n, jitter, rng):
    """n Fibonacci-lattice unit vectors, each jittered by up to `jitter` spacings."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    phi = i * math.pi * (3 - math.sqrt(5))
    d = np.column_stack([np.sqrt(1 - z * z) * np.cos(phi), np.sqrt(1 - z * z) * np.sin(phi), z])
    if jitter > 0:
        step = math.sqrt(4 * math.pi / n)
        d += jitter * step * np.cbrt(rng.uniform(size=(n, 1))) * _unit(rng.normal(size=(n, 3)))
    return _unit(d)


@dataclass
class _Patch:
    """A rectangle of the unit sphere in gnomonic coordinates around `centre` (unit):
    |a| <= half[0], |b| <= half[1] in the tangent frame (t1, t2); grid spacing `step`
    (two values, in units of the lattice spacing)."""

    centre: np.ndarray
    half: tuple[float, float]
    step: tuple[float, float]

    def frame(self):
        t1 = _unit(np.cross([0.0, 0.0, 1.0], self.centre))
        return t1, np.cross(self.centre, t1)

    def coords(self, d):  # gnomonic (a, b) of unit vectors d; nan behind the tangent plane
        t1, t2 = self.frame()
        w = d @ self.centre
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(w[:, None] > 0, np.column_stack([d @ t1, d @ t2]) / w[:, None], np.nan)

    def inside(self, d, margin):
        ab = self.coords(d)
        return (np.abs(ab[:, 0]) <= self.half[0] + margin) & (np.abs(ab[:, 1]) <= self.half[1] + margin)

    def grid(self, h):
        t1, t2 = self.frame()
        a = np.linspace(-self.half[0], self.half[0], max(2, round(2 * self.half[0] / (self.step[0] * h))) + 1)
        b = np.linspace(-self.half[1], self.half[1], max(2, round(2 * self.half[1] / (self.step[1] * h))) + 1)
        A, B = np.meshgrid(a, b, indexing="ij")
        return _unit(self.centre + A.ravel()[:, None] * t1 + B.ravel()[:, None] * t2)


def _junction_directions(axes, cap_angle, n_free, jitter, rng, patch=None):
    """Free unit directions on a sphere outside the caps around `axes` (k, 3) of half-angle
    `cap_angle` (radians): about n_free of them.  Returns (directions, fixed_in_place)
    where fixed_in_place marks the patch grid (never relaxed), and the spacing h (on the
    unit sphere)."""
    cos_keep = None
    n_total = n_free
    for _ in range(8):  # match the count of kept lattice points (and grid points)
        h = math.sqrt(8 * math.pi / (math.sqrt(3) * n_total))  # hexagonal spacing, unit sphere
        cos_keep = math.cos(cap_angle + _margin(axes, cap_angle, h))
        d = _fibonacci(n_total, 0.0, rng)
        keep = (d @ axes.T < cos_keep).all(axis=1)
        count = np.count_nonzero(keep)
        if patch is not None:
            count += len(patch.grid(h)) - np.count_nonzero(keep & patch.inside(d, 0.0))
        n_total = max(8, round(n_total * n_free / max(count, 1)))
    h = math.sqrt(8 * math.pi / (math.sqrt(3) * n_total))
    cos_keep = math.cos(cap_angle + _margin(axes, cap_angle, h))
    d = _fibonacci(n_total, jitter, rng)
    keep = (d @ axes.T < cos_keep).all(axis=1)
    grid = np.zeros((0, 3))
    if patch is not None:
        grid = patch.grid(h)
        keep &= ~patch.inside(d, _MARGIN * h)
    d = d[keep]
    # a coarse lattice may leave the narrow gap between two caps empty: bridge it
    for i, j in itertools.combinations(range(len(axes)), 2):
        mid = _unit(axes[i] + axes[j])
        if len(d) == 0 or (d @ mid).max() < math.cos(h / 2):
            d = np.concatenate([d, mid[None]])
    d = np.concatenate([grid, d])
    return d, np.arange(len(d)) < len(grid), h, cos_keep


def _margin(axes, cap_angle, h):
    """Angle kept free of lattice points around the caps: 0.6 spacings, or a quarter of
    the narrowest gap between two caps if that is less."""
    gap = min(math.acos(np.clip(a @ b, -1.0, 1.0)) for a, b in itertools.combinations(axes, 2)) - 2 * cap_angle
    return min(_MARGIN * h, gap / 4)


def _hull_faces(dirs, movable, rim, cos_keep, axes):
    """Convex hull of unit vectors `dirs`, with the flat cap facets (all three corners on
    one circle, `rim` (k,) circle index or -1) removed; a triangle between the samples of
    two circles gets a free vertex at its centre (appended to `dirs`).  Points of triangles with an angle
    below MIN_ANGLE_DEG + 2 that are `movable` are relaxed towards their neighbours (kept
    on the sphere and out of the caps).  Returns (dirs, faces)."""
    dirs, movable, rim = dirs.copy(), movable.copy(), rim.copy()
    for _ in range(60):
        s = ConvexHull(dirs).simplices.astype(np.int64)
        r = rim[s]
        s = s[~((r[:, 0] >= 0) & (r[:, 0] == r[:, 1]) & (r[:, 1] == r[:, 2]))]
        bridge = (rim[s] >= 0).all(axis=1)  # spans two circles: give it a free vertex
        if bridge.any():
            dirs = np.concatenate([dirs, _unit(dirs[s[bridge]].sum(axis=1))])
            movable = np.concatenate([movable, np.ones(bridge.sum(), bool)])
            rim = np.concatenate([rim, np.full(bridge.sum(), -1)])
            continue
        bad = (triangle_angles(dirs, s) < MIN_ANGLE_DEG + 2).any(axis=1)
        move = np.unique(s[bad])
        move = move[movable[move]]
        if len(move) == 0:
            break
        e = edges(s)
        e = np.concatenate([e, e[:, ::-1]])
        n = len(dirs)
        mean = np.stack([np.bincount(e[:, 0], dirs[e[:, 1], c], minlength=n) for c in range(3)], 1)
        mean /= np.maximum(np.bincount(e[:, 0], minlength=n), 1)[:, None]
        trial = _unit(0.5 * (dirs[move] + mean[move]))
        ok = (trial @ axes.T < cos_keep).all(axis=1)
        dirs[move[ok]] = trial[ok]
    return dirs, s


def _orient(vertices, normals, faces):
    """Orient every face along the vertex normals."""
    bad = np.einsum("ij,ij->i", face_normals(vertices, faces), normals[faces].sum(axis=1)) < 0
    faces = faces.copy()
    faces[bad] = faces[bad][:, ::-1]
    return faces


def _junction(centre, circles, circle_ids, samples, n_free, jitter, rng, patch=None):
    """Faces and free vertices of the junction sphere through `circles`.

    `samples[c]` are the global vertex ids of circle c's samples, `circle_ids` the global
    index of each of `circles`.  Returns (free positions (k, 3), free normals (k, 3),
    faces (m, 3) in local numbering: circle samples first (in the order of circle_ids),
    then the free vertices; the caller maps them)."""
    c0 = circles[0]
    R = math.hypot(np.linalg.norm(c0.centre - centre), c0.radius)
    axes = np.array([_unit(c.centre - centre) for c in circles])
    cap = math.atan2(c0.radius, np.linalg.norm(c0.centre - centre))
    free_dirs, in_grid, h, cos_keep = _junction_directions(axes, cap, n_free, jitter, rng, patch)
    rim_pts = np.concatenate([samples[c][1] for c in circle_ids])
    rim = np.concatenate([np.full(len(samples[c][1]), k) for k, c in enumerate(circle_ids)])
    dirs = np.concatenate([_unit(rim_pts - centre), free_dirs])
    rim = np.concatenate([rim, np.full(len(free_dirs), -1)])
    movable = np.concatenate([np.zeros(len(rim_pts), bool), ~in_grid])
    dirs, faces = _hull_faces(dirs, movable, rim, cos_keep, axes)
    free_dirs = dirs[len(rim_pts) :]
    return centre + R * free_dirs, free_dirs, faces, len(rim_pts)


def _assemble(name, fixed_pts, fixed_normals, on_circle, junctions, circles, symmetries, extra_faces=()):
    """Global arrays from the fixed vertices and the junctions' local meshes."""
    vertices, normals, faces = [fixed_pts], [fixed_normals], list(extra_faces)
    n = len(fixed_pts)
    for free_pts, free_normals, local_faces, rim_ids in junctions:
        ids = np.concatenate([rim_ids, n + np.arange(len(free_pts))])
        vertices.append(free_pts)
        normals.append(free_normals)
        faces.append(ids[local_faces])
        n += len(free_pts)
    vertices, normals = np.concatenate(vertices), np.concatenate(normals)
    faces = _orient(vertices, normals, np.concatenate(faces).astype(np.int64))
    free = np.arange(len(vertices)) >= len(fixed_pts)
    on_circle = np.concatenate([on_circle, np.full(len(vertices) - len(fixed_pts), -1)])
    return PaperScene(name, vertices, faces, free, normals, circles, on_circle.astype(np.int64), symmetries)


# --------------------------------------------------------------------------------------
# The scenes


def cylinder_blend(
    n_free: int = 824,
    circle_samples: int = 32,
    radius: float = 1.0,
    distance: float = 1.5,
    irregular_patch: bool = True,
    stub_length: float | None = None,
    jitter: float = 0.2,
    seed: int = 0,
) -> PaperScene:
    """Three cylinders of `radius` in the xy-plane at 120 degrees (the first along +y),
    cut by circles at `distance` from the origin, and the blend between them (Figs. 1, 2).

    The region has about `n_free` free vertices and 3 * `circle_samples` fixed circle
    samples: the paper's fine mesh is ``n_free=824, circle_samples=32`` (920 region
    vertices), the coarse one ``n_free=82, circle_samples=12`` (118).  The start mesh is the
    sphere of radius sqrt(distance^2 + radius^2) about the origin (it contains the
    circles).  `irregular_patch`: a rectangle of the upper front of the sphere, between
    the first two cylinders, is meshed as a regular grid of half the lattice spacing
    (rectangular cells, 0.5 x 0.7 spacings), as in Fig. 1a.  Each cylinder continues
    beyond its circle by a fixed stub of length `stub_length` (default `radius`, at least
    two rings) meshed with the circle's samples.
    """
    if distance <= radius / math.tan(math.pi / 3):
        raise ValueError("cylinder_blend: the circles overlap; make distance larger")
    stub = radius if stub_length is None else stub_length
    rng = np.random.default_rng(seed)
    circles = []
    for k in range(3):
        t = math.pi / 2 + 2 * math.pi * k / 3
        axis = np.array([math.cos(t), math.sin(t), 0.0])
        circles.append(Circle(distance * axis, axis, float(radius)))
    spacing = 2 * math.pi * radius / circle_samples
    rings = max(2, round(stub / spacing))
    pts, nrm, on, faces, samples = [], [], [], [], {}
    n = 0
    for k, c in enumerate(circles):
        ring_ids = []
        for i in range(rings + 1):  # ring 0 is the circle
            p, q = _circle_samples(c, np.array([0.0, 0.0, 1.0]), circle_samples)
            pts.append(p + (i * stub / rings) * c.axis)
            nrm.append(q)
            on.append(np.full(circle_samples, k if i == 0 else -1))
            ring_ids.append(n + np.arange(circle_samples))
            n += circle_samples
        samples[k] = (ring_ids[0], pts[-rings - 1])
        for i in range(rings):
            a, b = ring_ids[i], ring_ids[i + 1]
            a1, b1 = np.roll(a, -1), np.roll(b, -1)
            if i % 2 == 0:
                faces += [np.column_stack([a, a1, b1]), np.column_stack([a, b1, b])]
            else:
                faces += [np.column_stack([a, a1, b]), np.column_stack([a1, b1, b])]
    fixed_pts, fixed_nrm = np.concatenate(pts), np.concatenate(nrm)
    patch = None
    if irregular_patch:
        t = math.pi / 2 + math.pi / 3  # between the first two cylinders, above the plane
        patch = _Patch(_unit(np.array([math.cos(t), math.sin(t), 0.9])), (0.35, 0.25), (0.5, 0.7))
    free_pts, free_nrm, local, n_rim = _junction(np.zeros(3), circles, [0, 1, 2], samples, n_free, jitter, rng, patch)
    rim_ids = np.concatenate([samples[k][0] for k in range(3)])
    name = f"cylinder_blend({len(free_pts) + 3 * circle_samples})"
    return _assemble(
        name, fixed_pts, fixed_nrm, np.concatenate(on), [(free_pts, free_nrm, local, rim_ids)],
        circles, _dihedral_group(3), faces,
    )  # fmt: skip


TETRAHEDRON = np.array([[1.0, 1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [-1.0, -1.0, 1.0]])
"""Vertices of the tetrahedron of ``tetrathing`` (scale 1), the junction centres."""


def tetrathing(
    n_vertices: int = 13308,
    circle_samples: int | None = None,
    scale: float = 1.0,
    radius: float = 0.55,
    jitter: float = 0.2,
    seed: int = 0,
) -> PaperScene:
    """The tetrathing of Fig. 8: tubes along the six edges of the tetrahedron
    ``scale * TETRAHEDRON`` (edge length 2 sqrt(2) scale), defined by six circles of
    radius ``radius * scale`` at the edge midpoints, perpendicular to the edges.

    About `n_vertices` vertices in all (the paper's 500 and 13308); `circle_samples` per
    circle defaults to the free lattice spacing (at least 8).  Closed genus-3 mesh: every
    vertex but the circle samples is free, so pass ``normals`` as ``boundary_normals``.
    """
    s, rho = float(scale), float(radius) * float(scale)
    half_edge = s * math.sqrt(2)
    if rho >= half_edge * math.tan(math.pi / 6):
        raise ValueError("tetrathing: the circles of one junction overlap; make radius smaller")
    rng = np.random.default_rng(seed)
    centres = s * TETRAHEDRON
    pairs = list(itertools.combinations(range(4), 2))
    circles = [Circle((centres[a] + centres[b]) / 2, _unit(centres[b] - centres[a]), rho) for a, b in pairs]
    R = math.hypot(half_edge, rho)
    cap = math.atan2(rho, half_edge)
    area = 4 * math.pi * R * R * (1 - 1.5 * (1 - math.cos(cap)))  # one junction's sphere part
    if circle_samples is None:  # spacing of the free lattice at n_vertices
        h = math.sqrt(2 * 4 * area / (math.sqrt(3) * n_vertices))
        circle_samples = max(8, round(2 * math.pi * rho / h))
    n_free = round((n_vertices - 6 * circle_samples) / 4)
    pts, nrm, samples = [], [], {}
    for k, c in enumerate(circles):  # first sample: away from the tetrahedron's centre
        p, q = _circle_samples(c, c.centre, circle_samples)
        pts.append(p)
        nrm.append(q)
        samples[k] = (k * circle_samples + np.arange(circle_samples), p)
    junctions = []
    for v in range(4):
        ids = [k for k, pair in enumerate(pairs) if v in pair]
        free_pts, free_nrm, local, _ = _junction(
            centres[v], [circles[k] for k in ids], ids, samples, n_free, jitter, rng
        )
        junctions.append((free_pts, free_nrm, local, np.concatenate([samples[k][0] for k in ids])))
    on = np.repeat(np.arange(6), circle_samples)
    name = f"tetrathing({6 * circle_samples + sum(len(j[0]) for j in junctions)})"
    return _assemble(name, np.concatenate(pts), np.concatenate(nrm), on, junctions, circles, tetrahedral_group())
