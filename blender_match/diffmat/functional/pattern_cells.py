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


def worley(size: int, scale: int, seed: int, disorder=0.0, device=None, dtype=torch.float32):
    """Worley features in cell units: (F1, distance to the cell border, random value of the
    nearest cell, random value of the cell across the nearest border), each (B, 1, H, W)."""
    ref = ref_tensor(device, dtype)
    n = scale
    rnd = lattice_random(seed, 3, n * n, device, dtype)
    dis = param4d(disorder, ref)
    # point offsets from the cell centre, turned by disorder
    ang = TAU * (rnd[0] + dis.flatten()[:, None] * (0.5 + rnd[1]))  # (B, n*n)
    rad = 0.45 * torch.sqrt(rnd[1])
    ox, oy = rad * torch.cos(ang), rad * torch.sin(ang)  # (B, n*n)
    u, v = pixel_grid(size, device, dtype)
    X, Y = u * n, v * n
    cx0, cy0 = torch.floor(X), torch.floor(Y)
    fx, fy = X - cx0 - 0.5, Y - cy0 - 0.5
    dists, pxs, pys, vals = [], [], [], []
    b = ox.shape[0]
    for dj in (-1, 0, 1):
        for di in (-1, 0, 1):
            idx = (torch.remainder(cy0 + dj, n) * n + torch.remainder(cx0 + di, n)).long().view(1, -1)
            gx = torch.gather(ox, 1, idx.expand(b, -1)).view(b, 1, size, size) + di
            gy = torch.gather(oy, 1, idx.expand(b, -1)).view(b, 1, size, size) + dj
            dists.append(safe_hypot(gx - fx, gy - fy))
            pxs.append(gx)
            pys.append(gy)
            vals.append(rnd[2][idx].view(1, 1, size, size).expand(b, -1, -1, -1))
    D = torch.cat(dists, dim=1)  # (B, 9, H, W)
    P = torch.cat(pxs, dim=1)
    Q = torch.cat(pys, dim=1)
    V = torch.cat(vals, dim=1)
    f1, i1 = D.min(dim=1, keepdim=True)
    # exact distance to the cell's border: the nearest bisector between p1 and any other point
    dpx, dpy = P - P.gather(1, i1), Q - Q.gather(1, i1)
    sep = torch.sqrt(dpx * dpx + dpy * dpy + 1e-12)
    bis = (D * D - f1 * f1) / (2.0 * sep)
    bis = bis.scatter(1, i1, torch.full_like(f1, 1e3))
    border, i2 = bis.min(dim=1, keepdim=True)
    return f1, border, V.gather(1, i1), V.gather(1, i2)


def cells_soft(*, scale: int = 8, disorder=0.0, size: int = 512, seed: int = 0, device=None,
               dtype=torch.float32) -> torch.Tensor:
    """Cells 1: cushion-like cells, dark on their borders and rising to a rounded top inside
    (the distance to the border, normalised and eased)."""
    scale = check_int(scale, "cells_1.scale", 1, 256)
    _, border, _, _ = worley(size, scale, seed, disorder, device, dtype)
    t = (border / 0.45).clamp(0.0, 1.0)
    return 1.0 - (1.0 - t) ** 2


def cells_distance(*, scale: int = 8, disorder=0.0, size: int = 512, seed: int = 0, device=None,
                   dtype=torch.float32) -> torch.Tensor:
    """Cells 2: the distance to the nearest feature point (Worley F1): black at the points,
    brightening towards the cell borders."""
    scale = check_int(scale, "cells_2.scale", 1, 256)
    f1, _, _, _ = worley(size, scale, seed, disorder, device, dtype)
    return (f1 / 0.9).clamp(0.0, 1.0)


def cells_cracks(*, scale: int = 8, disorder=0.0, width=0.06, size: int = 512, seed: int = 0, device=None,
                 dtype=torch.float32) -> torch.Tensor:
    """Cells 3: flat white cells separated by thin dark crack lines ``width`` of a cell wide, with
    a slight rise towards the cell centres."""
    scale = check_int(scale, "cells_3.scale", 1, 256)
    _, border, _, _ = worley(size, scale, seed, disorder, device, dtype)
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
    _, border, _, _ = worley(size, scale, seed, disorder, device, dtype)
    ref = ref_tensor(device, dtype)
    wall = param4d(wall, ref) * 0.5
    depth = param4d(depth, ref)
    t = ((border - wall) / 0.35).clamp(0.0, 1.0)
    bowl = 1.0 - (1.0 - t) ** 2
    return (1.0 - depth * bowl).clamp(0.0, 1.0)
