"""Cellular (Worley / Voronoi) generators: Cells 1-4 and Alveolus.

One feature point per lattice cell (``scale`` × ``scale`` cells per image, so the pattern tiles),
at a random offset within 0.45 cell of the centre; ``disorder`` turns every point around its cell
centre by a random amount (smoothly, so it is differentiable and animates like Substance's
disorder). Each pixel searches the 3 × 3 neighbouring cells for its nearest point p1 (distance F1); the
exact distance to the cell border, min over the other points pj of (dj² - F1²) / (2 |pj - p1|), gives
resolution-independent, anti-aliased borders.
"""
from __future__ import annotations

import torch

from .common import param4d
from .pattern_shapes import TAU, aa_coverage, check_int, lattice_random, ref_tensor, smoothstep01

__all__ = ["cells_soft", "cells_distance", "cells_cracks", "cells_flat", "alveolus_pattern"]


_CHUNK_ELEMS = 1 << 20  # candidate values evaluated together (bounds the temporaries, stays in cache)
_GRID_CACHE: dict = {}


def _cell_axis(size: int, n: int, device, dtype):
    """Per pixel of an axis: its cell (long, (size,)) and its offset from that cell's centre, in
    cells ((size,)); cached per (size, n, device, dtype)."""
    key = (size, n, str(device), dtype)
    hit = _GRID_CACHE.get(key)
    if hit is None:
        c = (torch.arange(size, dtype=torch.float64) + 0.5) / size * n
        ci = torch.floor(c)
        hit = (ci.long().to(device), (c - ci - 0.5).to(device=device, dtype=dtype))
        if len(_GRID_CACHE) > 64:
            _GRID_CACHE.clear()
        _GRID_CACHE[key] = hit
    return hit


