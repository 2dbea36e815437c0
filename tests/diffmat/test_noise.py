"""Known properties of the noise generators (functional/noise_generators.py, noise_grunge.py):
statistics in range, frequency grows with scale, disorder and seeds change the pattern, the
continuous scale is continuous across integers, and the node-specific controls act as documented."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import EvalContext, F, Node
from blender_match.diffmat.functional.noise_generators import NOISE_RECIPES
from blender_match.diffmat.functional.noise_grunge import GRUNGE_RECIPES
from blender_match.diffmat.functional.noise_primitives import blend_scales, fractal_noise, lattice_noise

RECIPE_NAMES = list(NOISE_RECIPES) + list(GRUNGE_RECIPES)


def _zero_crossings(x: torch.Tensor) -> float:
    """Mean sign changes of (x - mean) along rows and columns, per pixel."""
    s = torch.sign(x - x.mean())
    return ((s[..., 1:] != s[..., :-1]).float().mean() + (s[..., 1:, :] != s[..., :-1, :]).float().mean()).item() / 2


def _high_freq_share(x: torch.Tensor, cutoff: float = 8.0) -> float:
    """Share of the spectral energy (mean removed) above ``cutoff`` cycles per image."""
    spec = torch.fft.rfft2(x - x.mean()).abs() ** 2
    n = x.shape[-1]
    fy = torch.fft.fftfreq(n, 1.0 / n).abs()[:, None]
    fx = torch.fft.rfftfreq(n, 1.0 / n)[None, :]
    high = (fx ** 2 + fy ** 2).sqrt() > cutoff
    return (spec[..., high].sum() / spec.sum()).item()


@pytest.mark.parametrize("name", RECIPE_NAMES)
def test_recipe_statistics_and_seeds(name):
    fn = getattr(F, f"noise_{name}")
    a = fn(size=128, seed=1)
    assert a.shape == (1, 1, 128, 128)
    assert 0.2 < a.mean().item() < 0.8, a.mean().item()
    assert 0.08 < a.std().item() < 0.45, a.std().item()
    assert torch.equal(a, fn(size=128, seed=1))
    assert (a - fn(size=128, seed=2)).abs().mean() > 0.02


@pytest.mark.parametrize("name", ["perlin_noise", "perlin_noise_zoom", "clouds_2", "bnw_spots_2", "moisture_noise",
                                  "crystal_1", "gaussian_spots_1", "grunge_map_012", "dirt_1"])
def test_higher_scale_gives_higher_frequency(name):
    fn = getattr(F, f"noise_{name}")
    lo = fn(scale=2.0, size=128, seed=0)
    hi = fn(scale=8.0, size=128, seed=0)
    assert _zero_crossings(hi) > 1.5 * _zero_crossings(lo)
    assert _high_freq_share(hi) > _high_freq_share(lo)


@pytest.mark.parametrize("name", ["perlin_noise", "clouds_1", "crystal_2", "gaussian_spots_2", "grunge_map_001"])
def test_disorder_changes_pattern_with_period_one(name):
    fn = getattr(F, f"noise_{name}")
    d0 = fn(disorder=0.0, size=64, seed=0)
    d3 = fn(disorder=0.3, size=64, seed=0)
    d1 = fn(disorder=1.0, size=64, seed=0)
    assert (d0 - d3).abs().mean() > 0.02
    torch.testing.assert_close(d0, d1, atol=1e-4, rtol=0)
    # small disorder, small change (continuous; cellular ones move cell borders, so on average)
    assert (d0 - fn(disorder=0.001, size=64, seed=0)).abs().mean() < 0.005


@pytest.mark.parametrize("name", ["perlin_noise_zoom", "clouds_2", "fractal_sum_1", "crystal_1"])
def test_scale_blend_is_continuous_across_integers(name):
    fn = getattr(F, f"noise_{name}")
    at = fn(scale=3.0, size=64, seed=0)
    below = fn(scale=3.0 - 1e-3, size=64, seed=0)
    above = fn(scale=3.0 + 1e-3, size=64, seed=0)
    half = fn(scale=3.5, size=64, seed=0)
    assert (at - below).abs().max() < 0.02
    assert (at - above).abs().max() < 0.02
    assert (at - half).abs().mean() > 0.03


def test_scale_blend_keeps_contrast_and_has_gradient():
    s = torch.tensor([[2.5]], dtype=torch.float64, requires_grad=True)
    out = blend_scales(s, lambda k, idx: lattice_noise(k * 4, 64, seed=k, dtype=torch.float64), dtype=torch.float64)
    assert 0.8 < out.std().item() < 1.2          # normalised blend: no loss of contrast mid-way
    out.pow(2).mean().backward()
    assert s.grad is not None and s.grad.abs().item() > 0


def test_batched_scale_rows_match_single_renders():
    batch = F.noise_clouds_2(scale=torch.tensor([[1.0], [2.5]]), size=32, seed=0)
    assert batch.shape == (2, 1, 32, 32)
    torch.testing.assert_close(batch[1:], F.noise_clouds_2(scale=torch.tensor([[2.5]]), size=32, seed=0))


def test_lattice_noise_is_zero_mean_unit_std_and_tiles():
    for kind in ("value", "gradient"):
        x = lattice_noise(16, 256, seed=0, kind=kind)
        assert abs(x.mean().item()) < 0.15 and 0.8 < x.std().item() < 1.2
        big = lattice_noise(16, 512, seed=0, kind=kind)
        # same continuous function at two resolutions
        assert (torch.nn.functional.avg_pool2d(big, 2) - x).abs().mean() < 0.02


def test_fractal_roughness_adds_detail():
    smooth = fractal_noise(4, 128, octaves=5, roughness=0.1, seed=0)
    rough = fractal_noise(4, 128, octaves=5, roughness=0.9, seed=0)
    assert _high_freq_share(rough, 16) > 2 * _high_freq_share(smooth, 16)


def test_fractal_sum_base_levels_and_roughness():
    coarse = F.noise_fractal_sum_base(roughness=0.5, min_level=1, max_level=3, size=128, seed=0)
    fine = F.noise_fractal_sum_base(roughness=0.5, min_level=1, max_level=7, size=128, seed=0)
    assert _high_freq_share(fine, 12) > _high_freq_share(coarse, 12)
    r0 = F.noise_fractal_sum_base(roughness=0.0, size=128, seed=0)
    r1 = F.noise_fractal_sum_base(roughness=1.0, size=128, seed=0)
    assert _zero_crossings(r1) > 2 * _zero_crossings(r0)


def test_anisotropic_noise_streaks_and_smoothness():
    x = F.noise_anisotropic(x_amount=4, y_amount=128, smoothness=1.0, size=256, seed=0)
    dx = (x[..., 1:] - x[..., :-1]).abs().mean()
    dy = (x[..., 1:, :] - x[..., :-1, :]).abs().mean()
    assert dy > 4 * dx                            # horizontal streaks: changes mostly down the image
    sharp = F.noise_anisotropic(x_amount=4, y_amount=32, smoothness=0.0, size=256, seed=0)
    # hard bands: every row of a band is identical (8 pixels per band at 32 cells down)
    assert torch.equal(sharp[..., 0, :], sharp[..., 7, :])
    assert not torch.equal(sharp[..., 7, :], sharp[..., 8, :])


def test_anisotropic_noise_y_amount_by_resolution_is_one_row_a_pixel_at_512():
    """Substance's Y Amount By Resolution: one lattice row a pixel (production brushed metals use it
    with X Amount 1 for hairlines); ours is the 512-row lattice at every output size."""
    by = F.noise_anisotropic(x_amount=1, y_amount=8, smoothness=0.0, y_amount_by_resolution=True, size=512, seed=0)
    assert torch.equal(by, F.noise_anisotropic(x_amount=1, y_amount=512, smoothness=0.0, size=512, seed=0))
    coarse = F.noise_anisotropic(x_amount=1, y_amount=8, smoothness=0.0, size=512, seed=0)
    changes = (by[..., 1:, 0] != by[..., :-1, 0]).float().mean()
    assert changes > 0.95 and (coarse[..., 1:, 0] != coarse[..., :-1, 0]).float().mean() < 0.02
    small = F.noise_anisotropic(x_amount=1, y_amount=8, y_amount_by_resolution=True, size=128, seed=0)
    assert small.std() < 0.8 * by.std()          # four rows a pixel at 128: averaged, not resampled


def test_white_noises_statistics_and_lattice():
    w = F.noise_white(size=512, seed=0)
    assert abs(w.mean().item() - 0.5) < 0.01 and abs(w.std().item() - 0.2887) < 0.01
    assert torch.equal(torch.nn.functional.avg_pool2d(F.noise_white(size=1024, seed=0), 2), w)
    fast = F.noise_white_fast(size=512, seed=0)
    assert torch.equal(fast[..., 0::2, 0::2], fast[..., 1::2, 1::2])     # 256-texel lattice: 2x2 blocks
    blue = F.noise_blue_fast(size=256, seed=0)
    white = F.noise_white_fast(size=256, seed=0)
    assert _high_freq_share(blue, 64) > _high_freq_share(white, 64) + 0.05
    assert not torch.equal(w, F.noise_white(size=512, seed=1))


def test_grunge_balance_and_contrast():
    base = F.noise_grunge_map_012(size=64, seed=0)
    bright = F.noise_grunge_map_012(balance=0.8, size=64, seed=0)
    flat = F.noise_grunge_map_012(contrast=0.1, size=64, seed=0)
    assert bright.mean() > base.mean() + 0.1
    assert flat.std() < 0.7 * base.std()
    inverted = F.noise_grunge_map_012(balance=0.8, invert=True, size=64, seed=0)
    torch.testing.assert_close(inverted, 1.0 - bright)   # Invert: 1 - the toned map


def test_nodes_have_substance_parameters():
    assert set(Node("clouds_2").theta) == {"scale", "disorder"}
    assert set(Node("grunge_map_001").theta) == {"scale", "disorder", "balance", "contrast"}
    assert set(Node("fractal_sum_1").theta) == {"scale", "disorder", "roughness"}
    node = Node("fractal_sum_base", {"min_level": 2, "max_level": 6})
    out = node(ctx=EvalContext(size=64, seed=0))
    assert out.shape == (1, 1, 64, 64) and 0 <= out.min() and out.max() <= 1


def test_gradient_noise_has_no_lattice_grid():
    """Perlin noise alone is 0 at its lattice points and its variance halves along the lattice
    lines (a visible axis-aligned grid); the layer's variance must be nearly the same at every
    position within a cell."""
    n, size = 40, 2048
    z = lattice_noise(n, size, seed=3, kind="gradient")[0, 0]
    phase = torch.remainder((torch.arange(size) + 0.5) / size * n - 0.5, 1.0)
    col = (z ** 2).mean(0)
    bins = torch.stack([col[(phase * 8).long() == k].mean() for k in range(8)])
    assert bins.max() / bins.min() < 1.3


def _axis_energy_ratio(x: torch.Tensor) -> float:
    """Spectral energy within 10 degrees of the axes over that within 10 degrees of the diagonals
    (1 for an isotropic pattern; square blocks put their energy on the axes)."""
    spec = torch.fft.fft2(x - x.mean()).abs() ** 2
    n = x.shape[-1]
    f = torch.fft.fftfreq(n, 1.0 / n)
    fy, fx = f[:, None].abs(), f[None, :].abs()
    r = (fx ** 2 + fy ** 2).sqrt()
    ang = torch.rad2deg(torch.atan2(fy, fx))
    ring = (r > 16) & (r < n / 2)
    axes = ring & ((ang < 10) | (ang > 80))
    diag = ring & ((ang - 45).abs() < 10)
    return (spec[axes].mean() / spec[diag].mean()).item()


def test_bnw_spots_2_has_no_pixel_blocks():
    """bnw_spots_2 at scale 16 is isotropic: value noise rendered it as square blocks of a few
    pixels, with most of its energy on the axes."""
    x = F.noise_bnw_spots_2(scale=16.0, size=512, seed=3)[0, 0]
    assert _axis_energy_ratio(x) < 1.3
