"""Build the Blender extension zip with Blender's own ``extension build`` and validate it.

    python3 scripts/build_extension.py [--wheel dist/geofair-*.whl ...] [--out dist]

Stages build/extension/geometric_fairing/: the add-on's Python files and its
blender_manifest.toml as the CMake build stamped them (build/addon/geometric_fairing/, so
``cmake --build build`` first), without the compiled module and the OpenMesh libraries,
plus the wheels (scripts/build_wheel.sh) in wheels/, listed in the manifest as
``wheels = [...]``: by default the cp311 wheel (Blender 4.2 to 5.0) and, if built, the
cp313 one (Blender 5.1 and later), Blender installing the one of its Python, of Linux
(scripts/build_wheel.sh) and, where built, Windows (scripts/build_windows.py), and for each
platform the wheel of their dependency scipy-openblas32 (the OpenBLAS the module loads),
downloaded from PyPI. Then runs what
``blender --command extension build --split-platforms``
and ``... validate`` run, Blender's bl_pkg command line, here through the bpy module from
PyPI (no Blender binary of 4.2+ needed), and writes one zip per platform of the wheels,
dist/geometric_fairing-<version>-<platform>.zip (linux_x64 and windows_x64 from this
machine's wheels; the release workflow adds linux_arm64, macos_arm64 and macos_x64).
Blender 4.2+ installs it with
``blender --command extension install-file -r user_default -e <zip>`` or Preferences ›
Get Extensions › Install from Disk, and installs the wheel for the add-on.
"""

import argparse
import json
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib
import zipfile

REPO = pathlib.Path(__file__).resolve().parents[1]
VERSION = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]

# Runs Blender's `blender --command extension ARGS` handler inside the bpy module.
BLENDER_COMMAND = """
import sys
import bpy
from bl_pkg import bl_extension_cli
sys.exit(bl_extension_cli.cli_extension_handler(sys.argv[1:]))
"""


def blender_extension_command(args, python=sys.executable):
    """``blender --command extension *args`` through the bpy module of ``python``; returns its output."""
    completed = subprocess.run([python, "-c", BLENDER_COMMAND, *map(str, args)], capture_output=True, text=True)
    output = completed.stdout + completed.stderr
    if completed.returncode != 0:
        raise SystemExit(f"extension {' '.join(map(str, args))} failed ({completed.returncode}):\n{output}")
    return output


# Wheel platform tags (their last part) and the Blender platforms they install on.
BLENDER_PLATFORMS = (
    (r"^manylinux_\d+_\d+_x86_64$", "linux-x64"),
    (r"^manylinux_\d+_\d+_aarch64$", "linux-arm64"),
    (r"^macosx_\d+_\d+_arm64$", "macos-arm64"),
    (r"^macosx_\d+_\d+_x86_64$", "macos-x64"),
    (r"^win_amd64$", "windows-x64"),
)


def blender_platform(wheel):
    """The Blender platform (``linux-x64``, ...) a wheel's platform tag installs on."""
    tag = wheel.name.removesuffix(".whl").split("-")[-1]
    for pattern, platform in BLENDER_PLATFORMS:
        if any(re.match(pattern, part) for part in tag.split(".")):
            return platform
    raise SystemExit(f"{wheel.name}: no Blender platform for the wheel tag {tag}")


# The OpenBLAS the module loads at import (a dependency of the wheel, which Blender does not
# resolve): its wheel for each platform goes into the extension beside geofair's.
SCIPY_OPENBLAS = "scipy-openblas32==0.3.34.481.3"
PIP_PLATFORMS = {
    "linux-x64": "manylinux_2_28_x86_64",
    "linux-arm64": "manylinux_2_28_aarch64",
    "macos-arm64": "macosx_11_0_arm64",
    "macos-x64": "macosx_11_0_x86_64",
    "windows-x64": "win_amd64",
}


