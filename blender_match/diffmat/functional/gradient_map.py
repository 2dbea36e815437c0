"""Gradient Map and Gradient Dynamic (Substance's atomic ``gradient`` and ``dyngradient`` filters):
a grayscale image indexes a colour (or gray) gradient.

Gradient Map keys are continuous parameters — ``positions`` (one per key) and ``colors`` (RGBA,
4 per key), in any order (sorted by position) — so an optimiser can move and recolour them.
"""
from __future__ import annotations

import torch

from ..errors import DiffMatError
from .common import GRAY, check_choice, check_image, param2d, param4d, sample_wrap

__all__ = ["gradient_map", "dynamic_gradient"]

INTERP_MODES = {0: "linear", 1: "smooth", 2: "flat tangents", 3: "none"}


def _keys(positions, colors, like: torch.Tensor):
    p = param2d(positions, like)
    c = param2d(colors, like)
    k = p.shape[1]
    if k < 1:
        raise DiffMatError("gradient.positions: a gradient needs at least one key")
    if c.shape[1] != 4 * k:
        raise DiffMatError(f"gradient.colors: {k} key position(s) need {4 * k} colour values (RGBA per key), "
                           f"got {c.shape[1]}")
    b = max(p.shape[0], c.shape[0])
    p = p.expand(b, -1)
    c = c.expand(b, -1).reshape(b, k, 4)
    order = torch.argsort(p.detach(), dim=1, stable=True)
    p = torch.gather(p, 1, order)
    c = torch.gather(c, 1, order[..., None].expand(-1, -1, 4))
    return p, c


def gradient_map(input1: torch.Tensor, *, positions=(0.0, 1.0), colors=(0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0),
                 interpmode: int = 0, colorswitch: bool = True, addressingrepeat: bool = False) -> torch.Tensor:
    """Map each gray value x of ``input1`` through the gradient of keys (``positions``, ``colors``).

    Between neighbouring keys the colour is interpolated by ``interpmode``: 0 linear; 1 smooth and
    2 flat tangents (both ease with zero slope at each key: smoothstep weights); 3 none (each key's
    colour holds until the next key). Below the first key and above the last the end colours hold;
    with ``addressingrepeat`` the gradient wraps instead, interpolating from the last key to the
    first key (+1). ``colorswitch`` False gives a grayscale output from the keys' first component.
    Batched (B, k) keys give B outputs.
    """
    x = check_image(input1, "gradient.input1", (GRAY,))
    check_choice(interpmode, INTERP_MODES, "gradient.interpmode")
    p, c = _keys(positions, colors, x)
    if not colorswitch:
        c = c[..., :1]
    if addressingrepeat:
        p = torch.cat([p[:, -1:] - 1, p, p[:, :1] + 1], dim=1)
        c = torch.cat([c[:, -1:], c, c[:, :1]], dim=1)
    x = x.clamp(0.0, 1.0)
    out = c[:, 0, :, None, None]
    for i in range(p.shape[1] - 1):
        lo = p[:, i, None, None, None]
        hi = p[:, i + 1, None, None, None]
        step = c[:, i + 1, :, None, None] - c[:, i, :, None, None]
        if interpmode == 3:
            wgt = (x >= hi).to(x.dtype)
        else:
            inv = 1.0 / (hi - lo).clamp_min(1e-6)
            wgt = torch.addcmul(-lo * inv, x, inv).clamp(0.0, 1.0)      # (x - lo) / (hi - lo)
            if interpmode in (1, 2):
                wgt = wgt * wgt * (3 - 2 * wgt)
        out = torch.addcmul(out, wgt, step)
    return out.clamp(0.0, 1.0)


def dynamic_gradient(input1: torch.Tensor, input2: torch.Tensor, *, uvselector: int = 0, coordinate=0.0,
                     addressingrepeat: bool = False) -> torch.Tensor:
    """Gradient Dynamic: map each gray value x of ``input1`` through a gradient read from the image
    ``input2``: along the row at v = ``coordinate`` (``uvselector`` 0, horizontal: the colour at
    (x, coordinate)) or along the column at u = ``coordinate`` (1, vertical: (coordinate, x)).

    Bilinear sampling; with ``addressingrepeat`` the lookup wraps around ``input2``, otherwise it is
    clamped to the first/last pixel centres. Output has ``input2``'s channel count.
    """
    x = check_image(input1, "dyngradient.input1", (GRAY,))
    grad = check_image(input2, "dyngradient.input2")
    check_choice(uvselector, (0, 1), "dyngradient.uvselector")
    coord = param4d(coordinate, x)
    if coord.shape[1] != 1:
        raise DiffMatError(f"dyngradient.coordinate: expected 1 component, got {coord.shape[1]}")
    h, w = grad.shape[-2:]
    along = x
    across = coord.expand(-1, -1, *x.shape[-2:])
    n_along, n_across = (w, h) if uvselector == 0 else (h, w)
    if not addressingrepeat:
        along = along.clamp(0.5 / n_along, 1 - 0.5 / n_along)
        across = across.clamp(0.5 / n_across, 1 - 0.5 / n_across)
    b = max(along.shape[0], across.shape[0])
    along = along.expand(b, -1, -1, -1)
    across = across.expand(b, -1, -1, -1)
    u, v = (along, across) if uvselector == 0 else (across, along)
    return sample_wrap(grad, u, v).clamp(0.0, 1.0)
