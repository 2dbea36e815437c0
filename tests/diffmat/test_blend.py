"""Known-value tests of the Blend node against the documented formulas (functional/blend.py)."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F

FG = torch.tensor([[0.0, 0.2, 0.4, 0.6], [0.8, 1.0, 0.1, 0.3], [0.5, 0.7, 0.9, 0.25], [0.05, 0.45, 0.55, 0.95]])
BG = torch.tensor([[0.9, 0.3, 0.5, 0.1], [0.2, 0.6, 0.4, 0.8], [0.35, 0.65, 0.15, 0.75], [0.5, 0.0, 1.0, 0.45]])


def _gray(t):
    return t[None, None].clone()


def _softlight(f, b):
    d = torch.where(b <= 0.25, ((16 * b - 12) * b + 4) * b, torch.sqrt(b))
    return torch.where(f <= 0.5, b - (1 - 2 * f) * b * (1 - b), b + (2 * f - 1) * (d - b))


# Expected full-opacity results, written out per documented mode (result = B + w (T - B), clamped).
TARGETS = {
    0: lambda f, b: f,
    1: lambda f, b: b + f,
    2: lambda f, b: b - f,
    3: lambda f, b: f * b,
    4: lambda f, b: b + 2 * f - 1,
    5: lambda f, b: torch.maximum(f, b),
    6: lambda f, b: torch.minimum(f, b),
    7: lambda f, b: f,
    8: lambda f, b: b / f.clamp_min(1e-4),
    9: lambda f, b: torch.where(b < 0.5, 2 * f * b, 1 - 2 * (1 - f) * (1 - b)),
    10: lambda f, b: 1 - (1 - f) * (1 - b),
    11: _softlight,
}


@pytest.mark.parametrize("mode", sorted(TARGETS))
def test_gray_modes_full_opacity(mode):
    out = F.blend(_gray(FG), _gray(BG), blendingmode=mode)
    expected = TARGETS[mode](FG, BG).clamp(0, 1)
    torch.testing.assert_close(out[0, 0], expected, atol=1e-6, rtol=0)


@pytest.mark.parametrize("mode", sorted(TARGETS))
def test_gray_modes_with_opacity_and_mask(mode):
    mask = torch.linspace(0, 1, 16).reshape(4, 4)
    out = F.blend(_gray(FG), _gray(BG), _gray(mask), blendingmode=mode, opacitymult=0.5)
    w = 0.5 * mask
    expected = (BG + w * (TARGETS[mode](FG, BG) - BG)).clamp(0, 1)
    torch.testing.assert_close(out[0, 0], expected, atol=1e-6, rtol=0)


def test_specific_values():
    f, b = _gray(torch.full((4, 4), 0.75)), _gray(torch.full((4, 4), 0.25))
    assert F.blend(f, b, blendingmode=1)[0, 0, 0, 0].item() == pytest.approx(1.0)       # add
    assert F.blend(f, b, blendingmode=2)[0, 0, 0, 0].item() == pytest.approx(0.0)       # subtract clamps
    assert F.blend(f, b, blendingmode=3)[0, 0, 0, 0].item() == pytest.approx(0.1875)    # multiply
    assert F.blend(f, b, blendingmode=4)[0, 0, 0, 0].item() == pytest.approx(0.75)      # add-sub: 0.25 + 0.5
    assert F.blend(f, b, blendingmode=8)[0, 0, 0, 0].item() == pytest.approx(1 / 3)     # divide
    assert F.blend(f, b, blendingmode=9)[0, 0, 0, 0].item() == pytest.approx(0.375)     # overlay: 2 f b
    assert F.blend(f, b, blendingmode=10)[0, 0, 0, 0].item() == pytest.approx(0.8125)   # screen
    assert F.blend(f, b, blendingmode=0, opacitymult=0.25)[0, 0, 0, 0].item() == pytest.approx(0.375)


def _rgba(gray_rgb, alpha):
    return torch.cat([gray_rgb[None, None].expand(1, 3, 4, 4), torch.full((1, 1, 4, 4), alpha)], dim=1)


@pytest.mark.parametrize("mode", sorted(TARGETS))
def test_color_source_alpha(mode):
    fg, bg = _rgba(FG, 0.5), _rgba(BG, 0.8)
    out = F.blend(fg, bg, blendingmode=mode, opacitymult=0.8)
    if mode == 7:   # switch ignores alpha: every channel lerps by the opacity
        w = 0.8
        rgb = BG + w * (FG - BG)
        alpha = 0.8 + w * (0.5 - 0.8)
    else:
        a = 0.8 * 0.5
        rgb = BG + a * (TARGETS[mode](FG, BG) - BG)
        alpha = 0.8 + a * (1 - 0.8)
    for c in range(3):
        torch.testing.assert_close(out[0, c], rgb.clamp(0, 1), atol=1e-6, rtol=0)
    torch.testing.assert_close(out[0, 3], torch.full((4, 4), alpha), atol=1e-6, rtol=0)


def test_color_ignore_alpha_blends_alpha_like_a_channel():
    fg, bg = _rgba(FG, 0.5), _rgba(BG, 0.8)
    out = F.blend(fg, bg, blendingmode=3, alphablending=1)
    torch.testing.assert_close(out[0, 0], FG * BG, atol=1e-6, rtol=0)
    torch.testing.assert_close(out[0, 3], torch.full((4, 4), 0.4), atol=1e-6, rtol=0)


def test_color_straight_and_premultiplied():
    fg, bg = _rgba(FG, 0.5), _rgba(BG, 0.5)
    out_a = 0.5 + 0.5 * 0.5
    straight = F.blend(fg, bg, alphablending=2)
    torch.testing.assert_close(straight[0, 0], (0.5 * FG + 0.5 * 0.5 * BG) / out_a, atol=1e-6, rtol=0)
    torch.testing.assert_close(straight[0, 3], torch.full((4, 4), out_a), atol=1e-6, rtol=0)
    premul = F.blend(fg, bg, alphablending=3)
    torch.testing.assert_close(premul[0, 0], (FG + 0.5 * BG).clamp(0, 1), atol=1e-6, rtol=0)
    torch.testing.assert_close(premul[0, 3], torch.full((4, 4), out_a), atol=1e-6, rtol=0)


def test_mask_rectangle_crops_with_area_coverage():
    f, b = _gray(torch.ones(4, 4)), _gray(torch.zeros(4, 4))
    out = F.blend(f, b, maskrectangle=(0.0, 0.5, 0.25, 1.0))[0, 0]
    expected = torch.tensor([[0, 0, 0, 0], [1, 1, 0, 0], [1, 1, 0, 0], [1, 1, 0, 0]], dtype=torch.float32)
    torch.testing.assert_close(out, expected)
    half = F.blend(f, b, maskrectangle=(0.0, 0.625, 0.0, 1.0))[0, 0]
    torch.testing.assert_close(half[0], torch.tensor([1.0, 1.0, 0.5, 0.0]))


def test_mask_rectangle_is_differentiable():
    rect = torch.tensor([0.0, 0.6, 0.0, 1.0], requires_grad=True)
    out = F.blend(_gray(torch.ones(4, 4)), _gray(torch.zeros(4, 4)), maskrectangle=rect)
    out.sum().backward()
    assert rect.grad[1].item() == pytest.approx(16.0)   # 4 rows x 4 px per texture unit


def test_batched_opacity():
    out = F.blend(_gray(FG), _gray(BG), opacitymult=torch.tensor([[0.0], [1.0]]))
    assert out.shape == (2, 1, 4, 4)
    torch.testing.assert_close(out[0, 0], BG)
    torch.testing.assert_close(out[1, 0], FG)


def test_errors():
    with pytest.raises(DiffMatError, match="channel"):
        F.blend(_rgba(FG, 1.0), _gray(BG))
    with pytest.raises(DiffMatError, match="blendingmode"):
        F.blend(_gray(FG), _gray(BG), blendingmode=12)
    with pytest.raises(DiffMatError, match="alphablending"):
        F.blend(_gray(FG), _gray(BG), alphablending=4)
    with pytest.raises(DiffMatError):
        Node("blend", {"blendingmode": 12})
    node = Node("blend", {"blendingmode": 3})
    with pytest.raises(DiffMatError):
        node(_rgba(FG, 1.0), _gray(BG), ctx=EvalContext(size=4))


def test_node_uses_destination_as_background():
    node = Node("blend", {"blendingmode": 0, "opacitymult": 0.0})
    out = node(_gray(FG), _gray(BG), ctx=EvalContext(size=4))
    torch.testing.assert_close(out[0, 0], BG)
