"""Known-value tests of Warp and Directional Warp (functional/warp.py)."""
from __future__ import annotations

import pytest
import torch
from imagecheck import smooth_tiling_image

from blender_match.diffmat import DiffMatError, EvalContext, F, Node


@pytest.mark.parametrize("channels", [1, 4])
def test_warp_zero_intensity_or_flat_gradient_is_identity(channels):
    img = smooth_tiling_image(channels, 16, seed=1)
    grad = smooth_tiling_image(1, 16, seed=2)
    torch.testing.assert_close(F.warp(img, grad, intensity=0.0), img, atol=1e-6, rtol=0)
    flat = torch.full((1, 1, 16, 16), 0.7)
    torch.testing.assert_close(F.warp(img, flat, intensity=20.0), img, atol=1e-6, rtol=0)


def test_warp_on_a_ramp_moves_content_down_the_slope():
    n = 16
    img = smooth_tiling_image(4, n, seed=3)
    ramp = (torch.arange(n, dtype=torch.float32) / n).reshape(1, 1, 1, n).expand(1, 1, n, n)
    # slope 1 per image width; intensity 16 displaces by 16 / 256 of the width = 1 px at 16 px
    out = F.warp(img, ramp, intensity=16.0)
    expected = torch.roll(img, -1, dims=-1)            # out(p) = in(p + 1 px): content moves left, downhill
    inner = slice(1, n - 1)                            # the ramp's wrap seam has another slope
    torch.testing.assert_close(out[..., inner], expected[..., inner], atol=1e-5, rtol=0)
    vramp = ramp.transpose(-1, -2)
    out = F.warp(img, vramp, intensity=32.0)           # 2 px downwards in v
    torch.testing.assert_close(out[..., inner, :], torch.roll(img, -2, dims=-2)[..., inner, :], atol=1e-5, rtol=0)


def test_warp_is_translation_equivariant_so_it_tiles():
    img = smooth_tiling_image(4, 32, seed=4)
    grad = smooth_tiling_image(1, 32, seed=5)
    out = F.warp(img, grad, intensity=3.0)
    shifted = F.warp(img.roll((5, 9), (-2, -1)), grad.roll((5, 9), (-2, -1)), intensity=3.0)
    torch.testing.assert_close(shifted.roll((-5, -9), (-2, -1)), out, atol=1e-5, rtol=0)


def test_warp_batched_and_differentiable():
    img = smooth_tiling_image(1, 16, seed=6)
    grad = smooth_tiling_image(1, 16, seed=7)
    k = torch.tensor([[1.0], [4.0]], requires_grad=True)
    out = F.warp(img, grad, intensity=k)
    assert out.shape == (2, 1, 16, 16)
    torch.testing.assert_close(out[1:], F.warp(img, grad, intensity=4.0), atol=1e-6, rtol=0)
    out.square().sum().backward()
    assert torch.isfinite(k.grad).all() and (k.grad.abs() > 0).all()


@pytest.mark.parametrize("channels", [1, 4])
def test_directional_warp_with_a_constant_map_is_a_shift(channels):
    n = 16
    img = smooth_tiling_image(channels, n, seed=8)
    ones = torch.ones(1, 1, n, n)
    # intensity 32 at 16 px = 2 px; angle in turns, clockwise on screen (v grows downwards)
    right = F.directional_warp(img, ones, intensity=32.0, warpangle=0.0)
    torch.testing.assert_close(right, torch.roll(img, 2, dims=-1), atol=1e-5, rtol=0)
    down = F.directional_warp(img, ones, intensity=32.0, warpangle=0.25)
    torch.testing.assert_close(down, torch.roll(img, 2, dims=-2), atol=1e-5, rtol=0)
    left = F.directional_warp(img, ones, intensity=32.0, warpangle=0.5)
    torch.testing.assert_close(left, torch.roll(img, -2, dims=-1), atol=1e-5, rtol=0)
    half = F.directional_warp(img, ones * 0.5, intensity=32.0, warpangle=0.0)
    torch.testing.assert_close(half, torch.roll(img, 1, dims=-1), atol=1e-5, rtol=0)


def test_directional_warp_follows_the_intensity_map():
    n = 16
    img = smooth_tiling_image(1, n, seed=9)
    m = torch.zeros(1, 1, n, n)
    m[..., : n // 2, :] = 1.0                           # top half moves, bottom half stays
    out = F.directional_warp(img, m, intensity=16.0, warpangle=0.0)
    torch.testing.assert_close(out[..., : n // 2, :], torch.roll(img, 1, dims=-1)[..., : n // 2, :], atol=1e-5, rtol=0)
    torch.testing.assert_close(out[..., n // 2:, :], img[..., n // 2:, :], atol=1e-6, rtol=0)


def test_directional_warp_gradients_and_batch():
    img = smooth_tiling_image(4, 16, seed=10)
    m = smooth_tiling_image(1, 16, seed=11)
    a = torch.tensor([[0.1], [0.3]], requires_grad=True)
    out = F.directional_warp(img, m, intensity=20.0, warpangle=a)
    assert out.shape == (2, 4, 16, 16)
    torch.testing.assert_close(out[:1], F.directional_warp(img, m, intensity=20.0, warpangle=0.1), atol=1e-6, rtol=0)
    out.square().sum().backward()
    assert (a.grad.abs() > 0).all()


@pytest.mark.parametrize("name", ["warp", "directionalwarp"])
def test_warp_nodes_reject_bad_input(name):
    node = Node(name)
    img = torch.rand(1, 4, 16, 16)
    with pytest.raises(DiffMatError):
        node(img, torch.rand(1, 4, 16, 16), ctx=EvalContext(size=16))       # second input must be gray
    with pytest.raises(DiffMatError):
        node(img, ctx=EvalContext(size=16))                                # missing input
    with pytest.raises(DiffMatError):
        F.warp(img, torch.rand(1, 3, 16, 16))
