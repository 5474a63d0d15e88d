"""Run the checks of tests/blender/ in Blender and in the bpy module from PyPI.

The built add-on is taken from ``$GEOFAIR_BUILD/addon`` (default ``<repo>/build``).
A missing Blender, bpy module, display server or build skips its test locally,
but fails when the environment variable CI is set.

- check_operator.py: the operator, the panel's options and figures, preferences, pins,
  region groups, errors, undo; also without the compiled module, and with a module
  built for another Python.
- check_inspect.py: the zebra and curvature toggles leave nothing behind.
- check_errors.py: bad selections (exact reports), solver failures, Edit Mode and undo after them.
- check_mesh_data.py: only positions change (shape keys, modifiers, custom normals, UV maps, colour
  attributes byte-identical); Edit and Object Mode store the same shape keys; hidden faces.
- check_multi_object.py: several objects in Edit Mode; the ones that cannot be faired are named.
- check_live.py: Live Fair Drag run as a script (its offset, rotation and scale in frames) on a UV
  sphere: the cold fair of the same input, only positions change, one undo; the radius region; no
  handle or region refused; frame times.
- check_scripting.py: fair_object, cancelling (progress callback, worker thread), UV distortion,
  Blender's UV sphere with its cap flattened (quads split at random) faired back onto the sphere.
- check_remesh.py: Remesh Always / If Needed on Suzanne's ear (no UV flip, the rest byte-identical),
  Fill Holes on a UV sphere's hole (back onto the sphere, manifold, UVs), its errors, undo.
- check_packaging.py: installs as a legacy add-on, and as an extension in Blender 4.2+; the
  legacy zip built from the shipped wheels in Blender 3.4 (nothing but glibc needed), its
  cp310 module in Python 3.10.
- examples/fair_object.py: the documented script runs.
- check_modal.py (Blender under Xvfb): the modal operator in a window, Esc cancels.
- check_live_modal.py (Blender under Xvfb): Live Fair Drag follows the mouse, Esc restores every
  byte, a click confirms with one undo step.
"""

import importlib.util
import os
import pathlib
import shutil
import subprocess
import sys
import tomllib
import zipfile

import pytest

from geofair_dev import paths
from geofair_dev.paths import BUILD, REPO
from geofair_dev.testing import unavailable

CHECKS = REPO / "tests" / "blender"


CHECKS_IN_BOTH = [
    "check_operator",
    "check_inspect",
    "check_scripting",
    "check_errors",
    "check_mesh_data",
    "check_multi_object",
    "check_live",
]


def _built_addon():
    addon = BUILD / "addon"
    if not list((addon / "geometric_fairing").glob("geofair*.so")):
        unavailable(f"no built add-on with its compiled module in {addon}: build the project first")
    return addon


def _blender_command(script):
    blender = shutil.which("blender")
    if blender is None:
        unavailable("blender is not installed")
    return [blender, "--background", "--factory-startup", "--python-exit-code", "1", "--python", str(script)]


def _bpy_module_command(script):
    if importlib.util.find_spec("bpy") is None:
        unavailable(f"the bpy module is not installed for {sys.executable}")
    return [sys.executable, str(script)]


COMMANDS = {"blender": _blender_command, "bpy-module": _bpy_module_command}


def _run(command, env=None, timeout=300):
    # A Blender built against the system Python finds its Python home through the first
    # python3.x on PATH; pyenv puts its own first, and Blender would then start with
    # pyenv's standard library and without the system's numpy. Look next to Blender first.
    # PYTHONPATH holds dev/, so the checks import geofair_dev (Debian's Blender reads it too).
    path = os.pathsep.join([os.path.dirname(shutil.which(command[0]) or command[0]), os.environ.get("PATH", "")])
    env = paths.subprocess_env(PATH=path, **(env or {}))
    completed = subprocess.run(command, cwd=REPO, env=env, capture_output=True, text=True, timeout=timeout)
    output = completed.stdout + completed.stderr
    assert completed.returncode == 0, f"{' '.join(command)} exited {completed.returncode}:\n{output}"
    return output


