"""Input nodes: Bitmap (an image file), and the SVG and Text placeholders (Substance's atomic
``bitmap``, ``svg`` and ``text`` nodes).

Bitmap reads a file from disk and resamples it to the context size with a wrap-around filter
(a tent kernel as wide as the scale factor when shrinking, bilinear when enlarging; pixels at one
edge are filtered with those at the opposite edge), so a tiling texture stays tiling.

SVG and Text would need a vector/font rasteriser; they are placeholders that render their
``background`` colour (or pass their ``background`` image input through).
"""
from __future__ import annotations

import os
from collections import OrderedDict

import numpy as np
import torch

from ..errors import DiffMatError
from .common import check_image, check_size, match_channels, param2d

__all__ = ["bitmap", "svg", "text"]

_CACHE: OrderedDict = OrderedDict()
_CACHE_SIZE = 16


def load_image(path: str) -> torch.Tensor:
    """Read an image file as a (1, 4, H, W) float32 RGBA tensor in [0, 1] (16-bit and float
    grayscale files keep their precision). DiffMatError naming the file when it cannot be read."""
    try:  # Pillow is imported when an image is read, not with the engine
        from PIL import Image
    except ImportError:  # pragma: no cover - pillow is a dependency
        raise DiffMatError(f"bitmap: cannot read {path!r}: Pillow is not installed") from None
    if not os.path.isfile(path):
        raise DiffMatError(f"bitmap: image file {path!r} does not exist")
    try:
        with Image.open(path) as img:
            img.load()
            mode = img.mode
            if mode in ("I;16", "I;16B", "I;16L", "I;16N"):
                gray = np.asarray(img, dtype=np.float32) / 65535.0
            elif mode == "I":
                arr = np.asarray(img, dtype=np.float64)
                gray = (arr / (65535.0 if arr.max() > 255 else 255.0)).astype(np.float32)
            elif mode == "F":
                gray = np.asarray(img, dtype=np.float32)
            else:
                gray = None
                rgba = np.asarray(img.convert("RGBA"), dtype=np.float32) / 255.0
    except DiffMatError:
        raise
    except Exception as exc:  # noqa: BLE001 - PIL raises many types for unreadable data
        raise DiffMatError(f"bitmap: cannot read image file {path!r}: {exc}") from None
    if gray is not None:
        g = torch.from_numpy(np.clip(gray, 0.0, 1.0).copy())[None, None]
        return torch.cat([g, g, g, torch.ones_like(g)], dim=1)
    return torch.from_numpy(rgba.copy()).permute(2, 0, 1)[None].contiguous()


def _resample_matrix(n_out: int, n_in: int, dtype=torch.float64) -> torch.Tensor:
    """(n_out, n_in) wrap-around resampling weights: a tent of half-width max(1, n_in / n_out)
    input pixels centred on each output pixel centre, rows normalised."""
    scale = n_in / n_out
    radius = max(1.0, scale)
    centres = (torch.arange(n_out, dtype=dtype) + 0.5) * scale - 0.5          # in input pixel units
    j = torch.arange(n_in, dtype=dtype)
    dist = centres[:, None] - j[None, :]
    dist = torch.remainder(dist + n_in / 2, n_in) - n_in / 2                    # nearest wrapped copy
    wgt = (1 - dist.abs() / radius).clamp_min(0.0)
    return wgt / wgt.sum(1, keepdim=True)


def resample_wrap(img: torch.Tensor, height: int, width: int) -> torch.Tensor:
    """Resize ``img`` (N, C, H, W) to (height, width) with wrap-around filtering (see module doc)."""
    n, c, h, w = img.shape
    if (h, w) == (height, width):
        return img
    ry = _resample_matrix(height, h).to(img.dtype)
    rx = _resample_matrix(width, w).to(img.dtype)
    return torch.einsum("yh,nchw,xw->ncyx", ry, img, rx)


