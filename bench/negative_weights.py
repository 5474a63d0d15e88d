"""Conformal inner fairness on meshes of obtuse triangles: inner_fairness="conformal"
(the mesh's cotangent weights, negative ones clamped at 0) against "conformal_intrinsic"
(the cotangent weights of the intrinsic Delaunay triangulation, Bobenko & Springborn 2007).

Accuracy. Meshes: scenes.squashed_lattice (nearly every triangle 133 degrees at its apex)
on the plane z = 0 and on the unit cylinder over 120 degrees; the free vertices of the
original are pushed off the surface by a bump of 0.1 plus 30% noise (as in
tests/test_negative_weights.py), so the weights come from a curved, obtuse original; G1
boundary normals exact. The faired surface is then the plane or the cylinder, and the
vertex positions on it are decided by inner fairness alone: the discrete harmonic map with
the intrinsic Delaunay weights of the original region (solved with scipy, geofair_dev.harmonic,
from geofair.intrinsic_delaunay_laplacian). Columns: free vertices; share of obtuse
triangles; intrinsic flips; "clamped map": max distance between the harmonic maps with
the clamped and with the intrinsic weights; per mode, the max distance of the faired free
vertices to the intrinsic harmonic map (mean edge lengths), the max distance to the
surface (mesh units), iterations and time. Levels as by default (one for the smaller, three
for the larger mesh), and one level on the plane: there H = 0 from the start, so the
result is the linear initial mesh, whose tangential part is the harmonic map on one level;
with multigrid the finest level starts from the prolongation and stops at once, with any
inner fairness (the residual measures outer fairness only).

Stability. Irregular 600-vertex sphere caps disturbed with noise as large as the bump
(needle and obtuse triangles everywhere, as in test_conformal_weights_of_a_rough_mesh),
max_iterations 5000: converged or the residual left, iterations, radial error.

    PYTHONPATH=build/python python3 bench/negative_weights.py [--quick]

--quick: without the 3000-vertex lattices (a minute each). Times on a shared machine are
noisy.
"""

import argparse
import time

import numpy as np

import geofair
from geofair_dev import harmonic, scenes


def scene(surface, nu, seed=3):
    """Original vertices, faces, free, normals and (u, v) of the lattice, on `surface`."""
    width = np.radians(120.0) if surface == "cylinder" else 2.0
    uv, f = scenes.squashed_lattice(nu, width)
    u, z = uv.T
    if surface == "cylinder":
        v = np.column_stack([np.cos(u), np.sin(u), z])
        n = np.column_stack([np.cos(u), np.sin(u), np.zeros_like(u)])
    else:
        v = np.column_stack([u, z, np.zeros_like(u)])
        n = np.tile([0.0, 0.0, 1.0], (len(u), 1))
    free = ~scenes.border_mask(f, len(v))
    rng = np.random.default_rng(seed)
    bump = (1 - (z / np.abs(z).max()) ** 2) * (1 - (u / np.abs(u).max()) ** 2)
    x = v + (free * 0.1 * bump * (1 + 0.3 * rng.uniform(-1, 1, len(v))))[:, None] * n
    return x, f, free, n, uv


def reference_map(surface, L, uv, free):
    if surface == "cylinder":
        u, z = harmonic.cylinder_harmonic_map(L, uv[:, 0], uv[:, 1], free)
        return np.column_stack([np.cos(u), np.sin(u), z])
    p = harmonic.planar_harmonic_map(L, uv, free)
    return np.column_stack([p, np.zeros(len(p))])


MODES = ("conformal", "conformal_intrinsic")


def accuracy(quick):
    print(
        "| surface | levels | free | obtuse | flips | clamped map | "
        + " | ".join(f"{m}: off map, surface error, iterations, time [s]" for m in MODES)
        + " |"
    )
    print("|---|---:|---:|---:|---:|---:|" + "---|" * len(MODES))
    rows = [("plane", 14, 1), ("cylinder", 14, 0)]
    if not quick:
        rows += [("plane", 40, 1), ("plane", 40, 0), ("cylinder", 40, 0)]
    for surface, nu, levels in rows:
        x, f, free, n, uv = scene(surface, nu)
        region = harmonic.region_faces(f, free)
        flips = geofair.intrinsic_delaunay(x, region)[2]
        obtuse = (scenes.triangle_angles(x, region).max(axis=1) > 90).mean()
        intrinsic = reference_map(surface, geofair.intrinsic_delaunay_laplacian(x, region), uv, free)
        clamped = reference_map(surface, harmonic.clamped(geofair.cotangent_laplacian(x, region)), uv, free)
        e = scenes.edges(region)
        h = np.linalg.norm(intrinsic[e[:, 0]] - intrinsic[e[:, 1]], axis=1).mean()
        cells = []
        for mode in MODES:
            t = time.perf_counter()
            r = geofair.fair(
                x,
                f,
                free,
                boundary_normals=n,
                inner_fairness=mode,
                levels=levels,
                max_iterations=50000,
                iteration=ITERATION[0],
            )
            t = time.perf_counter() - t
            q = r.vertices[free]
            error = np.abs(q[:, 2] if surface == "plane" else np.hypot(q[:, 0], q[:, 1]) - 1).max()
            off = np.linalg.norm(q - intrinsic[free], axis=1).max() / h
            converged = "" if r.converged else " (not converged)"
            cells.append(f"{off:.1e}, {error:.1e}, {r.iterations}{converged}, {t:.2f}")
        clamped_off = np.linalg.norm(clamped - intrinsic, axis=1)[free].max() / h
        head = f"| {surface} | {len(r.iterations_per_level)} | {free.sum()} | {obtuse:.0%} | {flips} "
        print(head + f"| {clamped_off:.2f} | " + " | ".join(cells) + " |")


ITERATION = ["paper"]  # the README's figures; --iteration changes it


def stability():
    print("\n| rough cap (seed) | flips | " + " | ".join(f"{m}: residual, iterations, error" for m in MODES) + " |")
    print("|---|---:|" + "---|" * len(MODES))
    for seed in (8, 10, 12, 14):
        s = scenes.sphere_cap(n_free=600, irregular=True, seed=seed)
        x = s.disturbed(seed=seed + 1, amplitude=0.1, noise=1.0)
        flips = geofair.intrinsic_delaunay(x, harmonic.region_faces(s.faces, s.free))[2]
        cells = []
        for mode in MODES:
            r = geofair.fair(
                x,
                s.faces,
                s.free,
                boundary_normals=s.normals,
                inner_fairness=mode,
                max_iterations=5000,
                iteration=ITERATION[0],
            )
            error = np.abs(s.distance(r.vertices[s.free])).max()
            cells.append(f"{'converged' if r.converged else f'{r.residual:.2g}'}, {r.iterations}, {error:.1e}")
        print(f"| {seed} | {flips} | " + " | ".join(cells) + " |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--iteration", default="paper", help="paper (default), newton or auto")
    parser.add_argument("--stability-only", action="store_true")
    args = parser.parse_args()
    ITERATION[0] = args.iteration
    if not args.stability_only:
        accuracy(args.quick)
    stability()


if __name__ == "__main__":
    main()
