"""The README's Python examples run as written, and the PyPI description (docs/PYPI.md, the
wheel's long description) holds no link that breaks off the repository.

- README.md's ```python blocks run in order in one namespace (the example builds its own
  mesh; the reference block after it calls every function on it), and the example's claim
  holds: the noisy disc is faired back onto the sphere of radius 2, where the linear Δ²f = 0
  is not;
- docs/PYPI.md's example is README's, byte for byte, and runs too; its links are absolute;
- pyproject.toml names docs/PYPI.md as the readme.
"""

import contextlib
import io
import re
import tomllib

import numpy as np

from geofair_dev.paths import REPO

BLOCK = re.compile(r"```python\n(.*?)```", re.S)


def run_blocks(blocks):
    namespace = {"__name__": "readme"}
    with contextlib.redirect_stdout(io.StringIO()) as printed:
        for block in blocks:
            exec(compile(block, "README.md", "exec"), namespace)
    return namespace, printed.getvalue()


def sphere_error(vertices):
    return float(np.abs(np.linalg.norm(vertices, axis=1) - 2).max())


def test_the_readme_python_blocks_run_as_written():
    blocks = BLOCK.findall((REPO / "README.md").read_text())
    assert len(blocks) >= 2, "the example and the reference block"
    namespace, printed = run_blocks(blocks[:1])
    result = namespace["result"]
    assert result.converged and sphere_error(result.vertices) < 1e-5, printed
    # What the README says of the linear fairing: it leaves the disc off the sphere.
    import geofair

    linear = geofair.fair(namespace["vertices"], namespace["faces"], namespace["free"], outer_fairness="bilaplacian")
    assert sphere_error(linear.vertices) > 1e-3
    # The reference block, on the example's mesh.
    namespace, _ = run_blocks(blocks)
    assert namespace["L"].shape == (namespace["n"] ** 2,) * 2
    filled, rows = namespace["filled"], len(namespace["vertices"])
    assert filled.converged and sphere_error(filled.vertices[rows:]) < 1e-4  # the hole filled with the sphere
    assert namespace["d"] == geofair.defaults()


def test_the_pypi_description_has_the_example_and_no_relative_link():
    description = (REPO / "docs" / "PYPI.md").read_text()
    assert tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["readme"] == "docs/PYPI.md"
    (example,) = BLOCK.findall(description)
    assert example == BLOCK.findall((REPO / "README.md").read_text())[0]
    namespace, _ = run_blocks([example])
    assert namespace["result"].converged
    links = re.findall(r"\]\(([^)]*)\)", description) + re.findall(r"<img[^>]*src=\"([^\"]*)\"", description)
    assert all(re.match(r"https?://", link) for link in links), links
