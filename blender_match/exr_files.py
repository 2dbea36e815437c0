"""OpenEXR files in numpy and zlib: photos may come as EXR and the game export writes EXR maps,
without making an EXR library a dependency.

Only what those jobs need: single-part scanline images, compression NONE, ZIPS or ZIP, pixel
types HALF, FLOAT and UINT. Tiled, multi-part and deep files, subsampled channels and the other
compressions (RLE, PIZ, PXR24, B44, DWA...) raise ``ExrError``, as does any damaged file: never
a struct, zlib or index error. Arrays are (H, W, C) float32; pixels are those of the data window.
"""
from __future__ import annotations

import mmap
import struct
import zlib
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import BlenderMatchError
from .safe_files import write_atomic

MAGIC = b"\x76\x2f\x31\x01"
_VERSION = 2
_TILED, _DEEP, _MULTIPART = 0x200, 0x800, 0x1000
_COMPRESSIONS = ("NONE", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB")
_LINES_PER_CHUNK = {"NONE": 1, "ZIPS": 1, "ZIP": 16}
_PIXEL_TYPES = ("UINT", "HALF", "FLOAT")
_DTYPES = {"UINT": "<u4", "HALF": "<f2", "FLOAT": "<f4"}
_HALF_MAX = 65504.0
_MAX_NAME = 256  # attribute and channel names are at most 255 bytes (long-name files)
_ZIP_LEVEL = 4  # EXR maps are large: a fast level costs little size
_MAX_ZIP_RATIO = 1032  # deflate's largest ratio: bounds the pixels a file can hold
_WRITE_LAYOUTS = {1: "Y", 3: "RGB", 4: "RGBA"}


class ExrError(BlenderMatchError):
    """An OpenEXR file that cannot be read or an array that cannot be written (names the file
    and the problem)."""


@dataclass(frozen=True)
class ExrHeader:
    """What ``read_exr`` needs to know, read without decoding any pixels."""

    width: int
    height: int
    channels: dict[str, str]  # name -> pixel type ("HALF", "FLOAT", "UINT"), in file order
    compression: str
    layout: str  # the channels read_exr returns: "RGB" or "RGBA" for colour, "Y" or "YA" gray
    data_window: tuple[int, int, int, int]  # x_min, y_min, x_max, y_max
    table_offset: int  # where the chunk offset table starts


class _Cursor:
    """Bounds-checked reads from the mapped file, so that a short or damaged file is an
    ``ExrError`` and never an IndexError or struct.error."""

    def __init__(self, buf, pos: int = 0):
        self.buf, self.pos = buf, pos

    def take(self, n: int) -> bytes:
        if n < 0 or self.pos + n > len(self.buf):
            raise ExrError("the file is truncated or corrupt")
        self.pos += n
        return self.buf[self.pos - n:self.pos]

    def unpack(self, fmt: str) -> tuple:
        return struct.unpack(fmt, self.take(struct.calcsize(fmt)))

    def name(self) -> str:
        """A NUL-terminated name; the empty name ends a list."""
        end = self.buf.find(b"\0", self.pos, self.pos + _MAX_NAME)
        if end < 0:
            raise ExrError("the header is truncated or corrupt")
        text = self.take(end - self.pos).decode("utf-8", "replace")
        self.pos += 1
        return text


def _parse_header(buf) -> ExrHeader:
    cur = _Cursor(buf)
    if cur.take(4) != MAGIC:
        raise ExrError("not an OpenEXR file")
    (version,) = cur.unpack("<I")
    if version & 0xFF != _VERSION:
        raise ExrError(f"OpenEXR file version {version & 0xFF} is not supported")
    for flag, what in ((_MULTIPART, "multi-part"), (_DEEP, "deep"), (_TILED, "tiled")):
        if version & flag:
            raise ExrError(f"{what} OpenEXR files are not supported (save it as a single-part "
                           "scanline image)")
    attributes = {}
    while name := cur.name():
        kind = cur.name()
        (size,) = cur.unpack("<i")
        attributes[name] = (kind, cur.take(size))

    def value(name: str, kind: str) -> bytes:
        found = attributes.get(name)
        if found is None or found[0] != kind:
            raise ExrError(f"the header has no {kind} attribute {name!r}")
        return found[1]

    (code,) = _Cursor(value("compression", "compression")).unpack("<B")
    compression = _COMPRESSIONS[code] if code < len(_COMPRESSIONS) else f"number {code}"
    if compression not in _LINES_PER_CHUNK:
        raise ExrError(f"OpenEXR compression {compression} is not supported (save it as ZIP or "
                       "uncompressed)")
    x_min, y_min, x_max, y_max = _Cursor(value("dataWindow", "box2i")).unpack("<4i")
    if x_max < x_min or y_max < y_min:
        raise ExrError(f"the data window {(x_min, y_min, x_max, y_max)} is empty")
    channels = _parse_channels(value("channels", "chlist"))
    return ExrHeader(width=x_max - x_min + 1, height=y_max - y_min + 1, channels=channels,
                     compression=compression, layout=_layout(channels),
                     data_window=(x_min, y_min, x_max, y_max), table_offset=cur.pos)


def _parse_channels(data: bytes) -> dict[str, str]:
    cur, channels = _Cursor(data), {}
    while name := cur.name():
        pixel_type, _linear, x_sampling, y_sampling = cur.unpack("<iB3xii")
        if not 0 <= pixel_type < len(_PIXEL_TYPES):
            raise ExrError(f"channel {name!r} has an unknown pixel type {pixel_type}")
        if (x_sampling, y_sampling) != (1, 1):
            raise ExrError(f"subsampled channel {name!r} is not supported")
        channels[name] = _PIXEL_TYPES[pixel_type]
    return channels


def _layout(channels: dict[str, str]) -> str:
    """Colour when any of R, G, B is present (a missing one reads as 0), else luminance Y."""
    if channels.keys() & {"R", "G", "B"}:
        colour = "RGB"
    elif "Y" in channels:
        colour = "Y"
    else:
        raise ExrError(f"no R, G, B or Y channel (channels: {', '.join(channels) or 'none'})")
    return colour + ("A" if "A" in channels else "")


@contextmanager
def _mapped(path: Path):
    """The file mapped read-only; any ExrError raised inside is prefixed with the file name."""
    try:
        with open(path, "rb") as f:
            if f.seek(0, 2) < len(MAGIC) + 4:
                raise ExrError("not an OpenEXR file (too short)")
            with mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as buf:
                yield buf
    except ExrError as exc:
        raise ExrError(f"{path}: {exc}") from None
    except FileNotFoundError:
        raise ExrError(f"{path}: no such file") from None
    except OSError as exc:
        raise ExrError(f"{path}: cannot read the file ({exc.strerror or exc})") from None


def read_exr_header(path: Path) -> ExrHeader:
    """The header of an OpenEXR file (size, channels, compression) without its pixels."""
    with _mapped(Path(path)) as buf:
        return _parse_header(buf)


def read_exr(path: Path) -> np.ndarray:
    """The pixels of an OpenEXR file as (H, W, C) float32, channels as ``header.layout``:
    R, G, B[, A] for colour or Y[, A] for luminance; other channels are ignored."""
    with _mapped(Path(path)) as buf:
        header = _parse_header(buf)
        planes = _read_planes(buf, header)
    out = np.zeros((header.height, header.width, len(header.layout)), np.float32)
    for i, name in enumerate(header.layout):
        if name in planes:
            out[..., i] = planes[name]
    return out


def _read_planes(buf, header: ExrHeader) -> dict[str, np.ndarray]:
    """Every channel as an (H, W) array, from the chunks the offset table points to (in any
    order, so increasing, decreasing and random line orders all read the same)."""
    row = np.dtype([(name, _DTYPES[kind], (header.width,)) for name, kind in header.channels.items()])
    if row.itemsize * header.height > _MAX_ZIP_RATIO * len(buf):
        raise ExrError(f"the header claims {header.width}x{header.height} pixels, more than the "
                       "file can hold (the file is corrupt)")
    lines = _LINES_PER_CHUNK[header.compression]
    count = -(-header.height // lines)
    offsets = np.frombuffer(_Cursor(buf, header.table_offset).take(8 * count), "<u8")
    data = bytearray(row.itemsize * header.height)
    seen = set()
    for offset in offsets.tolist():
        cur = _Cursor(buf, offset)
        y, size = cur.unpack("<ii")
        first = y - header.data_window[1]
        if not 0 <= first < header.height or first % lines or first in seen:
            raise ExrError(f"a chunk has an invalid scanline {y} (the file is corrupt)")
        seen.add(first)
        n = min(lines, header.height - first)
        data[first * row.itemsize:(first + n) * row.itemsize] = _unpack_chunk(
            cur.take(size), n * row.itemsize, header.compression)
    rows = np.frombuffer(data, row)
    return {name: rows[name] for name in header.channels}


def _unpack_chunk(packed: bytes, size: int, compression: str) -> bytes:
    """A chunk's raw bytes. ZIP(S) chunks that would not shrink are stored raw, as in OpenEXR."""
    if len(packed) == size:
        return packed
    if compression == "NONE" or len(packed) > size:
        raise ExrError("a chunk has the wrong size (the file is corrupt)")
    try:
        inflated = zlib.decompressobj().decompress(packed, size)
    except zlib.error:
        raise ExrError("a ZIP chunk is corrupt") from None
    if len(inflated) != size:
        raise ExrError("a ZIP chunk is corrupt (wrong size)")
    # Undo the predictor (each byte stored as the difference to the previous one, + 128) and
    # the interleave (first the even bytes, then the odd ones).
    diffs = np.frombuffer(inflated, np.uint8).copy()
    diffs[1:] -= 128
    split = np.cumsum(diffs, dtype=np.uint8)
    raw = np.empty(size, np.uint8)
    half = (size + 1) // 2
    raw[0::2], raw[1::2] = split[:half], split[half:]
    return raw.tobytes()


def _zip(raw: bytes) -> bytes:
    """The inverse of ``_unpack_chunk``'s ZIP decoding, raw when compression does not shrink it."""
    data = np.frombuffer(raw, np.uint8)
    split = np.concatenate([data[0::2], data[1::2]])
    split[1:] = split[1:] - split[:-1] + 128
    packed = zlib.compress(split.tobytes(), _ZIP_LEVEL)
    return packed if len(packed) < len(raw) else raw


def _attribute(name: str, kind: str, value: bytes) -> bytes:
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def encode_exr(array, half: bool = True, compression: str = "zip") -> bytes:
    """OpenEXR bytes of an (H, W, C) float image: C = 1 (channel Y), 3 (RGB) or 4 (RGBA), as
    HALF (values beyond +-65504 clamped, not infinite) or FLOAT; compression "zip" (16
    scanlines a chunk), "zips" (one) or "none"."""
    pixels = np.asarray(array, dtype=np.float32)
    if pixels.ndim != 3 or pixels.shape[2] not in _WRITE_LAYOUTS or 0 in pixels.shape:
        raise ExrError(f"cannot write an array of shape {pixels.shape} as OpenEXR; expected "
                       "(height, width, 1, 3 or 4 channels)")
    name = str(compression).upper()
    if name not in _LINES_PER_CHUNK:
        raise ExrError(f"cannot write OpenEXR compression {compression!r}; use 'zip', 'zips' "
                       "or 'none'")
    height, width, count = pixels.shape
    layout = _WRITE_LAYOUTS[count]
    order = sorted(range(count), key=lambda i: layout[i])  # EXR wants channels sorted: A, B, G, R
    pixel_type = "HALF" if half else "FLOAT"
    if half:
        pixels = np.clip(pixels, -_HALF_MAX, _HALF_MAX)
    rows = np.ascontiguousarray(pixels[:, :, order].transpose(0, 2, 1), dtype=_DTYPES[pixel_type])
    chlist = b"".join(layout[i].encode() + b"\0" + struct.pack("<iB3xii", _PIXEL_TYPES.index(
        pixel_type), 0, 1, 1) for i in order) + b"\0"
    window = struct.pack("<4i", 0, 0, width - 1, height - 1)
    header = (MAGIC + struct.pack("<I", _VERSION)
              + _attribute("channels", "chlist", chlist)
              + _attribute("compression", "compression", bytes([_COMPRESSIONS.index(name)]))
              + _attribute("dataWindow", "box2i", window)
              + _attribute("displayWindow", "box2i", window)
              + _attribute("lineOrder", "lineOrder", b"\0")
              + _attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
              + _attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0.0, 0.0))
              + _attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    lines = _LINES_PER_CHUNK[name]
    chunks = []
    for y in range(0, height, lines):
        raw = rows[y:y + lines].tobytes()
        packed = raw if name == "NONE" else _zip(raw)
        chunks.append(struct.pack("<ii", y, len(packed)) + packed)
    starts = len(header) + 8 * len(chunks) + np.cumsum([0] + [len(c) for c in chunks[:-1]])
    return header + starts.astype("<u8").tobytes() + b"".join(chunks)


def write_exr(path: Path, array, half: bool = True, overwrite: bool = False,
              compression: str = "zip"):
    """Encode and write an OpenEXR file atomically (see ``encode_exr``)."""
    write_atomic(Path(path), encode_exr(array, half, compression), overwrite=overwrite)
