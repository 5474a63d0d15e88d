"""Holes cut into meshes, and what a filled hole is measured by (bench/holes.py, tests/test_holes_bench.py).

- ``boundary_loops(faces)``: the boundary loops of a triangle mesh, each a vertex array in
  the direction of the triangles' own edges along it.
- ``manifold_problem(faces)``: why a triangle set is not an oriented 2-manifold (with
  border), or None: a triangle repeating a vertex, an edge in more than two triangles or
  twice in one direction (inconsistent orientation), a vertex whose triangles are not one
  fan (a "bowtie" vertex).
- ``cut_disc(vertices, faces, seed, count=... | radius=...)``: a hole: the geodesic disc
  around a seed vertex (Dijkstra distance along the edges; or BFS rings, ``distance=``
  ``hop_distance(faces, seed)``) removed with its triangles,
  cleaned up until it leaves exactly one new boundary loop on a manifold mesh; a ``Hole``
  with the cut mesh, its loop and the cut-away triangles (None when the seed gives no
  clean hole: the disc reaches the mesh border, cuts off a part larger than a pocket, or
  the cut-away part is not a disc).
- ``point_triangle_distance(p, a, b, c)``, ``fill_samples(vertices, faces)``,
  ``distance_to_mesh(points, vertices, faces)``: the distance of a fill from the surface
  that was cut away (exact point-to-triangle distance, geofair_dev.measures).
- ``folded_edges(vertices, faces, faces_of_interest)``: edges of the given triangles whose
  two triangles' normals have a negative dot product.
- ``check_fill(vertices_in, faces_in, loop, vertices_out, faces_out)``: the properties of a
  filled mesh (input kept, manifold, hole closed, folds), a dict.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass, field

import numpy as np

from geofair_dev.measures import _closest_on_triangles, point_mesh_distance

POCKET = 10  # parts of at most this many vertices cut off by a hole are removed with it
MAX_CLEANUPS = 50
MAX_HOLE_FRACTION = 0.25  # a corpus mesh is Loop-subdivided until a hole takes at most this
MAX_CANDIDATES = 40  # seed vertices tried for a clean corpus hole


# --------------------------------------------------------------------------------------
# Topology


def _directed_edges(faces):
    f = np.asarray(faces, np.int64)
    return np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])


def boundary_edges(faces):
    """(k, 2) directed edges a -> b of the triangles whose reverse b -> a no triangle has."""
    d = _directed_edges(faces)
    if len(d) == 0:
        return d
    n = int(d.max()) + 1
    key = d[:, 0] * n + d[:, 1]
    return d[~np.isin(d[:, 1] * n + d[:, 0], key)]


def boundary_loops(faces):
    """The boundary loops of a triangle mesh: a list of vertex arrays, each in the direction
    of the faces' edges (loop[i] -> loop[i + 1] is an edge of a triangle), longest first.
    A vertex on two loops (a bowtie) gets its outgoing edges in the order found."""
    b = boundary_edges(faces)
    out_edges = {}
    for i, a in enumerate(b[:, 0].tolist()):
        out_edges.setdefault(a, []).append(i)
    used = np.zeros(len(b), bool)
    loops = []
    for start in range(len(b)):
        if used[start]:
            continue
        loop, e = [], start
        while not used[e]:
            used[e] = True
            loop.append(int(b[e, 0]))
            nxt = [j for j in out_edges.get(int(b[e, 1]), []) if not used[j]]
            if not nxt:
                break
            e = nxt[0]
        loops.append(np.array(loop, np.int64))
    return sorted(loops, key=len, reverse=True)


def manifold_problem(faces):
    """Why ``faces`` is not an oriented 2-manifold with border, or None.

    Checked: no triangle repeats a vertex; no directed edge occurs twice (an edge in more
    than two triangles, or two triangles on it with the same orientation); the triangles
    around each vertex form one fan (connected through the edges at the vertex)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    f = np.asarray(faces, np.int64)
    if len(f) == 0:
        return None
    bad = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 0] == f[:, 2])
    if bad.any():
        return f"triangle {int(np.flatnonzero(bad)[0])} repeats a vertex"
    n = int(f.max()) + 1
    d = _directed_edges(f)
    key = d[:, 0] * n + d[:, 1]
    uniq, count = np.unique(key, return_counts=True)
    if (count > 1).any():
        k = int(uniq[count > 1][0])
        return f"edge {k // n}-{k % n} is used twice in one direction (non-manifold or inconsistently oriented)"
    und = np.sort(d, axis=1)
    _, ucount = np.unique(und[:, 0] * n + und[:, 1], return_counts=True)
    if (ucount > 2).any():  # cannot happen without a repeated directed edge; kept for clarity
        return "an edge is used by more than two triangles"
    # Fans: nodes are (vertex, neighbour) pairs; the triangle (a, b, c) joins (a, b) and
    # (a, c) at a, and likewise at b and c. One fan per vertex: its nodes are one component.
    a, b, c = f.ravel(), np.roll(f, -1, axis=1).ravel(), np.roll(f, -2, axis=1).ravel()
    nodes, inv = np.unique(np.concatenate([a * n + b, a * n + c]), return_inverse=True)
    k = len(a)
    graph = coo_matrix((np.ones(k), (inv[:k], inv[k:])), shape=(len(nodes), len(nodes)))
    _, label = connected_components(graph, directed=False)
    vertex = nodes // n
    fans = np.bincount(np.unique(vertex * len(nodes) + label) // len(nodes), minlength=n)
    if (fans > 1).any():
        v = int(np.flatnonzero(fans > 1)[0])
        return f"the triangles around vertex {v} are {int(fans[v])} fans, not one"
    return None


def euler_characteristic(faces):
    f = np.asarray(faces, np.int64)
    und = np.unique(np.sort(_directed_edges(f), axis=1), axis=0)
    return len(np.unique(f)) - len(und) + len(f)


def _vertex_components(faces, n):
    """(number, label (n,)) of the connected components of the edge graph; vertices in no
    triangle get a component each."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    d = _directed_edges(faces)
    graph = coo_matrix((np.ones(len(d)), (d[:, 0], d[:, 1])), shape=(n, n))
    return connected_components(graph, directed=False)


def _fan_count(faces, n):
    """(n,) the number of fans of triangles around each vertex (0: in no triangle)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    f = np.asarray(faces, np.int64)
    if len(f) == 0:
        return np.zeros(n, np.int64)
    a, b, c = f.ravel(), np.roll(f, -1, axis=1).ravel(), np.roll(f, -2, axis=1).ravel()
    nodes, inv = np.unique(np.concatenate([a * n + b, a * n + c]), return_inverse=True)
    k = len(a)
    graph = coo_matrix((np.ones(k), (inv[:k], inv[k:])), shape=(len(nodes), len(nodes)))
    _, label = connected_components(graph, directed=False)
    return np.bincount(np.unique((nodes // n) * len(nodes) + label) // len(nodes), minlength=n)


# --------------------------------------------------------------------------------------
# Cutting holes


@dataclass
class Hole:
    """A mesh with a hole cut into it.

    vertices (n', 3), faces (m', 3): the mesh without the disc (reindexed, every vertex in
    a triangle); loop (L,): the hole's boundary loop (indices into vertices, in the faces'
    direction); cut_vertices (k, 3), cut_faces (l, 3): the triangles that were removed, on
    their own vertices (the loop's vertices among them), the surface a fill is compared
    with; removed: vertices removed; seed: the seed vertex (input index); radius: the
    disc's radius (the Dijkstra distance of its farthest vertex, before clean-up); diameter:
    the largest distance between two vertices of the loop; edge_length: the loop's mean
    edge length; original_ids (n',): the input index of each vertex.
    """

    vertices: np.ndarray
    faces: np.ndarray
    loop: np.ndarray
    cut_vertices: np.ndarray
    cut_faces: np.ndarray
    removed: int
    seed: int
    radius: float
    diameter: float
    edge_length: float
    original_ids: np.ndarray
    notes: list = field(default_factory=list)


def edge_graph(vertices, faces):
    """Sparse symmetric (n, n) matrix of edge lengths."""
    from scipy.sparse import coo_matrix

    d = np.unique(np.sort(_directed_edges(faces), axis=1), axis=0)
    w = np.linalg.norm(vertices[d[:, 0]] - vertices[d[:, 1]], axis=1)
    n = len(vertices)
    return coo_matrix((np.r_[w, w], (np.r_[d[:, 0], d[:, 1]], np.r_[d[:, 1], d[:, 0]])), shape=(n, n)).tocsr()


def geodesic_distance(vertices, faces, seed):
    """(n,) Dijkstra distance along the edges from vertex ``seed`` (inf: unreachable)."""
    from scipy.sparse.csgraph import dijkstra

    return dijkstra(edge_graph(vertices, faces), directed=False, indices=int(seed))


def hop_distance(faces, seed, n=None):
    """(n,) edge-graph (BFS ring) distance from vertex ``seed``, in edges (inf: unreachable):
    the rings of ``cut_disc(..., distance=hop_distance(faces, seed))``."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import shortest_path

    f = np.asarray(faces, np.int64)
    n = int(f.max()) + 1 if n is None else n
    d = _directed_edges(f)
    graph = coo_matrix((np.ones(len(d)), (d[:, 0], d[:, 1])), shape=(n, n)).tocsr()
    return shortest_path(graph, directed=False, unweighted=True, indices=int(seed))


def loop_diameter(vertices, loop):
    p = np.asarray(vertices)[np.asarray(loop)]
    best = 0.0
    for start in range(0, len(p), 512):  # bounded memory
        d = np.linalg.norm(p[start : start + 512, None] - p[None], axis=2)
        best = max(best, float(d.max()))
    return best


def cut_disc(vertices, faces, seed, count=None, radius=None, distance=None):
    """Cut the geodesic disc around vertex ``seed`` out of the mesh: a ``Hole``, or (None,
    reason) when the seed gives no clean hole.

    The disc: the ``count`` vertices nearest to the seed (or those within ``radius``) by
    Dijkstra distance along the edges (or by ``distance``, (n,) given). Removed: the disc's
    vertices and every triangle using one. Then, until nothing changes: a vertex left in no
    triangle, or whose remaining triangles form more than one fan (the hole touching itself
    at a vertex), is removed too, and so is a part of at most POCKET vertices cut off from
    the rest. Rejected (None) when the disc reaches the mesh's border (the hole would merge
    with it), when it cuts off a larger part, or when the cut-away triangles are not a disc
    (Euler characteristic 1, one boundary loop) or the rest not a manifold with exactly one
    boundary loop more than the input.
    """
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    n = len(v)
    if (count is None) == (radius is None):
        raise ValueError("cut_disc: give count or radius")
    dist = geodesic_distance(v, f, seed) if distance is None else np.asarray(distance, float)
    from geofair_dev.scenes import border_mask

    border = border_mask(f, n)
    order = np.argsort(dist, kind="stable")
    if count is not None:
        if count > np.isfinite(dist).sum():
            return None, "the seed's component is too small"
        disc = np.zeros(n, bool)
        disc[order[:count]] = True
        r = float(dist[order[count - 1]])
    else:
        disc = dist <= radius
        r = float(radius)
    n_loops_before = len(boundary_loops(f))
    _, component = _vertex_components(f, n)
    same = component == component[seed]  # other parts of the mesh (e.g. separate eyes) stay as they are
    in_triangle = np.bincount(f.ravel(), minlength=n) > 0
    removed = disc.copy()
    for _ in range(MAX_CLEANUPS):
        if (removed & border).any():
            return None, "the disc reaches the mesh border"
        kept = f[~removed[f].any(axis=1)]
        more = (_fan_count(kept, n) != 1) & ~removed & in_triangle
        ncomp, label = _vertex_components(kept, n)
        alive = ~removed & ~more & same
        size = np.bincount(label[alive], minlength=ncomp)
        if (size > 0).sum() > 1:
            main = int(np.argmax(size))
            if (alive & (label != main) & (size[label] > POCKET)).any():
                return None, "the disc cuts off a part larger than a pocket"
            more |= alive & (label != main)
        if not more.any():
            break
        removed |= more
    else:
        return None, "the clean-up does not settle"
    keep = ~removed[f].any(axis=1)
    kept, cut = f[keep], f[~keep]
    problem = manifold_problem(kept)
    if problem:
        return None, f"the cut mesh is not a manifold: {problem}"
    loops = boundary_loops(kept)
    if len(loops) != n_loops_before + 1:
        return None, f"the cut leaves {len(loops) - n_loops_before} new boundary loops"
    touched = np.zeros(n, bool)
    touched[cut.ravel()] = True
    new = [lp for lp in loops if touched[lp].all() and not border[lp].any()]
    if len(new) != 1:
        return None, "no boundary loop of the cut mesh runs along the hole alone"
    if euler_characteristic(cut) != 1 or len(boundary_loops(cut)) != 1:
        return None, "the cut-away triangles are not a disc"
    used = np.unique(kept)
    local = np.full(n, -1, np.int64)
    local[used] = np.arange(len(used))
    cused = np.unique(cut)
    clocal = np.full(n, -1, np.int64)
    clocal[cused] = np.arange(len(cused))
    loop = local[new[0]]
    vv = v[used]
    lp = vv[loop]
    edge = float(np.linalg.norm(lp - np.roll(lp, -1, axis=0), axis=1).mean())
    hole = Hole(vv, local[kept], loop, v[cused], clocal[cut], int(removed.sum()), int(seed), r,
                loop_diameter(vv, loop), edge, used)  # fmt: skip
    return hole, None


def neighbourhood(hole: Hole, rings: int):
    """The hole's surroundings: the triangles within ``rings`` rings of the loop (and all
    triangles of a vertex where they would meet in a bowtie), reindexed: a Hole on a
    smaller manifold mesh (same loop, cut-away surface and figures). rings <= 0: the hole."""
    if rings <= 0:
        return hole
    f = hole.faces
    n = len(hole.vertices)
    near = np.zeros(n, bool)
    near[hole.loop] = True
    sel = np.zeros(len(f), bool)
    for _ in range(rings):
        sel = near[f].any(axis=1)
        near[f[sel].ravel()] = True
    for _ in range(MAX_CLEANUPS):  # no bowtie vertex on the surroundings' outer border: add its triangles
        bowtie = _fan_count(f[sel], n) > 1
        if not bowtie.any():
            break
        sel |= bowtie[f].any(axis=1)
    used = np.unique(f[sel])
    local = np.full(n, -1, np.int64)
    local[used] = np.arange(len(used))
    return Hole(hole.vertices[used], local[f[sel]], local[hole.loop], hole.cut_vertices, hole.cut_faces,
                hole.removed, hole.seed, hole.radius, hole.diameter, hole.edge_length,
                hole.original_ids[used], list(hole.notes))  # fmt: skip


# --------------------------------------------------------------------------------------
# Measuring fills


def point_triangle_distance(p, a, b, c):
    """Distance from points p to triangles (a, b, c), pairwise: all (k, 3) or (3,)
    (broadcast); (k,) float64, exact up to rounding (the closest point on the face, an edge
    or a corner)."""
    p, a, b, c = np.broadcast_arrays(*(np.atleast_2d(np.asarray(x, float)) for x in (p, a, b, c)))
    return np.linalg.norm(p - _closest_on_triangles(p, a, b, c), axis=1)


def fill_samples(vertices, faces, per_edge=4):
    """Sample points of a triangle set: its vertices and, on each triangle, the points of the
    barycentric grid (i, j, k) / per_edge (i + j + k = per_edge) other than the corners
    (per_edge <= 1: the vertices alone)."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    if per_edge <= 1:
        return v[np.unique(f)]
    grid = np.array([(i, j, per_edge - i - j) for i in range(per_edge + 1) for j in range(per_edge + 1 - i)], float)
    grid = grid[(grid < per_edge).all(axis=1)] / per_edge
    tri = v[f]
    inner = np.einsum("gk,fkd->fgd", grid, tri).reshape(-1, 3)
    return np.concatenate([v[np.unique(f)], inner])


def distance_to_mesh(points, vertices, faces):
    """(k,) distance from points to the triangle mesh (geofair_dev.measures.point_mesh_distance)."""
    return point_mesh_distance(points, vertices, faces)


def folded_edges(vertices, faces, of_interest):
    """Number of edges of the triangles ``of_interest`` ((m,) bool) with two triangles whose
    normals have a negative dot product (or a degenerate triangle: a zero normal)."""
    f = np.asarray(faces, np.int64)
    v = np.asarray(vertices, float)
    n = len(v)
    d = np.sort(_directed_edges(f), axis=1)
    owner = np.tile(np.arange(len(f)), 3)
    key = d[:, 0] * n + d[:, 1]
    order = np.argsort(key, kind="stable")
    key, owner = key[order], owner[order]
    _, start, count = np.unique(key, return_index=True, return_counts=True)
    two = count == 2
    f1, f2 = owner[start[two]], owner[start[two] + 1]
    interest = np.asarray(of_interest, bool)
    sel = interest[f1] | interest[f2]
    p = v[f]
    cr = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    dot = np.einsum("ij,ij->i", cr[f1[sel]], cr[f2[sel]])
    return int((dot <= 0).sum())


def check_fill(vertices_in, faces_in, loop, vertices_out, faces_out, removed=()):
    """The properties of a filled mesh, a dict: "input_kept" (the input's rows and faces come
    first, bit-identical; the faces less the rows ``removed``, in their order), "manifold"
    (manifold_problem's reason or None), "closed" (every edge of the loop and of the removed
    faces has two triangles or none, and no new boundary edge appeared), "folds" (folded
    edges of the new triangles, among them and with the old ones), "new_vertices",
    "new_faces", "min_angle" (degrees, the new triangles' smallest)."""
    from geofair_dev.scenes import triangle_angles

    vi, fi = np.asarray(vertices_in, float), np.asarray(faces_in, np.int64)
    vo, fo = np.asarray(vertices_out, float), np.asarray(faces_out, np.int64)
    removed = np.asarray(removed, np.int64).reshape(-1)
    kept_in = np.delete(fi, removed, axis=0)
    n, m = len(vi), len(kept_in)
    kept = len(vo) >= n and len(fo) >= m and np.array_equal(fo[:m], kept_in)
    bits = np.ascontiguousarray(vo[:n]).view(np.uint64), np.ascontiguousarray(vi).view(np.uint64)
    kept = kept and np.array_equal(*bits)
    new = np.zeros(len(fo), bool)
    new[m:] = True
    problem = manifold_problem(fo)
    before = {tuple(e) for e in boundary_edges(fi).tolist()}
    after = {tuple(e) for e in boundary_edges(fo).tolist()}
    lp = np.asarray(loop, np.int64)
    loop_edges = {tuple(e) for e in np.column_stack([lp, np.roll(lp, -1)]).tolist()}
    loop_edges |= {tuple(e) for e in _directed_edges(fi[removed]).tolist()}
    loop_edges |= {(b, a) for a, b in loop_edges}
    closed = not (after - before) and not (after & loop_edges)
    ang = triangle_angles(vo, fo[m:]) if len(fo) > m else np.zeros((0, 3))
    return {
        "input_kept": bool(kept),
        "manifold": problem,
        "closed": bool(closed),
        "folds": folded_edges(vo, fo, new),
        "new_vertices": len(vo) - n,
        "new_faces": len(fo) - m,
        "removed_faces": len(removed),
        "min_angle": float(ang.min()) if ang.size else None,
    }


def cut_surface_put_back(hole: Hole):
    """The cut-away triangles put back into the cut mesh: (vertices, faces) as a fill would
    give them (the cut mesh's rows and faces first, then the cut-away surface's inner vertices
    and triangles; its loop vertices matched to the cut mesh's by position)."""
    index = {tuple(p): i for i, p in enumerate(hole.vertices.tolist())}
    extra = [p for p in hole.cut_vertices.tolist() if tuple(p) not in index]
    index.update({tuple(p): len(hole.vertices) + k for k, p in enumerate(extra)})
    back = np.array([[index[tuple(hole.cut_vertices[i].tolist())] for i in t] for t in hole.cut_faces])
    return np.concatenate([hole.vertices, np.array(extra).reshape(-1, 3)]), np.concatenate([hole.faces, back])


def cut_surface_folds(hole: Hole):
    """Folded edges (check_fill's count) of the cut-away surface itself, put back: what a fill
    that reproduced the original surface exactly would count; None where the put-back mesh is
    not closed and manifold (a loop vertex matched to a coincident twin)."""
    vo, fo = cut_surface_put_back(hole)
    check = check_fill(hole.vertices, hole.faces, hole.loop, vo, fo)
    if not (check["input_kept"] and check["closed"] and check["manifold"] is None):
        return None
    return check["folds"]


def fill_distance(vertices_out, faces_out, n_faces_in, reference, per_edge=4):
    """(mean, max) distance of the new triangles (rows n_faces_in: of faces_out) from a
    reference: ``reference`` is a callable (k, 3) points -> (k,) distances (an analytic
    surface) or a (vertices, faces) mesh (the cut-away triangles). Sampled at the new
    triangles' vertices and their barycentric grid points (fill_samples; per_edge=1: at the
    vertices alone)."""
    fo = np.asarray(faces_out, np.int64)[n_faces_in:]
    if len(fo) == 0:
        return None, None
    pts = fill_samples(vertices_out, fo, per_edge)
    d = np.abs(reference(pts)) if callable(reference) else distance_to_mesh(pts, *reference)
    return float(d.mean()), float(d.max())


# --------------------------------------------------------------------------------------
# Finer meshes


def loop_subdivide(vertices, faces):
    """One step of Loop's subdivision (Loop 1987; Warren's β = 3/(8k) for valence k > 3,
    3/16 for k = 3; border edges and vertices by the cubic B-spline rules): (vertices,
    faces) with each triangle split in four, the input's vertices first (moved), the edge
    points after. A smooth finer mesh of a corpus mesh, for holes of more vertices than
    the mesh has to spare."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    n = len(v)
    d = _directed_edges(f)
    und = np.sort(d, axis=1)
    key = und[:, 0] * n + und[:, 1]
    uniq, edge_of, count = np.unique(key, return_inverse=True, return_counts=True)
    ne = len(uniq)
    a, b = uniq // n, uniq % n
    opposite = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])  # the third vertex of each directed edge
    opp_sum = np.zeros((ne, 3))
    np.add.at(opp_sum, edge_of, v[opposite])
    on_border = count == 1
    edge_point = np.where(on_border[:, None], 0.5 * (v[a] + v[b]), 0.375 * (v[a] + v[b]) + 0.125 * opp_sum)
    # Vertices: interior by Warren's weights, border by 3/4 and 1/8 of the two border neighbours.
    valence = np.bincount(np.r_[a, b], minlength=n)
    nb_sum = np.zeros((n, 3))
    np.add.at(nb_sum, a, v[b])
    np.add.at(nb_sum, b, v[a])
    border_sum = np.zeros((n, 3))
    np.add.at(border_sum, a[on_border], v[b[on_border]])
    np.add.at(border_sum, b[on_border], v[a[on_border]])
    border_vertex = np.bincount(np.r_[a[on_border], b[on_border]], minlength=n) > 0
    k = np.maximum(valence, 1).astype(float)
    beta = np.where(valence == 3, 3.0 / 16.0, 3.0 / (8.0 * k))
    moved = (1 - k * beta)[:, None] * v + beta[:, None] * nb_sum
    moved = np.where(border_vertex[:, None], 0.75 * v + 0.125 * border_sum, moved)
    moved[valence == 0] = v[valence == 0]
    m = len(f)
    e01, e12, e20 = (n + edge_of[i * m : (i + 1) * m] for i in range(3))
    out = np.concatenate([
        np.column_stack([f[:, 0], e01, e20]),
        np.column_stack([e01, f[:, 1], e12]),
        np.column_stack([e20, e12, f[:, 2]]),
        np.column_stack([e01, e12, e20]),
    ])  # fmt: skip
    return np.concatenate([moved, edge_point]), out


def corpus_hole(name, size, slot, cache, meshes=None):
    """bench/holes.py's corpus hole ``cgal/<name>/<size>/s<slot>``: the geodesic disc of
    ``size`` vertices cut out of CGAL's demo mesh ``name`` (geofair_dev.corpus.cgal_mesh),
    Loop-subdivided until the disc takes at most MAX_HOLE_FRACTION of its vertices, around
    the first of MAX_CANDIDATES seed vertices (off the border, in a random order seeded by
    the name, size and slot) that gives a clean hole. ``meshes``: a dict that keeps the
    subdivided meshes between calls. Returns (Hole, subdivision levels, seeds passed over);
    raises ValueError when no seed gives a clean hole."""
    # Imported here: the corpus reads CGAL's archive, which nothing else in this module needs.
    from geofair_dev.corpus import cgal_mesh
    from geofair_dev.scenes import border_mask

    meshes = {} if meshes is None else meshes
    v0, _ = cgal_mesh(name, cache)
    levels = 0
    while len(v0) * 4**levels * MAX_HOLE_FRACTION < size:
        levels += 1
    if (name, levels) not in meshes:
        v, f = cgal_mesh(name, cache)
        for _ in range(levels):
            v, f = loop_subdivide(v, f)
        meshes[name, levels] = (v, f)
    v, f = meshes[name, levels]
    border = border_mask(f, len(v))
    rng = np.random.default_rng([zlib.crc32(name.encode()), size, slot])
    order = rng.permutation(np.flatnonzero(~border & (np.bincount(f.ravel(), minlength=len(v)) > 0)))
    why = "no candidate seed"
    for j in range(min(MAX_CANDIDATES, len(order))):
        hole, why = cut_disc(v, f, int(order[j]), count=size)
        if hole is not None:
            return hole, levels, j
    raise ValueError(f"cgal/{name}/{size}/s{slot}: no clean hole in {MAX_CANDIDATES} seeds ({why})")
