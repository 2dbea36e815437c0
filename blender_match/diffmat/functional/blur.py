"""Blur family: the atomic quick Blur, Directional (motion) Blur and Sharpen.

All three are circular convolutions done in the frequency domain, so they wrap around the edges
(the output of a tiling input tiles) and cost the same whatever the radius. The kernels are built
in the spatial domain with fractional (linear) end weights, so they are non-negative, normalised
(the mean is preserved and values stay in [0, 1]) and piecewise-smooth in their parameters
(differentiable in ``intensity`` and the angle).

Sizes are in pixels of a 256-pixel image (``intensity`` 10 blurs by 20 pixels at 512); angles are
in turns, clockwise on screen from the +u (rightwards) direction, like Substance's.
"""
from __future__ import annotations

import math

import torch
import torch.nn.functional as F

from ..errors import DiffMatError
from .common import check_image, fft_filter, param2d

__all__ = ["blur", "directional_blur", "sharpen"]

REF = 256.0


def _wrapped_offsets(n: int, device, dtype) -> torch.Tensor:
    """Signed wrapped pixel offsets 0, 1, …, n/2, …, -1 of an n-periodic axis (FFT order)."""
    d = torch.arange(n, device=device, dtype=dtype)
    return torch.where(d > n / 2, d - n, d)


def _box_1d(radius_px: torch.Tensor, n: int) -> torch.Tensor:
    """Normalised periodic box kernels (B, n) of half-width ``radius_px`` (B, 1) pixels.

    A tap at distance d weighs clamp(r + 1/2 - |d|, 0, 1): whole pixels inside, a fraction at the
    ends, so the kernel grows continuously (and piecewise linearly) with r; r = 0 is the identity.
    """
    d = _wrapped_offsets(n, radius_px.device, radius_px.dtype).abs()
    w = torch.clamp(radius_px + 0.5 - d, 0.0, 1.0)
    return w / w.sum(dim=-1, keepdim=True)


def _conv_kernel(img: torch.Tensor, kernel: torch.Tensor) -> torch.Tensor:
    """Circular convolution of ``img`` (N, C, H, W) by ``kernel`` (B, H, W) with its origin at
    pixel (0, 0); the batch dimensions broadcast."""
    spec = torch.fft.rfft2(img)
    kspec = torch.fft.rfft2(kernel)[:, None]
    return torch.fft.irfft2(spec * kspec, s=img.shape[-2:])


def _intensity_px(intensity, img: torch.Tensor, name: str) -> torch.Tensor:
    r = param2d(intensity, img)
    if r.shape[1] != 1:
        raise DiffMatError(f"{name}.intensity: expected one value per batch item, got shape {tuple(r.shape)}")
    return r.abs() * (img.shape[-1] / REF)


def blur(input1: torch.Tensor, *, intensity=10.0) -> torch.Tensor:
    """Substance's atomic (quick) Blur: a square box blur of half-width ``intensity`` pixels (of a
    256-pixel image), wrapping around the edges. ``intensity`` 0 is the identity; at large values
    the image tends to its mean colour. Differentiable in ``intensity`` (fractional end taps)."""
    check_image(input1, "blur.input1")
    n, c, h, w = input1.shape
    r = _intensity_px(intensity, input1, "blur")
    kx = _box_1d(r, w)
    ky = _box_1d(r, h)
    # symmetric kernels have a real spectrum: the transfer is the product of the two 1-D spectra
    tx = torch.fft.rfft(kx, dim=-1).real
    ty = torch.fft.fft(ky, dim=-1).real
    transfer = ty[:, None, :, None] * tx[:, None, None, :]
    return fft_filter(input1, transfer).clamp(0.0, 1.0)


