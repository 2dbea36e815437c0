"""Distance: a linear fade outwards from the white parts of a mask, or a Voronoi-like fill with
the colour a source image has at the nearest white pixel.

The nearest mask pixel (value > 0.5) of every pixel is found on the torus (distances wrap around
the edges, so the output tiles) by jump flooding: log2(reach) vectorised passes, each comparing
every pixel's current candidate with those of its 8 neighbours at a halving step, plus one final
1-pixel pass. Jump flooding is exact in all but rare configurations, where it returns a near-
nearest pixel. Only pixels within ``distance`` matter, so the passes start at the smallest power
of two reaching that far.

The fade 1 − d / ``distance`` (clamped to [0, 1]) is differentiable in ``distance``; ``d`` is in
pixels of a 256-pixel image. The mask itself is thresholded (no gradient flows to it).
"""
from __future__ import annotations

import math

import torch

from ..errors import DiffMatError
from .common import check_image, match_channels, param4d

__all__ = ["distance"]

REF = 256.0


def nearest_mask_pixel(mask: torch.Tensor, reach_px: float, want_index: bool = True):
    """For a boolean mask (B, 1, H, W): the flat index (y·W + x) of the nearest True pixel on the
    torus (-1 where there is none within ``reach_px``) and the Euclidean distance to it in pixels
    (exact up to ``reach_px``; inf, or some larger distance, beyond it). With ``want_index`` off
    only the distance is computed (the index is None).

    Separable and exact: first, per column, the wrap-around vertical distance to the nearest mask
    pixel (two running max/min scans over two stacked copies of the column); then, per row, the
    minimum of g(x + dx)² + dx² over the horizontal offsets |dx| <= reach.
    """
    b, _, h, w = mask.shape
    dev = mask.device
    inf = float("inf")
    ys = torch.arange(h, device=dev, dtype=torch.float32).reshape(1, 1, h, 1)
    up = torch.where(mask, ys, -inf)
    last = torch.cummax(torch.cat([up - h, up], dim=-2), dim=-2).values[..., h:, :]   # last mask row <= y
    down = torch.where(mask, ys, inf)
    nxt = torch.cat([down, down + h], dim=-2).flip(-2)
    nxt = torch.cummin(nxt, dim=-2).values.flip(-2)[..., :h, :]                       # next mask row >= y
    above, below = ys - last, nxt - ys
    g = torch.minimum(above, below)                                                   # inf: empty column
    half = w // 2
    reach = int(math.ceil(reach_px))
    lo, hi = (-half, w - half - 1) if reach >= half else (-reach, reach)
    # one key per candidate, d² · K + (dx − lo), with d² capped just beyond the reach: exact
    # integers, so a running minimum yields the nearest distance and its column offset together
    # (ties: smallest dx); float32 while the keys stay below 2^24, float64 beyond
    k = float(hi - lo + 1)
    cap = float((reach + 1) ** 2)
    dtype = torch.float32 if (2 * cap + 1) * k < 2 ** 24 else torch.float64
    g2 = torch.clamp((g * g).to(dtype), max=cap) * k
    # circular padding once, then every offset is a view: column x + dx is padded[x + dx - lo]
    padded = torch.cat([g2[..., w + lo:], g2, g2[..., :hi]], dim=-1) if lo < 0 else g2
    best = g2 + float(-lo)
    for dx in range(lo, hi + 1):
        if dx == 0:
            continue
        cand = padded[..., dx - lo:dx - lo + w] + float(dx * dx * k + dx - lo)
        torch.minimum(best, cand, out=best)
    best = best.to(torch.float64)
    d2 = torch.floor(best / k)
    found = d2 < cap
    dist = torch.where(found, d2.sqrt(), math.inf)
    if not want_index:
        return None, dist
    best_dx = best - d2 * k + lo
    row = torch.where(above <= below, last, nxt)
    row = torch.remainder(torch.nan_to_num(row, nan=0.0, posinf=0.0, neginf=0.0), h)
    xs = torch.arange(w, device=dev).reshape(1, 1, 1, w)
    col = torch.remainder(xs + torch.nan_to_num(best_dx, nan=0.0).long(), w)
    near_row = torch.gather(row, -1, col.expand(b, 1, h, w)).long()
    idx = torch.where(found, near_row * w + col, torch.full_like(col, -1))
    return idx, dist


def distance(mask: torch.Tensor, source: torch.Tensor | None = None, *, distance=10.0,
             colorswitch: bool = False, combinedistance: bool = True) -> torch.Tensor:
    """Substance's Distance node.

    Without ``source``: fade = clamp(1 − d / ``distance``, 0, 1), d being the wrap-around distance
    (pixels of a 256-pixel image) to the nearest mask pixel above 0.5: 1 on the mask, falling
    linearly to 0 at ``distance``. Grayscale, or that gray in RGB with alpha 1 when
    ``colorswitch`` is on.

    With ``source``: every pixel takes the source's value (colour when ``colorswitch`` is on, gray
    otherwise) at its nearest mask pixel. ``combinedistance`` on multiplies it (all channels) by
    the fade; off keeps it unfaded up to ``distance`` and 0 beyond.
    """
    check_image(mask, "distance.mask", channels=(1,))
    if source is not None:
        check_image(source, "distance.source")
        if source.shape[-2:] != mask.shape[-2:]:
            raise DiffMatError(f"distance.source: size {tuple(source.shape[-2:])} differs from the mask's "
                               f"{tuple(mask.shape[-2:])}")
    dmax = param4d(distance, mask)
    if dmax.shape[1] != 1:
        raise DiffMatError(f"distance.distance: expected one value per batch item, got shape {tuple(dmax.shape)}")
    h, w = mask.shape[-2:]
    scale = w / REF                                                     # pixels per reference pixel
    reach = float(dmax.detach().abs().max()) * scale + 1.0
    with torch.no_grad():
        idx, dpx = nearest_mask_pixel(mask > 0.5, reach, want_index=source is not None)
    d_ref = (dpx / scale).to(mask.dtype)
    limit = dmax.abs().clamp(min=1e-6)
    # pixels with no mask pixel in reach: any finite distance beyond the limit (fade 0, no NaN grads)
    d_ref = torch.where(torch.isfinite(d_ref), d_ref, limit.detach() * 2 + 1)
    fade = torch.clamp(1.0 - d_ref / limit, 0.0, 1.0)
    channels = 4 if colorswitch else 1
    if source is None:
        return match_channels(fade, channels)
    src = match_channels(source, channels)
    b = max(src.shape[0], idx.shape[0], fade.shape[0])
    flat_src = src.expand(b, -1, -1, -1).reshape(b, channels, h * w)
    safe = idx.clamp(min=0).expand(b, 1, h, w).reshape(b, 1, h * w).expand(b, channels, h * w)
    near = torch.gather(flat_src, 2, safe).reshape(b, channels, h, w)
    found = (idx >= 0).to(mask.dtype)
    if combinedistance:
        return near * fade * found
    inside = (d_ref <= limit).to(mask.dtype)
    return near * inside * found
