"""Known-value tests of the FX-Map in its tiling form (functional/fxmap.py)."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, F, Node


def pattern(channels=1, n=16, seed=0):
    g = torch.Generator().manual_seed(seed)
    p = torch.rand(1, channels, n, n, generator=g) * 0.8 + 0.1
    if channels == 4:
        p[:, 3] = 1.0
    return p


@pytest.mark.parametrize("mode", [0, 1, 2])
def test_no_jitter_places_identical_tiles(mode):
    p = pattern(1)
    out = F.fx_map(p, size=64, x_amount=4, y_amount=4, blendingmode=mode, background=(0, 0, 0, 1))
    torch.testing.assert_close(out, p.repeat(1, 1, 4, 4), atol=1e-5, rtol=0)


def test_colour_alpha_blend_over_background():
    p = pattern(4)
    p[:, 3, :, :8] = 0.0                                    # left half transparent
    out = F.fx_map(p, size=32, x_amount=2, y_amount=2, blendingmode=2, colorswitch=True,
                   background=(0.2, 0.4, 0.6, 1.0))
    assert out.shape == (1, 4, 32, 32)
    torch.testing.assert_close(out[0, :3, 0, 0], torch.tensor([0.2, 0.4, 0.6]))
    torch.testing.assert_close(out[0, :3, :16, 8:16], p[0, :3, :, 8:], atol=1e-5, rtol=0)
    torch.testing.assert_close(out[..., :16, :16], out[..., 16:, 16:], atol=1e-6, rtol=0)


def test_non_square_grid_and_row_offset():
    p = pattern(1)
    out = F.fx_map(p, size=64, x_amount=4, y_amount=2)     # cells 16 x 32: pattern stretched
    torch.testing.assert_close(out[..., :32, :16], torch.repeat_interleave(p, 2, dim=-2), atol=0.2, rtol=0)
    torch.testing.assert_close(out[..., 1:32:2, :16], out[..., 0:32:2, :16], atol=0.2, rtol=0)
    brick = F.fx_map(p, size=64, x_amount=4, y_amount=4, offset=0.5)
    torch.testing.assert_close(brick[..., 16:32, :], torch.roll(brick[..., :16, :], 8, dims=-1), atol=1e-5, rtol=0)


def test_opacity_and_add_mode_scale_linearly():
    p = pattern(1)
    full = F.fx_map(p, size=32, x_amount=2, y_amount=2)
    half = F.fx_map(p, size=32, x_amount=2, y_amount=2, opacitymult=0.5)
    torch.testing.assert_close(half, 0.5 * full, atol=1e-6, rtol=0)
    bg = F.fx_map(p, size=32, x_amount=2, y_amount=2, opacitymult=0.5, background=(0.25, 0, 0, 1))
    torch.testing.assert_close(bg, (0.25 + 0.5 * full).clamp(0, 1), atol=1e-6, rtol=0)


def test_position_jitter_keeps_every_copy_whole_across_the_edges():
    p = torch.zeros(1, 1, 16, 16)
    p[..., 4:12, 4:12] = 0.5                                # a square smaller than its cell
    out = F.fx_map(p, size=64, x_amount=4, y_amount=4, position_random=0.8, seed=7)
    base = F.fx_map(p, size=64, x_amount=4, y_amount=4)
    assert not torch.allclose(out, base)
    # nothing is lost at the image edges: the copies wrap around (add mode, no overlap at 0.5)
    torch.testing.assert_close(out.sum(), base.sum(), rtol=1e-4, atol=1e-3)
    again = F.fx_map(p, size=64, x_amount=4, y_amount=4, position_random=0.8, seed=7)
    assert torch.equal(out, again)
    other = F.fx_map(p, size=64, x_amount=4, y_amount=4, position_random=0.8, seed=8)
    assert not torch.allclose(out, other)


def test_output_is_translation_consistent_when_it_tiles():
    # a 4 x 4 map rendered at 64 equals the 2 x 2 map of the same jitter-free pattern, repeated
    p = pattern(1)
    four = F.fx_map(p, size=64, x_amount=4, y_amount=4, scale=1.5, rotation=0.1, blendingmode=1)
    two = F.fx_map(p, size=32, x_amount=2, y_amount=2, scale=1.5, rotation=0.1, blendingmode=1)
    torch.testing.assert_close(four, two.repeat(1, 1, 2, 2), atol=1e-5, rtol=0)
    # a single copy larger than the image wraps onto itself: 1 x 1 at 32 repeated = 2 x 2 at 64
    one = F.fx_map(p, size=32, x_amount=1, y_amount=1, scale=1.7, rotation=0.05, blendingmode=0)
    twice = F.fx_map(p, size=64, x_amount=2, y_amount=2, scale=1.7, rotation=0.05, blendingmode=0)
    torch.testing.assert_close(twice, one.repeat(1, 1, 2, 2), atol=1e-5, rtol=0)
    assert (one > 0).all()                                  # the overlapping copy covers everything


def test_max_mode_takes_the_maximum_and_rotation_moves_the_pattern():
    p = pattern(1)
    big = F.fx_map(p, size=32, x_amount=2, y_amount=2, scale=1.8, blendingmode=1)
    add = F.fx_map(p, size=32, x_amount=2, y_amount=2, scale=1.8, blendingmode=0)
    assert (big <= add + 1e-6).all() and (big <= p.max() + 1e-6).all()
    assert (add > big + 0.05).any()                            # overlaps add up
    turned = F.fx_map(p, size=64, x_amount=1, y_amount=1, rotation=0.25)
    torch.testing.assert_close(turned[..., 8:56, 8:56],
                               torch.rot90(F.fx_map(p, size=64, x_amount=1, y_amount=1), k=-1,
                                           dims=(-2, -1))[..., 8:56, 8:56], atol=1e-4, rtol=0)


def test_jitter_amounts_are_differentiable_and_batched():
    p = pattern(4)
    amounts = torch.tensor([[0.2], [0.4]], requires_grad=True)
    out = F.fx_map(p, size=32, x_amount=2, y_amount=2, position_random=amounts, rotation_random=0.1,
                   scale_random=0.2, opacity_random=0.3, blendingmode=2, colorswitch=True, seed=3)
    assert out.shape == (2, 4, 32, 32)
    single = F.fx_map(p, size=32, x_amount=2, y_amount=2, position_random=0.4, rotation_random=0.1,
                      scale_random=0.2, opacity_random=0.3, blendingmode=2, colorswitch=True, seed=3)
    torch.testing.assert_close(out[1:], single, atol=1e-5, rtol=0)
    out.square().sum().backward()
    assert (amounts.grad.abs() > 0).all()


def test_fxmap_node_takes_the_seed_from_context_and_rejects_bad_input():
    node = Node("fxmaps", {"position_random": 0.5})
    p = pattern(1)
    a = node(p, ctx=EvalContext(size=32, seed=1))
    b = node(p, ctx=EvalContext(size=32, seed=2))
    assert a.shape == (1, 1, 32, 32) and not torch.allclose(a, b)
    with pytest.raises(DiffMatError):
        Node("fxmaps", {"blendingmode": 4})
    with pytest.raises(DiffMatError):
        F.fx_map(p, x_amount=0, size=32)
    with pytest.raises(DiffMatError):
        node(torch.rand(1, 3, 16, 16), ctx=EvalContext(size=32))
    with pytest.raises(DiffMatError):
        node(p, ctx=EvalContext(size=48))
