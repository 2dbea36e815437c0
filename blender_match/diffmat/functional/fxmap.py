"""FX-Map, in the limited "tiling" form of the MATch paper (section 5.5).

One input pattern is placed once per cell of an ``x_amount`` × ``y_amount`` grid on the torus
(every other row shifted by ``offset`` cells, as a brick bond), each copy with its own seeded
jitter of position, rotation, scale and opacity, and composited over a background colour (or a
background image) with Substance's Quadrant blending modes: 0 add, 1 max, 2 alpha-blend.

How it is computed (vectorised, differentiable): a pixel can only be reached by the copies of a
few cells around its own; the window radius follows from the largest possible copy (scale,
scale jitter, rotation, position jitter), so every copy that touches a pixel is evaluated there.
For each candidate copy the pixel is mapped into the pattern's own frame and the pattern is
sampled bilinearly with zero padding (copies have soft, one-texel edges, so the output moves
continuously with every continuous parameter). Cells and jitter are indexed modulo the grid,
so the output tiles across its edges; alpha-blend draws copies in row-major order, evaluated
translation-invariantly so the draw order survives the wrap. The pattern is box-prefiltered
(a mip level) to about the size of a copy in pixels, so minified copies do not alias.

The counts are discrete; ``offset``, ``scale``, ``rotation``, the four jitter amounts,
``opacitymult`` and ``background`` are continuous and differentiable. Random numbers come from
``torch.Generator().manual_seed(seed)``, one set per cell, so the same seed gives the same map.
"""
from __future__ import annotations

import math

import torch
import torch.nn.functional as F

from ..errors import DiffMatError
from .common import check_image, check_size, match_channels, param2d, param4d, sample_wrap

__all__ = ["fx_map"]

BLENDING = {0: "add", 1: "max", 2: "alpha"}
MAX_RADIUS = 4          # at most (2·4 + 1)² candidate copies per pixel


def _scalar(value, like, where):
    t = param4d(value, like)
    if t.shape[1] != 1:
        raise DiffMatError(f"fxmaps.{where}: expected one value per batch item, got shape {tuple(t.shape)}")
    return t


def _grid(size, device, dtype):
    c = (torch.arange(size, device=device, dtype=dtype) + 0.5) / size
    v, u = torch.meshgrid(c, c, indexing="ij")
    return u, v


def _check_fx_map_args(inputpattern, size, x_amount, y_amount, blendingmode) -> str:
    """Check the discrete arguments of ``fx_map``; returns the blending mode's name."""
    check_image(inputpattern, "fxmaps.inputpattern")
    check_size(size, "fxmaps.size")
    for name, value in (("x_amount", x_amount), ("y_amount", y_amount)):
        if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= 256:
            raise DiffMatError(f"fxmaps.{name}: expected an integer in [1, 256], got {value!r}")
    if blendingmode not in BLENDING:
        raise DiffMatError(f"fxmaps.blendingmode: unknown value {blendingmode!r}; expected one of {list(BLENDING)}")
    return BLENDING[blendingmode]


def _background(image: torch.Tensor | None, color: torch.Tensor, channels: int, size: int, dev, dt) -> torch.Tensor:
    """The image the copies are composited on: ``image`` resampled to ``size``, or ``color``."""
    if image is not None:
        check_image(image, "fxmaps.background")
        bg = match_channels(image, channels)
        if bg.shape[-2:] != (size, size):
            u, v = _grid(size, dev, dt)
            bg = sample_wrap(bg, u[None].expand(bg.shape[0], -1, -1), v[None].expand(bg.shape[0], -1, -1))
        return bg
    col = color if channels == 4 else color[:, :1]
    return col[:, :, None, None].expand(-1, -1, size, size)


