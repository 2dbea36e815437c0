"""Reading and writing image files: PNG 8/16-bit written atomically, never over an existing file
unless asked.

Tensors here are (1, C, H, W) in [0, 1] with C in (1, 3, 4). PNG is encoded here (zlib, numpy) so
that 16-bit colour PNGs, which Pillow cannot write, work without another dependency.
"""
from __future__ import annotations

import os
import struct
import tempfile
import zlib
from pathlib import Path

import numpy as np
import torch


class ImageFileError(ValueError):
    """An image file that cannot be read or written (names the file and the problem)."""


def write_atomic(path: Path, data: bytes, overwrite: bool = False):
    """Write ``data`` to ``path`` through a temporary file and a rename, so that a reader never
    sees a half-written file. Refuses to replace an existing file unless ``overwrite``."""
    path = Path(path)
    if path.exists() and not overwrite:
        raise ImageFileError(f"{path}: already exists (pass an overwrite option to replace it)")
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


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


def read_image(path: Path) -> torch.Tensor:
    """A (1, C, H, W) float tensor in [0, 1] from an image file (8/16-bit), C = 1, 3 or 4."""
    from PIL import Image, UnidentifiedImageError

    path = Path(path)
    try:
        with Image.open(path) as im:
            im.load()
            mode = im.mode
            arr = np.asarray(im)
    except FileNotFoundError:
        raise ImageFileError(f"{path}: file not found") from None
    except (UnidentifiedImageError, OSError, SyntaxError) as exc:
        raise ImageFileError(f"{path}: not a readable image ({exc})") from None
    scale = 65535.0 if mode.startswith("I;16") or arr.dtype == np.uint16 else 255.0
    if mode == "I":
        scale = 65535.0 if arr.max() > 255 else 255.0
    t = torch.from_numpy(arr.astype(np.float32) / scale)
    t = t[None] if t.dim() == 2 else t.permute(2, 0, 1)
    return t[None].clamp(0, 1)
