"""Selection to fairing region, without bpy (numpy only).

Turns a face selection on a triangle mesh into what ``geofair.fair`` needs: the
mask of free vertices, the G1 boundary around them with its prescribed normals
(:func:`boundary_normals`: the library's estimate, ``geofair.boundary_normals``,
except at vertices without an unselected face), and, for reporting and tests,
the boundary loops.

Conventions: ``V  #V×3 float64`` vertex positions, ``T  #T×3 int`` triangles,
consistently oriented (counter-clockwise seen from the outside), so the cross
product ``(b - a) × (c - a)`` of a triangle points outwards and its length is
twice the triangle area.
"""

import functools
import heapq
from dataclasses import dataclass, field

import numpy as np


class RegionError(ValueError):
    """The selection does not define a region that can be faired."""


class NothingSelectedError(RegionError):
    """There is nothing to fair: no face is selected (or a region group encloses none).

    With several objects in Edit Mode, an object with nothing to fair is skipped
    quietly while another one has something; any other RegionError is reported.
    """


NO_FACE_SELECTED = "No face is selected: select the faces to fair"
ONLY_VERTICES_OR_EDGES = (
    "No face is selected, only vertices or edges: select the faces to fair "
    "(in Face Select mode, or all vertices of each face)"
)
WHOLE_MESH_SELECTED = (
    "The whole mesh is selected and it has no open border: fairing needs unselected faces around "
    "the selection to hold it in place"
)
WHOLE_CLOSED_PART = (
    "The selection covers a whole closed part of the mesh: fairing needs unselected faces around the selection"
)


@dataclass(frozen=True)
class Region:
    """A fairing region on a triangle mesh with ``n`` vertices.

    Attributes:
        free: ``(n,)`` bool, vertices that may move: all their faces are
            selected and they are not on the open mesh border.
        boundary: ``(n,)`` bool, the G1 boundary: fixed vertices that share a
            face with a free vertex.
        keeps_normal: ``(n,)`` bool, the boundary vertices without an unselected
            face (on the open border, next to a hidden face, or pinned): no fixed
            surface around them to estimate a normal from, so they keep their
            current one.
        current_normals: ``(n, 3)`` float64, at ``keeps_normal`` rows the
            area-weighted normal of the (selected) faces at the vertex, unit
            length (zero where those faces are degenerate); zero elsewhere.
        border_fixed: ``(n,)`` bool, vertices with all faces selected that were
            kept fixed because they lie on the open mesh border.
        hidden_fixed: ``(n,)`` bool, vertices with all their present faces
            selected that were kept fixed because they also belong to an absent
            (hidden) face.
        pinned: ``(n,)`` bool, vertices with all faces selected that were kept
            fixed because they are pinned (not on the border); those next to a
            free vertex are G1 boundary vertices with their own current normal.
        loops: boundary loops, each an int array of vertex indices, oriented
            like the triangles of the region (the outer loop counter-clockwise);
            computed when first read (fairing does not need them).
    """

    free: np.ndarray
    boundary: np.ndarray
    keeps_normal: np.ndarray
    current_normals: np.ndarray
    border_fixed: np.ndarray
    hidden_fixed: np.ndarray
    pinned: np.ndarray
    region_triangles: np.ndarray = field(repr=False)  # (R, 3) the triangles with a free vertex

    @functools.cached_property
    def loops(self):
        return boundary_loops(self.region_triangles, self.free)


def triangulate_polygons(loop_start, loop_total, corner_verts):
    """Fan-triangulate polygons given as loop index arrays.

    Only correct for convex polygons; Blender's ``mesh.loop_triangles`` is the
    better source where bpy is available.

    Args:
        loop_start: ``(P,)`` int, first corner of each polygon.
        loop_total: ``(P,)`` int, number of corners of each polygon (>= 3).
        corner_verts: ``(L,)`` int, vertex index of each corner.

    Returns:
        ``(triangles, triangle_polygon)``: ``(T, 3)`` int64 vertex indices and
        ``(T,)`` int64 index of the polygon each triangle comes from.
    """
    loop_start = np.asarray(loop_start, dtype=np.int64)
    loop_total = np.asarray(loop_total, dtype=np.int64)
    corner_verts = np.asarray(corner_verts, dtype=np.int64)
    if np.any(loop_total < 3):
        raise ValueError("triangulate_polygons: every polygon needs at least 3 corners")
    per_polygon = loop_total - 2
    triangle_polygon = np.repeat(np.arange(len(loop_start)), per_polygon)
    # k-th triangle of a polygon: corners (0, k + 1, k + 2) of the fan.
    k = np.arange(len(triangle_polygon)) - np.repeat(np.cumsum(per_polygon) - per_polygon, per_polygon)
    first = loop_start[triangle_polygon]
    corners = np.stack([first, first + k + 1, first + k + 2], axis=1)
    return corner_verts[corners], triangle_polygon


