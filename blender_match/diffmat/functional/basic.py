"""The simplest atomic nodes: Uniform Color and the pass-through (Dot) node."""
from __future__ import annotations

import torch

from .common import param2d

__all__ = ["uniform_color", "passthrough"]


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
