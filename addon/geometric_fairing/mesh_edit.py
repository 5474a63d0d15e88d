"""Writing new triangles into a Blender mesh (BMesh), with the layers carried over.

Used where the library changed the triangles: a remeshed fairing region
(:func:`replace_region`) and filled holes (:func:`add_fill`). Everything is
computed and checked (numpy, :mod:`carry`) before the mesh is touched, so a result
that does not fit raises and leaves the mesh as it was.

A remeshed region: the old region's faces (every polygon with a triangle that has a
free vertex) and its free vertices are deleted, the new vertices and faces created;
the fixed vertices are the same BMVerts, so everything outside the region keeps its
data. A polygon only partly in the region (a quad whose other triangle has no free
vertex) comes back as its triangles outside the region, with their own corner data.
New elements first copy every attribute from the nearest old element (the vertex of
the origin triangle with the largest barycentric weight, the origin polygon, that
polygon's corner), then UV maps, colour attributes (point and corner, byte and float)
and vertex groups are interpolated through the origin triangle (:mod:`carry`).

Filled holes: the new vertices and faces are added; UV maps, colours and vertex groups
of the new elements are the harmonic interpolation of the values around each hole;
material, smooth shading and other face attributes come from the face across the
nearest boundary edge.

In Edit Mode the edit BMesh is changed; in Object Mode a BMesh is read from the mesh
and written back (``to_mesh``).
"""

import contextlib
from dataclasses import dataclass, field

import bmesh
import numpy as np

from . import carry


@dataclass
class Written:
    """What a write did, for the report.

    Attributes:
        faces_removed: faces (polygons) deleted.
        triangles_added: new faces created (region or fill).
        vertices_added, vertices_removed: vertices created and deleted.
        notes: what could not be carried over, one sentence each.
        metric_vertices, metric_triangles, metric_uvs: the new triangles, with their
            positions and active-UV corners, for the UV distortion after (None without UVs).
    """

    faces_removed: int = 0
    triangles_added: int = 0
    vertices_added: int = 0
    vertices_removed: int = 0
    notes: list = field(default_factory=list)
    metric_vertices: np.ndarray | None = None
    metric_triangles: np.ndarray | None = None
    metric_uvs: np.ndarray | None = None
    uv_flips: int = 0


@contextlib.contextmanager
def editable_bmesh(obj):
    """The BMesh of ``obj``'s mesh to change: the edit mesh in Edit Mode, else a copy written back on success.

    Everything is checked before the first change, but should writing still fail, the edit
    mesh is restored from a copy taken before (never a half-written mesh).
    """
    mesh = obj.data
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(mesh)
        snapshot = bm.copy()
        try:
            yield bm
        except BaseException:
            _restore(bm, snapshot)
            bmesh.update_edit_mesh(mesh, loop_triangles=True, destructive=True)
            raise
        finally:
            snapshot.free()
        bm.normal_update()
        bmesh.update_edit_mesh(mesh, loop_triangles=True, destructive=True)
        return
    bm = bmesh.new()
    try:
        bm.from_mesh(mesh)
        yield bm
        bm.normal_update()
        bm.to_mesh(mesh)
        mesh.update()
    finally:
        bm.free()


# The attribute layers copied from the nearest old element (by name on BMesh's layer access; the ones a
# Blender version lacks are skipped). Not BMElem.copy_from: in Blender 4.x it also copies the element's
# Python reference and leaves the new element's Python object invalid.
VERTEX_KINDS = ("bevel_weight", "crease", "paint_mask", "skin", "float", "int", "bool", "float_vector", "string")
FACE_KINDS = ("face_map", "float", "int", "bool", "float_vector", "string", "color", "float_color")
LOOP_KINDS = ("float", "int", "bool", "float_vector", "string", "color", "float_color")


def _layers(access, kinds):
    layers = []
    for kind in kinds:
        collection = getattr(access, kind, None)
        if collection is not None:
            layers += collection.values()
    return layers


def _copy_layers(destination, source, layers):
    """Copy the values of ``layers`` from element ``source`` to ``destination`` (skipping any that refuse)."""
    for layer in layers:
        try:
            destination[layer] = source[layer]
        except (TypeError, ValueError, AttributeError):
            pass


def _restore(bm, snapshot):
    """Put the contents of ``snapshot`` back into ``bm`` (through a temporary mesh data-block)."""
    import bpy

    temporary = bpy.data.meshes.new("geometric_fairing_restore")
    try:
        snapshot.to_mesh(temporary)
        bm.clear()
        bm.from_mesh(temporary)
    finally:
        bpy.data.meshes.remove(temporary)


