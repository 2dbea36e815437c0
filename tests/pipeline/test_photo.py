"""Reading the photo to match: formats, orientation, precision, the centred crop, and files that
must be refused with a one-line PhotoError naming the file (too small, too many pixels, damaged,
not an image)."""
from __future__ import annotations

import struct
import time
import warnings
import zlib

import numpy as np
import pytest
import torch
from PIL import Image, ImageOps

from blender_match.exr_files import write_exr
from blender_match.image_files import encode_png, write_png
from blender_match.photo import MIN_SIDE, PhotoError, load_photo, photo_info

RNG = np.random.default_rng(3)
RED, GREEN, BLUE = (255, 0, 0), (0, 255, 0), (0, 0, 255)


def _rgb(pixels) -> torch.Tensor:
    return torch.tensor(np.asarray(pixels, np.float32) / 255.0).reshape(1, 3, 1, 1)


def _bands(size, *colours, vertical=True) -> Image.Image:
    """Colour bands side by side (or stacked), widths given with each colour."""
    img = Image.new("RGB", size)
    at = 0
    for extent, colour in colours:
        box = (at, 0, at + extent, size[1]) if vertical else (0, at, size[0], at + extent)
        img.paste(colour, box)
        at += extent
    return img


def _png_claiming(path, width, height):
    """A valid PNG whose header claims width x height pixels over a tiny IDAT."""
    data = bytearray(encode_png(torch.zeros(1, 3, 2, 2)))
    data[16:24] = struct.pack(">II", width, height)
    data[29:33] = struct.pack(">I", zlib.crc32(bytes(data[12:29])))
    path.write_bytes(bytes(data))
    return path


def _tiff16(path, pixels: np.ndarray, deflate: bool):
    """A 16-bit RGB TIFF (one strip, little-endian), which Pillow cannot write."""
    height, width, _ = pixels.shape
    data = pixels.astype("<u2").tobytes()
    data = zlib.compress(data) if deflate else data
    data += b"\0" * (len(data) % 2)
    bits_at, data_at = 8, 14  # after the 8-byte header: BitsPerSample's 3 shorts, then the strip
    tags = [(256, 3, 1, width), (257, 3, 1, height), (258, 3, 3, bits_at),
            (259, 3, 1, 8 if deflate else 1), (262, 3, 1, 2), (273, 4, 1, data_at),
            (277, 3, 1, 3), (278, 3, 1, height), (279, 4, 1, len(data)), (284, 3, 1, 1)]
    ifd = struct.pack("<H", len(tags)) + b"".join(struct.pack("<HHII", *t) for t in tags)
    path.write_bytes(b"II*\0" + struct.pack("<I", data_at + len(data)) + struct.pack("<3H", 16, 16, 16)
                     + data + ifd + b"\0\0\0\0")
    return path


def _refused(path, match, **kwargs) -> str:
    with pytest.raises(PhotoError, match=match) as info:
        load_photo(path, **kwargs)
    message = str(info.value)
    assert message.startswith(f"{path}: ") and "\n" not in message
    return message


def test_exif_orientation_6_turns_a_jpeg_upright(tmp_path):
    path = tmp_path / "sideways.jpg"
    exif = Image.Exif()
    exif[274] = 6  # stored rotated: the viewer turns it 90 degrees clockwise
    _bands((300, 200), (150, RED), (150, BLUE)).save(path, quality=95, exif=exif.tobytes())
    photo = load_photo(path, size=128)
    assert photo.shape == (1, 3, 128, 128) and photo.dtype == torch.float32
    assert torch.allclose(photo[..., :56, :], _rgb(RED).expand(1, 3, 56, 128), atol=0.03)
    assert torch.allclose(photo[..., 72:, :], _rgb(BLUE).expand(1, 3, 56, 128), atol=0.03)
    assert photo_info(path) == {"width": 200, "height": 300, "format": "JPEG", "mode": "RGB"}


@pytest.mark.parametrize("orientation", range(1, 9))
def test_every_orientation_matches_pillows_exif_transpose(tmp_path, orientation):
    stored = Image.fromarray(RNG.integers(0, 256, (136, 170, 3), dtype=np.uint8))
    exif = Image.Exif()
    exif[274] = orientation
    path = tmp_path / "oriented.png"
    stored.save(path, exif=exif.tobytes())
    reference = tmp_path / "upright.png"
    with Image.open(path) as img:
        upright = ImageOps.exif_transpose(img)
    upright.save(reference)
    assert torch.equal(load_photo(path, size=136), load_photo(reference, size=136))
    info = photo_info(path)
    assert (info["width"], info["height"]) == upright.size


