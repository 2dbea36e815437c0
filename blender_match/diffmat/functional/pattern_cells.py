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

from .common import param4d, pixel_grid
from .pattern_shapes import TAU, aa_coverage, check_int, lattice_random, ref_tensor, safe_hypot, smoothstep01

__all__ = ["cells_soft", "cells_distance", "cells_cracks", "cells_flat", "alveolus_pattern"]


_CHUNK_ELEMS = 1 << 21  # candidate values evaluated together (bounds the temporaries; few large ops)


def worley(size: int, scale: int, seed: int, disorder=0.0, device=None, dtype=torch.float32, values: bool = True,
           border: bool = True):
    """Worley features in cell units: (F1, distance to the cell border, random value of the
    nearest cell, random value of the cell across the nearest border), each (B, 1, H, W); the
    two values are None when ``values`` is false, the border and values too when ``border`` is.

    Candidates are the 3 x 3 cells around the pixel's cell. A pixel's cell column depends on its
    column only and its cell row on its row only, so the candidates' points are two-level gathers
    from the (n, n) tables; the image is evaluated in blocks of rows with the nine candidates
    stacked on one axis."""
    ref = ref_tensor(device, dtype)
    n = scale
    rnd = lattice_random(seed, 3, n * n, device, dtype)
    dis = param4d(disorder, ref)
    # point offsets from the cell centre, turned by disorder
    ang = TAU * (rnd[0] + dis.flatten()[:, None] * (0.5 + rnd[1]))  # (B, n*n)
    rad = 0.45 * torch.sqrt(rnd[1])
    ox, oy = rad * torch.cos(ang), rad * torch.sin(ang)  # (B, n*n)
    b = ox.shape[0]
    c = (torch.arange(size, device=device, dtype=dtype) + 0.5) / size * n      # pixel centres, cells
    ci = torch.floor(c)
    f = c - ci - 0.5                                                          # (size,) from the centre
    ci = ci.long()
    near = torch.stack([torch.remainder(ci + d, n) for d in (-1, 0, 1)])     # (3, size)
    cols = near.reshape(-1)                                                   # (3 * size,)
    shift = torch.tensor([-1.0, 0.0, 1.0], device=device, dtype=dtype)
    # candidate k = 3 (dj + 1) + (di + 1); x offsets relative to the pixel: table + di - fx
    fx = (shift[:, None] - f[None, :]).reshape(1, 1, 3, size)                # (1, 1, 3(di), W)
    tx = ox.view(b, n, n)
    ty = oy.view(b, n, n)
    f1s, borders, i1s, i2s = [], [], [], []
    rows_all = torch.arange(size, device=device)
    chunk = max(16, _CHUNK_ELEMS // (9 * size * b))
    chunk = 1 << (chunk.bit_length() - 1)
    for r0 in range(0, size, chunk):
        r = rows_all[r0:r0 + chunk]
        m = r.shape[0]
        gxs, gys = [], []
        for j in range(3):
            rowi = near[j, r]
            gx = tx.index_select(1, rowi).index_select(2, cols).view(b, m, 3, size)
            gy = ty.index_select(1, rowi).index_select(2, cols).view(b, m, 3, size)
            gxs.append((gx + fx).transpose(1, 2))                            # (B, 3, m, W)
            gys.append((gy + (shift[j] - f[r]).view(1, m, 1, 1)).transpose(1, 2))
        GX = torch.stack(gxs, dim=1).reshape(b, 9, m, size)  # p - x per candidate
        GY = torch.stack(gys, dim=1).reshape(b, 9, m, size)
        D2 = torch.addcmul(GX * GX, GY, GY)
        if not border:
            f1s.append(D2.amin(dim=1, keepdim=True))
            continue
        f1sq, i1 = D2.min(dim=1, keepdim=True)
        # exact distance to the cell's border: the nearest bisector between p1 and any other point
        dpx = GX - GX.gather(1, i1)
        dpy = GY - GY.gather(1, i1)
        sep2 = torch.addcmul(dpx * dpx, dpy, dpy)
        bis = (D2 - f1sq) * torch.rsqrt(sep2 + 1e-12) * 0.5
        bis = bis.scatter(1, i1, torch.full_like(f1sq, 1e3))
        bd, i2 = bis.min(dim=1, keepdim=True)
        f1s.append(f1sq)
        borders.append(bd)
        i1s.append(i1)
        i2s.append(i2)
    f1 = torch.sqrt(torch.cat(f1s, dim=2) + 1e-12)
    if not border:
        return f1, None, None, None
    bd = torch.cat(borders, dim=2)
    if not values:
        return f1, bd, None, None

    def lookup(idx):
        k = torch.cat(idx, dim=2)                                   # (B, 1, H, W)
        dj = k // 3
        di = k - 3 * dj
        cy = torch.remainder(ci.view(1, 1, size, 1) + dj - 1, n)
        cx = torch.remainder(ci.view(1, 1, 1, size) + di - 1, n)
        return rnd[2][(cy * n + cx)]

    return f1, bd, lookup(i1s), lookup(i2s)


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