def _corner_loops(bm, data, n):
    """``loop_at(corner)``: the BMLoop of a corner of the mesh as read (``data``), after
    checking that ``bm`` still has the read mesh's ``n`` vertices and its faces.

    Raises:
        RuntimeError: the mesh changed during the run.
    """
    _lookup(bm)
    if len(bm.verts) != n or len(bm.faces) != len(data.loop_start):
        raise RuntimeError("the mesh changed during the run; result discarded")
    bm_faces = bm.faces
    corner_face = carry.corner_faces(data.loop_start, data.loop_total, len(data.corner_verts))

    def loop_at(corner):
        polygon = int(corner_face[corner])
        return bm_faces[polygon].loops[int(corner - data.loop_start[polygon])]

    return loop_at


def _lookup(bm):
    bm.verts.ensure_lookup_table()
    bm.faces.ensure_lookup_table()
    bm.edges.ensure_lookup_table()


def _corner_layers(bm):
    """``(kind, name, layer, width)`` of the corner layers that are interpolated: UV maps, corner colours."""
    layers = [("uv", name, layer, 2) for name, layer in bm.loops.layers.uv.items()]
    layers += [("colour", name, layer, 4) for name, layer in bm.loops.layers.color.items()]
    layers += [("colour", name, layer, 4) for name, layer in bm.loops.layers.float_color.items()]
    return layers


def _point_colour_layers(bm):
    return [*bm.verts.layers.color.values(), *bm.verts.layers.float_color.values()]


def _loop_value(loop, kind, layer):
    return loop[layer].uv[:] if kind == "uv" else loop[layer][:]


def _set_loop_value(loop, kind, layer, value):
    if kind == "uv":
        loop[layer].uv = value
    else:
        loop[layer] = value


def _deform(vertex, layer):
    return dict(vertex[layer].items()) if layer is not None else {}


def _set_deform(vertex, layer, weights):
    data = vertex[layer]
    data.clear()
    for group, weight in weights.items():
        if weight > 0.0:
            data[group] = min(float(weight), 1.0)


def _blend_weights(dicts, factors):
    out = {}
    for weights, factor in zip(dicts, factors, strict=True):
        for group, weight in weights.items():
            out[group] = out.get(group, 0.0) + factor * weight
    return out


def has_shape_keys(obj):
    return obj.data.shape_keys is not None


@dataclass
class _Layers:
    """The layers a write sets: copied from the nearest old element (vertex, face, loop) and interpolated (corner)."""

    vertex: list
    face: list
    loop: list
    corner: list


def _written_layers(bm):
    return _Layers(
        vertex=_layers(bm.verts.layers, VERTEX_KINDS),
        face=_layers(bm.faces.layers, FACE_KINDS),
        loop=_layers(bm.loops.layers, LOOP_KINDS),
        corner=_corner_layers(bm),
    )


def _copy_face(face, source, layers):
    """Copy the face layers, material and smooth shading of face ``source`` to ``face``."""
    _copy_layers(face, source, layers.face)
    face.material_index, face.smooth = source.material_index, source.smooth


def _set_corner_values(loop, layers, corner_values, f, k):
    """Set the interpolated corner layers of ``loop`` (corner ``k`` of new face ``f``)."""
    for (kind, _, layer, _), values in zip(layers.corner, corner_values, strict=True):
        _set_loop_value(loop, kind, layer, tuple(values[f, k]))


def _face_again(bm, face_verts, corners, source, layers):
    """A new face on ``face_verts`` with the data of polygon ``source`` and of the old ``corners`` (BMLoops)."""
    face = bm.faces.new(face_verts)
    _copy_face(face, source, layers)
    for loop, old in zip(face.loops, corners, strict=True):
        _copy_layers(loop, old, layers.loop)
        for kind, _, layer, _ in layers.corner:
            _set_loop_value(loop, kind, layer, _loop_value(old, kind, layer))
    return face


def replace_region(obj, data, input_index, old_free, result):
    """Replace the region's faces of ``obj``'s mesh by a remeshed result (``result.remeshed``).

    Args:
        obj: the mesh object the run read.
        data: its :class:`mesh_io.MeshData` as read for the run.
        input_index: ``(T,)`` loop-triangle index of each triangle given to the library.
        old_free: ``(n,)`` bool, the free mask given to the library.
        result: the library's result (``vertices``, ``faces``, ``free``, ``origin_face``,
            ``origin_barycentric``).

    Returns:
        :class:`Written`.

    Raises:
        carry.CarryError: the result does not fit the mesh (nothing written).
        RuntimeError: the mesh changed under the run (nothing written).
    """
    remeshed = _checked_remesh(data, input_index, old_free, result)
    written = Written()
    with editable_bmesh(obj) as bm:
        loop_at = _corner_loops(bm, data, len(data.vertices))
        carried = _read_region(bm, data, remeshed, loop_at, written)
        _note_region_losses(obj, bm, remeshed, written)
        _write_region(bm, data, remeshed, carried, loop_at, written)
    if written.metric_uvs is not None:
        written.metric_vertices = remeshed.vertices
        written.metric_triangles = remeshed.new_faces
    return written


