"""Reading the photo the user wants to match, as the square sRGB image the fit compares renders
with: (1, 3, size, size) float32 in [0, 1].

Any image Pillow reads (JPEG, PNG, TIFF, WebP, BMP...) or an OpenEXR file. The size is checked
from the header before any pixel is decoded, so that a file claiming billions of pixels is
refused instead of allocated. The photo is turned upright by its EXIF orientation, alpha is
dropped (not composited: the colour under it is the material), gray is repeated into RGB, and
16-bit and float pixels stay at full precision from the file to the resize, never through 8
bits. Pillow holds colour at 8 bits, so 16-bit RGB(A) PNGs and TIFFs are decoded twice, for the
high and the low byte of each sample (see ``_deep_colour``). 16-bit gray+alpha PNGs still come
as 8 bits (the downscale to ``size`` averages that away); float colour TIFFs, which Pillow cannot
read, are refused: save those as EXR.
"""
from __future__ import annotations

import sys
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F
from PIL import ExifTags, Image, ImageFile, UnidentifiedImageError

from .diffmat.render import linear_to_srgb
from .errors import BlenderMatchError
from .exr_files import MAGIC as EXR_MAGIC
from .exr_files import ExrError, read_exr, read_exr_header

MIN_SIDE = 128
MAX_PIXELS = 100_000_000

# EXIF orientation -> what turns the stored (H, W, C) pixels upright, as Pillow's exif_transpose
# does, but on arrays: 16-bit colour only exists as an array, and views cost no copy.
_UPRIGHT = {
    2: lambda a: a[:, ::-1],
    3: lambda a: a[::-1, ::-1],
    4: lambda a: a[::-1],
    5: lambda a: a.transpose(1, 0, 2),
    6: lambda a: np.rot90(a, -1),
    7: lambda a: np.rot90(a, 2).transpose(1, 0, 2),
    8: lambda a: np.rot90(a, 1),
}
_SIDEWAYS = (5, 6, 7, 8)
# 16-bit colour rawmodes (Pillow's names for how samples are packed) and the byte-order letter
# that makes Pillow's unpacker keep each sample's low byte instead of its high byte.
_DEEP_RAWMODES = ("RGB;16", "RGBA;16", "RGBX;16")
_OTHER_BYTE = {"B": "L", "L": "B", "N": "L" if sys.byteorder == "big" else "B"}


class PhotoError(BlenderMatchError):
    """A photo that cannot be used (names the file and the problem)."""


def photo_info(path: Path) -> dict:
    """Width and height (upright, as the photo is shown), format and mode of a photo, read from
    its header without decoding the pixels; for reports."""
    path = _existing_file(path)
    if _is_exr(path):
        with _exr_errors():
            header = read_exr_header(path)
        return {"width": header.width, "height": header.height, "format": "EXR",
                "mode": header.layout}
    with _opened(path) as img:
        width, height = img.size
        if _orientation(img) in _SIDEWAYS:
            width, height = height, width
        return {"width": width, "height": height, "format": img.format, "mode": img.mode}


def load_photo(path: Path, size: int = 512) -> torch.Tensor:
    """The photo as a (1, 3, size, size) float32 sRGB tensor in [0, 1]: upright, the centred
    square of its shorter side, resized with antialiasing. EXR files hold linear light: they are
    resized linear, then encoded as sRGB (values above 1 clamped); float TIFFs are taken as
    they are."""
    path = Path(path)
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 1:
        raise PhotoError(f"{path}: the photo size must be a positive whole number of pixels, "
                         f"not {size!r}")
    path = _existing_file(path)
    linear = _is_exr(path)
    if linear:
        with _exr_errors():
            header = read_exr_header(path)
            _check_dimensions(path, header.width, header.height)
            pixels = read_exr(path)
    else:
        with _opened(path) as img:
            _check_dimensions(path, *img.size)
            pixels = _decode(path, img)
    square = _to_tensor(_centre_square(pixels))
    out = F.interpolate(square, size=(int(size), int(size)), mode="bilinear", antialias=True,
                        align_corners=False)
    if linear:
        out = linear_to_srgb(out)
    return out.clamp(0.0, 1.0).expand(-1, 3, -1, -1).contiguous()


def _existing_file(path: Path) -> Path:
    path = Path(path)
    if not path.exists():
        raise PhotoError(f"{path}: no such file")
    if not path.is_file():
        raise PhotoError(f"{path}: not a file")
    return path


def _is_exr(path: Path) -> bool:
    """By content, not name: EXR files start with a magic number Pillow does not know."""
    try:
        with open(path, "rb") as f:
            return f.read(len(EXR_MAGIC)) == EXR_MAGIC
    except OSError as exc:
        raise PhotoError(f"{path}: cannot read the file ({exc.strerror or exc})") from None


@contextmanager
def _exr_errors():
    """ExrError as PhotoError (its message already names the file)."""
    try:
        yield
    except ExrError as exc:
        raise PhotoError(str(exc)) from None


def _check_dimensions(path: Path, width: int, height: int):
    if width * height > MAX_PIXELS:
        raise PhotoError(f"{path}: {width}x{height} pixels is more than the "
                         f"{MAX_PIXELS // 1_000_000} megapixels a photo may have; scale it down")
    if min(width, height) < MIN_SIDE:
        raise PhotoError(f"{path}: {width}x{height} pixels is too small; the shorter side must "
                         f"be at least {MIN_SIDE} pixels")


