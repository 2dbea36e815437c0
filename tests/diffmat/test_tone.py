"""Known-value tests of Levels, Curve, HSL, Grayscale Conversion and Channel Shuffle
(functional/tone.py)."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F

RAMP = torch.linspace(0, 1, 16).reshape(1, 1, 4, 4)


def _color():
    g = torch.Generator().manual_seed(3)
    img = torch.rand(1, 4, 4, 4, generator=g)
    img[:, 3] = torch.linspace(0.2, 1.0, 16).reshape(4, 4)
    return img


# ------------------------------------------------------------------ levels

def test_levels_identity_gray_and_color():
    torch.testing.assert_close(F.levels(RAMP), RAMP, atol=1e-6, rtol=0)
    img = _color()
    torch.testing.assert_close(F.levels(img), img, atol=1e-6, rtol=0)


def test_levels_invert_by_output_range():
    out = F.levels(RAMP, leveloutlow=(1, 1, 1, 0), levelouthigh=(0, 0, 0, 1))
    torch.testing.assert_close(out, 1 - RAMP, atol=1e-6, rtol=0)
    img = _color()
    out = F.levels(img, leveloutlow=(1, 1, 1, 0), levelouthigh=(0, 0, 0, 1))
    torch.testing.assert_close(out[:, :3], 1 - img[:, :3], atol=1e-6, rtol=0)
    torch.testing.assert_close(out[:, 3], img[:, 3], atol=1e-6, rtol=0)   # alpha keeps identity levels


def test_levels_invert_by_input_range():
    out = F.levels(RAMP, levelinlow=1.0, levelinhigh=0.0)
    torch.testing.assert_close(out, 1 - RAMP, atol=1e-6, rtol=0)


def test_levels_input_range_and_clamp():
    x = torch.tensor([0.1, 0.2, 0.4, 0.6, 0.9]).reshape(1, 1, 1, 5)
    out = F.levels(x, levelinlow=0.2, levelinhigh=0.6)
    torch.testing.assert_close(out.flatten(), torch.tensor([0.0, 0.0, 0.5, 1.0, 1.0]), atol=1e-6, rtol=0)
    out = F.levels(x, levelinlow=0.2, levelinhigh=0.6, leveloutlow=0.2, levelouthigh=0.4)
    torch.testing.assert_close(out.flatten(), torch.tensor([0.2, 0.2, 0.3, 0.4, 0.4]), atol=1e-6, rtol=0)


def test_levels_gray_reads_first_component_and_color_is_per_channel():
    out = F.levels(RAMP, levelouthigh=(0.5, 1.0, 1.0, 1.0))
    torch.testing.assert_close(out, RAMP * 0.5, atol=1e-6, rtol=0)
    img = _color()
    out = F.levels(img, levelouthigh=(0.5, 1.0, 0.25, 1.0))
    torch.testing.assert_close(out[:, 0], img[:, 0] * 0.5, atol=1e-6, rtol=0)
    torch.testing.assert_close(out[:, 1], img[:, 1], atol=1e-6, rtol=0)
    torch.testing.assert_close(out[:, 2], img[:, 2] * 0.25, atol=1e-6, rtol=0)


def test_levels_without_clampinterm_extrapolates_before_output_range():
    x = torch.tensor([0.0, 0.1, 0.5]).reshape(1, 1, 1, 3)
    out = F.levels(x, levelinlow=0.2, levelinhigh=0.6, leveloutlow=0.5, levelouthigh=0.7, clampinterm=False)
    # t = (x - .2) / .4 = -.5, -.25, .75 -> .5 + .2 t
    torch.testing.assert_close(out.flatten(), torch.tensor([0.4, 0.45, 0.65]), atol=1e-6, rtol=0)


def test_levels_batched():
    out = F.levels(RAMP, leveloutlow=torch.tensor([[0.0] * 4, [1.0, 1.0, 1.0, 0.0]]),
                   levelouthigh=torch.tensor([[1.0] * 4, [0.0, 0.0, 0.0, 1.0]]))
    assert out.shape == (2, 1, 4, 4)
    torch.testing.assert_close(out[1], 1 - RAMP[0], atol=1e-6, rtol=0)


# ------------------------------------------------------------------ curve

def test_curve_default_is_identity():
    torch.testing.assert_close(F.curve(RAMP), RAMP, atol=2e-3, rtol=0)


def test_curve_straight_handles_give_a_polyline():
    # points (0, 0), (0.5, 0.8), (1, 1) with handles on the chords: two straight segments
    pos = (0.0, 0.0, 0.5, 0.8, 1.0, 1.0)
    lefts = (0.0, 0.0, 0.5 - 1 / 6, 0.8 - 0.8 / 3, 1 - 1 / 6, 1 - 0.2 / 3)
    rights = (1 / 6, 0.8 / 3, 0.5 + 1 / 6, 0.8 + 0.2 / 3, 1.0, 1.0)
    x = torch.tensor([0.0, 0.25, 0.5, 0.75, 1.0]).reshape(1, 1, 1, 5)
    out = F.curve(x, positions=pos, lefts=lefts, rights=rights).flatten()
    torch.testing.assert_close(out, torch.tensor([0.0, 0.4, 0.8, 0.9, 1.0]), atol=2e-3, rtol=0)


def test_curve_points_in_any_order_and_flat_outside():
    pos = (0.8, 0.2, 0.2, 0.7)       # unsorted: (0.2, 0.7) then (0.8, 0.2)
    lefts = (0.6, 0.3667, 0.2, 0.7)
    rights = (0.8, 0.2, 0.4, 0.5333)
    x = torch.tensor([0.0, 0.1, 0.5, 0.9, 1.0]).reshape(1, 1, 1, 5)
    out = F.curve(x, positions=pos, lefts=lefts, rights=rights).flatten()
    torch.testing.assert_close(out, torch.tensor([0.7, 0.7, 0.45, 0.2, 0.2]), atol=3e-3, rtol=0)


def test_curve_color_keeps_alpha_and_handles_bend_the_curve():
    img = _color()
    # a curve bulging upwards: same ends, handles raised
    out = F.curve(img, positions=(0, 0, 1, 1), lefts=(0, 0, 0.5, 1.0), rights=(0.0, 0.5, 1, 1))
    torch.testing.assert_close(out[:, 3], img[:, 3])
    assert (out[:, :3] >= img[:, :3] - 1e-6).all() and (out[:, :3] > img[:, :3] + 0.05).any()


def test_curve_errors():
    with pytest.raises(DiffMatError, match="curve"):
        F.curve(RAMP, positions=(0, 0, 1))
    with pytest.raises(DiffMatError, match="curve"):
        F.curve(RAMP, positions=(0, 0, 1, 1), lefts=(0, 0), rights=(1, 1, 1, 1))


# ------------------------------------------------------------------ hsl

def _rgb(*values):
    rgb = torch.tensor(values, dtype=torch.float32).reshape(1, 3, 1, 1)
    return torch.cat([rgb, torch.ones(1, 1, 1, 1)], dim=1)


def test_hsl_identity():
    img = _color()
    torch.testing.assert_close(F.hsl(img), img, atol=1e-5, rtol=0)


def test_hsl_hue_shift():
    """Hue shifts by (2 hue - 1) turns: a third of a turn is hue 0.5 +/- 1/6."""
    red = _rgb(1.0, 0.0, 0.0)
    torch.testing.assert_close(F.hsl(red, hue=0.5 + 1 / 6), _rgb(0.0, 1.0, 0.0), atol=1e-5, rtol=0)
    torch.testing.assert_close(F.hsl(red, hue=0.5 - 1 / 6), _rgb(0.0, 0.0, 1.0), atol=1e-5, rtol=0)
    # a half-turn (hue 0.75 or 0.25) gives the complement
    torch.testing.assert_close(F.hsl(_rgb(0.8, 0.4, 0.2), hue=0.75), _rgb(0.2, 0.6, 0.8), atol=1e-5, rtol=0)
    torch.testing.assert_close(F.hsl(_rgb(0.8, 0.4, 0.2), hue=0.25), _rgb(0.2, 0.6, 0.8), atol=1e-5, rtol=0)


@pytest.mark.parametrize("hue", [0.0, 0.5, 1.0])
def test_hsl_at_hue_0_half_and_1_keeps_a_warm_colour_warm(hue):
    """The regression of production materials (bronze, cork, corten) turned blue: hue 0 and 1 are
    whole turns, not half turns."""
    warm = _rgb(0.8, 0.4, 0.2)
    out = F.hsl(warm, hue=hue)
    torch.testing.assert_close(out, warm, atol=1e-5, rtol=0)
    with torch.no_grad():
        assert torch.equal(F.hsl(warm, hue=hue), out)  # the no-grad twin agrees


def test_hsl_saturation_and_lightness_are_additive_and_clamped():
    c = _rgb(0.8, 0.4, 0.2)                                   # l = 0.5, s = 0.6
    torch.testing.assert_close(F.hsl(c, saturation=0.0), _rgb(0.5, 0.5, 0.5), atol=1e-5, rtol=0)
    torch.testing.assert_close(F.hsl(c, saturation=0.6), _rgb(0.9, 0.366667, 0.1), atol=1e-5, rtol=0)  # s 0.8
    torch.testing.assert_close(F.hsl(c, saturation=1.0), _rgb(1.0, 0.333333, 0.0), atol=1e-5, rtol=0)  # s 1
    torch.testing.assert_close(F.hsl(c, luminosity=0.0), _rgb(0.0, 0.0, 0.0), atol=1e-5, rtol=0)
    torch.testing.assert_close(F.hsl(c, luminosity=1.0), _rgb(1.0, 1.0, 1.0), atol=1e-5, rtol=0)
    torch.testing.assert_close(F.hsl(c, luminosity=0.6), _rgb(0.88, 0.64, 0.52), atol=1e-5, rtol=0)  # l 0.7
    with torch.no_grad():
        torch.testing.assert_close(F.hsl(c, saturation=0.6, luminosity=0.6),
                                   F.hsl(c.requires_grad_(), saturation=0.6, luminosity=0.6).detach())


def test_hsl_keeps_alpha_and_rejects_gray():
    img = _color()
    out = F.hsl(img, hue=0.7, saturation=0.3, luminosity=0.6)
    torch.testing.assert_close(out[:, 3], img[:, 3])
    with pytest.raises(DiffMatError, match="hsl"):
        F.hsl(RAMP)


# ------------------------------------------------------------------ grayscale conversion

def test_grayscale_conversion_weights():
    img = _color()
    out = F.grayscale_conversion(img, channelsweights=(0.2, 0.5, 0.3, 0.0))
    torch.testing.assert_close(out[:, 0], 0.2 * img[:, 0] + 0.5 * img[:, 1] + 0.3 * img[:, 2], atol=1e-6, rtol=0)
    alpha_only = F.grayscale_conversion(img, channelsweights=(0, 0, 0, 1))
    torch.testing.assert_close(alpha_only[:, 0], img[:, 3])
    default = F.grayscale_conversion(_rgb(1.0, 1.0, 1.0))
    assert default.item() == pytest.approx(0.99)


def test_grayscale_conversion_flatten_alpha():
    c = torch.tensor([0.2, 0.4, 0.6, 0.5]).reshape(1, 4, 1, 1)
    out = F.grayscale_conversion(c, channelsweights=(1 / 3, 1 / 3, 1 / 3, 0), alphamult=True, mattelevel=1.0)
    assert out.item() == pytest.approx(0.4 * 0.5 + 1.0 * 0.5, abs=1e-6)
    out0 = F.grayscale_conversion(c, channelsweights=(1 / 3, 1 / 3, 1 / 3, 0), alphamult=True, mattelevel=0.0)
    assert out0.item() == pytest.approx(0.2, abs=1e-6)


# ------------------------------------------------------------------ shuffle

def test_shuffle_identity_and_permutations():
    img = _color()
    torch.testing.assert_close(F.channel_shuffle(img), img)
    out = F.channel_shuffle(img, channelred=2, channelgreen=0, channelblue=3, channelalpha=1)
    torch.testing.assert_close(out, img[:, [2, 0, 3, 1]])


def test_shuffle_reads_input2_and_gray_inputs():
    img = _color()
    other = torch.rand(1, 4, 4, 4, generator=torch.Generator().manual_seed(9))
    out = F.channel_shuffle(img, other, channelred=4, channelgreen=7, channelblue=1, channelalpha=6)
    torch.testing.assert_close(out, torch.stack([other[:, 0], other[:, 3], img[:, 1], other[:, 2]], dim=1))
    out = F.channel_shuffle(img, RAMP, channelalpha=4)
    torch.testing.assert_close(out[:, 3:], RAMP)
    gray_out = F.channel_shuffle(RAMP, channelalpha=3)
    torch.testing.assert_close(gray_out[:, 3], torch.ones(1, 4, 4))


def test_shuffle_errors():
    with pytest.raises(DiffMatError, match="input2"):
        F.channel_shuffle(_color(), channelred=5)
    with pytest.raises(DiffMatError, match="channelblue"):
        F.channel_shuffle(_color(), channelblue=8)
    with pytest.raises(DiffMatError):
        Node("shuffle", {"channelgreen": 9})


def test_nodes_run():
    ctx = EvalContext(size=4)
    assert Node("levels", {"levelinmid": 0.3})(RAMP, ctx=ctx).shape == (1, 1, 4, 4)
    assert Node("grayscaleconversion")(_color(), ctx=ctx).shape == (1, 1, 4, 4)
    assert Node("shuffle", {"channelalpha": 4})(_color(), RAMP, ctx=ctx).shape == (1, 4, 4, 4)
    assert Node("curve")(_color(), ctx=ctx).shape == (1, 4, 4, 4)
