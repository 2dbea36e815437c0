"""Known-value tests of the library adjustment nodes (functional/library_adjust.py)."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F


def ramp(size=16):
    return torch.linspace(0.0, 1.0, size * size).reshape(1, 1, size, size)


def rgba(r, g, b, a=1.0, size=4):
    return torch.tensor([r, g, b, a]).reshape(1, 4, 1, 1).expand(1, 4, size, size).clone()


def test_histogram_scan_threshold_identity_and_ends():
    x = ramp()
    out = F.histogram_scan(x, position=0.5, contrast=1.0)
    far = (x - 0.5).abs() > 0.01
    assert torch.equal(out[far], (x[far] > 0.5).float())
    torch.testing.assert_close(F.histogram_scan(x, position=0.5, contrast=0.0), x)
    assert F.histogram_scan(x, position=0.0, contrast=0.3).max() <= 0.0 + 1e-6  # black
    assert F.histogram_scan(x, position=1.0, contrast=0.3)[x > 0].min() >= 1.0 - 1e-6  # white
    # a higher position whitens; invert_position reverses the direction
    a = F.histogram_scan(x, position=0.3, contrast=0.5).mean()
    b = F.histogram_scan(x, position=0.7, contrast=0.5).mean()
    c = F.histogram_scan(x, position=0.3, contrast=0.5, invert_position=True).mean()
    assert a < b and abs(c - b) < 1e-5


def test_histogram_range_and_select():
    x = ramp()
    torch.testing.assert_close(F.histogram_range(x, range=1.0, position=0.5), x)
    flat = F.histogram_range(x, range=0.0, position=0.3)
    torch.testing.assert_close(flat, torch.full_like(x, 0.3))
    half = F.histogram_range(x, range=0.5, position=0.5)
    assert abs(half.min().item() - 0.25) < 1e-6 and abs(half.max().item() - 0.75) < 1e-6
    sel = F.histogram_select(torch.tensor([0.5, 0.58, 0.9, 0.0]).reshape(1, 1, 2, 2), position=0.5,
                             range=0.1, contrast=1.0)
    assert sel.flatten().tolist() == [1.0, 1.0, 0.0, 0.0]


def test_invert_gray_and_colour():
    x = ramp()
    torch.testing.assert_close(F.invert(x), 1 - x)
    assert torch.equal(F.invert(x, invert=False), x)
    c = rgba(0.2, 0.4, 0.9, 0.7)
    out = F.invert(c)
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor([0.8, 0.6, 0.1, 0.7]))


def test_auto_levels_stretches_range():
    x = ramp() * 0.5 + 0.2
    out = F.auto_levels(x)
    assert abs(out.min().item()) < 1e-6 and abs(out.max().item() - 1) < 1e-6
    torch.testing.assert_close(out, ramp(), atol=1e-5, rtol=0)


def test_contrast_luminosity():
    x = ramp()
    torch.testing.assert_close(F.contrast_luminosity(x, contrast=0.0, luminosity=0.0), x)
    torch.testing.assert_close(F.contrast_luminosity(x * 0.5, luminosity=0.25), x * 0.5 + 0.25)
    flat = F.contrast_luminosity(x, contrast=-1.0)
    torch.testing.assert_close(flat, torch.full_like(x, 0.5))
    steep = F.contrast_luminosity(x, contrast=0.5)     # gain 3 about 0.5
    assert abs(steep[0, 0, 8, 8].item() - (0.5 + 3 * (x[0, 0, 8, 8].item() - 0.5))) < 1e-5


def test_replace_color_maps_source_to_target():
    src, dst = (0.8, 0.2, 0.2, 1.0), (0.2, 0.3, 0.8, 1.0)
    out = F.replace_color(rgba(*src), sourcecolor=src, targetcolor=dst)
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor(dst), atol=1e-4, rtol=0)
    img = torch.rand(1, 4, 8, 8)
    img[:, 3] = 1
    same = F.replace_color(img, sourcecolor=src, targetcolor=src)
    torch.testing.assert_close(same, img, atol=1e-4, rtol=0)


def test_switches():
    a, b = torch.zeros(1, 1, 4, 4), torch.ones(1, 1, 4, 4)
    assert torch.equal(Node("switch_grayscale")(a, b), a)
    assert torch.equal(Node("switch_grayscale", {"switch": False})(a, b), b)
    c = torch.full((1, 1, 4, 4), 0.5)
    node = Node("multi_switch_grayscale", {"input_number": 3, "input_selection": 3})
    assert torch.equal(node(a, b, c), c)
    with pytest.raises(DiffMatError):
        Node("multi_switch_grayscale", {"input_number": 2, "input_selection": 3})(a, b, c)


def test_channel_merge_and_split_round_trip():
    img = torch.rand(1, 4, 8, 8)
    r, g, b, a = Node("rgba_split")(img)
    torch.testing.assert_close(Node("rgba_merge")(r, g, b, a), img)
    assert Node("rgba_merge")(r, g, b)[:, 3].min() == 1.0
    rgb, alpha = Node("rgb-a_split")(img)
    assert torch.equal(alpha, img[:, 3:]) and rgb[:, 3].min() == 1.0
    torch.testing.assert_close(Node("rgb-a_merge")(rgb, alpha), img)


def test_convert_to_srgb_known_values():
    x = torch.tensor([0.0, 0.5, 1.0, 0.001]).reshape(1, 1, 2, 2)
    out = F.linear_to_srgb(x).flatten()
    torch.testing.assert_close(out, torch.tensor([0.0, 0.735357, 1.0, 0.01292]), atol=1e-5, rtol=0)
    torch.testing.assert_close(F.srgb_to_linear(F.linear_to_srgb(x)), x, atol=1e-5, rtol=0)


def test_batched_histogram_scan_gives_batch():
    node = Node("histogram_scan", {"contrast": 0.5})
    out = node(ramp(), ctx=EvalContext(size=16), override={"position": torch.tensor([[0.2], [0.8]])})
    assert out.shape[0] == 2 and out[0].mean() < out[1].mean()
