"""Known-value tests of Transformation 2D (functional/transform.py)."""
from __future__ import annotations

import pytest
import torch
import torch.nn.functional as TF
from imagecheck import smooth_tiling_image

from blender_match.diffmat import DiffMatError, EvalContext, F, Node


@pytest.mark.parametrize("channels", [1, 4])
def test_identity_and_integer_offset_is_a_roll(channels):
    n = 16
    img = smooth_tiling_image(channels, n, seed=1)
    torch.testing.assert_close(F.transformation_2d(img), img, atol=1e-6, rtol=0)
    out = F.transformation_2d(img, offset=(3 / n, 5 / n))
    torch.testing.assert_close(out, torch.roll(img, (5, 3), dims=(-2, -1)), atol=1e-5, rtol=0)
    out = F.transformation_2d(img, offset=(-0.25, 1.0))
    torch.testing.assert_close(out, torch.roll(img, -4, dims=-1), atol=1e-5, rtol=0)


def test_half_pixel_offset_is_the_mean_of_two_neighbours():
    n = 16
    img = smooth_tiling_image(1, n, seed=2)
    out = F.transformation_2d(img, offset=(0.5 / n, 0.0))
    torch.testing.assert_close(out, 0.5 * (img + torch.roll(img, 1, dims=-1)), atol=1e-5, rtol=0)


@pytest.mark.parametrize("channels", [1, 4])
def test_matrix_2_tiles_the_input_twice(channels):
    n = 16
    img = smooth_tiling_image(channels, n, seed=3)
    out = F.transformation_2d(img, matrix22=(2.0, 0.0, 0.0, 2.0))
    torch.testing.assert_close(out[..., : n // 2, :], out[..., n // 2:, :], atol=1e-6, rtol=0)
    torch.testing.assert_close(out[..., :, : n // 2], out[..., :, n // 2:], atol=1e-6, rtol=0)
    # about the centre: each copy is the input box-filtered to half size, centred on the image
    expected = torch.roll(TF.avg_pool2d(img, 2).repeat(1, 1, 2, 2), (n // 4, n // 4), dims=(-2, -1))
    torch.testing.assert_close(out, expected, atol=1e-5, rtol=0)
    # without mipmaps the same (a 2x minification samples between two texels = their box mean)
    manual = F.transformation_2d(img, matrix22=(2.0, 0.0, 0.0, 2.0), mipmapmode=1, manualmiplevel=0)
    torch.testing.assert_close(manual, expected, atol=1e-5, rtol=0)


def test_matrix_4_uses_the_mip_pyramid():
    n = 16
    img = smooth_tiling_image(1, n, seed=4, octaves=7)
    out = F.transformation_2d(img, matrix22=(4.0, 0.0, 0.0, 4.0))
    torch.testing.assert_close(out.mean(), img.mean(), atol=1e-5, rtol=0)
    expected = torch.roll(TF.avg_pool2d(img, 4).repeat(1, 1, 4, 4), (n // 8 * 3, n // 8 * 3), dims=(-2, -1))
    # sampled at level 2 (4x4 box means), exactly at its texel centres
    lvl2 = F.transformation_2d(img, matrix22=(4.0, 0.0, 0.0, 4.0), mipmapmode=1, manualmiplevel=2)
    torch.testing.assert_close(out, lvl2, atol=1e-6, rtol=0)
    torch.testing.assert_close(out, expected, atol=1e-5, rtol=0)


def test_quarter_turn_matrix_is_rot90():
    n = 16
    img = smooth_tiling_image(1, n, seed=5)
    out = F.transformation_2d(img, matrix22=(0.0, -1.0, 1.0, 0.0))
    # out(u, v) = in(0.5 - (v - 0.5), 0.5 + (u - 0.5)): out[j, i] = in[i, n-1-j]
    expected = torch.rot90(img, k=1, dims=(-2, -1))
    torch.testing.assert_close(out, expected, atol=1e-5, rtol=0)
    assert torch.allclose(out[0, 0, 2, 3], img[0, 0, 3, n - 1 - 2], atol=1e-5)


def test_nearest_filtering_snaps_to_texels():
    n = 16
    img = smooth_tiling_image(4, n, seed=6)
    out = F.transformation_2d(img, offset=(1.4 / n, 0.0), filtering=1)
    torch.testing.assert_close(out, torch.roll(img, 1, dims=-1), atol=1e-6, rtol=0)


def test_offset_is_differentiable_and_batched():
    img = smooth_tiling_image(4, 16, seed=7)
    off = torch.tensor([[0.01, 0.02], [0.3, -0.2]], requires_grad=True)
    out = F.transformation_2d(img, offset=off)
    assert out.shape == (2, 4, 16, 16)
    torch.testing.assert_close(out[1:], F.transformation_2d(img, offset=(0.3, -0.2)), atol=1e-6, rtol=0)
    out.square().sum().backward()
    assert (off.grad.abs() > 0).all()


def test_node_keeps_the_matrix_fixed_and_rejects_bad_values():
    node = Node("transformation", {"matrix22": (2.0, 0.0, 0.0, 2.0)})
    assert not node.theta["matrix22"].requires_grad
    assert node.theta["offset"].requires_grad
    with pytest.raises(DiffMatError):
        Node("transformation", {"filtering": 3})
    with pytest.raises(DiffMatError):
        F.transformation_2d(torch.rand(1, 4, 16, 16), filtering=7)
    with pytest.raises(DiffMatError):
        F.transformation_2d(torch.rand(1, 4, 16, 16), matrix22=(1.0, 0.0))
    with pytest.raises(DiffMatError):
        node(torch.rand(1, 2, 16, 16), ctx=EvalContext(size=16))