def fx_map(inputpattern: torch.Tensor, background_image: torch.Tensor | None = None, *,
           x_amount: int = 4, y_amount: int = 4, offset=0.0, scale=1.0, rotation=0.0,
           position_random=0.0, rotation_random=0.0, scale_random=0.0, opacity_random=0.0,
           opacitymult=1.0, blendingmode: int = 0, background=(0.0, 0.0, 0.0, 1.0),
           colorswitch: bool = False, size: int = 512, seed: int = 0, device=None,
           dtype=None) -> torch.Tensor:
    """Tile ``inputpattern`` over a (``size``, ``size``) image (see the module docstring).

    Per copy (cell indices taken modulo the grid; r… are the cell's seeded uniform numbers):
    centre = cell centre + ``position_random`` · (r₁, r₂) cells, r in [-1, 1];
    rotation = ``rotation`` + ``rotation_random`` · r₃ turns (clockwise on screen), r₃ in [-1, 1];
    size = ``scale`` · (1 + ``scale_random`` · r₄) cells, r₄ in [-1, 1];
    opacity = ``opacitymult`` · (1 − ``opacity_random`` · r₅), r₅ in [0, 1].
    Output: grayscale, or RGBA when ``colorswitch`` is on (the pattern is converted to match);
    colour patterns are composited premultiplied by their alpha. Values are clamped to [0, 1].
    """
    mode = _check_fx_map_args(inputpattern, size, x_amount, y_amount, blendingmode)
    like = inputpattern
    dev, dt = like.device, like.dtype
    nx, ny = x_amount, y_amount
    oc = 4 if colorswitch else 1

    off = _scalar(offset, like, "offset")
    sc = _scalar(scale, like, "scale")
    rot = _scalar(rotation, like, "rotation")
    pr = _scalar(position_random, like, "position_random")
    rr = _scalar(rotation_random, like, "rotation_random")
    sr = _scalar(scale_random, like, "scale_random")
    orr = _scalar(opacity_random, like, "opacity_random")
    om = _scalar(opacitymult, like, "opacitymult")
    bgc = param2d(background, like)
    if bgc.shape[1] != 4:
        raise DiffMatError(f"fxmaps.background: expected 4 components, got {bgc.shape[1]}")

    bg = _background(background_image, bgc, oc, size, dev, dt)

    # the pattern, premultiplied, with an alpha (coverage) channel last
    pat = match_channels(inputpattern, oc)
    if oc == 4:
        ext = torch.cat([pat[:, :3] * pat[:, 3:], pat[:, 3:]], dim=1)
    else:
        ext = torch.cat([pat, torch.ones_like(pat)], dim=1)

    # extents (detached: they only choose how many candidate cells to look at)
    s_max = float(sc.detach().abs().max()) * (1.0 + float(sr.detach().abs().max()))
    s_max = max(s_max, 1e-4)
    target = max(1.0, size * s_max / max(nx, ny))
    while ext.shape[-1] >= 2 * target and ext.shape[-2] >= 2 * target and min(ext.shape[-2:]) >= 2:
        ext = F.avg_pool2d(ext, 2)
    p_texels = min(ext.shape[-2:])
    hx, hy = s_max / (2 * nx), s_max / (2 * ny)                         # half sizes, texture units
    if float(rr.detach().abs().max()) > 0:
        eu = ev = math.hypot(hx, hy)
    else:
        th = (rot.detach().reshape(-1) * 2 * math.pi)
        cs, sn = th.cos().abs(), th.sin().abs()
        eu = float((hx * cs + hy * sn).max())
        ev = float((hx * sn + hy * cs).max())
    bleed = 0.5 * s_max / p_texels                                      # soft edge (half a texel), cells
    pmax = float(pr.detach().abs().max())
    # pixel centres keep at least `gap` cells from the cell borders (0 when rows are shifted)
    centres = (torch.arange(size, dtype=torch.float64) + 0.5) / size
    gap_u = float((centres * nx - torch.round(centres * nx)).abs().min())
    gap_v = float((centres * ny - torch.round(centres * ny)).abs().min())
    if float(off.detach().abs().max()) > 0:
        gap_u = 0.0
    # a copy of cell i0 + d reaches a pixel of cell i0 only if |d| < extent + 1/2 - gap
    ru = min(MAX_RADIUS, max(0, math.ceil(eu * nx + bleed + pmax + 0.5 - gap_u - 1e-6) - 1))
    rv = min(MAX_RADIUS, max(0, math.ceil(ev * ny + bleed + pmax + 0.5 - gap_v - 1e-6) - 1))

    # per-cell table of the copies' placement: (B, 6, ny * nx)
    g = torch.Generator().manual_seed(int(seed))
    rnd = torch.rand(5, ny * nx, generator=g, dtype=torch.float64).to(device=dev, dtype=dt)
    rpx, rpy, rrot, rsc = (rnd[:4] * 2 - 1).unbind(0)
    rop = rnd[4]

    def flat(t):
        return t.reshape(t.shape[0], 1)                                 # (B|1, 1)

    theta = (flat(rot) + flat(rr) * rrot) * (2 * math.pi)
    inv_s = 1.0 / torch.clamp(flat(sc) * (1.0 + flat(sr) * rsc), min=1e-4)
    bt = max(t.shape[0] for t in (off, sc, rot, pr, rr, sr, orr, om))
    table = torch.stack(torch.broadcast_tensors(
        flat(pr) * rpx, flat(pr) * rpy, torch.cos(theta) * inv_s, torch.sin(theta) * inv_s,
        flat(om) * (1.0 - flat(orr) * rop), torch.zeros(bt, ny * nx, device=dev, dtype=dt)), dim=1)

    # candidate cells, in draw order (row offset, then column offset)
    offs = [(dj, di) for dj in range(-rv, rv + 1) for di in range(-ru, ru + 1)]
    k = len(offs)
    dj = torch.tensor([o[0] for o in offs], device=dev).reshape(k, 1, 1)
    di = torch.tensor([o[1] for o in offs], device=dev).reshape(k, 1, 1)
    c = (torch.arange(size, device=dev, dtype=dt) + 0.5) / size
    cu = (c * nx).reshape(1, 1, size)                                    # cell units
    cv = (c * ny).reshape(1, size, 1)
    j = torch.floor(cv).long() + dj                                      # (K, S, 1)
    jw = torch.remainder(j, ny)
    parity = torch.remainder(jw, 2).to(dt)
    if float(off.detach().abs().max()) > 0 or off.requires_grad:
        shift = off.reshape(-1, 1, 1, 1) * parity                        # (B, K, S, 1)
        i = torch.floor(cu - shift.detach()).long() + di                 # (B, K, S, S)
    else:
        shift = torch.zeros((), device=dev, dtype=dt)
        i = (torch.floor(cu).long() + di).expand(k, size, size)[None]    # (1, K, S, S)
    iw = torch.remainder(i, nx)
    cell = jw * nx + iw                                                  # (Bi, K, S, S)
    bi = cell.shape[0]
    b = max(bt, bi, ext.shape[0])
    tab = table.expand(b, -1, -1)
    picked = torch.gather(tab, 2, cell.expand(b, -1, -1, -1).reshape(b, 1, -1).expand(b, 6, -1))
    picked = picked.reshape(b, 6, k, size, size)
    ju, jv, cs_, sn_, op = picked[:, 0], picked[:, 1], picked[:, 2], picked[:, 3], picked[:, 4]
    du = (cu - i.to(dt) - 0.5 - shift - ju) / nx                         # texture units, (B, K, S, S)
    dv = (cv - j.to(dt) - 0.5 - jv) / ny
    gx = 2 * nx * (cs_ * du + sn_ * dv)
    gy = 2 * ny * (cs_ * dv - sn_ * du)
    grid = torch.stack([gx, gy], dim=-1).transpose(0, 1).reshape(k * b, size, size, 2)
    src = ext.expand(b, -1, -1, -1)[None].expand(k, -1, -1, -1, -1).reshape(k * b, *ext.shape[1:])
    smp = F.grid_sample(src, grid, mode="bilinear", padding_mode="zeros", align_corners=False)
    smp = smp.reshape(k, b, ext.shape[1], size, size)
    op = op.transpose(0, 1)[:, :, None]                                  # (K, B, 1, S, S)
    kk = k

    if mode == "add":
        out = bg + (op * smp[:, :, :oc]).sum(dim=0)
    elif mode == "max":
        out = torch.maximum(bg, (op * smp[:, :, :oc]).amax(dim=0))
    else:
        out = bg
        for n in range(kk):
            a = op[n] * smp[n, :, -1:]
            out = out * (1.0 - a) + op[n] * smp[n, :, :oc]
    return out.clamp(0.0, 1.0)
