"""The real-mesh corpus: regions of real meshes, Blender primitives and the paper's scenes,
as fairing problems (bench/realmesh.py runs them; tests/test_realmesh.py its CI-sized subset).

``cases(quick, large)`` lists lightweight descriptors, ``load_case(desc)`` builds one,
``case_file(desc, cache)`` caches its input as .npz, ``new_folds(...)`` counts folds and
``region_topology(...)`` names a region's topology:

- ``cgal/<mesh>/<size>/s<k>``: geodesic discs on the libcgal-demo meshes elk, bull, dino,
  lion-head, knot1, blobby, cactus, hand, bear, cheese, diplodocus, ChineseDragon-10kv
  (/usr/share/doc/libcgal-dev/data.tar.gz, data/meshes/*.off, read in place; polygons
  fan-triangulated) of about 100, 1,000 and 10,000 free vertices, seeds k = 0, 1, 2. A
  disc: the vertices within edge-graph (BFS hop) distance r of a seed vertex, r the
  smallest radius that gives at least the size in free vertices, vertices on the mesh
  border excluded from free, enclosed fixed pockets of at most 10 vertices filled (a
  larger part cut off, e.g. a limb, stays fixed: another boundary loop). The solver gets
  a submesh: the triangles with a free vertex and two rings of fixed triangles around
  them; the G1 normals come from the surrounding fixed triangles (fair()'s default), and
  where a boundary vertex has none (on the mesh border, or a fixed vertex between free
  ones on the jagged front of the disc) its area-weighted normal over all its triangles
  is passed in ``boundary_normals``.
  Seed vertices: a permutation of the mesh's non-border vertices by
  ``numpy.random.default_rng([crc32(mesh), size, k])``, taken in order; a candidate whose
  region is invalid input (the seed's component is too small, a free vertex's triangles
  are not one consistently oriented manifold fan, or fair() raises ValueError) is
  skipped and counted in "inval". A size above 80 % of a mesh's vertex count is skipped
  for that mesh (printed at the start).
- ``blender/...``: primitives made by Blender through the ``bpy`` module (pip bpy; made
  in a subprocess, cached as .npz in the cache folder; without bpy these cases are skipped with a
  note), quads triangulated by ``bmesh.ops.triangulate`` and given to ``geofair.fair``
  with their ``polygon_ids`` (the polygon each triangle came from), as the add-on passes
  them: the UV sphere (64 segments, 32
  rings, radius 1) and icospheres of 4, 5, 6 (7 with --large) subdivisions (regular
  meshes), each with the cap above z = 0.25 free and flattened onto the plane z = 0.25
  (G1 normals: the exact sphere normals), radial error reported; Suzanne subdivided twice
  (Subdivision Surface level 2 applied, her separate eyes dropped) with the regions brow
  (scripts/main_job.py), ear and eye socket (the socket reaches the open border around
  the eye), each the faces whose centroid is in a ball (``geofair_dev.regions.ball_region``);
  the torus (``primitive_torus_add`` defaults) with geodesic discs of about 100 free
  vertices, seeds 0, 1, 2.
- ``paper/...``: the tetrathing of 500 and 13,308 vertices (geofair_dev.paper_scenes, exact
  normals as ``boundary_normals``), the bunny ear and the mannequin face as
  scripts/results.py selects them (geofair_dev.regions; as submeshes, the same triangles
  fair() uses).
- ``regular/sphere_cap_<n>``: bench/speed.py's caps with ``--regular`` (geofair_dev.caps:
  disturbed regular sphere caps, exact normals), about 2,000 and 13,000 free vertices
  (100,000 with --large); radial error reported.

--quick: 18 cases of at most about 1,000 free vertices. The inputs are cached in the folder
``cache`` (default /tmp/geofair_realmesh_cases) and reused; the Blender primitives are made
by ``python3 -m geofair_dev.corpus --make-blender --cache DIR`` (a subprocess that imports bpy).
"""

import argparse
import importlib.util
import json
import os
import subprocess
import sys
import tarfile
import zlib