def dependency_wheels(platforms, folder=REPO / "build" / "extension-deps"):
    """The scipy-openblas32 wheel of each Blender platform, from PyPI (cached in ``folder``)."""
    wheels = []
    for platform in platforms:
        target = folder / platform
        found = sorted(target.glob("scipy_openblas32-*.whl"))
        if not found:
            subprocess.run(
                [sys.executable, "-m", "pip", "download", "-q", "--disable-pip-version-check", "--no-deps",
                 "--only-binary=:all:", "--platform", PIP_PLATFORMS[platform], "--python-version", "3.11",
                 "-d", str(target), SCIPY_OPENBLAS],
                check=True,
            )  # fmt: skip
            found = sorted(target.glob("scipy_openblas32-*.whl"))
        if len(found) != 1 or blender_platform(found[0]) != platform:
            raise SystemExit(f"expected one scipy-openblas32 wheel for {platform} in {target}, found {found}")
        wheels += found
    return wheels


def stage(addon, wheels, folder):
    """Copy the add-on without compiled files and the wheels to ``folder``; list the wheels in its manifest."""
    shutil.rmtree(folder, ignore_errors=True)
    (folder / "wheels").mkdir(parents=True)
    for file in sorted(addon.iterdir()):
        if file.is_file() and file.suffix in (".py", ".toml"):
            shutil.copy(file, folder / file.name)
    for wheel in wheels:
        shutil.copy(wheel, folder / "wheels" / wheel.name)
    manifest = folder / "blender_manifest.toml"
    text = manifest.read_text()
    assert tomllib.loads(text)["version"] == VERSION, "build/addon is stale: cmake --build build"
    platforms = sorted({blender_platform(wheel) for wheel in wheels})
    text = re.sub(r"^platforms = .*$", f"platforms = {json.dumps(platforms)}", text, count=1, flags=re.MULTILINE)
    # A top-level key: before the first table ([permissions]).
    first_table = re.search(r"^\[", text, re.MULTILINE).start()
    listed = [f"./wheels/{wheel.name}" for wheel in wheels]
    text = f"{text[:first_table]}wheels = {json.dumps(listed)}\n\n{text[first_table:]}"
    manifest.write_text(text)
    assert tomllib.loads(text)["wheels"] == listed


