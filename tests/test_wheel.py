"""The self-contained wheels (scripts/build_wheel.sh) in fresh virtual environments.

Each wheel ``dist/geofair-<version>-cpXY-cpXY-manylinux_2_28_x86_64.whl`` (CPython 3.11, 3.12
and 3.13: this python3 and pyenv's) is installed into a new venv of its Python (3.11's
with its Python's own site-packages), with numpy, scipy, matplotlib, pytest and mypy from PyPI
where missing (never build/python: PYTHONPATH is cleared); then

- the module's tests pass against it: BINDINGS_TESTS against every wheel (the wheels differ
  only in the bindings) and SOLVER_TESTS against the cp311 wheel too (its compiler and
  SuiteSparse differ from build/python's, which runs every test) (conftest.py leaves build/python off sys.path with
  GEOFAIR_TEST_INSTALLED=1);
- its extension module (ldd, objdump): every library it loads is on the manylinux_2_28
  allow-list (auditwheel's policy), no glibc symbol is newer than 2.28, nothing is bundled
  beside it (the C++ runtime, OpenMesh and SuiteSparse are linked in), and the licences of
  what is linked in are in the wheel; at import it loads the OpenBLAS of its dependency
  scipy-openblas32, and says so when that is missing;
- auditwheel show finds the wheel consistent with its platform tag or an older glibc's;
- the stubs and py.typed are installed and mypy's stubtest finds them consistent with the
  module (tests/stubtest_allowlist.txt: what every pybind11 module differs in).

Missing wheel or Python: skipped locally, a failure when CI is set (scripts/setup.sh builds
them).
"""

import json
import os
import pathlib
import re
import subprocess
import sys
import tomllib

import pytest

from geofair_dev.testing import unavailable

REPO = pathlib.Path(__file__).resolve().parents[1]
VERSION = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]
NOT_MODULE_TESTS = {
    "test_blender.py",  # the add-on in Blender
    "test_extension.py",  # the extension zip in bpy
    "test_wheel.py",  # this file
    "test_stubs.py",  # the stubs against the build tree
    "test_native_import.py",  # the add-on's native.py
    "test_cgal_reference.py",  # build/bench
    "test_windows.py",  # the Windows wheels under wine64
}


TAGS = ("cp311", "cp312", "cp313")
TEST_REQUIREMENTS = ("numpy", "scipy", "matplotlib", "pytest", "mypy")  # of the module's tests
PYENV = pathlib.Path(os.environ.get("PYENV_ROOT") or pathlib.Path.home() / ".pyenv")


def built_wheel(tag):
    """The repaired wheel of this version for CPython ``tag`` in dist/ (skip or fail when there is none)."""
    wheels = sorted((REPO / "dist").glob(f"geofair-{VERSION}-{tag}-{tag}-manylinux*_x86_64.whl"))
    if not wheels:
        unavailable(f"no repaired {tag} wheel geofair-{VERSION}-*manylinux* in dist/: run scripts/build_wheel.sh")
    assert len(wheels) == 1, wheels
    return wheels[0]


def interpreter(tag):
    """The Python of ``tag``: this one (its base, outside any venv) for cp311, pyenv's for the others."""
    if tag == "cp311":
        if sys.version_info[:2] != (3, 11):
            unavailable(f"the cp311 wheel needs Python 3.11, this is {sys.version.split()[0]}")
        return pathlib.Path(getattr(sys, "_base_executable", sys.executable))
    minor = tag.removeprefix("cp3")
    found = sorted(PYENV.glob(f"versions/3.{minor}.*/bin/python3.{minor}"))
    if not found:
        unavailable(f"no Python 3.{minor} under {PYENV}/versions")
    return found[-1]


