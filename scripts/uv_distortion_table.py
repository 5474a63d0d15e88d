"""Texture distortion of uniform vs conformal inner fairness on Suzanne: a Markdown table for the README.

    blender --background --factory-startup --python-exit-code 1 \\
        --python scripts/uv_distortion_table.py -- --addon build/addon

For each region of Suzanne (subdivided twice; she comes with a UV map) and each
inner fairness, fairs a fresh copy with ``geometric_fairing.fair_object``
(intrinsic outer fairness, tolerance 1e-4) and measures the conformal
distortion σ1/σ2 of the UV map (1 = angles kept) over the triangles with a free
vertex, before and after. A run that fails or does not converge is listed as
such (uniform inner fairness is known not to converge on some of Suzanne's
regions).
"""

import argparse
import pathlib
import sys

import bpy
import numpy as np

from geofair_dev import paths
from geofair_dev.blender import add_subdivided_suzanne

# Regions: faces whose centre lies within the radius (Suzanne is 2.7 wide).
REGIONS = (
    ("left brow", (0.4, -0.7, 0.72), 0.25),
    ("left cheek", (0.55, -0.6, 0.0), 0.2),
    ("below the left eye", (0.3, -0.8, 0.45), 0.15),
)


def parse_args():
    parser = argparse.ArgumentParser(prog="uv_distortion_table.py")
    parser.add_argument("--addon", type=pathlib.Path, default=pathlib.Path("build/addon"))
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else [])


def main():
    args = parse_args()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    geometric_fairing = paths.import_addon(args.addon)
    print(f"Blender {bpy.app.version_string}, Suzanne subdivided twice, intrinsic outer fairness, tolerance 1e-4\n")
    print(
        "| region | free vertices | inner fairness | iterations | UV σ1/σ2 mean: before → after | max: before → after |"
    )
    print("|---|---:|---|---:|---|---|")
    for name, centre, radius in REGIONS:
        for inner in ("uniform", "conformal"):
            obj = add_subdivided_suzanne()
            centres = np.empty(3 * len(obj.data.polygons))
            obj.data.polygons.foreach_get("center", centres)
            faces = np.linalg.norm(centres.reshape(-1, 3) - centre, axis=1) < radius
            try:
                report = geometric_fairing.fair_object(obj, region=faces, inner_fairness=inner, tolerance=1e-4)
            except (ValueError, RuntimeError) as error:
                print(f"| {name} | | {inner} | failed: {error} | | |")
                continue
            finally:
                bpy.data.objects.remove(obj)
            before, after = report.uv_before, report.uv_after
            iterations = f"{report.iterations}" + ("" if report.converged else " (not converged)")
            print(
                f"| {name} | {report.free_vertices} | {inner} | {iterations} | "
                f"{before.mean:.3f} → {after.mean:.3f} | {before.max:.2f} → {after.max:.2f} |"
            )


main()
