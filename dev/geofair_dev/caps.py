"""The sphere caps of the speed benchmarks, generated once and cached as .npz files.

``load_scene(cache, n, kind, seed=1)``: (start vertices, faces, free, G1 normals or None) of
the cap with about ``n`` free vertices, made by ``geofair_dev.scenes`` on first use and kept in the
folder ``cache`` (bench/speed.py's ``--cache``, default /tmp/geofair_bench_scenes; the
real-mesh corpus's regular caps, bench/blender_roundtrip.py's meshes). Kinds:

- ``irregular``, ``regular``: ``scenes.sphere_cap(n_free=n, irregular=..., seed=seed,
  boundary_rings=2)`` disturbed by ``disturbed(seed=seed + 1, amplitude=0.1)``, exact normals;
- ``random``, ``icosphere``: ``scenes.flattened_sphere_cap(n, kind, seed=seed)``; exact
  normals on the random caps, None (the library's estimate) on the icosphere caps (whose
  seed only moves the jitter).

Generating the 1M-vertex irregular cap takes about 5 minutes and 1 GiB (100k: 11 s).
"""

import os
import sys
import time

import numpy as np

FLATTENED = ("random", "icosphere")  # scenes.flattened_sphere_cap's constructions


def scene_path(cache, n, kind="irregular", seed=1):
    if kind in FLATTENED:
        return os.path.join(cache, f"flattened_sphere_cap_{kind}_seed{seed}_{n}.npz")
    return os.path.join(cache, f"sphere_cap_{kind}_seed{seed}_rings2_{n}.npz")


def load_scene(cache, n, kind="irregular", seed=1):
    """(start vertices, faces, free, G1 normals or None) of the cap with about n free vertices."""
    path = scene_path(cache, n, kind, seed)
    if not os.path.exists(path):
        from geofair_dev import scenes

        t = time.perf_counter()
        if kind in FLATTENED:
            s, v = scenes.flattened_sphere_cap(n, kind, seed=seed)
        else:
            s = scenes.sphere_cap(n_free=n, irregular=kind == "irregular", seed=seed, boundary_rings=2)
            v = s.disturbed(seed=seed + 1, amplitude=0.1)
        os.makedirs(cache, exist_ok=True)
        tmp = f"{path}.{os.getpid()}.tmp.npz"  # one per process: parallel test workers
        np.savez(tmp, vertices=v, faces=s.faces.astype(np.int32), free=s.free, normals=s.normals)
        os.replace(tmp, path)
        print(f"# generated {path} in {time.perf_counter() - t:.0f} s", file=sys.stderr, flush=True)
    d = np.load(path)
    return d["vertices"], d["faces"], d["free"], None if kind == "icosphere" else d["normals"]
