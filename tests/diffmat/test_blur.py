"""Known-value tests of Blur, Directional Blur and Sharpen (functional/blur.py)."""
from __future__ import annotations

import pytest
import torch
from imagecheck import smooth_tiling_image

from blender_match.diffmat import DiffMatError, EvalContext, F, Node


def checker(n: int, channels: int = 1) -> torch.Tensor:
    y, x = torch.meshgrid(torch.arange(n), torch.arange(n), indexing="ij")
    c = ((x + y) % 2).float()[None, None]
    return c.expand(1, channels, n, n).clone()


def dot(n: int, y: int = 0, x: int = 0, channels: int = 1) -> torch.Tensor:
    img = torch.zeros(1, channels, n, n)
    img[..., y, x] = 1.0
    return img


@pytest.mark.parametrize("channels", [1, 4])
def test_blur_zero_intensity_is_identity(channels):
    img = smooth_tiling_image(channels, 16, seed=1)
    torch.testing.assert_close(F.blur(img, intensity=0.0), img, atol=1e-6, rtol=0)


@pytest.mark.parametrize("channels", [1, 4])
def test_blur_preserves_mean_and_flattens_a_checker(channels):
    img = checker(16, channels)
    # one pixel at 16 px is intensity 16 (pixels of a 256-px image): kernel [1/4, 1/2, 1/4] per axis
    out = F.blur(img, intensity=16.0)
    torch.testing.assert_close(out, torch.full_like(out, 0.5), atol=1e-5, rtol=0)
    img = smooth_tiling_image(channels, 32, seed=2)
    out = F.blur(img, intensity=37.0)
    torch.testing.assert_close(out.mean(dim=(-1, -2)), img.mean(dim=(-1, -2)), atol=1e-5, rtol=0)
    assert out.std() < img.std()


def test_blur_of_a_dot_is_a_wrapping_square_box():
    n = 32
    out = F.blur(dot(n), intensity=16.0)   # box [-2, 2] px at 32 px: taps 1/2, 1, 1, 1, 1/2 per axis
    taps = torch.tensor([0.5, 1.0, 1.0, 1.0, 0.5]) / 4
    expected = torch.zeros(n, n)
    idx = torch.tensor([-2, -1, 0, 1, 2]) % n
    expected[idx[:, None], idx[None, :]] = taps[:, None] * taps[None, :]
    torch.testing.assert_close(out[0, 0], expected, atol=1e-6, rtol=0)


def test_blur_scales_with_resolution():
    small = F.blur(dot(32), intensity=16.0)
    big = F.blur(dot(64), intensity=16.0)
    assert (small[0, 0, 0] > 1e-6).sum() == 5          # half-width 2 px at 32
    assert (big[0, 0, 0] > 1e-6).sum() == 9            # half-width 4 px at 64


def test_blur_fractional_intensity_is_differentiable():
    k = torch.tensor([28.0], requires_grad=True)       # 1.75 px at 16: taps 1, 1, 1/4 (of 3.5)
    out = F.blur(dot(16), intensity=k)
    row = out[0, 0, 0]
    torch.testing.assert_close(row[:3], torch.tensor([1.0, 1.0, 0.25]) / 3.5 / 3.5, atol=1e-6, rtol=0)
    assert row[3] == 0
    out[0, 0, 0, 0].backward()
    assert k.grad is not None and k.grad.item() < 0    # a wider box lowers the centre


def test_blur_batched_intensity():
    img = smooth_tiling_image(4, 16, seed=3)
    out = F.blur(img, intensity=torch.tensor([[4.0], [20.0]]))
    assert out.shape == (2, 4, 16, 16)
    torch.testing.assert_close(out[1:], F.blur(img, intensity=20.0), atol=1e-6, rtol=0)


