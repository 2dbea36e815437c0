"""Image checks used across tests: seams, smooth tiling inputs, box downsampling."""
from __future__ import annotations

import math

import torch
import torch.nn.functional as F


def smooth_tiling_image(channels: int, size: int, seed: int = 0, dtype=torch.float32, octaves: int = 3) -> torch.Tensor:
    """A random image that tiles: a sum of random low-frequency Fourier modes, scaled to [0.05, 0.95]."""
    g = torch.Generator().manual_seed(seed)
    c = torch.arange(size, dtype=torch.float64) / size
    y, x = torch.meshgrid(c, c, indexing="ij")
    out = torch.zeros(channels, size, size, dtype=torch.float64)
    for ch in range(channels):
        for _ in range(octaves * 3):
            fx, fy = torch.randint(-octaves, octaves + 1, (2,), generator=g).tolist()
            phase = torch.rand((), generator=g, dtype=torch.float64) * math.tau
            out[ch] += torch.cos(math.tau * (fx * x + fy * y) + phase)
    lo = out.amin(dim=(1, 2), keepdim=True)
    hi = out.amax(dim=(1, 2), keepdim=True)
    out = 0.05 + 0.9 * (out - lo) / (hi - lo + 1e-12)
    if channels == 4:
        out[3] = 1.0
    return out[None].to(dtype)


def seam_jumps(img: torch.Tensor) -> tuple[float, float]:
    """(largest jump across the wrap edges, largest jump between neighbours inside), horizontally
    and vertically together."""
    inside = max((img[..., 1:] - img[..., :-1]).abs().max().item(),
                 (img[..., 1:, :] - img[..., :-1, :]).abs().max().item())
    wrap = max((img[..., 0] - img[..., -1]).abs().max().item(),
               (img[..., 0, :] - img[..., -1, :]).abs().max().item())
    return wrap, inside


def assert_tiles(img: torch.Tensor, slack: float = 1e-5):
    """The jump across the wrap edges is no larger than the jumps inside.

    In a periodic image the wrap pair is one neighbour pair among the others, so it can be the
    largest by chance; a margin of half the largest inner jump allows that, while an image that
    does not tile (a ramp, an unwrapped filter) jumps across its edges many times more.
    """
    wrap, inside = seam_jumps(img)
    assert wrap <= 1.5 * inside + slack, f"seam jump {wrap:.4f} exceeds the largest inner jump {inside:.4f}"


def box_down(img: torch.Tensor, factor: int = 2) -> torch.Tensor:
    return F.avg_pool2d(img, factor)