import numpy as np

from geofair_dev import caps, paths, scenes
from geofair_dev.regions import CGAL_DATA

CGAL_MESHES = ("elk", "bull", "dino", "lion-head", "knot1", "blobby", "cactus", "hand", "bear", "cheese",
               "diplodocus", "ChineseDragon-10kv")  # fmt: skip
SIZES = (100, 1000, 10000)
SEEDS = 3
MAX_FILL = 0.8  # a disc size above this fraction of the mesh's vertices is skipped
MAX_CANDIDATES = 40  # seed candidates tried per case before giving up
POCKET = 10  # fixed parts of at most this many vertices enclosed by a disc are filled
RINGS = 2  # fixed triangle rings around the free region in the submesh
CAP_Z = 0.25
ICOSPHERES = (4, 5, 6)
ICOSPHERE_LARGE = 7
TORUS_SIZE = 100
# Suzanne (subdivided twice, 2.7 wide): faces whose centroid lies within the radius.
SUZANNE_REGIONS = {
    "brow": ((0.45, -0.72, 0.62), 0.3),  # scripts/main_job.py REGION_CENTRE, REGION_RADIUS
    "ear": ((1.15, 0.4, 0.2), 0.25),  # the left ear, x = 1.0 .. 1.33
    "eye_socket": ((0.35, -0.68, 0.25), 0.3),  # around the left eye's hole: an open border
}
REGULAR_CAPS = (2000, 13000)
REGULAR_CAP_LARGE = 100000
QUICK_DISCS = [(m, 100) for m in ("elk", "bull", "dino", "knot1", "blobby", "cactus", "hand", "cheese")]
QUICK_DISCS += [("bull", 1000), ("lion-head", 1000)]
DEFAULT_CACHE = "/tmp/geofair_realmesh_cases"
CORPUS_VERSION = 2  # part of the cached case file names: bump when a case definition changes


# --------------------------------------------------------------------------------------
# Meshes


def read_off(text):
    """(vertices (n, 3) float64, triangles (m, 3) int64) of an OFF/COFF text; polygons are
    fan-triangulated, colours and comments ignored."""
    lines = [s for s in (line.split("#", 1)[0].strip() for line in text.splitlines()) if s]
    head = lines[0].split()
    if not head[0].endswith("OFF"):
        raise ValueError("not an OFF file")
    counts, i = head[1:], 1
    if not counts:
        counts, i = lines[1].split(), 2
    nv, nf = int(counts[0]), int(counts[1])
    vertices = np.array([line.split()[:3] for line in lines[i : i + nv]], float)
    tris = []
    for line in lines[i + nv : i + nv + nf]:
        t = line.split()
        ids = [int(x) for x in t[1 : 1 + int(t[0])]]
        tris += [(ids[0], ids[j], ids[j + 1]) for j in range(1, len(ids) - 1)]
    return vertices, np.array(tris, np.int64).reshape(-1, 3)


def cgal_vertex_counts(names):
    """{name: vertex count} from the OFF headers in CGAL's archive (one pass)."""
    wanted = {f"data/meshes/{n}.off": n for n in names}
    out = {}
    with tarfile.open(CGAL_DATA) as tar:
        for member in tar:
            if member.name not in wanted:
                continue
            f = tar.extractfile(member)
            tokens = []
            while len(tokens) < 3:
                tokens += f.readline().decode().split("#", 1)[0].split()
            out[wanted[member.name]] = int(tokens[1])
            if len(out) == len(wanted):
                break
    return out


def _cached(cache, name, make):
    """{array name: array} from cache/name.npz, made by make() (a dict) if missing."""
    path = os.path.join(cache, name + ".npz")
    if not os.path.exists(path):
        arrays = make()
        os.makedirs(cache, exist_ok=True)
        tmp = f"{path}.{os.getpid()}.tmp.npz"
        np.savez(tmp, **arrays)
        os.replace(tmp, path)
    with np.load(path) as d:
        return {k: d[k] for k in d.files}


