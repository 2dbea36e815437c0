"""Pattern generators built from shapes: Shape, Polygon 1, the linear gradients, Normal Color,
Stripes, Scratches Generator and Creased — and the shared primitives every pattern generator
(here, ``pattern_tiles`` and ``pattern_cells``) is built from:

- ``aa_coverage``: analytic anti-aliasing of an implicit edge (a C1 smoothstep one pixel wide), so
  edges are resolution-independent and differentiable;
- ``shape_profile``: the library of shapes of Substance's Shape / Tile Generator (square, disc,
  paraboloid, bell, gaussian, thorn, pyramid, brick, gradation, waves, half bell, ridged bell,
  crescent, capsule, cone, hemisphere), each a height in [0, 1] on local coordinates where the
  shape fills the square [-1, 1]²;
- ``lattice_random``: per-cell random values of a lattice, drawn from a seeded ``torch.Generator``;
- ``tile_field``: a grid of cells (row offset for bricks) holding one shape each, with per-cell
  random position, scale, rotation, luminance and masking; each pixel evaluates its own cell, or
  the 3×3 (5×5) neighbourhood when shapes may spill over their cell.

All coordinates are texture units (1 = image width); every lattice has an integer number of cells
per image, so every output tiles. Angles are in turns.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import torch
import torch.nn.functional as F

from ..errors import DiffMatError
from .common import lerp, param4d, pixel_grid
from .library_normal import height_to_normal_map

__all__ = ["shape_pattern", "polygon_pattern", "linear_gradient", "mirrored_linear_gradient",
           "smooth_linear_gradient", "normal_color", "stripes", "scratches", "scratches_normal", "creased"]

TAU = 2.0 * math.pi

# Shape names in the order of Substance's Shape node "Pattern" list (enum value = index).
SHAPES = ("square", "disc", "paraboloid", "bell", "gaussian", "thorn", "pyramid", "brick",
          "gradation", "waves", "half_bell", "ridged_bell", "crescent", "capsule", "cone",
          "hemisphere")


# ----------------------------------------------------------------------------------------------
# primitives
# ----------------------------------------------------------------------------------------------
def ref_tensor(device=None, dtype=torch.float32) -> torch.Tensor:
    """An empty tensor carrying ``device`` and ``dtype`` (for ``param4d``)."""
    return torch.empty(0, device=device, dtype=dtype)


def smoothstep01(t: torch.Tensor) -> torch.Tensor:
    t = t.clamp(0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def aa_coverage(f: torch.Tensor, width) -> torch.Tensor:
    """Coverage of the region ``f < 0`` where ``f`` is a distance-like implicit function and
    ``width`` one pixel in the same units: a linear ramp from 1 (inside) to 0 over one pixel, 0.5 on
    the edge — the exact box-filtered coverage of a straight edge, so areas do not depend on the
    resolution; differentiable in the edge's position."""
    return (0.5 - f / width).clamp(0.0, 1.0)


def safe_sqrt(x: torch.Tensor) -> torch.Tensor:
    """sqrt with a finite gradient at 0 (0 for x <= 0)."""
    return torch.sqrt(x.clamp_min(1e-12)) * (x > 0)


def safe_hypot(x: torch.Tensor, y: torch.Tensor) -> torch.Tensor:
    return torch.sqrt(x * x + y * y + 1e-12)


def lattice_random(seed: int, channels: int, cells: int, device=None, dtype=torch.float32) -> torch.Tensor:
    """(channels, cells) uniform values in [0, 1) from ``torch.Generator().manual_seed(seed)``."""
    g = torch.Generator().manual_seed(int(seed) % (2 ** 63))
    return torch.rand(channels, cells, generator=g).to(device=device, dtype=dtype)


