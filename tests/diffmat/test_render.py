"""The flash renderer: known values of the BRDF under a co-located light, and gradients."""
from __future__ import annotations

import math

import pytest
import torch

from blender_match.diffmat import DiffMatError
from blender_match.diffmat.render import FlashCamera, linear_to_srgb, render_flash, render_maps, srgb_to_linear


def flat(value, channels=1, size=16):
    return torch.full((1, channels, size, size), float(value))


def test_srgb_round_trip():
    x = torch.linspace(0, 1, 11)
    torch.testing.assert_close(linear_to_srgb(srgb_to_linear(x)), x, atol=1e-5, rtol=0)


def test_white_lambertian_centre_matches_flash_power():
    camera = FlashCamera(power=0.5)
    img = render_flash(flat(1.0, 3), roughness=flat(1.0), metallic=flat(0.0), camera=camera)
    centre = srgb_to_linear(img[:, :, 7:9, 7:9]).mean().item()
    # diffuse part is exactly `power` at the centre; rough specular adds a little
    assert 0.5 <= centre <= 0.56


def test_falloff_towards_the_corners_and_symmetry():
    img = render_flash(flat(0.5, 3), roughness=flat(0.3))
    assert img[0, 0, 0, 0] < img[0, 0, 8, 8]
    torch.testing.assert_close(img, img.flip(-1))
    torch.testing.assert_close(img, img.flip(-2))


def test_the_falloff_moves_light_about_the_frame_and_keeps_its_mean():
    """A phone's beam pattern and vignetting: zero terms are the ideal flash; a positive u term
    brightens the right of the frame, a negative u² and v² term darkens the edges; the factor's
    mean over the frame is one, so the level stays the gain's."""
    base = dict(basecolor=flat(0.3, 3, 32), roughness=flat(1.0, 1, 32))
    ideal = render_flash(**base)
    torch.testing.assert_close(render_flash(**base, camera=FlashCamera(falloff=(0.0,) * 5)), ideal)
    right = srgb_to_linear(render_flash(**base, camera=FlashCamera(falloff=(0.8, 0, 0, 0, 0))))
    assert right[..., 16:].mean() > 1.5 * right[..., :16].mean()
    edges = srgb_to_linear(render_flash(**base, camera=FlashCamera(falloff=(0, 0, -1.0, -1.0, 0))))
    plain = srgb_to_linear(ideal)
    assert edges[0, 0, 0, 0] < 0.5 * plain[0, 0, 0, 0] and edges[0, 0, 16, 16] > plain[0, 0, 16, 16]
    assert edges.mean() == pytest.approx(float(plain.mean()), rel=0.05)


def test_highlight_grows_sharper_as_roughness_falls():
    smooth = render_flash(flat(0.2, 3), roughness=flat(0.15))
    rough = render_flash(flat(0.2, 3), roughness=flat(0.8))
    assert smooth[0, 0, 8, 8] > rough[0, 0, 8, 8]
    assert smooth[0, 0, 0, 0] < rough[0, 0, 0, 0]


def test_metal_takes_its_colour_into_the_highlight():
    red = torch.zeros(1, 3, 16, 16)
    red[:, 0] = 1.0
    metal = render_flash(red, roughness=flat(0.3), metallic=flat(1.0))
    centre = metal[0, :, 8, 8]
    assert centre[0] > 0.5 and centre[1] < 0.05 and centre[2] < 0.05
    dielectric = render_flash(red, roughness=flat(0.3), metallic=flat(0.0))
    assert dielectric[0, 1, 8, 8] > centre[1]  # a dielectric's highlight is white


def test_tilted_normal_darkens_and_gradients_flow():
    normal = torch.zeros(1, 3, 16, 16)
    normal[:, 0] = 0.5 + 0.5 * math.sin(0.6)
    normal[:, 1] = 0.5
    normal[:, 2] = 0.5 + 0.5 * math.cos(0.6)
    base = flat(0.5, 3).requires_grad_()
    tilted = render_flash(base, normal, flat(0.6))
    straight = render_flash(flat(0.5, 3), None, flat(0.6))
    assert tilted[0, 0, 8, 8] < straight[0, 0, 8, 8]
    tilted.mean().backward()
    assert base.grad.abs().sum() > 0


def test_render_maps_needs_a_basecolor():
    with pytest.raises(DiffMatError, match="no basecolor"):
        render_maps({"roughness": flat(0.5)})


# --- the anisotropic lobe (brushed metals) ----------------------------------------------------

METAL = dict(basecolor=flat(0.8, 3, 32), roughness=flat(0.45, 1, 32), metallic=flat(1.0, 1, 32))


def spread(img):
    """The second moments (x right, y up, about the centroid) of a render's highlight, in linear
    light above its darkest pixel: (var x, var y, cov xy)."""
    w = srgb_to_linear(img)[0].mean(0)
    w = (w - w.min()) / (w - w.min()).sum()
    n = w.shape[-1]
    y, x = torch.meshgrid(-(torch.arange(n) + 0.5 - n / 2), torch.arange(n) + 0.5 - n / 2, indexing="ij")
    x, y = x - (w * x).sum(), y - (w * y).sum()
    return float((w * x * x).sum()), float((w * y * y).sum()), float((w * x * y).sum())