@dataclass
class _Remeshed:
    """A remeshed result checked against the mesh as read (:func:`_checked_remesh`); rows are the result's."""

    input_index: np.ndarray  # (T,) loop triangle of each triangle given to the library
    triangles_in: np.ndarray  # (T, 3) the triangles given
    old_free: np.ndarray
    vertices: np.ndarray
    new_faces: np.ndarray  # the region's new faces
    new_free: np.ndarray
    origin_face: np.ndarray
    origin_bary: np.ndarray
    used: np.ndarray  # rows the new faces use
    used_free: np.ndarray  # the new vertices among them
    fixed_in_new: np.ndarray  # the fixed vertices among them
    in_region: np.ndarray  # (T,) bool, triangles given with a free vertex
    touched: np.ndarray  # polygons with a triangle in the region
    leftover: np.ndarray  # loop triangles of the touched polygons outside the region


def _checked_remesh(data, input_index, old_free, result):
    """The result as arrays, with the region's new faces and the polygons they replace.

    Raises:
        carry.CarryError: the result does not fit the mesh.
    """
    input_index = np.asarray(input_index, dtype=np.int64)
    triangles_in = data.triangles[input_index].astype(np.int64)
    n = len(data.vertices)
    vertices = np.asarray(result.vertices, dtype=np.float64)
    faces = np.asarray(result.faces, dtype=np.int64).reshape(-1, 3)
    new_free = np.asarray(result.free, dtype=bool).reshape(-1)
    origin_face = np.asarray(result.origin_face, dtype=np.int64).reshape(-1)
    origin_bary = np.asarray(result.origin_barycentric, dtype=np.float64).reshape(-1, 3)
    old_free = np.asarray(old_free, dtype=bool)
    carry.check_remeshed(vertices, faces, new_free, origin_face, origin_bary, len(triangles_in))
    if len(vertices) < n:
        raise carry.CarryError("the remeshed result has fewer vertex rows than the mesh; mesh unchanged")
    fixed_rows = np.flatnonzero(~old_free[:n])
    if np.any(new_free[fixed_rows]):
        raise carry.CarryError("the remeshed result frees a fixed vertex; mesh unchanged")
    new_faces = faces[carry.new_region_faces(triangles_in, old_free, faces)]
    used = np.unique(new_faces)
    bad = used[(used < n) & old_free[np.minimum(used, n - 1)] & ~new_free[used]]
    if len(bad) or np.any(~new_free[used[used >= n]]):
        raise carry.CarryError("the remeshed faces use vertices that are neither fixed nor new; mesh unchanged")
    in_region = old_free[triangles_in].any(axis=1)
    touched = np.unique(data.triangle_face[input_index[in_region]])
    # Triangles of touched polygons outside the region come back as triangles of their own.
    touched_mask = np.zeros(len(data.loop_start), dtype=bool)
    touched_mask[touched] = True
    leftover = np.flatnonzero(touched_mask[data.triangle_face] & ~old_free[data.triangles].any(axis=1))
    # No new face may repeat a face that stays.
    staying_tris = ~touched_mask[data.triangle_face] & (data.loop_total[data.triangle_face] == 3)
    new_keys, staying_keys = carry.face_keys(
        np.concatenate([new_faces, data.triangles[leftover]]), data.triangles[staying_tris]
    )
    if len(np.unique(new_keys)) != len(new_keys) or np.isin(new_keys, staying_keys).any():
        raise carry.CarryError("the remeshed faces repeat a face of the mesh; mesh unchanged")
    free_rows = np.flatnonzero(new_free)
    return _Remeshed(
        input_index=input_index,
        triangles_in=triangles_in,
        old_free=old_free,
        vertices=vertices,
        new_faces=new_faces,
        new_free=new_free,
        origin_face=origin_face,
        origin_bary=origin_bary,
        used=used,
        used_free=free_rows[np.isin(free_rows, used)],
        fixed_in_new=np.setdiff1d(used, free_rows),
        in_region=in_region,
        touched=touched,
        leftover=leftover,
    )


