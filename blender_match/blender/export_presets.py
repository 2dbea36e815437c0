"""Export a match result's maps as the texture set a game engine expects.

Each preset writes ``<name><suffix>.png`` (or ``.exr``) files; ``name`` defaults to the graph's.
Channels that a preset packs together come from the result's maps; ambient occlusion (AO) is
optional in a result, and where a packed channel would hold it but there is none, it is 1 (no
occlusion).

glTF 2.0 (metallic-roughness):
    _baseColor           RGB  base colour (sRGB)
    _metallicRoughness   RGB  R = AO (1 when none), G = roughness, B = metallic
    _normal              RGB  tangent-space normal, OpenGL (+Y up, glTF's convention)
  glTF reads roughness from G and metallic from B. R holds AO, the common "ORM" packing: a
  material's occlusionTexture (which reads R) may point at the same file, so no separate
  occlusion file is written. glTF has no height map.
    _anisotropy          RGB  KHR_materials_anisotropy's anisotropyTexture (anisotropic results):
                              RG = the direction the highlight stretches along, B = the level

Unreal Engine:
    _BaseColor           RGB  base colour (sRGB)
    _Normal              RGB  tangent-space normal, DirectX (G' = 1 - G)
    _ORM                 RGB  R = AO (1 when none), G = roughness, B = metallic
    _Anisotropy          gray the level, for the material's Anisotropy input (anisotropic results)
    _Tangent             RGB  the direction the highlight stretches along, DirectX, for "Tangent"

Unity (URP / HDRP Lit, metallic workflow):
    _Albedo              RGB  base colour (sRGB)
    _MetallicSmoothness  RGBA R = metallic, G = AO (1 when none), B = 1, A = smoothness (1 - roughness)
    _Normal              RGB  tangent-space normal, OpenGL (Unity's convention)
    _Height              gray height (when the result has one)
    _Occlusion           gray AO (when the result has one)
    _Anisotropy          gray the level: HDRP Lit's Anisotropy Map (anisotropic results)
    _Tangent             RGB  the direction the highlight stretches along, OpenGL: HDRP's Tangent Map
  URP's Metallic Map reads only R and A; G and B follow HDRP's Mask Map (G = AO, B = detail
  mask, 1 = detail everywhere, HDRP's own default) so the same file serves as HDRP's Mask Map.

Anisotropy (a result with an anisotropy level map; the angle is 0 when it has none): every format
takes the direction the highlight stretches along, which is across the brushing, so the angle
map (the brushing direction) is turned a quarter turn first, as for Blender's "Anisotropic
Rotation". The direction is a unit vector in the tangent plane, x along +u and y along +v,
encoded like a normal map (v * 0.5 + 0.5); glTF's RG pair is what Blender's own glTF exporter
writes (cos, sin of the rotation). The level is written as it is, Blender's 0..1 scale; each
engine turns a level into roughnesses its own way (glTF mixes the roughness along the direction
towards 1 by level², Unreal and HDRP scale it by 1 + level along and 1 - level across, Blender
by 1/aspect and aspect, aspect = sqrt(1 - 0.9 level)), so the same level stretches the
highlight somewhat differently there; the material's own strength factor (glTF's
anisotropyStrength, Unreal's and HDRP's Anisotropy) is left at 1 for the map to rule. URP Lit
has no anisotropy: it ignores the two files.

Formats: PNG at ``bits`` 8 or 16 (16 keeps normal and height smooth); OpenEXR at 16 (half) or
32 (float) bits. OpenEXR holds linear values, so base colour is converted from sRGB to linear
there; every other map is data and written as is.

Files are written through Blender's own image writer (Blender's Python has no Pillow, and our
PNG encoder needs torch): temporary images and a temporary scene carry the pixels and the
format settings and are removed afterwards. Each file is written under a temporary name and
renamed into place; existing files are refused, all checked before anything is written, unless
``overwrite``. The packing (``pack_preset`` and its helpers) is numpy only and needs no bpy.
"""
from __future__ import annotations

import os
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import BlenderMatchError
from ..vocabulary import ANISOTROPY, ANISOTROPY_ANGLE, ANISOTROPY_TANGENT_TURN, PBR_USAGES, USAGES
from .material_builder import graph_name, map_path, read_report, srgb_to_linear

PRESETS = ("gltf", "unreal", "unity")
EXTENSIONS = {"PNG": ".png", "OPEN_EXR": ".exr"}
BITS = {"PNG": (8, 16), "OPEN_EXR": (16, 32)}
REQUIRED = PBR_USAGES
OPTIONAL = tuple(u for u in USAGES if u not in REQUIRED)
_COLOR_MODES = {1: "BW", 3: "RGB", 4: "RGBA"}