def test_16_bit_colour_png_keeps_its_precision(tmp_path):
    steps = (32768 + np.arange(128, dtype=np.float32)) / 65535  # 128 steps within 1/255
    image = torch.stack([torch.tensor(steps).expand(128, 128), torch.tensor(steps[::-1].copy())
                         .expand(128, 128).T, torch.full((128, 128), 16384 / 65535)])[None]
    write_png(tmp_path / "deep.png", image, bits=16)
    photo = load_photo(tmp_path / "deep.png", size=128)
    assert (photo - image).abs().max() < 1e-6
    assert photo[0, 0].unique().numel() == 128 and photo[0, 1].unique().numel() == 128


@pytest.mark.parametrize("deflate", [False, True])  # Pillow's own decoder, then libtiff's
def test_16_bit_colour_tiff_keeps_its_precision(tmp_path, deflate):
    pixels = RNG.integers(0, 65536, (130, 140, 3), dtype=np.uint16)
    path = _tiff16(tmp_path / "deep.tif", pixels, deflate)
    with Image.open(path) as img:
        assert img.mode == "RGB" and img.size == (140, 130)  # 8 bits a sample, as Pillow holds it
    photo = load_photo(path, size=130)[0].permute(1, 2, 0).numpy()
    assert np.abs(photo - pixels[:, 5:135] / 65535).max() < 1e-6


def test_16_bit_rgba_png_drops_alpha_at_full_precision(tmp_path):
    image = torch.rand(1, 4, 128, 128)
    write_png(tmp_path / "deep.png", image, bits=16)
    expected = torch.round(image[:, :3] * 65535) / 65535
    assert (load_photo(tmp_path / "deep.png", size=128) - expected).abs().max() < 1e-6


def test_16_bit_gray_png_and_tiff_keep_their_precision(tmp_path):
    values = (40000 + np.arange(130 * 130).reshape(130, 130) % 200).astype(np.uint16)
    for name in ("gray16.png", "gray16.tif"):
        Image.fromarray(values).save(tmp_path / name)
        assert Image.open(tmp_path / name).mode.startswith("I;16")
        photo = load_photo(tmp_path / name, size=130)
        expected = torch.tensor(values / 65535.0, dtype=torch.float32).expand(1, 3, 130, 130)
        assert (photo - expected).abs().max() < 1e-6, name
        assert photo.unique().numel() == 200


def test_float_tiff(tmp_path):
    values = RNG.random((140, 140)).astype(np.float32)
    values[0, 0], values[0, 1] = 1.5, np.nan
    Image.fromarray(values).save(tmp_path / "float.tif")
    photo = load_photo(tmp_path / "float.tif", size=140)
    expected = np.clip(np.nan_to_num(values), 0, 1)
    assert np.abs(photo[0].numpy() - expected).max() < 1e-6


@pytest.mark.parametrize("name, options, tolerance", [
    ("photo.png", {}, 0), ("photo.bmp", {}, 0), ("photo.tif", {"compression": "tiff_lzw"}, 0),
    ("photo.webp", {"lossless": True}, 0), ("photo.jpg", {"quality": 95}, 0.02)])
def test_common_formats(tmp_path, name, options, tolerance):
    colour = (200, 120, 40)
    Image.new("RGB", (160, 130), colour).save(tmp_path / name, **options)
    photo = load_photo(tmp_path / name, size=32)
    assert (photo - _rgb(colour)).abs().max() <= tolerance + 1e-6


def test_alpha_is_dropped_not_composited(tmp_path):
    Image.new("RGBA", (130, 130), (200, 100, 50, 0)).save(tmp_path / "clear.png")
    Image.new("LA", (130, 130), (77, 0)).save(tmp_path / "clear_gray.png")
    assert (load_photo(tmp_path / "clear.png", size=16) - _rgb((200, 100, 50))).abs().max() < 1e-6
    assert (load_photo(tmp_path / "clear_gray.png", size=16) - 77 / 255).abs().max() < 1e-6


def test_gray_and_palette_images(tmp_path):
    Image.new("L", (130, 130), 77).save(tmp_path / "gray.png")
    assert (load_photo(tmp_path / "gray.png", size=16) - 77 / 255).abs().max() < 1e-6
    palette = _bands((260, 130), (65, (250, 250, 5)), (130, (10, 200, 30)), (65, (250, 250, 5)))
    palette = palette.quantize(2)
    assert palette.mode == "P"
    palette.save(tmp_path / "palette.png")
    photo = load_photo(tmp_path / "palette.png", size=130)
    assert (photo - _rgb((10, 200, 30))).abs().max() < 1e-6  # the centred square is one band