def clean_env(**extra):
    """The environment without PYTHONPATH (build/python) and with ``extra``."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "GEOFAIR_BUILD")}
    return dict(env, **extra)


@pytest.fixture(scope="module", params=TAGS)
def venv(request, tmp_path_factory):
    """``(python, package folder, wheel)`` of a fresh venv of the wheel's Python with the wheel installed."""
    tag = request.param
    wheel = built_wheel(tag)
    base = interpreter(tag)
    folder = tmp_path_factory.mktemp(f"venv-{tag}")
    # cp311: with the packages of the Python the tests run on (scripts/setup.sh's .venv sees
    # them too); pip installs what the tests need and it lacks.
    system = ["--system-site-packages"] if tag == "cp311" else []
    subprocess.run([base, "-m", "venv", *system, str(folder)], check=True)
    python = folder / "bin" / "python"
    subprocess.run(
        [python, "-m", "pip", "install", "-q", "--disable-pip-version-check", *TEST_REQUIREMENTS],
        check=True,
        env=clean_env(),
    )
    # With its dependencies, as a user installs it (numpy, and scipy-openblas32: the BLAS).
    subprocess.run(
        [python, "-m", "pip", "install", "-q", "--disable-pip-version-check", wheel],
        check=True,
        env=clean_env(),
    )
    where = subprocess.run(
        [python, "-c", "import geofair; print(geofair.__file__); print(geofair.__version__)"],
        capture_output=True,
        text=True,
        env=clean_env(),
        cwd=folder,
        check=True,
    ).stdout.split()
    package = pathlib.Path(where[0]).parent
    assert folder in package.parents and package.name == "geofair", f"geofair imported from {where[0]}"
    assert where[1] == VERSION
    return python, package, wheel


# The wheels of all Pythons compile the same library (once, scripts/build_wheel.sh); only the
# bindings differ: these run against every wheel (conversions, errors, a solve of each kind),
# and the solvers' own tests and the large solves (marked slow) against the cp311 wheel
# (Blender 4.2 to 5.0's) as well.
BINDINGS_TESTS = ("test_fairing.py", "test_bad_input.py", "test_defaults.py", "test_fill_holes.py", "test_remesh.py")
SOLVER_TESTS = ("test_newton.py", "test_multigrid.py", "test_bilaplacian.py", "test_accuracy.py")


