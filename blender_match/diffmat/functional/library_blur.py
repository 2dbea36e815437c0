"""Library (non-atomic) blur, warp and transform nodes of Substance's standard library, written
natively: Blur HQ, Slope Blur, Non-Uniform Blur, Highpass, Vector Warp, Vector Morph, Mosaic,
Safe Transform, Make It Tile Patch / Photo.

Every op wraps around the image edges (FFT filtering, ``sample_wrap``, ``roll``), so tiling inputs
give tiling outputs. Distances given in pixels are pixels of a 256-pixel image (``/ 256`` texture
units), so results look the same at every resolution.
"""
from __future__ import annotations

import math

import torch

from ..errors import DiffMatError
from .common import (
    check_bool,
    expand_batch,
    frequencies,
    gaussian_blur,
    gradient_wrap,
    grid_affine,
    lerp,
    param4d,
    pixel_grid,
    sample_wrap,
    to_gray,
)
from .warp import directional_warp

__all__ = ["blur_hq", "slope_blur", "non_uniform_blur", "highpass", "vector_warp", "vector_morph",
           "mosaic", "safe_transform", "make_it_tile_patch", "make_it_tile_photo"]

PX = 1.0 / 256.0          # one Substance pixel (of a 256-px image) in texture units
BLUR_SIGMA = 0.5          # Gaussian sigma per unit of Blur HQ intensity, in 256-px pixels
# Substance stores the mode as a blending-mode code: 5 max, 6 min, 7 (switch) blur; 0 and 1 are
# this engine's older spellings of blur, kept for graphs written with them
SLOPE_MODES = {0: "blur", 1: "blur", 5: "max", 6: "min", 7: "blur"}
MAX_SLOPE_SAMPLES = 4         # cost: one bilinear pass per sample


def _grid(img: torch.Tensor):
    return pixel_grid(img.shape[-1], img.device, img.dtype)


def blur_hq(source: torch.Tensor, *, intensity=10.0, quality=0.0):
    """Blur HQ: a high-quality (Gaussian) wrap-around blur; ``intensity`` in 256-px pixels gives a
    sigma of intensity / 2 pixels. ``quality`` (sample count in Substance) does not change this
    exact FFT version."""
    sigma = param4d(intensity, source).abs() * (BLUR_SIGMA * PX)
    return expand_batch(gaussian_blur(source, sigma).clamp(0.0, 1.0), quality)


def highpass(source: torch.Tensor, *, radius=6.0):
    """Highpass: ``source - blur(source) + 0.5`` with a Blur HQ of ``radius`` pixels, clamped."""
    x = to_gray(source)
    sigma = param4d(radius, x).abs() * (BLUR_SIGMA * PX)
    return (x - gaussian_blur(x, sigma) + 0.5).clamp(0.0, 1.0)


def slope_blur(source: torch.Tensor, effect: torch.Tensor, *, samples: int = 8, mode: int = 1,
               intensity=10.0):
    """Slope Blur: smears ``source`` along the slope of the ``effect`` height map.

    Each pixel combines itself and ``samples`` (at most 4, for speed) samples taken down-slope
    (towards lower effect values) at distances up to ``intensity`` 256-px pixels (negative:
    up-slope), scaled by the local steepness (g / sqrt(1 + |g|^2), g the slope in value per
    image width). ``mode``: 7 (Substance's code), 0 or 1 blur (average),
    5 max, 6 min (Substance's blend-mode codes).
    """
    if mode not in SLOPE_MODES:
        raise DiffMatError(f"slope_blur.mode: unknown value {mode!r}; expected one of {sorted(SLOPE_MODES)}")
    if isinstance(samples, bool) or int(samples) < 1:
        raise DiffMatError(f"slope_blur.samples: expected a positive integer, got {samples!r}")
    n = min(int(samples), MAX_SLOPE_SAMPLES)
    if not torch.is_grad_enabled() or not (source.requires_grad or effect.requires_grad or (
            isinstance(intensity, torch.Tensor) and intensity.requires_grad)):
        return _slope_blur_nograd(source, effect, n, SLOPE_MODES[mode], intensity)
    gx, gy = gradient_wrap(gaussian_blur(to_gray(effect), PX))
    norm = torch.sqrt(1.0 + gx * gx + gy * gy)
    k = -param4d(intensity, source) * PX
    dx, dy = k * gx / norm, k * gy / norm
    u, v = _grid(source)
    taken = [source.expand(dx.shape[0], -1, -1, -1) if dx.shape[0] > source.shape[0] else source]
    taken += [sample_wrap(source, u + dx * ((i + 1) / n), v + dy * ((i + 1) / n)) for i in range(n)]
    kind = SLOPE_MODES[mode]
    if kind == "blur":
        out = sum(taken) / len(taken)
    else:
        stack = torch.stack(taken, dim=0)
        out = stack.amax(dim=0) if kind == "max" else stack.amin(dim=0)
    assert isinstance(out, torch.Tensor)  # ``taken`` is never empty, so its sum is a tensor
    return out.clamp(0.0, 1.0)


