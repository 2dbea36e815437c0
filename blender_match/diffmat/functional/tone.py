"""Tone and channel ops: Levels, Curve, HSL, Grayscale Conversion and Channel Shuffle (Substance's
atomic ``levels``, ``curve``, ``hsl``, ``grayscaleconversion`` and ``shuffle`` filters).

All are per-pixel, so they tile whenever their input does. Per-channel parameters are RGBA
(Float4); a grayscale image reads the first (red) component, as Substance stores gray values with
equal RGB.
"""
from __future__ import annotations

import torch

from ..errors import DiffMatError
from .common import COLOR, GRAY, check_choice, check_image, param2d, param4d, step, to_color

__all__ = ["levels", "curve", "hsl", "grayscale_conversion", "channel_shuffle"]

# Levels' mid point as a gamma (the MATch reference implementation's reading of Substance, see
# docs/nodes.md): gamma = 1 + 8 |2 mid - 1|, at most 9, its inverse below mid 0.5.
_GAMMA_MAX = 9.0
_GAMMA_SLOPE = 8.0


def _per_channel(value, x: torch.Tensor, where: str) -> torch.Tensor:
    """A Float1/Float4 parameter as (B|1, C, 1, 1) for image ``x`` (C = 1 reads the first component)."""
    p = param4d(value, x)
    if p.shape[1] == 1:
        return p.expand(-1, x.shape[1], -1, -1)
    if p.shape[1] != COLOR:
        raise DiffMatError(f"{where}: expected 1 or 4 components, got {p.shape[1]}")
    return p[:, :1] if x.shape[1] == GRAY else p


def levels(input1: torch.Tensor, *, levelinlow=0.0, levelinmid=0.5, levelinhigh=1.0, leveloutlow=0.0,
           levelouthigh=1.0, clampinterm: bool = True) -> torch.Tensor:
    """Levels, per channel: t = (x - in_low) / (in_high - in_low) (in_low > in_high inverts);
    with ``clampinterm`` t is clamped to [0, 1]; then t^gamma with gamma = 1 + 8 |2 mid - 1|
    (at most 9) for mid >= 0.5 and its inverse below (mid 0.5 leaves t, mid 0.25 gives t^(1/5),
    mid 0.75 t^5: gamma is linear in the mid point, as in the MATch reference implementation;
    docs/nodes.md); finally out_low + t^gamma (out_high - out_low), clamped to [0, 1].

    Parameters are numbers or RGBA Float4 (a gray image uses the first component); batched (B, 4)
    parameters give B outputs.
    """
    x = check_image(input1, "levels.input1")
    lo = _per_channel(levelinlow, x, "levels.levelinlow")
    mid = _per_channel(levelinmid, x, "levels.levelinmid")
    hi = _per_channel(levelinhigh, x, "levels.levelinhigh")
    olo = _per_channel(leveloutlow, x, "levels.leveloutlow")
    ohi = _per_channel(levelouthigh, x, "levels.levelouthigh")
    span = hi - lo
    tiny = 1e-4
    sign = torch.where(span < 0, -1.0, 1.0).to(span.dtype)
    span = torch.where(span.abs() < tiny, sign * tiny, span)
    inv = 1.0 / span
    t = torch.addcmul(-lo * inv, x, inv)              # (x - lo) / span in one pass
    if clampinterm:
        t = t.clamp(0.0, 1.0)
    gamma = _mid_gamma(mid)
    if _needs_gamma(mid, gamma):
        t = _gamma_positive(t, gamma)
    return torch.addcmul(olo, t, ohi - olo).clamp(0.0, 1.0)


def _mid_gamma(mid: torch.Tensor) -> torch.Tensor:
    """The Levels exponent of a mid point: 1 + 8 |2 mid - 1| (at most 9), inverted below 0.5."""
    g = (torch.abs(mid * 2.0 - 1.0) * _GAMMA_SLOPE + 1.0).clamp_max(_GAMMA_MAX)
    return torch.where(mid < 0.5, 1.0 / g, g)


