"""The simplest nodes: Uniform Color, the pass-through (Dot) node and PBR Metal Reflectance."""
from __future__ import annotations

import torch

from ..errors import DiffMatError
from .common import param2d

__all__ = ["uniform_color", "passthrough", "metal_reflectance"]

# PBR Metal Reflectance's metals in the order of its "Metal Color" list (Substance's documentation),
# each the metal's reflectance at normal incidence (F0), sRGB-encoded as a base colour is: the
# measured linear values published for physically based shading (Gold 1.000 0.766 0.336, Silver
# 0.972 0.960 0.915, Aluminium 0.913 0.921 0.925, Iron 0.560 0.570 0.580, Copper 0.955 0.637 0.538,
# Titanium 0.542 0.497 0.449, Nickel 0.660 0.609 0.526, Cobalt 0.662 0.655 0.634, Platinum 0.672
# 0.637 0.585) through the sRGB curve
METAL_F0_SRGB = {
    "gold": (1.000, 0.889, 0.615), "silver": (0.988, 0.982, 0.962), "aluminium": (0.961, 0.964, 0.966),
    "iron": (0.774, 0.780, 0.786), "copper": (0.980, 0.819, 0.760), "titanium": (0.762, 0.733, 0.701),
    "nickel": (0.832, 0.803, 0.752), "cobalt": (0.833, 0.829, 0.818), "platinum": (0.839, 0.819, 0.789),
}
METALS = tuple(METAL_F0_SRGB)


def uniform_color(*, outputcolor=(0.0, 0.0, 0.0, 1.0), colorswitch: bool = True, size: int = 512,
                  device=None, dtype=torch.float32) -> torch.Tensor:
    """A flat image of ``outputcolor`` (RGBA), or of its first component when ``colorswitch`` is off
    (grayscale). Returns (B|1, 4 or 1, size, size); B when ``outputcolor`` is batched (B, 4)."""
    color = param2d(outputcolor).to(device=device, dtype=dtype)
    color = color if colorswitch else color[:, :1]
    return color[:, :, None, None].expand(-1, -1, size, size).clamp(0.0, 1.0)


def passthrough(input: torch.Tensor) -> torch.Tensor:
    """Identity (Substance's Dot node, and the stand-in for a node the translator cannot map)."""
    return input


def metal_reflectance(*, metal_color: int = 0, size: int = 512, device=None, dtype=torch.float32) -> torch.Tensor:
    """PBR Metal Reflectance: a flat base colour of the pure metal ``METALS[metal_color]`` (RGBA)."""
    if isinstance(metal_color, bool) or metal_color not in range(len(METALS)):
        raise DiffMatError(f"pbr_metal_reflectance.metal_color: unknown value {metal_color!r}; "
                           f"expected 0-{len(METALS) - 1} ({', '.join(METALS)})")
    return uniform_color(outputcolor=(*METAL_F0_SRGB[METALS[int(metal_color)]], 1.0), size=size, device=device,
                         dtype=dtype)
