"""Mesh data in and out of Blender, in Edit Mode (BMesh) and in Object Mode (foreach_get/foreach_set).

Positions are those of what the user edits: the active shape key's if the mesh
has shape keys, else the mesh's own. In Edit Mode that is what the BMesh holds;
they are written back there (Blender stores them on leaving Edit Mode). In
Object Mode they are written the way leaving Edit Mode would store the same
edit, so both modes give the same bytes: the active key changes, and so do the
keys relative to it, by the same offset (Blender's shape-key offsets, see
:func:`dependent_keys`); the mesh's own positions change with the reference
key only.

Everything else (other shape keys, UV maps, colour attributes, custom normals,
vertex groups, selection, hiding) is only read, never written.

Bulk data moves through numpy with ``foreach_get``/``foreach_set``; in Edit
Mode, ``update_from_editmode`` first copies the BMesh into the mesh so that it
can be read the same way (UVs from a temporary copy, see :func:`read_uvs`).
Only writing positions in Edit Mode goes through the BMesh element by element,
since a BMesh has no ``foreach_set``.
"""

from dataclasses import dataclass

import bmesh
import bpy
import numpy as np


@dataclass
class MeshData:
    """What fairing reads from a mesh with ``n`` vertices, ``P`` faces, ``L`` face corners, ``T`` triangles.

    Attributes:
        vertices: ``(n, 3)`` float64 positions in object space.
        triangles: ``(T, 3)`` int32, Blender's tessellation (``loop_triangles``,
            correct for concave n-gons), oriented like the faces.
        triangle_face: ``(T,)`` int32 face of each triangle.
        triangle_corners: ``(T, 3)`` int32 face corner (loop) of each triangle corner.
        face_selected: ``(P,)`` bool.
        face_hidden: ``(P,)`` bool, hidden faces.
        vertex_selected: ``(n,)`` bool (an edge selection selects its vertices too).
        loop_start, loop_total: ``(P,)`` int32 corner range of each face.
        corner_verts: ``(L,)`` int32 vertex of each corner.
        corner_uvs: ``(L, 2)`` float64 active UV map, or None without one.
    """

    vertices: np.ndarray
    triangles: np.ndarray
    triangle_face: np.ndarray
    triangle_corners: np.ndarray
    face_selected: np.ndarray
    face_hidden: np.ndarray
    vertex_selected: np.ndarray
    loop_start: np.ndarray
    loop_total: np.ndarray
    corner_verts: np.ndarray
    corner_uvs: np.ndarray | None


def _get(collection, attribute, dtype, width=1):
    values = np.empty(len(collection) * width, dtype=dtype)
    collection.foreach_get(attribute, values)
    return values.reshape(-1, width) if width > 1 else values


def read(obj, uvs=True):
    """Read ``obj``'s mesh (Edit Mode or Object Mode) into :class:`MeshData` (``corner_uvs`` None unless ``uvs``)."""
    edit = obj.mode == "EDIT"
    if edit:
        obj.update_from_editmode()  # the edit mesh (positions, topology, selection, UVs) into obj.data
    mesh = obj.data
    mesh.calc_loop_triangles()
    corner_verts = _get(mesh.loops, "vertex_index", np.int32)
    triangle_corners = _get(mesh.loop_triangles, "loops", np.int32, 3)
    key = obj.active_shape_key
    vertices = _get(key.data if key is not None else mesh.vertices, "co", np.float32, 3).astype(np.float64)
    data = MeshData(
        vertices=vertices,
        triangles=corner_verts[triangle_corners],
        triangle_face=_get(mesh.loop_triangles, "polygon_index", np.int32),
        triangle_corners=triangle_corners,
        face_selected=_get(mesh.polygons, "select", bool),
        face_hidden=_get(mesh.polygons, "hide", bool),
        vertex_selected=_get(mesh.vertices, "select", bool),
        loop_start=_get(mesh.polygons, "loop_start", np.int32),
        loop_total=_get(mesh.polygons, "loop_total", np.int32),
        corner_verts=corner_verts,
        corner_uvs=None,
    )
    if uvs:
        data.corner_uvs = read_uvs(obj, data)
    return data


