"""Transformation 2D: an affine resampling of the input with wrap-around addressing.

Convention (the one DiffMat uses; Substance stores the sampling matrix): ``matrix22`` = (a, b, c, d)
is the output-to-input matrix, row-major, acting on coordinates centred on the image centre, and
``offset`` moves the content by that many image widths:

    src = M · (p − ½ − offset) + ½,      out(p) = input1(src mod 1)

so ``2 0 0 2`` shows the input twice in each direction, ``0 -1 1 0`` turns it a quarter turn, and
an offset of k/N (N pixels) is ``torch.roll`` by k pixels.

Tiling: the output tiles for every offset, but only for integer matrices (p ↦ M p mod 1 is
continuous on the torus only then). The node therefore declares ``matrix22`` non-optimisable and
keeps ``offset`` optimisable.

Minification is filtered as Substance does on the GPU (``mipmapmode`` 0 auto): a box-filtered mip
pyramid (tiling-preserving ``avg_pool2d``) sampled at the level log2(largest column norm of M),
blended linearly between the two nearest levels (trilinear); ``mipmapmode`` 1 uses
``manualmiplevel``. ``filtering`` 0 is bilinear, 1 nearest.
"""
from __future__ import annotations

import math

import torch
import torch.nn.functional as F

from ..errors import DiffMatError
from .common import check_image, image_grid, param2d, sample_wrap

__all__ = ["transformation_2d"]

FILTERING = {0: "bilinear", 1: "nearest"}
MIPMAPMODES = (0, 1)


def transformation_2d(input1: torch.Tensor, *, matrix22=(1.0, 0.0, 0.0, 1.0), offset=(0.0, 0.0),
                      filtering: int = 0, mipmapmode: int = 0, manualmiplevel: int = 0,
                      mattecolor=(0.0, 0.0, 0.0, 1.0)) -> torch.Tensor:
    """Substance's Transformation 2D with tiling on (see the module docstring for the convention).

    ``mattecolor`` is accepted for compatibility and unused: the output always tiles (Substance's
    tiling-off mode, which shows the matte outside the image, is not supported).
    """
    check_image(input1, "transformation.input1")
    if filtering not in FILTERING:
        raise DiffMatError(f"transformation.filtering: unknown value {filtering!r}; expected one of {list(FILTERING)}")
    if mipmapmode not in MIPMAPMODES:
        raise DiffMatError(f"transformation.mipmapmode: unknown value {mipmapmode!r}; "
                           f"expected one of {list(MIPMAPMODES)}")
    m = param2d(matrix22, input1)
    o = param2d(offset, input1)
    if m.shape[1] != 4:
        raise DiffMatError(f"transformation.matrix22: expected 4 components, got {m.shape[1]}")
    if o.shape[1] != 2:
        raise DiffMatError(f"transformation.offset: expected 2 components, got {o.shape[1]}")
    b = max(m.shape[0], o.shape[0])
    m, o = m.expand(b, 4), o.expand(b, 2)
    e = [m[:, i].reshape(b, 1, 1, 1) for i in range(4)]
    u, v = image_grid(input1)
    du = u - 0.5 - o[:, 0].reshape(b, 1, 1, 1)
    dv = v - 0.5 - o[:, 1].reshape(b, 1, 1, 1)
    su = e[0] * du + e[1] * dv + 0.5
    sv = e[2] * du + e[3] * dv + 0.5
    mode = FILTERING[filtering]

    h, w = input1.shape[-2:]
    top = int(math.log2(min(h, w)))
    if mipmapmode == 1:
        if not 0 <= manualmiplevel <= 16:
            raise DiffMatError(f"transformation.manualmiplevel: {manualmiplevel!r} is outside [0, 16]")
        level = torch.full((b,), float(min(manualmiplevel, top)), device=input1.device, dtype=input1.dtype)
    else:
        # source texels per output pixel along each output axis (same-size input and output)
        col = torch.maximum(torch.hypot(m[:, 0], m[:, 2]), torch.hypot(m[:, 1], m[:, 3]))
        level = torch.log2(col.clamp(min=1.0)).clamp(max=float(top))
    if mode == "nearest":
        level = torch.round(level)
    lo = int(math.floor(float(level.detach().min())))
    hi = int(math.ceil(float(level.detach().max())))
    out = None
    img = input1
    for k in range(0, hi + 1):
        if k > 0:
            img = F.avg_pool2d(img, 2)
        if k < lo:
            continue
        weight = torch.clamp(1.0 - (level - k).abs(), min=0.0).reshape(b, 1, 1, 1)
        sample = sample_wrap(img, su, sv, mode=mode)
        out = sample * weight if out is None else out + sample * weight
    assert out is not None  # level >= 0, so lo <= hi and the loop samples at least once
    return out
