"""Write geofair's type stubs (native/python/stubs/geofair/__init__.pyi) from the compiled module.

    PYTHONPATH=build/python python3 scripts/make_stubs.py [OUT.pyi]

pybind11-stubgen (pinned in scripts/setup.sh) reads the module that ``import geofair``
finds: its classes, docstrings and, from each function's ``__text_signature__``, the
parameters and defaults. Those signatures carry no types (inspect.signature could not read
them), so each function's ``def`` line is rewritten here with the types of PARAMETER_TYPES
and RETURN_TYPES; a string option is typed ``typing.Literal[...]`` of the values the module
accepts, read from the message with which it rejects another value (the module's table,
``parse`` in bindings.cpp). ``__version__`` is declared ``str`` without its value
(pyproject.toml holds the version). The wheel ships the stubs with py.typed (PEP 561);
tests/test_stubs.py checks that they are what this script makes from the built module and
runs mypy's stubtest on them, tests/test_wheel.py runs it against the installed wheel.
"""

import inspect
import pathlib
import re
import subprocess
import sys
import tempfile

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[1]
STUBS = REPO / "native" / "python" / "stubs" / "geofair" / "__init__.pyi"

FLOAT64_ARRAY = "numpy.typing.NDArray[numpy.float64]"
INT32_ARRAY = "numpy.typing.NDArray[numpy.int32]"
INTEGER_ARRAY = "numpy.typing.NDArray[numpy.integer[typing.Any]]"
BOOL_ARRAY = "numpy.typing.NDArray[numpy.bool_]"
FLOAT = "typing.SupportsFloat | typing.SupportsIndex"  # what pybind11 converts to a C++ double
INT = "typing.SupportsInt | typing.SupportsIndex"  # to a C++ int

# Parameter types by name (the same name means the same thing in every function); a string
# option not listed is typed by the values the module accepts.
PARAMETER_TYPES = {
    "vertices": FLOAT64_ARRAY,
    "faces": INTEGER_ARRAY,
    "free": BOOL_ARRAY,
    "normals": FLOAT64_ARRAY,
    "boundary_normals": f"{FLOAT64_ARRAY} | None",
    "polygon_ids": f"{INTEGER_ARRAY} | None",
    "loops": "collections.abc.Iterable[collections.abc.Iterable[typing.SupportsIndex]] | None",
    "target_edge_length": f"{FLOAT} | None",
    "keep_outer_borders": "bool",
    "max_hole_edges": f"{INT} | None",
    "tolerance": FLOAT,
    "damping": FLOAT,
    "max_iterations": INT,
    "cg_iterations": INT,
    "levels": INT,
    "iterations": INT,
    "coarsen_boundary": "bool",
    "progress": "collections.abc.Callable[[int, float], bool | None] | None",
    "time_limit": f"{FLOAT} | None",
    "tuning": "dict[str, typing.Any] | None",
    "path": "str",
    "colors": "numpy.typing.NDArray[numpy.uint8] | None",
    "texcoords": f"{FLOAT64_ARRAY} | None",
    "details": "bool",
    "max_warm_steps": INT,
}
# mean_curvature's normals may be None (then estimated); relax_inner_fairness' may not.
PARAMETER_TYPES_OF = {("mean_curvature", "normals"): f"{FLOAT64_ARRAY} | None"}
RETURN_TYPES = {
    "boundary_loops": f"list[{INT32_ARRAY}]",
    "boundary_normals": FLOAT64_ARRAY,
    "cotangent_laplacian": "scipy.sparse.csr_matrix",
    "defaults": "dict[str, typing.Any]",
    "fair": "FairingResult",
    "fill_holes": "FillResult",
    "holes_to_fill": f"tuple[list[{INT32_ARRAY}], list[tuple[{INT32_ARRAY}, str]]]",
    "intrinsic_delaunay": f"tuple[{INT32_ARRAY}, {FLOAT64_ARRAY}, int]",
    "intrinsic_delaunay_laplacian": "scipy.sparse.csr_matrix",
    "mean_curvature": FLOAT64_ARRAY,
    "progressive_mesh": f"list[{INT32_ARRAY}]",
    "read_mesh": "dict[str, typing.Any]",
    "relax_inner_fairness": f"tuple[{FLOAT64_ARRAY}, float]",
    "remesh_region": "RemeshedRegion",
    "write_mesh": "None",
}
# Methods of the classes, by (class, method): their return types. __init__'s parameters are
# those of the class (its signature, without self).
METHOD_RETURN_TYPES = {("LiveFairing", "__init__"): "None", ("LiveFairing", "update"): "FairingResult"}
IMPORTS = ("collections.abc", "numpy", "numpy.typing", "scipy.sparse", "typing")


