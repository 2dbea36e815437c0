"""Library (non-atomic) adjustment nodes of Substance's standard library, written natively:
histogram scan/range/select, invert, auto levels, contrast/luminosity, replace colour, switches,
channel merges and splits, linear to sRGB.

All ops are per-pixel (no spatial work), so they tile whenever their inputs tile. Grayscale-only
library graphs take any image and reduce colour to gray first (Substance converts on connection).
"""
from __future__ import annotations

import torch

from ...colour import LINEAR_KNEE, SRGB_GAMMA, SRGB_KNEE, SRGB_OFFSET, SRGB_SCALE, SRGB_SLOPE
from ..errors import DiffMatError
from .common import COLOR, check_bool, expand_batch, lerp, param2d, param4d, to_gray

__all__ = ["histogram_scan", "histogram_range", "histogram_select", "invert", "auto_levels",
           "contrast_luminosity", "replace_color", "switch", "multi_switch", "rgba_merge",
           "rgba_split", "rgb_a_merge", "rgb_a_split", "linear_to_srgb", "srgb_to_linear"]

_EPS = 1e-4


# ---------------------------------------------------------------- helpers shared by library_*.py
def _gray(x: torch.Tensor) -> torch.Tensor:
    return to_gray(x)


def _map_rgb(x: torch.Tensor, fn) -> torch.Tensor:
    """Apply ``fn`` to the colour channels of ``x`` (RGB of RGBA, or the gray channel); alpha is kept."""
    if x.shape[1] == COLOR:
        rgb = fn(x[:, :3])
        alpha = x[:, 3:].expand(rgb.shape[0], -1, -1, -1)
        return torch.cat([rgb, alpha], dim=1)
    return fn(x)


def _remap(x: torch.Tensor, lo: torch.Tensor, hi: torch.Tensor) -> torch.Tensor:
    """Linear map of [lo, hi] onto [0, 1], clamped; a zero-width window is a (steep) threshold."""
    return ((x - lo) / (hi - lo).clamp_min(_EPS)).clamp(0.0, 1.0)


# ---------------------------------------------------------------- histogram family
def histogram_scan(input_1: torch.Tensor, *, position=0.0, contrast=0.0, invert_position: bool = False):
    """Histogram Scan: a levels window that scans the histogram.

    ``position`` moves the window: 0 gives black, 1 white, 0.5 centres it on mid-gray (inverted by
    ``invert_position``). At ``contrast`` 0 the window is one unit wide ([2t-1, 2t] clipped, t the
    threshold); ``contrast`` 1 shrinks it to the threshold t (a hard step at t).
    """
    x = _gray(input_1)
    p = param4d(position, x)
    t = p if check_bool(invert_position, "histogram_scan.invert_position") else 1.0 - p
    c = param4d(contrast, x)
    lo0 = (2 * t - 1).clamp_min(0.0)
    hi0 = (2 * t).clamp_max(1.0)
    lo = lerp(lo0, t, c)
    hi = lerp(hi0, t, c)
    return _remap(x, lo, hi)


def histogram_range(input: torch.Tensor, *, range=0.5, position=0.5):
    """Histogram Range: squeezes the value range to ``range`` wide around ``position``
    (range 1, position 0.5 is the identity; range 0 is a flat ``position``).

    The output range stays centred on ``position``: it is [max(p - r/2, 2p - 1), min(p + r/2, 2p)],
    so near 0 or 1 it narrows symmetrically instead of being clipped on one side (the MATch
    reference implementation's formula; docs/nodes.md).
    """
    x = _gray(input)
    r = param4d(range, x)
    p = param4d(position, x)
    lo = torch.maximum(p - r / 2, 2 * p - 1).clamp(0.0, 1.0)
    hi = torch.minimum(p + r / 2, 2 * p).clamp(0.0, 1.0)
    return lerp(lo, hi, x)


