"""Game-engine export presets: the numpy packing without bpy, the files through real bpy."""
from __future__ import annotations

import json

import numpy as np
import pytest
import torch

from blender_match.blender.export_presets import (
    ExportError,
    export_maps,
    flip_green,
    pack_channels,
    pack_preset,
    roughness_to_smoothness,
    stretch_direction,
)
from blender_match.blender.material_builder import srgb_to_linear
from blender_match.errors import ResultFolderError
from blender_match.image_files import write_png
from blender_match.vocabulary import ANISOTROPY, ANISOTROPY_ANGLE, MATERIAL_OUTPUTS

W, H = 8, 4
PNG_DEPTH, PNG_COLOR_TYPE = 24, 25  # byte offsets in the IHDR chunk
GRAY, RGB, RGBA = 0, 2, 6


def random_maps(ao=True, height=True):
    rng = np.random.default_rng(1)
    maps = {"basecolor": rng.random((H, W, 3), np.float32), "normal": rng.random((H, W, 3), np.float32),
            "roughness": rng.random((H, W), np.float32), "metallic": rng.random((H, W), np.float32)}
    if ao:
        maps["ambientocclusion"] = rng.random((H, W), np.float32)
    if height:
        maps["height"] = rng.random((H, W), np.float32)
    return maps


# --- numpy only ---------------------------------------------------------------------------------

def test_pack_channels_fills_scalars():
    a = np.full((2, 3), 0.25, np.float32)
    packed = pack_channels([a, 1.0, a * 2])
    assert packed.shape == (2, 3, 3) and packed.dtype == np.float32
    assert np.all(packed[..., 0] == 0.25) and np.all(packed[..., 1] == 1.0) and np.all(packed[..., 2] == 0.5)


def test_pack_channels_refuses_mismatched_sizes():
    with pytest.raises(ExportError, match="shapes"):
        pack_channels([np.zeros((2, 3)), np.zeros((3, 2))])
    with pytest.raises(ExportError):
        pack_channels([1.0, 0.0])


def test_flip_green_inverts_only_green_and_copies():
    normal = np.random.default_rng(0).random((2, 2, 3), np.float32)
    original = normal.copy()
    flipped = flip_green(normal)
    assert np.array_equal(normal, original)
    assert np.allclose(flipped[..., 1], 1 - normal[..., 1])
    assert np.array_equal(flipped[..., [0, 2]], normal[..., [0, 2]])
    assert np.allclose(flip_green(flipped), normal)


def test_roughness_to_smoothness():
    assert np.allclose(roughness_to_smoothness(np.array([0.0, 0.25, 1.0])), [1.0, 0.75, 0.0])


def test_srgb_to_linear_known_values():
    assert np.allclose(srgb_to_linear([0.0, 0.04045, 0.5, 1.0]), [0.0, 0.04045 / 12.92, 0.21404, 1.0], atol=1e-5)


def by_suffix(packed):
    return {p.suffix: p for p in packed}


def test_gltf_packs_ao_roughness_metallic():
    maps = random_maps()
    files = by_suffix(pack_preset("gltf", maps))
    assert list(files) == ["_baseColor", "_metallicRoughness", "_normal"]
    mr = files["_metallicRoughness"].pixels
    assert np.array_equal(mr[..., 0], maps["ambientocclusion"])
    assert np.array_equal(mr[..., 1], maps["roughness"]) and np.array_equal(mr[..., 2], maps["metallic"])
    assert np.array_equal(files["_normal"].pixels, maps["normal"])
    assert files["_baseColor"].srgb and not files["_normal"].srgb
    no_ao = by_suffix(pack_preset("gltf", random_maps(ao=False)))["_metallicRoughness"].pixels
    assert np.all(no_ao[..., 0] == 1.0)


def test_unreal_flips_normal_and_packs_orm():
    maps = random_maps(ao=False)
    files = by_suffix(pack_preset("unreal", maps))
    assert list(files) == ["_BaseColor", "_Normal", "_ORM"]
    assert np.allclose(files["_Normal"].pixels[..., 1], 1 - maps["normal"][..., 1])
    orm = files["_ORM"].pixels
    assert np.all(orm[..., 0] == 1.0)
    assert np.array_equal(orm[..., 1], maps["roughness"]) and np.array_equal(orm[..., 2], maps["metallic"])


