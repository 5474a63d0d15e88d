"""Stand-ins for the library's results that change the triangles, for tests of the add-on's writing.

:func:`centroid_remesh` and :func:`fan_fill` build results with the fields of
``geofair.fair(..., remesh=True)`` and ``geofair.fill_holes`` (docs/REFERENCE.md): they
split each region triangle at its centroid, or close each hole with a fan around its
centroid. The geometry is simple on purpose: the tests check how the add-on carries
layers over (a split at the centroid keeps every UV exactly where a remesh must put it),
not the library. :class:`RemeshingModule` wraps the real module so the add-on can be
driven through them in Blender. No bpy.
"""

import types

import numpy as np


def _result(vertices, faces, free, **fields):
    base = dict(
        vertices=np.asarray(vertices, dtype=np.float64),
        faces=np.asarray(faces, dtype=np.int32).reshape(-1, 3),
        free=np.asarray(free, dtype=bool),
        remeshed=True,
        unreferenced=np.zeros(0, dtype=np.int32),
        converged=True,
        iterations=1,
        residual=0.0,
        iterations_per_level=[1],
        vertices_per_level=[int(np.count_nonzero(free))],
        iteration="newton",
        folds=0,
        new_folds=0,
        message="converged (stand-in)",
        stop_reason="converged",
    )
    base.update(fields)
    return types.SimpleNamespace(**base)


def centroid_remesh(vertices, faces, free, faired=None):
    """A "remeshed" result: each triangle with a free vertex split in three at its centroid.

    Rows: the input's rows (the free ones keep their row and count as new free vertices),
    then one row per split triangle. Faces: those outside the region in input order, then
    the new ones. ``faired``: positions to place the vertices at (default: ``vertices``).
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    free = np.asarray(free, dtype=bool)
    faired = vertices if faired is None else np.asarray(faired, dtype=np.float64)
    region = free[faces].any(axis=1)
    region_rows = np.flatnonzero(region)
    n = len(vertices)
    centre_rows = n + np.arange(len(region_rows))
    out = np.concatenate([faired, faired[faces[region_rows]].mean(axis=1)])
    new_free = np.concatenate([free, np.ones(len(region_rows), dtype=bool)])
    a, b, c = faces[region_rows].T
    new_faces = np.concatenate(
        [np.stack([a, b, centre_rows], 1), np.stack([b, c, centre_rows], 1), np.stack([c, a, centre_rows], 1)]
    )
    origin_face = np.full(len(out), -1, dtype=np.int32)
    origin_bary = np.zeros((len(out), 3))
    origin_face[centre_rows] = region_rows
    origin_bary[centre_rows] = 1.0 / 3.0
    for v in np.flatnonzero(free):
        t = region_rows[np.flatnonzero((faces[region_rows] == v).any(axis=1))[0]]
        origin_face[v] = t
        origin_bary[v, int(np.flatnonzero(faces[t] == v)[0])] = 1.0
    return _result(
        out,
        np.concatenate([faces[~region], new_faces]),
        new_free,
        origin_face=origin_face,
        origin_barycentric=origin_bary,
    )


def fan_fill(vertices, faces, loops):
    """A "filled" result: each loop closed by a fan around a new vertex at its centroid.

    Each loop runs along the edges of the faces around it (as the add-on finds them), so
    the fan's triangles run against it.
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    n = len(vertices)
    rows, new_faces = [], []
    for i, loop in enumerate(loops):
        loop = np.asarray(loop, dtype=np.int64)
        rows.append(vertices[loop].mean(axis=0))
        centre = n + i
        new_faces += [[int(loop[(j + 1) % len(loop)]), int(loop[j]), centre] for j in range(len(loop))]
    out = np.concatenate([vertices, np.array(rows).reshape(-1, 3)])
    free = np.zeros(len(out), dtype=bool)
    free[n:] = True
    return _result(
        out,
        np.concatenate([faces, np.array(new_faces, dtype=np.int64).reshape(-1, 3)]),
        free,
        origin_face=np.full(len(out), -1, dtype=np.int32),
        origin_barycentric=np.zeros((len(out), 3)),
    )


def remesh_then_fair(real, vertices, faces, free, boundary_normals=None, **options):
    """``fair(remesh=True)`` composed of the library's own steps: ``remesh_region``, then ``fair`` on its
    triangles (boundary normals carried to the new rows, polygon ids dropped)."""
    options.pop("polygon_ids", None)
    region = real.remesh_region(vertices, faces, free)
    normals = None
    if boundary_normals is not None:
        normals = np.zeros((len(region.vertices), 3))
        normals[: len(boundary_normals)] = boundary_normals
        normals[np.asarray(region.free)] = 0.0
    result = real.fair(region.vertices, region.faces, region.free, boundary_normals=normals, **options)
    fields = {
        name: getattr(result, name)
        for name in (
            "converged iterations residual iterations_per_level vertices_per_level iteration folds new_folds "
            "message stop_reason"
        ).split()
    }
    return _result(
        result.vertices,
        region.faces,
        region.free,
        unreferenced=np.asarray(region.unreferenced),
        origin_face=np.asarray(region.origin_face),
        origin_barycentric=np.asarray(region.origin_barycentric),
        **fields,
    )


class RemeshingModule:
    """Stands in for the loaded ``geofair`` module: ``fair`` with ``remesh`` True or "if_needed" remeshes
    with the library's ``remesh_region`` where it has one (:func:`remesh_then_fair`), else fairs with the real
    one and splits the region as :func:`centroid_remesh`; ``fill_holes`` is :func:`fan_fill`."""

    def __init__(self, real):
        self.real = real
        self.calls = []

    def fair(self, vertices, faces, free, *, remesh=False, **options):
        self.calls.append(("fair", remesh))
        if remesh is False or not hasattr(self.real, "remesh_region"):
            result = self.real.fair(vertices, faces, free, **options)
            if remesh is False or (remesh == "if_needed" and result.converged and not result.new_folds):
                return result
            return centroid_remesh(vertices, faces, free, np.asarray(result.vertices))
        if remesh == "if_needed":
            result = self.real.fair(vertices, faces, free, **options)
            if result.converged and not result.new_folds:
                return result
        return remesh_then_fair(self.real, vertices, faces, free, **options)

    def fill_holes(self, vertices, faces, loops=None, **options):
        self.calls.append(("fill_holes", loops))
        return fan_fill(vertices, faces, loops)

    def __getattr__(self, name):
        return getattr(self.real, name)