@dataclass
class _CarriedRegion:
    """What the new region's elements take from the old ones, read before the mesh changes."""

    layers: _Layers
    corner_values: list  # per layer of layers.corner: (F, 3, width) values at the new faces' corners
    nearest_corner: dict  # new row -> the BMLoop of its nearest old corner
    fixed_loop: dict  # fixed row -> a BMLoop of it in a region triangle
    point_colours: list
    deform: object  # the active deform layer or None
    point_values: dict  # new row -> (point colours, vertex weights) at its origin triangle's corners
    origin_polygon: dict  # new face -> the polygon whose face data it takes


def _read_region(bm, data, remeshed, loop_at, written):
    """Read what the new region carries over (notes on what it cannot go to ``written``)."""
    r = remeshed
    region_input = np.flatnonzero(r.in_region)  # rows of triangles_in
    needed = np.unique(np.concatenate([region_input, r.origin_face[r.used_free]]))
    corner_loops = {int(t): [loop_at(c) for c in data.triangle_corners[r.input_index[t]]] for t in needed}
    layers = _written_layers(bm)
    corner_values = _region_corner_values(bm, r, region_input, corner_loops, layers.corner, written)
    # Nearest old element of each new vertex: its origin triangle's corner with the largest weight.
    nearest_corner = {}
    for row in r.used_free.tolist():
        t = int(r.origin_face[row])
        nearest_corner[row] = corner_loops[t][int(np.argmax(r.origin_bary[row]))]
    fixed_loop = {}
    for t in region_input.tolist():
        for loop in corner_loops[t]:
            fixed_loop.setdefault(loop.vert.index, loop)
    point_colours = _point_colour_layers(bm)
    deform = bm.verts.layers.deform.active
    return _CarriedRegion(
        layers=layers,
        corner_values=corner_values,
        nearest_corner=nearest_corner,
        fixed_loop=fixed_loop,
        point_colours=point_colours,
        deform=deform,
        point_values=_origin_point_values(r, corner_loops, point_colours, deform),
        origin_polygon=_origin_polygons(data, r, fixed_loop),
    )


def _region_corner_values(bm, remeshed, region_input, corner_loops, corner_layers, written):
    """Each corner layer interpolated to the new faces' corners (:func:`carry.interpolate_corners`).

    A layer with a seam across the region gets a note; the active UV map's values go to the metrics.
    """
    r = remeshed
    verts = bm.verts
    active_uv = bm.loops.layers.uv.active
    active_uv_name = active_uv.name if active_uv is not None else None
    old_free_rows = np.flatnonzero(r.old_free)
    corner_values = []
    for kind, name, layer, width in corner_layers:
        values = np.zeros((len(r.triangles_in), 3, width))
        for t, loops in corner_loops.items():
            values[t] = [_loop_value(loop, kind, layer) for loop in loops]
        candidates = carry.corner_candidates(r.triangles_in[region_input], values[region_input], r.fixed_in_new)
        fallback = {
            int(v): np.array(_loop_value(verts[int(v)].link_loops[0], kind, layer))
            for v in r.fixed_in_new
            if int(v) not in candidates and verts[int(v)].link_loops
        }
        interpolated = carry.interpolate_corners(
            r.new_faces, r.new_free, r.triangles_in, values, r.origin_face, r.origin_bary, candidates, fallback
        )
        corner_values.append(interpolated)
        split = carry.split_vertices(r.triangles_in[region_input], values[region_input], old_free_rows)
        if split:
            what = f"UV map '{name}'" if kind == "uv" else f"colour attribute '{name}'"
            written.notes.append(
                f"{what} has a seam across the region ({split} {'vertex' if split == 1 else 'vertices'}): "
                "the new faces interpolate across it"
            )
        if kind == "uv" and name == active_uv_name:
            written.metric_uvs = interpolated
            written.uv_flips = carry.flipped_uv_triangles(interpolated, values[region_input])
    return corner_values


def _origin_point_values(remeshed, corner_loops, point_colours, deform):
    """Point colours and vertex weights at the corners of each new vertex's origin triangle."""
    point_values = {}
    if point_colours or deform is not None:
        for row in remeshed.used_free.tolist():
            corners = corner_loops[int(remeshed.origin_face[row])]
            point_values[row] = (
                [np.array(corner.vert[layer][:]) for layer in point_colours for corner in corners],
                [_deform(corner.vert, deform) for corner in corners] if deform is not None else None,
            )
    return point_values


def _origin_polygons(data, remeshed, fixed_loop):
    """The polygon each new face takes its face data from: the origin polygon of its first new vertex."""
    r = remeshed
    origin_polygon = {}
    for f, tri in enumerate(r.new_faces.tolist()):
        at = [row for row in tri if r.new_free[row]]
        if at:
            origin_polygon[f] = int(data.triangle_face[r.input_index[r.origin_face[at[0]]]])
        else:  # all three fixed: the polygon of a region triangle at its first vertex
            origin_polygon[f] = fixed_loop[tri[0]].face.index if tri[0] in fixed_loop else int(r.touched[0])
    return origin_polygon


