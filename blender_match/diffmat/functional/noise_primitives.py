"""Noise primitives the noise generators are built from: lattice (value / gradient) noise, fractal
sums, cellular (Worley) fields, Gaussian spot fields, fixed-lattice white noise, domain warping and
the continuous-scale blend.

Conventions (docs/engine.md, "Generators"):
- every random number comes from a ``torch.Generator`` seeded from (seed, key, lattice size), so a
  lattice of a given size is the same whichever octave or blend asks for it;
- lattices live in texture space: ``n`` cells across the image, integer, wrapping, so the noise
  tiles and a render at any size samples the same continuous function. Where a lattice is fine
  relative to the output (fewer than 4 pixels a cell) it is rendered supersampled and box-filtered,
  so a 1024 render box-downsampled to 512 equals the 512 render;
- zero-mean primitives are normalised to unit standard deviation, so generators combine them by
  weights and map the result to [0, 1] at the end (``squash``);
- ``disorder`` animates every lattice point around a circle (a phase shift, period 1): continuous
  and differentiable, and disorder 0 and 1 give the same pattern;
- separable evaluation: interpolating a lattice along x then y needs gathers over (n x size) and
  (size x size) elements only, so a layer costs O(size^2) whatever its frequency.
"""
from __future__ import annotations

import math
import zlib
from typing import Callable

import torch
import torch.nn.functional as F

from .common import param4d, sample_wrap

__all__ = ["lattice_noise", "fractal_noise", "cellular_noise", "gaussian_spot_field", "white_lattice_noise",
           "blend_scales", "domain_warp", "squash", "noise_batch"]

TWO_PI = 2 * math.pi
MAX_CELLS = 1024          # finest lattice any generator uses (cells across the image)
# empirical standard deviations of one layer at disorder 0 (used to normalise layers to unit std)
LAYER_STD = {("value", "quintic"): 0.547, ("value", "cubic"): 0.518, ("value", "linear"): 0.464,
        ("value", "nearest"): 0.707, ("gradient", "quintic"): 0.215, ("gradient", "cubic"): 0.211,
        ("gradient", "linear"): 0.209, ("gradient", "nearest"): 0.209}


# ----------------------------------------------------------------------------------------------
# random lattices
def _rng(seed: int, *keys) -> torch.Generator:
    """A CPU generator seeded from the node seed and any keys (names, lattice sizes)."""
    h = zlib.crc32(repr((int(seed),) + tuple(keys)).encode()) & 0xFFFFFFFF
    return torch.Generator().manual_seed(h * 2654435761 % (2 ** 62) + int(seed) % 997)


def lattice_phases(seed: int, key, ny: int, nx: int, device, dtype) -> tuple[torch.Tensor, torch.Tensor]:
    """Per-lattice-point phase (turns) and disorder speed (+1 or -1), each (1, ny, nx)."""
    g = _rng(seed, key, ny, nx)
    phi = torch.rand(1, ny, nx, generator=g, dtype=torch.float64)
    speed = torch.randint(0, 2, (1, ny, nx), generator=g).to(torch.float64) * 2 - 1
    return phi.to(device=device, dtype=dtype), speed.to(device=device, dtype=dtype)


def _uniforms(seed: int, key, n: int, count: int, device, dtype) -> torch.Tensor:
    """``count`` uniform [0, 1) values per cell of an n x n lattice: (count, n * n)."""
    g = _rng(seed, key, n, count)
    return torch.rand(count, n * n, generator=g, dtype=torch.float64).to(device=device, dtype=dtype)


def _as_batch(d, device, dtype) -> torch.Tensor:
    """A parameter as a (B, 1, 1) tensor (B = 1 for a number)."""
    t = param4d(0.0 if d is None else d).to(device=device, dtype=dtype)
    return t.reshape(t.shape[0], 1, 1)


def supersample_factor(size: int, cells: int) -> int:
    """Supersampling factor so that a render has >= 4 samples per cell (at most 4 x)."""
    ss = 1
    while size * ss < 4 * cells and ss < 4:
        ss *= 2
    return ss


def _fade(t: torch.Tensor, interp: str) -> torch.Tensor:
    if interp == "quintic":
        return t * t * t * (t * (t * 6 - 15) + 10)
    if interp == "cubic":
        return t * t * (3 - 2 * t)
    if interp == "linear":
        return t
    return torch.zeros_like(t)     # nearest: the lower lattice point, positions are cell-centred


