"""Carrying a mesh's layers over to new triangles, without bpy (numpy only).

Two kinds of new triangles come from the library:

- a remeshed fairing region (``geofair.fair(..., remesh=True)``): each new vertex knows the
  input triangle it was created on and its barycentric coordinates there
  (``origin_face``, ``origin_barycentric``), so per-corner data (UVs, corner colours) and
  per-vertex data (vertex groups, point colours) are interpolated from that triangle;
  corners at fixed vertices take the value the vertex had in the old region's triangles.
- a filled hole (``geofair.fill_holes``): the new vertices lie where nothing was, so their
  values are the harmonic interpolation of the values around the hole's boundary
  (:func:`harmonic_fill`), a small Laplace system solved by conjugate gradients.

Conventions: ``triangles`` ``(T, 3)`` int vertex rows; per-corner values ``(T, 3, d)``
float64 (one row of ``d`` numbers per triangle corner); per-vertex values ``(n, d)``.
"""

import numpy as np

# Two UVs (or colours) closer than this are the same value (a vertex inside one UV island
# has bit-equal UVs in Blender; this only absorbs float32 round-off).
SAME_VALUE = 1e-6


class CarryError(ValueError):
    """The library's result does not fit the mesh it was computed for."""


def face_keys(*triangle_arrays):
    """Ids of triangles as vertex sets (the sorted rows), equal exactly for equal sets, across the arrays.

    Returns one ``(T_i,)`` int64 array per argument (any number of vertices: no packing that could
    overflow).
    """
    arrays = [np.sort(np.asarray(t, dtype=np.int64).reshape(-1, 3), axis=1) for t in triangle_arrays]
    rows = np.concatenate(arrays) if arrays else np.zeros((0, 3), dtype=np.int64)
    if len(rows) == 0:
        return [np.zeros(0, dtype=np.int64) for _ in arrays]
    _, inverse = np.unique(rows, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    return np.split(inverse, np.cumsum([len(a) for a in arrays])[:-1])


def corner_faces(loop_start, loop_total, corners):
    """``(L,)`` int64 polygon of each face corner, from the polygons' corner ranges."""
    loop_start = np.asarray(loop_start, dtype=np.int64)
    loop_total = np.asarray(loop_total, dtype=np.int64)
    offsets = np.arange(int(loop_total.sum())) - np.repeat(np.cumsum(loop_total) - loop_total, loop_total)
    face = np.full(corners, -1, dtype=np.int64)
    face[np.repeat(loop_start, loop_total) + offsets] = np.repeat(np.arange(len(loop_start)), loop_total)
    return face


def new_region_faces(input_triangles, free, result_faces):
    """The rows of a remeshed result's ``faces`` that are new: not a triangle outside the old region.

    Args:
        input_triangles: ``(T, 3)`` the triangles given to ``geofair.fair``.
        free: ``(n,)`` bool, the free mask given to it.
        result_faces: ``(T', 3)`` the result's ``faces``.

    Returns:
        ``(F,)`` int64 indices into ``result_faces``.

    Raises:
        CarryError: a triangle outside the region is missing from the result.
    """
    input_triangles = np.asarray(input_triangles, dtype=np.int64).reshape(-1, 3)
    result_faces = np.asarray(result_faces, dtype=np.int64).reshape(-1, 3)
    free = np.asarray(free, dtype=bool)
    outside = input_triangles[~free[input_triangles].any(axis=1)]
    outside_keys, result_keys = face_keys(outside, result_faces)
    kept = np.isin(result_keys, outside_keys)
    if np.count_nonzero(kept) != len(outside) or not np.isin(outside_keys, result_keys).all():
        raise CarryError("the remeshed result lost triangles outside the region; mesh unchanged")
    return np.flatnonzero(~kept)


def check_remeshed(result_vertices, result_faces, result_free, origin_face, origin_barycentric, t_in):
    """Check a remeshed result before anything is written: finite positions and barycentrics, faces in range,
    origin faces of the new free vertices in range. Raises :class:`CarryError`."""
    vertices = np.asarray(result_vertices)
    faces = np.asarray(result_faces)
    free = np.asarray(result_free, dtype=bool)
    if vertices.ndim != 2 or vertices.shape[1] != 3 or len(free) != len(vertices):
        raise CarryError("the solver returned a remeshed result of the wrong shape; mesh unchanged")
    if faces.size and (faces.min() < 0 or faces.max() >= len(vertices)):
        raise CarryError("the solver returned faces with invalid vertex rows; mesh unchanged")
    if len(faces) and np.any(np.diff(np.sort(faces, axis=1), axis=1) == 0):
        raise CarryError("the solver returned degenerate faces (a vertex twice); mesh unchanged")
    rows = np.flatnonzero(free)
    if not np.isfinite(vertices[rows]).all():
        raise CarryError("the solver returned invalid positions; mesh unchanged")
    origin = np.asarray(origin_face)[rows]
    bary = np.asarray(origin_barycentric)[rows]
    if np.any(origin < 0) or np.any(origin >= t_in) or not np.isfinite(bary).all():
        raise CarryError("the solver returned new vertices without a valid origin; mesh unchanged")


def interpolate_points(values, input_triangles, origin_face, origin_barycentric, rows):
    """Per-vertex ``values`` ``(n, d)`` at new vertices ``rows``: the barycentric blend over their origin triangle."""
    values = np.asarray(values, dtype=np.float64)
    tri = np.asarray(input_triangles, dtype=np.int64)[np.asarray(origin_face)[rows]]
    bary = np.asarray(origin_barycentric, dtype=np.float64)[rows]
    return np.einsum("rk,rkd->rd", bary, values[tri])


def corner_candidates(triangles, corner_values, vertices_of_interest):
    """The distinct values of each vertex's corners: ``{vertex: (k, d) array}`` for ``vertices_of_interest``.

    Args:
        triangles: ``(T, 3)`` triangles whose corners count (the old region's).
        corner_values: ``(T, 3, d)`` their corner values.
        vertices_of_interest: iterable of vertex rows.
    """
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    values = np.asarray(corner_values, dtype=np.float64).reshape(len(triangles) * 3, -1)
    corners = triangles.ravel()
    wanted = np.isin(corners, np.fromiter(vertices_of_interest, dtype=np.int64))
    order = np.argsort(corners[wanted], kind="stable")
    verts, vals = corners[wanted][order], values[wanted][order]
    starts = np.flatnonzero(np.r_[True, verts[1:] != verts[:-1]]) if len(verts) else np.zeros(0, dtype=np.int64)
    ends = np.r_[starts[1:], len(verts)]
    candidates = {}
    for start, end in zip(starts.tolist(), ends.tolist(), strict=True):
        candidates[int(verts[start])] = distinct_rows(vals[start:end])
    return candidates


def distinct_rows(values, tolerance=SAME_VALUE):
    """The rows of ``values`` ``(k, d)`` that differ from every earlier row by more than ``tolerance``."""
    kept = []
    for row in values:
        if not any(np.abs(row - other).max() <= tolerance for other in kept):
            kept.append(row)
    return np.array(kept).reshape(len(kept), values.shape[1])


def split_vertices(triangles, corner_values, vertices, tolerance=SAME_VALUE):
    """How many of ``vertices`` have corners with different values in ``triangles`` (a seam through them)."""
    candidates = corner_candidates(triangles, corner_values, vertices)
    return sum(len(values) > 1 for values in candidates.values())


def interpolate_corners(
    new_faces, new_free, input_triangles, corner_values, origin_face, origin_barycentric, candidates, fallback
):
    """Values at the corners of the new faces of a remeshed region.

    A corner at a new free vertex: the barycentric blend of its origin triangle's corner
    values. A corner at a fixed vertex: the value that vertex had in the old region's
    triangles (``candidates``); where it had several (a seam through it), the one nearest to
    the face's corners at free vertices, else the first.

    Args:
        new_faces: ``(F, 3)`` rows of the result's vertices.
        new_free: ``(n',)`` bool, the result's free vertices.
        input_triangles: ``(T, 3)`` the triangles given to the library.
        corner_values: ``(T, 3, d)`` values at their corners (only the origin triangles'
            rows are read).
        origin_face, origin_barycentric: the result's.
        candidates: :func:`corner_candidates` of the old region at the fixed vertices.
        fallback: ``{vertex: (d,) value}`` for fixed vertices without a candidate.

    Returns:
        ``(F, 3, d)`` float64.
    """
    new_faces = np.asarray(new_faces, dtype=np.int64).reshape(-1, 3)
    corner_values = np.asarray(corner_values, dtype=np.float64)
    d = corner_values.shape[2]
    new_free = np.asarray(new_free, dtype=bool)
    out = np.zeros((len(new_faces), 3, d))
    at_free = new_free[new_faces]
    rows = new_faces[at_free]
    origin = np.asarray(origin_face, dtype=np.int64)[rows]
    bary = np.asarray(origin_barycentric, dtype=np.float64)[rows]
    out[at_free] = np.einsum("rk,rkd->rd", bary, corner_values[origin])
    fixed_faces, fixed_corners = np.nonzero(~at_free)
    for f, k in zip(fixed_faces.tolist(), fixed_corners.tolist(), strict=True):
        vertex = int(new_faces[f, k])
        options = candidates.get(vertex)
        if options is None or len(options) == 0:
            out[f, k] = fallback.get(vertex, np.zeros(d))
            continue
        if len(options) == 1 or not at_free[f].any():
            out[f, k] = options[0]
            continue
        reference = out[f][at_free[f]].mean(axis=0)
        out[f, k] = options[np.argmin(np.abs(options - reference).sum(axis=1))]
    return out


def signed_areas_2d(corner_uvs):
    """``(F,)`` signed areas (times 2) of triangles given by their corner UVs ``(F, 3, 2)``."""
    uv = np.asarray(corner_uvs, dtype=np.float64)
    e1, e2 = uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0]
    return e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]


