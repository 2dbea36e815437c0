"""Relief ops: Normal (height to tangent-space normal map) and Emboss (Substance's atomic ``normal``
and ``emboss`` filters).

Slopes are wrap-around central differences (``gradient_wrap``), measured as height change per
pixel of a 256-pixel image, so the look does not depend on the resolution:
slope = intensity x (dh/du) / 256, with dh/du in value per texture unit.
"""
from __future__ import annotations

import math

import torch

from ..errors import DiffMatError
from .common import GRAY, check_image, gradient_wrap, param2d, param4d

__all__ = ["height_to_normal", "emboss"]

REFERENCE_SIZE = 256.0


def _scalar(value, like, where):
    t = param4d(value, like)
    if t.shape[1] != 1:
        raise DiffMatError(f"{where}: expected 1 component, got {t.shape[1]}")
    return t


def height_to_normal(input1: torch.Tensor, *, intensity=1.0, inversedy: bool = False,
                     input2alpha: bool = True) -> torch.Tensor:
    """Tangent-space normal map of the height ``input1`` (grayscale), RGBA in [0, 1] encoding
    (rgb = n / 2 + 1/2).

    n = normalise(-s dh/dx, s dh/dy, 1) with s = ``intensity`` / 256 per texture unit, x to the
    right and y up the image (OpenGL: green = up-facing). ``inversedy`` selects the normal format
    as Substance stores it: False = DirectX (green flipped: n_y = -s dh/dy), True = OpenGL.
    ``input2alpha`` copies the height into alpha; otherwise alpha is 1.
    """
    h = check_image(input1, "normal.input1", (GRAY,))
    s = _scalar(intensity, h, "normal.intensity") / REFERENCE_SIZE
    dx, dv = gradient_wrap(h)
    if (not torch.is_grad_enabled() or not (h.requires_grad or s.requires_grad)) and s.shape[0] <= h.shape[0]:
        # no-grad twin: the same arithmetic, in place, into one RGBA buffer (docs/engine.md, "No-grad twins")
        with torch.no_grad():
            nx = dx.mul_(-s)
            ny = dv.mul_(s)
            if not inversedy:
                ny.neg_()
            half_inv = (nx * nx).add_(ny * ny).add_(1.0).rsqrt_().mul_(0.5)
            out = torch.empty((h.shape[0], 4) + tuple(h.shape[-2:]), dtype=h.dtype, device=h.device)
            torch.mul(nx, half_inv, out=out[:, 0:1])
            torch.mul(ny, half_inv, out=out[:, 1:2])
            out[:, 2:3] = half_inv
            out[:, :3].add_(0.5)
            if input2alpha:
                out[:, 3:] = h
            else:
                out[:, 3:] = 1.0
            return out.clamp_(0.0, 1.0)
    nx = -s * dx
    ny = s * dv           # v grows downwards: dh/d(up) = -dh/dv, and n_y = -dh/d(up)
    if not inversedy:
        ny = -ny
    half_inv = 0.5 * torch.rsqrt(nx * nx + ny * ny + 1.0)      # 1 / (2 |n|)
    rgb = torch.cat([nx * half_inv, ny * half_inv, half_inv], dim=1) + 0.5
    alpha = h.expand(rgb.shape[0], -1, -1, -1) if input2alpha else torch.ones_like(rgb[:, :1])
    return torch.cat([rgb, alpha], dim=1).clamp(0.0, 1.0)


def emboss(input1: torch.Tensor, inputgradient: torch.Tensor, *, intensity=5.0, lightangle=0.0,
           highlightcolor=(1.0, 1.0, 1.0, 1.0), shadowcolor=(0.0, 0.0, 0.0, 0.0)) -> torch.Tensor:
    """Emboss: light ``input1`` as if raised by the height ``inputgradient`` and lit from the
    direction ``lightangle`` (turns; 0 = from the right, 0.25 = from the top).

    The light term is k = intensity x (slope of the height towards the light) / 256, clamped to
    [-1, 1]: slopes facing the light (k > 0) move the colour towards ``highlightcolor`` by k, slopes
    facing away towards ``shadowcolor`` by -k. Colour images keep their alpha; a grayscale image
    uses the colours' first component.
    """
    x = check_image(input1, "emboss.input1")
    hgt = check_image(inputgradient, "emboss.inputgradient", (GRAY,))
    if hgt.shape[-2:] != x.shape[-2:]:
        raise DiffMatError(f"emboss.inputgradient: size {tuple(hgt.shape[-2:])} differs from input1's "
                           f"{tuple(x.shape[-2:])}")
    s = _scalar(intensity, x, "emboss.intensity") / REFERENCE_SIZE
    a = _scalar(lightangle, x, "emboss.lightangle") * (2 * math.pi)
    hi = param2d(highlightcolor, x)
    lo = param2d(shadowcolor, x)
    for name, t in (("highlightcolor", hi), ("shadowcolor", lo)):
        if t.shape[1] != 4:
            raise DiffMatError(f"emboss.{name}: expected 4 components (RGBA), got {t.shape[1]}")
    dx, dv = gradient_wrap(hgt)
    # light direction L = (cos a, sin a) with y up, i.e. (cos a, -sin a) in (u, v); a slope faces
    # the light where the surface normal (-grad h, 1) leans towards L: k = -s grad h . L
    k = (s * (dv * torch.sin(a) - dx * torch.cos(a))).clamp(-1.0, 1.0)
    lit, shade = k.clamp_min(0.0), (-k).clamp_min(0.0)
    if x.shape[1] == GRAY:
        hc, sc = hi[:, :1, None, None], lo[:, :1, None, None]
        return (x + lit * (hc - x) + shade * (sc - x)).clamp(0.0, 1.0)
    rgb = x[:, :3]
    hc, sc = hi[:, :3, None, None], lo[:, :3, None, None]
    rgb = (rgb + lit * (hc - rgb) + shade * (sc - rgb)).clamp(0.0, 1.0)
    return torch.cat([rgb, x[:, 3:].expand(rgb.shape[0], -1, -1, -1)], dim=1)