def _gamma_positive(t: torch.Tensor, gamma: torch.Tensor) -> torch.Tensor:
    """t^gamma where t > 0, t elsewhere; exp(gamma log t) and arithmetic masks instead of ``pow``
    with a tensor exponent and ``where`` (both slow on CPU, forward and backward)."""
    y = torch.exp(torch.log(t.clamp_min(1e-12)) * gamma)
    positive = 1.0 - step(-t)
    return torch.addcmul(t, positive, y - t)


def _needs_gamma(mid: torch.Tensor, gamma: torch.Tensor) -> bool:
    """False only when every gamma is exactly 1 and no gradient must flow to the mid point."""
    if torch.is_grad_enabled() and mid.requires_grad:
        return True
    return not bool((gamma == 1.0).all())


# ---------------------------------------------------------------------------------------------
# Curve

_CURVE_SAMPLES = 48      # Bézier samples per segment
_CURVE_LUT = 1024        # uniform lookup-table resolution used per pixel


def _lut_lookup(lut: torch.Tensor, x: torch.Tensor) -> torch.Tensor:
    """Piecewise-linear lookup of x in [0, 1] (N, C, H, W) into a uniform table ``lut`` (B, L)."""
    b_lut, n_lut = lut.shape
    n = max(b_lut, x.shape[0])
    pos = x.clamp(0.0, 1.0) * (n_lut - 1)
    i0 = pos.detach().floor().clamp(0, n_lut - 2).long()
    frac = pos - i0.to(pos.dtype)
    flat = i0.expand(n, -1, -1, -1).reshape(n, -1)
    table = lut.expand(n, -1)
    v0 = torch.gather(table, 1, flat).reshape(n, *x.shape[1:])
    v1 = torch.gather(table, 1, flat + 1).reshape(n, *x.shape[1:])
    return v0 + frac * (v1 - v0)


def _curve_table(positions, lefts, rights, like: torch.Tensor) -> torch.Tensor:
    """Sample the Bézier curve on a uniform grid of x in [0, 1]: (B, _CURVE_LUT)."""
    p, left, right = (param2d(v, like) for v in (positions, lefts, rights))
    for name, t in (("positions", p), ("lefts", left), ("rights", right)):
        if t.shape[1] < 2 or t.shape[1] % 2:
            raise DiffMatError(f"curve.{name}: expected x, y pairs, got {t.shape[1]} values")
    k = p.shape[1] // 2
    if left.shape[1] // 2 != k or right.shape[1] // 2 != k:
        raise DiffMatError(f"curve: {k} points but {left.shape[1] // 2} left and {right.shape[1] // 2} right handles")
    b = max(p.shape[0], left.shape[0], right.shape[0])
    p, left, right = (t.expand(b, -1).reshape(b, k, 2) for t in (p, left, right))
    order = torch.argsort(p[..., 0].detach(), dim=1)[..., None].expand(-1, -1, 2)
    p, left, right = (torch.gather(t, 1, order) for t in (p, left, right))
    if k == 1:
        return p[:, :, 1].expand(-1, _CURVE_LUT)
    p0, p3 = p[:, :-1], p[:, 1:]                            # segment ends (B, k-1, 2)
    x0, x3 = p0[..., 0], p3[..., 0]
    # handles: the right handle of the start point and the left handle of the end point, their x
    # kept inside the segment so that x(s) is monotonic and y(x) is a function.
    c1 = torch.stack([torch.minimum(torch.maximum(right[:, :-1, 0], x0), x3), right[:, :-1, 1]], dim=-1)
    c2 = torch.stack([torch.minimum(torch.maximum(left[:, 1:, 0], x0), x3), left[:, 1:, 1]], dim=-1)
    s = torch.linspace(0.0, 1.0, _CURVE_SAMPLES, device=like.device, dtype=like.dtype)[:, None]
    bern = torch.stack([(1 - s) ** 3, 3 * s * (1 - s) ** 2, 3 * s ** 2 * (1 - s), s ** 3])  # (4, S, 1)
    ctrl = torch.stack([p0, c1, c2, p3])[:, :, :, None, :]                                  # (4, B, k-1, 1, 2)
    pts = (bern[:, None, None] * ctrl).sum(0)                                               # (B, k-1, S, 2)
    px = pts[..., 0].reshape(b, -1)
    py = pts[..., 1].reshape(b, -1)
    grid = torch.linspace(0.0, 1.0, _CURVE_LUT, device=like.device, dtype=like.dtype)
    g = grid.expand(b, -1).contiguous()
    idx = torch.searchsorted(px.detach().contiguous(), g, right=True).clamp(1, px.shape[1] - 1)
    xa, xb = torch.gather(px, 1, idx - 1), torch.gather(px, 1, idx)
    ya, yb = torch.gather(py, 1, idx - 1), torch.gather(py, 1, idx)
    w = ((g - xa) / (xb - xa).clamp_min(1e-9)).clamp(0.0, 1.0)
    table = ya + w * (yb - ya)
    # outside the first/last point the curve is flat
    table = torch.where(g < px[:, :1], py[:, :1], table)
    table = torch.where(g > px[:, -1:], py[:, -1:], table)
    return table