def _slope_blur_nograd(source, effect, n, kind, intensity):
    """``slope_blur`` without autograd: one padded copy of the source, the sample grids built
    in place, the samples accumulated in place (same arithmetic as the differentiable path).
    What it saves: docs/engine.md, "No-grad twins"."""
    with torch.no_grad():
        gx, gy = gradient_wrap(gaussian_blur(to_gray(effect), PX))
        norm = gx * gx
        norm.add_(1.0).add_(gy * gy).sqrt_()
        k = -param4d(intensity, source) * PX
        dx = (k * gx).div_(norm)
        dy = (k * gy).div_(norm)
        d = torch.stack([dx[:, 0], dy[:, 0]], dim=-1)                 # (B, H, W, 2)
        u, v = _grid(source)
        base = torch.stack([u[:, 0], v[:, 0]], dim=-1)                # (1, H, W, 2)
        b = max(source.shape[0], d.shape[0])
        h, w = source.shape[-2:]
        padded = torch.nn.functional.pad(source, (1, 1, 1, 1), mode="circular")
        if padded.shape[0] != b:
            padded = padded.expand(b, -1, -1, -1)
        scale, shift = grid_affine(w, h, source.device, source.dtype)
        out = source.expand(b, -1, -1, -1).clone() if kind == "blur" else None
        acc = source.expand(b, -1, -1, -1) if kind != "blur" else None
        for i in range(n):
            grid = d * ((i + 1) / n)
            grid.add_(base)
            grid.sub_(torch.floor(grid))
            grid = torch.addcmul(shift, grid, scale)
            if grid.shape[0] != b:
                grid = grid.expand(b, -1, -1, -1)
            smp = torch.nn.functional.grid_sample(padded, grid, mode="bilinear", padding_mode="border",
                                                  align_corners=True)
            if kind == "blur":
                out.add_(smp)
            elif kind == "max":
                acc = torch.maximum(acc, smp)
            else:
                acc = torch.minimum(acc, smp)
        if kind == "blur":
            out.div_(n + 1)
        else:
            out = acc.clone() if acc.data_ptr() == source.data_ptr() else acc
        return out.clamp_(0.0, 1.0)