def lattice_axis(res: int, n: int, device, dtype, interp: str, offset: float = 0.0):
    """Lattice indices (i0, i1), fraction and fade weight of ``res`` pixel centres on an n-cell axis
    whose lattice points sit ``offset`` cells in from the image edge."""
    c = (torch.arange(res, device=device, dtype=torch.float64) + 0.5) / res * n - offset
    if interp == "nearest":
        i0 = torch.floor(c).long() % n
        f = torch.zeros(res, dtype=torch.float64, device=device)
    else:
        i0 = torch.floor(c).long()
        f = c - i0
        i0 = i0 % n
    i1 = (i0 + 1) % n
    f = f.to(dtype)
    return i0, i1, f, _fade(f, interp)


# ----------------------------------------------------------------------------------------------
# separable lattice evaluation
#
# A layer of lattice noise is a sum of separable terms, out = Wy @ G @ Wx^T, where G is a small
# (ny, nx) lattice (the values, or one gradient component) and Wy / Wx are (pixels x cells)
# interpolation operators with two non-zeros a row (the fade weights of the two neighbouring
# lattice points; gradient noise adds the "ramp" operator whose weights carry the offset from the
# lattice point). Supersampling followed by box filtering is linear too, so it is folded into the
# operators (averaged over a pixel's sub-samples): no supersampled image is ever built. Coarse axes
# are applied as dense matrix products (one GEMM for all the coarse terms of a fractal sum); fine
# axes as a few row gathers ("taps").
_DENSE_MAX = 128          # x axes up to this many cells are dense products, finer ones taps
_BLOCK = 32               # pixel rows a block of the banded y product
_AXIS_CACHE: dict = {}
_PHASE_CACHE: dict = {}


class _AxisOp:
    """One axis operator of an n-cell lattice rendered at ``size`` pixels: the dense (size, n)
    matrix, its taps (pixel y reads cells base[y] + k, k < K, with weight w[y, k]) and, per block of
    ``_BLOCK`` pixels, the window of cells the block reads (``banded``)."""

    __slots__ = ("n", "size", "dense", "base", "w", "cols", "_band")

    def __init__(self, n, size, dense, base, w):
        self.n, self.size, self.dense, self.base, self.w = n, size, dense, base, w
        idx = torch.remainder(base[:, None] + torch.arange(w.shape[1], device=base.device), n)
        self.cols = [(idx[:, k].contiguous(), w[:, k].contiguous()) for k in range(w.shape[1])]
        self._band = None

    def window(self) -> int:
        """Cells read by one block of pixels (>= n: use the dense matrix)."""
        return self.banded()[0]

    def banded(self):
        """(L, idx (nblocks * L) long, W (nblocks, R, L)): block b of R pixels reads cells
        idx[b L: (b + 1) L] with weights W[b]."""
        if self._band is None:
            size, k = self.w.shape
            r = min(_BLOCK, size)
            nb = size // r
            base = self.base.view(nb, r)
            start = base[:, :1]
            length = int((base[:, -1:] - start).max()) + k
            if length >= self.n:
                self._band = (length, None, None)
                return self._band
            rel = (base - start)[:, :, None] + torch.arange(k, device=base.device)     # (nb, r, k)
            wb = torch.zeros(nb, r, length, dtype=self.w.dtype, device=self.w.device)
            wb.scatter_add_(2, rel, self.w.view(nb, r, k))
            idx = torch.remainder(start + torch.arange(length, device=base.device), self.n).reshape(-1)
            self._band = (length, idx, wb)
        return self._band


def _axis_ops(size: int, n: int, ss: int, interp: str, offset: float, device, dtype) -> dict:
    """The box-filtered ``lerp`` and ``ramp`` operators of an n-cell axis rendered at ``size``
    pixels with ``ss`` sub-samples a pixel, lattice points ``offset`` cells in from the edge."""
    key = (size, n, ss, interp, offset, str(device), dtype)
    hit = _AXIS_CACHE.get(key)
    if hit is not None:
        return hit
    res = size * ss
    c = (torch.arange(res, dtype=torch.float64) + 0.5) / res * n - offset
    i0 = torch.floor(c)
    if interp == "nearest":
        f = torch.zeros(res, dtype=torch.float64)
    else:
        f = c - i0
    f = f.to(dtype).to(torch.float64)
    w = _fade(f.to(dtype), interp).to(torch.float64) if interp != "nearest" else torch.zeros_like(f)
    i0 = i0.long().view(size, ss)
    base = i0[:, :1]
    rel = i0 - base                                                     # (size, ss), small
    k = int(rel.max()) + 2
    ops = {}
    for name, (w0, w1) in (("lerp", (1 - w, w)), ("ramp", ((1 - w) * f, w * (f - 1)))):
        taps = torch.zeros(size, k, dtype=torch.float64)
        taps.scatter_add_(1, rel, w0.view(size, ss) / ss)
        taps.scatter_add_(1, rel + 1, w1.view(size, ss) / ss)
        idx = torch.remainder(base + torch.arange(k), n)
        dense = torch.zeros(size, n, dtype=torch.float64).scatter_add_(1, idx, taps)
        ops[name] = _AxisOp(n, size, dense.to(device=device, dtype=dtype), base[:, 0].to(device),
                            taps.to(device=device, dtype=dtype))
    if len(_AXIS_CACHE) > 512:
        _AXIS_CACHE.clear()
    _AXIS_CACHE[key] = ops
    return ops