def test_module_tests_pass_against_the_wheel(venv):
    python, package, wheel = venv
    tests = sorted(p.name for p in (REPO / "tests").glob("test_*.py") if p.name not in NOT_MODULE_TESTS)
    assert "test_fairing.py" in tests and "test_multigrid.py" in tests
    assert set(BINDINGS_TESTS) | set(SOLVER_TESTS) <= set(tests)
    full = "-cp311-" in wheel.name
    tests = [*BINDINGS_TESTS, *(SOLVER_TESTS if full else ())]
    command = [python, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-x", *(f"tests/{t}" for t in tests)]
    if not full:
        command += ["-m", "not slow"]
    # A conftest check that the tests really use the wheel: geofair is imported from the venv.
    probe = "import geofair, sys; assert 'build' not in geofair.__file__, geofair.__file__"
    completed = subprocess.run(
        [python, "-c", probe], cwd=REPO, env=clean_env(GEOFAIR_TEST_INSTALLED="1"), capture_output=True, text=True
    )
    assert completed.returncode == 0, completed.stderr
    completed = subprocess.run(
        command, cwd=REPO, env=clean_env(GEOFAIR_TEST_INSTALLED="1"), capture_output=True, text=True, timeout=600
    )
    output = completed.stdout + completed.stderr
    assert completed.returncode == 0, output
    assert re.search(r"\d+ passed", output) and " failed" not in output and " error" not in output, output


def manylinux_allowed(tag):
    """The libraries auditwheel's policy for ``tag`` (e.g. manylinux_2_35_x86_64) allows from the system."""
    import auditwheel

    policies = json.loads((pathlib.Path(auditwheel.__file__).parent / "policy" / "manylinux-policy.json").read_text())
    name = re.sub(r"_x86_64$", "", tag)
    (policy,) = [p for p in policies if p["name"] == name or name in p.get("aliases", [])]
    return set(policy["lib_whitelist"])


def ldd(path):
    """``{soname: resolved path or None}`` of what the dynamic loader loads for ``path`` (ldd)."""
    output = subprocess.run(["ldd", str(path)], capture_output=True, text=True, check=True).stdout
    libraries = {}
    for line in output.splitlines():
        line = line.strip()
        if "=>" in line:
            name, _, rest = line.partition("=>")
            rest = rest.strip()
            libraries[name.strip()] = None if rest.startswith("not found") else rest.split(" (")[0]
        elif line.startswith("/"):  # the dynamic loader itself
            libraries[pathlib.Path(line.split(" (")[0]).name] = line.split(" (")[0]
        elif line.startswith("linux-vdso"):
            continue
    return libraries


def glibc_versions(path):
    """The GLIBC_x.y symbol versions ``path`` needs, as sorted (x, y) tuples (objdump -T)."""
    output = subprocess.run(["objdump", "-T", str(path)], capture_output=True, text=True, check=True).stdout
    return sorted({tuple(map(int, v.split("."))) for v in re.findall(r"\bGLIBC_(\d+\.\d+)", output)})


def test_the_module_needs_nothing_but_glibc_2_28(venv):
    """The shipped wheel (scripts/build_wheel.sh's default, zig for glibc 2.28): the module loads
    only manylinux_2_28 system libraries, needs no glibc symbol newer than 2.28, links its C++
    runtime, OpenMesh and SuiteSparse statically (no geofair.libs/, no libstdc++, libgomp,
    SuiteSparse or BLAS library), and the wheel carries the compiled-in libraries' licences."""
    _, package, wheel = venv
    tag = re.search(r"-(manylinux_\d+_\d+_x86_64)\.whl$", wheel.name).group(1)
    assert tag == "manylinux_2_28_x86_64", wheel.name
    allowed = manylinux_allowed(tag) | {"ld-linux-x86-64.so.2"}
    python_tag = wheel.name.split("-")[2].removeprefix("cp")
    (module,) = package.glob(f"__init__.cpython-{python_tag}-*.so")
    libraries = ldd(module)
    assert all(libraries.values()), f"unresolved: {[n for n, p in libraries.items() if p is None]}"
    assert set(libraries) <= allowed, f"not on the manylinux_2_28 allow-list: {set(libraries) - allowed}"
    for absent in ("libstdc++", "libgomp", "libumfpack", "libcholmod", "libopenblas", "libOpenMesh"):
        assert not any(n.startswith(absent) for n in libraries), (absent, libraries)
    assert not (package.parent / "geofair.libs").exists()
    versions = glibc_versions(module)
    assert versions and max(versions) <= (2, 28), versions
    (licenses,) = package.parent.glob("geofair-*.dist-info/licenses")
    for name in ("LICENSE", "OpenMesh.LICENSE", "libcxx.LICENSE", "libcxxabi.LICENSE", "libunwind.LICENSE"):
        assert (licenses / name).is_file(), sorted(p.name for p in licenses.iterdir())
    for name in ("SuiteSparse", "CHOLMOD", "UMFPACK", "AMD", "COLAMD", "METIS"):
        assert (licenses / f"{name}.LICENSE").is_file(), sorted(p.name for p in licenses.iterdir())


def test_the_module_loads_openblas_from_scipy_openblas32(venv):
    """The wheel's SuiteSparse runs on the OpenBLAS of its dependency scipy-openblas32, which
    the module loads at import; without it (or with GEOFAIR_BLAS naming no library) the import
    fails with an ImportError that says what to install, never at the first solve."""
    python, _, _ = venv
    probe = (
        "import numpy as np, geofair\n"
        "v = np.array([[0,0,0],[1,0,0],[0,1,0],[1,1,0],[.5,.5,.3]], float)\n"
        "f = np.array([[0,1,4],[1,3,4],[3,2,4],[2,0,4]])\n"
        "r = geofair.fair(v, f, np.arange(5) == 4, boundary='g0')\n"
        "print(r.converged, abs(r.vertices[4, 2]) < 1e-6)\n"
        "import scipy_openblas32, pathlib\n"
        "maps = pathlib.Path('/proc/self/maps').read_text()\n"
        "print(scipy_openblas32.get_lib_dir() in maps)"
    )
    done = subprocess.run([python, "-c", probe], capture_output=True, text=True, env=clean_env(), cwd="/")
    assert done.stdout.split() == ["True", "True", "True"], done.stdout + done.stderr
    blocked = "import sys; sys.modules['scipy_openblas32'] = None; import geofair"
    failed = subprocess.run([python, "-c", blocked], capture_output=True, text=True, env=clean_env(), cwd="/")
    assert failed.returncode != 0 and "ImportError" in failed.stderr, failed.stderr
    assert "pip install scipy-openblas32" in failed.stderr, failed.stderr
    wrong = subprocess.run(
        [python, "-c", "import geofair"],
        capture_output=True,
        text=True,
        env=clean_env(GEOFAIR_BLAS="/nonexistent/libopenblas.so"),
        cwd="/",
    )
    assert wrong.returncode != 0 and "/nonexistent/libopenblas.so" in wrong.stderr, wrong.stderr


def test_the_import_starts_no_blas_thread(venv):
    """OpenBLAS's worker threads spin for about 0.1 s of a core once started, which a solve
    right after the import lost; fair() runs its BLAS on one thread. The module loads its
    OpenBLAS with one thread, so the import starts none, and the caller's OPENBLAS_NUM_THREADS
    is left as it was (unset, or 3) in the process's environment and in os.environ."""
    python, _, _ = venv
    probe = (
        "import ctypes, os, pathlib, numpy\n"
        "def tasks(): return len(os.listdir('/proc/self/task'))\n"
        "before = tasks()\n"
        "import geofair, scipy_openblas32\n"
        "after = tasks()\n"
        "folder = pathlib.Path(scipy_openblas32.get_lib_dir())\n"
        "blas = ctypes.CDLL(str(next(folder.glob('libscipy_openblas*.so'))))\n"
        "libc = ctypes.CDLL(None)\n"
        "libc.getenv.restype = ctypes.c_char_p\n"
        "print(after - before, blas.scipy_openblas_get_num_threads(),"
        " libc.getenv(b'OPENBLAS_NUM_THREADS'), os.environ.get('OPENBLAS_NUM_THREADS'))"
    )
    for value, expected in ((None, ["None", "None"]), ("3", ["b'3'", "3"])):
        env = {k: v for k, v in clean_env().items() if k not in ("OPENBLAS_NUM_THREADS", "GEOFAIR_BLAS")}
        if value is not None:
            env["OPENBLAS_NUM_THREADS"] = value
        done = subprocess.run([python, "-c", probe], capture_output=True, text=True, env=env, cwd="/")
        assert done.stdout.split() == ["0", "1", *expected], done.stdout + done.stderr


@pytest.mark.parametrize("python_tag", TAGS)
def test_auditwheel_show_agrees_with_the_platform_tag(python_tag):
    """auditwheel finds the wheel consistent with its tag or an older glibc's (the module needs
    nothing newer than glibc 2.17; the wheel is tagged 2.28, Blender's and bpy's floor)."""
    wheel = built_wheel(python_tag)
    completed = subprocess.run(
        [sys.executable, "-m", "auditwheel", "show", str(wheel)], capture_output=True, text=True, check=True
    )
    tagged = re.search(r"-manylinux_(\d+)_(\d+)_x86_64\.whl$", wheel.name).groups()
    found = re.search(r'consistent with\nthe following platform tag: "manylinux_(\d+)_(\d+)_x86_64"', completed.stdout)
    assert found, completed.stdout
    assert tuple(map(int, found.groups())) <= tuple(map(int, tagged)), completed.stdout


def test_stubs_installed_and_consistent_with_the_module(venv, tmp_path):
    python, package, _ = venv
    shipped = (REPO / "native" / "python" / "stubs" / "geofair" / "__init__.pyi").read_text()
    assert (package / "__init__.pyi").read_text() == shipped
    assert (package / "py.typed").is_file()
    (tmp_path / "mypy.ini").write_text("[mypy]\nignore_missing_imports = True\n")  # scipy has no stubs
    completed = subprocess.run(
        [
            python,
            "-m",
            "mypy.stubtest",
            "--mypy-config-file",
            tmp_path / "mypy.ini",
            "--allowlist",
            REPO / "tests" / "stubtest_allowlist.txt",
            "geofair",
        ],
        cwd=tmp_path,
        env=clean_env(),
        capture_output=True,
        text=True,
    )
    assert completed.returncode == 0, completed.stdout + completed.stderr
    assert "Success: no issues found" in completed.stdout, completed.stdout
