"""The add-on's message when the compiled module is missing or built for another Python (bpy-free native.py)."""

import importlib.util
import pathlib

import pytest

_NATIVE_PY = pathlib.Path(__file__).resolve().parents[1] / "addon" / "geometric_fairing" / "native.py"
_spec = importlib.util.spec_from_file_location("geofair_native", _NATIVE_PY)
native = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(native)


@pytest.mark.parametrize(
    "filename, tag",
    [
        ("geofair.cpython-311-x86_64-linux-gnu.so", (3, 11)),
        ("geofair.cpython-310-darwin.so", (3, 10)),
        ("geofair.cp312-win_amd64.pyd", (3, 12)),
        ("geofair.so", None),
    ],
)
def test_python_tag(filename, tag):
    assert native.python_tag(filename) == tag


def test_module_built_for_another_python(tmp_path):
    (tmp_path / "geofair.cpython-312-x86_64-linux-gnu.so").write_bytes(b"")
    message = native.import_error_message(ImportError("No module named 'x.geofair'"), tmp_path, (3, 11))
    assert "was built for Python 3.12 (geofair.cpython-312-x86_64-linux-gnu.so)" in message
    assert "this Blender runs Python 3.11" in message
    assert "-DPython3_EXECUTABLE=" in message


def test_module_missing(tmp_path):
    message = native.import_error_message(ImportError("No module named 'x.geofair'"), tmp_path, (3, 11))
    assert message.startswith(f"The compiled module 'geofair' is missing from the add-on folder {tmp_path}")
    assert "cmake --build build" in message


def test_module_for_this_python_that_does_not_load(tmp_path):
    (tmp_path / "geofair.cpython-311-x86_64-linux-gnu.so").write_bytes(b"")
    error = ImportError("libOpenMeshCore.so.9.0: cannot open shared object file")
    message = native.import_error_message(error, tmp_path, (3, 11))
    assert "missing or cannot be loaded by Python 3.11" in message and "libOpenMeshCore" in message


def test_alone_the_file_does_not_import_geofair():
    assert native.geofair is None and "not part of the geometric_fairing package" in native.IMPORT_ERROR