def worley(size: int, scale: int, seed: int, disorder=0.0, device=None, dtype=torch.float32, values: bool = True,
           border: bool = True):
    """Worley features in cell units: (F1, distance to the cell border, random value of the
    nearest cell, random value of the cell across the nearest border), each (B, 1, H, W); the
    two values are None when ``values`` is false, the border and values too when ``border`` is.

    Candidates are the 3 x 3 cells around the pixel's cell, on a last, contiguous axis of 9. The
    squared distance splits into an x part that depends on (cell row, pixel column, candidate) and a
    y part on (cell column, pixel row, candidate): two small tables, so a block of pixel rows is two
    row-copy gathers and one add. Everything that depends on a pair of candidates only (their
    separation, their random values) is a per-cell table read once per pixel."""
    ref = ref_tensor(device, dtype)
    n = scale
    rnd = lattice_random(seed, 3, n * n, device, dtype)
    dis = param4d(disorder, ref)
    # point offsets from the cell centre, turned by disorder
    ang = TAU * (rnd[0] + dis.flatten()[:, None] * (0.5 + rnd[1]))  # (B, n*n)
    rad = 0.45 * torch.sqrt(rnd[1])
    ox, oy = rad * torch.cos(ang), rad * torch.sin(ang)  # (B, n*n)
    b = ox.shape[0]
    ci, f = _cell_axis(size, n, device, dtype)                                # (size,) each
    ar = torch.arange(n, device=device)
    # candidate k = 3 (dj + 1) + (di + 1): neighbour cell (cy + dj, cx + di)
    dj = torch.tensor([-1, -1, -1, 0, 0, 0, 1, 1, 1], device=device)
    di = torch.tensor([-1, 0, 1, -1, 0, 1, -1, 0, 1], device=device)
    ncell = (torch.remainder(ar[:, None, None] + dj, n) * n
             + torch.remainder(ar[None, :, None] + di, n))                    # (n cy, n cx, 9)
    px = ox[:, ncell] + di.to(dtype)                                          # (B, n, n, 9) from own centre
    py = oy[:, ncell] + dj.to(dtype)
    # x part: (B, cy, pixel column, 9); y part: (B, pixel row, cx, 9)
    ax = px[:, :, ci] - f[None, None, :, None]
    ax = ax * ax
    ay = py.index_select(1, ci) - f[None, :, None, None]
    ay = ay * ay
    if border:
        sx = px[..., :, None] - px[..., None, :]
        sy = py[..., :, None] - py[..., None, :]
        inv = 0.5 * torch.rsqrt(torch.addcmul(sx * sx, sy, sy) + 1e-12)      # (B, n, n, 9, 9)
        inv = inv.reshape(b, n * n * 9, 9)
    f1s, borders, k1s, k2s = [], [], [], []
    chunk = max(1, _CHUNK_ELEMS // (9 * size * b))
    for r0 in range(0, size, chunk):
        rows = ci[r0:r0 + chunk]
        m = rows.shape[0]
        d2 = ax.index_select(1, rows) + ay[:, r0:r0 + m].index_select(2, ci)  # (B, m, W, 9)
        if not border:
            f1s.append(d2.amin(dim=-1))
            continue
        f1sq, i1 = d2.min(dim=-1, keepdim=True)
        cell = (rows[:, None] * n + ci[None, :]).view(1, m, size, 1)
        k1 = cell * 9 + i1                                                    # (B, m, W, 1)
        # exact distance to the cell's border: the nearest bisector between p1 and any other point
        w = inv.gather(1, k1.reshape(b, -1, 1).expand(-1, -1, 9)).view(b, m, size, 9)
        bis = (d2 - f1sq) * w
        bis = bis.scatter(-1, i1, 1e3)
        bd, i2 = bis.min(dim=-1, keepdim=True)
        f1s.append(f1sq[..., 0])
        borders.append(bd[..., 0])
        k1s.append(k1[..., 0])
        k2s.append((cell * 9 + i2)[..., 0])
    f1 = torch.sqrt(torch.cat(f1s, dim=1) + 1e-12)[:, None]
    if not border:
        return f1, None, None, None
    bd = torch.cat(borders, dim=1)[:, None]
    if not values:
        return f1, bd, None, None
    vt = rnd[2][ncell].reshape(-1)                                            # (n * n * 9,)

    def lookup(ks):
        return vt[torch.cat(ks, dim=1)][:, None]

    return f1, bd, lookup(k1s), lookup(k2s)


def cells_soft(*, scale: int = 8, disorder=0.0, size: int = 512, seed: int = 0, device=None,
               dtype=torch.float32) -> torch.Tensor:
    """Cells 1: cushion-like cells, dark on their borders and rising to a rounded top inside
    (the distance to the border, normalised and eased)."""
    scale = check_int(scale, "cells_1.scale", 1, 256)
    _, border, _, _ = worley(size, scale, seed, disorder, device, dtype, values=False)
    t = (border / 0.45).clamp(0.0, 1.0)
    return 1.0 - (1.0 - t) ** 2


def cells_distance(*, scale: int = 8, disorder=0.0, size: int = 512, seed: int = 0, device=None,
                   dtype=torch.float32) -> torch.Tensor:
    """Cells 2: the distance to the nearest feature point (Worley F1): black at the points,
    brightening towards the cell borders."""
    scale = check_int(scale, "cells_2.scale", 1, 256)
    f1, _, _, _ = worley(size, scale, seed, disorder, device, dtype, border=False)
    return (f1 / 0.9).clamp(0.0, 1.0)


def cells_cracks(*, scale: int = 8, disorder=0.0, width=0.06, size: int = 512, seed: int = 0, device=None,
                 dtype=torch.float32) -> torch.Tensor:
    """Cells 3: flat white cells separated by thin dark crack lines ``width`` of a cell wide, with
    a slight rise towards the cell centres."""
    scale = check_int(scale, "cells_3.scale", 1, 256)
    _, border, _, _ = worley(size, scale, seed, disorder, device, dtype, values=False)
    ref = ref_tensor(device, dtype)
    half = 0.5 * param4d(width, ref)
    pix = scale / size
    line = aa_coverage(border - half, pix)
    return ((1.0 - line) * (0.85 + 0.15 * smoothstep01(border / 0.45))).clamp(0.0, 1.0)


def cells_flat(*, scale: int = 8, disorder=0.0, size: int = 512, seed: int = 0, device=None,
               dtype=torch.float32) -> torch.Tensor:
    """Cells 4: a Voronoi mosaic, each cell one random gray level; the border between two cells is
    anti-aliased over one pixel."""
    scale = check_int(scale, "cells_4.scale", 1, 256)
    _, border, v1, v2 = worley(size, scale, seed, disorder, device, dtype)
    pix = scale / size
    w2 = 0.5 * aa_coverage(border - 0.5 * pix, pix)  # 0.5 on the border, 0 a pixel inside
    return (v1 + (v2 - v1) * w2).clamp(0.0, 1.0)


def alveolus_pattern(*, scale: int = 8, disorder=0.0, wall=0.1, depth=0.8, size: int = 512, seed: int = 0,
                     device=None, dtype=torch.float32) -> torch.Tensor:
    """Alveolus: a honeycomb of rounded pits, bright walls ``wall`` of a cell thick between cells
    whose floors sink by ``depth`` in a bowl shape."""
    scale = check_int(scale, "alveolus.scale", 1, 256)
    _, border, _, _ = worley(size, scale, seed, disorder, device, dtype, values=False)
    ref = ref_tensor(device, dtype)
    wall = param4d(wall, ref) * 0.5
    depth = param4d(depth, ref)
    t = ((border - wall) / 0.35).clamp(0.0, 1.0)
    bowl = 1.0 - (1.0 - t) ** 2
    return (1.0 - depth * bowl).clamp(0.0, 1.0)
