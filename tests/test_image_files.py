"""PNG writing (``image_files``): filtered, deflated rows read back bit-exactly, by a decoder
written from the PNG specification here and by Pillow, at 8 and 16 bits, gray, RGB and RGBA."""
from __future__ import annotations

import io
import struct
import zlib

import numpy as np
import pytest
import torch
from PIL import Image

from blender_match.image_files import ImageFileError, encode_png, write_png

SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _paeth(a: int, b: int, c: int) -> int:
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else b if pb <= pc else c


def _decode(data: bytes) -> tuple[np.ndarray, list[int]]:
    """The samples (H, W, C) of a non-interlaced PNG and each row's filter type, decoded one
    byte at a time as the PNG specification describes (independent of the writer's numpy)."""
    assert data[:8] == SIGNATURE
    pos, idat = 8, b""
    while pos < len(data):
        length, tag = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        assert struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])[0] == zlib.crc32(tag + body)
        if tag == b"IHDR":
            width, height, bits, color_type, *_ = struct.unpack(">IIBBBBB", body)
        elif tag == b"IDAT":
            idat += body
        pos += 12 + length
    channels = {0: 1, 2: 3, 6: 4}[color_type]
    bpp, raw = channels * bits // 8, zlib.decompress(idat)
    stride = width * bpp
    previous, samples, types = bytearray(stride), bytearray(), []
    for y in range(height):
        line = raw[y * (stride + 1):(y + 1) * (stride + 1)]
        types.append(line[0])
        row = bytearray(stride)
        for i in range(stride):
            a, b = row[i - bpp] if i >= bpp else 0, previous[i]
            c = previous[i - bpp] if i >= bpp else 0
            prediction = (0, a, b, (a + b) // 2, _paeth(a, b, c))[line[0]]
            row[i] = (line[1 + i] + prediction) & 0xFF
        samples += row
        previous = row
    dtype = ">u2" if bits == 16 else np.uint8
    return np.frombuffer(bytes(samples), dtype).reshape(height, width, channels), types


def _test_samples(channels: int, bits: int, height: int = 23, width: int = 19) -> np.ndarray:
    """(H, W, C) integer samples with rows that each filter suits: noise, a plane (Paeth), rows
    repeating the one above (Up), ramps along x with jumps between rows (Sub), zeros (None)."""
    top = (1 << bits) - 1
    rng = np.random.default_rng(bits * 10 + channels)
    y, x = np.mgrid[0:height, 0:width]
    plane = (x * 7 + y * 3)[..., None] * np.arange(1, channels + 1)
    samples = rng.integers(0, top + 1, (height, width, channels))
    samples[5:10] = plane[5:10]
    samples[10:14] = samples[9]
    samples[14:18] = (rng.integers(0, top // 2, (4, 1, channels)) + 5 * x[14:18, :, None])
    samples[18:] = 0
    return samples.astype(np.uint16 if bits == 16 else np.uint8)


def _as_tensor(samples: np.ndarray, bits: int) -> torch.Tensor:
    return torch.from_numpy(samples.astype(np.float32) / ((1 << bits) - 1)).permute(2, 0, 1)[None]


@pytest.mark.parametrize("bits", [8, 16])
@pytest.mark.parametrize("channels", [1, 3, 4])
def test_png_reads_back_bit_exactly(bits, channels):
    samples = _test_samples(channels, bits)
    data = encode_png(_as_tensor(samples, bits), bits)
    decoded, types = _decode(data)
    np.testing.assert_array_equal(decoded, samples)
    assert {0, 1, 2, 4} <= set(types)  # every filter the writer uses is exercised
    with Image.open(io.BytesIO(data)) as img:
        pillow = np.asarray(img)
    pillow = pillow.reshape(*samples.shape[:2], -1)
    if bits == 16 and channels > 1:  # Pillow holds colour at 8 bits: the high byte of each sample
        np.testing.assert_array_equal(pillow, samples >> 8)
    else:
        np.testing.assert_array_equal(pillow, samples)


def test_rows_span_several_bands(tmp_path, monkeypatch):
    monkeypatch.setattr("blender_match.image_files.BAND_ROWS", 4)
    samples = _test_samples(3, 16)
    write_png(tmp_path / "banded.png", _as_tensor(samples, 16), bits=16)
    np.testing.assert_array_equal(_decode((tmp_path / "banded.png").read_bytes())[0], samples)


def test_bad_depth_and_channel_count():
    with pytest.raises(ImageFileError, match="bit depth"):
        encode_png(torch.zeros(1, 3, 4, 4), bits=12)
    with pytest.raises(ImageFileError, match="2-channel"):
        encode_png(torch.zeros(1, 2, 4, 4))
