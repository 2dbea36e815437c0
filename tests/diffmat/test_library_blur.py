"""Known-value tests of the library blur / warp / transform nodes (functional/library_blur.py)."""
from __future__ import annotations

import pytest
import torch
from imagecheck import seam_jumps, smooth_tiling_image

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F


def img(ch=1, size=32, seed=3):
    return smooth_tiling_image(ch, size, seed=seed)


def square(size=32, lo=8, hi=24):
    x = torch.zeros(1, 1, size, size)
    x[..., lo:hi, lo:hi] = 1.0
    return x


def test_blur_hq_keeps_mean_and_constants_and_smooths():
    x = square()
    out = F.blur_hq(x, intensity=8.0)
    assert abs(out.mean().item() - x.mean().item()) < 1e-3
    assert out.var() < x.var()
    torch.testing.assert_close(F.blur_hq(x, intensity=0.0), x, atol=1e-5, rtol=0)
    flat = torch.full((1, 4, 16, 16), 0.3)
    torch.testing.assert_close(F.blur_hq(flat, intensity=10.0), flat)


def test_blur_hq_is_resolution_independent():
    big = F.blur_hq(square(64, 16, 48), intensity=10.0)
    small = F.blur_hq(square(32, 8, 24), intensity=10.0)
    diff = (torch.nn.functional.avg_pool2d(big, 2) - small).abs()
    assert diff.mean() < 0.01 and diff.max() < 0.06


def test_slope_blur_flat_effect_and_zero_intensity_are_identity():
    x = img()
    flat = torch.full_like(x, 0.5)
    torch.testing.assert_close(F.slope_blur(x, flat, intensity=10.0), x, atol=1e-5, rtol=0)
    torch.testing.assert_close(F.slope_blur(x, img(seed=4), intensity=0.0), x, atol=1e-5, rtol=0)


def test_slope_blur_modes_order():
    x, e = img(), img(seed=4)
    blur = F.slope_blur(x, e, mode=1, intensity=12.0)
    mx = F.slope_blur(x, e, mode=5, intensity=12.0)
    mn = F.slope_blur(x, e, mode=6, intensity=12.0)
    assert (mn <= blur + 1e-6).all() and (blur <= mx + 1e-6).all() and (mn <= x + 1e-6).all()
    assert (mx - mn).max() > 1e-3
    with pytest.raises(DiffMatError):
        F.slope_blur(x, e, mode=3)


def test_slope_blur_moves_content_down_slope():
    # effect rising to the right around the bar: samples are taken to the left (down-slope)
    size = 32
    x = torch.zeros(1, 1, size, size)
    x[..., 15:17] = 1.0
    u = (torch.arange(size) + 0.5) / size
    effect = (0.5 - 0.4 * torch.sin(2 * torch.pi * u)).reshape(1, 1, 1, size).expand(1, 1, size, size)
    out = F.slope_blur(x, effect, mode=5, intensity=16.0)    # max: the bar spreads
    row = out[0, 0, 0]
    assert row[17:19].max() > 0.5 and row[12:15].max() < 1e-6  # bar widened to the right only


def test_non_uniform_blur_follows_effect():
    x = square()
    black, white = torch.zeros_like(x), torch.ones_like(x)
    torch.testing.assert_close(F.non_uniform_blur(x, black, intensity=10.0), x, atol=1e-5, rtol=0)
    torch.testing.assert_close(F.non_uniform_blur(x, white, intensity=10.0), F.blur_hq(x, intensity=10.0),
                               atol=1e-5, rtol=0)
    aniso = F.non_uniform_blur(x, white, intensity=10.0, anisotropy=1.0, angle=0.0)
    # blurred along u only: rows inside the square stay binary across v
    col = aniso[0, 0, :, 16]
    assert col[10:22].min() > 0.99 and col[:6].max() < 0.01


