"""Analytic test scenes for the fairing tests.

Every scene is a triangle mesh whose vertices lie *exactly* (to rounding) on a surface
with known geometry, together with the exact unit normals and a distance function, so a
test can measure how far a faired mesh drifted from the surface that solves
Delta_B H = 0 (Schneider & Kobbelt 2001, eq. (4)): spheres and cylinders (constant H),
the catenoid (a minimal surface, H = 0) and the plane.

Patches (``sphere_cap``, ``cylinder_patch``, ``catenoid_patch``, ``plane_disk``) are
disks meshed in a 2D parameter domain and mapped to the surface.  Their *free* vertices
(the interior, what the fairing may move) are surrounded by fixed vertices that carry the
G1 boundary condition: positions and normals.  With ``boundary_rings=1`` the fixed
vertices are exactly the samples of the region's boundary curve; every extra ring adds a
layer of fixed vertices outside it (for fairing schemes that want outside neighbours).

Closed/open test meshes for curvature estimates: ``sphere`` and ``cylinder_tube``.

``uv_sphere``: Blender's UV sphere (``primitive_uv_sphere_add``), its quads split into triangles.

Meshing, ``irregular=False``: structured meshes (concentric rings of 6k vertices on
disks, a grid with row-alternating diagonals on rectangles; both have interior valence
6).  ``irregular=True``: a hexagonal lattice jittered by up to 0.45 spacings plus exact
boundary samples at the same spacing, Delaunay-triangulated in the parameter domain
(seeded, reproducible); the few points of slivers are relaxed locally, so about half
of the interior vertices keep a valence other than 6 (4..9) while the smallest triangle
angle on the surface is at least ``MIN_ANGLE_DEG``.

Sign convention of ``Scene.mean_curvature``: geofair's, H = (k1 + k2) / 2 where a normal
curvature is positive when the surface bends away from ``normals``, so the sphere of
radius r with outward normals has H = 1/r and the cylinder H = 1/(2r).

Only numpy and scipy.spatial are used.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.spatial import ConvexHull, Delaunay

__all__ = [
    "MIN_ANGLE_DEG",
    "Scene",
    "sphere_cap",
    "cylinder_patch",
    "catenoid_patch",
    "plane_disk",
    "sphere",
    "cylinder_tube",
    "edges",
    "valences",
    "border_mask",
    "face_normals",
    "triangle_angles",
    "torus_patch",
    "squashed_lattice",
]

MIN_ANGLE_DEG = 18.0
"""Smallest triangle angle (degrees, measured on the surface) of every irregular mesh."""

_JITTER = 0.45  # lattice jitter radius, in lattice spacings
_MARGIN = 0.6  # interior samples keep this many spacings from the boundary curve

Points = Callable[[np.ndarray], np.ndarray]


# --------------------------------------------------------------------------------------
# The scene


@dataclass(eq=False)
class Scene:
    """A test mesh on an analytic surface.

    Attributes:
        name: short description, e.g. ``"sphere_cap(irregular)"``.
        vertices: (n, 3) float64, exact surface positions.
        faces: (m, 3) int64, triangles; the right-hand face normal agrees with `normals`.
        free: (n,) bool, vertices the fairing may move (the interior of the region).
        normals: (n, 3) float64, exact outward unit surface normals.
        uv: (n, 2) float64, parameter-domain coordinates the mesh was built in.
        distance: (k, 3) points -> (k,) float64, signed distance-like error to the surface
            (exact distance for plane, sphere, cylinder; first-order for the catenoid).
        boundary_distance: (k, 3) points on the surface -> (k,) float64, signed distance
            to the region's boundary curve (negative inside, 0 on it, positive outside;
            -inf everywhere for a closed surface).
        mean_curvature: exact H of the surface (constant), see the module's sign note.
        size: characteristic length of the patch (geodesic radius of a cap, radius of a
            disk, half the smaller side of a rectangle, radius of a sphere/tube).
        bump: (n,) float64, smooth profile used by `disturbed`, 1 near the centre, 0 on
            the boundary curve, 0 at fixed vertices.
    """

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    free: np.ndarray
    normals: np.ndarray
    uv: np.ndarray
    distance: Points
    boundary_distance: Points
    mean_curvature: float
    size: float
    bump: np.ndarray

    @property
    def n_free(self) -> int:
        """Number of free vertices."""
        return int(self.free.sum())

    def disturbed(self, seed: int = 0, amplitude: float = 0.1, noise: float = 0.3) -> np.ndarray:
        """A start mesh for fairing: free vertices pushed along their normals.

        Each free vertex moves by ``amplitude * size * (bump + noise * xi) * normal`` with
        xi uniform in [-1, 1] (seeded): a smooth bulge (negative `amplitude` flattens a
        convex patch) plus noise.  Fixed rows are bit-identical copies.

        Returns:
            (n, 3) float64, a new array.
        """
        rng = np.random.default_rng(seed)
        xi = rng.uniform(-1.0, 1.0, len(self.vertices))
        t = amplitude * self.size * (self.bump + noise * xi)
        out = self.vertices.copy()
        out[self.free] += t[self.free, None] * self.normals[self.free]
        return out


# --------------------------------------------------------------------------------------
# Small mesh utilities (also used by the tests)


def edges(faces: np.ndarray) -> np.ndarray:
    """Unique undirected edges, (e, 2) int64 with e[:, 0] < e[:, 1]."""
    e = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    return np.unique(e, axis=0)


def valences(faces: np.ndarray, n: int) -> np.ndarray:
    """Number of edge neighbours per vertex, (n,) int64."""
    return np.bincount(edges(faces).ravel(), minlength=n)


def border_mask(faces: np.ndarray, n: int) -> np.ndarray:
    """(n,) bool, vertices on a border edge (an edge with exactly one face)."""
    e = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(e, axis=0, return_counts=True)
    mask = np.zeros(n, bool)
    mask[uniq[count == 1].ravel()] = True
    return mask


def face_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Right-hand unit face normals, (m, 3) float64."""
    p = vertices[faces]
    c = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    return c / np.linalg.norm(c, axis=1, keepdims=True)