def bitmap(*, bitmapresourcepath: str = "", colorswitch: bool = True, size: int = 512, device=None,
           dtype=torch.float32) -> torch.Tensor:
    """The image file ``bitmapresourcepath`` resized to ``size`` x ``size`` (a non-square image is
    stretched), RGBA, or grayscale (mean of RGB) when ``colorswitch`` is off.

    An empty path is an unset resource and renders opaque black (Substance shows an empty bitmap).
    A path that is missing or unreadable (including an unresolved ``pkg:///`` URL) is a
    DiffMatError naming it. Files are cached by path, modification time and size.
    """
    check_size(size, "bitmap size")
    if not isinstance(bitmapresourcepath, str):
        raise DiffMatError(f"bitmap.bitmapresourcepath: expected a string, got {bitmapresourcepath!r}")
    if bitmapresourcepath == "":
        out = torch.zeros(1, 4, size, size, device=device, dtype=dtype)
        out[:, 3] = 1.0
    else:
        path = os.path.expanduser(bitmapresourcepath)
        try:
            stamp = os.stat(path).st_mtime_ns
        except OSError:
            raise DiffMatError(f"bitmap: image file {bitmapresourcepath!r} does not exist "
                               "or cannot be opened") from None
        key = (path, stamp, size)
        cached = _CACHE.get(key)
        if cached is None:
            cached = resample_wrap(load_image(path).double(), size, size).clamp(0.0, 1.0).float()
            _CACHE[key] = cached
            while len(_CACHE) > _CACHE_SIZE:
                _CACHE.popitem(last=False)
        else:
            _CACHE.move_to_end(key)
        out = cached.to(device=device, dtype=dtype)
    return out if colorswitch else out[:, :3].mean(dim=1, keepdim=True)


def _placeholder(image, node: str, background, colorswitch: bool, size: int, device, dtype) -> torch.Tensor:
    if image is not None:
        return match_channels(check_image(image, f"{node}.background"), 4 if colorswitch else 1)
    check_size(size, f"{node} size")
    color = param2d(background).to(device=device, dtype=dtype)
    if color.shape[1] != 4:
        raise DiffMatError(f"{node}.background: expected 4 components (RGBA), got {color.shape[1]}")
    color = color if colorswitch else color[:, :1]
    return color[:, :, None, None].expand(-1, -1, size, size).clamp(0.0, 1.0)


def svg(image: torch.Tensor | None = None, /, *, vectorresourcepath: str = "", background=(0.0, 0.0, 0.0, 0.0),
        colorswitch: bool = True, size: int = 512, device=None, dtype=torch.float32) -> torch.Tensor:
    """SVG placeholder: no vector rasteriser, so it renders only what lies under the drawing — the
    ``background`` image input when connected, else the ``background`` colour (RGBA; grayscale
    reads its first component when ``colorswitch`` is off). ``vectorresourcepath`` is ignored."""
    if not isinstance(vectorresourcepath, str):
        raise DiffMatError(f"svg.vectorresourcepath: expected a string, got {vectorresourcepath!r}")
    return _placeholder(image, "svg", background, colorswitch, size, device, dtype)


def text(image: torch.Tensor | None = None, /, *, text: str = "", fontdata: str = "", fontsize=0.25,
         frontcolor=(1.0, 1.0, 1.0, 1.0), position=(0.5, 0.5), alignment: int = 1,
         matrix22=(1.0, 0.0, 0.0, 1.0), background=(0.0, 0.0, 0.0, 0.0), colorswitch: bool = True,
         size: int = 512, device=None, dtype=torch.float32) -> torch.Tensor:
    """Text placeholder: no font rasteriser, so it renders only the ``background`` image input when
    connected, else the ``background`` colour; the text and its layout parameters are accepted and
    ignored."""
    if not isinstance(text, str) or not isinstance(fontdata, str):
        raise DiffMatError("text: 'text' and 'fontdata' must be strings")
    return _placeholder(image, "text", background, colorswitch, size, device, dtype)