class ExportError(BlenderMatchError):
    """An export that cannot be done (names the option or file and the problem)."""


@dataclass(frozen=True)
class PackedMap:
    """One file of a preset: ``pixels`` (H, W, C) float32 in [0, 1], C in (1, 3, 4); ``srgb``
    marks sRGB-encoded colour (linearised for OpenEXR)."""

    suffix: str
    pixels: np.ndarray
    srgb: bool = False


def pack_channels(channels) -> np.ndarray:
    """Stack (H, W) arrays and scalars (filled to the arrays' size) into an (H, W, N) image."""
    arrays = [np.asarray(c, dtype=np.float32) for c in channels]
    shapes = {a.shape for a in arrays if a.ndim}
    if len(shapes) != 1 or len(next(iter(shapes))) != 2:
        raise ExportError(f"cannot pack channels of shapes {sorted(shapes)}: need one (H, W) size")
    shape = shapes.pop()
    return np.stack([np.broadcast_to(a, shape) for a in arrays], axis=-1)


def flip_green(normal: np.ndarray) -> np.ndarray:
    """OpenGL <-> DirectX tangent-space normal map: the green (Y) channel inverted."""
    flipped = np.array(normal, dtype=np.float32)
    flipped[..., 1] = 1.0 - flipped[..., 1]
    return flipped


def roughness_to_smoothness(roughness: np.ndarray) -> np.ndarray:
    """Unity's smoothness is 1 - roughness (perceptual roughness, as the maps hold)."""
    return 1.0 - np.asarray(roughness, dtype=np.float32)