def test_highpass_of_constant_is_mid_gray():
    flat = torch.full((1, 1, 16, 16), 0.7)
    torch.testing.assert_close(F.highpass(flat, radius=6.0), torch.full_like(flat, 0.5))
    hp = F.highpass(square(), radius=4.0)
    assert hp[0, 0, 8, 16] > 0.5 and hp[0, 0, 7, 16] < 0.5


def test_vector_warp_shifts_by_vector():
    x = img()
    neutral = torch.full((1, 4, 32, 32), 0.5)
    torch.testing.assert_close(F.vector_warp(x, neutral, intensity=1.0), x, atol=1e-5, rtol=0)
    vec = neutral.clone()
    vec[:, 0] = 0.75                                      # u component +0.5
    out = F.vector_warp(x, vec, intensity=0.25)           # 0.125 image widths = 4 pixels
    torch.testing.assert_close(out, torch.roll(x, -4, dims=-1), atol=1e-5, rtol=0)
    vec[:, 0], vec[:, 1] = 0.5, 0.75                      # green up in OpenGL, down in DirectX
    dx = F.vector_warp(x, vec, intensity=0.25, vector_format=0)
    gl = F.vector_warp(x, vec, intensity=0.25, vector_format=1)
    torch.testing.assert_close(dx, torch.roll(x, -4, dims=-2), atol=1e-5, rtol=0)
    torch.testing.assert_close(gl, torch.roll(x, 4, dims=-2), atol=1e-5, rtol=0)


def test_vector_morph_and_mosaic_identity_at_zero():
    x = img()
    torch.testing.assert_close(F.vector_morph(x, img(4, seed=5), amount=0.0), x, atol=1e-5, rtol=0)
    torch.testing.assert_close(F.mosaic(x, intensity=0.0), x, atol=1e-5, rtol=0)
    assert (F.mosaic(x, intensity=1.0) - x).abs().max() > 1e-2


def test_safe_transform_tiling_offset_symmetry_rotation():
    x = img()
    two = F.safe_transform(x, tile=2)
    torch.testing.assert_close(two[..., :16, :16], two[..., 16:, 16:])
    # a two-times tiling reads every second texel pair: it matches a box-downsampled copy
    down = torch.nn.functional.avg_pool2d(x, 2)
    tiled = down.repeat(1, 1, 2, 2)
    assert (two - torch.roll(tiled, (8, 8), (-2, -1))).abs().max() < 1e-5
    torch.testing.assert_close(F.safe_transform(x, offset=(0.25, 0.5)), torch.roll(x, (16, 8), (-2, -1)),
                               atol=1e-5, rtol=0)
    torch.testing.assert_close(F.safe_transform(x, symmetry=1), torch.flip(x, (-1,)), atol=1e-5, rtol=0)
    r90 = F.safe_transform(x, rotation=0.25)
    assert any(torch.allclose(r90, torch.rot90(x, k, (-2, -1)), atol=1e-5) for k in (1, 3))
    r45 = F.safe_transform(x, rotation=0.125)              # tile-safe: the sqrt(2) zoom, still tiles
    wrap, inside = seam_jumps(r45)
    assert wrap <= inside + 1e-5


def test_safe_transform_batched_rotation():
    node = Node("safe_transform_grayscale", {"tile_safe_rotation": False})
    out = node(img(), ctx=EvalContext(size=32), override={"rotation": torch.tensor([[0.0], [0.25]])})
    assert out.shape[0] == 2
    torch.testing.assert_close(out[:1], img(), atol=1e-5, rtol=0)


def test_make_it_tile_photo_makes_a_ramp_tile():
    u = torch.linspace(0, 1, 32)
    ramp = (u[None, :] * 0.5 + u[:, None] * 0.5).reshape(1, 1, 32, 32)
    wrap0, _ = seam_jumps(ramp)
    out = F.make_it_tile_photo(ramp)
    wrap, inside = seam_jumps(out)
    assert wrap0 > 0.4 and wrap < 0.05
    centre = out[..., 12:20, 12:20]
    torch.testing.assert_close(centre, ramp[..., 12:20, 12:20])