@pytest.mark.parametrize("variant", COMMANDS)
@pytest.mark.parametrize("check", CHECKS_IN_BOTH)
def test_in_blender(check, variant):
    output = _run([*COMMANDS[variant](CHECKS / f"{check}.py"), "--", str(_built_addon())])
    assert f"{check}: all checks passed" in output, output


@pytest.mark.parametrize("variant", COMMANDS)
def test_fill_holes(variant):
    output = _run([*COMMANDS[variant](CHECKS / "check_remesh.py"), "--", str(_built_addon()), "--fill"])
    assert "check_remesh (fill): all checks passed" in output, output


@pytest.mark.parametrize("variant", COMMANDS)
def test_remesh(variant):
    output = _run([*COMMANDS[variant](CHECKS / "check_remesh.py"), "--", str(_built_addon()), "--remesh"])
    assert "check_remesh (remesh): all checks passed" in output, output


@pytest.mark.parametrize("variant", COMMANDS)
def test_operator_without_compiled_module(variant):
    command = COMMANDS[variant](CHECKS / "check_operator.py")
    output = _run([*command, "--", str(_built_addon()), "--no-native"])
    assert "check_operator (no native module): all checks passed" in output, output


@pytest.mark.parametrize("variant", COMMANDS)
def test_operator_with_module_for_another_python(variant, tmp_path):
    command = COMMANDS[variant](CHECKS / "check_operator.py")
    copy = tmp_path / "addon" / "geometric_fairing"
    shutil.copytree(_built_addon() / "geometric_fairing", copy)
    for module in copy.glob("geofair.cpython-3*"):
        module.rename(module.with_name(module.name.replace(f"cpython-3{sys.version_info.minor}", "cpython-39")))
    assert list(copy.glob("geofair.cpython-39*")), "expected a module named for this Python"
    output = _run([*command, "--", str(copy.parent), "--wrong-python"])
    assert "'geofair' was built for Python 3.9" in output, output
    assert "check_operator (no native module): all checks passed" in output, output


@pytest.mark.parametrize("variant", COMMANDS)
def test_packaging(variant, tmp_path):
    command = COMMANDS[variant](CHECKS / "check_packaging.py")
    user = {
        "BLENDER_USER_RESOURCES": str(tmp_path),
        "BLENDER_USER_SCRIPTS": str(tmp_path / "scripts"),
        "BLENDER_USER_CONFIG": str(tmp_path / "config"),
    }
    output = _run([*command, "--", str(_built_addon())], env=user)
    assert "check_packaging: all checks passed" in output, output


GLIBC = ("libc.so", "libm.so", "libpthread.so", "libdl.so", "librt.so", "ld-linux", "linux-vdso")


@pytest.fixture(scope="module")
def legacy(tmp_path_factory):
    """The legacy zip of dist/ (scripts/build_extension.py) unpacked: ``(folder, modules, OpenBLAS)``."""
    version = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]
    archive = REPO / "dist" / f"geometric_fairing-{version}-legacy_linux_x64.zip"
    if not archive.is_file():
        unavailable(f"no {archive}: scripts/setup.sh builds it (scripts/build_extension.py)")
    folder = tmp_path_factory.mktemp("legacy")
    with zipfile.ZipFile(archive) as zipped:
        zipped.extractall(folder)
    package = folder / "geometric_fairing"
    for module in package.glob("*.so"):
        module.chmod(0o755)
    modules = sorted(package.glob("geofair.cpython-3*.so"))
    blas = sorted(package.glob("libscipy_openblas*.so"))
    assert modules and blas, sorted(p.name for p in package.iterdir())
    return folder, modules, blas