def triangle_angles(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Interior angles in degrees, (m, 3) float64; column k is the angle at faces[:, k]."""
    p = vertices[faces]
    out = np.empty(faces.shape)
    for k in range(3):
        a = p[:, (k + 1) % 3] - p[:, k]
        b = p[:, (k + 2) % 3] - p[:, k]
        cos = np.einsum("ij,ij->i", a, b) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
        out[:, k] = np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
    return out


# --------------------------------------------------------------------------------------
# Parameter domains: a disk |uv| <= R or a rectangle |u| <= U, |v| <= V


@dataclass
class _Disk:
    R: float
    ring_radius: Callable[[float], float]  # regular meshes: ring k of K lies at ring_radius(k/K)

    def sd(self, uv):  # signed distance to the boundary circle, (k,)
        return np.hypot(uv[:, 0], uv[:, 1]) - self.R

    def outline(self, d, h):  # samples of the boundary offset outwards by d, spacing ~h
        n = max(6, round(2 * math.pi * (self.R + d) / h))
        t = 2 * math.pi * np.arange(n) / n
        return (self.R + d) * np.column_stack([np.cos(t), np.sin(t)])

    def half_extent(self):
        return self.R, self.R

    def bump(self, uv):
        return 1.0 - (uv[:, 0] ** 2 + uv[:, 1] ** 2) / self.R**2


@dataclass
class _Rect:
    U: float
    V: float

    def sd(self, uv):
        return np.maximum(np.abs(uv[:, 0]) - self.U, np.abs(uv[:, 1]) - self.V)

    def outline(self, d, h):
        U, V = self.U + d, self.V + d
        corners = np.array([[-U, -V], [U, -V], [U, V], [-U, V]])
        pts = []
        for a, b in zip(corners, np.roll(corners, -1, axis=0), strict=True):
            n = max(1, round(np.linalg.norm(b - a) / h))
            t = np.arange(n)[:, None] / n
            pts.append(a + t * (b - a))
        return np.concatenate(pts)

    def half_extent(self):
        return self.U, self.V

    def bump(self, uv):
        return (1.0 - (uv[:, 0] / self.U) ** 2) * (1.0 - (uv[:, 1] / self.V) ** 2)


def squashed_lattice(nu: int, width: float, squash: float = 4.0):
    """A mesh of obtuse triangles in the (u, v) plane: a hexagonal lattice of nu + 1 columns
    over u in [-width/2, width/2] and 2 nu + 1 rows, squashed `squash` times along v
    (centred on v = 0), triangulated as the unsquashed lattice. Nearly every triangle has
    the apex angle 2 atan(squash / sqrt 3) (133 degrees for 4); the shifted rows are
    clipped to the width at the sides. Returns uv (n, 2) float64 and counter-clockwise
    faces (m, 3) int64."""
    hu = width / nu
    hv = hu * math.sqrt(3) / 2 / squash
    nv = 2 * nu
    j, i = np.meshgrid(np.arange(nv + 1), np.arange(nu + 1), indexing="ij")
    u = np.clip(-width / 2 + (i + 0.5 * (j % 2)) * hu, -width / 2, width / 2).ravel()
    v = (j * hv - nv * hv / 2).ravel()
    uv = np.column_stack([u, v])
    return uv, _ccw(uv, Delaunay(uv * [1.0, squash]).simplices.astype(np.int64))


def _hex_lattice(U, V, h, rng=None):
    """Hexagonal lattice (spacing h) covering [-U, U] x [-V, V], optionally jittered."""
    dv = h * math.sqrt(3) / 2
    rows = np.arange(-math.ceil(V / dv) - 1, math.ceil(V / dv) + 2)
    cols = np.arange(-math.ceil(U / h) - 1, math.ceil(U / h) + 2)
    j, i = np.meshgrid(rows, cols, indexing="ij")
    uv = np.column_stack([(i + 0.5 * (j % 2)).ravel() * h, j.ravel() * dv])
    if rng is not None:
        r = _JITTER * h * np.sqrt(rng.uniform(size=len(uv)))
        a = rng.uniform(0, 2 * math.pi, len(uv))
        uv += np.column_stack([r * np.cos(a), r * np.sin(a)])
    return uv


def _ccw(uv, faces):
    """Flip the triangles that are clockwise in the (u, v) plane."""
    p = uv[faces]
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    cw = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] < 0
    faces = faces.copy()
    faces[cw] = faces[cw][:, ::-1]
    return faces


def _irregular_domain(dom, n_free, rings, rng):
    """Jittered lattice + exact boundary samples (the fixed vertices), Delaunay in the
    domain.  Returns uv (n, 2), faces (m, 3) counter-clockwise in uv, free (n,) bool.
    """
    U, V = dom.half_extent()
    h = math.sqrt(4 * U * V / n_free)  # first guess, then fix the unjittered count
    for _ in range(6):
        uv = _hex_lattice(U, V, h)
        count = np.count_nonzero(dom.sd(uv) < -_MARGIN * h)
        h *= math.sqrt(count / n_free)
    inner = _hex_lattice(U, V, h, rng)
    inner = inner[dom.sd(inner) < -_MARGIN * h]
    layers = [dom.outline(k * h, h) for k in range(rings)]
    padding = np.concatenate([dom.outline((rings + k) * h, h) for k in range(2)])
    uv = np.concatenate([inner, *layers])
    free = np.arange(len(uv)) < len(inner)
    # relaxed points stay > h/2 from the boundary, so the boundary edges stay Delaunay
    return _triangulate(uv, padding, free, lambda p: dom.sd(p) < -0.55 * h)


def _triangulate(uv, padding, movable, inside, period=None):
    """Delaunay triangulation of the mesh points `uv` (k, 2), with `padding` (p, 2)
    points that only keep the convex hull away from the mesh.  Movable points whose
    triangles have an angle below MIN_ANGLE_DEG + 2 are moved halfway to the mean of
    their neighbours and everything is re-triangulated, until no such triangle is left
    (this keeps most of the jitter, hence the valence spread, but removes slivers).
    Points that stay stuck in a sliver (a tight cluster at the boundary) are dropped.
    `inside(uv) -> (k,) bool` keeps relaxed points in the domain.  With `period`, u is
    periodic: the strip is padded by shifted copies and each triangle kept once.

    Returns uv (k', 2), faces (m, 3) int64 indexing it, counter-clockwise in the plane,
    and the movable mask (k',) of the remaining points.
    """
    uv, movable, k = uv.copy(), movable.copy(), len(uv)
    shifts = [0.0] if period is None else [0.0, -period, period]
    for it in range(30):
        base = np.concatenate([uv, padding])
        ext = np.concatenate([base + [s, 0.0] for s in shifts])
        owner = np.tile(np.arange(len(base)), len(shifts))
        s = Delaunay(ext).simplices.astype(np.int64)
        keep = (owner[s] < k).all(axis=1)
        if period:  # one copy of each triangle: the one whose centroid is in [0, P)
            cu = ext[s, 0].mean(axis=1)
            keep &= (cu >= 0) & (cu < period)
        flat = np.column_stack([ext, np.zeros(len(ext))])
        bad = keep & (triangle_angles(flat, s) < MIN_ANGLE_DEG + 2).any(axis=1)
        if not bad.any():
            break
        if it >= 10:  # stuck: drop a movable end of the shortest edge of each sliver
            t, p = owner[s[bad]], ext[s[bad]]
            c = np.linalg.norm(np.roll(p, -1, axis=1) - p, axis=2).argmin(axis=1)
            a, b = t[np.arange(len(t)), c], t[np.arange(len(t)), (c + 1) % 3]
            keep_pts = ~np.isin(np.arange(k), np.where(movable[a], a, b)[movable[a] | movable[b]])
            uv, movable, k = uv[keep_pts], movable[keep_pts], int(keep_pts.sum())
            continue
        if it >= 5:  # stuck (a cluster of points): relax the neighbourhood too
            bad |= np.isin(s, s[bad]).any(axis=1)
        move = np.unique(owner[s[bad]])
        move = move[move < k]
        move = move[movable[move]]
        # mean neighbour offset of the unshifted copies (each edge counted per triangle)
        mean = np.zeros((k, 2))
        for c in range(3):
            i, j, m = s[:, c], s[:, (c + 1) % 3], s[:, (c + 2) % 3]
            ok = i < k
            d = ext[j[ok]] + ext[m[ok]] - 2 * ext[i[ok]]
            mean += np.stack([np.bincount(i[ok], d[:, a], minlength=k) for a in (0, 1)], 1)
        mean /= np.maximum(2 * np.bincount(s[s < k], minlength=k), 1)[:, None]
        trial = uv[move] + 0.5 * mean[move]
        ok = inside(trial)
        uv[move[ok]] = trial[ok]
        if period:
            uv[:, 0] %= period
    return uv, owner[_ccw(ext, s[keep])], movable


def _zip(a, b):
    """Triangles between two closed rings of vertex ids starting at the same angle.

    Ring ``a`` has len(a) equally spaced vertices, ring ``b`` len(b); the next vertex is
    taken from the ring whose next angle is smaller, from the inner ring ``a`` on ties,
    which reproduces the hexagonal lattice for 6k and 6(k+1) vertices.
    """
    na, nb, i, j, out = len(a), len(b), 0, 0, []
    while i < na or j < nb:
        if j == nb or (i < na and (i + 1) * nb <= (j + 1) * na):
            out.append((a[i % na], a[(i + 1) % na], b[j % nb]))
            i += 1
        else:
            out.append((a[i % na], b[(j + 1) % nb], b[j % nb]))
            j += 1
    return out


def _regular_disk(dom, n_free, rings):
    """Concentric rings of 6k vertices: 1 + 3K(K-1) free vertices for K rings."""
    K = max(2, round(0.5 + math.sqrt(max(n_free - 1, 0) / 3 + 0.25)))
    uv, ids, faces = [np.zeros((1, 2))], [np.array([0])], []
    for k in range(1, K + rings):
        t = 2 * math.pi * np.arange(6 * k) / (6 * k)
        uv.append(dom.ring_radius(k / K) * np.column_stack([np.cos(t), np.sin(t)]))
        ids.append(ids[-1][-1] + 1 + np.arange(6 * k))
        if k == 1:
            faces += [(0, ids[1][s], ids[1][(s + 1) % 6]) for s in range(6)]
        else:
            faces += _zip(ids[k - 1], ids[k])
    uv = np.concatenate(uv)
    free = np.arange(len(uv)) < 1 + 3 * K * (K - 1)
    return uv, _ccw(uv, np.array(faces, np.int64)), free


def _grid_faces(nu, nv, periodic=False):
    """Triangles of an (nv+1) x (nu+1) vertex grid (row-major, id = j*(nu+1)+i), with
    the cell diagonal alternating from row to row (interior valence 6).  With
    `periodic`, column nu is identified with column 0 (the grid has nu columns)."""
    cols = nu if periodic else nu + 1
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="xy")
    i, j = i.ravel(), j.ravel()
    a, b = j * cols + i, j * cols + (i + 1) % cols
    c, d = a + cols, b + cols
    even = (j % 2 == 0)[:, None]
    t1 = np.where(even, np.column_stack([a, b, d]), np.column_stack([a, b, c]))
    t2 = np.where(even, np.column_stack([a, d, c]), np.column_stack([b, d, c]))
    return np.concatenate([t1, t2]).astype(np.int64)


def _regular_rect(dom, n_free, rings):
    """Square-ish grid over the rectangle, extended by rings-1 cells on every side."""
    # cells of side h with (2U/h - 1)(2V/h - 1) = n_free interior grid vertices
    s, p = dom.U + dom.V, dom.U * dom.V
    x = (s + math.sqrt(s * s + 4 * p * (n_free - 1))) / (4 * p)  # 1 / h
    nu, nv = max(2, round(2 * dom.U * x)), max(2, round(2 * dom.V * x))
    e = rings - 1
    u = np.linspace(-dom.U, dom.U, nu + 1)
    v = np.linspace(-dom.V, dom.V, nv + 1)
    du, dv = u[1] - u[0], v[1] - v[0]
    u = np.concatenate([u[0] - du * np.arange(e, 0, -1), u, u[-1] + du * np.arange(1, e + 1)])
    v = np.concatenate([v[0] - dv * np.arange(e, 0, -1), v, v[-1] + dv * np.arange(1, e + 1)])
    U, V = np.meshgrid(u, v, indexing="xy")
    uv = np.column_stack([U.ravel(), V.ravel()])
    Jg, Ig = np.meshgrid(np.arange(len(v)), np.arange(len(u)), indexing="ij")
    free = ((Ig > e) & (Ig < e + nu) & (Jg > e) & (Jg < e + nv)).ravel()
    faces = _grid_faces(len(u) - 1, len(v) - 1)
    return uv, _ccw(uv, faces), free


def _acceptable(vertices, faces, free, euler):
    """Irregular-mesh check: min angle, free vertices off the border, every vertex used,
    Euler characteristic V - E + F (1 for a disk, 0 for a tube, 2 for a sphere)."""
    n = len(vertices)
    return bool(
        triangle_angles(vertices, faces).min() >= MIN_ANGLE_DEG
        and not (border_mask(faces, n) & free).any()
        and np.bincount(faces.ravel(), minlength=n).all()
        and n - len(edges(faces)) + len(faces) == euler
    )


def _patch(name, dom, n_free, irregular, seed, rings, to_surface, surf, size, H):
    """Mesh `dom`, map it with `to_surface(uv) -> (points, normals)`, and assemble.

    `surf` is (distance, boundary_distance).
    """
    if rings < 1:
        raise ValueError("boundary_rings must be >= 1")
    rng = np.random.default_rng(seed)
    for _ in range(100):
        if irregular:
            uv, faces, free = _irregular_domain(dom, n_free, rings, rng)
        elif isinstance(dom, _Disk):
            uv, faces, free = _regular_disk(dom, n_free, rings)
        else:
            uv, faces, free = _regular_rect(dom, n_free, rings)
        vertices, normals = to_surface(uv)
        if not irregular or _acceptable(vertices, faces, free, euler=1):
            break
    else:  # pragma: no cover - would mean the sampling parameters are broken
        raise RuntimeError(f"{name}: no acceptable irregular mesh")
    faces = _orient(vertices, faces, normals)
    if (np.einsum("ij,ikj->ik", face_normals(vertices, faces), normals[faces]) <= 0).any():
        raise ValueError(f"{name}: folded mesh (do the boundary rings wrap around?)")
    bump = np.where(free, np.clip(dom.bump(uv), 0.0, None), 0.0)
    kind = "irregular" if irregular else "regular"
    return Scene(f"{name}({kind})", vertices, faces, free, normals, uv, *surf, H, size, bump)


def _orient(vertices, faces, normals):
    """Reverse all faces if they disagree with the vertex normals (the parameter map
    may reverse orientation); the consistent uv orientation is kept."""
    agree = np.einsum("ij,ij->i", face_normals(vertices, faces), normals[faces].sum(axis=1))
    return faces[:, ::-1].copy() if agree.sum() < 0 else faces


# --------------------------------------------------------------------------------------
# Patches


def sphere_cap(
    radius: float = 1.0,
    opening_angle: float = 60.0,
    n_free: int = 2000,
    irregular: bool = False,
    seed: int = 0,
    boundary_rings: int = 1,
    center=(0.0, 0.0, 0.0),
) -> Scene:
    """Cap of the sphere |p - center| = radius around +z.

    The region is the set of points whose angle to +z (seen from the centre) is below
    `opening_angle` (degrees, the polar angle of the boundary circle, so 60 gives a cap
    of area pi r^2 on the unit sphere).  Free vertices lie strictly inside; fixed
    vertices adjacent to them lie exactly on the boundary circle z = cz + r cos(angle).
    Built in stereographic coordinates (conformal, so irregular triangles keep their
    angles); regular meshes place ring k at polar angle k/K * opening_angle.
    Normals (p - center) / r, H = -1/r.
    """
    r, th0, c = float(radius), math.radians(opening_angle), np.asarray(center, float)

    def to_surface(uv):  # inverse stereographic projection from the south pole
        s = 4 * r * r / (4 * r * r + (uv**2).sum(axis=1))
        n = np.column_stack([uv * (s / r)[:, None], 2 * s - 1])
        return c + r * n, n

    def boundary_distance(p):
        d = np.asarray(p, float) - c
        return r * (np.arctan2(np.hypot(d[:, 0], d[:, 1]), d[:, 2]) - th0)

    dom = _Disk(2 * r * math.tan(th0 / 2), lambda t: 2 * r * math.tan(t * th0 / 2))
    return _patch(
        "sphere_cap", dom, n_free, irregular, seed, boundary_rings, to_surface,
        (_sphere_distance(c, r), boundary_distance), r * th0, 1.0 / r,
    )  # fmt: skip


def cylinder_patch(
    radius: float = 1.0,
    angle: float = 120.0,
    height: float | None = None,
    n_free: int = 2000,
    irregular: bool = False,
    seed: int = 0,
    boundary_rings: int = 1,
) -> Scene:
    """Patch of the cylinder x^2 + y^2 = r^2 (axis z) around +x.

    Region: polar angle in [-angle/2, angle/2] (degrees), z in [-height/2, height/2]
    (default height 2r).  Built in the isometric coordinates (r * phi, z).  Normals are
    radial, H = -1/(2r).
    """
    r = float(radius)
    hz = r if height is None else height / 2
    dom = _Rect(r * math.radians(angle) / 2, hz)

    def to_surface(uv):
        phi = uv[:, 0] / r
        n = np.column_stack([np.cos(phi), np.sin(phi), np.zeros(len(uv))])
        return np.column_stack([r * n[:, :2], uv[:, 1]]), n

    def distance(p):
        p = np.asarray(p, float)
        return np.hypot(p[:, 0], p[:, 1]) - r

    def boundary_distance(p):
        p = np.asarray(p, float)
        return dom.sd(np.column_stack([r * np.arctan2(p[:, 1], p[:, 0]), p[:, 2]]))

    return _patch(
        "cylinder_patch", dom, n_free, irregular, seed, boundary_rings, to_surface,
        (distance, boundary_distance), min(dom.U, dom.V), 0.5 / r,
    )  # fmt: skip


def catenoid_patch(
    a: float = 1.0,
    angle: float = 120.0,
    height: float | None = None,
    n_free: int = 2000,
    irregular: bool = False,
    seed: int = 0,
    boundary_rings: int = 1,
) -> Scene:
    """Patch of the catenoid x^2 + y^2 = (a cosh(z/a))^2 (a minimal surface, H = 0).

    Region: polar angle in [-angle/2, angle/2] (degrees) around +x, z in
    [-height/2, height/2] (default height 2a, so z in [-a, a]).  Built in the conformal
    coordinates (a * phi, z); the surface metric there is cosh(z/a)^2 times Euclidean, so
    triangles near z = +-a are about cosh(1) = 1.54 times larger than at z = 0.
    Normals point away from the axis: (cos phi, sin phi, -sinh(z/a)) / cosh(z/a).
    `distance` is (sqrt(x^2 + y^2) - a cosh(z/a)) / cosh(z/a), the signed distance to
    first order (error O(distance^2 / a)).
    """
    a = float(a)
    hz = a if height is None else height / 2
    dom = _Rect(a * math.radians(angle) / 2, hz)

    def to_surface(uv):
        phi, t = uv[:, 0] / a, uv[:, 1] / a
        ch = np.cosh(t)
        p = np.column_stack([a * ch * np.cos(phi), a * ch * np.sin(phi), uv[:, 1]])
        n = np.column_stack([np.cos(phi), np.sin(phi), -np.sinh(t)]) / ch[:, None]
        return p, n

    def distance(p):  # F / |grad F| for F = rho - a cosh(z/a): first-order exact
        p = np.asarray(p, float)
        ch = np.cosh(p[:, 2] / a)
        return (np.hypot(p[:, 0], p[:, 1]) - a * ch) / ch

    def boundary_distance(p):
        p = np.asarray(p, float)
        return dom.sd(np.column_stack([a * np.arctan2(p[:, 1], p[:, 0]), p[:, 2]]))

    return _patch(
        "catenoid_patch", dom, n_free, irregular, seed, boundary_rings, to_surface,
        (distance, boundary_distance), min(dom.U, dom.V), 0.0,
    )  # fmt: skip


def plane_disk(
    radius: float = 1.0,
    n_free: int = 2000,
    irregular: bool = False,
    seed: int = 0,
    boundary_rings: int = 1,
) -> Scene:
    """Disk x^2 + y^2 <= radius^2 in the plane z = 0; normals +z, H = 0."""
    R = float(radius)

    def to_surface(uv):
        n = np.zeros((len(uv), 3))
        n[:, 2] = 1.0
        return np.column_stack([uv, np.zeros(len(uv))]), n

    def distance(p):
        return np.asarray(p, float)[:, 2].copy()

    def boundary_distance(p):
        p = np.asarray(p, float)
        return np.hypot(p[:, 0], p[:, 1]) - R

    dom = _Disk(R, lambda t: R * t)
    return _patch(
        "plane_disk", dom, n_free, irregular, seed, boundary_rings, to_surface,
        (distance, boundary_distance), R, 0.0,
    )  # fmt: skip


# --------------------------------------------------------------------------------------
# Closed sphere and open tube, for curvature estimates


def _sphere_distance(c, r):
    return lambda p: np.linalg.norm(np.asarray(p, float) - c, axis=1) - r


def _no_boundary(p):
    return np.full(len(p), -np.inf)


def _icosphere_directions(n_vertices):
    """Unit vectors of a frequency-f geodesic icosphere (10 f^2 + 2 vertices) with f
    chosen to best match n_vertices, and its outward faces."""
    f = max(1, round(math.sqrt(max(n_vertices - 2, 10) / 10)))
    g = (1 + math.sqrt(5)) / 2
    ico = np.array([[-1, g, 0], [1, g, 0], [-1, -g, 0], [1, -g, 0], [0, -1, g], [0, 1, g],
                    [0, -1, -g], [0, 1, -g], [g, 0, -1], [g, 0, 1], [-g, 0, -1],
                    [-g, 0, 1]])  # fmt: skip
    tris = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
            (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
            (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]  # fmt: skip
    index, points, faces = {}, [], []

    def vid(corners, weights):  # shared edge/corner points get one id: exact integer keys
        key = tuple(sorted((c, w) for c, w in zip(corners, weights, strict=True) if w))
        if key not in index:
            index[key] = len(points)
            points.append(sum(w * ico[c] for c, w in key) / f)
        return index[key]

    for t in tris:
        v = {(i, j): vid(t, (f - i - j, i, j)) for i in range(f + 1) for j in range(f + 1 - i)}
        for i in range(f):
            for j in range(f - i):
                faces.append((v[i, j], v[i + 1, j], v[i, j + 1]))
                if i + j < f - 1:
                    faces.append((v[i + 1, j], v[i + 1, j + 1], v[i, j + 1]))
    d = np.array(points, float)
    return d / np.linalg.norm(d, axis=1, keepdims=True), np.array(faces, np.int64)


def _fibonacci_directions(n, rng):
    """n jittered Fibonacci-lattice unit vectors and their convex-hull triangles, relaxed
    locally like `_triangulate` until no angle is below MIN_ANGLE_DEG + 2."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    phi = i * math.pi * (3 - math.sqrt(5))
    d = np.column_stack([np.sqrt(1 - z * z) * np.cos(phi), np.sqrt(1 - z * z) * np.sin(phi), z])
    step = math.sqrt(4 * math.pi / n)  # mean spacing on the unit sphere
    d += _JITTER * step * np.cbrt(rng.uniform(size=(n, 1))) * _unit(rng.normal(size=(n, 3)))
    d = _unit(d)
    for _ in range(50):
        s = ConvexHull(d).simplices.astype(np.int64)
        move = np.unique(s[(triangle_angles(d, s) < MIN_ANGLE_DEG + 2).any(axis=1)])
        if len(move) == 0:
            break
        d[move] = _unit(0.5 * (d[move] + _neighbour_mean(d, s)[move]))
    return d, s


def _unit(v):
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def _neighbour_mean(points, faces):
    """(n, 3): the mean of each point's neighbours along the edges of `faces`."""
    n = len(points)
    e = edges(faces)
    e = np.concatenate([e, e[:, ::-1]])
    mean = np.stack([np.bincount(e[:, 0], points[e[:, 1], c], minlength=n) for c in range(3)], 1)
    return mean / np.bincount(e[:, 0], minlength=n)[:, None]


def sphere(
    radius: float = 1.0,
    n_vertices: int = 2000,
    irregular: bool = False,
    seed: int = 0,
    center=(0.0, 0.0, 0.0),
) -> Scene:
    """Closed sphere: all vertices are free (there is no boundary), H = -1/r.

    Regular: geodesic icosphere, 10 f^2 + 2 vertices with the frequency f closest to
    `n_vertices` (f need not be a power of two).  Irregular: `n_vertices` jittered
    Fibonacci points triangulated by their convex hull.  Faces oriented outward.
    `uv` holds the spherical coordinates (azimuth, polar angle) of the vertices.
    """
    r, c = float(radius), np.asarray(center, float)
    rng = np.random.default_rng(seed)
    for _ in range(100):
        if irregular:
            d, faces = _fibonacci_directions(n_vertices, rng)
        else:
            d, faces = _icosphere_directions(n_vertices)
        if not irregular or _acceptable(d, faces, np.zeros(len(d), bool), euler=2):
            break
    else:  # pragma: no cover
        raise RuntimeError("sphere: no acceptable irregular mesh")
    vertices = c + r * d
    faces = _orient_each(d, d, faces)
    uv = np.column_stack([np.arctan2(d[:, 1], d[:, 0]), np.arccos(np.clip(d[:, 2], -1, 1))])
    kind = "irregular" if irregular else "regular"
    return Scene(
        f"sphere({kind})", vertices, faces, np.ones(len(d), bool), d, uv,
        _sphere_distance(c, r), _no_boundary, 1.0 / r, r, 0.5 * (1 + d[:, 2]),
    )  # fmt: skip


def _orient_each(vertices, normals, faces):
    """Orient every face along the vertex normals (meshes built without a consistent
    parameter-domain orientation: convex hulls, seam-wrapped strips)."""
    bad = np.einsum("ij,ij->i", face_normals(vertices, faces), normals[faces].sum(axis=1)) < 0
    faces = faces.copy()
    faces[bad] = faces[bad][:, ::-1]
    return faces


def cylinder_tube(
    radius: float = 1.0,
    height: float = 2.0,
    n_vertices: int = 2000,
    irregular: bool = False,
    seed: int = 0,
) -> Scene:
    """Open tube x^2 + y^2 = r^2, z in [-height/2, height/2]; H = -1/(2r).

    Free vertices are the interior, the two border circles are fixed and sampled exactly
    on z = +-height/2.  Built in (r * phi, z) with phi periodic: regular = grid with
    row-alternating diagonals; irregular = jittered lattice, Delaunay-triangulated on the
    unwrapped strip padded by copies across the seam, keeping one copy of each triangle.
    Normals radial, outward.
    """
    r, hz = float(radius), height / 2
    P = 2 * math.pi * r
    x = (math.sqrt(P * P + 4 * P * height * n_vertices) - P) / (2 * P * height)  # 1 / h
    nu, nv = max(3, round(P * x)), max(2, round(height * x))  # nu (nv + 1) = n_vertices
    rng = np.random.default_rng(seed)
    for _ in range(100):
        if irregular:
            uv, faces = _irregular_tube(P, hz, n_vertices, rng)
        else:
            u = P * np.arange(nu) / nu
            U, V = np.meshgrid(u, np.linspace(-hz, hz, nv + 1), indexing="xy")
            uv = np.column_stack([U.ravel(), V.ravel()])
            faces = _grid_faces(nu, nv, periodic=True)
        phi = uv[:, 0] / r
        normals = np.column_stack([np.cos(phi), np.sin(phi), np.zeros(len(uv))])
        vertices = np.column_stack([r * normals[:, :2], uv[:, 1]])
        free = np.abs(uv[:, 1]) < hz
        if not irregular or _acceptable(vertices, faces, free, euler=0):
            break
    else:  # pragma: no cover
        raise RuntimeError("cylinder_tube: no acceptable irregular mesh")
    faces = _orient_each(vertices, normals, faces)
    kind = "irregular" if irregular else "regular"

    def distance(p):
        p = np.asarray(p, float)
        return np.hypot(p[:, 0], p[:, 1]) - r

    def boundary_distance(p):
        return np.abs(np.asarray(p, float)[:, 2]) - hz

    bump = np.where(free, 1 - (uv[:, 1] / hz) ** 2, 0.0)
    return Scene(
        f"cylinder_tube({kind})", vertices, faces, free, normals, uv,
        distance, boundary_distance, 0.5 / r, r, bump,
    )  # fmt: skip


def _irregular_tube(P, hz, n_vertices, rng):
    """Periodic Delaunay of a jittered lattice on [0, P) x [-hz, hz].

    Returns uv (n, 2) with u in [0, P) and faces (m, 3) indexing it."""
    h = math.sqrt(P * 2 * hz / n_vertices)
    for _ in range(6):  # match the total vertex count
        nu = max(3, round(P / h))
        h_u, dv = P / nu, P / nu * math.sqrt(3) / 2
        rows = np.arange(-math.ceil(hz / dv), math.ceil(hz / dv) + 1)
        total = nu * (np.count_nonzero(np.abs(rows * dv) < hz - _MARGIN * h_u) + 2)
        h *= math.sqrt(total / n_vertices)
    j, i = np.meshgrid(rows, np.arange(nu), indexing="ij")
    inner = np.column_stack([(i + 0.5 * (j % 2)).ravel() * h_u, j.ravel() * dv])
    rad = _JITTER * h_u * np.sqrt(rng.uniform(size=len(inner)))
    ang = rng.uniform(0, 2 * math.pi, len(inner))
    inner += np.column_stack([rad * np.cos(ang), rad * np.sin(ang)])
    inner = inner[np.abs(inner[:, 1]) < hz - _MARGIN * h_u]
    inner[:, 0] %= P
    ring = h_u * np.arange(nu)
    border = np.concatenate([np.column_stack([ring, np.full(nu, z)]) for z in (-hz, hz)])
    pad = np.concatenate([np.column_stack([ring, np.full(nu, z)]) for z in (-hz - h_u, hz + h_u)])
    uv = np.concatenate([inner, border])
    movable = np.arange(len(uv)) < len(inner)
    uv, faces, _ = _triangulate(uv, pad, movable, lambda p: np.abs(p[:, 1]) < hz - 0.55 * h_u, P)
    return uv, faces


# --------------------------------------------------------------------------------------
# Torus patch (a boundary condition whose solution of Delta_B H = 0 is not known in closed
# form: for comparing the faired results of different meshes of one region)


def torus_patch(
    major_radius: float = 2.0,
    minor_radius: float = 1.0,
    angle: float = 90.0,
    theta_range=(45.0, 135.0),
    n_free: int = 2000,
    irregular: bool = False,
    seed: int = 0,
    boundary_rings: int = 1,
) -> Scene:
    """Patch of the torus ((sqrt(x^2 + y^2) - R)^2 + z^2 = r^2 around the z axis.

    Points are (R + r cos theta)(cos phi, sin phi, 0) + r sin theta (0, 0, 1).  Region:
    phi in [-angle/2, angle/2] (degrees) around +x, theta in `theta_range` (degrees; the
    default 45..135 around the top circle theta = 90 covers positive Gaussian curvature
    outside, theta < 90, and negative inside).  Built in conformal coordinates
    (R phi, R (psi - psi_c)) with psi(theta) = integral r / (R + r cos theta) dtheta and psi_c
    the middle of the psi range: the surface metric is ((R + r cos theta) / R)^2 times
    Euclidean there (1 on the top circle), so triangles keep their angles.

    The torus does not solve Delta_B H = 0 (its H is not harmonic): the patch is a boundary
    condition (positions and exact normals) whose faired solution is unknown, for comparing
    results on different meshes.  `mean_curvature` is NaN; `distance` is the exact signed
    distance to the torus; normals point away from the tube's core circle.
    """
    R, r = float(major_radius), float(minor_radius)
    if not 0 < r < R:
        raise ValueError("torus_patch: need 0 < minor_radius < major_radius")
    root = math.sqrt(R * R - r * r)

    def psi(theta):  # integral_0^theta r / (R + r cos t) dt, for |theta| < pi
        return 2 * r / root * np.arctan(math.sqrt((R - r) / (R + r)) * np.tan(theta / 2))

    def theta_of(p):
        return 2 * np.arctan(math.sqrt((R + r) / (R - r)) * np.tan(p * root / (2 * r)))

    t1, t2 = (math.radians(t) for t in theta_range)
    if not -math.pi < t1 < t2 < math.pi:
        raise ValueError("torus_patch: theta_range must satisfy -180 < theta1 < theta2 < 180")
    psi1, psi2 = float(psi(t1)), float(psi(t2))
    psi_c = 0.5 * (psi1 + psi2)
    dom = _Rect(R * math.radians(angle) / 2, R * (psi2 - psi1) / 2)

    def to_surface(uv):
        phi, theta = uv[:, 0] / R, theta_of(uv[:, 1] / R + psi_c)
        rho = R + r * np.cos(theta)
        p = np.column_stack([rho * np.cos(phi), rho * np.sin(phi), r * np.sin(theta)])
        n = np.column_stack([np.cos(theta) * np.cos(phi), np.cos(theta) * np.sin(phi), np.sin(theta)])
        return p, n

    def distance(p):
        p = np.asarray(p, float)
        return np.hypot(np.hypot(p[:, 0], p[:, 1]) - R, p[:, 2]) - r

    def boundary_distance(p):
        p = np.asarray(p, float)
        theta = np.arctan2(p[:, 2], np.hypot(p[:, 0], p[:, 1]) - R)
        return dom.sd(np.column_stack([R * np.arctan2(p[:, 1], p[:, 0]), R * (psi(theta) - psi_c)]))

    return _patch(
        "torus_patch", dom, n_free, irregular, seed, boundary_rings, to_surface,
        (distance, boundary_distance), min(dom.U, dom.V), math.nan,
    )  # fmt: skip


def _random_directions(n, rng, relaxations=3):
    """n uniformly random unit vectors, lightly relaxed (half-steps towards the mean of their
    convex-hull neighbours), and their convex-hull triangles: an irregular sampling with
    valences 3 to 11 and thin triangles, unlike the lattices of `_triangulate`."""
    d = _unit(rng.normal(size=(n, 3)))
    for _ in range(relaxations):
        d = _unit(0.5 * (d + _neighbour_mean(d, ConvexHull(d).simplices.astype(np.int64))))
    return d, ConvexHull(d).simplices.astype(np.int64)


def flattened_sphere_cap(
    n_free: int = 2000,
    construction: str = "random",
    seed: int = 0,
    height: float = 0.3,
    jitter: float = 0.01,
) -> tuple[Scene, np.ndarray]:
    """A modeller's flattened selection on the unit sphere: the cap above z = `height` of a
    whole sphere mesh, pressed flat onto that plane.

    `construction`: "random" (uniformly random points, lightly relaxed, triangulated by
    their convex hull: irregular, valences 3 to 11) or "icosphere" (a geodesic icosphere of
    the frequency that gives about `n_free` cap vertices: regular, valence 6 but for a few
    5s). Free: the vertices above the plane; the rest of the sphere stays fixed. Returns the
    scene (exact sphere positions and normals, H = -1) and the start positions: the free
    vertices projected onto z = `height`, moved by `jitter` mean edge lengths (uniform in
    each coordinate, seeded by `seed`).
    """
    fraction = (1.0 - height) / 2.0  # of the sphere's area (and vertices) above the plane
    rng = np.random.default_rng(seed)
    n = max(int(round(n_free / fraction)), 50)
    if construction == "random":
        d, faces = _random_directions(n, rng)
    elif construction == "icosphere":
        d, faces = _icosphere_directions(n)
    else:
        raise ValueError(f"flattened_sphere_cap: construction {construction!r}")
    faces = _orient_each(d, d, faces)
    free = d[:, 2] > height
    uv = np.column_stack([np.arctan2(d[:, 1], d[:, 0]), np.arccos(np.clip(d[:, 2], -1, 1))])
    polar = math.acos(height)
    scene = Scene(
        f"flattened_sphere_cap({construction})", d.copy(), faces, free, d.copy(), uv,
        _sphere_distance(np.zeros(3), 1.0), lambda p: np.arccos(np.clip(_unit(p)[:, 2], -1, 1)) - polar,
        1.0, polar, np.where(free, (d[:, 2] - height) / (1 - height), 0.0),
    )  # fmt: skip
    h = np.linalg.norm(d[faces[:, 0]] - d[faces[:, 1]], axis=1).mean()
    start = d.copy()
    start[free, 2] = height
    start[free] += jitter * h * rng.uniform(-1, 1, size=(int(free.sum()), 3))
    return scene, start


def uv_sphere(segments=64, rings=32):
    """Blender's UV sphere of radius 1 (primitive_uv_sphere_add): ``segments`` meridians,
    ``rings`` bands; quads split into triangles, the poles triangle fans; faces outward.

    Vertex 0 is the north pole, then the rings of ``segments`` vertices from the north,
    then the south pole. (Blender numbers the vertices otherwise; the geometry is the same:
    its mesh, triangulated, gives the fairing figures of this module to 4 digits.)
    """
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    t, p = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1).reshape(-1, 3)
    vertices = np.vstack([[0.0, 0.0, 1.0], ring, [0.0, 0.0, -1.0]])
    south = len(vertices) - 1

    def index(r, s):
        return 1 + r * segments + s % segments

    faces = [[0, index(0, s), index(0, s + 1)] for s in range(segments)]
    for r in range(rings - 2):
        for s in range(segments):
            a, b, c, d = index(r, s), index(r + 1, s), index(r + 1, s + 1), index(r, s + 1)
            faces += [[a, b, c], [a, c, d]]
    faces += [[index(rings - 2, s), south, index(rings - 2, s + 1)] for s in range(segments)]
    faces = np.array(faces)
    assert (np.einsum("ij,ij->i", face_normals(vertices, faces), vertices[faces].mean(axis=1)) > 0).all()
    return vertices, faces