def _note_region_losses(obj, bm, remeshed, written):
    """Notes on what the new faces lose: custom split normals, seams inside the region."""
    if obj.data.has_custom_normals:
        written.notes.append("custom split normals are not carried over to the new faces")
    old_seams = sum(
        1
        for polygon in remeshed.touched.tolist()
        for edge in bm.faces[polygon].edges
        if edge.seam and any(remeshed.old_free[v.index] for v in edge.verts)
    )
    if old_seams:
        written.notes.append(f"{old_seams} seam edges inside the region are gone (new edges have no seam)")


def _write_region(bm, data, remeshed, carried, loop_at, written):
    """Create the new vertices and faces, re-create the leftover triangles, delete the old region."""
    r = remeshed
    n = len(data.vertices)
    verts, bm_faces = bm.verts, bm.faces
    # Every element the write reads or removes, before the first change (the index tables go stale).
    row_vert = {int(row): verts[int(row)] for row in r.fixed_in_new}
    source_faces = [bm_faces[carried.origin_polygon[f]] for f in range(len(r.new_faces))]
    leftover_sources = [
        (bm_faces[int(data.triangle_face[lt])], [loop_at(c) for c in data.triangle_corners[lt]])
        for lt in r.leftover.tolist()
    ]
    touched_faces = [bm_faces[int(p)] for p in r.touched]
    removed = [verts[int(row)] for row in np.flatnonzero(r.old_free[:n])]
    old_edges = {edge for face in touched_faces for edge in face.edges}

    for row in r.used_free.tolist():
        row_vert[row] = _new_region_vertex(verts, r, row, carried)
    created = [
        _new_region_face(bm, r, f, tri, row_vert, source_faces[f], carried)
        for f, tri in enumerate(r.new_faces.tolist())
    ]
    for polygon, corners in leftover_sources:
        face = _face_again(bm, [loop.vert for loop in corners], corners, polygon, carried.layers)
        face.select = polygon.select
        created.append(face)
    for polygon in touched_faces:
        bm_faces.remove(polygon)
    for vertex in removed:
        verts.remove(vertex)
    for edge in old_edges:
        if edge.is_valid and not edge.link_faces:
            bm.edges.remove(edge)
    bm.select_flush_mode()
    written.faces_removed = len(r.touched)
    written.triangles_added = len(created)
    written.vertices_added = len(r.used_free)
    written.vertices_removed = len(removed)


def _new_region_vertex(verts, remeshed, row, carried):
    """A new vertex at result row ``row``: its nearest old vertex's data, point colours and weights interpolated."""
    vertex = verts.new(remeshed.vertices[row].tolist())
    source = carried.nearest_corner[row].vert
    _copy_layers(vertex, source, carried.layers.vertex)
    vertex.select = source.select
    if row in carried.point_values:
        colours, weights = carried.point_values[row]
        bary = remeshed.origin_bary[row]
        for i, layer in enumerate(carried.point_colours):
            vertex[layer] = tuple(sum(bary[k] * colours[i * 3 + k] for k in range(3)))
        if weights is not None:
            _set_deform(vertex, carried.deform, _blend_weights(weights, bary))
    return vertex


def _new_region_face(bm, remeshed, f, tri, row_vert, source, carried):
    """New face ``f`` on result rows ``tri``: face data of polygon ``source``, each corner's from its nearest old
    corner, the interpolated corner layers."""
    face = bm.faces.new([row_vert[row] for row in tri])
    _copy_face(face, source, carried.layers)
    face.select = source.select
    for k, loop in enumerate(face.loops):
        row = tri[k]
        old = carried.nearest_corner.get(row) if remeshed.new_free[row] else carried.fixed_loop.get(row)
        if old is not None:
            _copy_layers(loop, old, carried.layers.loop)
        _set_corner_values(loop, carried.layers, carried.corner_values, f, k)
    return face