@pytest.mark.parametrize("light_offset", [None, (0.2, -0.1)])
def test_without_anisotropy_or_at_level_zero_the_render_is_the_isotropic_one(light_offset):
    """No maps: the isotropic formula, untouched. Level 0 (any angle, any normal): its terms are
    exactly zero, so the same pixels to the bit."""
    normal = torch.rand(1, 3, 32, 32) * 0.4 + torch.tensor([0.3, 0.3, 0.6])[:, None, None]
    iso = render_flash(**METAL, normal=normal, light_offset=light_offset)
    zero = render_flash(**METAL, normal=normal, light_offset=light_offset, anisotropy=flat(0.0, 1, 32),
                        anisotropy_angle=torch.rand(1, 1, 32, 32))
    assert torch.equal(iso, zero)
    assert torch.equal(render_flash(**METAL, light_offset=light_offset, anisotropy_angle=flat(0.3, 1, 32)),
                       render_flash(**METAL, light_offset=light_offset))
    maps = {"basecolor": METAL["basecolor"], "roughness": METAL["roughness"], "metallic": METAL["metallic"]}
    assert torch.equal(render_maps(maps), render_flash(**METAL))


def test_the_highlight_stretches_across_the_brushing():
    """Brushed along +u (angle 0): the lobe is rougher across the grooves, so the highlight is
    longer in y than in x, and longer the higher the level."""
    var_x, var_y, cov = spread(render_flash(**METAL, anisotropy=flat(0.8, 1, 32), anisotropy_angle=flat(0.0, 1, 32)))
    assert var_y > 2.5 * var_x and abs(cov) < 1e-3 * var_y
    iso_x, iso_y, _ = spread(render_flash(**METAL))
    assert iso_x == pytest.approx(iso_y, rel=1e-4)
    half_x, half_y, _ = spread(render_flash(**METAL, anisotropy=flat(0.4, 1, 32)))  # angle 0 when absent
    assert iso_y / iso_x < half_y / half_x < var_y / var_x


def test_a_quarter_turn_swaps_the_axes_and_an_eighth_turns_the_highlight_counter_clockwise():
    level = flat(0.8, 1, 32)
    along_u = render_flash(**METAL, anisotropy=level, anisotropy_angle=flat(0.0, 1, 32))
    along_v = render_flash(**METAL, anisotropy=level, anisotropy_angle=flat(0.25, 1, 32))
    torch.testing.assert_close(along_v, along_u.transpose(-1, -2), atol=2e-6, rtol=0)
    x, y, _ = spread(along_v)
    assert x > 2.5 * y
    # brushed towards +u+v (45°): the highlight runs across, along -u+v, so x and y anti-correlate
    _, _, cov = spread(render_flash(**METAL, anisotropy=level, anisotropy_angle=flat(0.125, 1, 32)))
    assert cov < -0.5 * x


def test_the_novel_light_path_stretches_the_same_way():
    level, angle = flat(0.8, 1, 32), flat(0.0, 1, 32)
    var_x, var_y, _ = spread(render_flash(**METAL, light_offset=(0.0, 0.0), anisotropy=level, anisotropy_angle=angle))
    assert var_y > 2.5 * var_x
    torch.testing.assert_close(render_flash(**METAL, light_offset=(0.0, 0.0), anisotropy=level, anisotropy_angle=angle),
                               render_flash(**METAL, anisotropy=level, anisotropy_angle=angle), atol=2e-6, rtol=0)


def test_gradients_reach_every_map_and_are_finite():
    normal = (torch.rand(1, 3, 16, 16) * 0.4 + torch.tensor([0.3, 0.3, 0.6])[:, None, None]).requires_grad_()
    maps = [flat(0.7, 3), normal, flat(0.4), flat(0.9), flat(0.6), flat(0.1)]
    for m in maps:
        m.requires_grad_()
    for offset in (None, (0.3, 0.1)):
        image = render_flash(*maps[:4], light_offset=offset, anisotropy=maps[4], anisotropy_angle=maps[5])
        image.mean().backward()
        for m in maps:
            assert torch.isfinite(m.grad).all() and m.grad.abs().sum() > 0
            m.grad = None


def test_gradcheck_of_the_anisotropic_lobe():
    """Analytic against numerical derivatives in float64, level and angle at interior values."""
    base = flat(0.6, 3, 8).double()
    rough, metal = flat(0.5, 1, 8).double(), flat(0.7, 1, 8).double()
    level = torch.full((1, 1, 8, 8), 0.6, dtype=torch.float64, requires_grad=True)
    angle = torch.full((1, 1, 8, 8), 0.1, dtype=torch.float64, requires_grad=True)
    assert torch.autograd.gradcheck(
        lambda lv, an: render_flash(base, None, rough, metal, light_offset=(0.2, 0.1), anisotropy=lv,
                                    anisotropy_angle=an), (level, angle))
