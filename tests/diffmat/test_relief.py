"""Known-value tests of Normal and Emboss (functional/relief.py)."""
from __future__ import annotations

import math

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F


def _ramp_u(size: int, slope: float = 1.0) -> torch.Tensor:
    """Height growing to the right by ``slope`` per texture unit (interior pixels; it wraps at the edge)."""
    u = (torch.arange(size, dtype=torch.float32) + 0.5) / size
    return (0.1 + slope * 0.8 * u)[None, None, None, :].expand(1, 1, size, size).contiguous()


INNER = slice(2, -2)


def test_flat_height_gives_straight_up_normal():
    out = F.height_to_normal(torch.full((1, 1, 4, 4), 0.3), input2alpha=False)
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor([0.5, 0.5, 1.0, 1.0]))


def test_normal_of_a_linear_ramp():
    size = 16
    h = _ramp_u(size)                      # slope 0.8 per texture unit
    out = F.height_to_normal(h, intensity=256 / 0.8)   # s * dh/du = 1 -> n = (-1, 0, 1) / sqrt 2
    r = 1 / math.sqrt(2)
    inner = out[0, :, :, INNER]
    torch.testing.assert_close(inner[0], torch.full_like(inner[0], 0.5 - 0.5 * r), atol=1e-5, rtol=0)
    torch.testing.assert_close(inner[1], torch.full_like(inner[1], 0.5), atol=1e-5, rtol=0)
    torch.testing.assert_close(inner[2], torch.full_like(inner[2], 0.5 + 0.5 * r), atol=1e-5, rtol=0)
    torch.testing.assert_close(out[0, 3], h[0, 0])                       # input2alpha: height in alpha


def test_normal_format_flips_green():
    size = 16
    h = _ramp_u(size).transpose(-1, -2)     # height grows downwards (towards +v)
    r = 1 / math.sqrt(2)
    opengl = F.height_to_normal(h, intensity=256 / 0.8, inversedy=True)[0, 1, INNER, :]
    directx = F.height_to_normal(h, intensity=256 / 0.8, inversedy=False)[0, 1, INNER, :]
    # the slope faces the top of the image: OpenGL's green (y up) is high, DirectX's low
    torch.testing.assert_close(opengl, torch.full_like(opengl, 0.5 + 0.5 * r), atol=1e-5, rtol=0)
    torch.testing.assert_close(directx, torch.full_like(directx, 0.5 - 0.5 * r), atol=1e-5, rtol=0)


def test_normal_is_resolution_independent_and_batched():
    small = F.height_to_normal(_ramp_u(16), intensity=50.0)[0, :3, 0, 8]
    big = F.height_to_normal(_ramp_u(64), intensity=50.0)[0, :3, 0, 32]
    torch.testing.assert_close(small, big, atol=1e-5, rtol=0)
    out = F.height_to_normal(_ramp_u(16), intensity=torch.tensor([[0.0], [50.0]]), input2alpha=False)
    assert out.shape == (2, 4, 16, 16)
    torch.testing.assert_close(out[0, :, 5, 5], torch.tensor([0.5, 0.5, 1.0, 1.0]))
    assert out[1, 0, 5, 5] < 0.5


def test_normal_rejects_color_input():
    with pytest.raises(DiffMatError):
        F.height_to_normal(torch.rand(1, 4, 4, 4))
    with pytest.raises(DiffMatError):
        Node("normal")(torch.rand(1, 4, 4, 4), ctx=EvalContext(size=4))


def test_emboss_flat_height_keeps_input():
    img = torch.rand(1, 4, 8, 8, generator=torch.Generator().manual_seed(1))
    out = F.emboss(img, torch.full((1, 1, 8, 8), 0.4))
    torch.testing.assert_close(out, img)


def test_emboss_lit_and_shadowed_slopes():
    size = 16
    h = _ramp_u(size).flip(-1)               # height falls to the right: the slope faces right
    x = torch.full((1, 1, size, size), 0.4)
    # k = intensity / 256 * 0.8 = 0.5
    lit = F.emboss(x, h, intensity=160.0, lightangle=0.0)[0, 0, :, INNER]      # light from the right
    torch.testing.assert_close(lit, torch.full_like(lit, 0.4 + 0.5 * (1 - 0.4)), atol=1e-5, rtol=0)
    dark = F.emboss(x, h, intensity=160.0, lightangle=0.5)[0, 0, :, INNER]     # light from the left
    torch.testing.assert_close(dark, torch.full_like(dark, 0.4 * 0.5), atol=1e-5, rtol=0)
    side = F.emboss(x, h, intensity=160.0, lightangle=0.25)[0, 0, :, INNER]    # light from the top
    torch.testing.assert_close(side, torch.full_like(side, 0.4), atol=1e-5, rtol=0)


def test_emboss_colors_and_alpha():
    size = 16
    h = _ramp_u(size).flip(-1)
    img = torch.cat([torch.full((1, 3, size, size), 0.5), torch.full((1, 1, size, size), 0.7)], dim=1)
    out = F.emboss(img, h, intensity=320.0, lightangle=0.0, highlightcolor=(1.0, 0.0, 0.2, 1.0))
    # k = 1: the colour becomes the highlight colour; alpha is kept
    torch.testing.assert_close(out[0, :, 5, 8], torch.tensor([1.0, 0.0, 0.2, 0.7]), atol=1e-5, rtol=0)
    out = F.emboss(img, h, intensity=320.0, lightangle=0.5, shadowcolor=(0.0, 0.0, 1.0, 0.0))
    torch.testing.assert_close(out[0, :, 5, 8], torch.tensor([0.0, 0.0, 1.0, 0.7]), atol=1e-5, rtol=0)
    with pytest.raises(DiffMatError, match="inputgradient"):
        F.emboss(img, torch.rand(1, 1, 8, 8))
