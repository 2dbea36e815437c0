"""Photometric calibration: the base colour gain (identity by default, never optimised, carried by
params.json) and its closed-form solve (a known exposure and white balance recovered, the clipped
flash highlight left out); the photo's flash falloff solved the same way."""
from __future__ import annotations

from dataclasses import replace

import pytest
import torch

from blender_match.diffmat import DiffMatError, MaterialGraph
from blender_match.diffmat.calibration import (
    CLIP_LEVEL,
    proposal_gains,
    solve_gain,
    solve_lighting,
    unclipped_level,
    with_gain,
)
from blender_match.diffmat.params_file import graph_params, load_params, save_params
from blender_match.diffmat.render import FlashCamera, linear_to_srgb, render_maps, srgb_to_linear
from blender_match.vocabulary import CALIBRATION, GAIN

KNOWN_GAIN = torch.tensor([1.6, 1.0, 0.45])


def sample(roughness: float = 0.6) -> MaterialGraph:
    """A warm, bumpy dielectric: a coloured noise as base colour, a relief as normal."""
    g = MaterialGraph("sample")
    g.add("noise", "perlin_noise", scale=8)
    g.add("tint", "gradient", {"input1": "noise"}, colors=(0.25, 0.12, 0.05, 1.0, 0.7, 0.55, 0.4, 1.0))
    g.add("relief", "normal", {"input1": "noise"}, intensity=0.4)
    g.add("rough", "uniform", colorswitch=False, outputcolor=(roughness,) * 4)
    g.set_output("basecolor", "tint")
    g.set_output("normal", "relief")
    g.set_output("roughness", "rough")
    return g


def target_with_gain(g: MaterialGraph, gain: torch.Tensor, camera: FlashCamera = FlashCamera()) -> torch.Tensor:
    g.calibration.set_values(**{GAIN: gain})
    with torch.no_grad():
        target = render_maps(g(size=128, seed=3), camera)[:1]
    g.calibration.set_values(**{GAIN: torch.ones(3)})
    return target


def test_the_gain_is_the_identity_by_default_and_scales_linear_light():
    g = sample()
    plain = g(size=32, seed=1)["basecolor"]
    assert g.calibration.apply_gain(plain) is plain
    g.calibration.set_values(**{GAIN: torch.tensor([2.0, 1.0, 0.5])})
    scaled = g(size=32, seed=1)["basecolor"]
    expected = linear_to_srgb(srgb_to_linear(plain[:, :3]) * torch.tensor([2.0, 1.0, 0.5]).view(1, 3, 1, 1))
    assert torch.allclose(scaled[:, :3], expected, atol=1e-6)
    assert not torch.allclose(scaled[:, :3], plain[:, :3], atol=1e-2)


def test_the_gain_is_never_optimised_and_its_name_is_reserved():
    g = sample()
    count = g.num_params()
    g.unfreeze("*")
    assert g.num_params() == count and not any(n.startswith(CALIBRATION) for n in g.param_names())
    with pytest.raises(DiffMatError, match="reserved"):
        g.add(CALIBRATION, "uniform")


def test_params_file_carries_the_gain(tmp_path):
    g = sample()
    g.calibration.set_values(**{GAIN: KNOWN_GAIN})
    save_params(g, tmp_path / "params.json")
    assert graph_params(g)[f"{CALIBRATION}.{GAIN}"] == pytest.approx(KNOWN_GAIN.tolist(), abs=1e-5)
    fresh = sample()
    load_params(fresh, tmp_path / "params.json")
    assert torch.allclose(fresh.calibration.gain(), KNOWN_GAIN, atol=1e-5)


def test_solve_recovers_a_known_exposure_and_white_balance():
    g = sample()
    target = target_with_gain(g, KNOWN_GAIN)
    gain = solve_gain(g, target, seed=3)
    assert torch.allclose(gain, KNOWN_GAIN, rtol=0.02), gain
    assert torch.allclose(g.calibration.gain(), gain)