def histogram_select(input: torch.Tensor, *, position=0.5, range=0.25, contrast=0.0):
    """Histogram Select: white where the value lies within ``range`` of ``position``; outside the
    band the output falls to black over (1 - ``contrast``) / 2 (contrast 1: a hard band)."""
    x = _gray(input)
    p = param4d(position, x)
    r = param4d(range, x)
    c = param4d(contrast, x)
    outside = ((x - p).abs() - r).clamp_min(0.0)
    soft = ((1 - c) * 0.5).clamp_min(_EPS)
    return (1.0 - outside / soft).clamp(0.0, 1.0)


# ---------------------------------------------------------------- simple adjustments
def invert(source: torch.Tensor, *, invert: bool = True):
    """Invert: 1 - x on gray, or on RGB keeping alpha; identity when ``invert`` is off."""
    if not check_bool(invert, "invert.invert"):
        return source
    return _map_rgb(source, lambda v: 1.0 - v)


def auto_levels(input: torch.Tensor, *, quality=0.0):
    """Auto Levels: stretches each image's value range to [0, 1] (min to 0, max to 1).
    ``quality`` (Substance's histogram precision) does not change this exact min/max version."""
    x = _gray(input)
    lo = x.amin(dim=(-2, -1), keepdim=True)
    hi = x.amax(dim=(-2, -1), keepdim=True)
    flat = (hi - lo) < _EPS
    out = (x - lo) / (hi - lo).clamp_min(_EPS)
    return expand_batch(torch.where(flat, torch.full_like(x, 0.5), out).clamp(0.0, 1.0), quality)


def contrast_luminosity(input: torch.Tensor, *, contrast=0.0, luminosity=0.0):
    """Contrast/Luminosity: ``contrast`` in [-1, 1] scales values about mid-gray by
    (1 + c) / (1 - c) (-1 flat gray, 1 a threshold); ``luminosity`` in [-1, 1] is added."""
    like = input
    c = param4d(contrast, like)
    lum = param4d(luminosity, like)
    gain = (1 + c) / (1 - c).clamp_min(1e-3)

    def fn(v):
        return ((v - 0.5) * gain + 0.5 + lum).clamp(0.0, 1.0)

    return _map_rgb(input, fn)


# ---------------------------------------------------------------- replace colour (HSL shift)
def _rgb_to_hsl(rgb: torch.Tensor):
    r, g, b = rgb.unbind(1)
    mx, _ = rgb.max(dim=1)
    mn, _ = rgb.min(dim=1)
    light = (mx + mn) / 2
    d = mx - mn
    ds = d.clamp_min(1e-6)
    sat = d / (1 - (2 * light - 1).abs()).clamp_min(1e-6)
    hr = torch.remainder((g - b) / ds, 6.0)
    hg = (b - r) / ds + 2
    hb = (r - g) / ds + 4
    hue = torch.where(mx == r, hr, torch.where(mx == g, hg, hb)) / 6
    hue = torch.where(d > 1e-6, hue, torch.zeros_like(hue))
    return hue, sat.clamp(0.0, 1.0), light


def _hsl_to_rgb(h, s, light):
    c = (1 - (2 * light - 1).abs()) * s
    k = torch.stack([torch.remainder(n + h * 12, 12.0) for n in (0.0, 8.0, 4.0)], dim=1)
    a = c[:, None] / 2
    f = light[:, None] - a * torch.clamp(torch.minimum(k - 3, 9 - k), -1.0, 1.0)
    return f


def replace_color(input: torch.Tensor, *, sourcecolor=(0.5, 0.5, 0.5, 1.0), targetcolor=(0.5, 0.5, 0.5, 1.0)):
    """Replace Color: shifts hue, saturation and lightness of the whole image by the difference
    between ``targetcolor`` and ``sourcecolor`` (HSL), so the source colour becomes the target."""
    x = input if input.shape[1] == COLOR else torch.cat([input] * 3 + [torch.ones_like(input)], 1)
    src = param2d(sourcecolor, x)[:, :3, None, None]
    dst = param2d(targetcolor, x)[:, :3, None, None]
    hs, ss, ls = _rgb_to_hsl(src)
    ht, st, lt = _rgb_to_hsl(dst)
    h, s, light = _rgb_to_hsl(x[:, :3])
    rgb = _hsl_to_rgb(torch.remainder(h + ht - hs, 1.0), (s + st - ss).clamp(0, 1), (light + lt - ls).clamp(0, 1))
    alpha = x[:, 3:].expand(rgb.shape[0], -1, -1, -1)
    return torch.cat([rgb.clamp(0.0, 1.0), alpha], dim=1)