def directional_blur(input1: torch.Tensor, *, intensity=10.0, mblurangle=0.0) -> torch.Tensor:
    """Substance's Directional Blur (``dirmotionblur``): a box blur along one direction.

    The kernel is the segment [-r, r]·(cos a, sin a) with r = ``intensity`` pixels of a 256-pixel
    image and a = ``mblurangle`` turns (clockwise on screen from +u), sampled every half pixel or
    less and splatted bilinearly onto the periodic pixel grid, so it moves smoothly with both
    parameters. Wraps around the edges; ``intensity`` 0 is the identity.
    """
    check_image(input1, "dirmotionblur.input1")
    n, c, h, w = input1.shape
    r = _intensity_px(intensity, input1, "dirmotionblur")                   # (B, 1)
    a = param2d(mblurangle, input1)
    if a.shape[1] != 1:
        raise DiffMatError(f"dirmotionblur.mblurangle: expected one value per batch item, got shape {tuple(a.shape)}")
    a = a * (2 * math.pi)
    b = max(r.shape[0], a.shape[0])
    r, a = r.expand(b, 1), a.expand(b, 1)
    # per item: m = 4 ceil(r) + 1 samples (spacing <= 0.5 px), trapezoid weights; items of a batch
    # are padded with zero-weight samples to the longest, so each item's kernel is its own
    mb = 4 * torch.ceil(r.detach()) + 1                                        # (B, 1)
    m = int(mb.max())
    kk = torch.arange(m, device=input1.device, dtype=input1.dtype)[None]       # (1, M)
    frac = kk / torch.clamp(mb - 1, min=1.0)
    t = (2 * frac - 1) * r * (mb > 1)                                           # (B, M) pixels
    wt = ((kk < mb) * torch.where((kk == 0) | (kk == mb - 1), 0.5, 1.0)).to(input1.dtype)
    wt = wt / wt.sum(dim=-1, keepdim=True)
    xs = t * torch.cos(a)                                                       # (B, M) pixels
    ys = t * torch.sin(a)

    def hats(pos, size):
        grid = torch.arange(size, device=input1.device, dtype=input1.dtype)
        d = torch.remainder(grid[None, None, :] - pos[:, :, None] + size / 2, size) - size / 2
        return torch.clamp(1.0 - d.abs(), min=0.0)                              # (B, M, size)

    hx = hats(xs, w)
    hy = hats(ys, h) * wt[:, :, None]
    kernel = torch.einsum("bmy,bmx->byx", hy, hx)
    return _conv_kernel(input1, kernel).clamp(0.0, 1.0)


def sharpen(input1: torch.Tensor, *, intensity=1.0) -> torch.Tensor:
    """Substance's Sharpen: x + intensity · (x − mean of the four neighbours), clamped to [0, 1].

    The neighbours lie one pixel of a 256-pixel image away (two pixels at 512), so the effect
    looks the same at any resolution; the shift is done in the frequency domain (exact for
    integer shifts, band-limited for fractional ones). Wraps around; ``intensity`` 0 is the identity.
    """
    check_image(input1, "sharpen.input1")
    k = param2d(intensity, input1)
    if k.shape[1] != 1:
        raise DiffMatError(f"sharpen.intensity: expected one value per batch item, got shape {tuple(k.shape)}")
    h, w = input1.shape[-2:]
    step = w / REF
    if step == int(step) and step >= 1:
        # whole-pixel neighbours (sizes >= 256): four rolls are exact (the FFT's phase shift by an
        # integer is a roll) and much cheaper than a transform
        s = int(step)
        x = input1
        # one circular pad, then the four neighbours as strided views of it (no roll copies)
        p = F.pad(x, (s, s, s, s), mode="circular")
        if not torch.is_grad_enabled() or not (x.requires_grad or k.requires_grad):
            # no-grad twin: the same arithmetic on one in-place buffer (docs/engine.md, "No-grad twins")
            with torch.no_grad():
                neigh = torch.add(p[..., s:s + h, :w], p[..., s:s + h, 2 * s:])
                neigh.add_(torch.add(p[..., :h, s:s + w], p[..., 2 * s:, s:s + w]))
                del p
                torch.addcmul(x, neigh, x.new_full((), -0.25), out=neigh)
                if neigh.shape[0] >= k.shape[0]:
                    torch.addcmul(x, neigh, k[:, :, None, None], out=neigh)
                    return neigh.clamp_(0.0, 1.0)
                return torch.addcmul(x, neigh, k[:, :, None, None]).clamp_(0.0, 1.0)
        neigh = (p[..., s:s + h, :w] + p[..., s:s + h, 2 * s:]) + (p[..., :h, s:s + w] + p[..., 2 * s:, s:s + w])
        lap = torch.addcmul(x, neigh, x.new_full((), -0.25))      # x - mean of the four neighbours
        return torch.addcmul(x, lap, k[:, :, None, None]).clamp(0.0, 1.0)
    # phase of a shift by w/256 pixels, per frequency bin, on the rfft2 grid
    px = torch.fft.rfftfreq(w, device=input1.device, dtype=input1.dtype) * (2 * math.pi * w / REF)
    py = torch.fft.fftfreq(h, device=input1.device, dtype=input1.dtype) * (2 * math.pi * w / REF)
    lap = 1.0 - 0.5 * (torch.cos(px)[None, :] + torch.cos(py)[:, None])
    transfer = 1.0 + k[:, :, None, None] * lap
    return fft_filter(input1, transfer).clamp(0.0, 1.0)
