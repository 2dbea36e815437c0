"""How a graph's material meets a real photo: its exposure and white balance (a per-channel gain
on the base colour), the falloff of its flash over the frame (``FlashCamera.falloff``), both
solved in closed form, and the scale it shows the material at (the zoom, searched by
``diffmat.zoom_search``; ``framed_maps`` renders it).

The renderer assumes a known flash power and a neutral white balance (``FlashCamera``); a phone
photo has neither. One flash photo fixes albedo only up to that gain (a bright photo of a dark
material and a dark photo of a bright one look alike), and a graph whose colour parameters cannot
reach the photo's colour would otherwise be left too dark, too bright or of another hue. The
descriptor loss is not the tool for it: a Gram matrix mixes colour with structure.

``solve_gain`` sets the gain for which the render's level equals the photo's, per channel: the
mean linear radiance of the darker 80% of the pixels that the image does not clip. The flash
highlight says nothing about colour: clipped pixels are left out, and so is the brightest fifth,
where a glossy photo's broad sheen or a metal's sparkle would pull a plain mean (a varnished wood's
sheen asked for four times its blue, greying the wood). A median would do the same but jumps
between the modes of a two-tone material (a speckled granite's gain went from 0.85 to 3). The
render's level is close to a * gain + b per channel (diffuse light scales with the base colour, a
dielectric's specular light does not; clipping bends it), so the first step applies the ratio and
the next ones the secant through the last two renders.

The gain lives in the graph as the graph-level parameter set ``calibration`` (``PhotoCalibration``,
applied to the ``basecolor`` output by ``MaterialGraph.forward``): the written maps, params.json,
a re-render and the Blender material all carry it. The zoom lives there too; the Blender material
carries it as its Mapping scale. Neither is ever part of the optimised vector.

``solve_lighting`` finds the photo's falloff: a phone's flash has a beam pattern and its lens
vignettes, so its light falls off towards the corners faster than the ideal flash's, often
off-centre. It fits the log ratio of photo and render luminance over a grid of cells with smooth
terms (least squares, clipped cells left out). The falloff belongs to the photo, not to the
material: it lives on the camera the fit renders with, and no map carries it.
"""
from __future__ import annotations

import math
from dataclasses import replace

import torch
import torch.nn.functional as F

from ..vocabulary import CALIBRATION, GAIN, ZOOM
from .nodes.module import ParameterSet
from .render import FlashCamera, linear_to_srgb, render_maps, srgb_to_linear

# Three stops either way: beyond that the gain no longer stands for an exposure but rewrites a colour
# the graph cannot make, and magnifies the noise and tint of a near-black map (a black leather went green).
GAIN_RANGE = (1 / 8, 8.0)
CLIP_LEVEL = 0.98  # an sRGB value at or above this, in any channel, counts as clipped
MIN_UNCLIPPED = 0.05  # below this share of unclipped pixels, every pixel counts
KEEP_DARKEST = 0.8  # the level is the mean of this darker share of the unclipped pixels
SOLVE_STEPS = 4
# From half a texture period across the photo to four periods: beyond, the graph's own scale
# parameters are the better lever (and zooming in costs the square in pixels).
ZOOM_RANGE = (0.5, 4.0)
MIN_TILE = 16  # the smallest tile a zoomed-out graph is evaluated at, in pixels
LIGHTING_CELLS = 16  # the falloff is fitted to the frame's light in this many cells across
MIN_LIGHTING_CELLS = 32  # fewer usable (unclipped, lit) cells than this: the falloff is left as it is
# The most any falloff term may reach: exp(-1) from the centre to an edge, about what a phone's
# flash held close and its lens's vignetting make on matte samples (the development photos' matte
# ones solve to -0.2 to -0.8 per quadratic term). Beyond it the fit follows the material, not the
# light: a glossy photo's broad sheen solved to -2.2, and the material then lost its gloss.
FALLOFF_LIMIT = 1.0


class PhotoCalibration(ParameterSet):
    """How the graph's material meets the photo: the gain on the linear base colour (3
    components, 1 = none; set by ``solve_gain``) and the zoom, the number of texture periods
    across the photo's width (1 = one tile fills the photo; set by ``diffmat.zoom_search``).
    Both fixed: never optimised."""

    def __init__(self):
        super().__init__(CALIBRATION)
        self._store(GAIN, [1.0, 1.0, 1.0], *GAIN_RANGE, size=3, widen=False, trainable=False)
        self._store(ZOOM, 1.0, *ZOOM_RANGE, size=1, widen=False, trainable=False)

    def optimizable(self, name: str) -> bool:
        return False

    def gain(self) -> torch.Tensor:
        return self.values()[GAIN]

    def periods(self) -> float:
        """The zoom: texture periods across the photo."""
        return float(self.values()[ZOOM])

    def apply_gain(self, basecolor: torch.Tensor) -> torch.Tensor:
        """``basecolor`` (N, C, H, W) sRGB with its RGB scaled by the gain in linear light (alpha
        kept); unchanged when the gain is one."""
        gain = self.gain().to(basecolor)
        if bool((gain == 1).all()) or basecolor.shape[1] < 3:
            return basecolor
        return scaled_basecolor(basecolor, gain.view(1, 3))


