"""Mesh data in and out of Blender, in Edit Mode (BMesh) and in Object Mode (foreach_get/foreach_set).

Positions are those of what the user edits: the BMesh in Edit Mode, the active
shape key (if any) in Object Mode; they are written back to the same place.
"""

from dataclasses import dataclass

import bmesh
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
        loop_start, loop_total: ``(P,)`` int32 corner range of each face.
        corner_verts: ``(L,)`` int32 vertex of each corner.
        corner_uvs: ``(L, 2)`` float64 active UV map, or None without one.
    """

    vertices: np.ndarray
    triangles: np.ndarray
    triangle_face: np.ndarray
    triangle_corners: np.ndarray
    face_selected: np.ndarray
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
        obj.update_from_editmode()  # topology and selection of the edit mesh into obj.data
    mesh = obj.data
    mesh.calc_loop_triangles()
    triangles = _get(mesh.loop_triangles, "vertices", np.int32, 3)
    triangle_corners = _get(mesh.loop_triangles, "loops", np.int32, 3)
    triangle_face = _get(mesh.loop_triangles, "polygon_index", np.int32)
    face_selected = _get(mesh.polygons, "select", bool)
    loop_start = _get(mesh.polygons, "loop_start", np.int32)
    loop_total = _get(mesh.polygons, "loop_total", np.int32)
    corner_verts = _get(mesh.loops, "vertex_index", np.int32)
    if edit:
        # In Edit Mode the BMesh holds the edited positions (of the active shape
        # key) and the UVs; the mesh's UV layers read as empty.
        bm = bmesh.from_edit_mesh(mesh)
        vertices = np.array([v.co[:] for v in bm.verts], dtype=np.float64).reshape(-1, 3)
        layer = bm.loops.layers.uv.active if uvs else None
        corner_uvs = None
        if layer is not None:  # corners in face order, the order of mesh.loops after update_from_editmode
            corner_uvs = np.array([loop[layer].uv[:] for face in bm.faces for loop in face.loops], dtype=np.float64)
            corner_uvs = corner_uvs.reshape(-1, 2)
    else:
        key = obj.active_shape_key
        vertices = _get(key.data if key is not None else mesh.vertices, "co", np.float64, 3)
        uv_layer = mesh.uv_layers.active if uvs else None
        corner_uvs = _get(uv_layer.data, "uv", np.float64, 2) if uv_layer is not None else None
    return MeshData(
        vertices=vertices,
        triangles=triangles,
        triangle_face=triangle_face,
        triangle_corners=triangle_corners,
        face_selected=face_selected,
        loop_start=loop_start,
        loop_total=loop_total,
        corner_verts=corner_verts,
        corner_uvs=corner_uvs,
    )


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
    """Move the vertices ``indices`` of ``obj``'s mesh to ``positions[indices]`` (Edit or Object Mode)."""
    indices = np.asarray(indices, dtype=np.int64)
    mesh = obj.data
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(mesh)
        bm.verts.ensure_lookup_table()
        verts = bm.verts
        for i, co in zip(indices.tolist(), positions[indices].tolist(), strict=True):
            verts[i].co = co
        bm.normal_update()
        bmesh.update_edit_mesh(mesh, loop_triangles=True, destructive=False)
        return
    key = obj.active_shape_key
    targets = [mesh.vertices] if key is None else [key.data]
    if key is not None and key == mesh.shape_keys.reference_key:
        targets.append(mesh.vertices)  # the basis is also the mesh's own positions
    for target in targets:
        co = _get(target, "co", np.float32, 3)
        co[indices] = positions[indices]
        target.foreach_set("co", co.ravel())
    mesh.update()