def add_fill(obj, data, result):
    """Add the new vertices and faces of ``geofair.fill_holes``'s result to ``obj``'s mesh.

    Where the library removed triangles at a hole's rim (``result.removed_faces``, rim="trim"),
    their faces are deleted; a face of which only some triangles were removed is replaced by its
    other triangles (corner data copied), and vertices left in no face are deleted.

    Args:
        obj: the mesh object the run read.
        data: its :class:`mesh_io.MeshData` (all its loop triangles were given to the library).
        result: the library's result: ``vertices`` (n + k rows), ``faces`` (T - r + l rows: the
            triangles less the r ``removed_faces``, in order, then the fill's).

    Returns:
        :class:`Written`.

    Raises:
        carry.CarryError: the result does not fit the mesh (nothing written).
        RuntimeError: the mesh changed under the run (nothing written).
    """
    fill = _checked_fill(data, result)
    written = Written()
    with editable_bmesh(obj) as bm:
        loop_at = _corner_loops(bm, data, fill.n)
        carried = _read_fill(bm, data, fill, loop_at, written)
        _write_fill(bm, data, fill, carried, loop_at, written)
        if obj.data.has_custom_normals:
            written.notes.append("custom split normals are not carried over to the new faces")
        bm.select_flush(True)
        written.triangles_added = len(fill.new_faces)
        written.vertices_added = len(fill.vertices) - fill.n
    if written.metric_uvs is not None:
        written.metric_vertices = fill.vertices
        written.metric_triangles = fill.new_faces
    return written


@dataclass
class _Fill:
    """A fill checked against the mesh as read (:func:`_checked_fill`); rows are the result's."""

    n: int  # the mesh's vertices
    vertices: np.ndarray  # (n + k, 3)
    new_faces: np.ndarray  # the fill's faces
    removed: np.ndarray  # loop triangles removed at the rims
    alive: np.ndarray  # (T,) bool, the loop triangles that stay
    boundary_rows: np.ndarray  # the mesh's vertices the new faces use
    boundary_half: list  # (a, b, half-edge of the triangle across) per boundary edge of the fill


def _checked_fill(data, result):
    """The result as arrays, with the fill's boundary edges and the mesh's triangles across them.

    Raises:
        carry.CarryError: the result does not fit the mesh.
    """
    n, t = len(data.vertices), len(data.triangles)
    vertices = np.asarray(result.vertices, dtype=np.float64)
    faces = np.asarray(result.faces, dtype=np.int64).reshape(-1, 3)
    removed = np.asarray(getattr(result, "removed_faces", ()), dtype=np.int64).reshape(-1)
    if removed.size and (removed.min() < 0 or removed.max() >= t or len(np.unique(removed)) != len(removed)):
        raise carry.CarryError("the solver removed triangles that are not the mesh's; mesh unchanged")
    alive = np.ones(t, dtype=bool)
    alive[removed] = False
    t_kept = t - len(removed)
    if vertices.ndim != 2 or vertices.shape[1] != 3 or len(vertices) < n or len(faces) < t_kept:
        raise carry.CarryError("the solver returned a result of the wrong shape; mesh unchanged")
    if not np.array_equal(faces[:t_kept], data.triangles[alive]):
        raise carry.CarryError("the solver changed the mesh's faces; mesh unchanged")
    if not np.isfinite(vertices[n:]).all():
        raise carry.CarryError("the solver returned invalid positions; mesh unchanged")
    new_faces = faces[t_kept:]
    if len(new_faces) == 0:
        raise carry.CarryError("the solver added no face; mesh unchanged")
    if new_faces.min() < 0 or new_faces.max() >= len(vertices):
        raise carry.CarryError("the solver returned faces with invalid vertex rows; mesh unchanged")
    if np.any(np.diff(np.sort(new_faces, axis=1), axis=1) == 0):
        raise carry.CarryError("the solver returned degenerate faces; mesh unchanged")
    boundary_rows = np.unique(new_faces[new_faces < n])
    # Only the mesh's triangles at the fill's old vertices can be repeated by a new face or lie
    # across its boundary (a small set: the checks below do not scan a large mesh).
    at_boundary = np.isin(data.triangles, boundary_rows) & alive[:, None]
    repeatable = at_boundary.all(axis=1) & (data.loop_total[data.triangle_face] == 3)
    keys, existing = carry.face_keys(new_faces, data.triangles[repeatable])
    if len(np.unique(keys)) != len(keys) or np.isin(keys, existing).any():
        raise carry.CarryError("the new faces repeat a face of the mesh; mesh unchanged")
    boundary_half = _fill_boundary_edges(data, n, len(vertices), new_faces, at_boundary)
    if not boundary_half:
        raise carry.CarryError("the new faces do not meet the mesh at a hole; mesh unchanged")
    return _Fill(n, vertices, new_faces, removed, alive, boundary_rows, boundary_half)


