"""The Blender extension zip (scripts/build_extension.py) in bpy 4.5, 5.0 and 5.2.

- the zip is built by Blender's own ``extension build`` from the built add-on and the
  repaired wheels (dist/: cp311 for Blender 4.2 to 5.0, cp313 for 5.1 and later), and
  ``extension validate`` of every bpy accepts it; it holds the wheels byte for byte, no
  compiled module of its own, and the manifest's version, licence, copyright, platform and permissions;
- tests/blender/check_extension.py installs it into a fresh user folder of bpy 4.5 (this
  Python's), of bpy 5.0 (Python 3.11, its own venv, ``$XDG_CACHE_HOME/geofair/bpy5-venv``
  made by scripts/setup.sh, or GEOFAIR_BPY5_PYTHON) and of bpy 5.2 (Python 3.13,
  ``.../bpy52-venv`` or GEOFAIR_BPY52_PYTHON), and the operator fairs the UV sphere's cap
  with geofair from the wheel of that Python; the faired positions must be those the build tree's module
  computes for the same region and options, and the cap must have changed.

A missing wheel, bpy or bpy venv is skipped locally and fails when CI is set.
"""

import importlib.util
import json
import os
import pathlib
import subprocess
import sys
import tomllib
import zipfile

import numpy as np
import pytest

import geofair
from geofair_dev import paths
from geofair_dev.paths import BUILD, REPO
from geofair_dev.testing import unavailable

VERSION = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]
CACHE = pathlib.Path(os.environ.get("XDG_CACHE_HOME") or pathlib.Path.home() / ".cache")
BPY_VENVS = {  # variant: (the venv's python, its environment override, its Python's wheel tag)
    "bpy-5.0": (os.environ.get("GEOFAIR_BPY5_PYTHON", CACHE / "geofair" / "bpy5-venv" / "bin" / "python"), "cp311"),
    "bpy-5.2": (os.environ.get("GEOFAIR_BPY52_PYTHON", CACHE / "geofair" / "bpy52-venv" / "bin" / "python"), "cp313"),
}
VARIANTS = ["bpy-4.5", *BPY_VENVS]
BLENDER_COMMAND = paths.source_module(REPO / "scripts" / "build_extension.py").BLENDER_COMMAND


def bpy_python(variant):
    if variant == "bpy-4.5":
        if importlib.util.find_spec("bpy") is None:
            unavailable(f"the bpy module is not installed for {sys.executable}")
        return sys.executable
    python = pathlib.Path(BPY_VENVS[variant][0])
    if not python.is_file():
        unavailable(f"no {variant} venv at {python}: scripts/setup.sh makes it")
    return str(python)


def run(command, **kwargs):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "GEOFAIR_BUILD")}
    env.update(kwargs.pop("env", {}))
    completed = subprocess.run(command, capture_output=True, text=True, env=env, timeout=300, **kwargs)
    output = completed.stdout + completed.stderr
    assert completed.returncode == 0, f"{' '.join(map(str, command))} exited {completed.returncode}:\n{output}"
    return output


@pytest.fixture(scope="module")
def extension_zip(tmp_path_factory):
    """The zip that scripts/build_extension.py builds (with bpy 4.5) from build/addon and dist/'s wheel."""
    wheels = [
        wheel
        for tag in ("cp311", "cp313")
        for wheel in sorted((REPO / "dist").glob(f"geofair-{VERSION}-{tag}-{tag}-manylinux*.whl"))
    ]
    if [w.name.split("-")[2] for w in wheels] != ["cp311", "cp313"]:
        unavailable(f"no repaired cp311 and cp313 wheels in dist/ ({wheels}): run scripts/build_wheel.sh")
    if not (BUILD / "addon" / "geometric_fairing" / "blender_manifest.toml").is_file():
        unavailable(f"no built add-on in {BUILD / 'addon'}")
    bpy_python("bpy-4.5")
    out = tmp_path_factory.mktemp("extension")
    run(
        [
            sys.executable,
            REPO / "scripts" / "build_extension.py",
            "--out",
            out,
            "--addon",
            BUILD / "addon" / "geometric_fairing",
        ]
    )
    archive = out / f"geometric_fairing-{VERSION}-linux_x64.zip"
    assert archive.is_file(), list(out.iterdir())
    return archive, wheels


def test_the_zip_holds_the_wheels_and_a_complete_manifest(extension_zip):
    archive, wheels = extension_zip
    with zipfile.ZipFile(archive) as zipped:
        names = zipped.namelist()
        manifest = tomllib.loads(zipped.read("blender_manifest.toml").decode())
        for wheel in wheels:
            assert zipped.read(f"wheels/{wheel.name}") == wheel.read_bytes()
    assert manifest["version"] == VERSION and manifest["id"] == "geometric_fairing"
    # What Blender installs from a --split-platforms zip: [build.generated]'s platforms and wheels.
    generated = manifest.get("build", {}).get("generated", manifest)
    # geofair's wheels, and the OpenBLAS they load (their dependency, which Blender does not resolve).
    (openblas,) = [w for w in generated["wheels"] if w.startswith("./wheels/scipy_openblas32-")]
    assert "manylinux" in openblas and "x86_64" in openblas, openblas
    assert [w for w in generated["wheels"] if w != openblas] == [f"./wheels/{wheel.name}" for wheel in wheels]
    assert not [n for n in names if "win_amd64" in n or "macosx" in n], names  # only this platform's wheels
    assert manifest["blender_version_min"] == "4.2.0"
    assert generated["platforms"] == ["linux-x64"] and manifest["license"] == ["SPDX:GPL-3.0-or-later"]
    assert set(manifest["permissions"]) == {"files"}
    credited = " ".join(manifest["copyright"])
    for library in ("OpenMesh", "SuiteSparse", "METIS", "libc++", "libunwind", "Eigen", "pybind11", "OpenBLAS"):
        assert library in credited, library
    assert "__init__.py" in names and "native.py" in names
    assert not [n for n in names if n.endswith(".so") or ".so." in n], names  # the module comes from the wheel


