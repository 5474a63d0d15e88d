"""Write geofair's type stubs (native/python/stubs/geofair/__init__.pyi) from the compiled module.

    PYTHONPATH=build/python python3 scripts/make_stubs.py [OUT.pyi]

pybind11-stubgen (pinned in scripts/setup.sh) reads the module that ``import geofair``
finds; ``__version__`` is declared ``str`` without its value (pyproject.toml holds the
version). The wheel ships the stubs
with py.typed (PEP 561); tests/test_stubs.py checks that they are what this script makes
from the built module, and mypy's stubtest checks them against the installed wheel.
"""

import pathlib
import re
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parents[1]
STUBS = REPO / "native" / "python" / "stubs" / "geofair" / "__init__.pyi"


def generate():
    """The stub text for the ``geofair`` that this Python imports."""
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run(
            [
                sys.executable,
                "-m",
                "pybind11_stubgen",
                "--exit-code",
                "--numpy-array-use-type-var",
                "-o",
                folder,
                "geofair",
            ],
            check=True,
            capture_output=True,
            text=True,
        )
        text = (pathlib.Path(folder) / "geofair.pyi").read_text()
    version = re.compile(r"^__version__: str = .*$", re.MULTILINE)
    assert len(version.findall(text)) == 1, "pybind11-stubgen wrote no __version__"
    return version.sub("__version__: str", text)


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else STUBS
    out.write_text(generate())
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
