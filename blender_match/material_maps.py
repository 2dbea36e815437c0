"""Material maps as files (the file, channels and bit depth of each: ``vocabulary.OUTPUTS``) and
flat-map detection.

Maps are (1, C, H, W) tensors from a MaterialGraph: base colour RGBA/gray (sRGB-encoded, as
Substance outputs it), normal RGBA in OpenGL convention, roughness, metallic, height, ambient
occlusion grayscale. A map whose every pixel is within 1/512 of its mean is *flat*: callers may
write a constant instead of a texture (model no more than the scene needs).
"""
from __future__ import annotations

from pathlib import Path

import torch

from .image_files import write_png
from .safe_files import FileWriteError
from .vocabulary import OUTPUTS

FLAT_TOLERANCE = 1.0 / 512


def to_channels(img: torch.Tensor, channels: int) -> torch.Tensor:
    """Gray→RGB by repetition, RGBA→RGB by dropping alpha, colour→gray by the mean of RGB."""
    if channels == 3:
        return img[:, :3] if img.shape[1] >= 3 else img.expand(-1, 3, -1, -1)
    return img if img.shape[1] == 1 else img[:, :3].mean(dim=1, keepdim=True)


def flat_value(img: torch.Tensor) -> list[float] | None:
    """The map's constant value (per channel) if it is flat, else None."""
    mean = img.mean(dim=(0, 2, 3))
    if (img - mean[None, :, None, None]).abs().max() <= FLAT_TOLERANCE:
        return [round(float(v), 4) for v in mean]
    return None


def write_maps(maps: dict[str, torch.Tensor], out_dir: Path, overwrite: bool = False) -> dict:
    """Write every map of ``maps`` into ``out_dir``; returns {usage: {"file", "flat"}}.

    Checks every target first, so a refused overwrite writes nothing.
    """
    out_dir = Path(out_dir)
    targets = {u: out_dir / OUTPUTS[u].file for u in maps if u in OUTPUTS}
    if not overwrite:
        existing = [str(p) for p in targets.values() if p.exists()]
        if existing:
            raise FileWriteError(f"{existing[0]}: already exists (use --overwrite to replace it)")
    written = {}
    for usage, path in targets.items():
        output = OUTPUTS[usage]
        img = to_channels(maps[usage].detach()[:1].float().cpu(), output.file_channels)
        write_png(path, img, bits=output.bits, overwrite=True)
        written[usage] = {"file": path.name, "flat": flat_value(img)}
    return written
