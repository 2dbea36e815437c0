"""OpenEXR reading and writing: exact round trips, the header, damaged and unsupported files, and
agreement with an independent implementation (Blender's OpenEXR, through the bpy module)."""
from __future__ import annotations

import importlib.util
import struct
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from blender_match.exr_files import ExrError, encode_exr, read_exr, read_exr_header, write_exr
from blender_match.safe_files import FileWriteError

RNG = np.random.default_rng(7)


def _image(height=19, width=37, channels=4, scale=4.0) -> np.ndarray:
    """Values in [-1, scale - 1): negatives and values above 1 both survive EXR."""
    return (RNG.random((height, width, channels)) * scale - 1).astype(np.float32)


def _stored(array: np.ndarray, half: bool) -> np.ndarray:
    return array.astype(np.float16).astype(np.float32) if half else array


def _write(tmp_path, data: bytes, name="image.exr"):
    path = tmp_path / name
    path.write_bytes(data)
    return path


def _offsets(data: bytes, header) -> list[int]:
    count = -(-header.height // {"ZIP": 16}.get(header.compression, 1))
    return list(struct.unpack_from(f"<{count}Q", data, header.table_offset))


@pytest.mark.parametrize("compression", ["zip", "zips", "none"])
@pytest.mark.parametrize("channels", [1, 3, 4])
@pytest.mark.parametrize("half", [True, False])
def test_round_trip_is_exact(tmp_path, half, channels, compression):
    image = _image(channels=channels)
    path = tmp_path / "image.exr"
    write_exr(path, image, half=half, compression=compression)
    back = read_exr(path)
    assert back.dtype == np.float32 and back.shape == (19, 37, channels)
    np.testing.assert_array_equal(back, _stored(image, half))


@pytest.mark.parametrize("shape", [(1, 1), (16, 5), (33, 2), (2, 300)])
def test_odd_sizes_and_chunk_boundaries(tmp_path, shape):
    image = _image(*shape, channels=3)
    path = _write(tmp_path, encode_exr(image))
    np.testing.assert_array_equal(read_exr(path), _stored(image, True))


def test_header_fields(tmp_path):
    data = encode_exr(_image(channels=4), half=True)
    assert data[:4] == b"\x76\x2f\x31\x01" and struct.unpack_from("<I", data, 4)[0] == 2
    for name, kind in [("channels", "chlist"), ("compression", "compression"),
                       ("dataWindow", "box2i"), ("displayWindow", "box2i"),
                       ("lineOrder", "lineOrder"), ("pixelAspectRatio", "float"),
                       ("screenWindowCenter", "v2f"), ("screenWindowWidth", "float")]:
        assert f"{name}\0{kind}\0".encode() in data, name
    header = read_exr_header(_write(tmp_path, data))
    assert (header.width, header.height) == (37, 19)
    assert list(header.channels.items()) == [(c, "HALF") for c in "ABGR"]  # sorted, as EXR wants
    assert header.compression == "ZIP" and header.layout == "RGBA"
    assert header.data_window == (0, 0, 36, 18)
    offsets = _offsets(data, header)  # ZIP: 16 scanlines a chunk, so 19 lines make 2 chunks
    assert [struct.unpack_from("<i", data, o)[0] for o in offsets] == [0, 16]
    assert offsets[0] == header.table_offset + 16

    gray = read_exr_header(_write(tmp_path, encode_exr(_image(channels=1), half=False,
                                                       compression="none"), "gray.exr"))
    assert gray.channels == {"Y": "FLOAT"} and gray.layout == "Y" and gray.compression == "NONE"


def test_zip_compresses_and_incompressible_chunks_are_stored_raw(tmp_path):
    flat = np.full((64, 64, 3), 0.25, np.float32)
    assert len(encode_exr(flat)) < len(encode_exr(flat, compression="none")) / 20
    noise = RNG.random((16, 64, 3)).astype(np.float32)  # float noise does not deflate
    data = encode_exr(noise, half=False)
    header = read_exr_header(_write(tmp_path, data))
    (size,) = struct.unpack_from("<i", data, _offsets(data, header)[0] + 4)
    assert size == 16 * 64 * 3 * 4
    np.testing.assert_array_equal(read_exr(tmp_path / "image.exr"), noise)


def test_half_clamps_instead_of_overflowing(tmp_path):
    image = np.array([[[1e6, -1e6, 0.5]]], np.float32)
    back = read_exr(_write(tmp_path, encode_exr(image)))
    np.testing.assert_array_equal(back, [[[65504.0, -65504.0, 0.5]]])


def test_channel_layouts(tmp_path):
    """A missing colour channel reads as 0; files without R, G, B or Y are refused."""
    data = encode_exr(_image(channels=3), half=False)
    only_rg = _write(tmp_path, data.replace(b"B\0\x02\0\0\0", b"Z\0\x02\0\0\0", 1), "rg.exr")
    back = read_exr(only_rg)
    assert back.shape == (19, 37, 3) and not back[..., 2].any() and back[..., 0].any()
    depth = data.replace(b"R\0\x02", b"X\0\x02", 1).replace(b"G\0\x02", b"W\0\x02", 1)
    depth = _write(tmp_path, depth.replace(b"B\0\x02", b"Z\0\x02", 1), "depth.exr")
    with pytest.raises(ExrError, match=r"depth\.exr: no R, G, B or Y channel \(channels: Z, W, X\)"):
        read_exr(depth)


def _patched(data: bytes, marker: bytes, value: bytes) -> bytes:
    at = data.index(marker) + len(marker)
    return data[:at] + value + data[at + len(value):]


def test_unsupported_files_name_the_file_and_the_problem(tmp_path):
    data = encode_exr(_image(channels=3))
    piz = _write(tmp_path, _patched(data, b"compression\0compression\0\x01\0\0\0", b"\x04"), "piz.exr")
    with pytest.raises(ExrError) as info:
        read_exr(piz)
    assert str(info.value) == (f"{piz}: OpenEXR compression PIZ is not supported (save it as ZIP "
                               "or uncompressed)")
    for flag, what in [(0x200, "tiled"), (0x1000, "multi-part"), (0x800, "deep")]:
        path = _write(tmp_path, data[:4] + struct.pack("<I", 2 | flag) + data[8:], f"{what}.exr")
        with pytest.raises(ExrError, match=rf"^.*{what}\.exr: {what} OpenEXR files are not supported"):
            read_exr_header(path)
    png = _write(tmp_path, b"\x89PNG\r\n\x1a\n" + bytes(100), "fake.exr")
    with pytest.raises(ExrError, match=r"fake\.exr: not an OpenEXR file$"):
        read_exr(png)
    with pytest.raises(ExrError, match=r"missing\.exr: no such file"):
        read_exr(tmp_path / "missing.exr")


def test_truncated_files_raise_exr_error_naming_the_file(tmp_path):
    data = encode_exr(_image(height=40, channels=4))
    for cut in list(range(0, len(data), 37)) + [len(data) - 1]:
        path = _write(tmp_path, data[:cut], "cut.exr")
        with pytest.raises(ExrError, match=r"cut\.exr: ") as info:
            read_exr(path)
        assert "\n" not in str(info.value)


def test_corrupt_bytes_never_escape_as_other_errors(tmp_path):
    data = bytearray(encode_exr(_image(height=40, channels=4)))
    for _ in range(300):
        bad = bytearray(data)
        for at in RNG.integers(0, len(bad), size=RNG.integers(1, 4)):
            bad[at] = RNG.integers(0, 256)
        path = _write(tmp_path, bytes(bad), "bad.exr")
        try:
            assert read_exr(path).ndim == 3
        except ExrError as exc:
            assert str(exc).startswith(f"{path}: ")


def test_a_header_claiming_too_many_pixels_is_refused_without_allocating(tmp_path):
    data = _patched(encode_exr(_image(channels=1)), b"dataWindow\0box2i\0\x10\0\0\0",
                    struct.pack("<4i", 0, 0, 99_999, 99_999))
    with pytest.raises(ExrError, match="more than the file can hold"):
        read_exr(_write(tmp_path, data))


def test_encode_rejects_bad_input_and_write_refuses_to_overwrite(tmp_path):
    for bad in (np.zeros((4, 4, 2)), np.zeros((4, 4)), np.zeros((0, 4, 3))):
        with pytest.raises(ExrError, match="cannot write an array of shape"):
            encode_exr(bad)
    with pytest.raises(ExrError, match="compression 'piz'"):
        encode_exr(np.zeros((4, 4, 3)), compression="piz")
    path = tmp_path / "out.exr"
    write_exr(path, np.zeros((4, 4, 3)))
    with pytest.raises(FileWriteError):
        write_exr(path, np.ones((4, 4, 3)))
    write_exr(path, np.ones((4, 4, 3)), overwrite=True)
    assert read_exr(path).min() == 1.0


# --- Blender's OpenEXR, as an independent implementation -------------------------------------

_BLENDER_SCRIPT = textwrap.dedent("""
    import sys
    from pathlib import Path
    import bpy
    import numpy as np

    folder = Path(sys.argv[1])

    def pixels(image):  # Blender keeps RGBA float rows bottom first
        flat = np.empty(len(image.pixels), np.float32)
        image.pixels.foreach_get(flat)
        return flat.reshape(image.size[1], image.size[0], 4)[::-1]

    for path in sorted(folder.glob("ours_*.exr")):
        np.save(folder / (path.stem + ".npy"), pixels(bpy.data.images.load(str(path))))

    source = np.load(folder / "source.npy")
    image = bpy.data.images.new("source", source.shape[1], source.shape[0], float_buffer=True,
                                alpha=True)
    image.pixels.foreach_set(np.ascontiguousarray(source[::-1]).ravel())
    scene = bpy.context.scene
    scene.view_settings.view_transform = "AgX"  # overridden below: the file must stay linear
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_management = "OVERRIDE"
    settings.view_settings.view_transform = "Standard"
    for codec, depth, mode in [("ZIP", "16", "RGBA"), ("ZIPS", "32", "RGB"), ("NONE", "16", "RGB"),
                               ("PIZ", "16", "RGBA")]:
        settings.exr_codec, settings.color_depth, settings.color_mode = codec, depth, mode
        image.save_render(str(folder / f"blender_{codec}_{depth}_{mode}.exr"), scene=scene)
""")


@pytest.fixture(scope="module")
def blender_folder(tmp_path_factory):
    """One Blender run: it loads the files we wrote and writes files of its own."""
    if importlib.util.find_spec("bpy") is None:
        pytest.skip("the bpy module (Blender as a Python module) is not installed")
    folder = tmp_path_factory.mktemp("blender")
    for channels, half, compression in [(1, True, "zip"), (3, False, "none"), (4, True, "zip"),
                                        (4, False, "zips")]:
        write_exr(folder / f"ours_{channels}_{half}_{compression}.exr",
                  _image(channels=channels, scale=3.0), half=half, compression=compression)
    np.save(folder / "source.npy", _image(height=21, width=35, channels=4, scale=3.0))
    done = subprocess.run([sys.executable, "-c", _BLENDER_SCRIPT, str(folder)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    return folder


@pytest.mark.bpy
def test_blender_reads_our_files(blender_folder):
    paths = sorted(blender_folder.glob("ours_*.exr"))
    assert len(paths) == 4
    for path in paths:
        ours = read_exr(path)
        expected = np.ones(ours.shape[:2] + (4,), np.float32)
        expected[..., :3] = ours[..., :3] if ours.shape[2] >= 3 else ours[..., :1]
        expected[..., 3:] = ours[..., 3:] if ours.shape[2] == 4 else 1.0
        np.testing.assert_array_equal(np.load(path.with_suffix(".npy")), expected, err_msg=path.name)


@pytest.mark.bpy
def test_we_read_blenders_files(blender_folder):
    source = np.load(blender_folder / "source.npy")
    for codec, depth, mode in [("ZIP", "16", "RGBA"), ("ZIPS", "32", "RGB"), ("NONE", "16", "RGB")]:
        path = blender_folder / f"blender_{codec}_{depth}_{mode}.exr"
        header = read_exr_header(path)
        assert header.compression == codec and header.layout == mode
        assert set(header.channels.values()) == {"HALF" if depth == "16" else "FLOAT"}
        np.testing.assert_array_equal(read_exr(path), _stored(source[..., :len(mode)], depth == "16"),
                                      err_msg=path.name)
    piz = blender_folder / "blender_PIZ_16_RGBA.exr"
    with pytest.raises(ExrError, match=r"blender_PIZ_16_RGBA\.exr: OpenEXR compression PIZ is not supported"):
        read_exr(piz)
