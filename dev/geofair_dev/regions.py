"""Regions of the real meshes of the paper's figures, in CGAL's demo data (scripts/results.py,
the real-mesh corpus of geofair_dev.corpus, tests/test_negative_weights.py).

The meshes: Debian's libcgal-demo data, /usr/share/doc/libcgal-dev/data.tar.gz, read in
place (``load_cgal_mesh``). A region: the faces whose centroid lies within ``radius`` of
``centre`` (mesh units), the connected part around the face nearest to the centre, holes
filled (``ball_region``). ``harmonic_disk_uv``: texture coordinates of a region, a discrete
harmonic map onto the unit disk (Fig. 10's UV distortion).
"""

from __future__ import annotations

import tarfile

import numpy as np

CGAL_DATA = "/usr/share/doc/libcgal-dev/data.tar.gz"

# Regions of real meshes: faces whose centroid lies within `radius` of `centre` (mesh units),
# the connected part around the face nearest to the centre, holes filled.
MANNEQUIN = "data/meshes/mannequin-devil.off"
BUNNY = "data/meshes/bunny00.off"
HORN = ((5.5, -7.0, 15.5), 5.0)  # the left horn (+x) of mannequin-devil (40 x 33 x 25 units)
FACE = ((0.0, -13.0, 2.0), 6.5)  # the mannequin's face: eyes, nose, cheeks (about 1,400 vertices)
EAR = ((-0.334, 0.372, -0.235), 0.3)  # bunny00's ear at the back (about 4,800 vertices)


def load_cgal_mesh(member):
    """(vertices (n, 3), faces (m, 3)) of an OFF file inside CGAL's data archive."""
    with tarfile.open(CGAL_DATA) as tar:
        text = tar.extractfile(member).read().decode()
    tokens = text.split()
    if tokens[0] != "OFF":
        raise ValueError(f"{member}: not an OFF file")
    nv, nf = int(tokens[1]), int(tokens[2])
    v = np.array(tokens[4 : 4 + 3 * nv], float).reshape(nv, 3)
    f = np.array(tokens[4 + 3 * nv : 4 + 3 * nv + 4 * nf], np.int64).reshape(nf, 4)
    if (f[:, 0] != 3).any():
        raise ValueError(f"{member}: not a triangle mesh")
    return v, f[:, 1:].copy()


def face_adjacency(faces):
    """Sparse (m, m) adjacency of triangles sharing an edge."""
    from scipy.sparse import coo_matrix

    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    e.sort(axis=1)
    owner = np.tile(np.arange(len(faces)), 3)
    key = e[:, 0] * (faces.max() + 1) + e[:, 1]
    order = np.argsort(key, kind="stable")
    same = key[order][1:] == key[order][:-1]
    a, b = owner[order][1:][same], owner[order][:-1][same]
    m = len(faces)
    return coo_matrix((np.ones(2 * len(a)), (np.r_[a, b], np.r_[b, a])), shape=(m, m)).tocsr()


def ball_region(vertices, faces, centre, radius):
    """Selected faces (m,) bool: centroids within the ball, the connected part around the
    face nearest to the centre, with the holes (unselected parts not reaching the rest of
    the mesh) filled.  Returns (selected faces, free vertices): a vertex is free when all
    its faces are selected, as the add-on does it."""
    from scipy.sparse.csgraph import connected_components

    centroid = vertices[faces].mean(axis=1)
    dist = np.linalg.norm(centroid - np.asarray(centre), axis=1)
    sel = dist < radius
    adj = face_adjacency(faces)
    _, label = connected_components(adj[sel][:, sel], directed=False)
    seed = np.argmin(np.where(sel, dist, np.inf)[sel])
    part = np.flatnonzero(sel)[label == label[seed]]
    sel = np.zeros(len(faces), bool)
    sel[part] = True
    n_out, label = connected_components(adj[~sel][:, ~sel], directed=False)
    if n_out > 1:  # keep the largest outside part, fill the rest
        biggest = np.argmax(np.bincount(label))
        sel[np.flatnonzero(~sel)[label != biggest]] = True
    touched = np.zeros(len(vertices), bool)
    touched[faces[~sel].ravel()] = True
    inside = np.zeros(len(vertices), bool)
    inside[faces[sel].ravel()] = True
    return sel, inside & ~touched


def boundary_loop(faces):
    """The longest boundary loop (vertex ids in order) of a triangle set."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    key = {tuple(x) for x in e.tolist()}
    nxt = {a: b for a, b in e.tolist() if (b, a) not in key}
    loops, seen = [], set()
    for start in nxt:
        if start in seen:
            continue
        loop, v = [], start
        while v not in seen:
            seen.add(v)
            loop.append(v)
            v = nxt[v]
        loops.append(loop)
    return np.array(max(loops, key=len))


def harmonic_disk_uv(vertices, faces):
    """UV (n, 2) of the vertices of `faces`: a discrete harmonic map (cotangent weights)
    onto the unit disk, the boundary loop placed by arc length (Floater/Eck et al.); rows
    of vertices outside `faces` are 0."""
    from scipy.sparse.linalg import spsolve

    used = np.unique(faces)
    loop = boundary_loop(faces)
    local = -np.ones(len(vertices), np.int64)
    local[used] = np.arange(len(used))
    import geofair

    L = geofair.cotangent_laplacian(vertices[used], local[faces]).tocsr()
    seg = np.linalg.norm(vertices[np.roll(loop, -1)] - vertices[loop], axis=1)
    t = 2 * np.pi * np.r_[0.0, np.cumsum(seg)[:-1]] / seg.sum()
    fixed = np.zeros(len(used), bool)
    fixed[local[loop]] = True
    uv = np.zeros((len(used), 2))
    uv[local[loop]] = np.column_stack([np.cos(t), np.sin(t)])
    inner = np.flatnonzero(~fixed)
    A = L[inner][:, inner].tocsc()
    rhs = -L[inner][:, np.flatnonzero(fixed)] @ uv[fixed]
    uv[inner] = np.column_stack([spsolve(A, rhs[:, k]) for k in range(2)])
    out = np.zeros((len(vertices), 2))
    out[used] = uv
    return out