def test_unity_metallic_smoothness_and_optional_maps():
    maps = random_maps()
    files = by_suffix(pack_preset("unity", maps))
    assert list(files) == ["_Albedo", "_MetallicSmoothness", "_Normal", "_Height", "_Occlusion"]
    ms = files["_MetallicSmoothness"].pixels
    assert ms.shape == (H, W, 4)
    assert np.array_equal(ms[..., 0], maps["metallic"]) and np.array_equal(ms[..., 1], maps["ambientocclusion"])
    assert np.all(ms[..., 2] == 1.0) and np.allclose(ms[..., 3], 1 - maps["roughness"])
    assert np.array_equal(files["_Normal"].pixels, maps["normal"])
    assert files["_Height"].pixels.shape == (H, W, 1)
    bare = by_suffix(pack_preset("unity", random_maps(ao=False, height=False)))
    assert list(bare) == ["_Albedo", "_MetallicSmoothness", "_Normal"]
    assert np.all(bare["_MetallicSmoothness"].pixels[..., 1] == 1.0)


def test_the_stretch_direction_is_the_brushing_turned_a_quarter():
    x, y = stretch_direction(np.array([0.0, 0.25, 0.125]))
    assert np.allclose(x, [0.0, -1.0, -np.sqrt(0.5)], atol=1e-6) and np.allclose(y, [1.0, 0.0, np.sqrt(0.5)], atol=1e-6)


def brushed(maps, angle=True):
    """``maps`` with an anisotropy level and (``angle``) an angle map of 1/8 turn, brushed towards
    +u+v: the highlight stretches along -u+v."""
    maps[ANISOTROPY] = np.random.default_rng(2).random((H, W), np.float32)
    if angle:
        maps[ANISOTROPY_ANGLE] = np.full((H, W), 0.125, np.float32)
    return maps


def test_each_preset_carries_the_anisotropy_its_format_takes():
    maps = brushed(random_maps())
    half = np.sqrt(0.5) * 0.5
    gltf = by_suffix(pack_preset("gltf", maps))
    assert list(gltf)[-1] == "_anisotropy"
    aniso = gltf["_anisotropy"].pixels
    assert np.allclose(aniso[..., 0], 0.5 - half) and np.allclose(aniso[..., 1], 0.5 + half)
    assert np.array_equal(aniso[..., 2], maps[ANISOTROPY])
    for preset, green in (("unreal", 0.5 - half), ("unity", 0.5 + half)):  # Unreal's tangent space is DirectX
        files = by_suffix(pack_preset(preset, maps))
        assert list(files)[-2:] == ["_Anisotropy", "_Tangent"]
        assert np.array_equal(files["_Anisotropy"].pixels[..., 0], maps[ANISOTROPY])
        tangent = files["_Tangent"].pixels
        assert tangent.shape == (H, W, 3) and not files["_Tangent"].srgb
        assert np.allclose(tangent[..., 0], 0.5 - half) and np.allclose(tangent[..., 1], green)
        assert np.all(tangent[..., 2] == 0.5)


def test_without_an_angle_map_the_brushing_runs_along_u_and_without_a_level_nothing_is_added():
    aniso = by_suffix(pack_preset("gltf", brushed(random_maps(), angle=False)))["_anisotropy"].pixels
    assert np.allclose(aniso[..., 0], 0.5, atol=1e-6) and np.allclose(aniso[..., 1], 1.0)
    only_angle = random_maps()
    only_angle[ANISOTROPY_ANGLE] = np.zeros((H, W), np.float32)
    assert list(by_suffix(pack_preset("unity", only_angle)))[-1] == "_Occlusion"


def test_pack_preset_errors():
    with pytest.raises(ExportError, match="unknown export preset 'godot'"):
        pack_preset("godot", random_maps())
    maps = random_maps()
    del maps["metallic"]
    with pytest.raises(ExportError, match="metallic"):
        pack_preset("gltf", maps)


# --- through bpy --------------------------------------------------------------------------------

@pytest.fixture
def bpy():
    module = pytest.importorskip("bpy")
    module.ops.wm.read_factory_settings(use_empty=True)
    return module