def curve(input1: torch.Tensor, *, positions=(0.0, 0.0, 1.0, 1.0), lefts=(0.0, 0.0, 2 / 3, 2 / 3),
          rights=(1 / 3, 1 / 3, 1.0, 1.0)) -> torch.Tensor:
    """Luminance curve: each value x (RGB of a colour image, the gray of a grayscale one; alpha is
    kept) becomes y(x) on the cubic Bézier curve through the control points.

    ``positions`` holds the points' (x, y) pairs, ``lefts`` and ``rights`` their left and right
    Bézier handles (x, y) — flat lists, 2 values per point, any order (sorted by x). Segment i runs
    from point i with control points right_i, left_{i+1} to point i+1; handle x values are kept
    inside the segment. Left of the first point and right of the last the curve is flat. A broken
    handle is expressed by setting it to the point itself. Evaluated through a 1024-entry table.
    """
    x = check_image(input1, "curve.input1")
    table = _curve_table(positions, lefts, rights, x)
    if x.shape[1] == GRAY:
        return _lut_lookup(table, x).clamp(0.0, 1.0)
    rgb = _lut_lookup(table, x[:, :3]).clamp(0.0, 1.0)
    return torch.cat([rgb, x[:, 3:].expand(rgb.shape[0], -1, -1, -1)], dim=1)


# ---------------------------------------------------------------------------------------------
# HSL

def _rgb_to_hsl(rgb: torch.Tensor):
    r, g, b = rgb[:, 0:1], rgb[:, 1:2], rgb[:, 2:3]
    mx = rgb.amax(dim=1, keepdim=True)
    mn = rgb.amin(dim=1, keepdim=True)
    d = mx - mn
    s2 = mx + mn                                   # 2 l
    light = s2 * 0.5
    colour = step(d - 1e-7)                       # 0 on grays (d < 1e-7)
    inv = 1.0 / (d + (1.0 - colour))               # 1 / d, or 1 on grays (no division by 0)
    # saturation d / (1 - |2 l - 1|)
    sat = (d / (1.0 - (s2 - 1.0).abs()).clamp_min(1e-7)).clamp(0.0, 1.0) * colour
    # hue sector by the largest channel (r first, then g, then b, as a chain of where)
    with torch.no_grad():
        is_r = step(r - mx)
        is_g = (1.0 - is_r) * step(g - mx)
        is_b = 1.0 - is_r - is_g
    hr = (g - b) * inv
    hr = hr + 6.0 * (1.0 - step(hr))              # remainder(hr, 6) for hr in [-1, 1]
    # sectors: hr, (b - r)/d + 2, (r - g)/d + 4; the offsets 2 and 4 folded into one mask term
    hue = hr * is_r + ((b - r) * is_g + (r - g) * is_b) * inv + (2.0 * is_g + 4.0 * is_b)
    return hue * (colour * (1.0 / 6.0)), sat, light


_HSL_OFFSETS: dict = {}