def test_make_it_tile_photo_warping_runs_minus_to_plus_100():
    """Mask Warping is a Directional Warp intensity (-100..100): a production silk sets 89; it was
    read as a fraction of the image and moved the fade out of the picture."""
    g = torch.Generator().manual_seed(2)
    u = torch.linspace(0, 1, 32)
    ramp = (u[None, :] * 0.5 + u[:, None] * 0.5).reshape(1, 1, 32, 32)
    noisy = (ramp + 0.2 * torch.rand(1, 1, 32, 32, generator=g)).clamp(0, 1)
    plain = F.make_it_tile_photo(noisy)
    bent = F.make_it_tile_photo(noisy, mask_warping_h=89.0, mask_warping_v=-60.0)
    assert (bent - plain).abs().max() > 0.02
    torch.testing.assert_close(bent[..., 14:18, 14:18], noisy[..., 14:18, 14:18])
    wrap, _ = seam_jumps(bent)
    assert wrap < 0.3


def test_make_it_tile_patch_stamps_the_whole_input_shrunk():
    # octave 1, stamps one cell wide with a hard full mask: each quarter is the input at half size
    x = torch.rand(1, 1, 32, 32, generator=torch.Generator().manual_seed(5))
    out = F.make_it_tile_patch(x, octave=1, pattern_size_width=100.0, pattern_size_height=100.0,
                               mask_precision=1.0)
    half = torch.nn.functional.avg_pool2d(x, 2)
    torch.testing.assert_close(out, half.repeat(1, 1, 2, 2), atol=1e-5, rtol=0)


def test_make_it_tile_patch_covers_a_flat_input_and_tiles():
    flat = torch.full((1, 1, 32, 32), 0.4)
    torch.testing.assert_close(F.make_it_tile_patch(flat, mask_precision=1.0, seed=1), flat, atol=1e-5, rtol=0)
    # the default soft mask lets the black background through between stamps, as the reference's does
    assert float(F.make_it_tile_patch(flat, seed=1).min()) < 0.35
    x = torch.linspace(0, 1, 32)[None, None, None, :].expand(1, 1, 32, 32).contiguous()
    spread = {"disorder": 0.1, "rotation_variation": 0.5, "size_variation": 50.0}
    a, b = F.make_it_tile_patch(x, seed=1, **spread), F.make_it_tile_patch(x, seed=2, **spread)
    assert torch.equal(a, F.make_it_tile_patch(x, seed=1, **spread)) and (a - b).abs().max() > 0.05
    # the ramp's own seam (a jump of 1) is gone: across the wrap the stamps meet as they do across
    # the cell boundary in the middle
    for out in (a, b):
        across = (out[..., 0] - out[..., -1]).abs().mean()
        middle = (out[..., 16] - out[..., 15]).abs().mean()
        assert across < 2 * middle + 0.02 < 0.3


def test_make_it_tile_patch_colour_variation_and_background():
    flat = torch.full((1, 1, 32, 32), 0.8)
    darker = F.make_it_tile_patch(flat, mask_precision=1.0, color_variation=0.5, seed=3)
    assert 0.4 < float(darker.min()) and float(darker.mean()) < 0.75
    # where no stamp reaches, the grayscale node shows its colour variation as a level (Substance's)
    gaps = F.make_it_tile_patch(flat, mask_size=0.3, color_variation=0.25, seed=3)
    assert abs(float(gaps[..., 0, 0]) - 0.25) < 1e-4
    rgba = torch.full((1, 4, 32, 32), 0.8)
    red = F.make_it_tile_patch(rgba, mask_size=0.3, background_color=(1.0, 0.0, 0.0, 1.0))
    torch.testing.assert_close(red[0, :, 0, 0], torch.tensor([1.0, 0.0, 0.0, 1.0]))
