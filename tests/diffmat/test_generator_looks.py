"""The generators' look against Substance's own (docs/generators.md): feature scale, value
distribution and contrast of the defaults that were corrected, plus tiling, seed determinism and
agreement across resolutions of those generators."""
from __future__ import annotations

import pytest
import torch
import torch.nn.functional as tnf

from blender_match.diffmat import F
from blender_match.diffmat.functional.common import gaussian_blur

CHANGED_NOISES = ("clouds_2", "bnw_spots_2", "bnw_spots_3", "moisture_noise")


def _spectral_centroid(x: torch.Tensor) -> float:
    """Energy-weighted mean spatial frequency (cycles per image) of a (1, 1, n, n) image."""
    x = x[0, 0].double()
    spec = torch.fft.rfft2(x - x.mean()).abs() ** 2
    n = x.shape[-1]
    fy = torch.fft.fftfreq(n, 1.0 / n).abs()[:, None]
    fx = torch.fft.rfftfreq(n, 1.0 / n)[None, :]
    r = (fx ** 2 + fy ** 2).sqrt()
    return ((spec * r).sum() / spec.sum()).item()


def _high_freq_share(x: torch.Tensor, cutoff: float) -> float:
    x = x[0, 0].double()
    spec = torch.fft.rfft2(x - x.mean()).abs() ** 2
    n = x.shape[-1]
    fy = torch.fft.fftfreq(n, 1.0 / n).abs()[:, None]
    fx = torch.fft.rfftfreq(n, 1.0 / n)[None, :]
    return (spec[(fx ** 2 + fy ** 2).sqrt() > cutoff].sum() / spec.sum()).item()


def _saturated(x: torch.Tensor) -> float:
    """Share of pixels within 0.05 of black or white."""
    return ((x < 0.05) | (x > 0.95)).float().mean().item()


@pytest.mark.parametrize("size", [64, 128, 256])
def test_white_noise_is_uniform_at_every_size(size):
    """Substance's white noise is uniform on [0, 1] per pixel at any size; box averages of the
    512 lattice had a quarter of the spread at 128 px and nothing below 0.3."""
    for fn in (F.noise_white, F.noise_white_fast):
        w = fn(size=size, seed=4)
        assert abs(w.mean().item() - 0.5) < 0.01
        assert abs(w.std().item() - 0.2887) < 0.01
        assert abs((w < 0.1).float().mean().item() - 0.1) < 0.01
        assert torch.equal(w, fn(size=size, seed=4))
        assert not torch.equal(w, fn(size=size, seed=5))


def test_white_noise_small_render_follows_the_large_one():
    """Below the lattice size the render is a monotone re-toning of the box-downsampled large render."""
    small = F.noise_white(size=128, seed=2, dtype=torch.float64).flatten()
    down = tnf.avg_pool2d(F.noise_white(size=512, seed=2, dtype=torch.float64), 4).flatten()
    assert torch.equal(torch.argsort(small, stable=True), torch.argsort(down, stable=True))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_clouds_2_has_medium_features(seed):
    """Clouds 2 starts at FX-map levels of 8 patterns across (5 x 1 cells each): its energy sits at
    about 4-8 cycles per image, not at the 2-3 of the large soft blobs it had."""
    c = _spectral_centroid(F.noise_clouds_2(size=128, seed=seed))
    assert 4.0 < c < 8.0, c


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_bnw_spots_3_is_dense_speckle_not_saturated_patches(seed):
    """BnW Spots 3 sums levels of 4 to 512 patterns across at equal opacity into a mid-gray range:
    fine detail everywhere, few pixels at pure black or white (it was about half)."""
    x = F.noise_bnw_spots_3(size=128, seed=seed)
    assert _saturated(x) < 0.2
    assert _high_freq_share(x, 16) > 0.15
    assert 0.25 < x.std().item() < 0.35


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_bnw_spots_2_is_balanced_black_and_white(seed):
    """BnW Spots 2: as much white as black with fine detail (the billowed version was dark, with
    saturated white blobs over about 45 % of the image)."""
    x = F.noise_bnw_spots_2(size=128, seed=seed)
    assert 0.45 < x.mean().item() < 0.55
    assert 0.2 < _saturated(x) < 0.4


def _streakiness(x: torch.Tensor) -> float:
    """Mean coherence of the structure tensor (0: no preferred direction anywhere, 1: parallel
    streaks everywhere) of a (1, 1, n, n) image, gradients smoothed over about 8 pixels."""
    gx = (x.roll(-1, -1) - x.roll(1, -1)) / 2
    gy = (x.roll(-1, -2) - x.roll(1, -2)) / 2
    xx, yy, xy = (gaussian_blur(t, 4.0) for t in (gx * gx, gy * gy, gx * gy))
    return ((xx - yy) ** 2 + 4 * xy * xy).sqrt().div(xx + yy + 1e-9).mean().item()


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_moisture_noise_is_discs_around_grey_not_swirls(seed):
    """Moisture noise: discs of varying size added to and subtracted from a base grey (Substance's
    documentation). Its mean stays at mid-grey and nothing in it runs in one direction; the
    domain-warped fractal it replaced drew marble-like swirls (streakiness 0.06-0.12, here under 0.045)."""
    x = F.noise_moisture_noise(size=256, seed=seed)
    assert 0.47 < x.mean().item() < 0.53
    assert _streakiness(x) < 0.045


