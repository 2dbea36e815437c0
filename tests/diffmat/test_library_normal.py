"""Known-value tests of the library normal / height / relief nodes (functional/library_normal.py)."""
from __future__ import annotations

import pytest
import torch
from imagecheck import smooth_tiling_image

from blender_match.diffmat import DiffMatError, Node
from blender_match.diffmat import functional as F


def flat_normal(size=16):
    return torch.tensor([0.5, 0.5, 1.0, 1.0]).reshape(1, 4, 1, 1).expand(1, 4, size, size).clone()


def bump(size=32, sigma=0.12):
    c = (torch.arange(size) + 0.5) / size - 0.5
    r2 = c[None, :] ** 2 + c[:, None] ** 2
    return torch.exp(-r2 / (2 * sigma ** 2)).reshape(1, 1, size, size)


def square(size=32, lo=8, hi=24):
    x = torch.zeros(1, 1, size, size)
    x[..., lo:hi, lo:hi] = 1.0
    return x


def some_normal(size=32, fmt=0):
    return F.height_to_normal_map(smooth_tiling_image(1, size, seed=9), 20.0, fmt)


@pytest.mark.parametrize("quality", [0, 1])
def test_normal_combine_with_flat_is_identity(quality):
    n = some_normal()
    torch.testing.assert_close(F.normal_combine(n, flat_normal(32), blend_quality=quality), n, atol=1e-5, rtol=0)
    torch.testing.assert_close(F.normal_combine(flat_normal(32), n, blend_quality=quality), n, atol=1e-5, rtol=0)
    both = F.normal_combine(n, n, blend_quality=quality)

    def tilt(m):
        return (m[:, :2] - 0.5).abs().mean()

    assert tilt(both) > tilt(n) * 1.3                      # details add up
    with pytest.raises(DiffMatError):
        F.normal_combine(n, n, blend_quality=2)


def test_normal_blend_opacity_and_mask():
    a, b = some_normal(), flat_normal(32)
    torch.testing.assert_close(F.normal_blend(a, b, opacity=0.0), a, atol=1e-5, rtol=0)
    torch.testing.assert_close(F.normal_blend(a, b, opacity=1.0), b, atol=1e-5, rtol=0)
    mask = torch.zeros(1, 1, 32, 32)
    mask[..., :16] = 1.0
    out = F.normal_blend(a, b, mask, opacity=1.0)
    torch.testing.assert_close(out[..., :16], b[..., :16], atol=1e-5, rtol=0)
    torch.testing.assert_close(out[..., 16:], a[..., 16:], atol=1e-5, rtol=0)
    torch.testing.assert_close(F.normal_blend(a, b, mask, opacity=1.0, use_mask=False), b, atol=1e-5, rtol=0)


def test_normal_normalise_unit_length():
    n = some_normal()
    torch.testing.assert_close(F.normal_normalise(n), n, atol=1e-5, rtol=0)
    short = n.clone()
    short[:, :3] = (n[:, :3] - 0.5) * 0.5 + 0.5
    v = F.normal_normalise(short)[:, :3] * 2 - 1
    torch.testing.assert_close(v.norm(dim=1), torch.ones(1, 32, 32), atol=1e-4, rtol=0)


@pytest.mark.parametrize("fmt", [0, 1])
def test_normal_to_height_recovers_height(fmt):
    h = smooth_tiling_image(1, 32, seed=9)
    rec = F.normal_to_height(F.height_to_normal_map(h, 5.0, fmt), normal_format=fmt)
    corr = torch.corrcoef(torch.stack([h.flatten(), rec.flatten()]))[0, 1]
    assert corr > 0.98
    wrong = F.normal_to_height(F.height_to_normal_map(h, 5.0, fmt), normal_format=1 - fmt)
    assert torch.corrcoef(torch.stack([h.flatten(), wrong.flatten()]))[0, 1] < 0.9


def test_curvature_flat_and_bump():
    torch.testing.assert_close(F.curvature(flat_normal()), torch.full((1, 1, 16, 16), 0.5))
    for fmt in (0, 1):
        n = F.height_to_normal_map(bump(), 20.0, fmt)
        c = F.curvature(n, normal_format=fmt, intensity=5.0)
        assert c[0, 0, 16, 16] > 0.55                        # convex top bright
        s = F.curvature_smooth(n, normal_format=fmt)
        assert s[0, 0, 16, 16] > 0.6 and s[0, 0, 0, 0] < 0.55


