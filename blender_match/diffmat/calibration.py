"""Photometric calibration: a real photo's exposure and white balance as a per-channel gain on
the base colour, solved in closed form.

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

The gain lives in the graph as the graph-level parameter set ``calibration`` (``BaseColourGain``,
applied to the ``basecolor`` output by ``MaterialGraph.forward``): the written maps, params.json,
a re-render and the Blender material all carry it. It is never part of the optimised vector.
"""
from __future__ import annotations

import torch

from .nodes.module import ParameterSet
from .render import FlashCamera, linear_to_srgb, render_maps, srgb_to_linear

CALIBRATION = "calibration"  # the graph-level parameter set's name in params.json ("calibration.basecolor_gain")
GAIN = "basecolor_gain"
# Three stops either way: beyond that the gain no longer stands for an exposure but rewrites a colour
# the graph cannot make, and magnifies the noise and tint of a near-black map (a black leather went green).
GAIN_RANGE = (1 / 8, 8.0)
CLIP_LEVEL = 0.98  # an sRGB value at or above this, in any channel, counts as clipped
MIN_UNCLIPPED = 0.05  # below this share of unclipped pixels, every pixel counts
KEEP_DARKEST = 0.8  # the level is the mean of this darker share of the unclipped pixels
SOLVE_STEPS = 4


class BaseColourGain(ParameterSet):
    """The gain on the linear base colour (3 components, 1 = none); fixed, set by ``solve_gain``."""

    def __init__(self):
        super().__init__(CALIBRATION)
        self._store(GAIN, [1.0, 1.0, 1.0], *GAIN_RANGE, size=3, widen=False, trainable=False)

    def optimizable(self, name: str) -> bool:
        return False

    def gain(self) -> torch.Tensor:
        return self.values()[GAIN]

    def scale(self, basecolor: torch.Tensor) -> torch.Tensor:
        """``basecolor`` (N, C, H, W) sRGB with its RGB scaled by the gain in linear light (alpha
        kept); unchanged when the gain is one."""
        gain = self.gain().to(basecolor)
        if bool((gain == 1).all()) or basecolor.shape[1] < 3:
            return basecolor
        rgb = linear_to_srgb(srgb_to_linear(basecolor[:, :3]) * gain.view(1, 3, 1, 1))
        return torch.cat([rgb, basecolor[:, 3:]], dim=1)


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


def solve_gain(graph, photo: torch.Tensor, seed: int = 0, camera: FlashCamera = FlashCamera(),
               steps: int = SOLVE_STEPS) -> torch.Tensor:
    """Set ``graph.calibration``'s gain so that the graph's flash render has the photo's
    (1, 3, S, S) level per channel (``unclipped_level``); returns the gain (3,). The render is
    made at the photo's size: a relief's shading darkens as its detail is resolved, so a render at
    another size has another level. A channel whose render is black keeps its gain."""
    size = photo.shape[-1]
    with torch.no_grad():
        target = unclipped_level(photo.float())
        gain = graph.calibration.gain().detach().clone()
        target = target.to(gain)
        previous = None
        for _ in range(steps):
            rendered = unclipped_level(render_maps(graph(size=size, seed=seed), camera)[:1]).to(gain)
            gain_next = torch.where(rendered > 1e-6, gain * target / rendered.clamp_min(1e-6), gain)
            if previous is not None:  # the secant through the last two renders: exact for a*gain + b
                slope = (rendered - previous[1]) / (gain - previous[0])
                secant = gain + (target - rendered) / slope
                usable = (gain - previous[0]).abs() > 1e-4
                usable &= slope > 1e-6
                gain_next = torch.where(usable, secant, gain_next)
            previous = (gain, rendered)
            gain = gain_next.clamp(*GAIN_RANGE)
            graph.calibration.set_values(**{GAIN: gain})
    return gain
