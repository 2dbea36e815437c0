"""Blend (Substance's atomic ``blend`` filter): composite a foreground over a background with one of
twelve blending modes, an opacity (slider x optional mask x cropping rectangle) and, for colour
images, an alpha-blending rule.

Formulas (Substance's "Blending modes" page; F = foreground, B = background, w = opacity weight):
the mode gives a target T(F, B), and the result is B + w (T - B), clamped to [0, 1] at the end.

==  ===========  ==========================================================================
 0  copy         T = F
 1  add          T = B + F                      (so the result is B + w F)
 2  subtract     T = B - F
 3  multiply     T = F B
 4  add-sub      T = B + 2F - 1                 (F above 0.5 adds, below 0.5 subtracts)
 5  max          T = max(F, B)                  (lighten)
 6  min          T = min(F, B)                  (darken)
 7  switch       T = F, and w is the opacity alone: colour alpha never enters it
 8  divide       T = B / F                      (F clamped away from 0)
 9  overlay      T = 2 F B where B < 0.5, else 1 - 2 (1 - F)(1 - B)
10  screen       T = 1 - (1 - F)(1 - B)
11  soft light   the W3C / PDF soft light: B - (1 - 2F) B (1 - B) where F <= 0.5, else
                 B + (2F - 1)(D(B) - B) with D(B) = ((16B - 12)B + 4)B for B <= 0.25, sqrt(B) above
==  ===========  ==========================================================================

w = ``opacitymult`` (clamped to [0, 1]) x ``opacity`` mask (when connected) x the coverage of ``maskrectangle``
(left, right, top, bottom in texture units; a pixel straddling an edge is covered by its area
fraction, so the rectangle's edges are differentiable).

Colour images and ``alphablending`` (the docs name the four choices; what they do to the output
alpha is not documented, these are the conventional compositing rules):

0. use source alpha (default): RGB = B + w F.a (T - B); alpha = B.a + w F.a (1 - B.a) (source-over);
1. ignore alpha: all four channels follow the mode with weight w;
2. straight alpha blending: a = w F.a; alpha = a + B.a (1 - a); RGB = (a T + (1 - a) B.a B) / alpha;
3. premultiplied alpha blending: a = w F.a; RGB = w T + (1 - a) B; alpha = a + B.a (1 - a).

Switch (mode 7) ignores ``alphablending`` and lerps all four channels by w.
"""
from __future__ import annotations

import torch

from ..errors import DiffMatError
from .common import COLOR, GRAY, broadcast_shape, check_choice, check_image, param2d, param4d, step

__all__ = ["blend"]

BLEND_MODES = {0: "copy", 1: "add", 2: "subtract", 3: "multiply", 4: "add_sub", 5: "max", 6: "min",
               7: "switch", 8: "divide", 9: "overlay", 10: "screen", 11: "soft_light"}
ALPHA_BLENDING = (0, 1, 2, 3)
_DIVIDE_EPS = 1e-4


def _target(mode: int, fg: torch.Tensor, bg: torch.Tensor) -> torch.Tensor:
    """The mode's full-opacity result T(F, B), before opacity and clamping."""
    if mode in (0, 7):
        return fg
    if mode == 1:
        return bg + fg
    if mode == 2:
        return bg - fg
    if mode == 3:
        return fg * bg
    if mode == 4:
        return bg + 2 * fg - 1
    if mode == 5:
        return torch.maximum(fg, bg)
    if mode == 6:
        return torch.minimum(fg, bg)
    if mode == 8:
        return bg / fg.clamp_min(_DIVIDE_EPS)
    if mode == 9:
        # where(bg < 0.5, lo, hi) as lo + [bg >= 0.5] (hi - lo): an arithmetic mask is much cheaper
        # than ``where`` on CPU, forward and backward
        # hi - lo = 1 - 2 (1 - F)(1 - B) - 2 F B = 2 (F + B) - 4 F B - 1, sharing F B
        fb = fg * bg
        diff = torch.addcmul((fg + bg) * 2.0 - 1.0, fb, fb.new_full((), -4.0))
        return torch.addcmul(fb * 2.0, step(bg - 0.5), diff)
    if mode == 10:
        return 1 - (1 - fg) * (1 - bg)
    if mode == 11:
        d = torch.where(bg <= 0.25, ((16 * bg - 12) * bg + 4) * bg, torch.sqrt(bg.clamp_min(0.25)))
        return torch.where(fg <= 0.5, bg - (1 - 2 * fg) * bg * (1 - bg), bg + (2 * fg - 1) * (d - bg))
    raise DiffMatError(f"blend.blendingmode: unknown value {mode!r}; expected one of {list(BLEND_MODES)}")


def mask_rectangle_coverage(rect, height: int, width: int, like: torch.Tensor) -> torch.Tensor:
    """Per-pixel area coverage (B|1, 1, H, W) of the rectangle ``rect`` = (left, right, top, bottom)
    in texture units (v grows downwards). Piecewise linear, so differentiable in the edges."""
    r = param2d(rect, like)
    if r.shape[1] != 4:
        raise DiffMatError(f"blend.maskrectangle: expected 4 components (left right top bottom), got {r.shape[1]}")
    cx, cy = _coverage_xy(r, height, width, like)
    return cy * cx