def scaled_basecolor(basecolor: torch.Tensor, gain: torch.Tensor) -> torch.Tensor:
    """``basecolor`` (N, C >= 3, H, W) sRGB with its RGB scaled by ``gain`` (N or 1, 3) in linear
    light (alpha kept)."""
    rgb = linear_to_srgb(srgb_to_linear(basecolor[:, :3]) * gain[:, :, None, None])
    return torch.cat([rgb, basecolor[:, 3:]], dim=1)


def framed_maps(graph, size: int, seed: int = 0, theta: torch.Tensor | None = None,
                cache: bool = True) -> dict[str, torch.Tensor]:
    """The graph's maps as the photo frames them, ``size`` px across: one texture period is
    evaluated at ``size / zoom`` px (the graph gives the same texture at every power-of-two size;
    a zoom between octaves is taken at the nearest octave) and repeated, or cropped, to ``size``.
    Repeating a period keeps the maps seamless, as the Blender material's Mapping scale does."""
    side = max(MIN_TILE, 2 ** round(math.log2(size / graph.calibration.periods())))
    maps = graph(size=side, seed=seed, theta=theta, cache=cache)
    if side == size:
        return maps
    reps = -(-size // side)
    return {u: m.repeat(1, 1, reps, reps)[..., :size, :size] for u, m in maps.items()}


def framed_render(graph, photo: torch.Tensor, seed: int = 0, camera: FlashCamera = FlashCamera(),
                  theta: torch.Tensor | None = None) -> torch.Tensor:
    """The flash render (1, 3, S, S) under ``camera`` of the graph's ``framed_maps`` at the size of
    ``photo`` (1, 3, S, S), of the parameters ``theta`` (P,) when given, else its own."""
    vector = None if theta is None else theta.reshape(1, -1).to(photo.device)
    return render_maps(framed_maps(graph, photo.shape[-1], seed, vector), camera)[:1]


def unclipped_level(image: torch.Tensor) -> torch.Tensor:
    """Per-channel level (3,) of an sRGB (1, 3, H, W) image: the mean linear radiance of the
    darker ``KEEP_DARKEST`` of the pixels with no channel at ``CLIP_LEVEL`` or above (of every
    pixel when fewer than ``MIN_UNCLIPPED`` are unclipped)."""
    keep = (image[0] < CLIP_LEVEL).all(dim=0)
    if float(keep.float().mean()) < MIN_UNCLIPPED:
        keep = torch.ones_like(keep)
    levels = []
    for channel in srgb_to_linear(image[0]):
        values = channel[keep].sort().values
        levels.append(values[:max(1, int(KEEP_DARKEST * values.numel()))].mean())
    return torch.stack(levels)


def cell_levels(image: torch.Tensor, cells: int = LIGHTING_CELLS) -> tuple[torch.Tensor, torch.Tensor]:
    """(mean linear luminance, share of clipped pixels) of each of ``cells`` x ``cells`` cells of an
    sRGB (1, 3, S, S) image."""
    lum = srgb_to_linear(image[:1].float()).mean(dim=1, keepdim=True)
    clipped = (image[:1] >= CLIP_LEVEL).any(dim=1, keepdim=True).float()
    side = image.shape[-1] // cells
    return F.avg_pool2d(lum, side)[0, 0], F.avg_pool2d(clipped, side)[0, 0]


def solve_lighting(graph, photo: torch.Tensor, seed: int = 0, camera: FlashCamera = FlashCamera(),
                   theta: torch.Tensor | None = None) -> FlashCamera:
    """``camera`` with the ``falloff`` under which the graph's framed flash render (of the
    parameters ``theta`` (P,) when given, else its own) has the photo's
    (1, 3, S, S) distribution of light over the frame: the log ratio of the two images' cell
    luminances (``cell_levels``), cells more than half clipped in either left out, fitted by least
    squares with the falloff's smooth terms (added to the camera's own, which the render already
    has). The constant of that fit is the level, which the gain takes. The camera is returned
    unchanged when too few cells are usable."""
    with torch.no_grad():
        render = framed_render(graph, photo, seed, camera, theta)
        (p_lum, p_clip), (r_lum, r_clip) = cell_levels(photo), cell_levels(render)
        usable = (p_clip <= 0.5) & (r_clip <= 0.5) & (p_lum > 1e-4) & (r_lum > 1e-4)
        if int(usable.sum()) < MIN_LIGHTING_CELLS:
            return camera
        cells = p_lum.shape[-1]
        centres = (torch.arange(cells, dtype=torch.float64) + 0.5) / cells * 2 - 1
        v, u = torch.meshgrid(-centres, centres, indexing="ij")
        design = torch.stack([torch.ones_like(u), u, v, u * u, v * v, u * v], dim=-1)[usable.cpu()]
        ratio = (p_lum.double() / r_lum.double()).log()[usable].cpu()
        coefficients = torch.linalg.lstsq(design, ratio[:, None]).solution[1:, 0]
    falloff = tuple(max(-FALLOFF_LIMIT, min(FALLOFF_LIMIT, old + float(new)))
                    for old, new in zip(camera.falloff, coefficients))
    return replace(camera, falloff=falloff)


def rgb_basecolor(maps: dict[str, torch.Tensor]) -> torch.Tensor | None:
    """The maps' ``basecolor`` when it has RGB channels (a gain can scale it), else None."""
    basecolor = maps.get("basecolor")
    return basecolor if basecolor is not None and basecolor.shape[1] >= 3 else None


def with_gain(maps: dict[str, torch.Tensor], gain: torch.Tensor) -> dict[str, torch.Tensor]:
    """``maps`` with the RGB of their ``basecolor`` scaled by ``gain`` (N or 1, 3) in linear light
    (``scaled_basecolor``); unchanged without an RGB base colour."""
    basecolor = rgb_basecolor(maps)
    return maps if basecolor is None else {**maps, "basecolor": scaled_basecolor(basecolor, gain)}


def secant_gain(level, target: torch.Tensor, gain: torch.Tensor, steps: int = SOLVE_STEPS) -> torch.Tensor:
    """The gain (N, 3) at which ``level(gain)`` (N, 3), the render's level under that gain, meets
    ``target`` (N or 1, 3), from ``gain``: the first step applies the ratio, the next ones the
    secant through the last two renders (exact for a * gain + b); within ``GAIN_RANGE``. A
    channel whose render is black keeps its gain."""
    previous = None
    for _ in range(steps):
        rendered = level(gain)
        gain_next = torch.where(rendered > 1e-6, gain * target / rendered.clamp_min(1e-6), gain)
        if previous is not None:
            slope = (rendered - previous[1]) / (gain - previous[0])
            secant = gain + (target - rendered) / slope
            usable = (gain - previous[0]).abs() > 1e-4
            usable &= slope > 1e-6
            gain_next = torch.where(usable, secant, gain_next)
        previous = (gain, rendered)
        gain = gain_next.clamp(*GAIN_RANGE)
    return gain


def solve_gain(graph, photo: torch.Tensor, seed: int = 0, camera: FlashCamera = FlashCamera(),
               steps: int = SOLVE_STEPS, theta: torch.Tensor | None = None) -> torch.Tensor:
    """Set ``graph.calibration``'s gain so that the graph's flash render (of the parameters
    ``theta`` (P,) when given, else its own) has the photo's (1, 3, S, S) level per channel
    (``unclipped_level``, ``secant_gain``); returns the gain (3,). The render is made at the
    photo's size: a relief's shading darkens as its detail is resolved, so a render at another
    size has another level."""

    def level(gain: torch.Tensor) -> torch.Tensor:
        graph.calibration.set_values(**{GAIN: gain[0]})
        return unclipped_level(framed_render(graph, photo, seed, camera, theta))[None].to(gain)

    with torch.no_grad():
        start = graph.calibration.gain().detach().clone()[None]
        gain = secant_gain(level, unclipped_level(photo.float())[None].to(start), start, steps)[0]
        graph.calibration.set_values(**{GAIN: gain})
    return gain


def proposal_gains(maps: dict[str, torch.Tensor], photo: torch.Tensor,
                   camera: FlashCamera = FlashCamera(), steps: int = SOLVE_STEPS) -> torch.Tensor:
    """The gain (N, 3) that gives each of a batch of maps (N, C, S, S) the photo's (1, 3, S, S)
    level per channel, as ``solve_gain`` does for a graph, but on maps already evaluated (only the
    flash render is repeated, the graph is not); ones where the maps have no RGB base colour."""

    def level(gain: torch.Tensor) -> torch.Tensor:
        image = render_maps(with_gain(maps, gain), camera)
        return torch.stack([unclipped_level(image[i:i + 1]) for i in range(image.shape[0])])

    basecolor = rgb_basecolor(maps)
    if basecolor is None:
        count = next(iter(maps.values())).shape[0]
        return torch.ones(count, 3, device=photo.device)
    with torch.no_grad():
        start = torch.ones(basecolor.shape[0], 3, dtype=basecolor.dtype, device=basecolor.device)
        return secant_gain(level, unclipped_level(photo.float())[None].to(start), start, steps)