def test_legacy_addon_needs_nothing_but_glibc(legacy, tmp_path):
    # The legacy zip for Blender 3.4 to 4.1, built from the shipped wheels' modules (cp310,
    # cp311) with scipy-openblas32's OpenBLAS beside them: they load nothing from the build
    # machine but glibc, and the add-on installs and fairs in Blender 3.4.
    folder, modules, blas = legacy
    assert {m.name.split(".")[1] for m in modules} >= {"cpython-310-x86_64-linux-gnu", "cpython-311-x86_64-linux-gnu"}
    for library in modules + blas:
        needed = subprocess.run(["ldd", str(library)], capture_output=True, text=True, check=True).stdout
        for line in needed.strip().splitlines():
            soname = os.path.basename(line.split()[0])
            assert "not found" not in line and soname.startswith(GLIBC), (library.name, line)
    user = {
        "BLENDER_USER_RESOURCES": str(tmp_path),
        "BLENDER_USER_SCRIPTS": str(tmp_path / "scripts"),
        "BLENDER_USER_CONFIG": str(tmp_path / "config"),
    }
    command = _blender_command(CHECKS / "check_packaging.py")
    output = _run([*command, "--", str(folder)], env=user)
    assert "check_packaging: all checks passed" in output, output


def test_legacy_addon_cp310_module_fairs_in_python_3_10(legacy, tmp_path):
    # Blender 3.x and 4.0 run Python 3.10: the legacy zip's cp310 module loads there (with the
    # OpenBLAS beside it) and fairs a pyramid's apex into its base plane (G0, a minimal surface).
    folder, modules, blas = legacy
    assert any("cpython-310" in m.name for m in modules), modules
    pythons = sorted(
        (pathlib.Path(os.environ.get("PYENV_ROOT") or pathlib.Path.home() / ".pyenv")).glob(
            "versions/3.10.*/bin/python3.10"
        )
    )
    if not pythons:
        unavailable("no Python 3.10 under pyenv")
    subprocess.run([pythons[-1], "-m", "venv", str(tmp_path / "venv")], check=True)
    python = tmp_path / "venv" / "bin" / "python"
    subprocess.run([python, "-m", "pip", "install", "-q", "--disable-pip-version-check", "numpy"], check=True)
    probe = (
        "import sys; sys.path.insert(0, sys.argv[1]); import numpy as np, geofair\n"
        "v = np.array([[0,0,0],[1,0,0],[0,1,0],[1,1,0],[.5,.5,.3]], float)\n"
        "f = np.array([[0,1,4],[1,3,4],[3,2,4],[2,0,4]])\n"
        "r = geofair.fair(v, f, np.arange(5) == 4, boundary='g0')\n"
        "print(geofair.__file__, r.converged, abs(r.vertices[4, 2]) < 1e-6)"
    )
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["GEOFAIR_BLAS"] = str(blas[0])  # as the add-on's native.py sets it
    done = subprocess.run(
        [python, "-c", probe, str(folder / "geometric_fairing")], capture_output=True, text=True, env=env, cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split()[1:] == ["True", "True"] and "cpython-310" in done.stdout, done.stdout


@pytest.mark.parametrize("variant", COMMANDS)
def test_fair_object_example(variant, tmp_path):
    command = COMMANDS[variant](REPO / "examples" / "fair_object.py")
    output = _run([*command, "--", "--addon", str(_built_addon()), "--out", str(tmp_path / "example.blend")])
    assert "fair_object example: done" in output and (tmp_path / "example.blend").is_file(), output
    assert "vertex group 'Brow'" in output and "cancelled" in output, output


@pytest.mark.parametrize("check", ["check_modal", "check_live_modal"])
def test_modal_operator_under_xvfb(check):
    """The modal operators (Fair's progress and cancel; the live drag) by simulated events
    in Blender with a window (xvfb)."""
    blender, xvfb = shutil.which("blender"), shutil.which("xvfb-run")
    if blender is None or xvfb is None:
        unavailable("the modal checks need blender and xvfb-run")
    command = [
        xvfb,
        "-a",
        "-s",
        "-screen 0 1280x800x24",
        blender,
        "--factory-startup",
        "--enable-event-simulate",
        "--python",
        str(CHECKS / f"{check}.py"),
        "--",
        str(_built_addon()),
    ]
    output = _run(command, timeout=180)
    assert f"{check}: all checks passed" in output, output
