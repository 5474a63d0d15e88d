"""Curvature colours, the zebra matcap and the PNG writer (the add-on's bpy-free display module)."""

import importlib.util
import pathlib
import struct
import zlib

import numpy as np
import pytest

_DISPLAY_PY = pathlib.Path(__file__).resolve().parents[1] / "addon" / "geometric_fairing" / "display.py"
_spec = importlib.util.spec_from_file_location("geofair_display", _DISPLAY_PY)
display = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(display)


def read_png(path):
    """Decode an 8-bit RGB/RGBA PNG written with filter 0 (what write_png writes)."""
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    position, chunks = 8, {}
    while position < len(data):
        (length,) = struct.unpack(">I", data[position : position + 4])
        kind = data[position + 4 : position + 8]
        body = data[position + 8 : position + 8 + length]
        (crc,) = struct.unpack(">I", data[position + 8 + length : position + 12 + length])
        assert crc == zlib.crc32(kind + body) & 0xFFFFFFFF
        chunks[kind] = chunks.get(kind, b"") + body
        position += 12 + length
    width, height, depth, color_type = struct.unpack(">IIBB", chunks[b"IHDR"][:10])
    channels = {2: 3, 6: 4}[color_type]
    rows = np.frombuffer(zlib.decompress(chunks[b"IDAT"]), dtype=np.uint8).reshape(height, 1 + width * channels)
    assert depth == 8 and np.all(rows[:, 0] == 0)
    return rows[:, 1:].reshape(height, width, channels)


def test_curvature_colors_are_symmetric_around_zero():
    h = np.array([-2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0, np.nan])
    colors, limit = display.curvature_colors(h, limit=1.0)
    assert limit == 1.0 and colors.dtype == np.float32 and colors.shape == (8, 4)
    np.testing.assert_array_equal(colors[:, 3], 1.0)
    np.testing.assert_allclose(colors[3, :3], 1.0)  # H = 0 is white
    np.testing.assert_allclose(colors[7], colors[3])  # NaN drawn as 0
    np.testing.assert_allclose(colors[0], colors[1])  # clamped beyond the limit
    np.testing.assert_allclose(colors[1, :3], display.srgb_to_linear(display.NEGATIVE_SRGB), rtol=1e-6)
    np.testing.assert_allclose(colors[5, :3], display.srgb_to_linear(display.POSITIVE_SRGB), rtol=1e-6)
    # Same distance from white at ±H: the sRGB offset is |H|/limit times the end colour's.
    srgb_offset = lambda i, end: (np.asarray(display.ZERO_SRGB) - end) * abs(h[i])  # noqa: E731
    for i, j in ((2, 4), (1, 5)):
        np.testing.assert_allclose(
            colors[i, :3], display.srgb_to_linear(display.ZERO_SRGB - srgb_offset(i, display.NEGATIVE_SRGB)), rtol=1e-6
        )
        np.testing.assert_allclose(
            colors[j, :3], display.srgb_to_linear(display.ZERO_SRGB - srgb_offset(j, display.POSITIVE_SRGB)), rtol=1e-6
        )
    assert colors[5, 0] > colors[5, 2] and colors[1, 2] > colors[1, 0]  # red positive, blue negative


def test_symmetric_limit_ignores_outliers_and_signs():
    h = np.concatenate([np.linspace(-1, 1, 1001), [1e6, np.inf, np.nan]])
    limit = display.symmetric_limit(h)  # the 90th percentile of |H|: 0.9 here, the spike ignored
    assert 0.89 < limit < 0.91
    assert display.symmetric_limit(-h) == pytest.approx(limit)
    assert display.symmetric_limit(np.zeros(5)) == 1.0


def test_zebra_matcap():
    image = display.zebra_matcap(size=64, stripes=6)
    assert image.shape == (64, 64, 3) and image.dtype == np.uint8
    np.testing.assert_array_equal(image[:, :, 0], image[:, :, 1])  # grey
    np.testing.assert_array_equal(image, image[:, ::-1])  # horizontal bands: mirror symmetric left-right
    # Next to the middle row the normal tilts sideways only: the reflected ray stays near the horizon, in one band
    # (elevation 0 is a band edge: the two rows at the middle lie on either side of it).
    for row in (31, 32):
        assert np.ptp(image[row, 8:56, 0].astype(int)) <= 1
    assert image[31, 32, 0] != image[32, 32, 0]
    # Bands alternate dark and light going up: count the transitions along the middle column near the centre.
    column = image[:32, 32, 0] > 127
    assert 2 <= np.count_nonzero(column[1:] != column[:-1]) <= 2 * 6 * 2


def test_write_png_round_trip(tmp_path):
    rng = np.random.default_rng(1)
    for channels in (3, 4):
        pixels = rng.integers(0, 256, size=(7, 5, channels), dtype=np.uint8)
        path = tmp_path / f"image{channels}.png"
        display.write_png(path, pixels)
        np.testing.assert_array_equal(read_png(path), pixels)
    with pytest.raises(ValueError, match="must be"):
        display.write_png(tmp_path / "bad.png", np.zeros((4, 4), dtype=np.uint8))