def non_uniform_blur(source: torch.Tensor, effect: torch.Tensor, *, intensity=10.0, anisotropy=0.0,
                     asymmetry=0.0, angle=0.0, samples: int = 4, blades: int = 5):
    """Non-Uniform Blur: a blur whose radius follows ``effect`` (white: ``intensity`` 256-px
    pixels, as Blur HQ; black: none).

    The image is blurred at ``samples`` + 1 radii (2 to 7 levels, FFT) and each pixel blends the two
    levels around its effect value. ``anisotropy`` narrows the kernel across ``angle`` (turns),
    ``asymmetry`` shifts it forward along ``angle``. ``blades`` (bokeh shape) is not modelled: the
    kernel is Gaussian.
    """
    if isinstance(samples, bool) or int(samples) < 1:
        raise DiffMatError(f"non_uniform_blur.samples: expected a positive integer, got {samples!r}")
    levels = min(max(int(samples), 1), 6) + 1
    size = source.shape[-1]
    fx, fy = frequencies(size, source.device, source.dtype)
    smax = param4d(intensity, source).abs() * (BLUR_SIGMA * PX)
    a = param4d(angle, source) * (2 * math.pi)
    along = fx * torch.cos(a) + fy * torch.sin(a)
    across = -fx * torch.sin(a) + fy * torch.cos(a)
    aniso = param4d(anisotropy, source).clamp(0.0, 1.0)
    asym = param4d(asymmetry, source)
    spec = torch.fft.rfft2(source)
    t = to_gray(effect).clamp(0.0, 1.0) * (levels - 1)
    out = source * (1.0 - t).clamp(0.0, 1.0)
    for k in range(1, levels):
        s = smax * (k / (levels - 1))
        sa = s * (1.0 - aniso)
        mag = torch.exp(-2 * math.pi ** 2 * (s ** 2 * along ** 2 + sa ** 2 * across ** 2))
        phase = -2 * math.pi * along * (asym * s * 2.0)
        transfer = torch.complex(mag * torch.cos(phase), mag * torch.sin(phase))
        level = torch.fft.irfft2(spec * transfer, s=source.shape[-2:])
        w = (1.0 - (t - k).abs()).clamp(0.0, 1.0)
        out = out + level * w
    return out.clamp(0.0, 1.0)


def _vector(vector_map: torch.Tensor, vector_format: int, name: str):
    """Displacement (du, dv) from an RG vector map: (c * 2 - 1); green points up in OpenGL (1),
    down in DirectX (0)."""
    if vector_format not in (0, 1):
        raise DiffMatError(f"{name}.vector_format: unknown value {vector_format!r}; expected 0 (DirectX) or 1 (OpenGL)")
    if vector_map.shape[1] == 1:
        du = vector_map * 2 - 1
        dv = du
    else:
        du = vector_map[:, 0:1] * 2 - 1
        dv = vector_map[:, 1:2] * 2 - 1
    return du, (-dv if vector_format == 1 else dv)


def vector_warp(input: torch.Tensor, vector_map: torch.Tensor, *, intensity=1.0, vector_format: int = 0):
    """Vector Warp: samples ``input`` displaced by the vector map (RG in [0, 1] mapped to [-1, 1],
    times ``intensity`` image widths)."""
    du, dv = _vector(vector_map, vector_format, "vector_warp")
    k = param4d(intensity, input)
    u, v = _grid(input)
    return sample_wrap(input, u + k * du, v + k * dv).clamp(0.0, 1.0)


MORPH_STEPS = 2
MORPH_SCALE = 0.25        # image widths travelled at amount 1 along a unit vector


def vector_morph(input: torch.Tensor, vector_field: torch.Tensor, *, amount=1.0, vector_format: int = 0):
    """Vector Morph: advects ``input`` along the vector field (RG mapped to [-1, 1]), following the
    field in 2 steps over ``amount`` * 0.25 image widths."""
    _vector(vector_field, vector_format, "vector_morph")
    step = param4d(amount, input) * (MORPH_SCALE / MORPH_STEPS)
    u, v = _grid(input)
    pu, pv = u.expand(step.shape[0], -1, -1, -1), v.expand(step.shape[0], -1, -1, -1)
    for _ in range(MORPH_STEPS):
        field = sample_wrap(vector_field, pu, pv)
        du, dv = _vector(field, vector_format, "vector_morph")
        pu, pv = pu + step * du, pv + step * dv
    return sample_wrap(input, pu, pv).clamp(0.0, 1.0)


def mosaic(input: torch.Tensor, effect: torch.Tensor | None = None, *, intensity=0.5, samples: int = 4):
    """Mosaic: a multi-step warp of ``input`` along directions read from ``effect`` (or from the
    input itself): direction angle = value turns, total length ``intensity`` * 0.1 image widths, in
    ``samples`` steps (at most 4), which shatters the image into warped facets."""
    if isinstance(samples, bool) or int(samples) < 1:
        raise DiffMatError(f"mosaic.samples: expected a positive integer, got {samples!r}")
    n = min(int(samples), 4)
    k = param4d(intensity, input) * (0.1 / n)
    x = input
    u, v = _grid(input)
    for _ in range(n):
        e = to_gray(effect if effect is not None else x) * (2 * math.pi)
        x = sample_wrap(x, u + k * torch.cos(e), v + k * torch.sin(e))
    return x.clamp(0.0, 1.0)