def check_int(value, name: str, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or int(value) != value or not lo <= value <= hi:
        raise DiffMatError(f"{name}: expected an integer in [{lo}, {hi}], got {value!r}")
    return int(value)


def check_enum(value, name: str, choices) -> int:
    integral = not isinstance(value, bool) and isinstance(value, (int, float)) and int(value) == value
    if not integral or int(value) not in choices:
        raise DiffMatError(f"{name}: unknown value {value!r}; expected one of {list(choices)}")
    return int(value)


# ----------------------------------------------------------------------------------------------
# the shape library
# ----------------------------------------------------------------------------------------------
def _bell(r):
    return 0.5 + 0.5 * torch.cos(math.pi * r.clamp(max=1.0))


_BOX_SHAPES = ("square", "pyramid", "brick", "gradation", "waves")


def shape_profile(name: str, x: torch.Tensor, y: torch.Tensor, w, spec) -> torch.Tensor:
    """Height in [0, 1] of shape ``name`` at local coordinates (x, y) (the shape fills [-1, 1]²,
    y downwards). ``w``: one pixel in local units (anti-aliasing); ``spec``: Substance's "pattern
    specific" control in [0, 1] (bevel, frequency, offset… depending on the shape)."""
    if name in _BOX_SHAPES:
        return _box_profile(name, x, y, w, spec)
    if name == "capsule":
        rad = 0.25 + 0.5 * spec
        px = (x.abs() - (1.0 - rad)).clamp_min(0.0)
        d = safe_hypot(px, y) / rad
        return safe_sqrt(1.0 - d * d) * aa_coverage((d - 1.0) * rad, w)
    return _round_profile(name, x, y, w, spec)


def _box_profile(name: str, x: torch.Tensor, y: torch.Tensor, w, spec) -> torch.Tensor:
    """The shapes built on the square's distance max(|x|, |y|) (``_BOX_SHAPES``)."""
    m = torch.maximum(x.abs(), y.abs())
    if name == "square":
        return aa_coverage(m - 1.0, w)
    if name == "pyramid":
        return (1.0 - m).clamp_min(0.0)
    if name == "brick":
        bevel = 0.02 + 0.5 * spec
        return ((1.0 - m) / bevel).clamp(0.0, 1.0)
    box = aa_coverage(m - 1.0, w)
    if name == "gradation":
        return box * ((x + 1.0) * 0.5).clamp(0.0, 1.0)
    k = 1.0 + 4.0 * spec
    return box * (0.5 + 0.5 * torch.cos(math.pi * k * x))


def _round_profile(name: str, x: torch.Tensor, y: torch.Tensor, w, spec) -> torch.Tensor:
    """The shapes built on the distance to the centre r = hypot(x, y)."""
    r = safe_hypot(x, y)
    if name == "disc":
        return aa_coverage(r - 1.0, w)
    if name == "paraboloid":
        return (1.0 - r * r).clamp_min(0.0)
    if name == "bell":
        return _bell(r)
    if name == "gaussian":
        e = math.exp(-4.5)
        return ((torch.exp(-4.5 * (r * r).clamp(max=1.0)) - e) / (1.0 - e)).clamp_min(0.0)
    if name == "thorn":
        return (1.0 - r).clamp_min(0.0) ** (1.5 + 2.5 * spec)
    if name == "half_bell":
        return _bell(r) * aa_coverage(y, w)
    if name == "ridged_bell":
        return 1.0 - torch.sin(0.5 * math.pi * r.clamp(max=1.0))
    if name == "crescent":
        shift = 0.2 + 0.6 * spec
        inner = aa_coverage(safe_hypot(x - shift, y) - 0.9, w)
        return aa_coverage(r - 1.0, w) * (1.0 - inner)
    if name == "cone":
        return (1.0 - r).clamp_min(0.0)
    if name == "hemisphere":
        return safe_sqrt(1.0 - r * r)
    raise DiffMatError(f"pattern: unknown shape {name!r}")


def polygon_profile(sides: int, gradient, curve) -> Callable:
    """A profile function for a regular polygon (circumradius 1, one vertex up): flat inside with
    its edge anti-aliased; ``gradient`` in [0, 1] blends towards a pyramid-like falloff from the
    centre, ``curve`` bends that falloff (0 linear … 1 rounded)."""
    sector = TAU / sides
    apothem = math.cos(math.pi / sides)

    def profile(x, y, w, spec, ex=None, ey=None):
        a = torch.atan2(x, -y)
        a = torch.remainder(a, sector) - 0.5 * sector
        r = safe_hypot(x, y)
        d = r * torch.cos(a)  # distance along the sector's apothem direction
        flat = aa_coverage(d - apothem, w)
        t = (1.0 - d / apothem).clamp(0.0, 1.0)
        shaped = lerp(t, 1.0 - (1.0 - t) ** 2, curve)
        return flat * lerp(torch.ones_like(t), shaped, gradient)

    return profile


# ----------------------------------------------------------------------------------------------
# the tiled-cell layout
# ----------------------------------------------------------------------------------------------
RND_LUM, RND_MASK, RND_SCALE, RND_PX, RND_PY, RND_ROT, RND_SPEC, RND_R, RND_G, RND_B = range(10)
N_RND = 10


_AXIS_CACHE: dict = {}


def _pixel_axis(size: int, device, dtype) -> torch.Tensor:
    """Pixel-centre coordinates (size,) in [0, 1), cached per (size, device, dtype)."""
    key = (size, str(device), dtype)
    hit = _AXIS_CACHE.get(key)
    if hit is None:
        hit = ((torch.arange(size, dtype=torch.float64) + 0.5) / size).to(device=device, dtype=dtype)
        if len(_AXIS_CACHE) > 64:
            _AXIS_CACHE.clear()
        _AXIS_CACHE[key] = hit
    return hit


def _split2(value, ref):
    t = param4d(value, ref)
    if t.shape[1] == 1:
        return t, t
    return t[:, 0:1], t[:, 1:2]


def jitter_cells(spread: torch.Tensor, r: torch.Tensor) -> torch.Tensor:
    """A tile's position jitter in cells: ``spread`` × (2r - 1), uniform over ± ``spread`` cells
    as the MATch reference draws it, folded into ± 1 cell beyond that (one cell each way already
    lets every tile land anywhere in its own or a neighbour's cell; a Substance file's Position
    Random of 10 would otherwise need a window of 21 × 21 cells at every pixel)."""
    t = spread * (2.0 * r - 1.0)
    return torch.where(t.abs() <= 1.0, t, torch.remainder(t + 1.0, 2.0) - 1.0)


def _active(t: torch.Tensor) -> bool:
    """Whether a per-cell random control matters: non-zero, or trainable."""
    return t.requires_grad or bool((t != 0).any())


def _tile_reach(nx, ny, hx, hy, rotation, rotation_random, position_random, softness):
    """How many cells (per axis) around a pixel's own may hold a shape reaching it: (rotated,
    window x, window y), the windows per batch element (B|1, 1, 1, 1). The shape's reach is
    detached: it only chooses how many candidate cells to evaluate."""
    with torch.no_grad():
        rotated = bool((torch.remainder(rotation * 4.0, 1.0) != 0).any() or (rotation_random != 0).any())
        if rotated:
            rad = torch.sqrt(hx * hx + hy * hy)
            ext_x, ext_y = rad * nx, rad * ny
        else:
            rot_q = torch.remainder(torch.round(rotation * 4.0), 2.0)  # quarter turns swap axes
            ext_x = torch.where(rot_q == 1, hy, hx) * nx
            ext_y = torch.where(rot_q == 1, hx, hy) * ny
        jit_x, jit_y = (j.abs().clamp_max(1.0) for j in _split2(position_random, hx))   # ``jitter_cells``
        grow = 1.0 + 0.5 * softness.abs()
        # (the half-pixel anti-aliasing spill of a neighbour is ignored)
        rx, ry = ext_x * grow + jit_x, ext_y * grow + jit_y
        # cells whose centre lies within reach: m per axis, starting at floor(x + 1/2 - m/2); a
        # batch uses the largest window and masks each element to its own (same result as alone)
        mxb = torch.ceil(2.0 * rx - 1e-6).clamp(1, min(5, nx))
        myb = torch.ceil(2.0 * ry - 1e-6).clamp(1, min(5, ny))
    return rotated, mxb, myb


@dataclass(frozen=True)
class GridMask:
    """The Tile Generator's mask switches: ``checker`` hides every other tile, ``columns`` every
    other column (Substance's Horizontal Mask), ``rows`` every other row (Vertical Mask), each
    the odd ones; ``invert`` swaps what the masks, random mask included, hide and show."""

    checker: bool = False
    columns: bool = False
    rows: bool = False
    invert: bool = False

    @property
    def active(self) -> bool:
        return self.checker or self.columns or self.rows or self.invert

    def shown(self, nx: int, ny: int, device, dtype) -> torch.Tensor:
        """1 where the switches leave a cell, 0 where they hide it: (1, ny * nx), row-major."""
        j = torch.arange(ny, device=device).view(ny, 1)
        i = torch.arange(nx, device=device).view(1, nx)
        hidden = torch.zeros(ny, nx, dtype=torch.bool, device=device)
        if self.checker:
            hidden = hidden | ((i + j) % 2 == 1)
        if self.columns:
            hidden = hidden | (i % 2 == 1)
        if self.rows:
            hidden = hidden | (j % 2 == 1)
        return (~hidden).to(dtype).reshape(1, -1)

    def apply(self, shown: torch.Tensor) -> torch.Tensor:
        return 1.0 - shown if self.invert else shown


def _cell_values(nx, ny, rnd, pix, hx, hy, softness, position_random, scale_random, rotation, rotation_random,
                 luminance_random, mask_random, spec, spec_random, cr, *, use_pos, use_scale, use_rot, use_lum,
                 use_mask, use_spec, grid_mask: GridMask, lum_offset=None, lum_floor: bool = False,
                 by_number: bool = False, across: bool = False, reverse: bool = False,
                 by_scale: bool = False) -> dict[str, torch.Tensor]:
    """The per-cell quantities that vary between cells, each (B|1, ny * nx). ``lum_offset``: a
    level subtracted from every cell's luminance (the background under added tiles), the result at
    least 0 with ``lum_floor``; ``by_number``: luminance × (k + 1) / N for the k-th tile counted
    down each column, then across (``across``: along each row, then down); ``reverse``: the cells
    take the random values, and the numbers, in the reverse order (by number: × (N - k) / N);
    ``by_scale``: luminance × the cell's random scale factor."""
    # per-cell derived quantities (B|1, ny * nx): every transcendental is evaluated once a cell, and
    # a pixel gathers only what varies between cells
    if reverse:
        rnd = rnd.flip(-1)

    def pc(t):
        return t.reshape(-1, 1)

    cellv = {}
    ex_c, ey_c = hx, hy
    sc: float | torch.Tensor = 1.0
    if use_scale:
        sc = 1.0 - pc(scale_random) * rnd[RND_SCALE]
        ex_c, ey_c = (pc(hx) * sc).clamp_min(1e-6), (pc(hy) * sc).clamp_min(1e-6)
        cellv["ex"], cellv["ey"] = ex_c, ey_c
        cellv["w"] = pix / torch.sqrt(ex_c * ey_c) + pc(softness)
    if use_pos:
        spread_x, spread_y = _split2(position_random, rnd)
        cellv["jx"] = jitter_cells(pc(spread_x), rnd[RND_PX]) / nx
        cellv["jy"] = jitter_cells(pc(spread_y), rnd[RND_PY]) / ny
    if use_rot:
        ang = TAU * (pc(rotation) + pc(rotation_random) * (2.0 * rnd[RND_ROT] - 1.0))
        ca, sa = torch.cos(ang), torch.sin(ang)
        iex = 1.0 / (ex_c if use_scale else pc(hx.clamp_min(1e-6)))
        iey = 1.0 / (ey_c if use_scale else pc(hy.clamp_min(1e-6)))
        cellv["a11"], cellv["a12"], cellv["a21"], cellv["a22"] = ca * iex, sa * iex, -sa * iey, ca * iey
    by_scale = by_scale and use_scale
    if use_lum or use_mask or grid_mask.active or lum_offset is not None or by_number or by_scale:
        fac: float | torch.Tensor = 1.0
        if use_lum:
            fac = 1.0 - pc(luminance_random) * rnd[RND_LUM]
        if by_scale:
            fac = fac * torch.as_tensor(sc).clamp(0.0, 1.0)
        if by_number:   # tile k of the N (row-major cells): k = column x ny + row, or row x nx + column across
            column = torch.arange(nx, device=rnd.device).view(1, nx)
            row = torch.arange(ny, device=rnd.device).view(ny, 1)
            k = row * nx + column if across else column * ny + row
            rank = nx * ny - k if reverse else k + 1
            fac = fac * (rank.reshape(1, -1).to(rnd.dtype) / (nx * ny))
        if lum_offset is not None:
            shifted = fac - pc(lum_offset) + rnd.new_zeros(1, nx * ny)   # one value a cell, whatever came before
            fac = shifted.clamp_min(0.0) if lum_floor else shifted
        if use_mask or grid_mask.active:
            # soft mask: fully visible at mask_random = 0, fully hidden at mask_random = 1
            shown = smoothstep01((rnd[RND_MASK] - pc(mask_random) * 1.05) / 0.05 + 1.0)
            fac = fac * grid_mask.apply(shown * grid_mask.shown(nx, ny, rnd.device, rnd.dtype))
        cellv["fac"] = fac
    if use_spec:
        cellv["sp"] = (pc(spec) + pc(spec_random) * (rnd[RND_SPEC] - 0.5)).clamp(0.0, 1.0)
    if cr is not None:
        for name, k in (("r", RND_R), ("g", RND_G), ("b", RND_B)):
            cellv[name] = 1.0 - pc(cr) * (1.0 - rnd[k])
    return cellv


def _gather_rows(values: torch.Tensor, rows: torch.Tensor) -> torch.Tensor:
    """``values`` (B|1, ny, nx) per cell, at the row indices ``rows`` (B|1, H, 1): (B|1, H, nx)."""
    b = max(values.shape[0], rows.shape[0])
    return torch.gather(values.expand(b, -1, -1), 1, rows.expand(b, -1, values.shape[2]))


@dataclass(frozen=True)
class _CellShape:
    """What evaluating a candidate cell's shape needs besides the cell's own values: the profile,
    which per-cell quantities vary, and the fixed ones (half extents, pixel width, spec)."""

    profile: Callable
    size: int
    nx: int
    use_pos: bool
    use_scale: bool
    use_rot: bool
    use_spec: bool
    hx: torch.Tensor
    hy: torch.Tensor
    w: torch.Tensor
    spec: torch.Tensor

    def height(self, rows: dict, c: torch.Tensor, fx: torch.Tensor, fy: torch.Tensor):
        """The shape of cell column ``c`` (``rows``: the row's cell values) at offsets (fx, fy)
        from the cell centres; returns (height, the cell values gathered per pixel)."""
        bsz, size = c.shape[0], self.size
        vals = {}
        if rows:
            cidx = torch.remainder(c, self.nx).long().view(bsz, size, -1).expand(-1, -1, size)
            for k, t in rows.items():
                bk = max(bsz, t.shape[0])
                vals[k] = torch.gather(t.expand(bk, -1, -1), 2, cidx.expand(bk, -1, -1)).unsqueeze(1)
        dx, dy = fx, fy
        if self.use_pos:
            dx = dx - vals["jx"]
            dy = dy - vals["jy"]
        ex, ey = (vals["ex"], vals["ey"]) if self.use_scale else (self.hx, self.hy)
        if self.use_rot:
            lx = vals["a11"] * dx + vals["a12"] * dy
            ly = vals["a21"] * dx + vals["a22"] * dy
        else:
            lx, ly = dx / ex, dy / ey
        w = vals["w"] if self.use_scale else self.w
        sp = vals["sp"] if self.use_spec else self.spec
        h = self.profile(lx, ly, w, sp, ex, ey)
        if "fac" in vals:
            h = h * vals["fac"]
        return h, vals


def _combine(acc, h, vals, add: bool):
    """Overlapping shapes combine by maximum, or by sum with ``add``; the colour (``vals`` given)
    follows the highest shape either way. ``acc``: None or (combined, highest, colour)."""
    col = torch.cat([vals["r"], vals["g"], vals["b"]], dim=1) if vals is not None else None
    if acc is None:
        if col is not None and col.shape[0] < h.shape[0]:
            col = col.expand(h.shape[0], -1, -1, -1)
        return h, h, col
    combined, highest, color = acc
    if col is not None:
        color = torch.where(h > highest, col, color)
    highest = torch.maximum(highest, h)
    return (combined + h if add else highest), highest, color


# the fewest pixels across a cell at which ``tile_field`` samples its shapes directly; smaller cells
# are drawn supersampled and box-filtered down (``tile_supersampling``)
MIN_CELL_PIXELS = 8
# the seed offset of the per-row random shifts (``tile_field(offset_random=)``), apart from the tiles'
ROW_SEED = 7919
# the seed offset of the random scales that an own Scale Random Seed draws (``tile_field``)
SCALE_SEED = 6007
# how overlapping shapes combine (``tile_field(blending=)``): the Tile Generator's Blending Mode
BLENDINGS = ("max", "add", "add_sub")
# supersampling never draws more than this many pixels across (memory: at 2048 px every cell of up
# to 256 per row already has 8 pixels)
MAX_SUPERSAMPLED_SIZE = 2048


def tile_supersampling(size: int, nx: int, ny: int) -> int:
    """The factor (a power of 2, 1 when none) by which ``tile_field`` draws a ``size``-px grid of
    ``nx`` × ``ny`` cells before box-filtering it down. A shape's profile is point-sampled at
    pixel centres; with a few pixels a cell, those centres miss its bevels and gaps (a Brick of
    64 cells at 256 px sampled as a constant 1.0), so the small render would not be the
    box-downsampled large one, as every generator's must be."""
    k = 1
    while size * k < MIN_CELL_PIXELS * max(nx, ny) and size * k * 2 <= MAX_SUPERSAMPLED_SIZE:
        k *= 2
    return k


def _cell_randoms(seed: int, cells: int, scale_random_seed: int, device, dtype) -> torch.Tensor:
    """The (N_RND, cells) random values of ``tile_field``'s cells; an own ``scale_random_seed``
    (not 0) redraws the scales' row from a stream of its own."""
    rnd = lattice_random(seed, N_RND, cells, device, dtype)
    if scale_random_seed:
        rnd[RND_SCALE] = lattice_random(seed + SCALE_SEED + int(scale_random_seed), 1, cells, device, dtype)[0]
    return rnd


def _row_randoms(seed: int, rows: int, offset_random_seed: int, device, dtype) -> torch.Tensor:
    """The (rows,) random values of ``tile_field``'s row shifts, from their own stream."""
    return lattice_random(seed + ROW_SEED + int(offset_random_seed), 1, rows, device, dtype)[0]


def tile_field(size: int, nx: int, ny: int, *, seed: int, profile: Callable, scale=1.0, size_xy=(1.0, 1.0),
               interstice=(0.0, 0.0), offset=0.0, position_random=0.0, scale_random=0.0, rotation=0.0,
               rotation_random=0.0, luminance_random=0.0, mask_random=0.0, pattern_specific=0.5,
               pattern_specific_random=0.0, softness=0.0, color_random=None, grid_mask: GridMask = GridMask(),
               own_cell: bool = False, blending: str = "max", background=0.0, opacity=1.0,
               offset_every_row: bool = False, luminance_by_number: bool = False, numbered_across: bool = False,
               offset_random=0.0, global_offset=(0.0, 0.0), reverse_order: bool = False,
               luminance_by_scale: bool = False, offset_random_seed: int = 0, scale_random_seed: int = 0,
               device=None, dtype=torch.float32):
    """A grid of ``nx`` × ``ny`` cells, one shape per cell; every alternate row is shifted right by
    ``offset`` cells. The shape fills its cell at scale 1 less the ``interstice`` gap (fraction of
    the cell), times ``size_xy`` (non-uniform size). Per cell, from ``lattice_random(seed)``:
    position jitter up to ± ``position_random`` cells (one value, or one for x and one for y;
    ``jitter_cells``), scale × (1 - ``scale_random`` r), rotation ``rotation`` ± ``rotation_random``
    turns (both spreads as the MATch reference draws them), luminance × (1 - ``luminance_random``
    r), and the cell is hidden when r < ``mask_random`` (a soft threshold, so mask_random is
    differentiable), and ``grid_mask`` hides every other tile, column or row (or, inverted, shows
    only those). ``reverse_order``: the cells take their random values in the reverse order (the
    reference's Reverse Rendering Order reverses the tiles' positions against every other per-tile
    value; overlapping tiles are summed or maximised, so the drawing order itself changes nothing).
    ``global_offset`` (x, y; fractions of the image) moves the whole layout.

    ``blending`` (the Tile Generator's Blending Mode): "max" keeps the highest shape over the
    ``background`` level; "add" adds to it each shape's luminance less the background (at least 0);
    "add_sub" adds each shape's luminance less the background, so darker tiles darken. ``opacity``
    scales what the shapes add (Global Opacity). The result is clamped to [0, 1].
    ``offset_every_row``: row k is shifted by k × ``offset`` cells (k in [0, ny), the Tile
    Generator's Offset), instead of every other row by ``offset``; ``offset_random`` adds to row k a
    random shift of up to ``offset_random`` × (k + 1) / ny of the image. ``luminance_by_number``:
    tile k of the N, counted down each column and then across (``numbered_across``: along each
    row, then down), has its luminance scaled by (k + 1) / N. ``luminance_by_scale``: each tile's
    luminance scaled by its random scale factor. ``offset_random_seed`` / ``scale_random_seed`` (the
    older Tile Generator's own seeds of its random row shifts and tile scales): a non-zero value
    draws those values from a stream of their own (0: the layout's), so that two nodes of one seed
    can differ there.

    ``softness`` (local units, 1 = the half size) widens hard edges beyond the one-pixel
    anti-aliasing. ``profile(x, y, w, spec, ex, ey)`` gives the shape's height at local coordinates
    (the shape fills [-1, 1]²), ``w`` one pixel (plus softness) in local units, ``ex``/``ey`` the
    half extents in texture units. Overlapping shapes combine as ``blending`` says. Returns ``(height, color)``:
    height (B, 1, H, W) and, when ``color_random`` is given, the winning cell's random colour
    (B, 3, H, W) mixed towards white by 1 - color_random, else None.

    ``own_cell``: the caller's profile never increases away from the shape's centre along x or y
    (square, disc, bell…); then, when every cell has the same geometry (no position, scale,
    rotation, mask or pattern-specific randomness, quarter-turn rotation), a neighbour's shape is
    never higher than the pixel's own shape, and only the own cell is evaluated (the neighbours'
    soft edges spilling over the border differ from the own one's by their luminance only). Shapes
    that are added must also stay within their cells, without softness.

    Cells of fewer than ``MIN_CELL_PIXELS`` pixels are drawn at a multiple of ``size`` and
    box-filtered down (``tile_supersampling``).
    """
    k = tile_supersampling(size, nx, ny)
    size = size * k
    ref = ref_tensor(device, dtype)
    ucoord = _pixel_axis(size, device, dtype)
    if blending not in BLENDINGS:
        raise DiffMatError(f"tile blending {blending!r}: expected one of {', '.join(BLENDINGS)}")
    rnd = _cell_randoms(seed, nx * ny, scale_random_seed, device, dtype)
    background = param4d(background, ref)
    lum_offset = background if blending != "max" else None
    scale = param4d(scale, ref)
    sx, sy = _split2(size_xy, ref)
    ix, iy = _split2(interstice, ref)
    offset = param4d(offset, ref)
    position_random = param4d(position_random, ref)
    scale_random = param4d(scale_random, ref)
    rotation = param4d(rotation, ref)
    rotation_random = param4d(rotation_random, ref)
    luminance_random = param4d(luminance_random, ref)
    mask_random = param4d(mask_random, ref)
    spec = param4d(pattern_specific, ref)
    spec_random = param4d(pattern_specific_random, ref)
    softness = param4d(softness, ref)
    cr = param4d(color_random, ref) if color_random is not None else None
    # half extents of the shape in texture units
    hx = (0.5 / nx) * (1.0 - ix).clamp_min(0.0) * scale * sx
    hy = (0.5 / ny) * (1.0 - iy).clamp_min(0.0) * scale * sy

    rotated, mxb, myb = _tile_reach(nx, ny, hx, hy, rotation, rotation_random, position_random, softness)
    mx, my = int(mxb.max()), int(myb.max())
    per_element = bool((mxb != mx).any() or (myb != my).any())
    use_pos, use_scale = _active(position_random), _active(scale_random)
    use_rot = _active(rotation) or _active(rotation_random)
    use_lum, use_mask, use_spec = _active(luminance_random), _active(mask_random), _active(spec_random)
    if grid_mask.invert and not (use_mask or grid_mask.checker or grid_mask.columns or grid_mask.rows):
        grid_mask = GridMask()  # nothing masked: nothing to invert
    if blending != "max":
        # shapes that are added must not reach into a neighbour's cell (but for its edge pixel)
        with torch.no_grad():
            own_cell = own_cell and not _active(softness) and bool((hx * nx <= 0.5 + 1e-6).all()) \
                and bool((hy * ny <= 0.5 + 1e-6).all())
    if own_cell and not (rotated or use_pos or use_scale or use_mask or grid_mask.active or use_spec
                         or _active(rotation_random)):
        mx, my, per_element = 1, 1, False

    # separable coordinates: rows depend on v only, so row quantities are (.., H, 1)
    gx, gy = _split2(global_offset, ref)   # (B|1, 1, 1, 1)
    X = (ucoord.view(1, 1, 1, size) - gx) * nx   # (B|1, 1, 1, W)
    Y = (ucoord.view(1, 1, size, 1) - gy) * ny   # (B|1, 1, H, 1)
    offset_random = param4d(offset_random, ref)
    row_random = _row_randoms(seed, ny, offset_random_seed, device, dtype) if _active(offset_random) else None
    row0 = torch.floor(Y + 0.5 - 0.5 * my)
    pix = 1.0 / size
    cellv = _cell_values(nx, ny, rnd, pix, hx, hy, softness, position_random, scale_random, rotation,
                         rotation_random, luminance_random, mask_random, spec, spec_random, cr,
                         use_pos=use_pos, use_scale=use_scale, use_rot=use_rot, use_lum=use_lum,
                         use_mask=use_mask, use_spec=use_spec, grid_mask=grid_mask, lum_offset=lum_offset,
                         lum_floor=blending == "add", by_number=luminance_by_number, across=numbered_across,
                         reverse=reverse_order,
                         by_scale=luminance_by_scale)
    cellv = {k: v.reshape(v.shape[0], ny, nx) for k, v in cellv.items()}
    hx_e, hy_e = hx.clamp_min(1e-6), hy.clamp_min(1e-6)
    shape = _CellShape(profile, size, nx, use_pos, use_scale, use_rot, use_spec, hx_e, hy_e,
                       pix / torch.sqrt(hx_e * hy_e) + softness, spec)
    acc = None
    for dj in range(my):
        r = row0 + dj
        row = torch.remainder(r, float(ny))   # the row's index in the tile, (B|1, 1, H, 1)
        if offset_every_row:   # whole cells of shift move no shape: only which tile's random values sit where
            shift = torch.remainder(offset * row, 1.0)
        else:
            shift = offset * torch.remainder(r, 2.0)
        if row_random is not None:
            shift = shift + offset_random * row_random[row.long()] * (row + 1.0) / ny * nx
        xs = X - shift
        c0 = torch.floor(xs + 0.5 - 0.5 * mx)
        fy = (Y - r - 0.5) / ny
        ridx = torch.remainder(r, ny).long().view(r.shape[0], size, 1)   # (B|1, H, 1): each element's rows
        rows = {k: _gather_rows(v, ridx) for k, v in cellv.items()}  # (B|1, H, nx)
        if per_element:
            r_lo = torch.floor(Y + 0.5 - 0.5 * myb)
            keep_r = (r >= r_lo) & (r < r_lo + myb)
            c_lo = torch.floor(xs + 0.5 - 0.5 * mxb)
        for di in range(mx):
            c = c0 + di
            fx = (xs - c - 0.5) / nx  # (B|1, 1, H, W)
            h, vals = shape.height(rows, c, fx, fy)
            if per_element:
                h = h * (keep_r & (c >= c_lo) & (c < c_lo + mxb))
            if h.shape[-2:] != (size, size):
                h = h.expand(-1, -1, size, size)
            acc = _combine(acc, h, vals if cr is not None else None, blending != "max")
    assert acc is not None  # the windows mx, my are at least 1
    shapes, _, color = acc
    if blending == "max":
        shapes = torch.maximum(shapes, background) - background
    best = (background + param4d(opacity, ref) * shapes).clamp(0.0, 1.0)
    if k > 1:
        pooled = F.avg_pool2d(best, k)
        if color is not None:
            # averaged weighted by the height, so that colour × height (what a caller draws) is
            # exactly the box filter of the supersampled one, whatever the colour under h = 0
            color = F.avg_pool2d(color * best, k) / pooled.clamp_min(1e-6)
        best = pooled
    return best, color


# ----------------------------------------------------------------------------------------------
# Shape and Polygon 1
# ----------------------------------------------------------------------------------------------
def shape_pattern(*, pattern: int = 0, tiling: int = 1, pattern_specific=0.5, scale=1.0,
                  size_xy=(1.0, 1.0), angle=0.0, rotation_45: bool = False, size: int = 512, seed: int = 0,
                  device=None, dtype=torch.float32) -> torch.Tensor:
    """Substance's Shape: ``tiling`` × ``tiling`` copies of one shape (``pattern`` indexes
    ``SHAPES``), each filling its tile at ``scale`` 1, stretched by ``size_xy``, rotated by
    ``angle`` turns (+1/8 with ``rotation_45``). Shapes that outgrow their tile overlap the
    neighbours' (maximum)."""
    name = SHAPES[check_enum(pattern, "shape.pattern", range(len(SHAPES)))]
    tiling = check_int(tiling, "shape.tiling", 1, 64)
    rot = param4d(angle, ref_tensor(device, dtype)) + (0.125 if rotation_45 else 0.0)
    out, _ = tile_field(size, tiling, tiling, seed=seed,
                        profile=lambda x, y, w, s, ex, ey: shape_profile(name, x, y, w, s),
                        scale=scale, size_xy=size_xy, rotation=rot, pattern_specific=pattern_specific,
                        device=device, dtype=dtype)
    return out


def polygon_pattern(*, sides: int = 3, tiling: int = 1, scale=0.8, rotation=0.0, gradient=0.0, curve=0.0,
                    size: int = 512, seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """Substance's Polygon 1: a regular polygon with ``sides`` sides, circumradius ``scale``/2 of
    its tile, rotated by ``rotation`` turns; ``gradient`` fades it from the centre to its edge,
    ``curve`` rounds that fade."""
    sides = check_int(sides, "polygon_1.sides", 3, 64)
    tiling = check_int(tiling, "polygon_1.tiling", 1, 64)
    ref = ref_tensor(device, dtype)
    prof = polygon_profile(sides, param4d(gradient, ref), param4d(curve, ref))
    out, _ = tile_field(size, tiling, tiling, seed=seed, profile=prof, scale=scale, rotation=rotation,
                        device=device, dtype=dtype)
    return out


# ----------------------------------------------------------------------------------------------
# gradients
# ----------------------------------------------------------------------------------------------
def _axis_coordinate(size, rotation, device, dtype):
    """Pixel-centre coordinate along the direction ``rotation`` snapped to quarter turns (a ramp
    along another direction cannot tile): u at 0, v at 1/4, 1-u at 1/2, 1-v at 3/4. (B,1,H,W)."""
    u, v = pixel_grid(size, device, dtype)
    q = torch.remainder(torch.round(param4d(rotation, ref_tensor(device, dtype)) * 4.0), 4.0)
    return torch.where(q == 0, u, torch.where(q == 1, v, torch.where(q == 2, 1.0 - u, 1.0 - v)))


def _ramp(t: torch.Tensor, pw: float) -> torch.Tensor:
    """A periodic 0→1 ramp of period 1 in ``t`` whose drop is anti-aliased over one pixel ``pw``
    (the last pixel of each period reads 0.5), so the image tiles like every hard edge."""
    f = torch.remainder(t, 1.0)
    rise = f / (1.0 - pw)
    fall = (1.0 - f) / pw
    return torch.where(f < 1.0 - pw, rise, fall).clamp(0.0, 1.0)


def linear_gradient(*, tiling: int = 1, rotation=0.0, size: int = 512, device=None,
                    dtype=torch.float32) -> torch.Tensor:
    """Gradient Linear 1: a black-to-white ramp repeated ``tiling`` times, rising upwards at
    rotation 0 (white at the top, black at the bottom, as Substance's) and turned clockwise by
    ``rotation`` (quarter turns: 1/4 rises to the right)."""
    tiling = check_int(tiling, "gradient_linear_1.tiling", 1, 256)
    t = _axis_coordinate(size, rotation - 0.25, device, dtype) * tiling
    return _ramp(t, tiling / size)


def mirrored_linear_gradient(*, tiling: int = 1, rotation=0.0, size: int = 512, device=None,
                             dtype=torch.float32) -> torch.Tensor:
    """Gradient Linear 2: a symmetric black-white-black ramp (white in the middle of each period)."""
    tiling = check_int(tiling, "gradient_linear_2.tiling", 1, 256)
    t = _axis_coordinate(size, rotation, device, dtype) * tiling
    return 1.0 - (2.0 * torch.remainder(t, 1.0) - 1.0).abs()


def smooth_linear_gradient(*, tiling: int = 1, rotation=0.0, position=0.5, size: int = 512, device=None,
                           dtype=torch.float32) -> torch.Tensor:
    """Gradient Linear 3: a smooth (cosine) black-white-black ramp whose white peak sits at
    ``position`` of each period."""
    tiling = check_int(tiling, "gradient_linear_3.tiling", 1, 256)
    t = _axis_coordinate(size, rotation, device, dtype) * tiling
    pos = param4d(position, ref_tensor(device, dtype))
    return 0.5 + 0.5 * torch.cos(TAU * (t - pos))


# ----------------------------------------------------------------------------------------------
# Normal Color
# ----------------------------------------------------------------------------------------------
def normal_color(*, direction=0.0, slope_angle=0.0, invert_y: bool = False, size: int = 512, device=None,
                 dtype=torch.float32) -> torch.Tensor:
    """Normal Color: a flat normal map tilted by ``slope_angle`` (turns from the vertical) towards
    ``direction`` (turns, 0 = +x); RGBA with rgb = n/2 + 1/2; ``invert_y`` flips green (DirectX)."""
    ref = ref_tensor(device, dtype)
    d = param4d(direction, ref) * TAU
    s = param4d(slope_angle, ref) * TAU
    nx = torch.sin(s) * torch.cos(d)
    ny = torch.sin(s) * torch.sin(d)
    if invert_y:
        ny = -ny
    nz = torch.cos(s)
    rgb = torch.cat([nx, ny, nz], dim=1) * 0.5 + 0.5
    rgba = torch.cat([rgb, torch.ones_like(nx)], dim=1)
    return rgba.expand(-1, -1, size, size).clamp(0.0, 1.0)


# ----------------------------------------------------------------------------------------------
# Stripes
# ----------------------------------------------------------------------------------------------
def stripes(*, number: int = 10, width=0.5, softness=0.0, shift: int = 0, size: int = 512, device=None,
            dtype=torch.float32) -> torch.Tensor:
    """Stripes: ``number`` white stripes per image along x (vertical bands), each ``width`` of its
    period wide, edges softened over ``softness`` of the half period; ``shift`` (integer, so it
    tiles) slants them by shifting the stripe pattern ``shift`` periods over the image height."""
    number = check_int(number, "stripes.number", 1, 512)
    shift = check_int(shift, "stripes.shift", -64, 64)
    ref = ref_tensor(device, dtype)
    u, v = pixel_grid(size, device, dtype)
    t = u * number + v * shift
    d = (torch.remainder(t, 1.0) - 0.5).abs()  # distance from the stripe centre, in periods
    half = 0.5 * param4d(width, ref)
    soft = param4d(softness, ref) * 0.5
    pw = number / size
    return aa_coverage((d - half) / (soft + pw) * pw, pw)


# ----------------------------------------------------------------------------------------------
# Scratches
# ----------------------------------------------------------------------------------------------
def scratches(*, amount: int = 6, length=1.4, width=0.02, angle=0.0, angle_random=0.5,
              length_random=0.5, luminance_random=0.5, mask_random=0.0, size: int = 512, seed: int = 0,
              device=None, dtype=torch.float32) -> torch.Tensor:
    """Scratches Generator (simplified): an ``amount`` × ``amount`` lattice of cells, each holding
    one thin line (a capsule) of ``length`` cell lengths (× 1 - length_random r) and ``width`` of
    a cell, oriented ``angle`` ± ``angle_random``/2 turns, luminance × 1 - luminance_random r; two
    staggered lattices so lines cross cell borders. Lines taper towards their ends.

    The lines are thin, so each is rasterised over its own band of pixels only (the pixels whose
    box can meet it: one column, or row, of a few pixels per pixel of its length) and the bands are
    combined by a maximum scattered into the image, wrapping around (the image tiles); a pixel's
    value is the same formula as a full-image evaluation, so the result does not depend on how the
    bands are cut."""
    amount = check_int(amount, "scratches_generator.amount", 1, 256)
    n = amount
    ref = ref_tensor(device, dtype)

    def pc(v):
        return param4d(v, ref).reshape(-1, 1)

    length, width, angle, angle_random = pc(length), pc(width), pc(angle), pc(angle_random)
    length_random, luminance_random, mask_random = pc(length_random), pc(luminance_random), pc(mask_random)
    pix = 1.0 / size
    # the lines of both layers: centres, half extents, direction, luminance (B|1, L)
    cxs, cys, rnds = [], [], []
    r_idx = torch.arange(n, device=device, dtype=dtype).repeat_interleave(n)   # row of each cell
    c_idx = torch.arange(n, device=device, dtype=dtype).repeat(n)
    for layer in range(2):
        rnd = lattice_random(seed * 2 + layer + 1, N_RND, n * n, device, dtype)
        shift = 0.5 * layer * torch.remainder(r_idx, 2.0)
        # position_random 0.5: jitter up to a quarter cell each way
        cxs.append((c_idx + 0.5 + shift) / n + 0.5 * (rnd[RND_PX] - 0.5) / n)
        cys.append((r_idx + 0.5) / n + 0.5 * (rnd[RND_PY] - 0.5) / n)
        rnds.append(rnd)
    rnd = torch.cat(rnds, dim=1)                                          # (N_RND, L)
    cx, cy = torch.cat(cxs)[None], torch.cat(cys)[None]                   # (1, L)
    s = 1.0 - length_random * rnd[RND_SCALE]
    ex = (0.5 / n * length * s).clamp_min(1e-6)                           # (B|1, L)
    ey = (0.5 / n * width * s).clamp_min(1e-6)
    ang = TAU * (angle + angle_random * (rnd[RND_ROT] - 0.5))
    ca, sa = torch.cos(ang), torch.sin(ang)
    lum = (1.0 - luminance_random * rnd[RND_LUM]) * smoothstep01((rnd[RND_MASK] - mask_random * 1.05) / 0.05 + 1.0)
    w = pix / torch.sqrt(ex * ey)
    ratio = torch.sqrt(ex / ey)
    b = max(t.shape[0] for t in (ex, ey, ca, lum))
    cx, cy, ex, ey, ca, sa, lum, w, ratio = (t.expand(b, -1) for t in (cx, cy, ex, ey, ca, sa, lum, w, ratio))
    with torch.no_grad():
        # band of each line: along its major axis every pixel of its extent, across it the pixels
        # within half a width (+ half a pixel of anti-aliasing) of the centre line
        lh, wh = ex + 0.5 * pix, ey + 0.5 * pix
        xmajor = ca.abs() >= sa.abs()
        cmaj = torch.where(xmajor, ca, sa).abs()
        major_half = lh * torch.where(xmajor, ca, sa).abs() + wh * torch.where(xmajor, sa, ca).abs()
        k_max = int(torch.ceil(2.0 * major_half.max() * size)) + 2
        r_max = int(torch.ceil(2.0 * (wh / cmaj).max() * size)) + 2
        cmaj_c = torch.where(xmajor, cx, cy)                                # centre on the major axis
        cmin_c = torch.where(xmajor, cy, cx)
        slope = torch.where(xmajor, sa / ca, ca / sa)                       # minor per major
        k0 = torch.floor((cmaj_c - major_half) * size)                      # first pixel (major)
        kk = k0[..., None] + torch.arange(k_max, device=device, dtype=dtype)          # (B, L, K)
        centre_minor = cmin_c[..., None] + ((kk + 0.5) * pix - cmaj_c[..., None]) * slope[..., None]
        j0 = torch.floor(centre_minor * size - 0.5 * r_max + 0.5)
        jj = j0[..., None] + torch.arange(r_max, device=device, dtype=dtype)          # (B, L, K, R)
        kk = kk[..., None].expand_as(jj)
        xm = xmajor[..., None, None]
        pxi = torch.where(xm, kk, jj)
        pyi = torch.where(xm, jj, kk)
        flat = (torch.remainder(pyi, size) * size + torch.remainder(pxi, size)).long().reshape(b, -1)
    e = (slice(None), slice(None), None, None)
    dx = (pxi + 0.5) * pix - cx[e]
    dy = (pyi + 0.5) * pix - cy[e]
    lx = (ca[e] * dx + sa[e] * dy) / ex[e]
    ly = (ca[e] * dy - sa[e] * dx) / ey[e]
    taper = safe_sqrt(1.0 - lx * lx)
    h = aa_coverage(ly.abs() - taper, w[e] * ratio[e]) * aa_coverage(lx.abs() - 1.0, w[e] / ratio[e]) * lum[e]
    out = torch.zeros(b, size * size, device=device, dtype=dtype)
    out = out.scatter_reduce(1, flat, h.reshape(b, -1), reduce="amax", include_self=True)
    return out.view(b, 1, size, size)


# ----------------------------------------------------------------------------------------------
# Creased
# ----------------------------------------------------------------------------------------------

# our choice (no public figure): at Normal Intensity 1 a groove one 256-px pixel wide tilts its
# walls by about 60 degrees, a clearly cut scratch; 0.5 (a production anodised metal's) about 45
SCRATCH_NORMAL_GAIN = 4.0


def scratches_normal(*, amount: int = 6, length=1.4, width=0.02, angle=0.0, angle_random=0.5,
                     length_random=0.5, luminance_random=0.5, mask_random=0.0, normal_intensity=0.5,
                     normal_format: int = 0, size: int = 512, seed: int = 0, device=None,
                     dtype=torch.float32) -> tuple[torch.Tensor, torch.Tensor]:
    """Scratches Generator (Normal): the scratches of ``scratches`` as grooves, returned as
    (normal map, mask). Substance's documentation: the same scratches, with a normal map "based on
    the depth of these scratches"; here the depth is the mask itself, its slopes scaled by
    ``normal_intensity`` × ``SCRATCH_NORMAL_GAIN`` (DirectX or OpenGL green, ``normal_format``)."""
    mask = scratches(amount=amount, length=length, width=width, angle=angle, angle_random=angle_random,
                     length_random=length_random, luminance_random=luminance_random, mask_random=mask_random,
                     size=size, seed=seed, device=device, dtype=dtype)
    gain = param4d(normal_intensity, ref_tensor(device, dtype)) * SCRATCH_NORMAL_GAIN
    return height_to_normal_map(1.0 - mask, gain, normal_format), mask

def creased(*, scale: int = 4, disorder=0.0, folds: int = 12, size: int = 512, seed: int = 0, device=None,
            dtype=torch.float32) -> torch.Tensor:
    """Creased: crumpled-paper creases, a sum of ``folds`` triangle waves (sharp ridges) along random
    integer directions (so it tiles) of about ``scale`` creases per image, with random phases that
    ``disorder`` (turns of phase) shifts smoothly; normalised to [0, 1]."""
    scale = check_int(scale, "creased.scale", 1, 256)
    folds = check_int(folds, "creased.folds", 1, 64)
    ref = ref_tensor(device, dtype)
    g = torch.Generator().manual_seed(int(seed) % (2 ** 63))
    dirs = torch.randint(-scale, scale + 1, (folds, 2), generator=g)
    dirs[(dirs == 0).all(dim=1)] = torch.tensor([scale, 1])
    phase = torch.rand(folds, generator=g)
    amp = 0.5 + torch.rand(folds, generator=g)
    speed = torch.rand(folds, generator=g) * 2.0 - 1.0
    u, v = pixel_grid(size, device, dtype)
    dis = param4d(disorder, ref)
    acc: float | torch.Tensor = 0.0
    for k in range(folds):
        t = u * float(dirs[k, 0]) + v * float(dirs[k, 1]) + float(phase[k]) + dis * float(speed[k])
        tri = (2.0 * torch.remainder(t, 1.0) - 1.0).abs()  # triangle wave in [0, 1], sharp ridges
        acc = acc + float(amp[k]) * tri
    total = float(amp.sum())
    out = acc / total
    assert isinstance(out, torch.Tensor)  # folds >= 1
    # spread the (roughly Gaussian) sum around its mean 0.5 to use the whole range
    return (0.5 + (out - 0.5) * 2.5).clamp(0.0, 1.0)
