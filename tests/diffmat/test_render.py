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