def legacy_addon(addon, wheels, out):
    """The legacy add-on zip (Blender 3.4 to 4.1: Preferences › Add-ons › Install) of the Linux
    x86-64 wheels of Python 3.10 and 3.11 among ``wheels``: the add-on's files, each wheel's
    compiled module as ``geofair.cpython-3XY-x86_64-linux-gnu.so`` and the OpenBLAS library of
    the scipy-openblas32 wheel beside them (native.py points the module at it), and the
    licences of what they compile in; written to ``out``/geometric_fairing-<version>-legacy_linux_x64.zip.
    """
    modules = [w for w in wheels if w.name.split("-")[2] in ("cp310", "cp311") and blender_platform(w) == "linux-x64"]
    if not modules:
        print("no cp310 or cp311 Linux x86-64 wheel: no legacy add-on")
        return None
    (openblas,) = [w for w in wheels if w.name.startswith("scipy_openblas32-") and blender_platform(w) == "linux-x64"]
    folder = pathlib.Path(tempfile.mkdtemp()) / "geometric_fairing"
    folder.mkdir()
    for file in sorted(addon.iterdir()):
        if file.is_file() and file.suffix in (".py", ".toml"):
            shutil.copy(file, folder / file.name)
    for wheel in modules:
        with zipfile.ZipFile(wheel) as archive:
            (name,) = [n for n in archive.namelist() if re.fullmatch(r"geofair/__init__\.cpython-3\d+-.*\.so", n)]
            target = folder / pathlib.PurePosixPath(name).name.replace("__init__", "geofair")
            target.write_bytes(archive.read(name))
            target.chmod(0o755)
            # The licences of what the module compiles in (the wheel's), in licenses/.
            for name in archive.namelist():
                if re.fullmatch(r"geofair-[^/]+\.dist-info/licenses/[^/]+", name):
                    licence = folder / "licenses" / pathlib.PurePosixPath(name).name
                    licence.parent.mkdir(exist_ok=True)
                    licence.write_bytes(archive.read(name))
    with zipfile.ZipFile(openblas) as archive:
        (name,) = [n for n in archive.namelist() if re.fullmatch(r"scipy_openblas32/lib/libscipy_openblas[^/]*\.so", n)]
        (folder / pathlib.PurePosixPath(name).name).write_bytes(archive.read(name))
        for name in archive.namelist():
            if re.fullmatch(r"scipy_openblas32-[^/]+\.dist-info/licenses/[^/]+", name):
                licence = folder / "licenses" / ("OpenBLAS-" + pathlib.PurePosixPath(name).name)
                licence.parent.mkdir(exist_ok=True)
                licence.write_bytes(archive.read(name))
    legacy = out.resolve() / f"geometric_fairing-{VERSION}-legacy_linux_x64.zip"
    with zipfile.ZipFile(legacy, "w", zipfile.ZIP_DEFLATED) as archive:
        for file in sorted(folder.rglob("*")):
            if file.is_file():
                archive.write(file, f"geometric_fairing/{file.relative_to(folder).as_posix()}")
    shutil.rmtree(folder.parent)
    print(f"wrote {legacy} (modules: {', '.join(w.name.split('-')[2] for w in modules)})")
    return legacy


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "--wheel",
        type=pathlib.Path,
        action="append",
        help="repeatable, any platforms; default: dist/geofair-<version>-cp311-*.whl and, if built, -cp313-",
    )
    parser.add_argument("--addon", type=pathlib.Path, default=REPO / "build" / "addon" / "geometric_fairing")
    parser.add_argument("--out", type=pathlib.Path, default=REPO / "dist")
    args = parser.parse_args()
    wheels = args.wheel
    if wheels is None:
        wheels = []
        for tag in ("cp310", "cp311", "cp313"):
            folder = REPO / ("build/legacy-wheels" if tag == "cp310" else "dist")  # cp310: scripts/build_wheel.sh
            found = sorted(folder.glob(f"geofair-{VERSION}-{tag}-{tag}-*manylinux*.whl"))
            if len(found) > 1 or (tag == "cp311" and not found):
                raise SystemExit(
                    f"expected one dist/geofair-{VERSION}-{tag}-*manylinux*.whl, found {found}: scripts/build_wheel.sh"
                )
            wheels += found
            if tag != "cp310":  # scripts/build_windows.py's, where built
                wheels += sorted((REPO / "dist").glob(f"geofair-{VERSION}-{tag}-{tag}-win_amd64.whl"))
    wheels = [wheel.resolve() for wheel in wheels]
    wheels += dependency_wheels(sorted({blender_platform(wheel) for wheel in wheels}))
    args.out.mkdir(parents=True, exist_ok=True)
    legacy_addon(args.addon, wheels, args.out)
    # The extension: Blender 4.2 and later run Python 3.11 or newer.
    wheels = [w for w in wheels if w.name.split("-")[2] != "cp310"]
    folder = REPO / "build" / "extension" / "geometric_fairing"
    stage(args.addon, wheels, folder)
    args.out.mkdir(parents=True, exist_ok=True)
    # One zip per platform (Blender's --split-platforms), each with that platform's wheels.
    platforms = sorted({blender_platform(wheel) for wheel in wheels})
    archives = [args.out.resolve() / f"geometric_fairing-{VERSION}-{p.replace('-', '_')}.zip" for p in platforms]
    for archive in archives:
        archive.unlink(missing_ok=True)
    print(blender_extension_command(["build", "--split-platforms", "--source-dir", folder, "--output-dir", args.out]))
    for archive in archives:
        print(blender_extension_command(["validate", archive]))
        assert archive.is_file(), archive
        print(f"wrote {archive}")


if __name__ == "__main__":
    main()
