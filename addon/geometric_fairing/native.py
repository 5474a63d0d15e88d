"""The compiled module ``geofair``, in this package or from the wheel, and a clear message when it cannot load.

The legacy zip (dist/geometric_fairing-<version>-legacy_linux_x64.zip, scripts/build_extension.py;
a development build's build/geometric_fairing.zip) puts ``geofair.cpython-3XY-<platform>.so``
(or ``.pyd``) next to this file, and in the legacy zip the OpenBLAS it loads at import
(``libscipy_openblas.so``, named to the module by the environment variable GEOFAIR_BLAS;
the wheel loads it from its dependency scipy-openblas32). The extension has none here:
Blender 4.2+ installs the wheel its manifest lists into the extensions' site-packages,
and ``import geofair`` finds it there. A module built for another Python than Blender's
does not import; the message then names both versions instead of Python's "No module named".
No bpy here.
"""

import importlib
import os
import pathlib
import re
import sys

PACKAGE_DIR = pathlib.Path(__file__).resolve().parent


def module_files(folder=PACKAGE_DIR):
    """Names of the compiled ``geofair`` modules in ``folder``, sorted."""
    return sorted(p.name for p in pathlib.Path(folder).glob("geofair*") if p.suffix in (".so", ".pyd"))


def python_tag(filename):
    """``(major, minor)`` a compiled module file was built for, from ``cpython-3XY`` or ``cp3XY``; None if unknown."""
    match = re.search(r"(?:cpython-|cp)(\d)(\d+)", filename)
    return (int(match.group(1)), int(match.group(2))) if match else None


def import_error_message(error, folder=PACKAGE_DIR, version=None):
    """Explain why ``geofair`` could not be imported from ``folder``.

    Args:
        error: the ImportError (or its text).
        folder: the package folder that should hold the compiled module.
        version: ``sys.version_info`` of the running Python (for tests).
    """
    version = tuple((version or sys.version_info)[:2])
    running = f"{version[0]}.{version[1]}"
    files = module_files(folder)
    if not files:
        return (
            f"The compiled module 'geofair' is missing from the add-on folder {folder} and no geofair wheel is "
            f"installed: install the extension zip (scripts/build_extension.sh) in Blender 4.2+, or build the project "
            f"(cmake --build build) and install build/geometric_fairing.zip ({error})"
        )
    built_for = {python_tag(name) for name in files} - {None}
    if built_for and version not in built_for:
        wanted = ", ".join(f"{major}.{minor}" for major, minor in sorted(built_for))
        return (
            f"The compiled module 'geofair' was built for Python {wanted} ({', '.join(files)}), but this Blender "
            f"runs Python {running}: rebuild it with Blender's Python "
            f"(cmake -B build -DPython3_EXECUTABLE=/path/to/python{running}) ({error})"
        )
    return (
        f"The compiled module 'geofair' is missing or cannot be loaded by Python {running} "
        f"(module files in the add-on: {', '.join(files)}): {error}"
    )


def load():
    """Return ``(geofair, None)``, or ``(None, message)`` when the compiled module cannot be loaded."""
    if not __package__:  # loaded as a lone file (tests of the functions above)
        return None, "native.py is not part of the geometric_fairing package"
    try:
        if not module_files():  # the extension: the module comes from its wheel
            return importlib.import_module("geofair"), None
        bundled_blas = sorted(PACKAGE_DIR.glob("libscipy_openblas*.so"))
        if bundled_blas:
            os.environ.setdefault("GEOFAIR_BLAS", str(bundled_blas[0]))
        return importlib.import_module(".geofair", __package__), None
    except ImportError as error:
        # pybind11 registers its types once per process: a second copy of the module (the add-on
        # installed both as legacy add-on and as extension, or reloaded from another folder) does not
        # import. The copy already loaded is the same code of some version: use it.
        if "already registered" in str(error):
            loaded = already_loaded()
            if loaded is not None:
                return loaded, None
        return None, import_error_message(error)


def already_loaded():
    """A ``geofair`` module some other package (or sys.path) has already loaded in this process, or None."""
    for name, module in list(sys.modules.items()):
        if name.rpartition(".")[2] == "geofair" and module is not None and hasattr(module, "FairingResult"):
            return module
    return None


geofair, IMPORT_ERROR = load()