def _apply_x(g: torch.Tensor, op: _AxisOp) -> torch.Tensor:
    """g (B, ny, nx) times op^T: (B, ny, size)."""
    if op.n <= _DENSE_MAX:
        return torch.matmul(g, op.dense.t())
    out = None
    for idx, w in op.cols:
        t = g.index_select(-1, idx) * w
        out = t if out is None else out + t
    assert out is not None  # an axis op has at least one tap
    return out


def _apply_y(terms):
    """Sum of op_y @ t over ``terms`` [(op_y, t (B, ny, size))]: (B, size, size). Terms whose
    blocks of pixels read the whole lattice are one dense matrix product; the others one batched
    product over blocks of rows, each reading its window of lattice rows."""
    dense = [(op, t) for op, t in terms if op.window() >= op.n]
    band = [(op, t) for op, t in terms if op.window() < op.n]
    out = None
    if dense:
        a = torch.cat([op.dense for op, _ in dense], dim=1) if len(dense) > 1 else dense[0][0].dense
        b = max(t.shape[0] for _, t in dense)
        ts = [t.expand(b, -1, -1) for _, t in dense]
        out = torch.matmul(a, torch.cat(ts, dim=1) if len(ts) > 1 else ts[0])
    if band:
        size = band[0][0].size
        b = max(t.shape[0] for _, t in band)
        ws, rows = [], []
        for op, t in band:
            length, idx, wb = op.banded()
            ws.append(wb)
            rows.append(t.index_select(-2, idx).view(t.shape[0], wb.shape[0], length, size).expand(b, -1, -1, -1))
        w = torch.cat(ws, dim=2) if len(ws) > 1 else ws[0]
        r = torch.cat(rows, dim=2) if len(rows) > 1 else rows[0]
        prod = torch.matmul(w, r).view(b, size, size)
        out = prod if out is None else out + prod
    return out


def _phases_cached(seed, key, ny, nx, device, dtype):
    k = (int(seed), repr(key), ny, nx, str(device), dtype)
    hit = _PHASE_CACHE.get(k)
    if hit is None:
        hit = lattice_phases(seed, key, ny, nx, device, dtype)
        if len(_PHASE_CACHE) > 256:
            _PHASE_CACHE.clear()
        _PHASE_CACHE[k] = hit
    return hit


def _second_theta(seed, key, kind, ny, nx, disorder, device, dtype):
    """Phases of the second (half-cell offset) gradient lattice, animated by disorder like the first."""
    phi, speed = _phases_cached(seed, (key, kind, "offset"), ny, nx, device, dtype)
    d = _as_batch(disorder, device, dtype)
    if isinstance(disorder, torch.Tensor) or d.shape[0] > 1 or float(d.reshape(-1)[0]) != 0.0:
        return TWO_PI * (phi + speed * d)
    return TWO_PI * phi