# ---------------------------------------------------------------- switches
def switch(input_1: torch.Tensor, input_2: torch.Tensor, *, switch: bool = True):
    """Switch: ``input_1`` when ``switch`` is on, else ``input_2``."""
    return input_1 if check_bool(switch, "switch.switch") else input_2


def multi_switch(*inputs, input_number: int = 2, input_selection: int = 1):
    """Multi Switch: the ``input_selection``-th (1-based) of the first ``input_number`` inputs."""
    if not 1 <= input_selection <= input_number:
        raise DiffMatError(f"multi_switch.input_selection: {input_selection} is outside [1, {input_number}]")
    if input_selection > len(inputs) or inputs[input_selection - 1] is None:
        raise DiffMatError(f"multi_switch: input_{input_selection} is selected but not connected")
    return inputs[input_selection - 1]


# ---------------------------------------------------------------- channels
def rgba_merge(r: torch.Tensor, g: torch.Tensor, b: torch.Tensor, a: torch.Tensor | None = None,
               *, usealpha: bool = True):
    """RGBA Merge: four grayscale images to one RGBA image (alpha 1 when ``a`` is absent or unused)."""
    chans = [to_gray(r), to_gray(g), to_gray(b)]
    use_alpha = a is not None and check_bool(usealpha, "rgba_merge.usealpha")
    chans.append(to_gray(a) if a is not None and use_alpha else torch.ones_like(chans[0]))
    n = max(c.shape[0] for c in chans)
    return torch.cat([c.expand(n, -1, -1, -1) for c in chans], dim=1)


def rgba_split(rgba: torch.Tensor):
    """RGBA Split: an RGBA image to four grayscale images (r, g, b, a); gray input gives alpha 1."""
    x = rgba if rgba.shape[1] == COLOR else torch.cat([rgba] * 3 + [torch.ones_like(rgba)], 1)
    return tuple(x[:, i:i + 1] for i in range(4))


def rgb_a_merge(rgb: torch.Tensor, a: torch.Tensor):
    """RGB-A Merge: the RGB of a colour image with a grayscale alpha."""
    c = rgb if rgb.shape[1] == COLOR else torch.cat([rgb] * 3 + [torch.ones_like(rgb)], 1)
    alpha = to_gray(a)
    n = max(c.shape[0], alpha.shape[0])
    return torch.cat([c[:, :3].expand(n, -1, -1, -1), alpha.expand(n, -1, -1, -1)], dim=1)


def rgb_a_split(rgba: torch.Tensor):
    """RGB-A Split: (the RGB part with alpha 1, the alpha as grayscale)."""
    x = rgba if rgba.shape[1] == COLOR else torch.cat([rgba] * 3 + [torch.ones_like(rgba)], 1)
    return torch.cat([x[:, :3], torch.ones_like(x[:, 3:])], dim=1), x[:, 3:]


def linear_to_srgb(input: torch.Tensor):
    """Convert to sRGB: the sRGB transfer curve (``blender_match.colour``) on the colour channels
    (alpha kept)."""
    def fn(v):
        v = v.clamp(0.0, 1.0)
        lin = v * SRGB_SLOPE
        curve = SRGB_SCALE * v.clamp_min(LINEAR_KNEE) ** (1 / SRGB_GAMMA) - SRGB_OFFSET
        return torch.where(v <= LINEAR_KNEE, lin, curve)

    return _map_rgb(input, fn)


def srgb_to_linear(input: torch.Tensor):
    """The inverse sRGB curve on the colour channels (alpha kept)."""
    def fn(v):
        v = v.clamp(0.0, 1.0)
        curve = ((v.clamp_min(SRGB_KNEE) + SRGB_OFFSET) / SRGB_SCALE) ** SRGB_GAMMA
        return torch.where(v <= SRGB_KNEE, v / SRGB_SLOPE, curve)

    return _map_rgb(input, fn)