def cgal_mesh(name, cache=DEFAULT_CACHE):
    """(vertices, triangles) of data/meshes/<name>.off in CGAL's archive."""

    def make():
        with tarfile.open(CGAL_DATA) as tar:
            v, f = read_off(tar.extractfile(f"data/meshes/{name}.off").read().decode(errors="replace"))
        return {"vertices": v, "faces": f}

    d = _cached(cache, f"mesh_cgal_{name}", make)
    return d["vertices"], d["faces"]


BLENDER_MESHES = ("uv_sphere", *(f"icosphere{k}" for k in (*ICOSPHERES, ICOSPHERE_LARGE)), "suzanne", "torus")


def bpy_available():
    return importlib.util.find_spec("bpy") is not None


def blender_mesh(name, cache=DEFAULT_CACHE):
    """(vertices, triangles, polygon of each triangle) of a Blender primitive; made (all of
    them at once) by a subprocess that imports bpy, cached as .npz."""
    path = os.path.join(cache, f"mesh_blender_{name}.npz")
    if os.path.exists(path):
        with np.load(path) as d:
            if "polygons" not in d.files:  # made before the polygons were kept
                os.remove(path)
    if not os.path.exists(path):
        os.makedirs(cache, exist_ok=True)
        cmd = [sys.executable, "-m", "geofair_dev.corpus", "--make-blender", "--cache", cache]
        run = subprocess.run(cmd, capture_output=True, text=True, env=paths.subprocess_env())
        if run.returncode != 0 or not os.path.exists(path):
            raise RuntimeError(f"making the Blender meshes failed: {run.stderr.strip()[-500:]}")
    with np.load(path) as d:
        return d["vertices"], d["faces"], d["polygons"]


def make_blender_meshes(cache):
    """Runs in its own process: Blender's primitives, triangulated (with the polygon of each
    triangle), as .npz."""
    import bpy  # first: the bpy module from PyPI makes bmesh importable

    # isort: split
    import bmesh

    from geofair_dev.blender import add_subdivided_suzanne

    makers = {
        "uv_sphere": lambda: bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=1.0),
        "suzanne": add_subdivided_suzanne,
        "torus": lambda: bpy.ops.mesh.primitive_torus_add(),
    }
    for k in (*ICOSPHERES, ICOSPHERE_LARGE):
        makers[f"icosphere{k}"] = lambda k=k: bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=k, radius=1.0)
    for name in BLENDER_MESHES:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        makers[name]()
        bm = bmesh.new()
        bm.from_mesh(bpy.context.active_object.data)
        polygon = bm.faces.layers.int.new("polygon")  # the triangles inherit their polygon's value
        for face in bm.faces:
            face[polygon] = face.index
        bmesh.ops.triangulate(bm, faces=bm.faces[:])
        bm.verts.index_update()
        v = np.array([x.co[:] for x in bm.verts], float)
        f = np.array([[x.index for x in face.verts] for face in bm.faces], np.int64)
        p = np.array([face[polygon] for face in bm.faces], np.int64)
        bm.free()
        path = os.path.join(cache, f"mesh_blender_{name}.npz")
        tmp = f"{path}.{os.getpid()}.tmp.npz"  # one per process: parallel test workers
        np.savez(tmp, vertices=v, faces=f, polygons=p)
        os.replace(tmp, path)
        print(f"{name}: {len(v)} vertices, {len(f)} triangles", flush=True)


# --------------------------------------------------------------------------------------
# Regions


def _adjacency(faces, n):
    from scipy.sparse import coo_matrix

    e = scenes.edges(faces)
    return coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()


