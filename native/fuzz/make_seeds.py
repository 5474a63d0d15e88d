"""Writes seed inputs for fuzz_fair (see the layout in fuzz_fair.cpp): small valid meshes so
that the fuzzer starts inside the fairing path rather than at input validation."""

import pathlib

import numpy as np


def encode(vertices, free, faces, flags):
    out = bytearray([len(vertices) - 3, len(faces) - 1, flags])
    for v, f in zip(vertices, free, strict=True):
        out += bytes(int(np.clip(round(c * 16), -128, 127)) & 0xFF for c in v)
        out.append(int(f))
    for t in faces:
        out += bytes(int(i) for i in t)
    return bytes(out)


def grid(n, bump):
    xs = np.linspace(-3, 3, n)
    vertices = [(x, y, bump * np.exp(-(x * x + y * y))) for y in xs for x in xs]
    faces = []
    for j in range(n - 1):
        for i in range(n - 1):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i
            faces += [(a, b, c), (a, c, d)]
    free = [1 < i < n - 2 and 1 < j < n - 2 for j in range(n) for i in range(n)]
    return vertices, free, faces


if __name__ == "__main__":
    folder = pathlib.Path(__file__).with_name("corpus")
    folder.mkdir(exist_ok=True)
    for n, bump, flags in ((6, 1.0, 0), (7, 2.0, 1), (8, 1.5, 4), (7, 0.0, 2)):
        (folder / f"grid{n}_{flags}").write_bytes(encode(*grid(n, bump), flags))