# ---------------------------------------------------------------- safe transform
SYMMETRY = (0, 1, 2, 3)   # none, X, Y, X and Y


def _hash01(seed: int, n: int) -> torch.Tensor:
    g = torch.Generator().manual_seed(int(seed) & 0x7FFFFFFF)
    return torch.rand(n, generator=g, dtype=torch.float64)


def safe_transform(input: torch.Tensor, *, tile: int = 1, tile_mode: int = 0, tile_xy=(1.0, 1.0),
                   tile_safe_rotation: bool = True, offset=(0.0, 0.0), offset_mode: int = 0,
                   rotation=0.0, symmetry: int = 0, mipmap_mode: int = 0, mipmap_level: int = 0,
                   seed: int = 0):
    """Safe Transform: tiling, rotation, offset and mirroring that keep the image tileable.

    The output reads ``input`` at M (p - offset - 1/2) + 1/2, M = tiling x rotation. With
    ``tile_safe_rotation`` the rotation snaps to the nearest angle whose matrix is integer
    ([[a, -b], [b, a]], a = round(n cos r), b = round(n sin r); 45 degrees at tile 1 gives the
    classic sqrt(2) zoom); without it the rotation is continuous (and only tiles at multiples of
    90 degrees). ``tile_mode`` 1 uses ``tile_xy`` (per axis). ``offset_mode`` 1 adds a random
    offset from the seed. ``symmetry``: 0 none, 1 mirror X, 2 mirror Y, 3 both. Mipmap settings are
    accepted; a Gaussian pre-filter replaces mipmaps when minifying.
    """
    if symmetry not in SYMMETRY:
        raise DiffMatError(f"safe_transform.symmetry: unknown value {symmetry!r}; expected one of {list(SYMMETRY)}")
    if tile_mode not in (0, 1) or offset_mode not in (0, 1):
        raise DiffMatError("safe_transform: tile_mode and offset_mode must be 0 or 1")
    if isinstance(tile, bool) or int(tile) < 1:
        raise DiffMatError(f"safe_transform.tile: expected a positive integer, got {tile!r}")
    x = input
    if tile_mode == 1:
        txy = param4d(tile_xy, x).detach().flatten()
        tx, ty = max(1, round(float(txy[0]))), max(1, round(float(txy[-1])))
    else:
        tx = ty = int(tile)
    r = param4d(rotation, x)[:, :1]
    if check_bool(tile_safe_rotation, "safe_transform.tile_safe_rotation"):
        ang = r.detach().flatten().tolist()
        mats = []
        for a in ang:
            if tx == ty:
                ca = round(tx * math.cos(2 * math.pi * a))
                sb = round(tx * math.sin(2 * math.pi * a))
                if ca == 0 and sb == 0:
                    ca = 1
                mats.append((ca, -sb, sb, ca))
            else:
                q = round(4 * a) % 4
                qc, qs = ((1, 0), (0, 1), (-1, 0), (0, -1))[q]
                mats.append((qc * tx, -qs * ty, qs * tx, qc * ty))
        m = torch.tensor(mats, dtype=x.dtype, device=x.device).reshape(-1, 4, 1, 1)
        m = m + 0.0 * r  # keeps the batch (and the autograd graph) of ``rotation``
        m00, m01, m10, m11 = m[:, 0:1], m[:, 1:2], m[:, 2:3], m[:, 3:4]
    else:
        a = r * (2 * math.pi)
        c, s = torch.cos(a), torch.sin(a)
        m00, m01, m10, m11 = c * tx, -s * ty, s * tx, c * ty
    off = param4d(offset, x)
    ou, ov = off[:, :1], off[:, -1:]
    if offset_mode == 1:
        rnd = _hash01(seed, 2).to(dtype=x.dtype, device=x.device)
        ou, ov = ou + rnd[0], ov + rnd[1]
    u, v = _grid(x)
    if symmetry in (1, 3):
        u = 1.0 - u
    if symmetry in (2, 3):
        v = 1.0 - v
    pu, pv = u - ou - 0.5, v - ov - 0.5
    su = m00 * pu + m01 * pv + 0.5
    sv = m10 * pu + m11 * pv + 0.5
    scale = float(torch.sqrt(m00 * m00 + m10 * m10).detach().max()) if tx == ty else float(max(tx, ty))
    if scale > 2.0:
        x = gaussian_blur(x, 0.35 * scale / x.shape[-1])
    return sample_wrap(x, su, sv).clamp(0.0, 1.0)


