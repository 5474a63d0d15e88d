"""A small software renderer for the result figures (numpy only): flat shading with the
mesh edges, and reflection lines, as in the paper's pictures.

Orthographic camera, z-buffered triangles, supersampled for antialiasing.  Deterministic
and headless; fast enough for meshes of some 10^4 triangles at 1000 pixels.

- ``shade="flat"``: one colour per triangle (Lambert, a key light from the upper left
  plus a head light), mesh edges drawn in a darker tone; triangles in `highlight` are
  tinted.  Flat shading shows every facet, like the paper's pictures.
- ``shade="zebra"``: reflection lines: the view direction reflected at the normal
  interpolated from the vertex normals (area-weighted), striped by its azimuth about the
  screen's vertical axis: the picture of vertical light bars around the object.  Lines
  are continuous across curves where the surface is G1 and smooth where it is G2.
"""

from __future__ import annotations

import numpy as np

__all__ = ["Camera", "render"]

BACKGROUND = np.array([1.0, 1.0, 1.0])
GRAY = np.array([0.78, 0.78, 0.78])
TINT = np.array([0.62, 0.74, 0.92])


class Camera:
    """Orthographic camera looking along `direction` (3,) with `up` (3,) up on screen."""

    def __init__(self, direction, up=(0.0, 0.0, 1.0)):
        d = np.asarray(direction, float)
        self.forward = d / np.linalg.norm(d)
        right = np.cross(self.forward, np.asarray(up, float))
        self.right = right / np.linalg.norm(right)
        self.up = np.cross(self.right, self.forward)

    def project(self, p):
        """(k, 3) points -> (k, 3): screen x (right), screen y (up), depth (away)."""
        return np.column_stack([p @ self.right, p @ self.up, p @ self.forward])


def _vertex_normals(v, f):
    c = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n = np.zeros_like(v)
    for k in range(3):
        np.add.at(n, f[:, k], c)
    return n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300), c


