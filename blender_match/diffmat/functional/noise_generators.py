"""Substance's noise generators, natively: each is a *recipe* over the primitives of
``noise_primitives`` (lattice noise, fractal sums, cellular fields, Gaussian spots, domain warp).

Substance's random numbers are closed, so each generator reproduces its namesake's documented look
and statistics (feature scale, density, contrast, anisotropy, disorder), not its pixels. The
recipes are data (``RECIPES``): one table row per generator says which primitive it starts from,
on how many lattice cells at scale 1, how many octaves with which roughness, whether the octaves
are ridged or billowed, how far the result is domain-warped, which detail layer is mixed in and
how the result is toned into [0, 1]. ``noise_grunge`` adds the dirt / grunge families as further
rows of the same table.

Common parameters (Substance identifiers, lower case):
- ``scale``: lattice frequency multiplier, continuous: a fractional scale blends the renders at the
  two neighbouring integer scales (``blend_scales``), so it is differentiable and tiling;
- ``disorder``: phase shift of every random lattice point (period 1), differentiable;
- ``roughness`` (fractal sums): weight ratio between successive octaves;
- ``balance`` / ``contrast`` (grunge maps): offset and steepness of the final tone curve.
Every generator returns (B, 1, size, size) in [0, 1]; B > 1 when a parameter is batched (B, 1).
"""
from __future__ import annotations

from dataclasses import dataclass

import torch
import torch.nn.functional as F

from .common import gaussian_blur, param4d
from .noise_primitives import (
    LAYER_STD,
    blend_scales,
    cellular_noise,
    domain_warp,
    fractal_noise,
    gaussian_spot_field,
    lattice_axis,
    lattice_noise,
    lattice_phases,
    noise_batch,
    select_rows,
    shard_field,
    squash,
    supersample_factor,
    white_lattice_noise,
)

__all__ = ["noise_recipe", "noise_white", "noise_white_fast", "noise_blue_fast", "noise_fractal_sum_base",
           "noise_anisotropic"]


@dataclass(frozen=True)
class Recipe:
    """How one named generator combines the primitives (see the module docstring).

    base: "fbm" (fractal lattice noise), "facet" (cellular: a random plane per cell, crystal look),
    "edges" (cellular F2 - F1: bright cell interiors, dark seams), "spots" (Gaussian spot field),
    "discs" (signed Gaussian spot fields over octaves: ``signed_disc_field``), "shards" (upright
    half-bell shards of signed brightness over octaves: ``shard_field``).
    cells: lattice cells across the image at scale 1; aspect: (x, y) multipliers of it (a small x
    and large y give horizontal streaks). kind / interp / octaves / roughness / mode: the fractal
    sum (``fractal_noise``). warp: domain-warp distance (texture units) by a fractal vector field
    of 2x the base cells. detail: None, "speckle" (fine fractal grain, 16x the cells), "spots",
    "cells" (cellular F1) or "edges" at ``detail_cells`` x scale, mixed with weight
    ``detail_weight``. gain / offset: the tone curve 0.5 + 0.5 tanh(gain z + offset) of the
    standardised result z; invert flips it.
    """

    base: str = "fbm"
    cells: int = 2
    aspect: tuple = (1, 1)
    kind: str = "gradient"
    interp: str = "quintic"
    octaves: int = 6
    roughness: float = 0.5
    mode: str = "fbm"
    warp: float = 0.0
    detail: str | None = None
    detail_cells: int = 16
    detail_weight: float = 0.0
    gain: float = 0.5
    offset: float = 0.0
    invert: bool = False
    radius: float = 0.3
    density: float = 1.0


def _standardise(x: torch.Tensor) -> torch.Tensor:
    s, m = torch.std_mean(x, dim=(-2, -1), keepdim=True)
    inv = 1.0 / (s + 1e-6)
    return torch.addcmul(-m * inv, x, inv)


