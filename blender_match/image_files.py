"""Writing image files: PNG 8/16-bit, written atomically, never over an existing file unless asked
(images are read by the engine's ``diffmat.functional.inputs.load_image``).

Tensors here are (1, C, H, W) in [0, 1] with C in (1, 3, 4). PNG is encoded here (zlib, numpy) so
that 16-bit colour PNGs, which Pillow cannot write, work without another dependency.

Compression: each row is stored with the PNG filter (None, Sub, Up or Paeth) whose residuals have
the smallest sum of absolute values as signed bytes, the heuristic libpng and Pillow use, and the
rows are deflated with zlib's run-length strategy. On filtered maps, whose residuals are mostly
small and, at 16 bits, whose low bytes are close to noise, run-length matching gives files about
as small as zlib's default string search in a fraction of its time (figures: docs/benchmarks.md).
The Average filter is left out: it was almost never the best on library maps. Rows are filtered
in bands of ``BAND_ROWS`` so that temporaries stay small.
"""
from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np
import torch

from .errors import BlenderMatchError
from .safe_files import write_atomic


class ImageFileError(BlenderMatchError):
    """An image that cannot be written (names the problem)."""


BAND_ROWS = 256
_NONE, _SUB, _UP, _PAETH = 0, 1, 2, 4  # PNG filter types (the byte that starts each stored row)
_FILTER_TYPES = np.array([_NONE, _SUB, _UP, _PAETH], np.uint8)


def _chunk(tag: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF)


def _filter_candidates(rows: np.ndarray, above: np.ndarray, bpp: int) -> np.ndarray:
    """(4, R, S) uint8: ``rows`` (R, S) bytes filtered with None, Sub, Up and Paeth; ``above`` is
    the row before the band (zeros for the first), ``bpp`` the bytes per pixel. Byte arithmetic
    wraps modulo 256, as PNG defines it."""
    up = np.empty_like(rows)
    up[0], up[1:] = above, rows[:-1]
    left = np.zeros_like(rows)
    left[:, bpp:] = rows[:, :-bpp]
    up_left = np.zeros_like(rows)
    up_left[:, bpp:] = up[:, :-bpp]
    a, b, c = (x.astype(np.int16) for x in (left, up, up_left))
    pa, pb, pc = np.abs(b - c), np.abs(a - c), np.abs(a + b - 2 * c)
    paeth = np.where((pa <= pb) & (pa <= pc), left, np.where(pb <= pc, up, up_left))
    return np.stack([rows, rows - left, rows - up, rows - paeth])


def _filtered_band(rows: np.ndarray, above: np.ndarray, bpp: int) -> np.ndarray:
    """(R, 1 + S) uint8: each row of ``rows`` as PNG stores it, its filter type then its bytes
    filtered by the type whose residuals sum to the least in absolute value (as signed bytes)."""
    candidates = _filter_candidates(rows, above, bpp)
    cost = np.abs(candidates.view(np.int8).astype(np.int16)).sum(axis=2)
    best = cost.argmin(axis=0)
    return np.concatenate([_FILTER_TYPES[best][:, None], candidates[best, np.arange(len(rows))]], axis=1)


def _deflated_scanlines(rows: np.ndarray, bpp: int) -> bytes:
    """The IDAT data of (H, S) uint8 rows: filtered per row, deflated with run-length matching."""
    compressor = zlib.compressobj(strategy=zlib.Z_RLE)
    parts, above = [], np.zeros(rows.shape[1], np.uint8)
    for top in range(0, len(rows), BAND_ROWS):
        band = rows[top:top + BAND_ROWS]
        parts.append(compressor.compress(_filtered_band(band, above, bpp).tobytes()))
        above = band[-1]
    parts.append(compressor.flush())
    return b"".join(parts)


def encode_png(image: torch.Tensor, bits: int = 8) -> bytes:
    """PNG bytes of a (1, C, H, W) or (C, H, W) image in [0, 1]; C = 1 gray, 3 RGB, 4 RGBA."""
    if bits not in (8, 16):
        raise ImageFileError(f"PNG bit depth must be 8 or 16, not {bits}")
    img = image.detach().float().cpu()
    img = img[0] if img.dim() == 4 else img
    channels, height, width = img.shape
    color_type = {1: 0, 3: 2, 4: 6}.get(channels)
    if color_type is None:
        raise ImageFileError(f"cannot write a {channels}-channel image as PNG")
    scale = 255 if bits == 8 else 65535
    arr = np.rint(img.clamp(0, 1).numpy() * scale).astype(">u2" if bits == 16 else np.uint8)
    rows = np.ascontiguousarray(arr.transpose(1, 2, 0)).reshape(height, -1).view(np.uint8)
    header = struct.pack(">IIBBBBB", width, height, bits, color_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header)
            + _chunk(b"IDAT", _deflated_scanlines(rows, channels * bits // 8)) + _chunk(b"IEND", b""))


def write_png(path: Path, image: torch.Tensor, bits: int = 8, overwrite: bool = False):
    """Encode and write a PNG atomically."""
    write_atomic(Path(path), encode_png(image, bits), overwrite=overwrite)