def _rasterize(xy, depth, f, width, height):
    """Z-buffer: per pixel the nearest triangle id (-1: none) and its barycentrics."""
    face_id = np.full(width * height, -1, np.int64)
    zbuf = np.full(width * height, np.inf)
    bary = np.zeros((width * height, 3))
    p = xy[f]  # (m, 3, 2)
    x0 = np.clip(np.floor(p[:, :, 0].min(axis=1)).astype(np.int64), 0, width - 1)
    x1 = np.clip(np.ceil(p[:, :, 0].max(axis=1)).astype(np.int64), 0, width - 1)
    y0 = np.clip(np.floor(p[:, :, 1].min(axis=1)).astype(np.int64), 0, height - 1)
    y1 = np.clip(np.ceil(p[:, :, 1].max(axis=1)).astype(np.int64), 0, height - 1)
    nx, ny = x1 - x0 + 1, y1 - y0 + 1
    count = nx * ny
    det = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1])
    order = np.flatnonzero(np.abs(det) > 1e-12)
    start = 0
    while start < len(order):  # chunks of about 4M candidate pixels
        stop = start + max(1, int(np.searchsorted(np.cumsum(count[order[start:]]), 4_000_000)))
        tri = order[start:stop]
        start = stop
        k = count[tri]
        t = np.repeat(tri, k)
        local = np.arange(k.sum()) - np.repeat(np.cumsum(k) - k, k)
        px = x0[t] + local % nx[t]
        py = y0[t] + local // nx[t]
        cx, cy = px + 0.5, py + 0.5
        a, b, c = p[t, 0], p[t, 1], p[t, 2]
        w1 = ((cx - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (cy - a[:, 1])) / det[t]
        w2 = ((b[:, 0] - a[:, 0]) * (cy - a[:, 1]) - (cx - a[:, 0]) * (b[:, 1] - a[:, 1])) / det[t]
        w0 = 1 - w1 - w2
        inside = (w0 >= -1e-9) & (w1 >= -1e-9) & (w2 >= -1e-9)
        t, px, py, w0, w1, w2 = t[inside], px[inside], py[inside], w0[inside], w1[inside], w2[inside]
        z = w0 * depth[f[t, 0]] + w1 * depth[f[t, 1]] + w2 * depth[f[t, 2]]
        pix = py * width + px
        srt = np.lexsort((z, pix))
        first = srt[np.r_[True, pix[srt][1:] != pix[srt][:-1]]]
        pix, z = pix[first], z[first]
        closer = z < zbuf[pix]
        sel = first[closer]
        pix = pix[closer]
        zbuf[pix] = z[closer]
        face_id[pix] = t[sel]
        bary[pix] = np.column_stack([w0[sel], w1[sel], w2[sel]])
    return face_id, bary


def render(
    vertices: np.ndarray,
    faces: np.ndarray,
    camera: Camera,
    shade: str = "flat",
    width: int = 800,
    height: int = 800,
    frame: np.ndarray | None = None,
    highlight: np.ndarray | None = None,
    edges: bool = True,
    stripes: int = 14,
    supersample: int = 3,
    normals: np.ndarray | None = None,
) -> np.ndarray:
    """Render a triangle mesh; returns (height, width, 3) float64 RGB in [0, 1].

    vertices (n, 3), faces (m, 3) int (counter-clockwise seen from outside); `frame`
    (k, 3): points the picture must show (default: the vertices), so that several
    renders of one scene share a camera; `highlight` (m,) bool: triangles to tint;
    `normals` (n, 3): exact vertex normals for the reflection lines where a row is
    finite (NaN rows: the area-weighted normal of the mesh).
    """
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    s = supersample
    W, H = width * s, height * s
    scr = camera.project(v)
    fr = camera.project(np.asarray(frame, float) if frame is not None else v)
    lo, hi = fr[:, :2].min(axis=0), fr[:, :2].max(axis=0)
    scale = 0.92 * min(W / (hi[0] - lo[0]), H / (hi[1] - lo[1]))
    mid = (lo + hi) / 2
    xy = np.column_stack([(scr[:, 0] - mid[0]) * scale + W / 2, H / 2 - (scr[:, 1] - mid[1]) * scale])
    face_id, bary = _rasterize(xy, scr[:, 2], f, W, H)
    hit = face_id >= 0
    t = face_id[hit]
    vn, fc = _vertex_normals(v, f)
    if normals is not None:
        given = np.isfinite(normals).all(axis=1)
        vn[given] = normals[given]
    fn = fc / np.maximum(np.linalg.norm(fc, axis=1, keepdims=True), 1e-300)
    view = -camera.forward  # towards the camera
    facing = fn[t] @ view
    img = np.tile(BACKGROUND, (W * H, 1))
    base = np.tile(GRAY, (len(t), 1))
    if highlight is not None:
        base[np.asarray(highlight, bool)[t]] = TINT
    if shade == "flat":
        n = fn[t] * np.sign(facing)[:, None]
        key = camera.right * -0.5 + camera.up * 0.8 + view * 0.6
        key /= np.linalg.norm(key)
        light = 0.2 + 0.55 * np.clip(n @ key, 0, None) + 0.3 * np.abs(facing)
        col = base * light[:, None]
        col[facing < 0] *= 0.55  # inside of a tube
        if edges:  # distance to the nearest edge, in supersampled pixels
            p = xy[f[t]]
            area2 = np.abs(
                (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1])
            )
            length = np.stack([np.linalg.norm(p[:, (k + 2) % 3] - p[:, (k + 1) % 3], axis=1) for k in range(3)], 1)
            dist = (bary[hit] * area2[:, None] / np.maximum(length, 1e-12)).min(axis=1)
            col *= np.where(dist < 0.45 * s, 0.55, 1.0)[:, None]
    elif shade == "zebra":
        n = (bary[hit, :, None] * vn[f[t]]).sum(axis=1)
        n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
        n *= np.where(n @ view < 0, -1.0, 1.0)[:, None]
        d = camera.forward
        r = d - 2 * (n @ d)[:, None] * n
        azimuth = np.arctan2(r @ camera.right, r @ camera.forward)
        band = np.floor(azimuth * stripes / np.pi).astype(np.int64) % 2
        col = np.where(band[:, None] == 1, 0.08, 0.97) * np.ones(3)
        col = col * 0.85 + 0.15 * base
    else:
        raise ValueError(f"render: shade must be 'flat' or 'zebra', got {shade!r}")
    img[hit] = col
    img = img.reshape(H, W, 3).reshape(height, s, width, s, 3).mean(axis=(1, 3))
    return np.clip(img, 0.0, 1.0)