def probe_arguments():
    """Valid positional arguments by name: a fan of 6 triangles around a free centre."""
    angles = np.linspace(0.0, 2.0 * np.pi, 7)[:-1]
    ring = np.stack([np.cos(angles), np.sin(angles), np.zeros(6)], axis=1)
    vertices = np.vstack([[0.0, 0.0, 0.1], ring])
    free = np.zeros(7, dtype=bool)
    free[0] = True
    return {
        "vertices": vertices,
        "faces": np.array([[0, 1 + i, 1 + (i + 1) % 6] for i in range(6)]),
        "free": free,
        "normals": np.tile([0.0, 0.0, 1.0], (7, 1)),
    }


def accepted_values(function, option):
    """The strings ``function`` takes for ``option``, in the module's order: those its error
    message lists when it is given another (remesh: besides False and True)."""
    signature = inspect.signature(function)
    known = probe_arguments()
    arguments = [known[p.name] for p in signature.parameters.values() if p.default is inspect.Parameter.empty]
    try:
        function(*arguments, **{option: "no such value"})
    except ValueError as error:
        listed = re.fullmatch(rf"{option} must be (?:one of )?(.*), got 'no such value'", str(error))
        if listed:
            return re.findall(r"'([^']*)'", listed.group(1))
        raise
    raise AssertionError(f"{function.__name__} accepted {option}='no such value'")


def annotation(function, parameter):
    """The stub type of ``parameter`` of ``function``."""
    key = (function.__name__, parameter.name)
    if key in PARAMETER_TYPES_OF:
        return PARAMETER_TYPES_OF[key]
    if parameter.name in PARAMETER_TYPES:
        return PARAMETER_TYPES[parameter.name]
    if parameter.name == "remesh":
        return f"bool | typing.Literal[{', '.join(map(repr, accepted_values(function, 'remesh')))}]"
    if isinstance(parameter.default, str):
        return f"typing.Literal[{', '.join(map(repr, accepted_values(function, parameter.name)))}]"
    raise LookupError(f"no stub type for {function.__name__}({parameter.name})")


def typed_def(function, name=None, returns=None, method=False):
    """The ``def`` line of ``function`` with the types of its parameters and result; a
    method's (``name``, ``returns``) with self first, untyped."""
    parts, star = (["self"] if method else []), False
    for p in inspect.signature(function).parameters.values():
        if method and p.name == "self":
            continue
        if p.kind is inspect.Parameter.KEYWORD_ONLY and not star:
            parts.append("*")
            star = True
        part = f"{p.name}: {annotation(function, p)}"
        parts.append(part if p.default is inspect.Parameter.empty else f"{part} = {p.default!r}")
    name = name or function.__name__
    returns = returns or RETURN_TYPES[name]
    return f"def {name}({', '.join(parts)}) -> {returns}:"


def typed_method(cls, name):
    """The ``def`` line of method ``name`` of class ``cls`` (METHOD_RETURN_TYPES)."""
    function = cls if name == "__init__" else getattr(cls, name)
    return typed_def(function, name, METHOD_RETURN_TYPES[(cls.__name__, name)], method=True)


def generate():
    """The stub text for the ``geofair`` that this Python imports."""
    import geofair

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
    text = version.sub("__version__: str", text)

    def typed(match):
        return typed_def(getattr(geofair, match.group(1)))

    text, count = re.subn(r"^def (\w+)\(.*\):$", typed, text, flags=re.MULTILINE)
    assert count == len(RETURN_TYPES), f"{count} functions, {len(RETURN_TYPES)} return types"
    for cls_name, method in METHOD_RETURN_TYPES:
        head = re.compile(rf"^(class {cls_name}:\n(?:(?!class ).*\n)*?)    def {method}\(.*\):$", re.MULTILINE)
        line = "    " + typed_method(getattr(geofair, cls_name), method)
        text, count = head.subn(lambda m, line=line: m.group(1) + line, text)
        assert count == 1, f"no def {method} in class {cls_name}"
    # Properties that return a bool array (pybind11-stubgen cannot name numpy's bool).
    text = text.replace("numpy.ndarray[typing.Any, numpy.dtype[typing.Any]]", BOOL_ARRAY)
    imports = re.compile(r"^import [\w.]+\n", re.MULTILINE)
    first = imports.search(text).start()
    text = imports.sub("", text)
    return text[:first] + "".join(f"import {name}\n" for name in IMPORTS) + text[first:]


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else STUBS
    out.write_text(generate())
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
