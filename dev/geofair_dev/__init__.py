"""geofair_dev: the development package of the repository's tests, benchmarks and scripts.

What tests/, bench/, scripts/ and examples/ share, imported the same way by all of them
(``from geofair_dev import scenes``); none of them imports another's files.

- ``paths``: where things are (the repository, the build and its ``geofair`` module, the
  add-on) and the one place that puts a folder on ``sys.path``.
- ``scenes``: analytic test scenes (sphere caps, patches, tubes, Blender's UV sphere) with
  exact normals and distances; mesh helpers (edges, border, normals, angles).
- ``measures``: distances between meshes (Hausdorff, symmetry error).
- ``paper_scenes``: the paper's cylinder blend and tetrathing.
- ``harmonic``: discrete harmonic maps (scipy), the reference of conformal inner fairness.
- ``polygons``: Blender's UV sphere with its quads split four ways, its cap faired.
- ``regions``: the paper's regions of CGAL's demo meshes (``ball_region``), harmonic disk UV.
- ``caps``: the speed benchmark's sphere caps, cached as .npz.
- ``corpus``: the real-mesh corpus (bench/realmesh.py, tests/test_realmesh.py).
- ``cgal_fair``: CGAL's linear fair as a reference (runs build/bench/cgal_fair).
- ``holes``: holes cut into meshes and the measures of their fills (bench/holes.py).
- ``cgal_fill_hole``: CGAL's triangulate_refine_and_fair_hole as a reference (runs
  build/bench/cgal_fill_hole).
- ``blender``: inside Blender or the bpy module: enable the add-on, Suzanne, select faces.
- ``child``: a benchmark's solves, each in a child process (bench/realmesh.py, bench/holes.py).
- ``testing``: a missing tool skips a test locally and fails it in CI (tests/).

Installed editable by scripts/setup.sh (``python3 -m pip install -e dev/``); see paths.py for
how each interpreter finds it.
"""