def stretch_direction(angle: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The (x, y) components, in [-1, 1], of the unit direction the highlight stretches along
    (x along +u, y along +v) for an anisotropy angle map (H, W): the brushing direction, in turns,
    plus a quarter turn."""
    radians = 2 * np.pi * (np.asarray(angle, dtype=np.float32) + ANISOTROPY_TANGENT_TURN)
    return np.cos(radians).astype(np.float32), np.sin(radians).astype(np.float32)


def _anisotropy_files(preset: str, level: np.ndarray, angle) -> list[PackedMap]:
    """The anisotropy files of ``preset`` (see the module docstring) for a level map (H, W) and an
    angle map (H, W) or a constant angle."""
    x, y = stretch_direction(np.broadcast_to(np.asarray(angle, dtype=np.float32), level.shape))
    if preset == "gltf":
        return [PackedMap("_anisotropy", pack_channels([x * 0.5 + 0.5, y * 0.5 + 0.5, level]))]
    tangent = pack_channels([x * 0.5 + 0.5, y * 0.5 + 0.5, 0.5])
    return [PackedMap("_Anisotropy", level[..., None]),
            PackedMap("_Tangent", flip_green(tangent) if preset == "unreal" else tangent)]


def pack_preset(preset: str, maps: dict) -> list[PackedMap]:
    """The files of ``preset`` from ``maps``: usage -> array, base colour and normal (H, W, 3),
    the others (H, W); "height", "ambientocclusion" and the anisotropy level and angle may be
    absent."""
    _check_choice("export preset", preset, PRESETS)
    missing = [u for u in REQUIRED if u not in maps]
    if missing:
        raise ExportError(f"cannot export without the {', '.join(missing)} map")
    color, normal, roughness, metallic = (maps[u] for u in REQUIRED)
    ao = maps.get("ambientocclusion")
    occlusion = 1.0 if ao is None else ao
    anisotropy = [] if ANISOTROPY not in maps else _anisotropy_files(preset, maps[ANISOTROPY],
                                                                      maps.get(ANISOTROPY_ANGLE, 0.0))
    if preset == "gltf":
        return [PackedMap("_baseColor", color, srgb=True),
                PackedMap("_metallicRoughness", pack_channels([occlusion, roughness, metallic])),
                PackedMap("_normal", normal), *anisotropy]
    if preset == "unreal":
        return [PackedMap("_BaseColor", color, srgb=True),
                PackedMap("_Normal", flip_green(normal)),
                PackedMap("_ORM", pack_channels([occlusion, roughness, metallic])), *anisotropy]
    packed = [PackedMap("_Albedo", color, srgb=True),
              PackedMap("_MetallicSmoothness",
                        pack_channels([metallic, occlusion, 1.0, roughness_to_smoothness(roughness)])),
              PackedMap("_Normal", normal)]
    if "height" in maps:
        packed.append(PackedMap("_Height", maps["height"][..., None]))
    if ao is not None:
        packed.append(PackedMap("_Occlusion", ao[..., None]))
    return packed + anisotropy


def export_maps(result_dir, out_dir, preset, size=None, bits=8, file_format="PNG", name=None,
                overwrite=False) -> list[Path]:
    """Write the result's maps as ``preset``'s files into ``out_dir``; returns their paths.

    ``size``: resize every map to ``size`` x ``size`` pixels (default: the result's size).
    ``name``: the files' stem (default: the graph's name).
    """
    import bpy  # here, not at the top: the packing helpers serve without Blender

    _check_choice("export preset", preset, PRESETS)
    _check_choice("file format", file_format, EXTENSIONS)
    if bits not in BITS[file_format]:
        raise ExportError(f"{file_format} is written at {' or '.join(map(str, BITS[file_format]))} bits, not {bits}")
    if size is not None and not (isinstance(size, int) and size > 0):
        raise ExportError(f"export size must be a positive number of pixels, not {size!r}")
    report = read_report(result_dir)
    stem = _file_stem(name or graph_name(report, result_dir))
    usages = REQUIRED + tuple(u for u in OPTIONAL if u in report["maps"])
    paths = {u: map_path(result_dir, report, u) for u in usages}

    maps = {u: _read_map(bpy, path, size, gray=u not in ("basecolor", "normal")) for u, path in paths.items()}
    packed = pack_preset(preset, maps)
    out_dir = Path(out_dir)
    targets = [out_dir / f"{stem}{p.suffix}{EXTENSIONS[file_format]}" for p in packed]
    existing = [str(t) for t in targets if t.exists()]
    if existing and not overwrite:
        raise ExportError(f"{existing[0]}: already exists (pass overwrite to replace it)")
    out_dir.mkdir(parents=True, exist_ok=True)
    scene = bpy.data.scenes.new("blender_match export")
    try:
        scene.render.dither_intensity = 0.0  # exact values, not noise, in 8-bit files
        settings = scene.render.image_settings
        settings.file_format = file_format
        settings.color_depth = str(bits)
        for item, target in zip(packed, targets):
            pixels = srgb_to_linear(item.pixels) if item.srgb and file_format == "OPEN_EXR" else item.pixels
            _write_image(bpy, scene, pixels, target)
    finally:
        bpy.data.scenes.remove(scene)
    return targets


def _check_choice(what: str, value, choices):
    if value not in choices:
        raise ExportError(f"unknown {what} {value!r} (one of {', '.join(choices)})")


def _file_stem(name: str) -> str:
    """``name`` safe as a file name on every system (runs of other characters become "_")."""
    stem = re.sub(r"[^\w.-]+", "_", name).strip("._")
    if not stem:
        raise ExportError(f"{name!r} gives no usable file name")
    return stem


def _read_map(bpy, path: Path, size, gray: bool) -> np.ndarray:
    """A map file's values as stored ((H, W) or (H, W, 3)), through a temporary image that is
    removed afterwards (loaded anew, so a user's image of the same file is never touched)."""
    image = bpy.data.images.load(str(path), check_existing=False)
    try:
        image.colorspace_settings.name = "Non-Color"  # the file's own values, no conversion
        if size is not None:
            image.scale(size, size)
        width, height = image.size
        pixels = np.empty(width * height * image.channels, dtype=np.float32)
        image.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(image)
    pixels = pixels.reshape(height, width, -1)
    return pixels[..., 0] if gray else pixels[..., :3]


def _write_image(bpy, scene, pixels: np.ndarray, path: Path):
    """Write (H, W, C) values as stored data (no colour conversion) through a temporary image,
    under a temporary name renamed to ``path``."""
    height, width, channels = pixels.shape
    rgba = np.ones((height, width, 4), dtype=np.float32)
    rgba[..., :3] = pixels[..., :3] if channels >= 3 else pixels[..., :1]
    if channels == 4:
        rgba[..., 3] = pixels[..., 3]
        if scene.render.image_settings.file_format == "PNG":
            # Blender un-premultiplies float images when writing PNG (leaving alpha-0 pixels
            # alone), so premultiply to get the packed channels back unchanged.
            alpha = rgba[..., 3:]
            rgba[..., :3] = np.where(alpha > 0, rgba[..., :3] * alpha, rgba[..., :3])
    scene.render.image_settings.color_mode = _COLOR_MODES[channels]
    image = bpy.data.images.new("blender_match export", width, height, alpha=channels == 4,
                                float_buffer=True, is_data=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.", suffix=path.suffix)
    os.close(fd)
    try:
        image.pixels.foreach_set(rgba.ravel())
        try:
            image.save_render(tmp, scene=scene)
        except RuntimeError as exc:
            raise ExportError(f"{path}: cannot be written ({str(exc).strip().splitlines()[-1]})") from None
        os.replace(tmp, path)
    finally:
        bpy.data.images.remove(image)
        Path(tmp).unlink(missing_ok=True)