# ---------------------------------------------------------------- make it tile
PATCH_MASK_FALLOFF = 21.3     # the stamp's round mask exp(-21.3 r²), r in stamp widths (MATch reference's Gaussian)
PATCH_MASK_FLOOR = 0.01       # mask values below this count as outside the stamp (they change nothing visible)
MAX_PATCH_RADIUS = 4          # at most (2·4 + 1)² cells of stamps looked at per pixel


def _cell_tables(n: int, seed: int, count: int, like: torch.Tensor) -> torch.Tensor:
    g = torch.Generator().manual_seed(int(seed) & 0x7FFFFFFF)
    return torch.rand(count, n, n, generator=g, dtype=torch.float64).to(device=like.device, dtype=like.dtype)


def _stamp_reach(size_cells: torch.Tensor, mask_size: torch.Tensor) -> torch.Tensor:
    """How far (in cells) from its centre a stamp ``size_cells`` wide can change a pixel: where
    its mask stays above ``1 - mask_size`` (and ``PATCH_MASK_FLOOR``), at most its half diagonal."""
    floor = (1.0 - mask_size).clamp_min(PATCH_MASK_FLOOR)
    return size_cells * torch.sqrt(torch.log(1.0 / floor) / PATCH_MASK_FALLOFF).clamp_max(0.5 * math.sqrt(2.0))


def _fold(cells: torch.Tensor, period: float, slack: torch.Tensor) -> torch.Tensor:
    """A displacement in cells folded onto the torus (``period`` cells) and, where it still goes
    further than ``slack`` cells, wrapped into ± ``slack`` (a stamp that far is anywhere anyway)."""
    cells = torch.remainder(cells + period / 2, period) - period / 2
    room = slack.clamp_min(1e-6)
    folded = torch.where(slack > 0, torch.remainder(cells + room, 2 * room) - room, torch.zeros_like(cells))
    return torch.where(slack >= period / 2, cells, folded)