def test_exr_is_linear_and_becomes_srgb(tmp_path):
    write_exr(tmp_path / "grey.exr", np.full((130, 150, 4), [0.5, 0.5, 0.5, 0.0], np.float32))
    photo = load_photo(tmp_path / "grey.exr", size=64)
    assert (photo - 0.7354).abs().max() < 1e-3
    write_exr(tmp_path / "hot.exr", np.full((130, 130, 1), 7.0, np.float32), half=False)
    assert (load_photo(tmp_path / "hot.exr", size=8) - 1).abs().max() < 1e-6
    assert photo_info(tmp_path / "grey.exr") == {"width": 150, "height": 130, "format": "EXR",
                                                 "mode": "RGBA"}


def test_the_crop_is_the_centred_square(tmp_path):
    _bands((300, 200), (50, RED), (200, GREEN), (50, BLUE)).save(tmp_path / "wide.png")
    _bands((200, 300), (50, RED), (200, GREEN), (50, BLUE), vertical=False).save(tmp_path / "tall.png")
    for name in ("wide.png", "tall.png"):
        assert (load_photo(tmp_path / name, size=64) - _rgb(GREEN)).abs().max() < 1e-6


def test_too_small(tmp_path):
    Image.new("RGB", (MIN_SIDE - 1, 400)).save(tmp_path / "small.png")
    _refused(tmp_path / "small.png", r"127x400 pixels is too small; the shorter side must be at "
                                     r"least 128 pixels")
    Image.new("RGB", (MIN_SIDE, 400)).save(tmp_path / "enough.png")
    assert load_photo(tmp_path / "enough.png", size=16).shape == (1, 3, 16, 16)


def test_decompression_bomb_is_refused_from_the_header(tmp_path, monkeypatch):
    bomb = _png_claiming(tmp_path / "bomb.png", 100_000, 100_000)
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # Pillow's DecompressionBombWarning must not escape either
        _refused(bomb, "megapixels a photo may have")
        _refused(_png_claiming(tmp_path / "big.png", 12_000, 9_000), "12000x9000 pixels is more")
        assert photo_info(_png_claiming(tmp_path / "ok.png", 9_500, 9_500))["width"] == 9_500
    monkeypatch.setattr(Image, "MAX_IMAGE_PIXELS", None)  # a host that switched Pillow's check off
    _refused(bomb, "100000x100000 pixels is more than the 100 megapixels")
    assert time.perf_counter() - start < 2.0


def test_damaged_and_non_image_files(tmp_path):
    path = tmp_path / "cut.jpg"
    Image.fromarray(RNG.integers(0, 256, (300, 300, 3), dtype=np.uint8)).save(path, quality=90)
    path.write_bytes(path.read_bytes()[:len(path.read_bytes()) // 2])
    _refused(path, "cannot read the image")
    deep = tmp_path / "cut16.png"
    deep.write_bytes(encode_png(torch.rand(1, 3, 200, 200), bits=16)[:30_000])
    _refused(deep, "cannot read the image")
    text = tmp_path / "notes.jpg"
    text.write_text("these are not pixels\n")
    _refused(text, "not an image file that can be read")
    bad_exr = tmp_path / "bad.exr"
    bad_exr.write_bytes(b"\x76\x2f\x31\x01" + bytes(40))
    _refused(bad_exr, "bad.exr: ")
    _refused(tmp_path / "missing.png", "no such file")
    _refused(tmp_path, "not a file")
    with pytest.raises(PhotoError, match="notes.jpg: not an image"):
        photo_info(text)


@pytest.mark.parametrize("size", [0, -3, 1.5, True, "512", None])
def test_size_must_be_a_positive_whole_number(tmp_path, size):
    Image.new("RGB", (130, 130)).save(tmp_path / "photo.png")
    _refused(tmp_path / "photo.png", "the photo size must be a positive whole number", size=size)


def test_real_photos(shared_dir):
    paths = sorted((shared_dir / "data" / "photos").glob("*.png"))
    assert paths
    for path in paths:
        photo = load_photo(path)
        assert photo.shape == (1, 3, 512, 512) and photo.dtype == torch.float32
        assert 0.0 <= photo.min() and photo.max() <= 1.0 and photo.std() > 0.01
        with Image.open(path) as img:  # at its own size the photo is read unchanged
            native = np.asarray(img.convert("RGB"), np.float32) / 255
            same = load_photo(path, size=img.width)[0].permute(1, 2, 0).numpy()
        assert img.width == img.height and np.abs(same - native).max() < 1e-6