def test_solve_ignores_the_clipped_flash_highlight():
    """A glossy sample under a strong flash: the highlight clips in the target; the gain found
    over the other pixels is still the true one."""
    g = sample(roughness=0.1)
    camera = FlashCamera(power=2.0)
    target = target_with_gain(g, KNOWN_GAIN, camera)
    assert float((target >= CLIP_LEVEL).any(dim=1).float().mean()) > 0.01
    gain = solve_gain(g, target, seed=3, camera=camera)
    assert torch.allclose(gain, KNOWN_GAIN, rtol=0.05), gain


def test_proposal_gains_solve_each_of_a_batch_of_maps_as_solve_gain_does():
    """Two proposals of the same material, one rendered twice as bright: each gets the gain that
    brings it to the photo's level, the dim one's the product of the brighter one's and two."""
    g = sample()
    target = target_with_gain(g, KNOWN_GAIN)
    with torch.no_grad():
        maps = g(size=128, seed=3)
        bright = with_gain(maps, torch.full((1, 3), 2.0))
        batch = {u: torch.cat([maps[u], bright[u]]) for u in maps}
    gains = proposal_gains(batch, target)
    assert torch.allclose(gains[0], KNOWN_GAIN, rtol=0.02), gains
    assert torch.allclose(gains[1] * 2, KNOWN_GAIN, rtol=0.03), gains
    assert torch.allclose(gains[0], solve_gain(g, target, seed=3), rtol=1e-3)


def test_with_gain_leaves_maps_without_a_colour_base_colour_alone():
    maps = {"basecolor": torch.rand(2, 1, 8, 8), "roughness": torch.rand(2, 1, 8, 8)}
    assert with_gain(maps, torch.full((2, 3), 2.0)) is maps
    assert torch.equal(proposal_gains({"roughness": maps["roughness"]}, torch.rand(1, 3, 8, 8)), torch.ones(2, 3))


KNOWN_FALLOFF = (0.3, -0.2, -0.8, -0.6, 0.1)


def test_solve_lighting_recovers_a_known_falloff_and_finds_little_where_there_is_none():
    """The target is the graph under a phone-like falloff: solved from the ideal flash, the
    falloff comes back to 0.01. With another noise seed the material's own coarse pattern differs
    between target and render, and a target under the ideal flash solves to a falloff that stays
    small: the terms follow the light more than the material."""
    g = sample()
    with torch.no_grad():
        target = render_maps(g(size=128, seed=3), FlashCamera(falloff=KNOWN_FALLOFF))[:1]
        plain = render_maps(g(size=128, seed=3))[:1]
    camera = solve_lighting(g, target, seed=3)
    assert camera.falloff == pytest.approx(KNOWN_FALLOFF, abs=0.01)
    assert camera.power == FlashCamera().power
    assert max(abs(v) for v in solve_lighting(g, plain, seed=0).falloff) < 0.2


def test_solve_lighting_leaves_out_clipped_cells():
    """A glossy sample under a flash so strong that its centre clips: the falloff of the light
    around it is still found, and the clipped centre does not flatten it."""
    g = sample(roughness=0.1)
    camera = FlashCamera(power=2.0)
    with torch.no_grad():
        target = render_maps(g(size=128, seed=3), replace(camera, falloff=KNOWN_FALLOFF))[:1]
    assert float((target >= CLIP_LEVEL).any(dim=1).float().mean()) > 0.01
    assert solve_lighting(g, target, seed=3, camera=camera).falloff == pytest.approx(KNOWN_FALLOFF, abs=0.02)


def test_unclipped_level_leaves_out_clipped_pixels():
    image = torch.full((1, 3, 8, 8), 0.5)
    image[..., :2, :] = 1.0
    assert torch.allclose(unclipped_level(image), srgb_to_linear(torch.tensor(0.5)).expand(3))
    white = torch.ones(1, 3, 8, 8)  # nothing left unclipped: every pixel counts
    assert torch.allclose(unclipped_level(white), torch.ones(3))