def _base_layer(r: Recipe, k: int, size: int, seed: int, key: str, disorder, roughness, device, dtype):
    if r.base == "fbm":
        cells = (max(1, round(r.cells * r.aspect[0] * k)), max(1, round(r.cells * r.aspect[1] * k)))
        return fractal_noise(cells, size, octaves=r.octaves, roughness=roughness, seed=seed, key=key,
                             kind=r.kind, interp=r.interp, disorder=disorder, mode=r.mode,
                             device=device, dtype=dtype)
    if r.base in ("facet", "edges"):
        c = cellular_noise(r.cells * k, size, seed=seed, key=key, disorder=disorder, device=device, dtype=dtype)
        if r.base == "facet":
            return c["facet"]
        return (c["f2"] - c["f1"]) + 0.25 * c["facet"]
    if r.base == "spots":
        return gaussian_spot_field(r.cells * k, size, seed=seed, key=key, radius=r.radius, density=r.density,
                                   disorder=disorder, device=device, dtype=dtype)
    if r.base == "discs":
        return signed_disc_field(r, k, size, seed, key, disorder, roughness, device, dtype)
    if r.base == "shards":
        return level_sum(lambda cells, level: shard_field(cells, size, seed=seed, key=(key, level), disorder=disorder,
                                                          device=device, dtype=dtype),
                         r, k, size, roughness, device, dtype)
    raise ValueError(f"unknown recipe base {r.base!r}")


def level_sum(level_field, r: Recipe, k: int, size: int, roughness, device, dtype) -> torch.Tensor:
    """The sum over ``r.octaves`` levels of ``level_field(cells, level)``, from ``r.cells`` x ``k``
    cells across, each level twice as dense and ``roughness`` times as strong. Levels with fewer
    than two pixels a cell are left out of the render, as ``fractal_noise`` does."""
    weight = param4d(roughness).to(device=device, dtype=dtype)
    total: torch.Tensor | float = 0.0
    for level in range(r.octaves):
        cells = r.cells * k * 2 ** level
        if level and 2 * cells > size:
            break
        total = total + weight ** level * level_field(cells, level)
    assert isinstance(total, torch.Tensor)
    return total


def signed_disc_field(r: Recipe, k: int, size: int, seed: int, key: str, disorder, roughness, device, dtype):
    """Soft discs of random size added to and subtracted from a flat field over ``level_sum``'s
    levels (Substance's Moisture noise: "discs of varying hardness and size are scattered and add
    or subtract from the color below, starting from a base gray"). (B, 1, size, size)."""
    def discs(cells: int, level: int) -> torch.Tensor:
        ups, downs = (gaussian_spot_field(cells, size, seed=seed, key=(key, sign, level), radius=r.radius,
                                          density=r.density, disorder=disorder, device=device, dtype=dtype)
                      for sign in ("add", "subtract"))
        return ups - downs
    return level_sum(discs, r, k, size, roughness, device, dtype)


def _detail_layer(r: Recipe, k: int, size: int, seed: int, key: str, disorder, device, dtype):
    n = r.detail_cells * k
    if r.detail == "speckle":
        return fractal_noise(min(n, 512), size, octaves=2, roughness=0.5, seed=seed, key=(key, "speckle"),
                             kind="value", interp="cubic", disorder=disorder, device=device, dtype=dtype)
    if r.detail == "spots":
        return gaussian_spot_field(n, size, seed=seed, key=(key, "spots"), radius=0.25, density=0.6,
                                   disorder=disorder, device=device, dtype=dtype)
    c = cellular_noise(n, size, seed=seed, key=(key, "cells"), disorder=disorder, device=device, dtype=dtype)
    if r.detail == "cells":
        return -c["f1"]
    if r.detail == "edges":
        return c["f2"] - c["f1"]
    raise ValueError(f"unknown recipe detail {r.detail!r}")