def flipped_uv_triangles(new_corner_uvs, old_corner_uvs):
    """Number of new triangles whose UV orientation is opposite to the majority of the old region's."""
    old = signed_areas_2d(old_corner_uvs)
    sign = np.sign(old[np.abs(old) > 0].sum()) or 1.0
    return int(np.count_nonzero(signed_areas_2d(new_corner_uvs) * sign <= 0.0))


# -- holes ---------------------------------------------------------------------------------------


def boundary_corner_values(triangles, corner_values, loop, n, tolerance=SAME_VALUE):
    """The values of a hole's boundary vertices from the faces around it, and whether they are continuous.

    Each boundary vertex has a corner in the triangle of each of its two boundary edges;
    where those two differ (a UV seam meets the hole), the value is not continuous around
    the hole there: the first is taken.

    Returns:
        ``((k, d) values along the loop, number of vertices where the values jump)``.
    """
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    corner_values = np.asarray(corner_values, dtype=np.float64)
    loop = np.asarray(loop, dtype=np.int64)
    heads = triangles.ravel()
    tails = triangles[:, [1, 2, 0]].ravel()
    directed = {}
    for index, key in enumerate((heads * n + tails).tolist()):
        directed.setdefault(key, index)
    flat = corner_values.reshape(len(triangles) * 3, -1)
    values = np.zeros((len(loop), flat.shape[1]))
    jumps = 0
    following = np.roll(loop, -1)
    preceding = np.roll(loop, 1)
    for i, (v, after, before) in enumerate(zip(loop.tolist(), following.tolist(), preceding.tolist(), strict=True)):
        seen = []
        for a, b in ((v, after), (before, v)):
            half = directed.get(a * n + b)
            if half is None:
                half = directed.get(b * n + a)
            if half is None:
                continue
            t = half // 3
            k = int(np.flatnonzero(triangles[t] == v)[0])
            seen.append(flat[t * 3 + k])
        if not seen:
            continue
        values[i] = seen[0]
        if len(seen) > 1 and np.abs(seen[0] - seen[1]).max() > tolerance:
            jumps += 1
    return values, jumps