@pytest.mark.parametrize("channels", [1, 4])
def test_directional_blur_horizontal_and_vertical(channels):
    n = 32
    img = dot(n, 5, 7, channels)
    horiz = F.directional_blur(img, intensity=16.0, mblurangle=0.0)    # half-length 2 px
    assert horiz[..., 5, :].sum(dim=-1).allclose(torch.ones(1, channels), atol=1e-5)
    assert horiz[..., :5, :].abs().max() < 1e-6 and horiz[..., 6:, :].abs().max() < 1e-6
    row = horiz[0, 0, 5]
    torch.testing.assert_close(row[7 - 2], row[7 + 2])             # symmetric
    assert row[7 - 3] < 1e-6 and row[7 + 3] < 1e-6 and row[7] > 0.15
    vert = F.directional_blur(img, intensity=16.0, mblurangle=0.25)
    torch.testing.assert_close(vert[..., :, 7], horiz[..., 5, :].roll(5 - 7, dims=-1), atol=1e-5, rtol=0)
    half = F.directional_blur(img, intensity=16.0, mblurangle=0.5)
    torch.testing.assert_close(half, horiz, atol=1e-5, rtol=0)


def test_directional_blur_wraps_and_keeps_mean():
    img = dot(16, 0, 0)
    out = F.directional_blur(img, intensity=32.0, mblurangle=0.125)   # diagonal, 2 px
    assert out[0, 0, -1, -1] > 0.1 and out[0, 0, 1, 1] > 0.1      # both ends of the diagonal
    torch.testing.assert_close(out.sum(), torch.tensor(1.0), atol=1e-5, rtol=0)
    assert out[0, 0, 0, 8] < 1e-6


def test_directional_blur_zero_is_identity_and_angle_differentiable():
    img = smooth_tiling_image(4, 16, seed=4)
    torch.testing.assert_close(F.directional_blur(img, intensity=0.0, mblurangle=0.3), img, atol=1e-5, rtol=0)
    a = torch.tensor([0.1], requires_grad=True)
    F.directional_blur(img, intensity=20.0, mblurangle=a).square().sum().backward()
    assert a.grad is not None and a.grad.abs().item() > 0


def test_sharpen_matches_the_laplacian_formula_at_256():
    img = smooth_tiling_image(1, 256, seed=5, octaves=12) * 0.5 + 0.25
    out = F.sharpen(img, intensity=0.5)
    mean4 = (img.roll(1, -1) + img.roll(-1, -1) + img.roll(1, -2) + img.roll(-1, -2)) / 4
    expected = (img + 0.5 * (img - mean4)).clamp(0, 1)
    torch.testing.assert_close(out, expected, atol=1e-5, rtol=0)


def test_sharpen_uses_two_pixel_neighbours_at_512_and_is_identity_at_zero():
    img = smooth_tiling_image(4, 512, seed=6, octaves=8) * 0.5 + 0.25
    out = F.sharpen(img, intensity=1.0)
    mean4 = (img.roll(2, -1) + img.roll(-2, -1) + img.roll(2, -2) + img.roll(-2, -2)) / 4
    torch.testing.assert_close(out, (2 * img - mean4).clamp(0, 1), atol=1e-5, rtol=0)
    torch.testing.assert_close(F.sharpen(img, intensity=0.0), img, atol=1e-5, rtol=0)
    flat = torch.full((1, 1, 16, 16), 0.3)
    torch.testing.assert_close(F.sharpen(flat, intensity=3.0), flat, atol=1e-6, rtol=0)


def test_sharpen_increases_contrast():
    img = checker(16) * 0.5 + 0.25
    out = F.sharpen(img, intensity=0.2)
    assert out.std() > img.std()


@pytest.mark.parametrize("name", ["blur", "dirmotionblur", "sharpen"])
def test_blur_family_nodes_reject_bad_input(name):
    node = Node(name)
    with pytest.raises(DiffMatError):
        node(torch.rand(1, 3, 16, 16), ctx=EvalContext(size=16))
    with pytest.raises(DiffMatError):
        F.blur(torch.rand(16, 16))
    with pytest.raises(DiffMatError):
        Node(name, {"intensity": -5.0})