def test_one_zip_per_platform_of_the_wheels(extension_zip, tmp_path):
    """What the release workflow does with every platform's wheels: one zip per Blender platform,
    each with its platform in the manifest and only its own wheels. The other platforms' wheels
    are stand-ins here (the Linux wheel's bytes under a macOS and a Windows name)."""
    _, wheels = extension_zip
    stand_ins = []
    for wheel in wheels:
        python = "-".join(wheel.name.split("-")[:4])
        for platform in ("macosx_11_0_arm64", "win_amd64"):
            stand_in = tmp_path / f"{python}-{platform}.whl"
            stand_in.write_bytes(wheel.read_bytes())
            stand_ins.append(stand_in)
    out = tmp_path / "out"
    arguments = [a for w in [*wheels, *stand_ins] for a in ("--wheel", w)]
    addon = BUILD / "addon" / "geometric_fairing"
    run([sys.executable, REPO / "scripts" / "build_extension.py", *arguments, "--out", out, "--addon", addon])
    expected = {"linux-x64": "manylinux", "macos-arm64": "macosx_11_0_arm64", "windows-x64": "win_amd64"}
    # (and the legacy add-on of the Linux wheels, tests/test_blender.py)
    assert sorted(p.name for p in out.glob("*.zip")) == sorted(
        [f"geometric_fairing-{VERSION}-{platform.replace('-', '_')}.zip" for platform in expected]
        + [f"geometric_fairing-{VERSION}-legacy_linux_x64.zip"]
    )
    for platform, marker in expected.items():
        with zipfile.ZipFile(out / f"geometric_fairing-{VERSION}-{platform.replace('-', '_')}.zip") as zipped:
            manifest = tomllib.loads(zipped.read("blender_manifest.toml").decode())
            packed = [n for n in zipped.namelist() if n.startswith("wheels/")]
        # Blender's build writes each zip's own platform and wheels under [build.generated].
        generated = manifest["build"]["generated"]
        assert generated["platforms"] == [platform]
        # cp311, cp313 and the platform's scipy-openblas32
        assert len(packed) == 3 and all(marker in n for n in packed), packed
        assert sum("scipy_openblas32" in n for n in packed) == 1, packed
        assert sorted(generated["wheels"]) == sorted(f"./{n}" for n in packed)


@pytest.mark.parametrize("variant", VARIANTS)
def test_blender_validates_the_zip(variant, extension_zip):
    archive, _ = extension_zip
    output = run([bpy_python(variant), "-c", BLENDER_COMMAND, "validate", archive], cwd=archive.parent)
    assert "Success parsing TOML" in output, output


def reference(data):
    """What the build tree's geofair makes of the region the add-on fairs, with the same options."""
    options = json.loads(str(data["options"]))
    assert "build" in geofair.__file__, geofair.__file__  # (conftest: build/python)
    return geofair.fair(
        data["vertices"],
        data["triangles"],
        data["free"],
        boundary_normals=data["boundary_normals"],
        polygon_ids=data["polygon_ids"],
        inner_fairness=options["inner_fairness"].lower(),
        outer_fairness=options["outer_fairness"].lower(),
        tolerance=options["tolerance"],
        max_iterations=options["max_iterations"],
        levels=options["levels"],
        iteration=options["iteration"].lower(),
    )


@pytest.mark.parametrize("variant", VARIANTS)
def test_the_extension_installs_and_fairs_the_sphere_cap(variant, extension_zip, tmp_path):
    archive, _ = extension_zip
    user = {
        "BLENDER_USER_RESOURCES": str(tmp_path),
        "BLENDER_USER_SCRIPTS": str(tmp_path / "scripts"),
        "BLENDER_USER_CONFIG": str(tmp_path / "config"),
    }
    out = tmp_path / "sphere.npz"
    command = [bpy_python(variant), REPO / "tests" / "blender" / "check_extension.py", "--", archive, out]
    output = run(command, env=user, cwd=tmp_path)
    assert "check_extension: all checks passed" in output, output
    data = np.load(out)
    assert str(data["blender"]).startswith(variant.removeprefix("bpy-")), str(data["blender"])
    module = pathlib.Path(str(data["module"]))
    assert tmp_path in module.parents and "site-packages" in module.parts, module
    tag = BPY_VENVS[variant][1] if variant in BPY_VENVS else "cp311"
    assert f"cpython-{tag.removeprefix('cp')}" in module.name, module  # the wheel of Blender's Python
    free, before, after = data["free"], data["before"], data["after"]
    assert 700 < free.sum() < 900, free.sum()  # the cap above z = 0.25 less its boundary ring
    assert np.array_equal(after[~free], before[~free]), "vertices outside the region moved"
    assert np.abs(after[free] - before[free]).max() > 0.05, "the cap did not change"
    expected = reference(data).vertices.astype(np.float32).astype(np.float64)  # Blender stores float32
    assert np.abs(after - expected).max() < 1e-6, np.abs(after - expected).max()