def cotangent_weights(vertices, faces):
    """``(E, 2)`` edges and ``(E,)`` weights of the cotangent Laplacian of ``faces``, clamped to be positive."""
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    edges, weights = [], []
    for k in range(3):
        i, j, o = faces[:, (k + 1) % 3], faces[:, (k + 2) % 3], faces[:, k]
        u, v = vertices[i] - vertices[o], vertices[j] - vertices[o]
        cross = np.linalg.norm(np.cross(u, v), axis=1)
        cot = np.einsum("ij,ij->i", u, v) / np.maximum(cross, 1e-300)
        edges.append(np.stack([i, j], axis=1))
        weights.append(0.5 * cot)
    edges, weights = np.concatenate(edges), np.concatenate(weights)
    n = int(faces.max(initial=-1)) + 1
    keys = np.minimum(edges[:, 0], edges[:, 1]) * n + np.maximum(edges[:, 0], edges[:, 1])
    unique, inverse = np.unique(keys, return_inverse=True)
    summed = np.bincount(inverse, weights=weights, minlength=len(unique))
    edges = np.stack([unique // max(n, 1), unique % max(n, 1)], axis=1)
    floor = 1e-3 * max(float(np.abs(summed).mean()) if len(summed) else 1.0, 1e-12)
    return edges, np.maximum(summed, floor)


def harmonic_fill(vertices, faces, known, known_values, iterations=2000, tolerance=1e-10):
    """Harmonic interpolation over ``faces``: values at the unknown vertices with the known ones fixed.

    Solves the cotangent Laplace equation (weights clamped positive, so the system is
    symmetric positive definite) on the vertices of ``faces`` that are not ``known`` by
    conjugate gradients with a Jacobi preconditioner, one column of ``known_values`` at a time.

    Args:
        vertices: ``(n, 3)`` positions.
        faces: ``(F, 3)`` the triangles to interpolate over.
        known: ``(n,)`` bool, the vertices with a value (the hole's boundary).
        known_values: ``(n, d)`` values (rows of unknown vertices are ignored).

    Returns:
        ``(n, d)`` float64: ``known_values`` with the unknown rows of ``faces`` filled in.
    """
    known = np.asarray(known, dtype=bool)
    values = np.array(known_values, dtype=np.float64, copy=True)
    faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    edges, weights = cotangent_weights(vertices, faces)
    unknown_rows = np.setdiff1d(np.unique(faces), np.flatnonzero(known))
    if len(unknown_rows) == 0:
        return values
    index = np.full(len(known), -1, dtype=np.int64)
    index[unknown_rows] = np.arange(len(unknown_rows))
    m = len(unknown_rows)
    diagonal = np.bincount(edges.ravel(), weights=np.repeat(weights, 2), minlength=len(known))[unknown_rows]
    a, b = index[edges[:, 0]], index[edges[:, 1]]
    inner = (a >= 0) & (b >= 0)
    ia, ib, w_in = a[inner], b[inner], weights[inner]

    def apply(x):
        y = diagonal * x
        y -= np.bincount(ia, weights=w_in * x[ib], minlength=m)
        y -= np.bincount(ib, weights=w_in * x[ia], minlength=m)
        return y

    # Right-hand side: the known neighbours' weighted values.
    to_a = (a >= 0) & (b < 0)
    to_b = (b >= 0) & (a < 0)
    for column in range(values.shape[1]):
        rhs = np.zeros(m)
        rhs += np.bincount(a[to_a], weights=weights[to_a] * values[edges[to_a, 1], column], minlength=m)
        rhs += np.bincount(b[to_b], weights=weights[to_b] * values[edges[to_b, 0], column], minlength=m)
        x = np.full(m, rhs.sum() / max(diagonal.sum(), 1e-300))
        r = rhs - apply(x)
        z = r / diagonal
        p = z.copy()
        rz = r @ z
        norm = max(np.linalg.norm(rhs), 1e-300)
        for _ in range(iterations):
            if np.linalg.norm(r) <= tolerance * norm:
                break
            q = apply(p)
            alpha = rz / (p @ q)
            x += alpha * p
            r -= alpha * q
            z = r / diagonal
            rz, previous = r @ z, rz
            p = z + (rz / previous) * p
        values[unknown_rows, column] = x
    return values