def read_uvs(obj, data):
    """``(L, 2)`` float64 active UV map of ``obj``'s mesh read as :class:`MeshData` ``data``, or None without one.

    Call after :func:`read` (``data``), with the mesh unchanged since. In Object
    Mode the corners are read with ``foreach_get``. In Edit Mode the mesh's UV
    maps read as empty, so they are read from a temporary copy of the object's
    mesh (``Object.to_mesh``; no modifiers, and no data-block of ``bpy.data``,
    which would turn the operator's undo step into a global one), which holds
    the BMesh's UVs since :func:`read` called ``update_from_editmode``; corners
    in the same order. (The BMesh corner by corner took 10x as long.)
    """
    mesh = obj.data
    if mesh.uv_layers.active is None:
        return None
    if obj.mode != "EDIT":
        return _get(mesh.uv_layers.active.data, "uv", np.float32, 2).astype(np.float64)
    copy = obj.to_mesh()
    try:
        layer = copy.uv_layers.active
        if layer is None:
            return None
        if len(copy.loops) != len(data.corner_verts):
            raise RuntimeError("the mesh changed while it was read")
        return _get(layer.data, "uv", np.float32, 2).astype(np.float64)
    finally:
        obj.to_mesh_clear()


def edge_selection(obj):
    """``(E, 2)`` int64 vertex pairs of the selected edges of ``obj``'s mesh as :func:`read` left it.

    Call after :func:`read` (which copied the edit mesh into the mesh in Edit Mode).
    """
    mesh = obj.data
    selected = _get(mesh.edges, "select", bool)
    return _get(mesh.edges, "vertices", np.int32, 2).reshape(-1, 2)[selected].astype(np.int64)


def vertex_group_weights(obj, name):
    """``(n,)`` float64 weights of vertex group ``name`` (0 where a vertex is not in it).

    Raises:
        ValueError: ``obj`` has no vertex group ``name``.
    """
    group = obj.vertex_groups.get(name)
    if group is None:
        raise ValueError(f"'{obj.name}' has no vertex group '{name}'")
    index = group.index
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(obj.data)
        layer = bm.verts.layers.deform.active
        if layer is None:
            return np.zeros(len(bm.verts))
        return np.array([v[layer].get(index, 0.0) for v in bm.verts], dtype=np.float64)
    weights = np.zeros(len(obj.data.vertices))
    for vertex in obj.data.vertices:
        for element in vertex.groups:
            if element.group == index:
                weights[vertex.index] = element.weight
    return weights


def vertex_count(obj):
    """Number of vertices of ``obj``'s mesh as edited (the BMesh's in Edit Mode)."""
    if obj.mode == "EDIT":
        return len(bmesh.from_edit_mesh(obj.data).verts)
    return len(obj.data.vertices)


def write_positions(obj, positions, indices):
    """Move the vertices ``indices`` of ``obj``'s mesh to ``positions[indices]`` (Edit or Object Mode).

    Only positions change (see the module's docstring for shape keys), stored
    as float32 like Blender's.
    """
    indices = np.asarray(indices, dtype=np.int64)
    new = positions[indices].astype(np.float32)
    mesh = obj.data
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(mesh)
        bm.verts.ensure_lookup_table()
        verts = bm.verts
        for vertex, co in zip(map(verts.__getitem__, indices.tolist()), new.tolist(), strict=True):
            vertex.co = co
        bm.normal_update()
        bmesh.update_edit_mesh(mesh, loop_triangles=True, destructive=False)
        return
    key = obj.active_shape_key
    if key is None:
        _set_rows(mesh.vertices, indices, new)
    else:
        # What leaving Edit Mode does with an edited shape key: the keys relative to it move
        # by the same offset (new - old, in float32 like Blender); the mesh's own positions
        # are the reference key's.
        old = _get(key.data, "co", np.float32, 3)[indices]
        offset = new - old
        for other in dependent_keys(mesh.shape_keys, key):
            co = _get(other.data, "co", np.float32, 3)
            co[indices] += offset
            other.data.foreach_set("co", co.ravel())
        _set_rows(key.data, indices, new)
        if key == mesh.shape_keys.reference_key:
            _set_rows(mesh.vertices, indices, new)
    mesh.update()


def dependent_keys(shape_keys, key):
    """The shape keys that move with ``key`` when it is edited in Edit Mode.

    Blender 4.0 and later: every key whose chain of relative keys reaches
    ``key``; up to 3.6, only the keys directly relative to it.
    """
    recursive = bpy.app.version >= (4, 0, 0)
    dependent = []
    for other in shape_keys.key_blocks:
        if other == key:
            continue
        relative, seen = other.relative_key, {other.name}
        while relative != key and recursive and relative.name not in seen:  # ends at the basis, relative to itself
            seen.add(relative.name)
            relative = relative.relative_key
        if relative == key:
            dependent.append(other)
    return dependent


def _set_rows(collection, indices, values):
    co = _get(collection, "co", np.float32, 3)
    co[indices] = values
    collection.foreach_set("co", co.ravel())