def test_hbao_flat_is_one_and_pit_is_dark():
    flat = torch.full((1, 1, 32, 32), 0.5)
    torch.testing.assert_close(F.hbao(flat), torch.ones_like(flat))
    pit = 1 - bump()
    ao = F.hbao(pit, height_depth=0.3)
    assert ao[0, 0, 16, 16] < 0.9 and ao[0, 0, 0, 0] > ao[0, 0, 16, 16]
    ao8 = Node("hbao", {"quality": 8})(pit)
    assert ao8.shape == pit.shape


def test_ambient_occlusion_2_flat_is_one_and_pit_is_dark():
    flat = torch.full((1, 1, 32, 32), 0.3)
    torch.testing.assert_close(F.ambient_occlusion(flat), torch.ones_like(flat), atol=1e-5, rtol=0)
    ao = F.ambient_occlusion(1 - bump(), height_depth=0.5, spreading=0.5)
    assert ao[0, 0, 16, 16] < 0.9 and ao[0, 0, 0, 0] > 0.99


def test_ambient_occlusion_2_as_the_reference_draws_it():
    """The reference's facts: a texel below its neighbourhood's mean by d gives 1 − 2d (squared
    on flat ground), a ridge nothing; the equalizer at 0 leaves every band as it is, its fine
    bands raised sharpen the occlusion and lowered spread it; Levels at the end (a production dry
    mud sets 0.513 as its low, which turns its cells' seams into black cracks)."""
    size = 64
    groove = torch.ones(1, 1, size, size)
    groove[..., 31:34, :] = 0.0                 # three pixels wide, across the image
    plain = F.ambient_occlusion(groove, spreading=0.08)
    assert float(plain[0, 0, 31, 5]) < 0.3 and float(plain[0, 0, 5, 5]) == pytest.approx(1.0, abs=1e-5)
    assert float(F.ambient_occlusion(1 - groove, spreading=0.08)[0, 0, 32, 5]) == pytest.approx(1.0, abs=1e-5)
    torch.testing.assert_close(F.ambient_occlusion(groove, spreading=0.08, equalizer=(0.0, 0.0, 0.0)), plain)
    sharper = F.ambient_occlusion(groove, spreading=0.08, equalizer=(0.0, 0.0, 1.0))
    assert float(sharper[0, 0, 31, 5]) < 0.5 * float(plain[0, 0, 31, 5])
    softer = F.ambient_occlusion(groove, spreading=0.08, equalizer=(0.0, -0.4, -0.4))
    assert float(softer[0, 0, 30, 5]) < 0.95 < float(plain[0, 0, 30, 5])
    cut = F.ambient_occlusion(groove, spreading=0.08, levels=(0.513, 0.5, 1.0))
    assert float(cut[0, 0, 31, 5]) == 0.0 and float(cut[0, 0, 5, 5]) > 0.99


def test_ambient_occlusion_2_keeps_our_three_blur_model_for_the_library():
    """Model 1 is the occlusion our library graphs were authored with (three blurs, a gain of
    8 x height depth): a pit darkens at its centre and open ground stays white, but not as
    Substance's construction (model 0) draws it; an unknown model is refused."""
    pit = 1 - bump(64, sigma=0.1)
    ours = F.ambient_occlusion(pit, height_depth=0.3, spreading=0.5, model=1)
    substance = F.ambient_occlusion(pit, height_depth=0.3, spreading=0.5, model=0)
    assert float(ours[0, 0, 32, 32]) < 0.9 and float(ours[0, 0, 0, 0]) > 0.99
    assert (ours - substance).abs().max() > 0.05
    torch.testing.assert_close(F.ambient_occlusion(torch.full((1, 1, 16, 16), 0.4), model=1),
                               torch.ones(1, 1, 16, 16), atol=1e-5, rtol=0)
    with pytest.raises(DiffMatError, match="model"):
        F.ambient_occlusion(pit, model=2)


def test_edge_detect_finds_square_contour():
    """Black lines on white unless inverted: the MATch reference's Edge Detect ends by inverting
    the lines it found (its ``invert`` inverts them back)."""
    out = F.edge_detect(square(), edge_width=2.0, edge_roundness=0.0, invert=True)
    assert out[0, 0, 16, 8] > 0.9 and out[0, 0, 8, 16] > 0.9           # on the contour
    assert out[0, 0, 16, 16] < 0.01 and out[0, 0, 0, 0] < 0.01         # inside and outside
    plain = F.edge_detect(square(), edge_width=2.0, edge_roundness=0.0)
    torch.testing.assert_close(plain, 1 - out)
    assert plain[0, 0, 16, 8] < 0.1 and plain[0, 0, 0, 0] > 0.99