def make_it_tile_patch(source: torch.Tensor, *, octave: int = 3, mask_size=1.0, mask_precision=0.5,
                       mask_warping=0.0, pattern_size_width=200.0, pattern_size_height=200.0, disorder=0.0,
                       size_variation=0.0, rotation=0.0, rotation_variation=0.0, color_variation=0.0,
                       background_color=(0.0, 0.0, 0.0, 1.0), seed: int = 0):
    """Make It Tile Patch: stamps the whole input, shrunk, over a grid so that it tiles.

    Substance's node is an FX-map; these are the facts of its documentation and of the MATch
    reference: a (2^octave)² grid of cells, two stamps a cell, each the whole input drawn
    ``pattern_size_width`` x ``pattern_size_height`` percent of a cell (plus the same random
    (r₁ − r₂) · ``size_variation`` percent on both), turned ``rotation`` + r · ``rotation_variation``
    turns, moved ``disorder`` image widths in a random direction, its colour multiplied by
    1 − r · ``color_variation`` per channel (the grayscale node's Luminosity Variation), and cut
    by a round mask: exp(−21.3 r²) through Levels with input range [1 − mask_size,
    1 − mask_precision · mask_size], displaced along the slope of the blurred input by
    ``mask_warping`` (a Warp of intensity mask_warping × 0.05 in stamp space). The stamps are
    laid over ``background_color`` (the grayscale node: over a level of ``color_variation``,
    as Substance does) by their masks, in order.

    Our choices: the stamps are laid in row-major order of their (unwrapped) cells, two a cell,
    so the order survives the wrap (Substance's FX-map order is a quadtree's); each pixel looks
    at the stamps of at most 9 x 9 cells around its own (``MAX_PATCH_RADIUS``): a disorder that
    would carry a stamp further wraps within that window, where its place is random anyway.
    """
    if isinstance(octave, bool) or not 0 <= int(octave) <= 8:
        raise DiffMatError(f"make_it_tile_patch.octave: expected an integer in [0, 8], got {octave!r}")
    x = source
    n = 2 ** int(octave)
    size = x.shape[-1]
    ms = param4d(mask_size, x).clamp(1e-3, 1.0)
    mp = param4d(mask_precision, x).clamp(0.0, 1.0)
    warp = param4d(mask_warping, x) * (0.05 / 256.0)
    width = param4d(pattern_size_width, x) / 100.0
    height = param4d(pattern_size_height, x) / 100.0
    variation = param4d(size_variation, x) / 100.0
    dis = param4d(disorder, x) * n
    rot = param4d(rotation, x)
    rvar = param4d(rotation_variation, x)
    cvar = param4d(color_variation, x)
    gray = x.shape[1] == 1

    # per batch item (detached: they only choose where to look), so that a batch gives each item
    # what it gives alone: how far stamps reach, how far they may move, how much the input is shrunk
    with torch.no_grad():
        reach = _stamp_reach(torch.maximum(width, height).abs() * (1.0 + variation.abs()), ms)
        slack = MAX_PATCH_RADIUS + 0.5 - reach
        moved = torch.where(slack >= n / 2, dis.abs().clamp_max(n / 2), torch.minimum(dis.abs(), slack.clamp_min(0.0)))
        within = torch.floor(reach + moved + 0.5).clamp_max(MAX_PATCH_RADIUS)
        shrink = n / torch.minimum(width, height).abs().clamp_min(1e-3)
        sigma = torch.where(shrink > 2.0, 0.35 * shrink / size, torch.zeros_like(shrink))
    radius = int(within.max())
    picture = gaussian_blur(x, sigma) if float(sigma.max()) > 0 else x
    warped = bool((warp != 0).any())
    if warped:
        slope_u, slope_v = gradient_wrap(gaussian_blur(to_gray(x), 1.6 * BLUR_SIGMA * PX))

    # per cell and stamp, once (B|1, quantity, stamp, cell): where its centre moves (cells), how it
    # turns, its size (image widths) and its tint; a pixel gathers these from its candidate cells
    def flat(t):
        return t.reshape(-1, 1, 1)

    angle, r1, r2, turn, c0, c1, c2 = _cell_tables(n, seed, 2 * 7, x).reshape(2, 7, n * n).unbind(1)
    a = angle * (2 * math.pi)
    t = (flat(rot) + turn * flat(rvar)) * (2 * math.pi)
    grow = (r1 - r2) * flat(variation)
    tints = [(1.0 - c * flat(cvar)).clamp(0.0, 1.0) for c in (c0, c1, c2)]
    per_cell = torch.stack(torch.broadcast_tensors(
        _fold(flat(dis) * torch.cos(a), n, flat(slack)), _fold(flat(dis) * torch.sin(a), n, flat(slack)),
        torch.cos(t), torch.sin(t), (flat(width) + grow).abs().clamp_min(1e-3) / n,
        (flat(height) + grow).abs().clamp_min(1e-3) / n, *tints), dim=1)
    u, v = _grid(x)
    i0 = torch.floor(u * n).long()
    j0 = torch.floor(v * n).long()
    if gray:
        out = cvar.clamp(0.0, 1.0).expand(-1, 1, size, size)
    else:
        back = param4d(background_color, x)
        out = back.expand(-1, x.shape[1], size, size) if back.shape[1] == x.shape[1] else \
            back[:, :x.shape[1]].expand(-1, -1, size, size)
    for dj in range(-radius, radius + 1):
        for di in range(-radius, radius + 1):
            i, j = i0 + di, j0 + dj
            cells = (torch.remainder(j, n) * n + torch.remainder(i, n)).reshape(-1)
            picked = per_cell[..., cells].unflatten(-1, (size, size))        # (B|1, 9, 2, H, W)
            near = (max(abs(di), abs(dj)) <= within).to(x.dtype)
            for k in range(2):
                du, dv, ca, sa, w, h, t0, t1, t2 = picked[:, :, k:k + 1].unbind(1)
                lu = u - (i.to(x.dtype) + 0.5 + du) / n
                lv = v - (j.to(x.dtype) + 0.5 + dv) / n
                pu = (ca * lu + sa * lv) / w
                pv = (ca * lv - sa * lu) / h
                inside = ((pu.abs() <= 0.5) & (pv.abs() <= 0.5)).to(x.dtype)
                qu, qv = pu, pv
                if warped:
                    qu = qu + warp * sample_wrap(slope_u, pu + 0.5, pv + 0.5)
                    qv = qv + warp * sample_wrap(slope_v, pu + 0.5, pv + 0.5)
                mask = torch.exp(-PATCH_MASK_FALLOFF * (qu * qu + qv * qv))
                alpha = ((mask - (1.0 - ms)) / (ms * (1.0 - mp)).clamp_min(1e-6)).clamp(0.0, 1.0) * inside * near
                tint = torch.cat([t0, t1, t2], dim=1)
                if gray:
                    tint = tint.mean(dim=1, keepdim=True)
                elif x.shape[1] == 4:
                    tint = torch.cat([tint, torch.ones_like(tint[:, :1])], dim=1)
                out = lerp(out, sample_wrap(picture, pu + 0.5, pv + 0.5) * tint, alpha)
    return out.clamp(0.0, 1.0)