def _one_line(exc: Exception) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


@contextmanager
def _opened(path: Path) -> Iterator[ImageFile.ImageFile]:
    """The image opened by Pillow (lazily: header only). Pillow's own decompression-bomb limit
    (a global the host application may have changed) warns above ~89 and fails above ~179
    megapixels; its warning is silenced, its failure becomes a PhotoError and MAX_PIXELS is
    checked by the caller, so the limit is ours whatever that global says."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", Image.DecompressionBombWarning)
        try:
            img = Image.open(path)
        except Image.DecompressionBombError:
            raise PhotoError(f"{path}: the image has more than the {MAX_PIXELS // 1_000_000} "
                             "megapixels a photo may have; scale it down") from None
        except UnidentifiedImageError:
            raise PhotoError(f"{path}: not an image file that can be read (unknown or damaged "
                             "format)") from None
        except Exception as exc:  # noqa: BLE001 - Pillow's format plugins raise many types for bad headers
            raise PhotoError(f"{path}: cannot read the image ({_one_line(exc)})") from None
        with img:
            yield img


def _decode(path: Path, img: ImageFile.ImageFile) -> np.ndarray:
    """The pixels, upright, as an (H, W, C) array: uint8, uint16 or float32."""
    try:
        pixels = _deep_colour(path, img) if _is_deep_colour(img) else _pixels(img)
    except Exception as exc:  # noqa: BLE001 - truncated or damaged data: Pillow's decoders raise many types
        raise PhotoError(f"{path}: cannot read the image ({_one_line(exc)})") from None
    return _UPRIGHT.get(_orientation(img), np.asarray)(pixels)


def _tile_args(tile) -> tuple:
    """A tile's decoder arguments (tiles are codec, extents, offset, args); the first is the
    rawmode, how its samples are packed."""
    return tile[3] if isinstance(tile[3], tuple) else (tile[3],)


def _is_deep_colour(img: ImageFile.ImageFile) -> bool:
    rawmodes = [next(iter(_tile_args(t)), None) for t in img.tile]
    return bool(rawmodes) and all(isinstance(r, str) and r[:-1] in _DEEP_RAWMODES for r in rawmodes)


def _deep_colour(path: Path, img: ImageFile.ImageFile) -> np.ndarray:
    """16-bit colour at full precision. Pillow unpacks each 16-bit sample to its high byte;
    decoding the same data again with the other byte order in the rawmode unpacks the low
    bytes, and the two make the samples exactly."""
    with Image.open(path) as low:
        low.tile = [_low_byte_tile(t) for t in low.tile]
        low_bytes = np.asarray(low.convert("RGB"), dtype=np.uint16)
    return np.asarray(img.convert("RGB"), dtype=np.uint16) << 8 | low_bytes


def _low_byte_tile(tile):
    rawmode, *rest = _tile_args(tile)
    return tile._replace(args=(rawmode[:-1] + _OTHER_BYTE[rawmode[-1]], *rest))


def _pixels(img: Image.Image) -> np.ndarray:
    mode = img.mode
    if mode.startswith("I;16"):
        return np.asarray(img).astype(np.uint16)[..., None]  # native byte order
    if mode == "I":  # 32-bit integers, in practice 16-bit data
        return np.clip(np.asarray(img), 0, 65535).astype(np.uint16)[..., None]
    if mode == "F":
        return np.asarray(img, dtype=np.float32)[..., None]
    if mode in ("1", "L", "LA", "La"):
        return np.asarray(img.convert("L"))[..., None]
    return np.asarray(img.convert("RGB"))  # colour, palette, CMYK...: alpha dropped


def _orientation(img: Image.Image) -> int:
    """The EXIF orientation, 1 (upright) when absent or unreadable. A PNG's EXIF is only looked
    for before its pixel data: Pillow would decode the whole image to look after it."""
    if img.format == "PNG" and "exif" not in img.info:
        return 1
    try:
        return int(img.getexif().get(ExifTags.Base.Orientation, 1))
    except Exception:  # noqa: BLE001 - damaged EXIF must not make the photo unreadable
        return 1


def _centre_square(pixels: np.ndarray) -> np.ndarray:
    height, width = pixels.shape[:2]
    side = min(height, width)
    top, left = (height - side) // 2, (width - side) // 2
    return pixels[top:top + side, left:left + side]


def _to_tensor(pixels: np.ndarray) -> torch.Tensor:
    """(1, C, H, W) float32 in [0, 1], C = 1 (gray) or 3 (colour): integers scaled by their
    maximum, float clamped (NaN as 0)."""
    pixels = pixels[..., :1] if pixels.shape[2] < 3 else pixels[..., :3]
    scale = np.iinfo(pixels.dtype).max if pixels.dtype.kind in "ui" else 1.0
    tensor = torch.from_numpy(np.array(pixels, dtype=np.float32, order="C")).permute(2, 0, 1)[None]
    return tensor.div_(scale).nan_to_num_(0.0).clamp_(0.0, 1.0)