@pytest.mark.parametrize("name", ["dirt_1", "dirt_2", "dirt_3", "dirt_4", "dirt_5"])
def test_dirt_noises_are_grainy_not_swirled_or_streaked(name):
    """Substance's documentation: each Dirt noise is "a variation of the grainy Dirt noises". None is
    domain-warped or ridged into swirls, and none runs in one direction (dirt_5 was stretched into
    horizontal streaks, streakiness 0.63-0.67)."""
    from blender_match.diffmat.functional.noise_grunge import GRUNGE_RECIPES
    recipe = GRUNGE_RECIPES[name][0]
    assert recipe.warp == 0 and recipe.mode != "ridged" and recipe.aspect == (1, 1)
    for seed in (0, 1, 2):
        x = getattr(F, f"noise_{name}")(size=256, seed=seed)
        assert _streakiness(x) < 0.1


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_crystal_2_is_upright_shards_in_a_grey_range(seed):
    """Crystal 2 sums long near-upright shards of signed brightness onto mid-grey, its coarsest
    level dominating (the MATch reference: std about 0.11, no black or white): steps across are
    several times the steps down. The cellular F2 - F1 it replaced had no direction (ratio about
    1) and three times the contrast, 18 % of it black or white."""
    x = F.noise_crystal_2(size=128, seed=seed)[0, 0]
    across = (x[:, 1:] - x[:, :-1]).abs().mean().item()
    down = (x[1:] - x[:-1]).abs().mean().item()
    assert across > 2.5 * down
    assert 0.08 < x.std().item() < 0.14
    assert _saturated(x) < 0.01


def test_crystal_2_tiles_and_agrees_across_sizes():
    """Its hard shard edges make steps between neighbouring rows vary a lot, so the step across the
    wrap is held to the largest step inside (a seam would stand above all of them)."""
    x = F.noise_crystal_2(size=128, seed=3)
    img = x[0, 0]
    for rows in (img, img.T):
        steps = (rows - rows.roll(1, 0)).abs().mean(1)       # steps[0] is across the wrap
        assert steps[0] <= steps[1:].max()
    assert (tnf.avg_pool2d(F.noise_crystal_2(size=256, seed=3), 2) - x).abs().mean() < 0.05


@pytest.mark.parametrize("name", CHANGED_NOISES)
def test_changed_noises_tile_and_agree_across_sizes(name):
    fn = getattr(F, f"noise_{name}")
    x = fn(size=128, seed=3)
    assert torch.equal(x, fn(size=128, seed=3))
    img = x[0, 0]
    inner_x = (img[:, 1:] - img[:, :-1]).abs().mean()
    inner_y = (img[1:] - img[:-1]).abs().mean()
    assert (img[:, 0] - img[:, -1]).abs().mean() < 1.4 * inner_x        # no seam across the wrap
    assert (img[0] - img[-1]).abs().mean() < 1.4 * inner_y
    big = fn(size=256, seed=3)
    assert (tnf.avg_pool2d(big, 2) - x).abs().mean() < 0.05
    assert x.dtype == torch.float32 and 0.0 <= x.min() and x.max() <= 1.0


def test_tile_generator_default_brick_has_a_narrow_bevel():
    """Substance's Tile Generator defaults to Brick with pattern specific (bevel) 0.2: flat tops
    over most of each tile, a thin ramp down to the gaps (0.5 bevelled about half of every tile)."""
    t = F.tile_pattern(pattern=8, size=128, seed=0)
    assert (t > 0.99).float().mean().item() > 0.7
    assert t[0, 0, 6, :].min().item() < 0.2            # the ramp still reaches down at the tile borders


def test_anisotropic_noise_rotate_turns_the_streaks_upright():
    """Production files set Anisotropic Noise's ``rotate`` on one of two otherwise equal noises (a
    crossed scrim); it turns the horizontal streaks a quarter turn."""
    flat = F.noise_anisotropic(size=64, seed=2)
    upright = F.noise_anisotropic(size=64, seed=2, rotate=True)
    assert torch.equal(upright, flat.transpose(-1, -2))
    across = (upright[..., :, 1:] - upright[..., :, :-1]).abs().mean()
    down = (upright[..., 1:, :] - upright[..., :-1, :]).abs().mean()
    assert across > 3 * down