def disc_free(vertices, faces, seed_vertex, target, border=None):
    """(free (n,) bool, radius) of the geodesic disc around seed_vertex with at least
    target free vertices (border vertices excluded, pockets filled), or (None, None) if
    the seed's component is too small."""
    from scipy.sparse.csgraph import connected_components, shortest_path

    n = len(vertices)
    border = scenes.border_mask(faces, n) if border is None else border
    dist = shortest_path(_adjacency(faces, n), directed=False, unweighted=True, indices=seed_vertex)
    ok = np.isfinite(dist) & ~border
    cum = np.cumsum(np.bincount(dist[ok].astype(np.int64)))
    if cum[-1] < target:
        return None, None
    r = int(np.searchsorted(cum, target))
    disc = np.isfinite(dist) & (dist <= r)
    # Fill pockets: parts of the rest of the seed's component of at most POCKET vertices
    # cut off from the rest (specks of the hop metric; larger cut-off parts, e.g. a limb,
    # stay fixed: another boundary loop of the region).
    rest = np.flatnonzero(np.isfinite(dist) & ~disc)
    if len(rest):
        _, label = connected_components(_adjacency(faces, n)[rest][:, rest], directed=False)
        size = np.bincount(label)
        if len(size) > 1:
            disc[rest[size[label] <= POCKET]] = True
    return disc & ~border, r


def submesh(vertices, faces, free, rings=RINGS, polygons=None):
    """The triangles with a free vertex and `rings` rings of triangles around them,
    reindexed: (vertices, faces, free, original vertex ids), and with ``polygons`` (one id
    per triangle) the ids of the triangles kept."""
    n = len(vertices)
    sel = free[faces].any(axis=1)
    for _ in range(rings):
        touched = np.zeros(n, bool)
        touched[faces[sel]] = True
        sel = touched[faces].any(axis=1)
    used = np.unique(faces[sel])
    local = np.full(n, -1, np.int64)
    local[used] = np.arange(len(used))
    if polygons is not None:
        return vertices[used], local[faces[sel]], free[used], used, polygons[sel]
    return vertices[used], local[faces[sel]], free[used], used