def _hsl_to_rgb(hue, sat, light):
    a = sat * torch.minimum(light, 1 - light)
    key = (hue.device, hue.dtype)
    off = _HSL_OFFSETS.get(key)
    if off is None:
        off = _HSL_OFFSETS[key] = torch.tensor([0.0, 8.0, 4.0], device=hue.device, dtype=hue.dtype).reshape(1, 3, 1, 1)
    k = torch.addcmul(off, hue, hue.new_full((), 12.0))   # (N, 3, H, W): the three channels at once
    k = k - 12.0 * torch.floor(k.detach() * (1.0 / 12.0))  # remainder(k, 12) without torch.remainder
    m = torch.minimum(k - 3, 9 - k).clamp(-1.0, 1.0)
    return torch.addcmul(light, a, m, value=-1.0)


def hsl(input1: torch.Tensor, *, hue=0.5, saturation=0.5, luminosity=0.5) -> torch.Tensor:
    """Hue / saturation / lightness adjustment of a colour image (0.5 = unchanged; alpha kept).

    In HSL space: hue h + (2 hue - 1) turns (0, 0.5 and 1 all leave it unchanged: the slider runs
    from one full turn back to one full turn forward); saturation s + (2 sat - 1) and lightness
    l + (2 lum - 1), each clamped to [0, 1] (sat 0 = gray, lum 0 = black, lum 1 = white). These
    are the semantics of the MATch paper's public reference implementation, which its authors
    validated against Substance's renders (docs/engine.md, "HSL").
    """
    x = check_image(input1, "hsl.input1", (COLOR,))
    dh = param4d(hue, x)
    ds = param4d(saturation, x) * 2 - 1
    dl = param4d(luminosity, x) * 2 - 1
    for name, t in (("hue", dh), ("saturation", ds), ("luminosity", dl)):
        if t.shape[1] != 1:
            raise DiffMatError(f"hsl.{name}: expected 1 component, got {t.shape[1]}")
    if (not torch.is_grad_enabled() or not (x.requires_grad or dh.requires_grad or ds.requires_grad
                                              or dl.requires_grad)) \
            and max(dh.shape[0], ds.shape[0], dl.shape[0]) <= x.shape[0]:
        return _hsl_nograd(x, dh, ds, dl)
    h, s, light = _rgb_to_hsl(x[:, :3])
    h = h + 2 * dh - 1
    s = (s + ds).clamp(0.0, 1.0)
    light = (light + dl).clamp(0.0, 1.0)
    rgb = _hsl_to_rgb(h, s, light).clamp(0.0, 1.0)
    return torch.cat([rgb, x[:, 3:].expand(rgb.shape[0], -1, -1, -1)], dim=1)


def _hsl_nograd(x, dh, ds, dl):
    """``hsl`` without autograd: the same arithmetic as ``_rgb_to_hsl`` / ``hsl`` /
    ``_hsl_to_rgb``, op for op, on in-place temporaries, written straight into the output. What
    it saves: docs/engine.md, "No-grad twins"."""
    with torch.no_grad():
        rgb = x[:, :3]
        r, g, b = rgb[:, 0:1], rgb[:, 1:2], rgb[:, 2:3]
        mx = rgb.amax(dim=1, keepdim=True)
        mn = rgb.amin(dim=1, keepdim=True)
        d = mx - mn
        s2 = mn.add_(mx)                                   # 2 l (mx + mn)
        light = s2 * 0.5
        colour = step(d - 1e-7)
        inv = (1.0 - colour).add_(d).reciprocal_()
        t = (s2 - 1.0).abs_().neg_().add_(1.0).clamp_min_(1e-7)
        sat = d.div_(t).clamp_(0.0, 1.0).mul_(colour)
        del t, s2
        is_r = step(r - mx)
        not_r = (1.0 - is_r)
        is_g = step(g - mx).mul_(not_r)
        is_b = not_r.sub_(is_g)
        del mx, not_r
        hr = (g - b).mul_(inv)
        hr.add_(step(hr).neg_().add_(1.0).mul_(6.0))
        hue = hr.mul_(is_r)
        del is_r
        t = (b - r).mul_(is_g)
        t.add_((r - g).mul_(is_b))
        hue.add_(t.mul_(inv))
        del t, inv
        hue.add_(is_g.mul_(2.0).add_(is_b.mul_(4.0)))
        del is_g, is_b
        hue.mul_(colour.mul_(1.0 / 6.0))
        # adjustments (hsl)
        h = hue.add_(dh, alpha=2.0).sub_(1.0)
        s = sat.add_(ds).clamp_(0.0, 1.0)
        light.add_(dl).clamp_(0.0, 1.0)
        # back to RGB (_hsl_to_rgb)
        a = torch.minimum(light, 1 - light).mul_(s)
        key = (h.device, h.dtype)
        off = _HSL_OFFSETS.get(key)
        if off is None:
            off = _HSL_OFFSETS[key] = torch.tensor([0.0, 8.0, 4.0], device=h.device, dtype=h.dtype).reshape(1, 3, 1, 1)
        k = torch.addcmul(off, h, h.new_full((), 12.0))
        k.sub_(torch.floor(k * (1.0 / 12.0)).mul_(12.0))
        m = torch.minimum(k - 3, k.neg_().add_(9.0)).clamp_(-1.0, 1.0)
        n = h.shape[0]
        out = torch.empty((n, 4) + tuple(x.shape[-2:]), dtype=x.dtype, device=x.device)
        torch.addcmul(light, a, m, value=-1.0, out=out[:, :3])
        out[:, :3].clamp_(0.0, 1.0)
        out[:, 3:] = x[:, 3:]
        return out