def _seam_weight(t: torch.Tensor, size, precision, warping, guide: torch.Tensor, angle: float) -> torch.Tensor:
    """How much of the image shifted by half replaces the image at ``t`` (1 at the border, 0 in
    the middle). The MATch reference's facts: the kept share is Levels of 1 − x² (x = |2t − 1|)
    with input range [1 − size, 1 − precision · size], bent by a Directional Warp of the blurred
    image (``guide``) of intensity ``warping`` (−100..100) there and back along the axis."""
    x = (2.0 * t - 1.0).abs()
    keep = ((1.0 - x * x - (1.0 - size)) / (size * (1.0 - precision)).clamp_min(1e-6)).clamp(0.0, 1.0)
    keep = keep.expand(max(keep.shape[0], guide.shape[0]), 1, guide.shape[-2], guide.shape[-1])
    if bool((param4d(warping, guide) != 0).any()):
        keep = directional_warp(keep, guide, intensity=warping, warpangle=angle)
        keep = directional_warp(keep, guide, intensity=warping, warpangle=angle + 0.5)
    return 1.0 - keep


def make_it_tile_photo(source: torch.Tensor, *, mask_warping_h=0.0, mask_size_h=0.5, mask_precision_h=0.5,
                       mask_warping_v=0.0, mask_size_v=0.5, mask_precision_v=0.5):
    """Make It Tile Photo: hides the seams of a photo by cross-fading, near each border, to the
    image shifted by half its size (whose middle then straddles the border), first horizontally,
    then vertically (``_seam_weight``: ``mask_size`` how far the fade reaches, ``mask_precision``
    its hardness, ``mask_warping`` bends it with the image's blurred values). Our choice: the two
    fades one after the other; the reference crosses them in one mask and lays two more discs of
    the image shifted by a quarter at the middles of the edges."""
    x = source
    u, v = _grid(x)
    guide = blur_hq(to_gray(x), intensity=2.75)
    w = x.shape[-1]
    wh = _seam_weight(u, param4d(mask_size_h, x), param4d(mask_precision_h, x), mask_warping_h, guide, 0.0)
    h = lerp(x, torch.roll(x, w // 2, dims=-1), wh)
    wv = _seam_weight(v, param4d(mask_size_v, x), param4d(mask_precision_v, x), mask_warping_v,
                      blur_hq(to_gray(h), intensity=2.75), 0.25)
    return lerp(h, torch.roll(h, x.shape[-2] // 2, dims=-2), wv).clamp(0.0, 1.0)
