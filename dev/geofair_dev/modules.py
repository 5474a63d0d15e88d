"""Which ``geofair`` a benchmark's child process imports: this environment's, a build folder's,
or an installed wheel's (bench/speed.py ``--module``).

A module is named by a spec: ``this`` (whatever ``import geofair`` finds here), a folder
holding the compiled module (``build/python``; put first on PYTHONPATH), or a wheel file,
installed with its dependencies (numpy, scipy-openblas32) into a venv of its own under
``~/.cache/geofair/bench-venvs/`` (made once per wheel, by its file name and content hash; the venv
sees this Python's site-packages for numpy and geofair_dev, as a user's would see theirs).
"""

import hashlib
import os
import pathlib
import subprocess
import sys

VENVS = pathlib.Path(os.environ.get("XDG_CACHE_HOME") or pathlib.Path.home() / ".cache") / "geofair" / "bench-venvs"


def parse(spec):
    """``(label, spec)`` of ``LABEL=SPEC`` or ``SPEC`` (the label then derived from it)."""
    label, sep, rest = spec.partition("=")
    if sep and not os.path.exists(spec):
        return label, rest
    if spec == "this":
        return "this", spec
    path = pathlib.Path(spec)
    if path.suffix == ".whl":
        return "wheel " + path.name.split("-")[2], spec
    return str(path), spec


def _site_folders():
    """This environment's site-packages folders (a venv's own, and its base Python's where it sees them)."""
    import site

    return site.getsitepackages()


def _venv_for(wheel):
    """The venv with ``wheel`` installed (made on first use)."""
    wheel = pathlib.Path(wheel).resolve()
    if not wheel.is_file():
        raise FileNotFoundError(f"no wheel {wheel}")
    # Keyed by the wheel's content: two builds of one version can have the same size.
    digest = hashlib.sha256(wheel.read_bytes()).hexdigest()[:16]
    folder = VENVS / f"{wheel.stem}-{digest}"
    python = folder / "bin" / "python"
    installed = folder / "geofair-installed"  # written last: an interrupted install is redone
    if not installed.exists():
        subprocess.run([sys.executable, "-m", "venv", str(folder)], check=True)
        # This environment's packages after the venv's own (also where this is a venv, which
        # --system-site-packages would skip for its base Python's).
        site = subprocess.run([python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"],
                              capture_output=True, text=True, check=True).stdout.strip()  # fmt: skip
        parent = [p for p in _site_folders() if os.path.isdir(p)]
        # map, not a comprehension: site runs the line with exec, whose names a comprehension's
        # scope does not see.
        line = f"import site; list(map(site.addsitedir, {parent!r}))\n"
        pathlib.Path(site, "geofair_bench_parent.pth").write_text(line)
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        subprocess.run(
            [python, "-m", "pip", "install", "-q", "--disable-pip-version-check", str(wheel)], check=True, env=env
        )
        installed.write_text(str(wheel) + "\n")
    return python


def command(spec):
    """``(python executable, environment)`` under which a child process imports the module of ``spec``."""
    env = dict(os.environ)
    if spec == "this":
        return sys.executable, env
    path = pathlib.Path(spec)
    if path.suffix == ".whl":
        env.pop("PYTHONPATH", None)
        env.pop("GEOFAIR_BUILD", None)
        return str(_venv_for(path)), env
    if not path.is_dir():
        raise FileNotFoundError(f"--module {spec}: neither a folder, a .whl file nor 'this'")
    env["PYTHONPATH"] = str(path.resolve()) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return sys.executable, env
