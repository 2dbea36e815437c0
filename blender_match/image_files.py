"""Writing image files: PNG 8/16-bit, written atomically, never over an existing file unless asked
(images are read by the engine's ``diffmat.functional.inputs.load_image``).

Tensors here are (1, C, H, W) in [0, 1] with C in (1, 3, 4). PNG is encoded here (zlib, numpy) so
that 16-bit colour PNGs, which Pillow cannot write, work without another dependency.
"""
from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np
import torch

from .safe_files import write_atomic


class ImageFileError(ValueError):
    """An image that cannot be written (names the problem)."""


def _chunk(tag: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF)


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
    raw = np.concatenate([np.zeros((height, 1), np.uint8), rows], axis=1).tobytes()
    header = struct.pack(">IIBBBBB", width, height, bits, color_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header) + _chunk(b"IDAT", zlib.compress(raw, 6))
            + _chunk(b"IEND", b""))


def write_png(path: Path, image: torch.Tensor, bits: int = 8, overwrite: bool = False):
    """Encode and write a PNG atomically."""
    write_atomic(Path(path), encode_png(image, bits), overwrite=overwrite)