def face_cross_products(vertices, triangles):
    """Return ``(T, 3)`` cross products ``(b - a) × (c - a)`` (twice the area times the unit normal)."""
    a, b, c = (vertices[triangles[:, i]] for i in range(3))
    return np.cross(b - a, c - a)


def border_vertices(n, triangles):
    """Return ``(n,)`` bool: vertices on an open border edge (one triangle) or a non-manifold edge (more than two)."""
    triangles = np.asarray(triangles, dtype=np.int64)
    edges = np.sort(triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    keys, counts = np.unique(edges[:, 0] * n + edges[:, 1], return_counts=True)
    border = keys[counts != 2]
    on_border = np.zeros(n, dtype=bool)
    on_border[border // n] = True
    on_border[border % n] = True
    return on_border


def require_selected_faces(face_selected, vertex_selected=None):
    """Raise :class:`NothingSelectedError` when no face is selected, saying whether vertices or edges are.

    Args:
        face_selected: ``(P,)`` bool, selected faces.
        vertex_selected: ``(n,)`` bool or None, selected vertices (a selected
            edge selects its two vertices).
    """
    if np.any(face_selected):
        return
    if vertex_selected is not None and np.any(vertex_selected):
        raise NothingSelectedError(ONLY_VERTICES_OR_EDGES)
    raise NothingSelectedError(NO_FACE_SELECTED)


def _region_arguments(vertices, triangles, selected, pinned, present):
    """:func:`find_region`'s arguments as arrays, ``pinned`` and ``present`` filled in when None, lengths checked."""
    vertices = np.asarray(vertices, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    selected = np.asarray(selected, dtype=bool)
    n = len(vertices)
    if selected.shape != (len(triangles),):
        raise ValueError("find_region: selected must have one entry per triangle")
    present = np.ones(len(triangles), dtype=bool) if present is None else np.asarray(present, dtype=bool)
    if present.shape != (len(triangles),):
        raise ValueError("find_region: present must have one entry per triangle")
    pinned = np.zeros(n, dtype=bool) if pinned is None else np.asarray(pinned, dtype=bool)
    if pinned.shape != (n,):
        raise ValueError("find_region: pinned must have one entry per vertex")
    return vertices, triangles, selected, pinned, present


def _selected_normals(vertices, triangles, selected, keeps_normal):
    """``(n, 3)``: the area-weighted unit normal of the selected triangles at ``keeps_normal`` vertices, else zero."""
    current = _vertex_sums(len(vertices), triangles[selected], face_cross_products(vertices, triangles)[selected])
    current[~keeps_normal] = 0.0
    length = np.linalg.norm(current, axis=1)
    usable = length > 0.0
    current[usable] /= length[usable, None]
    return current


def find_region(vertices, triangles, selected, pinned=None, present=None):
    """Compute the fairing region of a face selection.

    A vertex is free when all its faces are selected, unless it lies on the
    open mesh border (kept fixed, counted in ``border_fixed``), belongs to an
    absent face (kept fixed, counted in ``hidden_fixed``) or is pinned (kept
    fixed, counted in ``pinned``).

    Absent triangles (``present`` False: Blender's hidden faces) take no part:
    the mesh ends at them as at an open border. Their vertices never move; those
    next to a free vertex are G1 boundary vertices whose normal comes from the
    present faces at them.

    Boundary normals are not computed here but by :func:`boundary_normals`,
    except at a fixed vertex with every present face selected (on the open
    border, next to an absent face, or pinned inside the region): it has no
    unselected face and keeps the area-weighted normal of its selected faces,
    its current vertex normal (``current_normals``).

    Args:
        vertices: ``(n, 3)`` float vertex positions.
        triangles: ``(T, 3)`` int triangles (the triangulated faces).
        selected: ``(T,)`` bool, triangles of selected faces.
        pinned: ``(n,)`` bool or None, vertices that must not move (a pin
            vertex group); pins outside the region change nothing.
        present: ``(T,)`` bool or None (all present), triangles that take part.

    Returns:
        The :class:`Region`.

    Raises:
        NothingSelectedError: no present triangle is selected.
        RegionError: no free vertex, or a selected part with no fixed boundary
            (the whole closed mesh, or a whole closed piece of it).
    """
    vertices, triangles, selected, pinned, present = _region_arguments(vertices, triangles, selected, pinned, present)
    n = len(vertices)
    touches_absent = np.zeros(n, dtype=bool)
    touches_absent[triangles[~present].ravel()] = True
    triangles, selected = triangles[present], selected[present]
    if not selected.any():
        raise NothingSelectedError(NO_FACE_SELECTED)

    faces_at = np.bincount(triangles.ravel(), minlength=n)
    selected_at = np.bincount(triangles[selected].ravel(), minlength=n)
    inside = (faces_at > 0) & (selected_at == faces_at)
    hidden_fixed = inside & touches_absent
    on_border = border_vertices(n, triangles)
    border_fixed = inside & on_border & ~hidden_fixed
    pinned = inside & pinned & ~border_fixed & ~hidden_fixed
    free = inside & ~border_fixed & ~hidden_fixed & ~pinned
    if not free.any():
        if pinned.any():
            raise RegionError("Every vertex inside the selection is pinned: nothing is left to move")
        raise RegionError("No vertex lies inside the selection: select faces that surround at least one vertex")

    in_region = free[triangles].any(axis=1)
    boundary = np.zeros(n, dtype=bool)
    boundary[triangles[in_region].ravel()] = True
    boundary &= ~free
    closed = WHOLE_MESH_SELECTED if selected.all() and not on_border.any() else WHOLE_CLOSED_PART
    _check_every_part_has_boundary(triangles, free, boundary, closed)

    keeps_normal = boundary & (selected_at == faces_at)
    return Region(
        free=free,
        boundary=boundary,
        keeps_normal=keeps_normal,
        current_normals=_selected_normals(vertices, triangles, selected, keeps_normal),
        border_fixed=border_fixed,
        hidden_fixed=hidden_fixed,
        pinned=pinned,
        region_triangles=triangles[in_region],
    )


def boundary_normals(fairing_region, vertices, triangles, estimate):
    """The unit normals ``geofair.fair`` is given at the G1 boundary.

    The library's estimate from the fixed surface around the region (a
    least-squares quadric through the fixed vertices within two rings, error
    O(h²); see ``geofair.boundary_normals``), except at the ``keeps_normal``
    vertices, which have no unselected face and keep their current normal.

    Args:
        fairing_region: the :class:`Region` of ``vertices`` and ``triangles``.
        vertices: ``(n, 3)`` float64 vertex positions.
        triangles: ``(T, 3)`` int triangles that take part (the present ones).
        estimate: ``geofair.boundary_normals``: ``(vertices, triangles, free)`` to
            ``(n, 3)`` unit rows at G1 boundary vertices, zero rows where it has
            no surrounding triangle to estimate from.

    Returns:
        ``(n, 3)`` float64, unit rows at boundary vertices, zero elsewhere.

    Raises:
        RegionError: a boundary normal that cannot be computed (degenerate faces).
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    normals = np.array(estimate(vertices, triangles, fairing_region.free), dtype=np.float64)
    keeps = fairing_region.keeps_normal
    normals[keeps] = fairing_region.current_normals[keeps]
    normals[~fairing_region.boundary] = 0.0
    degenerate = fairing_region.boundary & ~(np.linalg.norm(normals, axis=1) > 0.0)
    if degenerate.any():
        raise RegionError(f"{np.count_nonzero(degenerate)} boundary vertices have no usable normal (degenerate faces)")
    return normals


def region_triangles(triangles, free):
    """Return ``(T,)`` bool: the triangles with at least one free vertex, the ones fairing changes."""
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    return np.asarray(free, dtype=bool)[triangles].any(axis=1)


def polygons_inside(vertex_mask, loop_start, loop_total, corner_verts):
    """Return ``(P,)`` bool: polygons all of whose corners are in ``vertex_mask``.

    The faces a vertex set encloses, the way Blender selects faces from a
    vertex selection; used to turn a vertex group into a face region.

    Args:
        vertex_mask: ``(n,)`` bool.
        loop_start: ``(P,)`` int, first corner of each polygon.
        loop_total: ``(P,)`` int, number of corners of each polygon.
        corner_verts: ``(L,)`` int, vertex index of each corner.
    """
    vertex_mask = np.asarray(vertex_mask, dtype=bool)
    loop_start = np.asarray(loop_start, dtype=np.int64)
    loop_total = np.asarray(loop_total, dtype=np.int64)
    corner_verts = np.asarray(corner_verts, dtype=np.int64)
    polygon = np.repeat(np.arange(len(loop_start)), loop_total)
    offset = np.arange(len(polygon)) - np.repeat(np.cumsum(loop_total) - loop_total, loop_total)
    outside = ~vertex_mask[corner_verts[loop_start[polygon] + offset]]
    missing = np.bincount(polygon, weights=outside, minlength=len(loop_start))
    return missing == 0


def surface_distances(vertices, triangles, sources, limit):
    """Distances along the mesh's edges from the ``sources`` vertices (Dijkstra), up to ``limit``.

    The radius region of Live Fair Drag: the vertices within ``limit`` of the handle along the
    surface (the triangles' edges; a quad's diagonal counts as a path too).

    Args:
        vertices: ``(n, 3)`` float positions.
        triangles: ``(T, 3)`` int triangles.
        sources: ``(n,)`` bool, the vertices at distance 0.
        limit: the largest distance looked for (mesh units).

    Returns:
        ``(n,)`` float distances, ``inf`` beyond ``limit`` or where no edge path leads.
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    n = len(vertices)
    edges = np.unique(np.sort(triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1), axis=0)
    edges = np.concatenate([edges, edges[:, ::-1]])
    edges = edges[np.argsort(edges[:, 0], kind="stable")]
    start = np.searchsorted(edges[:, 0], np.arange(n + 1))
    neighbour = edges[:, 1].tolist()
    length = np.linalg.norm(vertices[edges[:, 0]] - vertices[edges[:, 1]], axis=1).tolist()
    start = start.tolist()
    distance = np.full(n, np.inf)
    queue = [(0.0, int(v)) for v in np.flatnonzero(np.asarray(sources, dtype=bool))]
    heapq.heapify(queue)
    while queue:
        d, v = heapq.heappop(queue)
        if d >= distance[v]:
            continue
        distance[v] = d
        for k in range(start[v], start[v + 1]):
            e = d + length[k]
            if e <= limit and e < distance[neighbour[k]]:
                heapq.heappush(queue, (e, neighbour[k]))
    return distance


def boundary_loops(triangles, free):
    """Return the boundary loops around the free vertices.

    The loops run along the outline of the triangles that touch a free vertex,
    in the direction of those triangles' edges. A vertex where the region
    touches itself appears in more than one loop (or twice in one).

    Args:
        triangles: ``(T, 3)`` int triangles.
        free: ``(n,)`` bool free vertices.

    Returns:
        List of ``(k,)`` int64 arrays of vertex indices, longest first.
    """
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    region = triangles[np.asarray(free, dtype=bool)[triangles].any(axis=1)]
    heads = region.ravel()
    tails = region[:, [1, 2, 0]].ravel()
    n = int(max(heads.max(initial=0), tails.max(initial=0))) + 1
    outline = ~np.isin(tails * n + heads, heads * n + tails)

    successors = {}
    for head, tail in zip(heads[outline].tolist(), tails[outline].tolist(), strict=True):
        successors.setdefault(head, []).append(tail)
    loops = []
    while successors:
        start = next(iter(successors))
        loop = [start]
        vertex = _pop_successor(successors, start)
        while vertex != start:
            loop.append(vertex)
            if vertex not in successors:  # an open chain: only with misoriented triangles
                break
            vertex = _pop_successor(successors, vertex)
        loops.append(np.array(loop, dtype=np.int64))
    loops.sort(key=len, reverse=True)
    return loops


NO_HOLE = "'{name}' has no hole: every edge has two faces"
ONLY_OUTER_BORDERS = (
    "'{name}' has no hole to fill: {left_open}. Select a loop (Alt+click one of its edges) to fill it anyway"
)
NO_HOLE_SELECTED = (
    "No hole is selected: select the whole boundary loop of each hole to fill (Alt+click one of its edges), "
    "or deselect everything to fill every hole"
)
OPEN_LOOP_SELECTED = (
    "The selected boundary edges close no hole: select the whole boundary loop of a hole (Alt+click one of its edges)"
)


def mesh_holes(triangles, n):
    """The mesh's boundary loops (its holes, open borders included), each along its triangles' edges."""
    return boundary_loops(triangles, np.ones(n, dtype=bool))


def choose_holes(loops, n, selected_edges, name="the mesh"):
    """The holes to fill among the mesh's boundary ``loops``: those whose every edge is selected.

    Args:
        loops: the mesh's boundary loops (:func:`mesh_holes`).
        n: number of vertices.
        selected_edges: ``(E, 2)`` vertex pairs of the selected edges.
        name: the object's name, for the message.

    Raises:
        NothingSelectedError: the mesh has no hole, or no hole is selected.
        RegionError: selected boundary edges that close no loop.
    """
    if not loops:
        raise NothingSelectedError(NO_HOLE.format(name=name))
    edges = np.asarray(selected_edges, dtype=np.int64).reshape(-1, 2)
    selected = np.minimum(edges[:, 0], edges[:, 1]) * n + np.maximum(edges[:, 0], edges[:, 1])
    chosen, on_boundary = [], []
    for loop in loops:
        following = np.roll(loop, -1)
        keys = np.minimum(loop, following) * n + np.maximum(loop, following)
        on_boundary.append(keys)
        if np.isin(keys, selected).all():
            chosen.append(loop)
    if chosen:
        return chosen
    if np.isin(selected, np.concatenate(on_boundary)).any():
        raise RegionError(OPEN_LOOP_SELECTED)
    raise NothingSelectedError(NO_HOLE_SELECTED)


def every_hole(library, vertices, triangles, name="the mesh"):
    """The holes to fill when none is selected, by the library's rule (``geofair.holes_to_fill``: every
    boundary loop but the outer border of each open part), and the loops it leaves open.

    Args:
        library: the compiled ``geofair`` module.
        vertices: ``(n, 3)`` float64 positions; triangles: ``(T, 3)`` int triangles.
        name: the object's name, for the message.

    Returns:
        ``(holes, left_open)``: a list of ``(k,)`` int64 vertex arrays, and a list of ``(loop, reason)``.

    Raises:
        NothingSelectedError: the mesh has no boundary loop, or the rule leaves every one open.
        ValueError: the library refuses the mesh (e.g. holes that touch at a vertex).
    """
    holes, left_open = library.holes_to_fill(vertices, np.asarray(triangles, dtype=np.int32))
    if not holes and not left_open:
        raise NothingSelectedError(NO_HOLE.format(name=name))
    if not holes:
        raise NothingSelectedError(ONLY_OUTER_BORDERS.format(name=name, left_open=left_open_text(left_open)))
    return [np.asarray(loop, dtype=np.int64) for loop in holes], list(left_open)


def left_open_text(left_open, most=3):
    """The loops ``geofair.holes_to_fill`` left open, for a report: each with its edges, a vertex and why."""
    parts = [f"the loop of {len(loop)} edges at vertex {int(loop[0])} is left open, {why}" for loop, why in left_open]
    if len(parts) > most:
        parts = [*parts[:most], f"and {len(parts) - most} more loops"]
    return "; ".join(parts)


# How each of geofair.fill_holes' methods reads in a report.
FILL_METHOD_WORDS = {
    "intrinsic": "intrinsic",
    "intrinsic_finer": "intrinsic at half the edge length",
    "intrinsic_trimmed": "after cleaning its rim",
    "g0": "G0 (positions only)",
    "linear": "linear",
}


def hole_records(holes, triangle_face=None):
    """``geofair.FillResult.holes`` as plain dicts for a report: ``method``, ``filled``, ``converged``,
    ``folds``, ``vertex`` (a vertex of its loop), ``removed_faces`` (the removed triangles' faces:
    polygon indices through ``triangle_face``, ``(T,)``, where given, else triangle rows; sorted) and
    ``reason`` (why it was left open, else "")."""
    out = []
    for hole in holes:
        removed = np.asarray(hole.removed_faces, dtype=np.int64)
        if triangle_face is not None:
            removed = np.unique(np.asarray(triangle_face)[removed])
        out.append({
            "method": str(hole.method),
            "filled": bool(hole.filled),
            "converged": bool(hole.converged),
            "folds": int(hole.folds),
            "vertex": int(hole.loop[0]) if len(hole.loop) else -1,
            "removed_faces": [int(f) for f in removed],
            "reason": str(hole.reason),
        })  # fmt: skip
    return out


def fill_text(records, most=8):
    """One sentence for the holes of :func:`hole_records`, e.g. "9 holes filled: 7 intrinsic, 1 after cleaning
    its rim (4 faces removed: 12, 13, 40, 41), 1 linear; 2 folded edges; 1 not converged"."""
    filled = [r for r in records if r["filled"]]
    counts = {}
    for r in filled:
        counts[r["method"]] = counts.get(r["method"], 0) + 1
    parts = []
    for method, count in counts.items():
        part = f"{count} {FILL_METHOD_WORDS.get(method, method)}"
        removed = sorted({f for r in filled if r["method"] == method for f in r["removed_faces"]})
        if removed:
            shown = ", ".join(map(str, removed[:most])) + (", ..." if len(removed) > most else "")
            part += f" ({len(removed)} face{'s' if len(removed) != 1 else ''} removed: {shown})"
        parts.append(part)
    text = f"{len(filled)} hole{'s' if len(filled) != 1 else ''} filled"
    if parts:
        text += ": " + ", ".join(parts)
    folds = sum(r["folds"] for r in filled)
    if folds:
        text += f"; {folds} folded edge{'s' if folds != 1 else ''}"
    unconverged = sum(not r["converged"] for r in filled)
    if unconverged:
        text += f"; {unconverged} not converged (the best fill kept)"
    for r in records:
        if not r["filled"] and r["reason"] and not r["reason"].startswith(("an outer border", "more edges than")):
            text += f"; the hole at vertex {r['vertex']} is not filled: {r['reason']}"
    return text


def hole_lines(records):
    """One line per hole of :func:`hole_records`: its vertex, method, convergence, folds, removed faces."""
    lines = []
    for r in records:
        if not r["filled"]:
            lines.append(f"hole at vertex {r['vertex']}: left open, {r['reason']}")
            continue
        line = f"hole at vertex {r['vertex']}: {FILL_METHOD_WORDS.get(r['method'], r['method'])}"
        line += ", converged" if r["converged"] else ", not converged"
        line += f", {r['folds']} folded edge{'s' if r['folds'] != 1 else ''}"
        if r["removed_faces"]:
            line += f", faces removed: {', '.join(map(str, r['removed_faces']))}"
        lines.append(line)
    return lines


def _pop_successor(successors, vertex):
    following = successors[vertex]
    tail = following.pop()
    if not following:
        del successors[vertex]
    return tail


def _vertex_sums(n, triangles, values):
    """Sum per-triangle ``values`` (T, 3) into the ``n`` vertices of each triangle."""
    corners = triangles.ravel()
    per_corner = np.repeat(values, 3, axis=0)
    return np.stack([np.bincount(corners, weights=per_corner[:, k], minlength=n) for k in range(3)], axis=1)


def connected_parts(n, edges):
    """Return ``(n,)`` int64: for each vertex the smallest vertex index of its connected part.

    Hooking of roots and pointer jumping (Shiloach–Vishkin) in numpy: a few
    passes over the edges, whatever the diameter of the parts.

    Args:
        n: number of vertices.
        edges: ``(E, 2)`` int vertex pairs.
    """
    parent = np.arange(n)
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    u, v = edges[:, 0], edges[:, 1]
    while True:
        pu, pv = parent[u], parent[v]  # roots: parent is fully jumped
        differ = pu != pv
        if not differ.any():
            return parent
        u, v, pu, pv = u[differ], v[differ], pu[differ], pv[differ]
        np.minimum.at(parent, np.maximum(pu, pv), np.minimum(pu, pv))  # hook the larger root to the smaller
        while True:
            grand = parent[parent]
            if np.array_equal(grand, parent):
                break
            parent = grand


def _check_every_part_has_boundary(triangles, free, boundary, message):
    """Raise RegionError(message) if a connected set of free vertices touches no boundary vertex."""
    edges = triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    label = connected_parts(len(free), edges[free[edges].all(axis=1)])
    touching = np.zeros(len(free), dtype=bool)
    for a, b in ((0, 1), (1, 0)):
        link = free[edges[:, a]] & boundary[edges[:, b]]
        touching[label[edges[link, a]]] = True
    if np.any(free & ~touching[label]):
        raise RegionError(message)
