"""Build the Blender extension zip with Blender's own ``extension build`` and validate it.

    python3 scripts/build_extension.py [--wheel dist/geofair-*.whl ...] [--out dist]

Stages build/extension/geometric_fairing/: the add-on's Python files and its
blender_manifest.toml as the CMake build stamped them (build/addon/geometric_fairing/, so
``cmake --build build`` first), without the compiled module and the OpenMesh libraries,
plus the self-contained wheels (scripts/build_wheel.sh) in wheels/, listed in the manifest
as ``wheels = [...]``: by default the cp311 wheel (Blender 4.2 to 5.0) and, if built, the
cp313 one (Blender 5.1 and later); Blender installs the one of its Python. Then runs what
``blender --command extension build --split-platforms``
and ``... validate`` run, Blender's bl_pkg command line, here through the bpy module from
PyPI (no Blender binary of 4.2+ needed), and writes one zip per platform of the wheels,
dist/geometric_fairing-<version>-<platform>.zip (linux_x64 from this machine's wheels; the
release workflow adds linux_arm64, macos_arm64, macos_x64 and windows_x64). Blender 4.2+ installs it with
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
import tomllib

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
        for tag in ("cp311", "cp313"):
            found = sorted((REPO / "dist").glob(f"geofair-{VERSION}-{tag}-{tag}-*manylinux*.whl"))
            if len(found) > 1 or (tag == "cp311" and not found):
                raise SystemExit(
                    f"expected one dist/geofair-{VERSION}-{tag}-*manylinux*.whl, found {found}: scripts/build_wheel.sh"
                )
            wheels += found
    folder = REPO / "build" / "extension" / "geometric_fairing"
    stage(args.addon, [wheel.resolve() for wheel in wheels], folder)
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