def _render(r: Recipe, k: int, idx, size, seed, key, disorder, roughness, device, dtype):
    d = select_rows(disorder, idx)
    rough = select_rows(roughness, idx)
    z = _standardise(_base_layer(r, k, size, seed, key, d, rough, device, dtype))
    if r.detail is not None and r.detail_weight > 0:
        dz = _standardise(_detail_layer(r, k, size, seed, key, d, device, dtype))
        z = _standardise(z + r.detail_weight * dz)
    if r.warp > 0:
        wc = max(1, 2 * r.cells * k // 2)
        du = fractal_noise(wc, size, octaves=3, roughness=0.5, seed=seed, key=(key, "warp_u"), kind="gradient",
                           disorder=d, device=device, dtype=dtype)
        dv = fractal_noise(wc, size, octaves=3, roughness=0.5, seed=seed, key=(key, "warp_v"), kind="gradient",
                           disorder=d, device=device, dtype=dtype)
        z = domain_warp(z, du, dv, r.warp / max(k, 1) ** 0.5)
    return z


def noise_recipe(recipe: Recipe, *, scale=1.0, disorder=0.0, roughness=None, balance=0.5, contrast=0.5,
                 name: str = "noise", size: int = 512, seed: int = 0, device=None,
                 dtype=torch.float32) -> torch.Tensor:
    """Render ``recipe`` (see ``Recipe``): continuous ``scale`` (blend of integer scales),
    ``disorder``, optional ``roughness`` (defaults to the recipe's), ``balance`` (0.5 = the node's
    own look; higher is brighter) and ``contrast`` (0.5 = the node's own look; the tone-curve gain
    is multiplied by exp(3 (contrast - 0.5))). Returns (B, 1, size, size) in [0, 1]."""
    rough = recipe.roughness if roughness is None else roughness
    if isinstance(rough, torch.Tensor):
        rough = rough.to(device=device, dtype=dtype)
    batch = noise_batch(scale, disorder, rough, balance, contrast)

    def render(k, idx):
        return _render(recipe, k, idx, size, seed, name, disorder, rough, device, dtype)

    z = blend_scales(scale, render, batch=batch, device=device, dtype=dtype)
    like = z
    gain = recipe.gain * torch.exp(3.0 * (param4d(contrast, like) - 0.5))
    offset = recipe.offset + 4.0 * (param4d(balance, like) - 0.5)
    t = torch.tanh(torch.addcmul(offset, z, gain))
    # squash (0.5 + 0.5 tanh), inverted when the recipe says so
    return t.mul(-0.5 if recipe.invert else 0.5).add_(0.5)


# ----------------------------------------------------------------------------------------------
# generators that are not recipes
def noise_white(*, size: int = 512, seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """White Noise: an independent uniform value per texel of a fixed 512 x 512 texture-space
    lattice (per pixel at 512; blocks above; below, box averages re-toned to a uniform histogram,
    see ``white_lattice_noise``)."""
    return white_lattice_noise(size, cells=512, seed=seed, key="white_noise", device=device, dtype=dtype)


def noise_white_fast(*, size: int = 512, seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """White Noise Fast: the cheaper variant, a uniform value per texel of a 256 x 256 lattice."""
    return white_lattice_noise(size, cells=256, seed=seed, key="white_noise_fast", device=device, dtype=dtype)


def noise_blue_fast(*, size: int = 512, seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """Blue Noise Fast: white noise on a 256 x 256 lattice with its low frequencies removed
    (minus a Gaussian blur of 1 texel), standardised, toned into [0, 1] and sampled like White
    Noise: grain without clumps."""
    lat = white_lattice_noise(256, cells=256, seed=seed, key="blue_noise_fast", device=device,
                              dtype=torch.float64)
    hp = lat - gaussian_blur(lat, 1.0 / 256)
    hp = squash(_standardise(hp), 0.55)
    hp = hp.to(dtype)
    if size >= 256:
        return hp.repeat_interleave(size // 256, -1).repeat_interleave(size // 256, -2)
    return F.avg_pool2d(hp, 256 // size)


def noise_fractal_sum_base(*, roughness=0.5, min_level: int = 1, max_level: int = 8, size: int = 512,
                           seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """Fractal Sum Base: a sum of value-noise levels; level L has 2^L cells and weight
    roughness^(L - min_level), for L in [min_level, max_level] (levels above 10 are dropped).
    Roughness 0 keeps only the coarsest level; 1 weighs all levels equally."""
    lo, hi = min(min_level, max_level), max(min_level, max_level)
    z = fractal_noise(2 ** lo, size, octaves=hi - lo + 1, roughness=roughness, seed=seed, key="fractal_sum_base",
                      kind="value", interp="cubic", device=device, dtype=dtype)
    return squash(z, 0.45)


# the rows of an Anisotropic Noise whose Y Amount follows the resolution: one a pixel at 512 px,
# White Noise's texture-space lattice, so that the maps stay the same at every output size
RESOLUTION_ROWS = 512
# the most lattice cells a side Anisotropic Noise takes: production files set 289 and 512
MAX_LATTICE = 1024


def noise_anisotropic(*, x_amount: int = 8, y_amount: int = 128, smoothness=0.5, interpolation: bool = True,
                      rotate: bool = False, y_amount_by_resolution: bool = False, size: int = 512, seed: int = 0,
                      device=None, dtype=torch.float32) -> torch.Tensor:
    """Anisotropic Noise: random values on an x_amount x y_amount lattice, interpolated smoothly
    along x (long horizontal streaks when y_amount > x_amount). ``smoothness`` blends the hard-edged
    version (each streak a constant band down y) with the smoothly interpolated one;
    ``interpolation`` off uses linear instead of cubic interpolation; ``rotate`` turns the result a
    quarter turn (vertical streaks). ``y_amount_by_resolution`` replaces ``y_amount`` by
    ``RESOLUTION_ROWS`` rows (Substance: one row a pixel of the output; brushed-metal hairlines)."""
    if y_amount_by_resolution:
        y_amount = RESOLUTION_ROWS
    interp = "cubic" if interpolation else "linear"
    smooth = lattice_noise((x_amount, y_amount), size, seed=seed, key="anisotropic", kind="value", interp=interp,
                           device=device, dtype=dtype)
    # hard rows: the same lattice values, nearest along y (value interpolated along x only)
    sharp = _rows_nearest(x_amount, y_amount, size, seed, interp, device, dtype)
    t = param4d(smoothness).to(device=device, dtype=dtype)
    z = ((1 - t) * sharp + t * smooth) / torch.sqrt((1 - t) ** 2 + t ** 2)
    out = squash(z, 0.5)
    return out.transpose(-1, -2) if rotate else out


def _rows_nearest(nx, ny, size, seed, interp, device, dtype):
    """Value noise of lattice (nx, ny), interpolated along x, nearest (constant bands) along y."""
    phi, _ = lattice_phases(seed, ("anisotropic", "value"), ny, nx, device, dtype)
    lat = torch.cos(2 * torch.pi * phi)
    ss = max(supersample_factor(size, nx), supersample_factor(size, ny))
    res = size * ss
    ix0, ix1, fx, wx = lattice_axis(res, nx, device, dtype, interp)
    iy0, _, _, _ = lattice_axis(res, ny, device, dtype, "nearest")
    t = lat[..., ix0] * (1 - wx) + lat[..., ix1] * wx
    out = t[:, iy0][:, None] / LAYER_STD[("value", interp)]
    if ss > 1:
        out = F.avg_pool2d(out, ss)
    return out


# ----------------------------------------------------------------------------------------------
# the recipe table: name -> (recipe, (scale min, max, default), extra parameter names)
# Scale ranges follow Substance's sliders where known (Perlin Noise 1-256, most noises 1-32);
# the cells-per-scale figure sets what scale 1 looks like.
NOISE_RECIPES: dict[str, tuple[Recipe, tuple, tuple]] = {
    # soft fractal gradient noise, zoomable: 6 octaves from `scale` cells
    "perlin_noise_zoom": (Recipe(cells=1, octaves=6, roughness=0.5, gain=0.55), (1, 64, 10), ()),
    # Clouds 1: soft value-noise clouds, 8 octaves from 2 cells
    "clouds_1": (Recipe(kind="value", cells=2, octaves=8, roughness=0.5, gain=0.45), (1, 32, 1), ()),
    # Clouds 2: more contrasted, more detailed gradient clouds; Substance builds it from FX-map levels of
    # 8 to 256 patterns across (each 5 x 1 cells, randomly turned) with roughness 0.66 per level
    "clouds_2": (Recipe(cells=4, octaves=7, roughness=0.66, gain=0.7), (1, 32, 1), ()),
    # Clouds 3: very soft, large, slightly swirled clouds
    "clouds_3": (Recipe(kind="value", interp="cubic", cells=1, octaves=5, roughness=0.45, warp=0.05, gain=0.4),
                 (1, 32, 1), ()),
    # BnW Spots 1/2/3: black and white spots, coarse to fine. Substance's BnW Spots 3 sums FX-map levels of
    # 4 to 512 patterns across at equal opacity (roughness 1) into a mid-gray range: dense speckle over
    # soft mottling, not saturated blobs; Spots 2 lies between it and the coarse Spots 1
    "bnw_spots_1": (Recipe(cells=4, octaves=5, roughness=0.5, gain=1.6), (1, 32, 1), ()),
    "bnw_spots_2": (Recipe(cells=4, octaves=7, roughness=0.75, gain=1.5), (1, 32, 1), ()),
    "bnw_spots_3": (Recipe(cells=4, octaves=7, roughness=0.9, gain=0.9), (1, 32, 1), ()),
    # Moisture Noise: soft discs added to and subtracted from grey, 5 levels from 4 cells
    "moisture_noise": (Recipe(base="discs", cells=4, octaves=5, roughness=0.6, radius=0.35, gain=0.6), (1, 32, 1), ()),
    # Fractal Sum 1-4: presets of a fractal sum (plain value, ridged, billowed, fine gradient)
    "fractal_sum_1": (Recipe(kind="value", cells=2, octaves=8, roughness=0.5, gain=0.45), (1, 32, 1), ("roughness",)),
    "fractal_sum_2": (Recipe(cells=2, octaves=7, roughness=0.55, mode="ridged", gain=0.6), (1, 32, 1), ("roughness",)),
    "fractal_sum_3": (Recipe(kind="value", cells=4, octaves=6, roughness=0.6, mode="billow", gain=0.5), (1, 32, 1),
                      ("roughness",)),
    "fractal_sum_4": (Recipe(cells=8, octaves=6, roughness=0.7, gain=0.45), (1, 32, 1), ("roughness",)),
    # Perlin Noise: one octave of gradient noise on `scale` cells
    "perlin_noise": (Recipe(cells=1, octaves=1, gain=0.5), (1, 256, 32), ()),
    # legacy Perlin Noise 1 / 2: two and three octaves, low roughness
    "perlin_noise_1": (Recipe(cells=1, octaves=2, roughness=0.35, gain=0.5), (1, 64, 8), ()),
    "perlin_noise_2": (Recipe(kind="value", interp="cubic", cells=1, octaves=3, roughness=0.4, gain=0.5),
                       (1, 64, 16), ()),
    # Directional noise: horizontally stretched fractal (8x more cells down than across)
    "directionnal_noise": (Recipe(cells=1, aspect=(1, 8), octaves=5, roughness=0.55, gain=0.55), (1, 32, 4), ()),
    "directional_noise_4": (Recipe(kind="value", cells=1, aspect=(1, 12), octaves=4, roughness=0.5, mode="ridged",
                                   warp=0.02, gain=0.6), (1, 32, 4), ()),
    # Crystal 1: random facets per cell; Crystal 2: upright half-bell shards of signed brightness over
    # grey, 3 levels from 8 cells, each 0.18 times as strong (the MATch reference's facts)
    "crystal_1": (Recipe(base="facet", cells=4, detail="speckle", detail_cells=16, detail_weight=0.15, gain=1.0),
                  (1, 32, 2), ()),
    "crystal_2": (Recipe(base="shards", cells=8, octaves=3, roughness=0.18, gain=0.22), (1, 16, 1), ()),
    # Herb 1: vertical blades (16x more cells across than down), ridged, slightly warped
    "herb_1": (Recipe(cells=1, aspect=(16, 1), octaves=3, roughness=0.5, mode="ridged", warp=0.03, gain=1.2,
                      offset=-0.3), (1, 32, 2), ()),
    # Wood fibers: fine vertical fibres
    "wood_fibers_1": (Recipe(kind="value", interp="cubic", cells=1, aspect=(24, 1), octaves=3, roughness=0.6,
                             gain=0.9), (1, 32, 2), ()),
    "wood_fibers_2": (Recipe(cells=1, aspect=(24, 1), octaves=3, roughness=0.5, mode="ridged", warp=0.02, gain=0.9),
                      (1, 32, 2), ()),
    # Vertical noise: values vary across, barely down (vertical streaks)
    "vertical_noise": (Recipe(kind="value", interp="cubic", cells=1, aspect=(8, 1), octaves=4, roughness=0.5,
                              gain=0.5), (1, 32, 4), ()),
    # Gaussian spots: soft round spots on a jittered grid, dense or sparse
    "gaussian_spots_1": (Recipe(base="spots", cells=8, radius=0.3, density=0.8, gain=1.2, offset=-0.6),
                         (1, 32, 1), ()),
    "gaussian_spots_2": (Recipe(base="spots", cells=8, radius=0.22, density=0.45, detail="spots", detail_cells=4,
                                detail_weight=0.5, gain=1.2, offset=-0.8), (1, 32, 1), ()),
    # Gaussian noise: fine grain with a Gaussian histogram (almost linear tone)
    "gaussian_noise": (Recipe(kind="value", cells=32, octaves=2, roughness=0.5, gain=0.3), (1, 16, 1), ()),
    # Plasma: many-octave value fractal
    "plasma": (Recipe(kind="value", interp="cubic", cells=1, octaves=9, roughness=0.62, gain=0.5), (1, 32, 1), ()),
    # Fluid: strongly warped ridged fractal; Liquid: warped billows
    "fluid": (Recipe(cells=2, octaves=6, roughness=0.5, mode="ridged", warp=0.15, gain=0.7), (1, 32, 1), ()),
    "liquid": (Recipe(kind="value", cells=2, octaves=5, roughness=0.45, mode="billow", warp=0.1, gain=0.9),
               (1, 32, 1), ()),
    # Fur 1-4: fine anisotropic hair strands, warped
    "fur_1": (Recipe(cells=4, aspect=(16, 1), octaves=2, roughness=0.5, warp=0.03, gain=0.8), (1, 16, 1), ()),
    "fur_2": (Recipe(kind="value", cells=6, aspect=(16, 1), octaves=2, roughness=0.5, mode="ridged", warp=0.05,
                     gain=0.9), (1, 16, 1), ()),
    "fur_3": (Recipe(cells=3, aspect=(16, 1), octaves=3, roughness=0.5, mode="billow", warp=0.08, gain=0.8),
              (1, 16, 1), ()),
    "fur_4": (Recipe(cells=8, aspect=(16, 1), octaves=2, roughness=0.5, warp=0.02, detail="spots", detail_cells=16,
                     detail_weight=0.3, gain=0.9), (1, 16, 1), ()),
}


def make_recipe_generator(name: str, recipe: Recipe, extra: tuple = ()):
    """A named functional for a recipe row: keyword parameters scale, disorder (+ ``extra``:
    roughness, balance and contrast, invert)."""
    has_rough = "roughness" in extra
    has_tone = "balance" in extra
    has_invert = "invert" in extra

    def generator(*, scale=1.0, disorder=0.0, roughness=recipe.roughness, balance=0.5, contrast=0.5,
                  invert: bool = False, size: int = 512, seed: int = 0, device=None,
                  dtype=torch.float32) -> torch.Tensor:
        out = noise_recipe(recipe, scale=scale, disorder=disorder, roughness=roughness if has_rough else None,
                           balance=balance if has_tone else 0.5, contrast=contrast if has_tone else 0.5,
                           name=name, size=size, seed=seed, device=device, dtype=dtype)
        return 1.0 - out if invert and has_invert else out

    generator.__name__ = generator.__qualname__ = f"noise_{name}"
    generator.__doc__ = f"Substance's {name}: {recipe}. See ``Recipe`` and ``noise_recipe``."
    return generator


for _name, (_recipe, _scale, _extra) in NOISE_RECIPES.items():
    globals()[f"noise_{_name}"] = make_recipe_generator(_name, _recipe, _extra)
    __all__.append(f"noise_{_name}")
