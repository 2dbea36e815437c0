"""One test per semantic fact documented in docs/nodes.md (the node audit): each pins the formula or
convention the table names, on small constant or hand-made images, so a change of meaning fails here.
Facts already pinned elsewhere are referenced from the table instead of repeated (test_tone.py for
HSL's warm-colour regression, test_transform.py for tiling, test_warp.py for warp directions)."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F
from blender_match.diffmat.functional.function_graph import fit_components

SIZE = 16


def gray(value: float, size: int = SIZE) -> torch.Tensor:
    return torch.full((1, 1, size, size), float(value), dtype=torch.float64)


def rgba(r, g, b, a=1.0, size: int = SIZE) -> torch.Tensor:
    return torch.tensor([r, g, b, a], dtype=torch.float64).reshape(1, 4, 1, 1).expand(1, 4, size, size).clone()


def value(img: torch.Tensor) -> list[float]:
    """The (constant) per-channel value of a flat image."""
    return [round(v, 6) for v in img[0, :, 0, 0].tolist()]


# ------------------------------------------------------------------ blend: each mode's formula
F_, B_ = 0.6, 0.3
BLEND_CASES = {
    0: F_,                                          # copy
    1: B_ + F_,                                     # add (linear dodge), clamped below
    2: B_ - F_,                                     # subtract
    3: F_ * B_,                                     # multiply
    4: B_ + 2 * F_ - 1,                             # add-sub
    5: max(F_, B_),                                 # max (lighten)
    6: min(F_, B_),                                 # min (darken)
    7: F_,                                          # switch
    8: B_ / F_,                                     # divide
    9: 2 * F_ * B_,                                 # overlay, B < 0.5
    10: 1 - (1 - F_) * (1 - B_),                    # screen
}


@pytest.mark.parametrize("mode", sorted(BLEND_CASES))
@pytest.mark.parametrize("opacity", [1.0, 0.5])
def test_blend_mode_formula_on_constant_images(mode, opacity):
    out = F.blend(gray(F_), gray(B_), blendingmode=mode, opacitymult=opacity)
    target = BLEND_CASES[mode]
    expected = min(max(B_ + opacity * (target - B_), 0.0), 1.0)
    assert value(out)[0] == pytest.approx(expected, abs=1e-6)


def test_blend_overlay_above_half_and_soft_light_at_half_foreground():
    out = F.blend(gray(0.6), gray(0.7), blendingmode=9)
    assert value(out)[0] == pytest.approx(1 - 2 * 0.4 * 0.3, abs=1e-6)
    # soft light with a 0.5 foreground leaves the background unchanged
    assert value(F.blend(gray(0.5), gray(0.7), blendingmode=11))[0] == pytest.approx(0.7, abs=1e-6)


def test_blend_add_and_subtract_clamp_to_unit_range():
    assert value(F.blend(gray(0.8), gray(0.7), blendingmode=1))[0] == 1.0
    assert value(F.blend(gray(0.8), gray(0.3), blendingmode=2))[0] == 0.0


def test_blend_opacity_above_one_does_not_extrapolate():
    out = F.blend(gray(0.6), gray(0.2), blendingmode=0, opacitymult=1.5)
    assert value(out)[0] == pytest.approx(0.6, abs=1e-6)       # clamped to opacity 1, not 0.2 + 1.5 * 0.4


def test_blend_opacity_mask_multiplies_the_opacity():
    mask = gray(0.5)
    out = F.blend(gray(1.0), gray(0.0), mask, blendingmode=0, opacitymult=0.5)
    assert value(out)[0] == pytest.approx(0.25, abs=1e-6)


def test_blend_colour_source_alpha_scales_the_weight_and_alpha_is_source_over():
    out = F.blend(rgba(1, 1, 1, 0.5), rgba(0, 0, 0, 0.4), blendingmode=0)
    r, _, _, a = value(out)
    assert r == pytest.approx(0.5, abs=1e-6)
    assert a == pytest.approx(0.5 + 0.4 * 0.5, abs=1e-6)


def test_blend_switch_ignores_source_alpha():
    out = F.blend(rgba(1, 1, 1, 0.0), rgba(0, 0, 0, 1.0), blendingmode=7, opacitymult=1.0)
    assert value(out) == [1.0, 1.0, 1.0, 0.0]


# ------------------------------------------------------------------ levels
def test_levels_input_and_output_points():
    x = torch.tensor([0.1, 0.3, 0.5, 0.9], dtype=torch.float64).reshape(1, 1, 1, 4)
    out = F.levels(x, levelinlow=0.3, levelinhigh=0.5, leveloutlow=0.2, levelouthigh=0.6).flatten()
    torch.testing.assert_close(out, torch.tensor([0.2, 0.2, 0.6, 0.6], dtype=torch.float64))


@pytest.mark.parametrize("mid, gamma", [(0.5, 1.0), (0.25, 1 / 5), (0.75, 5.0), (0.0, 1 / 9), (1.0, 9.0),
                                        (0.425, 1 / 2.2)])
def test_levels_mid_point_gamma_is_linear_in_the_mid_point(mid, gamma):
    x = torch.tensor([0.2, 0.5, 0.8], dtype=torch.float64).reshape(1, 1, 1, 3)
    out = F.levels(x, levelinmid=mid).flatten()
    torch.testing.assert_close(out, x.flatten() ** gamma, atol=1e-9, rtol=1e-6)


def test_levels_in_low_above_in_high_inverts():
    x = torch.tensor([0.0, 0.25, 1.0], dtype=torch.float64).reshape(1, 1, 1, 3)
    torch.testing.assert_close(F.levels(x, levelinlow=1.0, levelinhigh=0.0).flatten(), 1 - x.flatten())


# ------------------------------------------------------------------ tone and channels
@pytest.mark.parametrize("hue", [0.0, 0.5, 1.0])
def test_hsl_hue_0_half_and_1_keep_a_warm_colour_warm(hue):
    r, _, b, _ = value(F.hsl(rgba(0.8, 0.5, 0.2), hue=hue))
    assert r > b


def test_hsl_saturation_0_is_gray_and_lightness_0_1_are_black_white():
    r, g, b, _ = value(F.hsl(rgba(0.8, 0.5, 0.2), saturation=0.0))
    assert r == pytest.approx(g, abs=1e-6) and g == pytest.approx(b, abs=1e-6)
    assert value(F.hsl(rgba(0.8, 0.5, 0.2), luminosity=0.0))[:3] == [0.0, 0.0, 0.0]
    assert value(F.hsl(rgba(0.8, 0.5, 0.2), luminosity=1.0))[:3] == [1.0, 1.0, 1.0]


def test_grayscale_conversion_default_weights():
    out = F.grayscale_conversion(rgba(0.9, 0.3, 0.6, 0.5))
    assert value(out)[0] == pytest.approx(0.33 * (0.9 + 0.3 + 0.6), abs=1e-6)


def test_grayscale_conversion_flatten_alpha_over_the_matte():
    out = F.grayscale_conversion(rgba(0.0, 0.0, 0.0, 0.25), channelsweights=(1 / 3, 1 / 3, 1 / 3, 0),
                                 alphamult=True, mattelevel=1.0)
    assert value(out)[0] == pytest.approx(0.75, abs=1e-6)


def test_uniform_colour_and_its_grayscale_first_component():
    out = F.uniform_color(outputcolor=(0.2, 0.4, 0.6, 0.8), size=SIZE)
    assert out.shape == (1, 4, SIZE, SIZE) and value(out) == [0.2, 0.4, 0.6, 0.8]
    assert value(F.uniform_color(outputcolor=(0.2, 0.4, 0.6, 0.8), colorswitch=False, size=SIZE)) == [0.2]


def test_invert_grayscale_and_colour_keeps_alpha():
    assert value(F.invert(gray(0.3)))[0] == pytest.approx(0.7)
    assert value(F.invert(rgba(0.2, 0.4, 0.9, 0.7))) == pytest.approx([0.8, 0.6, 0.1, 0.7])


def test_gradient_map_endpoints_and_midpoint():
    x = torch.tensor([0.0, 0.5, 1.0], dtype=torch.float64).reshape(1, 1, 1, 3)
    out = F.gradient_map(x, positions=(0.0, 1.0), colors=(1, 0, 0, 1, 0, 0, 1, 1))
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor([1.0, 0, 0, 1], dtype=torch.float64))
    torch.testing.assert_close(out[0, :, 0, 2], torch.tensor([0.0, 0, 1, 1], dtype=torch.float64))
    torch.testing.assert_close(out[0, :, 0, 1], torch.tensor([0.5, 0, 0.5, 1], dtype=torch.float64))


def test_gradient_map_flat_tangents_ease_with_smoothstep():
    x = torch.tensor([0.25], dtype=torch.float64).reshape(1, 1, 1, 1)
    out = F.gradient_map(x, interpmode=2, colorswitch=False)
    assert out.item() == pytest.approx(0.25 * 0.25 * (3 - 0.5), abs=1e-9)


# ------------------------------------------------------------------ library adjustments
def test_histogram_scan_contrast_1_is_a_step_at_one_minus_position():
    x = torch.linspace(0, 1, 64, dtype=torch.float64).reshape(1, 1, 8, 8)
    out = F.histogram_scan(x, position=0.3, contrast=1.0)
    far = (x - 0.7).abs() > 0.02
    assert torch.equal(out[far], (x[far] > 0.7).to(x.dtype))


def test_histogram_range_stays_centred_on_the_position():
    x = torch.tensor([0.0, 1.0], dtype=torch.float64).reshape(1, 1, 1, 2)
    out = F.histogram_range(x, range=1.0, position=0.8).flatten()
    # [max(0.3, 0.6), min(1.3, 1.6) -> 1]: symmetric about 0.8, not the clipped [0.3, 1]
    torch.testing.assert_close(out, torch.tensor([0.6, 1.0], dtype=torch.float64))
    out = F.histogram_range(x, range=0.5, position=0.2).flatten()
    torch.testing.assert_close(out, torch.tensor([0.0, 0.4], dtype=torch.float64))


def test_histogram_range_inside_the_unit_range_is_unchanged():
    x = torch.tensor([0.0, 1.0], dtype=torch.float64).reshape(1, 1, 1, 2)
    torch.testing.assert_close(F.histogram_range(x, range=0.2, position=0.3).flatten(),
                               torch.tensor([0.2, 0.4], dtype=torch.float64))


# ------------------------------------------------------------------ spatial conventions
def test_transformation_offset_moves_content_by_image_widths():
    x = torch.zeros(1, 1, SIZE, SIZE, dtype=torch.float64)
    x[..., 0, 0] = 1.0
    out = F.transformation_2d(x, offset=(4 / SIZE, 0.0))
    assert out[0, 0, 0, 4].item() == pytest.approx(1.0)


def test_transformation_scale_2_tiles_twice():
    x = torch.rand(1, 1, SIZE, SIZE, dtype=torch.float64, generator=torch.Generator().manual_seed(1))
    out = F.transformation_2d(x, matrix22=(2.0, 0.0, 0.0, 2.0), mipmapmode=1, manualmiplevel=0)
    torch.testing.assert_close(out[..., :SIZE // 2, :SIZE // 2], out[..., SIZE // 2:, SIZE // 2:])


@pytest.mark.parametrize("size", [32, 64])
def test_warp_intensity_is_in_pixels_of_a_256_image(size):
    # a ramp rising by 1 across the image displaces by ``intensity`` 256-px pixels: a shift of
    # intensity * size / 256 pixels at every resolution
    u = (torch.arange(size, dtype=torch.float64) + 0.5) / size
    ramp = torch.remainder(u, 1.0).reshape(1, 1, 1, size).expand(1, 1, size, size)
    x = torch.zeros(1, 1, size, size, dtype=torch.float64)
    x[..., size // 2] = 1.0
    out = F.warp(x, torch.full_like(ramp, 0.5) + 0.0 * ramp, intensity=64.0)
    torch.testing.assert_close(out, x)                                      # flat gradient: identity
    shifted = F.directional_warp(x, torch.ones_like(x), intensity=64.0)     # 64/256 of the width
    assert shifted[0, 0, 0].argmax().item() == size // 2 + size // 4


def test_directional_blur_and_blur_preserve_a_flat_image_mean():
    x = torch.rand(1, 1, SIZE, SIZE, dtype=torch.float64, generator=torch.Generator().manual_seed(2))
    for out in (F.blur(x, intensity=3.0), F.directional_blur(x, intensity=3.0, mblurangle=0.2)):
        assert out.mean().item() == pytest.approx(x.mean().item(), abs=1e-9)


def test_normal_format_green_for_a_height_rising_down_the_image():
    # the slope faces up the image: OpenGL green (y up) above 0.5, DirectX green (y down) below
    # (n = (-dh/dx, -dh/dy, 1) per 256-px pixel, as the MATch reference implementation)
    v = (torch.arange(SIZE, dtype=torch.float64) + 0.5) / SIZE
    h = (0.5 + 0.25 * torch.sin(2 * torch.pi * v)).reshape(1, 1, SIZE, 1).expand(1, 1, SIZE, SIZE)
    dx = F.height_to_normal(h, intensity=10.0, inversedy=False)
    gl = F.height_to_normal(h, intensity=10.0, inversedy=True)
    row = 0                                   # the height rises downwards at the top row
    assert gl[0, 1, row, 0] > 0.5 > dx[0, 1, row, 0]
    torch.testing.assert_close(dx[:, 0], torch.full_like(dx[:, 0], 0.5))


def test_slope_blur_accepts_substances_blur_code_7():
    x = torch.rand(1, 1, SIZE, SIZE, dtype=torch.float64, generator=torch.Generator().manual_seed(3))
    e = torch.rand(1, 1, SIZE, SIZE, dtype=torch.float64, generator=torch.Generator().manual_seed(4))
    torch.testing.assert_close(F.slope_blur(x, e, mode=7, intensity=4.0), F.slope_blur(x, e, mode=1, intensity=4.0))
    node = Node("slope_blur_grayscale", {"mode": 7})
    assert node(x.float(), e.float(), ctx=EvalContext(size=SIZE)).shape == (1, 1, SIZE, SIZE)
    with pytest.raises(DiffMatError):
        F.slope_blur(x, e, mode=2)


# ------------------------------------------------------------------ vector width conversion
def test_fit_components_broadcasts_one_component():
    assert fit_components(torch.tensor([0.3]), 4, "p").tolist() == pytest.approx([0.3] * 4)


def test_fit_components_drops_extra_components():
    assert fit_components(torch.tensor([0.1, 0.2, 0.3, 0.4]), 2, "p").tolist() == pytest.approx([0.1, 0.2])


def test_fit_components_fills_missing_ones_from_the_default():
    out = fit_components(torch.tensor([0.1, 0.2, 0.3]), 4, "p", fill=(0.0, 0.0, 0.0, 0.9))
    assert out.tolist() == pytest.approx([0.1, 0.2, 0.3, 0.9])


def test_fit_components_without_a_default_refuses_missing_components():
    with pytest.raises(DiffMatError):
        fit_components(torch.tensor([0.1, 0.2, 0.3]), 4, "p")


def test_pbr_metal_reflectance_gives_each_metals_published_base_colour():
    """PBR Metal Reflectance: the metals in the documentation's order, each its measured F0 colour
    sRGB-encoded (gold 1.000 0.766 0.336 linear)."""
    def colour(k):
        return F.metal_reflectance(metal_color=k, size=4)[0, :, 0, 0]
    gold, silver, copper = colour(0), colour(1), colour(4)
    published = F.linear_to_srgb(torch.tensor([1.0, 0.766, 0.336]).view(1, 3, 1, 1))[0, :, 0, 0]
    torch.testing.assert_close(gold[:3], published, atol=2e-3, rtol=0)
    assert gold[0] > gold[1] > gold[2] and copper[0] > copper[1] > copper[2]   # warm metals
    assert silver[:3].min() > 0.95 and gold[3] == 1
    with pytest.raises(DiffMatError):
        F.metal_reflectance(metal_color=9)