def test_edge_detect_draws_a_full_line_for_a_small_step():
    """As Substance does: tiles of random grey get lines as white as a black and white mask."""
    full = F.edge_detect(square(), edge_width=2.0, edge_roundness=0.0, invert=True)
    faint = F.edge_detect(square() * 0.15 + 0.3, edge_width=2.0, edge_roundness=0.0, invert=True)
    torch.testing.assert_close(faint, full, atol=0.05, rtol=0)
    assert faint[0, 0, 16, 8] > 0.9
    # the tolerance (0-1) moves a threshold of about 0.002 at most (the MATch reference): a step of
    # 0.15 is an edge at tolerance 1 too (it was read as a step size, which erased every line)
    strict = F.edge_detect(square() * 0.15 + 0.3, edge_width=2.0, edge_roundness=0.0, tolerance=1.0,
                           invert=True)
    assert strict[0, 0, 16, 8] > 0.9
    flat = F.edge_detect(torch.full((1, 1, 32, 32), 0.4), edge_width=2.0, edge_roundness=0.0, tolerance=1.0,
                         invert=True)
    assert float(flat.max()) < 0.01


def test_bevel_grows_outwards_for_a_positive_distance_and_bevels_inwards_for_a_negative_one():
    """The MATch reference builds Bevel from the Distance node: a positive distance d keeps the
    shape at 1 and ramps down outside it over d x 128 pixels of a 256-px image, a negative one
    ramps up inside it from the contour."""
    size = 64
    x = square(size, 16, 48)
    h, n = F.bevel(x, distance=0.1)                 # 12.8 reference px = 3.2 px at 64
    row = h[0, 0, 32]
    assert row[20] > 0.99 and row[16] > 0.99 and row[4] < 0.01          # the shape, then nothing
    assert 0.1 < row[14] < 0.9 and row[15] > row[14] > row[13]          # falling ramp outside
    assert n.shape[1] == 4
    torch.testing.assert_close(n[0, :3, 32, 32], torch.tensor([0.5, 0.5, 1.0]), atol=1e-3, rtol=0)
    inside, _ = F.bevel(x, distance=-0.1)
    row = inside[0, 0, 32]
    assert row[32] > 0.99 and row[12] < 0.01 and row[16] < 0.5          # nothing outside, low at the rim
    assert 0.1 < row[17] < 0.9 and row[16] < row[17] < row[18]          # rising ramp inside
    same, _ = F.bevel(x, distance=0.0)
    torch.testing.assert_close(same, x)


def test_bevel_keeps_a_thin_line():
    """A one-pixel line bevelled outwards is a ridge as wide as the bevel (the blurred estimate of
    the contour it replaced lost lines thinner than the bevel: a production leather's relief was
    flat)."""
    x = torch.zeros(1, 1, 64, 64)
    x[..., 32, :] = 1.0
    h, _ = F.bevel(x, distance=0.04)               # 5.1 reference px = 1.3 px at 64
    assert h[0, 0, 32].min() > 0.99
    assert 0.0 < h[0, 0, 31].mean() < 1.0 and h[0, 0, 28].max() < 0.01
    d = torch.tensor([0.04], requires_grad=True)
    F.bevel(x, distance=d)[0].sum().backward()
    assert d.grad is not None and d.grad.item() > 0


def test_pbr_conversion_known_values():
    base = torch.tensor([0.8, 0.4, 0.2, 1.0]).reshape(1, 4, 1, 1).expand(1, 4, 4, 4)
    zero, one = torch.zeros(1, 1, 4, 4), torch.ones(1, 1, 4, 4)
    diff, spec, gloss = F.metallic_roughness_to_specular_glossiness(base, zero, torch.full((1, 1, 4, 4), 0.3))
    torch.testing.assert_close(diff, base, atol=1e-5, rtol=0)
    srgb004 = 1.055 * 0.04 ** (1 / 2.4) - 0.055
    torch.testing.assert_close(spec[0, :3, 0, 0], torch.full((3,), srgb004), atol=1e-4, rtol=0)
    torch.testing.assert_close(gloss, torch.full((1, 1, 4, 4), 0.7))
    diff, spec, _ = F.metallic_roughness_to_specular_glossiness(base, one, zero)
    assert diff[:, :3].max() < 1e-6
    torch.testing.assert_close(spec, base, atol=1e-5, rtol=0)