def _coverage_xy(r: torch.Tensor, height: int, width: int, like: torch.Tensor):
    """Column and row coverage of the rectangle rows ``r`` (B, 4): (B, 1, 1, W) and (B, 1, H, 1)."""
    xs = torch.arange(width, device=like.device, dtype=like.dtype) / width
    ys = torch.arange(height, device=like.device, dtype=like.dtype) / height
    left, right, top, bottom = (r[:, i:i + 1] for i in range(4))
    cx = (torch.minimum(right, xs + 1.0 / width) - torch.maximum(left, xs)).clamp(0.0, 1.0 / width) * width
    cy = (torch.minimum(bottom, ys + 1.0 / height) - torch.maximum(top, ys)).clamp(0.0, 1.0 / height) * height
    return cx[:, None, None, :], cy[:, None, :, None]


def blend(source: torch.Tensor, destination: torch.Tensor, opacity: torch.Tensor | None = None, *,
          blendingmode: int = 0, opacitymult=1.0, alphablending: int = 0,
          maskrectangle=(0.0, 1.0, 0.0, 1.0)) -> torch.Tensor:
    """Blend ``source`` (foreground) onto ``destination`` (background, the primary input).

    ``source`` and ``destination`` must have the same channel count (1 or 4) and size; ``opacity``
    is an optional grayscale mask. Continuous parameters may be batched (B, k). Returns an image of
    the background's channel count, clamped to [0, 1]. See the module docstring for the formulas.
    """
    fg = check_image(source, "blend.source")
    bg = check_image(destination, "blend.destination")
    check_choice(blendingmode, BLEND_MODES, "blend.blendingmode")
    check_choice(alphablending, ALPHA_BLENDING, "blend.alphablending")
    if fg.shape[1] != bg.shape[1]:
        raise DiffMatError(f"blend: source has {fg.shape[1]} channel(s) but destination has {bg.shape[1]}; "
                           "foreground and background must both be colour or both grayscale")
    if fg.shape[-2:] != bg.shape[-2:]:
        raise DiffMatError(f"blend: source is {tuple(fg.shape[-2:])} but destination is {tuple(bg.shape[-2:])}")
    h, w_ = bg.shape[-2:]
    weight = param4d(opacitymult, bg)
    if weight.shape[1] != 1:
        raise DiffMatError(f"blend.opacitymult: expected 1 component, got {weight.shape[1]}")
    weight = weight.clamp(0.0, 1.0)   # an opacity above 1 does not extrapolate (docs/nodes.md)
    rect = param2d(maskrectangle, bg)
    if rect.shape[1] != 4:
        raise DiffMatError(f"blend.maskrectangle: expected 4 components (left right top bottom), got {rect.shape[1]}")
    cx, cy = _coverage_xy(rect, h, w_, bg)
    weight = (weight * cy) * cx                        # (B, 1, H, W): one full-size product
    if opacity is not None:
        mask = check_image(opacity, "blend.opacity", (GRAY,))
        if mask.shape[-2:] != bg.shape[-2:]:
            raise DiffMatError(f"blend.opacity: mask is {tuple(mask.shape[-2:])} "
                               f"but destination is {tuple(bg.shape[-2:])}")
        weight = weight * mask

    mode = blendingmode
    if bg.shape[1] == GRAY or mode == 7 or alphablending == 1:
        return torch.lerp(bg, _target(mode, fg, bg), weight).clamp(0.0, 1.0)

    assert bg.shape[1] == COLOR
    if alphablending == 0 and (not torch.is_grad_enabled() or not (
            fg.requires_grad or bg.requires_grad or weight.requires_grad)):
        return _blend_color_nograd(mode, fg, bg, weight)
    f_rgb, f_a = fg[:, :3], fg[:, 3:]
    b_rgb, b_a = bg[:, :3], bg[:, 3:]
    t = _target(mode, f_rgb, b_rgb)
    a = weight * f_a
    out_a = a + b_a * (1 - a)
    if alphablending == 0:
        rgb = torch.lerp(b_rgb, t, a)
    elif alphablending == 2:
        rgb = (a * t + (1 - a) * b_a * b_rgb) / out_a.clamp_min(1e-6)
    else:  # 3: premultiplied
        rgb = weight * t + (1 - a) * b_rgb
    return torch.cat([rgb, out_a], dim=1).clamp(0.0, 1.0)


def _blend_color_nograd(mode: int, fg: torch.Tensor, bg: torch.Tensor, weight: torch.Tensor) -> torch.Tensor:
    """Colour blend with alpha blending 0 (source alpha) without autograd: the same arithmetic as
    ``blend``, written into one preallocated RGBA output and clamped in place. What it saves:
    docs/engine.md, "No-grad twins"."""
    with torch.no_grad():
        f_rgb, f_a = fg[:, :3], fg[:, 3:]
        b_rgb, b_a = bg[:, :3], bg[:, 3:]
        if mode == 9:
            fb = f_rgb * b_rgb
            diff = (f_rgb + b_rgb).mul_(2.0).sub_(1.0).addcmul_(fb, fb.new_full((), -4.0))
            t = fb.mul_(2.0).addcmul_(step(b_rgb - 0.5), diff)
            del diff
        elif mode == 10:
            t = (1 - f_rgb).mul_(1 - b_rgb).neg_().add_(1.0)
        else:
            t = _target(mode, f_rgb, b_rgb)
        a = weight * f_a
        shape = broadcast_shape(t.shape, a.shape, b_rgb.shape)
        out = torch.empty((shape[0], 4) + tuple(shape[2:]), dtype=bg.dtype, device=bg.device)
        torch.lerp(b_rgb, t, a, out=out[:, :3])
        torch.addcmul(a, b_a, (1 - a), out=out[:, 3:])
        return out.clamp_(0.0, 1.0)