def _layer_terms(cells, size: int, *, seed, key, kind, interp, disorder, weight, device, dtype):
    """The separable terms [(op_y, t)] of one lattice layer times ``weight`` (number or (B, 1, 1))
    (see the section comment); the layer is ``_apply_y(terms)``."""
    nx, ny = (cells, cells) if isinstance(cells, int) else (int(cells[0]), int(cells[1]))
    nx, ny = max(nx, 1), max(ny, 1)
    phi, speed = _phases_cached(seed, (key, kind), ny, nx, device, dtype)
    d = _as_batch(disorder, device, dtype)
    if isinstance(disorder, torch.Tensor) or d.shape[0] > 1 or float(d.reshape(-1)[0]) != 0.0:
        theta = TWO_PI * (phi + speed * d)                               # (B, ny, nx)
    else:
        theta = TWO_PI * phi
    ss = max(supersample_factor(size, nx), supersample_factor(size, ny))
    # any lattice offset tiles; value noise is flattest at its lattice points and gradient noise
    # steepest there, so value lattices sit on the image edge and gradient ones half a cell in.
    off = 0.0 if kind == "value" else 0.5
    if kind == "value":
        ax = _axis_ops(size, nx, ss, interp, off, device, dtype)
        ay = _axis_ops(size, ny, ss, interp, off, device, dtype)
        w = weight / LAYER_STD[(kind, interp)]
        return [(ay["lerp"], _apply_x(torch.cos(theta) * w, ax["lerp"]))]
    if kind == "gradient":
        # Perlin noise is 0 at its lattice points and its variance halves along the lattice lines,
        # which shows as a faint axis-aligned grid; a second, independent lattice offset by half a
        # cell (variance highest where the first's is lowest) makes the sum's variance nearly
        # uniform, so the noise looks isotropic. Both tile; the sum keeps unit std.
        interp_ = "linear" if interp == "nearest" else interp
        w = weight / (LAYER_STD[(kind, interp)] * math.sqrt(2.0))
        terms = []
        for lat_off, th in ((off, theta), (0.0, _second_theta(seed, key, kind, ny, nx, disorder, device, dtype))):
            ax = _axis_ops(size, nx, ss, interp_, lat_off, device, dtype)
            ay = _axis_ops(size, ny, ss, interp_, lat_off, device, dtype)
            gx, gy = torch.cos(th) * w, torch.sin(th) * w
            terms += [(ay["lerp"], _apply_x(gx, ax["ramp"])), (ay["ramp"], _apply_x(gy, ax["lerp"]))]
        return terms
    raise ValueError(f"lattice_noise: unknown kind {kind!r}")


def lattice_noise(cells, size: int, *, seed: int = 0, key="lattice", kind: str = "gradient",
                  interp: str = "quintic", disorder=0.0, device=None, dtype=torch.float32) -> torch.Tensor:
    """One layer of tileable lattice noise, zero mean and unit standard deviation: (B, 1, size, size).

    ``cells`` is an int or (nx, ny): lattice cells across and down the image (anisotropic when they
    differ). ``kind`` "value" interpolates random values, "gradient" is Perlin's gradient noise;
    ``interp`` is the fade ("quintic", "cubic", "linear", "nearest"). ``disorder`` (number or (B, 1))
    phase-shifts every lattice point (value = cos, gradient direction = angle of the phase).
    Fine lattices (< 4 pixels a cell) are supersampled and box-filtered (folded into the
    separable operators).
    """
    terms = _layer_terms(cells, size, seed=seed, key=key, kind=kind, interp=interp, disorder=disorder,
                         weight=1.0, device=device, dtype=dtype)
    return _apply_y(terms)[:, None]