def make_result(root, ao=True, anisotropy=False):
    """A result folder as the pipeline writes it (random maps; ``flat`` all None); the anisotropy
    maps only with ``anisotropy`` (a brushed metal's)."""
    root.mkdir(parents=True)
    maps = {}
    for usage, file, channels, bits in ((o.name, o.file, o.file_channels, o.bits) for o in MATERIAL_OUTPUTS):
        if (usage == "ambientocclusion" and not ao) or (usage in (ANISOTROPY, ANISOTROPY_ANGLE) and not anisotropy):
            continue
        write_png(root / file, torch.rand(1, channels, H, W), bits=bits)
        maps[usage] = {"file": file, "flat": None}
    (root / "params.json").write_text("{}")
    (root / "report.json").write_text(json.dumps({"graph": "marble", "size": W, "loss_final": 0.1, "maps": maps}))
    return root


def read(bpy, path):
    """A file's stored values (H, W, 4) through bpy, as an engine would read them."""
    image = bpy.data.images.load(str(path), check_existing=False)
    image.colorspace_settings.name = "Non-Color"
    image.alpha_mode = "CHANNEL_PACKED"
    width, height = image.size
    pixels = np.empty(width * height * image.channels, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(height, width, -1)


def png_header(path):
    data = path.read_bytes()[:26]
    return data[PNG_DEPTH], data[PNG_COLOR_TYPE]


def datablock_counts(bpy):
    return len(bpy.data.images), len(bpy.data.scenes)


def test_gltf_png_8bit(bpy, tmp_path):
    result = make_result(tmp_path / "r")
    before = datablock_counts(bpy)
    paths = export_maps(result, tmp_path / "out", "gltf")
    assert [p.name for p in paths] == ["marble_baseColor.png", "marble_metallicRoughness.png", "marble_normal.png"]
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(p.name for p in paths)  # no temp files
    assert datablock_counts(bpy) == before
    assert [png_header(p) for p in paths] == [(8, RGB), (8, RGB), (8, RGB)]
    mr = read(bpy, paths[1])
    assert np.abs(mr[..., 0] - read(bpy, result / "ambientocclusion.png")[..., 0]).max() <= 1 / 255
    assert np.abs(mr[..., 1] - read(bpy, result / "roughness.png")[..., 0]).max() <= 1 / 255
    assert np.abs(mr[..., 2] - read(bpy, result / "metallic.png")[..., 0]).max() <= 1 / 255
    base = read(bpy, paths[0])[..., :3]
    assert np.abs(base - read(bpy, result / "basecolor.png")[..., :3]).max() <= 1 / 255  # sRGB kept as is


def test_unreal_png_16bit_flips_green(bpy, tmp_path):
    result = make_result(tmp_path / "r", ao=False)
    paths = export_maps(result, tmp_path / "out", "unreal", bits=16, name="Wall tile")
    assert [p.name for p in paths] == ["Wall_tile_BaseColor.png", "Wall_tile_Normal.png", "Wall_tile_ORM.png"]
    assert all(png_header(p) == (16, RGB) for p in paths)
    normal, source = read(bpy, paths[1]), read(bpy, result / "normal.png")
    assert np.abs(normal[..., 1] - (1 - source[..., 1])).max() <= 1 / 65535
    assert np.abs(normal[..., [0, 2]] - source[..., [0, 2]]).max() <= 1 / 65535
    orm = read(bpy, paths[2])
    assert np.all(orm[..., 0] == 1.0)
    assert np.abs(orm[..., 1] - read(bpy, result / "roughness.png")[..., 0]).max() <= 1 / 255
    assert np.abs(orm[..., 2] - read(bpy, result / "metallic.png")[..., 0]).max() <= 1 / 255


@pytest.mark.parametrize("bits", [8, 16])
def test_unity_metallic_smoothness_alpha(bpy, tmp_path, bits):
    result = make_result(tmp_path / "r")
    paths = export_maps(result, tmp_path / "out", "unity", bits=bits)
    names = [p.name for p in paths]
    assert names == ["marble_Albedo.png", "marble_MetallicSmoothness.png", "marble_Normal.png",
                     "marble_Height.png", "marble_Occlusion.png"]
    assert [png_header(p) for p in paths] == [(bits, RGB), (bits, RGBA), (bits, RGB), (bits, GRAY), (bits, GRAY)]
    ms = read(bpy, paths[1])
    roughness = read(bpy, result / "roughness.png")[..., 0]
    tolerance = 1 / 255 if bits == 8 else 1 / 65535
    assert np.abs(ms[..., 3] - (1 - roughness)).max() <= tolerance
    assert np.abs(ms[..., 0] - read(bpy, result / "metallic.png")[..., 0]).max() <= tolerance
    assert np.abs(read(bpy, paths[3])[..., 0] - read(bpy, result / "height.png")[..., 0]).max() <= 1 / 255


def test_anisotropic_results_export_their_anisotropy_files(bpy, tmp_path):
    result = make_result(tmp_path / "r", anisotropy=True)
    level = read(bpy, result / "anisotropylevel.png")[..., 0]
    x, y = stretch_direction(read(bpy, result / "anisotropyangle.png")[..., 0])
    gltf = export_maps(result, tmp_path / "gltf", "gltf")
    assert gltf[-1].name == "marble_anisotropy.png" and png_header(gltf[-1]) == (8, RGB)
    packed = read(bpy, gltf[-1])
    assert np.abs(packed[..., 2] - level).max() <= 1 / 255
    assert np.abs(packed[..., 0] - (x * 0.5 + 0.5)).max() <= 1 / 255
    assert np.abs(packed[..., 1] - (y * 0.5 + 0.5)).max() <= 1 / 255
    for preset, sign in (("unreal", -1), ("unity", 1)):
        paths = export_maps(result, tmp_path / preset, preset)
        assert [p.name for p in paths[-2:]] == ["marble_Anisotropy.png", "marble_Tangent.png"]
        assert [png_header(p) for p in paths[-2:]] == [(8, GRAY), (8, RGB)]
        assert np.abs(read(bpy, paths[-2])[..., 0] - level).max() <= 1 / 255
        assert np.abs(read(bpy, paths[-1])[..., 1] - (sign * y * 0.5 + 0.5)).max() <= 1 / 255


def test_exr_is_linear_float(bpy, tmp_path):
    result = make_result(tmp_path / "r")
    paths = export_maps(result, tmp_path / "out", "gltf", file_format="OPEN_EXR", bits=32)
    assert [p.suffix for p in paths] == [".exr"] * 3
    assert all(p.read_bytes()[:4] == b"\x76\x2f\x31\x01" for p in paths)  # OpenEXR magic
    base = read(bpy, paths[0])[..., :3]
    assert np.allclose(base, srgb_to_linear(read(bpy, result / "basecolor.png")[..., :3]), atol=1e-6)
    assert np.allclose(read(bpy, paths[2])[..., :3], read(bpy, result / "normal.png")[..., :3], atol=1e-6)


def test_size_option_resizes(bpy, tmp_path):
    paths = export_maps(make_result(tmp_path / "r"), tmp_path / "out", "unreal", size=16)
    assert all(read(bpy, p).shape[:2] == (16, 16) for p in paths)


def test_refused_overwrite_writes_nothing(bpy, tmp_path):
    result = make_result(tmp_path / "r")
    out = tmp_path / "out"
    out.mkdir()
    (out / "marble_ORM.png").write_bytes(b"keep")
    with pytest.raises(ExportError, match="marble_ORM.png: already exists"):
        export_maps(result, out, "unreal")
    assert [p.name for p in out.iterdir()] == ["marble_ORM.png"]
    assert (out / "marble_ORM.png").read_bytes() == b"keep"
    paths = export_maps(result, out, "unreal", overwrite=True)
    assert png_header(paths[2]) == (8, RGB)


@pytest.mark.parametrize("options, message", [
    ({"preset": "godot"}, "unknown export preset"),
    ({"file_format": "TIFF"}, "unknown file format"),
    ({"bits": 8, "file_format": "OPEN_EXR"}, "OPEN_EXR is written at 16 or 32 bits, not 8"),
    ({"bits": 12}, "PNG is written at 8 or 16 bits"),
    ({"size": 0}, "positive"),
])
def test_bad_options_are_refused_before_reading(bpy, tmp_path, options, message):
    kwargs = {"preset": "gltf", **options}
    with pytest.raises(ExportError, match=message):
        export_maps(tmp_path / "nowhere", tmp_path / "out", **kwargs)
    assert not (tmp_path / "out").exists()


def test_missing_result_folder_names_it(bpy, tmp_path):
    with pytest.raises(ResultFolderError, match="report.json"):
        export_maps(tmp_path, tmp_path / "out", "gltf")
