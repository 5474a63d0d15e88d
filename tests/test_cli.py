"""The geofair command line (native/python/cli/geofair_cli.py; ``geofair`` in the wheel): mesh
files in and out through OpenMesh's IO, every hole of a scan filled end to end, several files
at once with a broken one among them, a region faired, and never a partial output."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import geofair


def run(*args):
    """``python -m geofair_cli ARGS``: (exit status, stdout, stderr)."""
    out = subprocess.run([sys.executable, "-m", "geofair_cli", *map(str, args)], capture_output=True, text=True)
    return out.returncode, out.stdout, out.stderr


def scan(n=320, hole=0.05):
    """A height field of (n + 1)² vertices over [0, 1]² with a round hole at its middle, and a
    colour per vertex that varies with x (red) and y (green)."""
    x, y = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    vertices = np.stack([x.ravel(), y.ravel(), 0.1 * np.sin(3 * x.ravel()) * np.cos(2 * y.ravel())], axis=1)
    a = (np.arange(n)[None, :] + (n + 1) * np.arange(n)[:, None]).ravel()
    faces = np.concatenate([np.stack([a, a + 1, a + n + 2], 1), np.stack([a, a + n + 2, a + n + 1], 1)])
    inside = np.hypot(vertices[:, 0] - 0.5, vertices[:, 1] - 0.5) < hole
    faces = faces[~inside[faces].any(axis=1)]
    colors = np.zeros((len(vertices), 4), np.uint8)
    colors[:, 0] = np.rint(255 * vertices[:, 0])
    colors[:, 1] = np.rint(255 * vertices[:, 1])
    colors[:, 3] = 255
    return vertices, faces, colors


def test_a_scan_of_over_100000_vertices_is_filled_end_to_end_with_its_colours(tmp_path):
    v, f, colors = scan()
    assert len(v) > 100_000
    source, target, report = tmp_path / "scan.ply", tmp_path / "filled.ply", tmp_path / "report.json"
    geofair.write_mesh(str(source), v, f, colors=colors)
    status, out, err = run("fill", source, "-o", target, "--report", report)
    assert status == 0, err
    assert "1 hole filled" in out and "hole at vertex" in out, out
    filled = geofair.read_mesh(str(target))
    written = geofair.read_mesh(str(source))
    n = len(written["vertices"])
    # The scan's vertices and colours come back first (the file's float32 precision); the
    # hole is closed (only the sheet's outer border is left).
    np.testing.assert_array_equal(filled["vertices"][:n], written["vertices"][:n])
    np.testing.assert_array_equal(filled["colors"][:n, :3], colors[:n, :3])
    new = filled["vertices"][n:]
    assert len(new) > 10
    # The new vertices' colours are interpolated: red and green follow x and y (within the
    # hole's span of 0.1, the colours of its loop).
    np.testing.assert_allclose(filled["colors"][n:, 0], 255 * new[:, 0], atol=0.1 * 255 / 2)
    np.testing.assert_allclose(filled["colors"][n:, 1], 255 * new[:, 1], atol=0.1 * 255 / 2)
    (loop,) = [h for h in geofair.boundary_loops(filled["vertices"], filled["faces"])]
    assert len(loop) == 4 * 320  # the outer border alone
    data = json.loads(report.read_text())
    (entry,) = data["files"]
    assert entry["status"] == "ok" and entry["converged"] and entry["carried"] == ["colors"]
    hole, border = entry["holes"]  # the hole, then the outer border the rule left open
    assert hole["method"] == "intrinsic" and hole["filled"] and hole["folds"] == 0
    assert not border["filled"] and border["reason"].startswith("an outer border"), border


def test_several_files_at_once_a_broken_one_reported_and_the_others_written(tmp_path):
    v, f, _ = scan(n=30, hole=0.2)
    good = []
    for k, ext in enumerate(("obj", "off", "stl")):
        path = tmp_path / f"mesh{k}.{ext}"
        geofair.write_mesh(str(path), v, f)
        good.append(path)
    broken = tmp_path / "broken.ply"
    broken.write_text("ply\nformat ascii 1.0\nelement vertex 3\nend_header\n0 0\n")
    out_dir, report = tmp_path / "out", tmp_path / "report.json"
    status, out, err = run("fill", *good, broken, "--output-dir", out_dir, "--jobs", 2, "--report", report)
    assert status == 1, (out, err)
    assert f"error: {broken}" in err, err
    for path in good:
        filled = geofair.read_mesh(str(out_dir / path.name))
        assert len(filled["faces"]) > len(f), path
    assert not (out_dir / broken.name).exists(), "a partial output was written"
    assert sorted(os.listdir(out_dir)) == sorted(p.name for p in good), "a temporary file was left"
    files = json.loads(report.read_text())["files"]
    assert [e["status"] for e in files] == ["ok", "ok", "ok", "error"]


def test_a_region_is_faired_and_bad_input_writes_nothing(tmp_path):
    v, f, _ = scan(n=30, hole=0.0)
    free = np.flatnonzero(np.hypot(v[:, 0] - 0.5, v[:, 1] - 0.5) < 0.2)
    source, target, region = tmp_path / "sheet.obj", tmp_path / "faired.obj", tmp_path / "region.txt"
    bumped = v.copy()
    bumped[free, 2] += 0.05  # a bump the fairing removes
    geofair.write_mesh(str(source), bumped, f)
    region.write_text(" ".join(map(str, free)))
    status, out, err = run("fair", source, "--region", region, "-o", target)
    assert status == 0, err
    faired = geofair.read_mesh(str(target))["vertices"]
    assert np.abs(faired[free, 2] - v[free, 2]).max() < 0.02 < np.abs(bumped[free, 2] - v[free, 2]).min()
    # A face mask in a .npy file names the same region (the vertices whose faces are all in it).
    mask = np.isin(f, free).all(axis=1)
    np.save(tmp_path / "faces.npy", mask)
    status, _, err = run("fair", source, "--region", tmp_path / "faces.npy", "-o", tmp_path / "faired2.obj")
    assert status == 0, err
    # Bad input: an index out of range, a closed mesh without a hole, an unknown format.
    region.write_text(f"0 1 {len(v) + 5}")
    status, _, err = run("fair", source, "--region", region, "-o", tmp_path / "never.obj")
    assert status == 1 and "out of range" in err and not (tmp_path / "never.obj").exists(), err
    status, _, err = run("fill", source, "-o", tmp_path / "never.obj")
    assert status == 1 and "no hole to fill" in err and not (tmp_path / "never.obj").exists(), err
    status, _, err = run("fill", source, "-o", tmp_path / "never.xyz")
    assert status == 1 and "unknown mesh format" in err, err
    status, _, err = run("fill", source, tmp_path / "other.obj", "-o", tmp_path / "x.obj")
    assert status == 2 and "--output-dir" in err, err
    # Two inputs of one name would overwrite each other in --output-dir: refused, nothing written.
    (tmp_path / "a").mkdir()
    geofair.write_mesh(str(tmp_path / "a" / "sheet.obj"), v, f)
    status, _, err = run("fill", source, tmp_path / "a" / "sheet.obj", "--output-dir", tmp_path / "o")
    assert status == 2 and "overwrite each other" in err and not (tmp_path / "o").exists(), err


@pytest.mark.parametrize("ext", ["obj", "ply", "off", "stl"])
def test_mesh_files_round_trip(tmp_path, ext):
    v, f, colors = scan(n=8, hole=0.0)
    path = str(tmp_path / f"m.{ext}")
    geofair.write_mesh(path, v, f, colors=colors, texcoords=v[:, :2])
    back = geofair.read_mesh(path)
    assert len(back["faces"]) == len(f) and len(back["vertices"]) == len(v)
    np.testing.assert_allclose(np.sort(back["vertices"], axis=0), np.sort(v, axis=0), atol=1e-6)  # float32 files
    assert (back["colors"] is not None) == (ext in ("ply", "off"))
    assert (back["texcoords"] is not None) == (ext in ("obj", "ply"))
    with pytest.raises(geofair.InvalidInputError, match="cannot be read"):
        geofair.read_mesh(str(tmp_path / f"missing.{ext}"))
    with pytest.raises(OSError, match="cannot be written"):
        geofair.write_mesh(str(tmp_path / "no" / f"m.{ext}"), v, f)


def test_mesh_files_read_and_written_from_threads_at_once(tmp_path):
    """OpenMesh's readers and writers are process-wide: concurrent calls (without the GIL)
    take turns, and every file comes back whole; the writes leave no temporary file."""
    from concurrent.futures import ThreadPoolExecutor

    v, f, colors = scan(n=40, hole=0.0)  # every vertex in a triangle: STL keeps only those

    def round_trip(k):
        path = str(tmp_path / f"m{k}.{('obj', 'ply', 'off', 'stl')[k % 4]}")
        geofair.write_mesh(path, v + k, f, colors=colors)
        back = geofair.read_mesh(path)
        return len(back["vertices"]), len(back["faces"]), float(np.sort(back["vertices"], axis=0)[0, 0]) - k

    with ThreadPoolExecutor(4) as pool:
        results = list(pool.map(round_trip, range(16)))
    assert all(r[:2] == (len(v), len(f)) and abs(r[2] - v[:, 0].min()) < 1e-5 for r in results), results
    assert len(os.listdir(tmp_path)) == 16, sorted(os.listdir(tmp_path))


def test_option_values_are_the_librarys_and_a_bad_one_is_a_usage_error(tmp_path):
    # The command line's choices are the values geofair.fair accepts (its error lists them), so
    # a bad value is refused before any file is read (exit 2), as --boundary and --rim are.
    import re

    sys.path.insert(0, os.path.dirname(geofair.__file__))
    import geofair_cli

    v, f, _ = scan(n=6, hole=0.0)
    free = np.zeros(len(v), bool)
    free[len(v) // 2] = True
    actions = {a.dest: a for a in geofair_cli.build_parser()._subparsers._group_actions[0].choices["fill"]._actions}
    for name in ("inner_fairness", "outer_fairness", "iteration", "boundary"):
        with pytest.raises(geofair.InvalidInputError) as error:
            geofair.fair(v, f, free, **{name: "no-such-value"})
        accepted = re.findall(r"'([a-z0-9_]+)'", str(error.value).split(", got")[0])
        assert sorted(actions[name].choices) == sorted(accepted), (name, str(error.value))
        flag = f"--{name.replace('_', '-')}"
        status, _, err = run("fill", tmp_path / "missing.obj", "-o", tmp_path / "x.obj", flag, "x")
        assert status == 2 and "invalid choice" in err, err
    for length in ("0", "-1", "nan", "a"):
        status, _, err = run("fill", tmp_path / "missing.obj", "-o", tmp_path / "x.obj", "--edge-length", length)
        assert status == 2 and "--edge-length: must be a positive length" in err, err