def _fill_boundary_edges(data, n, size, new_faces, at_boundary):
    """Each boundary edge of the fill (an edge of a new face between two old vertices) and the
    triangle across it: ``(a, b, half-edge)``, the half-edge ``3 * triangle + corner`` in the mesh."""
    near = np.flatnonzero(at_boundary.any(axis=1))
    near_triangles = data.triangles[near].astype(np.int64)
    heads = near_triangles.ravel()
    tails = near_triangles[:, [1, 2, 0]].ravel()
    halves = (3 * near[:, None] + np.arange(3)).ravel()  # their half-edges' indices in the mesh
    directed = {}
    for half, key in zip(halves.tolist(), (heads * size + tails).tolist(), strict=True):
        directed.setdefault(key, half)
    boundary_half = []
    for tri in new_faces.tolist():
        for i in range(3):
            a, b = tri[i], tri[(i + 1) % 3]
            if a < n and b < n:
                half = directed.get(b * size + a, directed.get(a * size + b))
                if half is not None:
                    boundary_half.append((a, b, half))
    return boundary_half


@dataclass
class _CarriedFill:
    """What the fill's elements take from the mesh around each hole, read before the mesh changes."""

    layers: _Layers
    boundary_loops: dict  # boundary vertex -> its BMLoops in the faces across the boundary edges
    corner_values: list  # per layer of layers.corner: (F, 3, width) values at the new faces' corners
    point_colours: list
    deform: object  # the active deform layer or None
    point_filled: list  # per point colour layer: (n + k, 4) values
    weights_filled: tuple | None  # (groups, (n + k, groups) weights) or None
    nearest_vertex: np.ndarray  # (k,) nearest boundary vertex of each new vertex
    source_polygon: list  # per new face: the polygon across its nearest boundary edge


def _read_fill(bm, data, fill, loop_at, written):
    """Read what the fill carries over from around the holes (notes on seams go to ``written``)."""
    # Corner loops of the boundary vertices in the faces across the boundary edges.
    boundary_loops = {}  # vertex -> list of BMLoop (one per boundary edge at it)
    across_face = []  # (midpoint, polygon index) per boundary edge
    for a, b, half in fill.boundary_half:
        tri, corner = divmod(half, 3)
        corners = data.triangle_corners[tri]
        rows = data.triangles[tri].tolist()
        for v in (a, b):
            boundary_loops.setdefault(v, []).append(loop_at(corners[rows.index(v)]))
        across_face.append(((fill.vertices[a] + fill.vertices[b]) / 2, int(data.triangle_face[tri])))
    midpoints = np.array([m for m, _ in across_face])
    known = np.zeros(len(fill.vertices), dtype=bool)
    known[fill.boundary_rows] = True
    layers = _written_layers(bm)
    corner_values = _fill_corner_values(bm, fill, known, boundary_loops, layers.corner, written)
    point_colours = _point_colour_layers(bm)
    deform = bm.verts.layers.deform.active
    point_filled, weights_filled = _fill_point_values(bm.verts, fill, known, point_colours, deform)
    # Nearest boundary vertex of each new vertex, nearest boundary edge of each new face.
    vertices, boundary_rows = fill.vertices, fill.boundary_rows
    nearest_vertex = (
        boundary_rows[
            np.argmin(np.linalg.norm(vertices[fill.n :, None] - vertices[None, boundary_rows], axis=2), axis=1)
        ]
        if len(vertices) > fill.n
        else np.zeros(0, dtype=np.int64)
    )
    centres = vertices[fill.new_faces].mean(axis=1)
    nearest_edge = np.argmin(np.linalg.norm(centres[:, None] - midpoints[None], axis=2), axis=1)
    return _CarriedFill(
        layers=layers,
        boundary_loops=boundary_loops,
        corner_values=corner_values,
        point_colours=point_colours,
        deform=deform,
        point_filled=point_filled,
        weights_filled=weights_filled,
        nearest_vertex=nearest_vertex,
        source_polygon=[across_face[int(e)][1] for e in nearest_edge],
    )


def _fill_corner_values(bm, fill, known, boundary_loops, corner_layers, written):
    """Each corner layer at the new faces' corners: the harmonic fill of its values at the boundary.

    A layer not continuous around a hole gets a note; the active UV map's values go to the metrics.
    """
    active_uv = bm.loops.layers.uv.active
    active_uv_name = active_uv.name if active_uv is not None else None
    corner_values = []
    for kind, name, layer, width in corner_layers:
        values = np.zeros((len(fill.vertices), width))
        jumps = 0
        for v, loops in boundary_loops.items():
            seen = [np.array(_loop_value(loop, kind, layer)) for loop in loops]
            values[v] = seen[0]
            if any(np.abs(other - seen[0]).max() > carry.SAME_VALUE for other in seen[1:]):
                jumps += 1
        filled = carry.harmonic_fill(fill.vertices, fill.new_faces, known, values)
        corner_values.append(filled[fill.new_faces])
        if jumps:
            what = f"UV map '{name}'" if kind == "uv" else f"colour attribute '{name}'"
            written.notes.append(
                f"{what} is not continuous around the hole ({jumps} boundary "
                f"{'vertex' if jumps == 1 else 'vertices'} on a seam): "
                "the fill's values are interpolated from one side"
            )
        if kind == "uv" and name == active_uv_name:
            written.metric_uvs = filled[fill.new_faces]
    return corner_values


