"""Pictures for judging a faired surface, without bpy (numpy only).

- :func:`curvature_colors`: mean curvature H as vertex colours, a diverging
  blue–white–red map symmetric around H = 0.
- :func:`zebra_matcap`: a matcap image whose stripes are reflection lines: a
  surface shaded with it shows the reflection of an environment of horizontal
  light bands, the picture the paper uses to judge G1 continuity at the
  boundary and smoothness inside.
- :func:`write_png`: an 8-bit PNG writer (zlib only), for the matcap file.
"""

import struct
import zlib

import numpy as np

# Diverging map in sRGB: concave (H < 0) blue, flat white, convex (H > 0) red.
NEGATIVE_SRGB = (0.13, 0.40, 0.85)
ZERO_SRGB = (1.0, 1.0, 1.0)
POSITIVE_SRGB = (0.85, 0.15, 0.10)


def srgb_to_linear(c):
    """sRGB components in [0, 1] to linear ones (IEC 61966-2-1)."""
    c = np.asarray(c, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def symmetric_limit(values, percentile=90.0):
    """The colour range ±limit for ``values``: the given percentile of ``|values|``.

    A percentile, not the maximum, so that the sharpest features (Suzanne's ears
    and eyelids: |H| up to 10 times its median) and spikes at an open border or
    a degenerate vertex do not wash out the rest; the top tenth is drawn
    saturated. Non-finite values are ignored; returns 1.0 when every finite
    value is 0.
    """
    magnitude = np.abs(np.asarray(values, dtype=np.float64))
    magnitude = magnitude[np.isfinite(magnitude)]
    limit = float(np.percentile(magnitude, percentile)) if magnitude.size else 0.0
    return limit if limit > 0.0 else 1.0


def curvature_colors(mean_curvature, limit=None):
    """Colour each vertex by its mean curvature, symmetric around 0.

    Args:
        mean_curvature: ``(n,)`` float, H in 1/length (H = 1/r on a sphere with
            outward normals: positive where the surface bends away from its normal).
        limit: H mapped to the full colours, ``-limit`` blue and ``+limit`` red;
            values beyond are clamped. ``None``: :func:`symmetric_limit`.

    Returns:
        ``(colors, limit)``: ``(n, 4)`` float32 linear RGBA (alpha 1), the
        convention of Blender's float colour attributes, and the limit used.
        Non-finite H is drawn as H = 0.
    """
    h = np.asarray(mean_curvature, dtype=np.float64)
    if limit is None:
        limit = symmetric_limit(h)
    t = np.clip(np.nan_to_num(h / limit, nan=0.0, posinf=1.0, neginf=-1.0), -1.0, 1.0)
    zero, negative, positive = (np.asarray(c, dtype=np.float64) for c in (ZERO_SRGB, NEGATIVE_SRGB, POSITIVE_SRGB))
    end = np.where(t[:, None] < 0.0, negative, positive)
    srgb = zero + np.abs(t)[:, None] * (end - zero)
    colors = np.ones((len(h), 4), dtype=np.float32)
    colors[:, :3] = srgb_to_linear(srgb)
    return colors, float(limit)


def zebra_matcap(size=256, stripes=10, dark=0.04, light=0.92, supersampling=4):
    """A matcap of reflection lines: stripes of the reflected view ray's elevation.

    A matcap is looked up by the view-space normal n = (x, y, z) of the surface
    at pixel ``(0.5 + x/2, 0.5 + y/2)``. The ray from the eye (looking along -z)
    reflects to ``r = 2 z n - (0, 0, 1)``; the pixel is light or dark by the
    elevation ``asin(r_y)`` of r, ``stripes`` bands over [-90°, 90°]: the
    reflection of an environment of horizontal light bands at infinity. Lines
    that kink at a curve show a normal discontinuity there (not G1); lines
    that wiggle show curvature that varies.

    Args:
        size: width and height in pixels.
        stripes: light/dark band pairs over the elevations.
        dark, light: grey levels of the bands, in [0, 1] (sRGB).
        supersampling: samples per pixel along each axis (anti-aliasing).

    Returns:
        ``(size, size, 3)`` uint8 sRGB, first row at the top (as PNG stores it).
    """
    steps = size * supersampling
    coordinate = (np.arange(steps) + 0.5) / steps * 2.0 - 1.0
    x, y = np.meshgrid(coordinate, -coordinate)  # y up: the first row is the top
    radius = np.hypot(x, y)
    # Outside the disk no normal maps there; continue the rim outwards.
    scale = np.where(radius > 1.0, 1.0 / np.maximum(radius, 1e-12), 1.0)
    x, y = x * scale, y * scale
    z = np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))
    elevation = np.arcsin(np.clip(2.0 * z * y, -1.0, 1.0))
    band = np.floor((elevation / np.pi + 0.5) * 2.0 * stripes).astype(np.int64) % 2
    value = np.where(band == 0, dark, light)
    value = value.reshape(size, supersampling, size, supersampling).mean(axis=(1, 3))
    grey = np.round(np.clip(value, 0.0, 1.0) * 255.0).astype(np.uint8)
    return np.repeat(grey[:, :, None], 3, axis=2)


def write_png(path, pixels):
    """Write ``(h, w, 3)`` or ``(h, w, 4)`` uint8 ``pixels`` (first row at the top) as an 8-bit PNG."""
    pixels = np.ascontiguousarray(pixels, dtype=np.uint8)
    if pixels.ndim != 3 or pixels.shape[2] not in (3, 4):
        raise ValueError(f"write_png: pixels must be (h, w, 3) or (h, w, 4), got {pixels.shape}")
    height, width, channels = pixels.shape
    rows = np.concatenate([np.zeros((height, 1), dtype=np.uint8), pixels.reshape(height, -1)], axis=1)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    color_type = 2 if channels == 3 else 6
    header = struct.pack(">IIBBBBB", width, height, 8, color_type, 0, 0, 0)
    with open(path, "wb") as file:
        file.write(b"\x89PNG\r\n\x1a\n")
        file.write(chunk(b"IHDR", header))
        file.write(chunk(b"IDAT", zlib.compress(rows.tobytes(), 6)))
        file.write(chunk(b"IEND", b""))