def fractal_noise(cells, size: int, *, octaves: int, roughness=0.5, seed: int = 0, key="fractal",
                  kind: str = "gradient", interp: str = "quintic", disorder=0.0, lacunarity: int = 2,
                  mode: str = "fbm", first_octave: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """A fractal sum of lattice layers, zero mean and about unit std: (B, 1, size, size).

    Octave o has ``cells * lacunarity**o`` cells and weight ``roughness**o`` (roughness a number or
    (B, 1), differentiable). ``mode``: "fbm" (plain sum), "ridged" (sum of 1 - 2|layer|, sharp
    crests), "billow" (sum of 2|layer| - 1, puffy). Octaves finer than MAX_CELLS are dropped (their
    weight is negligible at every size the engine renders); octaves with fewer than two pixels a cell are
    left out of the render (an anti-aliasing prefilter) but kept in the normalisation, so the other
    octaves have the same amplitude at every size. A plain sum is evaluated as one batch of
    separable terms (a single matrix product for all coarse octaves).
    """
    nx, ny = (cells, cells) if isinstance(cells, int) else (int(cells[0]), int(cells[1]))
    r = param4d(roughness).to(device=device, dtype=dtype)
    rb = r.reshape(r.shape[0], 1, 1)
    total = None
    terms = []
    norm: float | torch.Tensor = 0.0
    bias: float | torch.Tensor = 0.0
    for o in range(first_octave, first_octave + octaves):
        f = lacunarity ** o
        cx, cy = nx * f, ny * f
        if max(cx, cy) > MAX_CELLS and o > first_octave:
            break
        w = r ** (o - first_octave)
        norm = norm + w * w               # the norm counts every octave, rendered or not
        if 2 * max(cx, cy) > size and o > first_octave:
            continue                      # above Nyquist (< 2 pixels a cell): removed (prefilter)
        if mode == "fbm":
            wb = rb ** (o - first_octave) if o > first_octave else 1.0
            terms += _layer_terms((cx, cy), size, seed=seed, key=(key, o), kind=kind, interp=interp,
                                  disorder=disorder, weight=wb, device=device, dtype=dtype)
            continue
        layer = _apply_y(_layer_terms((cx, cy), size, seed=seed, key=(key, o), kind=kind, interp=interp,
                                      disorder=disorder, weight=1.0, device=device, dtype=dtype))[:, None]
        if mode in ("ridged", "billow"):
            # (1.6 |layer|~ - 1.3) / 0.95, |layer|~ = sqrt(layer^2 + 0.01) (a rounded crease), negated
            # when ridged; the constant part is added once at the end
            soft_abs = torch.hypot(layer, _const(0.1, layer))
            sign = -1.0 if mode == "ridged" else 1.0
            gain = w * (sign * 1.6 / 0.95)
            bias = bias + w * (-sign * 1.3 / 0.95)
            total = soft_abs * gain if total is None else torch.addcmul(total, soft_abs, gain)
        else:
            total = layer * w if total is None else torch.addcmul(total, layer, w)
    assert isinstance(norm, torch.Tensor)  # octaves >= 1: the first octave is always counted
    if mode == "fbm":
        total = _apply_y(terms)[:, None]
        return total * torch.rsqrt(norm)
    inv = torch.rsqrt(norm)
    assert total is not None  # the first octave is always rendered
    return torch.addcmul(bias * inv, total, inv)


def _const(value: float, like: torch.Tensor) -> torch.Tensor:
    return torch.tensor(value, device=like.device, dtype=like.dtype)


# ----------------------------------------------------------------------------------------------
# cellular fields
def _cell_grid(size: int, n: int, device, dtype):
    ss = supersample_factor(size, n)
    res = size * ss
    c = (torch.arange(res, device=device, dtype=dtype) + 0.5) / res * n
    ci = torch.floor(c.detach()).long()
    return ss, res, ci, c - ci.to(dtype)


def _feature_points(n: int, seed: int, key, jitter, disorder, device, dtype):
    """Feature point offsets inside each cell, (B, n*n) each for x and y, plus 4 random attributes."""
    u = _uniforms(seed, key, n, 7, device, dtype)                       # (7, n*n)
    j = _as_batch(jitter, device, dtype).reshape(-1, 1)
    d = _as_batch(disorder, device, dtype).reshape(-1, 1)
    speed = torch.where(u[6] < 0.5, -1.0, 1.0).to(dtype)
    ang = TWO_PI * (u[2] + speed * d)
    ang0 = TWO_PI * u[2]
    px = 0.5 + j * 0.42 * (u[0] * 2 - 1) + 0.12 * (torch.cos(ang) - torch.cos(ang0))
    py = 0.5 + j * 0.42 * (u[1] * 2 - 1) + 0.12 * (torch.sin(ang) - torch.sin(ang0))
    return px, py, u[3:6]


_NB_DJ = (-1, -1, -1, 0, 0, 0, 1, 1, 1)
_NB_DI = (-1, 0, 1, -1, 0, 1, -1, 0, 1)
_ROWS_CHUNK = 1 << 20     # candidate values a block of rows evaluates together


def _neighbour_tables(size: int, n: int, device, dtype):
    """Supersampling factor, per-sample cell (res,), offset from the cell's corner (res,) and the
    flat cell index of the 9 neighbours of every cell, (n, n, 9) (candidate k = 3 (dy+1) + (dx+1))."""
    ss, res, ci, cf = _cell_grid(size, n, device, dtype)
    ar = torch.arange(n, device=device)
    dj = torch.tensor(_NB_DJ, device=device)
    di = torch.tensor(_NB_DI, device=device)
    ncell = torch.remainder(ar[:, None, None] + dj, n) * n + torch.remainder(ar[None, :, None] + di, n)
    return ss, res, ci, cf, ncell, dj.to(dtype), di.to(dtype)


def _split_offsets(px, py, size, n, device, dtype):
    """Offsets from each sample to the 9 candidate points, split by axis: ox (B, n cy, res x, 9)
    and oy (B, res y, n cx, 9) (so a sample's offsets are a row of each)."""
    ss, res, ci, cf, ncell, dj, di = _neighbour_tables(size, n, device, dtype)
    tx = px[:, ncell] + di                                                  # (B, n, n, 9)
    ty = py[:, ncell] + dj
    ox = (cf[:, None] - tx[:, :, ci])                                       # (B, n, res, 9)
    oy = (cf[:, None, None] - ty.index_select(1, ci))                       # (B, res, n, 9)
    return ss, res, ci, ncell, ox, oy


def _row_chunks(tx: torch.Tensor, ty: torch.Tensor, ci: torch.Tensor, res: int, b: int):
    """Blocks of sample rows (at most ``_ROWS_CHUNK`` candidate values each): yields the block's
    cell rows and its two row gathers, ``tx`` (B, n, res, 9) by cell row and ``ty`` (B, res, n, 9)
    by cell column, each (B, m, res, 9)."""
    chunk = max(1, _ROWS_CHUNK // (9 * res * b))
    for r0 in range(0, res, chunk):
        rows = ci[r0:r0 + chunk]
        yield rows, tx.index_select(1, rows), ty[:, r0:r0 + rows.shape[0]].index_select(2, ci)


def cellular_noise(cells: int, size: int, *, seed: int = 0, key="cells", jitter=1.0, disorder=0.0,
                   device=None, dtype=torch.float32) -> dict:
    """Worley (cellular) fields on an n x n jittered grid that wraps.

    Returns a dict of (B, 1, size, size) tensors: ``f1`` and ``f2`` (distances to the nearest and
    second-nearest feature point, in cells), ``value`` (a uniform random value of the nearest cell),
    ``facet`` (a random plane across the nearest cell: the value plus a random slope times the
    offset from its feature point, the look of crystal facets).

    The 9 candidates lie on a last, contiguous axis; a sample's x offsets depend on its cell row and
    its column only, its y offsets on its row and cell column, so a block of rows is two row
    gathers of small tables; the candidates' random values are read once per sample, for the
    nearest only.
    """
    n = max(int(cells), 1)
    px, py, attr = _feature_points(n, seed, key, jitter, disorder, device, dtype)
    ss, res, ci, ncell, ox, oy = _split_offsets(px, py, size, n, device, dtype)
    b = ox.shape[0]
    nflat = ncell.reshape(-1)
    val = attr[0][nflat]                                                    # (n*n*9,)
    slx = (attr[1] * 2 - 1)[nflat]
    sly = (attr[2] * 2 - 1)[nflat]
    d1s, d2s, v1s, fcs = [], [], [], []
    for rows, gx, gy in _row_chunks(ox, oy, ci, res, b):
        m = rows.shape[0]
        dist = torch.addcmul(gx * gx, gy, gy)
        d12, i12 = torch.topk(dist, 2, dim=-1, largest=False)               # sorted ascending
        i1 = i12[..., :1]
        k1 = ((rows[:, None] * n + ci[None, :]).view(1, m, res, 1) * 9 + i1)[..., 0]   # (B, m, res)
        o1x = gx.gather(-1, i1)[..., 0]
        o1y = gy.gather(-1, i1)[..., 0]
        v = val[k1]
        d1s.append(d12[..., 0])
        d2s.append(d12[..., 1])
        v1s.append(v)
        fcs.append(v + 0.6 * (slx[k1] * o1x + sly[k1] * o1y))
    out = {"f1": torch.sqrt(torch.cat(d1s, 1) + 1e-12), "f2": torch.sqrt(torch.cat(d2s, 1) + 1e-12),
           "value": torch.cat(v1s, 1), "facet": torch.cat(fcs, 1)}
    out = {k: v[:, None] for k, v in out.items()}
    if ss > 1:
        out = {k: F.avg_pool2d(v, ss) for k, v in out.items()}
    return out


def gaussian_spot_field(cells: int, size: int, *, seed: int = 0, key="spots", radius=0.35, jitter=1.0,
                        disorder=0.0, density=1.0, device=None, dtype=torch.float32) -> torch.Tensor:
    """A sum of Gaussian bumps, one per lattice cell at a jittered point, random amplitude and
    random size (radius in cells, x [0.5, 1.5]); a cell shows its spot when its random draw is
    below ``density`` (smoothly, so density is differentiable). Returns (B, 1, size, size) >= 0.

    A bump is separable, amp exp(-ox^2 / 2r^2) exp(-oy^2 / 2r^2): the x factor (with the amplitude)
    is a table over (cell row, sample column, candidate), the y factor over (sample row, cell
    column, candidate), so the field is a 9-term dot product of two row gathers per sample.
    """
    n = max(int(cells), 1)
    px, py, attr = _feature_points(n, seed, key, jitter, disorder, device, dtype)
    ss, res, ci, ncell, ox, oy = _split_offsets(px, py, size, n, device, dtype)
    rad = _as_batch(radius, device, dtype).reshape(-1, 1) * (0.5 + attr[1])   # (B, n*n)
    dens = _as_batch(density, device, dtype).reshape(-1, 1)
    amp = (0.4 + 0.6 * attr[0]) * torch.sigmoid((dens - attr[2]) * 12.0)
    inv2r2 = 0.5 / (rad * rad)
    ex = amp[:, ncell][:, :, ci] * torch.exp(-(ox * ox) * inv2r2[:, ncell][:, :, ci])          # (B, n, res, 9)
    iy = inv2r2[:, ncell].index_select(1, ci)                                                   # (B, res, n, 9)
    ey = torch.exp(-(oy * oy) * iy)
    b = max(ex.shape[0], ey.shape[0])
    ex, ey = ex.expand(b, -1, -1, -1), ey.expand(b, -1, -1, -1)
    parts = [(gx * gy).sum(-1) for _, gx, gy in _row_chunks(ex, ey, ci, res, b)]
    out = torch.cat(parts, 1)[:, None]
    if ss > 1:
        out = F.avg_pool2d(out, ss)
    return out


SHARD_REACH = (3, 5)   # cells a shard reaches from its own, across and down (see shard_field)


def shard_field(cells: int, size: int, *, seed: int = 0, key="shards", disorder=0.0, device=None,
                dtype=torch.float32) -> torch.Tensor:
    """Upright half-bell shards, one per cell of a ``cells`` x ``cells`` lattice, each of random
    brightness in [-1, 1] added to a flat zero field: (B, 1, size, size).

    A shard is 1-2 cells wide and 4-8 cells tall, turned by up to 0.0675 turn (about 24 degrees)
    from upright; its profile is a bell, (1 - r^2)^2 over its ellipse, cut off sharply along its
    long axis (the right half is empty), so every shard has one soft and one hard edge. These are
    the facts of Crystal 2's patterns in the public MATch reference (docs/generators.md). A shard
    reaches at most ``SHARD_REACH`` cells from its own, so each sample sums the shards of that
    neighbourhood of cells.
    """
    n = max(int(cells), 1)
    px, py, _ = _feature_points(n, seed, key, 0.6, disorder, device, dtype)            # (B, n*n)
    width, height, turn, level = _uniforms(seed, (key, "shape"), n, 4, device, dtype)
    angle = TWO_PI * 0.0675 * (turn * 2 - 1)
    b = px.shape[0]
    centres = torch.cat([px, py])                                                      # (2B, n*n)
    # per cell: cos and sin of the turn over the half width, then over the half height, brightness
    shapes = torch.stack([torch.cos(angle) * 2 / (1.0 + width), torch.sin(angle) * 2 / (1.0 + width),
                          torch.cos(angle) / (2.0 + 2.0 * height), torch.sin(angle) / (2.0 + 2.0 * height),
                          level * 2 - 1])                                              # (5, n*n)
    ss, res, ci, cf = _cell_grid(size, n, device, dtype)
    out = torch.zeros(b, res * res, device=device, dtype=dtype)
    fx = cf[None, :].expand(res, res).reshape(-1)
    fy = cf[:, None].expand(res, res).reshape(-1)
    reach_x, reach_y = SHARD_REACH
    for dy in range(-reach_y, reach_y + 1):
        rows = torch.remainder(ci + dy, n)[:, None] * n
        for dx in range(-reach_x, reach_x + 1):
            cell = (rows + torch.remainder(ci + dx, n)[None, :]).reshape(-1)
            centre = centres[:, cell]
            cos_w, sin_w, cos_h, sin_h, brightness = shapes[:, cell]
            ox = fx - dx - centre[:b]
            oy = fy - dy - centre[b:]
            u = ox * cos_w + oy * sin_w
            v = oy * cos_h - ox * sin_h
            out = out + brightness * (1 - u * u - v * v).clamp(min=0) ** 2 * (u <= 0).to(dtype)
    out = out.reshape(b, 1, res, res)
    if ss > 1:
        out = F.avg_pool2d(out, ss)
    return out


def white_lattice_noise(size: int, *, cells: int = 512, seed: int = 0, key="white", device=None,
                        dtype=torch.float32) -> torch.Tensor:
    """Uniform white noise on a fixed texture-space lattice of ``cells`` x ``cells`` values:
    shown as blocks above that size; below it, box-averaged and then mapped through its own ranks
    back to a uniform histogram. (1, 1, size, size) in [0, 1].

    Substance draws white noise per pixel at every output size, so its histogram is uniform on
    [0, 1] whatever the size. Plain box averages of k values keep the mean but shrink the spread
    by sqrt(k) and never reach 0 or 1, so a threshold downstream (levels, histogram scan: sparse
    dots, scratches, speckle) finds nothing at small sizes. The rank map is monotone, so the small
    render is still the box-downsampled large one, only re-toned to a uniform histogram."""
    g = _rng(seed, key, cells)
    lat = torch.rand(1, 1, cells, cells, generator=g, dtype=torch.float64)
    if size >= cells:
        lat = lat.to(device=device, dtype=dtype)
        return lat.repeat_interleave(size // cells, -1).repeat_interleave(size // cells, -2)
    avg = F.avg_pool2d(lat, cells // size).reshape(-1)
    ranks = torch.empty_like(avg)
    ranks[torch.argsort(avg, stable=True)] = torch.arange(avg.numel(), dtype=torch.float64)
    return ((ranks + 0.5) / avg.numel()).reshape(1, 1, size, size).to(device=device, dtype=dtype)


# ----------------------------------------------------------------------------------------------
# composition helpers
def noise_batch(*params) -> int:
    """The batch size B the (number or (k,) or (B, k)) parameters broadcast to."""
    b = 1
    for p in params:
        if isinstance(p, torch.Tensor) and p.dim() >= 2:
            b = max(b, p.shape[0])
    return b


def blend_scales(scale, render: Callable[[int, torch.Tensor], torch.Tensor], *, batch: int = 1,
                 device=None, dtype=torch.float32) -> torch.Tensor:
    """A continuous scale from integer-frequency renders.

    ``render(k, idx)`` returns the zero-mean unit-std noise at integer scale k for the batch rows
    ``idx`` (a LongTensor), shape (len(idx), 1, S, S). The scale s (number or (B, 1)) gives
    ``((1 - t) A + t B) / sqrt((1 - t)^2 + t^2)`` with A, B the renders at floor(s) and floor(s) + 1
    and t the fraction: continuous across integers (t -> 1 gives the next integer's render),
    differentiable in s, and the normalisation keeps the contrast of a single render.
    """
    s = param4d(scale).to(device=device, dtype=dtype).reshape(-1)
    s = torch.clamp(s, min=1.0)
    if s.shape[0] == 1 and batch > 1:
        s = s.expand(batch)
    nb = s.shape[0]
    k0 = torch.floor(s.detach() + 1e-4)          # snap within 1e-4 of an integer (float round-off)
    t = s - k0
    need_upper = s.requires_grad or bool((t.detach().abs() > 1e-4).any())
    wanted: dict[int, list[int]] = {}
    for b in range(nb):
        k = int(k0[b])
        wanted.setdefault(k, []).append(b)
        if need_upper:
            wanted.setdefault(k + 1, []).append(b)
    renders = {}
    for k, rows in wanted.items():
        idx = torch.tensor(rows, dtype=torch.long)
        img = render(k, idx)
        renders[k] = {b: img[i if img.shape[0] > 1 else 0] for i, b in enumerate(rows)}
    def gather(shift):
        if nb == 1:
            return renders[int(k0[0]) + shift][0][None]     # a view: no copy of the image
        return torch.stack([renders[int(k0[b]) + shift][b] for b in range(nb)])
    lo = gather(0)
    if not need_upper:
        return lo
    hi = gather(1)
    t = t.reshape(-1, 1, 1, 1)
    inv = torch.rsqrt((1 - t) ** 2 + t ** 2)
    return torch.addcmul(lo * ((1 - t) * inv), hi, t * inv)


def domain_warp(img: torch.Tensor, du: torch.Tensor, dv: torch.Tensor, amount) -> torch.Tensor:
    """Sample ``img`` at (u + amount du, v + amount dv), wrapping; amount in texture units, a number
    or (B, 1); differentiable in everything."""
    size = img.shape[-1]
    c = (torch.arange(size, device=img.device, dtype=img.dtype) + 0.5) / size
    v, u = torch.meshgrid(c, c, indexing="ij")
    a = param4d(amount, img)
    uu = u[None, None] + a * du
    vv = v[None, None] + a * dv
    b = max(img.shape[0], uu.shape[0])
    if img.shape[0] != b:
        img = img.expand(b, -1, -1, -1)
    return sample_wrap(img, uu.expand(b, -1, -1, -1), vv.expand(b, -1, -1, -1))


def squash(x: torch.Tensor, gain=1.0, offset=0.0) -> torch.Tensor:
    """Map a zero-mean signal to (0, 1) smoothly: 0.5 + 0.5 tanh(gain x + offset)."""
    if isinstance(gain, torch.Tensor) or isinstance(offset, torch.Tensor):
        y = torch.addcmul(torch.as_tensor(offset, dtype=x.dtype, device=x.device), x,
                          torch.as_tensor(gain, dtype=x.dtype, device=x.device))
    else:
        y = x * gain + offset if offset != 0 else x * gain
    return torch.tanh(y).mul(0.5).add_(0.5)


def select_rows(p, idx: torch.Tensor):
    """Rows ``idx`` of a batched (B, k) parameter; numbers and unbatched tensors pass through."""
    if isinstance(p, torch.Tensor) and p.dim() >= 2 and p.shape[0] > 1:
        return p[idx.to(p.device)]
    return p