def _fill_point_values(verts, fill, known, point_colours, deform):
    """Point colours and vertex weights at every row: the harmonic fill of their values at the boundary.

    Returns:
        ``(point_filled, weights_filled)``: per colour layer ``(n + k, 4)`` values, and ``(groups, (n + k, g)
        weights)`` or None (no deform layer or no group at the boundary).
    """
    boundary_rows = fill.boundary_rows.tolist()
    point_filled = []
    for layer in point_colours:
        values = np.zeros((len(fill.vertices), 4))
        for v in boundary_rows:
            values[v] = verts[v][layer][:]
        point_filled.append(carry.harmonic_fill(fill.vertices, fill.new_faces, known, values))
    weights_filled = None
    if deform is not None:
        groups = sorted({g for v in boundary_rows for g in verts[v][deform].keys()})
        if groups:
            values = np.zeros((len(fill.vertices), len(groups)))
            for v in boundary_rows:
                for g, w in verts[v][deform].items():
                    values[v, groups.index(g)] = w
            weights_filled = (groups, carry.harmonic_fill(fill.vertices, fill.new_faces, known, values))
    return point_filled, weights_filled


def _write_fill(bm, data, fill, carried, loop_at, written):
    """Create the fill's vertices and faces; at a trimmed rim, re-create the staying triangles of the
    faces with removed triangles and delete those faces (with the edges and vertices left in none)."""
    verts, bm_faces = bm.verts, bm.faces
    # Every element the write reads, before the first change (the index tables go stale).
    row_vert = {int(v): verts[int(v)] for v in fill.boundary_rows}
    nearest_verts = [verts[int(v)] for v in carried.nearest_vertex]
    source_faces = [bm_faces[p] for p in carried.source_polygon]
    # The faces the rim's removed triangles belong to, and their triangles that stay.
    touched = np.unique(data.triangle_face[fill.removed]) if fill.removed.size else np.zeros(0, dtype=np.int64)
    doomed = [bm_faces[int(p)] for p in touched]
    staying = np.flatnonzero(np.isin(data.triangle_face, touched) & fill.alive)
    restore = [
        (
            [verts[int(v)] for v in data.triangles[tri]],
            [loop_at(int(c)) for c in data.triangle_corners[tri]],
            bm_faces[int(data.triangle_face[tri])],
        )
        for tri in staying.tolist()
    ]
    for i, row in enumerate(range(fill.n, len(fill.vertices))):
        row_vert[row] = _new_fill_vertex(verts, fill, row, nearest_verts[i], carried)
    for f, tri in enumerate(fill.new_faces.tolist()):
        _new_fill_face(bm, f, tri, row_vert, source_faces[f], carried)
    for tri_verts, tri_loops, source in restore:
        _face_again(bm, tri_verts, tri_loops, source, carried.layers)
    if doomed:
        count = len(bm.verts)
        bmesh.ops.delete(bm, geom=doomed, context="FACES")
        written.faces_removed = len(doomed)
        written.vertices_removed = count - len(bm.verts)


def _new_fill_vertex(verts, fill, row, nearest, carried):
    """A new vertex at result row ``row``: the data of vertex ``nearest``, point colours and weights filled."""
    vertex = verts.new(fill.vertices[row].tolist())
    _copy_layers(vertex, nearest, carried.layers.vertex)
    vertex.select = True
    for j, layer in enumerate(carried.point_colours):
        vertex[layer] = tuple(carried.point_filled[j][row])
    if carried.weights_filled is not None:
        groups, values = carried.weights_filled
        _set_deform(vertex, carried.deform, dict(zip(groups, values[row].tolist(), strict=True)))
    return vertex


def _new_fill_face(bm, f, tri, row_vert, source, carried):
    """New face ``f`` on result rows ``tri``: face data of polygon ``source``, each corner's from the boundary
    vertex's corner across the boundary (else ``source``'s first corner), the filled corner layers."""
    face = bm.faces.new([row_vert[row] for row in tri])
    _copy_face(face, source, carried.layers)
    face.select = True
    source_loop = source.loops[0]
    for c, loop in enumerate(face.loops):
        row = tri[c]
        old = carried.boundary_loops[row][0] if row in carried.boundary_loops else source_loop
        _copy_layers(loop, old, carried.layers.loop)
        _set_corner_values(loop, carried.layers, carried.corner_values, f, c)
    return face