def region_problem(faces, free):
    """Why fair() would reject the region (the triangles with a free vertex) as
    topologically invalid, or None: a repeated vertex, a non-manifold or inconsistently
    oriented edge, a free vertex whose triangles are not one closed fan, no fixed vertex."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = len(free)
    reg = faces[free[faces].any(axis=1)]
    if len(reg) == 0:
        return "no vertex is free"
    if ((reg[:, 0] == reg[:, 1]) | (reg[:, 1] == reg[:, 2]) | (reg[:, 0] == reg[:, 2])).any():
        return "a triangle repeats a vertex"
    d = np.concatenate([reg[:, [0, 1]], reg[:, [1, 2]], reg[:, [2, 0]]])
    key = d[:, 0] * n + d[:, 1]
    if len(np.unique(key)) < len(key):
        return "a non-manifold or inconsistently oriented edge"
    if ((free[d[:, 0]] | free[d[:, 1]]) & ~np.isin(d[:, 1] * n + d[:, 0], key)).any():
        return "a free vertex on the border"
    if free[reg].all():
        return "every vertex of the region is free"
    a, b, c = reg.ravel(), np.roll(reg, -1, axis=1).ravel(), np.roll(reg, -2, axis=1).ravel()
    m = free[a]
    a, b, c = a[m], b[m], c[m]
    nodes, inv = np.unique(np.concatenate([a * n + b, a * n + c]), return_inverse=True)
    k = len(a)
    graph = coo_matrix((np.ones(k), (inv[:k], inv[k:])), shape=(len(nodes), len(nodes)))
    _, label = connected_components(graph, directed=False)
    if len(np.unique((nodes // n) * len(nodes) + label)) != int(free.sum()):
        return "a free vertex whose triangles are not one fan"
    return None


def region_topology(faces, free):
    """Topology of the region (the triangles with a free vertex): (kind, Euler
    characteristic V - E + F, boundary loops), kind "disc" (one loop, χ = 1), "annulus"
    (two loops, χ = 0: a tube or a ring) or "other" (more loops, or handles). Loops are
    the connected components of the border edges (two loops touching at a vertex count
    as one)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    reg = np.asarray(faces, np.int64)[np.asarray(free)[faces].any(axis=1)]
    e = np.sort(np.concatenate([reg[:, [0, 1]], reg[:, [1, 2]], reg[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(e, axis=0, return_counts=True)
    chi = len(np.unique(reg)) - len(uniq) + len(reg)
    border = uniq[count == 1]
    loops = 0
    if len(border):
        n = len(free)
        graph = coo_matrix((np.ones(len(border)), (border[:, 0], border[:, 1])), shape=(n, n))
        _, label = connected_components(graph, directed=False)
        loops = len(np.unique(label[border[:, 0]]))
    kind = {(1, 1): "disc", (2, 0): "annulus"}.get((loops, chi), "other")
    return kind, int(chi), loops


def _vertex_sums(faces, values, n):
    return np.stack([np.bincount(faces.ravel(), np.repeat(values[:, c], 3), minlength=n) for c in range(3)], 1)


def g1_normals(vertices, faces, free):
    """None when every G1 boundary vertex (a fixed vertex of a triangle with a free one)
    has a triangle without free vertices (fair()'s default normal applies); else (n, 3)
    unit normals: fair()'s default (area-weighted over those triangles) where it exists,
    the area-weighted normal over all the vertex's triangles elsewhere (the mesh border)."""
    n = len(vertices)
    p = vertices[faces]
    cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    touches = free[faces].any(axis=1)
    g1 = np.zeros(n, bool)
    g1[faces[touches]] = True
    g1 &= ~free
    outer = _vertex_sums(faces[~touches], cross[~touches], n)
    has = np.linalg.norm(outer, axis=1) > 0
    if has[g1].all():
        return None
    out = np.where(has[:, None], outer, _vertex_sums(faces, cross, n))
    length = np.linalg.norm(out, axis=1)
    out[~g1] = (0.0, 0.0, 1.0)
    length[~g1] = 1.0
    return out / length[:, None]


def new_folds(vertices_before, vertices_after, faces, free):
    """Number of edges with a free endpoint and two triangles whose normals have a
    negative dot product in vertices_after but not in vertices_before (None: all of them)."""
    faces = np.asarray(faces, np.int64)
    n = len(vertices_after)
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    e.sort(axis=1)
    owner = np.tile(np.arange(len(faces)), 3)
    key = e[:, 0] * n + e[:, 1]
    order = np.argsort(key, kind="stable")
    key, owner, e = key[order], owner[order], e[order]
    uniq, start, count = np.unique(key, return_index=True, return_counts=True)
    two = (count == 2) & (free[e[start, 0]] | free[e[start, 1]])
    f1, f2 = owner[start[two]], owner[start[two] + 1]

    def folded(v):
        p = v[faces]
        cr = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        return np.einsum("ij,ij->i", cr[f1], cr[f2]) < 0

    after = folded(np.asarray(vertices_after))
    return int((after if vertices_before is None else after & ~folded(np.asarray(vertices_before))).sum())


# --------------------------------------------------------------------------------------
# The corpus


def corpus(quick=False, large=False, cache=DEFAULT_CACHE):
    """(case descriptors, notes): the cases and what was skipped, and why."""
    notes, out = [], []
    counts = cgal_vertex_counts(CGAL_MESHES)
    discs = QUICK_DISCS if quick else [(m, s) for m in CGAL_MESHES for s in SIZES]
    for mesh, size in discs:
        if size > MAX_FILL * counts[mesh]:
            notes.append(f"cgal/{mesh}/{size}: skipped, the mesh has only {counts[mesh]} vertices")
            continue
        for k in range(1 if quick else SEEDS):
            out.append({"name": f"cgal/{mesh}/{size}/s{k}", "kind": "disc", "mesh": f"cgal:{mesh}", "size": size,
                        "slot": k})  # fmt: skip
    if bpy_available() or os.path.exists(os.path.join(cache, "mesh_blender_torus.npz")):
        for k in range(1 if quick else SEEDS):
            out.append({"name": f"blender/torus/{TORUS_SIZE}/s{k}", "kind": "disc", "mesh": "blender:torus",
                        "size": TORUS_SIZE, "slot": k})  # fmt: skip
        spheres = ["uv_sphere"] + [f"icosphere{k}" for k in ICOSPHERES[: 2 if quick else None]]
        spheres += [f"icosphere{ICOSPHERE_LARGE}"] if large and not quick else []
        out += [{"name": f"blender/{s}_cap", "kind": "cap", "mesh": f"blender:{s}"} for s in spheres]
        out += [{"name": f"blender/suzanne_{r}", "kind": "ball", "mesh": "blender:suzanne", "region": r}
                for r in SUZANNE_REGIONS]  # fmt: skip
    else:
        notes.append("blender/*: skipped, bpy is not importable (pip install 'bpy==4.5.*')")
    tetrathings = (500,) if quick else (500, 13308)
    out += [{"name": f"paper/tetrathing_{n}", "kind": "tetrathing", "n": n} for n in tetrathings]
    if not quick:
        out.append({"name": "paper/bunny_ear", "kind": "ball", "mesh": "cgal:bunny00", "region": "EAR"})
        out.append({"name": "paper/mannequin_face", "kind": "ball", "mesh": "cgal:mannequin-devil", "region": "FACE"})
        sizes = REGULAR_CAPS + ((REGULAR_CAP_LARGE,) if large else ())
        out += [{"name": f"regular/sphere_cap_{n}", "kind": "regular_cap", "n": n} for n in sizes]
    return out, notes


def cases(quick=False, large=False):
    """Lightweight case descriptors (JSON-able dicts with a "name"); see load_case."""
    return corpus(quick, large)[0]


def _mesh(spec, cache):
    """(vertices, faces, polygon of each triangle or None)."""
    where, name = spec.split(":", 1)
    return (*cgal_mesh(name, cache), None) if where == "cgal" else blender_mesh(name, cache)


def _largest_component(vertices, faces, polygons):
    from scipy.sparse.csgraph import connected_components

    _, label = connected_components(_adjacency(faces, len(vertices)), directed=False)
    biggest = np.argmax(np.bincount(label[faces[:, 0]]))
    keep = label[faces[:, 0]] == biggest
    used = np.unique(faces[keep])
    local = np.full(len(vertices), -1, np.int64)
    local[used] = np.arange(len(used))
    return vertices[used], local[faces[keep]], None if polygons is None else polygons[keep]


def _region_case(vertices, faces, free, meta, polygons=None):
    if polygons is None:
        v, f, fr, _ = submesh(vertices, faces, free)
    else:
        v, f, fr, _, polygons = submesh(vertices, faces, free, polygons=polygons)
    case = {"vertices": v, "faces": f, "free": fr, "boundary_normals": g1_normals(v, f, fr), "meta": meta}
    return dict(case, polygon_ids=polygons)


def load_case(desc, cache=DEFAULT_CACHE):
    """The arrays of a case: dict(vertices (n, 3) float64, faces (m, 3) int64, free (n,)
    bool, boundary_normals (n, 3) or None, polygon_ids (m,) int64 or None (Blender's
    meshes: the polygon each triangle came from), meta: dict). Disc cases take the first valid
    seed candidate from desc.get("attempt", 0) on; meta["invalid"] is the number of
    candidates before it (all invalid)."""
    kind, meta = desc["kind"], {"name": desc["name"], "sphere": False}
    if kind == "disc":
        v, f, polygons = _mesh(desc["mesh"], cache)
        n = len(v)
        border = scenes.border_mask(f, n)
        used = np.zeros(n, bool)
        used[f] = True
        rng = np.random.default_rng([zlib.crc32(desc["mesh"].encode()), desc["size"], desc["slot"]])
        order = rng.permutation(np.flatnonzero(used & ~border))
        first = desc.get("attempt", 0)
        reasons = []
        for j in range(first, min(first + MAX_CANDIDATES, len(order))):
            free, r = disc_free(v, f, int(order[j]), desc["size"], border)
            problem = "the seed's component is too small" if free is None else None
            if free is not None:
                meta_j = dict(meta, seed_vertex=int(order[j]), radius=r, invalid=j)
                case = _region_case(v, f, free, meta_j, polygons)
                problem = region_problem(case["faces"], case["free"])
                if problem is None and case["boundary_normals"] is not None:
                    bn, g1 = case["boundary_normals"], case["free"][case["faces"]].any(axis=1)
                    if not np.isfinite(bn[case["faces"][g1]]).all():
                        problem = "a G1 boundary vertex without a normal"
                if problem is None:
                    case["meta"]["redraw_reasons"] = reasons
                    return case
            reasons.append(f"seed {int(order[j])}: {problem}")
        raise ValueError(f"{desc['name']}: no valid seed in {MAX_CANDIDATES} candidates ({reasons[-1]})")
    if kind == "cap":
        v, f, polygons = _mesh(desc["mesh"], cache)
        v, f, free, _, polygons = submesh(v, f, v[:, 2] > CAP_Z, polygons=polygons)
        normals = v / np.linalg.norm(v, axis=1, keepdims=True)
        v = v.copy()
        v[free, 2] = CAP_Z
        meta.update(sphere=True)
        return {"vertices": v, "faces": f, "free": free, "boundary_normals": normals, "polygon_ids": polygons,
                "meta": meta}  # fmt: skip
    if kind == "ball":
        from geofair_dev import regions  # ball_region and the paper's regions

        v, f, polygons = _mesh(desc["mesh"], cache)
        if desc["mesh"] == "blender:suzanne":
            v, f, polygons = _largest_component(v, f, polygons)  # the head, without the eyes
            centre, radius = SUZANNE_REGIONS[desc["region"]]
        else:
            centre, radius = getattr(regions, desc["region"])
        _, free = regions.ball_region(v, f, centre, radius)
        free &= ~scenes.border_mask(f, len(v))
        return _region_case(v, f, free, meta, polygons)
    if kind == "tetrathing":
        from geofair_dev import paper_scenes

        def make():
            sc = paper_scenes.tetrathing(desc["n"])
            return {"vertices": sc.vertices, "faces": sc.faces, "free": sc.free, "normals": sc.normals}

        d = _cached(cache, f"scene_tetrathing_{desc['n']}", make)
        return {"vertices": d["vertices"], "faces": d["faces"], "free": d["free"], "boundary_normals": d["normals"],
                "polygon_ids": None, "meta": meta}  # fmt: skip
    if kind == "regular_cap":
        v, f, free, normals = caps.load_scene(cache, desc["n"], "regular")
        meta.update(sphere=True)
        return {"vertices": v, "faces": f, "free": free, "boundary_normals": normals, "polygon_ids": None,
                "meta": meta}  # fmt: skip
    raise ValueError(f"unknown case kind {kind!r}")


def case_file(desc, cache):
    """Path of the case's input .npz (made by load_case on first use)."""
    safe = "".join(c if c.isalnum() else "_" for c in desc["name"])
    path = os.path.join(cache, "cases", f"v{CORPUS_VERSION}_{safe}_a{desc.get('attempt', 0)}.npz")
    if not os.path.exists(path):
        case = load_case(desc, cache)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        bn, polygons = case["boundary_normals"], case["polygon_ids"]
        tmp = f"{path}.{os.getpid()}.tmp.npz"
        np.savez(tmp, vertices=case["vertices"], faces=case["faces"], free=case["free"],
                 boundary_normals=np.zeros((0, 3)) if bn is None else bn,
                 polygon_ids=np.zeros(0, np.int64) if polygons is None else polygons,
                 meta=json.dumps(case["meta"]))  # fmt: skip
        os.replace(tmp, path)
    return path


def main():
    """``--make-blender --cache DIR``: make Blender's primitives (run by ``blender_mesh``)."""
    parser = argparse.ArgumentParser(description="Make the corpus's Blender primitives (needs bpy).")
    parser.add_argument("--make-blender", action="store_true", required=True)
    parser.add_argument("--cache", default=DEFAULT_CACHE)
    make_blender_meshes(parser.parse_args().cache)


if __name__ == "__main__":
    main()