# ---------------------------------------------------------------------------------------------
# Grayscale conversion and channel shuffle

def grayscale_conversion(input1: torch.Tensor, *, channelsweights=(0.33, 0.33, 0.33, 0.0),
                         alphamult: bool = False, mattelevel=1.0) -> torch.Tensor:
    """Colour to grayscale: sum of R, G, B, A weighted by ``channelsweights``, clamped to [0, 1].

    With ``alphamult`` (flatten alpha) the RGB is first composited over a background of gray
    level ``mattelevel``: c a + matte (1 - a).
    """
    x = check_image(input1, "grayscaleconversion.input1", (COLOR,))
    w = param4d(channelsweights, x)
    if w.shape[1] != COLOR:
        raise DiffMatError(f"grayscaleconversion.channelsweights: expected 4 components, got {w.shape[1]}")
    rgb, a = x[:, :3], x[:, 3:]
    if alphamult:
        matte = param4d(mattelevel, x)
        rgb = rgb * a + matte * (1 - a)
    gray = (rgb * w[:, :3]).sum(1, keepdim=True) + a * w[:, 3:]
    return gray.clamp(0.0, 1.0)


def channel_shuffle(input1: torch.Tensor, input2: torch.Tensor | None = None, *, channelred: int = 0,
                    channelgreen: int = 1, channelblue: int = 2, channelalpha: int = 3) -> torch.Tensor:
    """Channel Shuffle: an RGBA image whose each channel is copied from one channel of the inputs:
    0-3 = input1 R, G, B, A; 4-7 = input2 R, G, B, A. A grayscale input reads as (g, g, g, 1)."""
    a = to_color(check_image(input1, "shuffle.input1"))
    b = to_color(check_image(input2, "shuffle.input2")) if input2 is not None else None
    if b is not None and b.shape[-2:] != a.shape[-2:]:
        raise DiffMatError(f"shuffle.input2: size {tuple(b.shape[-2:])} differs from input1's {tuple(a.shape[-2:])}")
    chans = []
    for name, idx in (("channelred", channelred), ("channelgreen", channelgreen),
                      ("channelblue", channelblue), ("channelalpha", channelalpha)):
        check_choice(idx, range(8), f"shuffle.{name}")
        if idx >= 4 and b is None:
            raise DiffMatError(f"shuffle.{name}: reads input2 (value {idx}) but input2 is not connected")
        src = a if idx < 4 else b
        assert src is not None  # checked just above
        chans.append(src[:, idx % 4:idx % 4 + 1])
    n = max(c.shape[0] for c in chans)
    return torch.cat([c.expand(n, -1, -1, -1) for c in chans], dim=1)
