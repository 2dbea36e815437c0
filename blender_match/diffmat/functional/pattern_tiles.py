"""Tile-layout pattern generators: Tile Generator (grayscale and colour), Tile Sampler
(simplified), Brick Generator, Checker 1, Parquet 1, Weave Generator, Mesh 1 and Splatter
Circular. All are built on the shared primitives of ``pattern_shapes`` (``tile_field``, the shape
library, ``aa_coverage``, ``lattice_random``); see that module for the conventions.
"""
from __future__ import annotations

import math

import torch
import torch.nn.functional as F

from .common import param4d, pixel_grid, to_gray
from .pattern_shapes import (
    SHAPES,
    TAU,
    GridMask,
    aa_coverage,
    check_enum,
    check_int,
    lattice_random,
    ref_tensor,
    safe_sqrt,
    shape_profile,
    tile_field,
)

__all__ = ["tile_pattern", "tile_pattern_color", "tile_sampler_pattern", "brick_pattern", "brick_relief",
           "checker_pattern", "parquet_pattern", "weave_pattern", "plain_weave", "mesh_pattern", "circular_splatter"]

# Tile Generator "Pattern" list: 0 is the image input, then the shape library in Substance's order.
TILE_PATTERNS = ("image",) + SHAPES[:15]
# Tile Sampler's list goes one shape further, to Hemisphere (16): production files set it
TILE_SAMPLER_PATTERNS = ("image",) + SHAPES
# the most tiles a side a layout takes. Substance's sliders stop at 64, but a file may hold more,
# and production files do (400 and 500 a side: about a pixel a tile at 512 px)
MAX_TILES = 1024


def _image_profile(image):
    """A profile reading a grayscale ``image`` stretched over the shape's [-1, 1]² square."""
    img = to_gray(image)

    def profile(x, y, w, spec, ex=None, ey=None):
        x, y = torch.broadcast_tensors(x, y)
        b = max(x.shape[0], img.shape[0])
        grid = torch.stack([x[:, 0], y[:, 0]], dim=-1)
        grid = grid.expand(b, -1, -1, -1)
        src = img.to(dtype=x.dtype, device=x.device).expand(b, -1, -1, -1)
        return F.grid_sample(src, grid, mode="bilinear", padding_mode="zeros", align_corners=False)

    return profile


# shapes whose height never increases away from their centre along x or y (``tile_field(own_cell=)``)
MONOTONE_SHAPES = frozenset(("square", "disc", "paraboloid", "bell", "gaussian", "thorn", "pyramid", "brick",
                             "ridged_bell", "capsule", "cone", "hemisphere"))


def _pattern_profile(name: str, image):
    """The height profile of the pattern ``name`` (a ``TILE_SAMPLER_PATTERNS`` entry)."""
    if name == "image":
        if image is None:  # nothing connected: Substance draws nothing
            return lambda x, y, w, s, ex=None, ey=None: torch.zeros_like(x)
        return _image_profile(image)
    return lambda x, y, w, s, ex=None, ey=None: shape_profile(name, x, y, w, s)


# the arguments of the Tile Generator family that ``tile_field`` takes as they are
_TILE_FIELD_ARGS = ("scale", "size_xy", "interstice", "offset", "position_random", "scale_random", "rotation",
                    "rotation_random", "luminance_random", "mask_random", "pattern_specific", "softness",
                    "color_random", "global_offset", "seed", "device", "dtype")
# the Tile Generator's Blending Mode as files store it (index 1 is an empty entry of Substance's
# list, read as Add; the MATch reference implementation, config/generators/tile_generator.yml)
TILE_BLENDINGS = ("add", "add", "max", "add_sub")
# the (x, y) pairs that a Vertical Offset layout takes transposed (``_transposed_layout``)
_XY_ARGS = ("size_xy", "interstice", "position_random", "global_offset")


def _transposed_layout(nx: int, ny: int, profile, field: dict, grid_mask: GridMask):
    """The layout of a Vertical Offset Tile Generator drawn in the transposed image: its columns
    become rows, which ``tile_field`` offsets (the MATch reference offsets column k down by
    k × Offset cells instead of row k across). Every (x, y) pair swaps, the pattern is read with
    its axes swapped, a rotation turns the other way, the column and row masks trade places, and
    Luminance By Number counts along the rows (the final image's columns); the caller transposes
    the result back."""
    swapped = dict(field)
    for k in _XY_ARGS:
        if k in swapped:
            t = param4d(swapped[k])
            swapped[k] = t.flip(1) if t.shape[1] == 2 else t
    swapped["rotation"] = -param4d(field.get("rotation", 0.0))
    swapped["numbered_across"] = True

    def read_transposed(x, y, w, s, ex=None, ey=None):
        return profile(y, x, w, s, ey, ex)

    mask = GridMask(checker=grid_mask.checker, columns=grid_mask.rows, rows=grid_mask.columns,
                    invert=grid_mask.invert)
    return ny, nx, read_transposed, swapped, mask


def _tile_generator(where: str, image, args: dict, patterns: tuple[str, ...] = TILE_PATTERNS):
    """The layout of a Tile Generator family node: its grid and pattern (an index of ``patterns``)
    checked, then ``tile_field`` with the node's arguments ``args`` (its ``locals()``) that
    ``tile_field`` takes."""
    nx = check_int(args["x_amount"], f"{where}.x_amount", 1, MAX_TILES)
    ny = check_int(args["y_amount"], f"{where}.y_amount", 1, MAX_TILES)
    pattern = patterns[check_enum(args["pattern"], f"{where}.pattern", range(len(patterns)))]
    profile = _pattern_profile(pattern, image)
    field = {k: args[k] for k in _TILE_FIELD_ARGS if k in args}
    if "blending_mode" in args:
        field["blending"] = TILE_BLENDINGS[check_enum(args["blending_mode"], f"{where}.blending_mode",
                                                      range(len(TILE_BLENDINGS)))]
        field["opacity"] = args["global_opacity"]
        field["background"] = args.get("background_level", 0.0)
        field["offset_every_row"] = True
        field["luminance_by_number"] = bool(args["luminance_by_number"])
        field["offset_random"] = args["offset_random"]
        field["reverse_order"] = bool(args["reverse_rendering_order"])
        field["luminance_by_scale"] = bool(args["luminance_by_scale"])
        for seed_name in ("offset_random_seed", "scale_random_seed"):
            field[seed_name] = check_int(args[seed_name], f"{where}.{seed_name}", 0, 2 ** 31 - 1)
    grid_mask = GridMask(checker=bool(args.get("checker_mask")), columns=bool(args.get("horizontal_mask")),
                         rows=bool(args.get("vertical_mask")), invert=bool(args.get("invert_mask")))
    transposed = bool(args.get("vertical_offset"))
    if transposed:
        nx, ny, profile, field, grid_mask = _transposed_layout(nx, ny, profile, field, grid_mask)
    height, color = tile_field(args["size"], nx, ny, profile=profile, own_cell=pattern in MONOTONE_SHAPES,
                               grid_mask=grid_mask, **field)
    if transposed:
        height = height.transpose(-1, -2)
        color = color.transpose(-1, -2) if color is not None else None
    return height, color


def tile_pattern(pattern_input_1=None, *, x_amount: int = 10, y_amount: int = 10, pattern: int = 1,
                 pattern_specific=0.2, scale=1.0, size_xy=(1.0, 1.0), interstice=(0.0, 0.0), offset=0.0,
                 position_random=0.0, scale_random=0.0, rotation=0.0, rotation_random=0.0, luminance_random=0.0,
                 mask_random=0.0, softness=0.0, checker_mask: bool = False, horizontal_mask: bool = False,
                 vertical_mask: bool = False, invert_mask: bool = False, blending_mode: int = 0,
                 global_opacity=1.0, luminance_by_number: bool = False, offset_random=0.0,
                 vertical_offset: bool = False, global_offset=(0.0, 0.0), reverse_rendering_order: bool = False,
                 luminance_by_scale: bool = False, background_level=0.0, offset_random_seed: int = 0,
                 scale_random_seed: int = 0, size: int = 512, seed: int = 0, device=None,
                 dtype=torch.float32) -> torch.Tensor:
    """Tile Generator: an ``x_amount`` × ``y_amount`` grid of one pattern (``TILE_PATTERNS``;
    0 reads ``pattern_input_1``), row k shifted by k × ``offset`` cells ("offsets the entire
    pattern incrementally over every consecutive row", Substance's documentation), with per-tile
    random position, scale, rotation, luminance and masking (see ``tile_field``); the mask
    switches hide every other tile (checker), column (horizontal) or row (vertical), or with
    ``invert_mask`` show only what the masks hide (``GridMask``). Overlapping tiles combine by
    ``blending_mode`` (``TILE_BLENDINGS``: Add by default, as Substance's) over the
    ``background_level``, the tiles scaled by ``global_opacity``; ``luminance_by_number`` fades
    the tiles' luminance over their order, ``luminance_by_scale`` over their random scale;
    ``offset_random`` shifts each row at random (``offset_random_seed`` and ``scale_random_seed``: the
    older node's own seeds, see ``tile_field``); ``vertical_offset`` offsets columns instead of
    rows; ``global_offset`` moves the whole layout; ``reverse_rendering_order`` gives the tiles
    their random values in the reverse order (``tile_field``)."""
    out, _ = _tile_generator("tile_generator", pattern_input_1, locals())
    return out


def tile_pattern_color(pattern_input_1=None, *, x_amount: int = 10, y_amount: int = 10, pattern: int = 1,
                       pattern_specific=0.2, scale=1.0, size_xy=(1.0, 1.0), interstice=(0.0, 0.0), offset=0.0,
                       position_random=0.0, scale_random=0.0, rotation=0.0, rotation_random=0.0,
                       luminance_random=0.0, mask_random=0.0, softness=0.0, checker_mask: bool = False,
                       horizontal_mask: bool = False, vertical_mask: bool = False, invert_mask: bool = False,
                       blending_mode: int = 0, global_opacity=1.0, luminance_by_number: bool = False,
                       offset_random=0.0, vertical_offset: bool = False, global_offset=(0.0, 0.0),
                       reverse_rendering_order: bool = False, luminance_by_scale: bool = False, color_random=1.0,
                       pattern_color=(1.0, 1.0, 1.0, 1.0), background_color=(0.0, 0.0, 0.0, 1.0),
                       offset_random_seed: int = 0, scale_random_seed: int = 0, size: int = 512, seed: int = 0,
                       device=None, dtype=torch.float32) -> torch.Tensor:
    """Tile Generator Color: the tile layout of ``tile_pattern``; each tile takes
    ``pattern_color`` × a random colour (mixed in by ``color_random``) × its height, over
    ``background_color``; overlapping tiles combine as ``tile_pattern``'s (Add Sub as Add: the
    background colour is laid under the tiles afterwards). RGBA, opaque."""
    h, col = _tile_generator("tile_generator_color", pattern_input_1, locals())
    ref = ref_tensor(device, dtype)
    fg = param4d(pattern_color, ref)[:, :3] * col
    bg = param4d(background_color, ref)[:, :3]
    rgb = bg + (fg - bg) * h
    return torch.cat([rgb, torch.ones_like(h).expand(rgb.shape[0], -1, -1, -1)], dim=1).clamp(0.0, 1.0)


def tile_sampler_pattern(pattern_input=None, *, x_amount: int = 16, y_amount: int = 16, pattern: int = 1,
                         scale=0.8, size_xy=(1.0, 1.0), position_random=0.0, offset=0.0, rotation=0.0,
                         rotation_random=0.0, scale_random=0.0, luminance_random=0.0, mask_random=0.0,
                         size: int = 512, seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """Tile Sampler (simplified): the Tile Generator layout with the Tile Sampler's parameters
    (no map inputs, no vector/colour outputs)."""
    out, _ = _tile_generator("tile_sampler", pattern_input, locals(), TILE_SAMPLER_PATTERNS)
    return out


# Brick Generator's Height and Slope when they change nothing: (min, max, balance, variance) and
# (x, y, balance, variance)
FLAT_BRICKS = (1.0, 1.0, 0.0, 0.0)
NO_SLOPE = (0.0, 0.0, 0.0, 0.0)
# the seed offset of the bricks' own random values (heights and slopes), apart from the tiles'
BRICK_SEED = 104729


def brick_pattern(*, x_amount: int = 4, y_amount: int = 8, offset=0.5, interstice=(0.04, 0.08), bevel=0.1,
                  luminance_random=0.3, mask_random=0.0, height=FLAT_BRICKS, slope=NO_SLOPE, size: int = 512,
                  seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """Brick Generator: ``x_amount`` × ``y_amount`` bricks (cells of 1/x_amount by 1/y_amount, so
    4 × 8 gives 2:1 bricks), alternate rows offset by ``offset``, separated by ``interstice`` (gap
    as a fraction of the brick's width/height), bevelled over ``bevel`` × the brick height, with
    random luminance per brick; each brick then scaled by its ``height`` and ``slope``
    (``brick_relief``)."""
    nx = check_int(x_amount, "brick_generator.x_amount", 1, 256)
    ny = check_int(y_amount, "brick_generator.y_amount", 1, 256)
    ref = ref_tensor(device, dtype)
    bevel = param4d(bevel, ref)

    def brick(x, y, w, s, ex, ey):
        # distance to the brick's edge in texture units, bevel relative to the brick height
        d = torch.minimum((1.0 - x.abs()) * ex, (1.0 - y.abs()) * ey)
        ramp = (d / (bevel * 2.0 * ey).clamp_min(1e-6)).clamp(0.0, 1.0)
        return ramp * aa_coverage(torch.maximum(x.abs(), y.abs()) - 1.0, w)

    out, _ = tile_field(size, nx, ny, seed=seed, profile=brick, interstice=interstice, offset=offset,
                        luminance_random=luminance_random, mask_random=mask_random, device=device,
                        dtype=dtype)
    height, slope = param4d(height, ref), param4d(slope, ref)
    if bool((height != torch.tensor(FLAT_BRICKS, dtype=dtype, device=ref.device).view(1, 4, 1, 1)).any()) \
            or bool((slope != 0).any()):
        out = out * brick_relief(nx, ny, param4d(offset, ref), height, slope, size, seed)
    return out


def brick_relief(nx: int, ny: int, offset: torch.Tensor, height: torch.Tensor, slope: torch.Tensor, size: int,
                 seed: int) -> torch.Tensor:
    """The factor (B|1, 1, size, size) by which the Brick Generator's Height and Slope scale each
    brick of ``brick_pattern``'s layout (facts: the MATch reference implementation, whose
    parameters these are; the formulas here are ours). ``height`` (min, max, balance, variance):
    a brick stands at ``min`` or ``max``, the share at ``max`` (1 + balance) / 2, then lowered
    towards 0 by a random factor as far as |variance| says; heights below 0 read as 0. ``slope``
    (x, y, balance, variance): a ramp across the brick, 1 at its high end and 1 - |x| at its low
    end (rising rightwards for x > 0) or, down the brick, 1 - |y| (rising upwards for y > 0);
    balance 1 gives every brick the x ramp, -1 the y ramp, 0 a random mix of the two per brick;
    a share |variance| / 2 of the bricks have their ramps turned round."""
    rnd = lattice_random(seed + BRICK_SEED, 4, nx * ny, offset.device, offset.dtype)
    u, v = pixel_grid(size, offset.device, offset.dtype)
    row = torch.floor(v * ny)
    xs = u * nx - offset * torch.remainder(row, 2.0)
    col = torch.remainder(torch.floor(xs), float(nx))
    fx, fy = xs - torch.floor(xs), v * ny - row
    cell = (row * nx + col).long()
    pick, spread, mix, turn = (r[cell] for r in rnd)

    h_min, h_max, h_balance, h_variance = height.split(1, dim=1)
    level = torch.where(pick < (1.0 + h_balance) / 2.0, h_max, h_min).clamp_min(0.0)
    level = level * (1.0 - h_variance.abs() * (1.0 - spread))

    s_x, s_y, s_balance, s_variance = slope.split(1, dim=1)
    turned = turn < s_variance.abs() / 2.0
    along_x = torch.where(turned != (s_x < 0), 1.0 - fx, fx)
    along_y = torch.where(turned != (s_y < 0), fy, 1.0 - fy)
    ramp_x = 1.0 - (1.0 - along_x) * s_x.abs()
    ramp_y = 1.0 - (1.0 - along_y) * s_y.abs()
    weight = torch.lerp(s_balance.clamp(0.0, 1.0), (s_balance + 1.0).clamp(0.0, 1.0), 1.0 - mix)
    return level * torch.lerp(ramp_y, ramp_x, weight)


def _square_wave(t: torch.Tensor, pw: float) -> torch.Tensor:
    """1 on the first half of each period of ``t``, 0 on the second, edges anti-aliased (pw: one
    pixel in periods)."""
    f = torch.remainder(t, 1.0)
    return aa_coverage((f - 0.25).abs() - 0.25, pw)


def checker_pattern(*, tiling: int = 2, size: int = 512, device=None, dtype=torch.float32) -> torch.Tensor:
    """Checker 1: a checkerboard of 2·``tiling`` × 2·``tiling`` squares, white first (top left)."""
    tiling = check_int(tiling, "checker_1.tiling", 1, 256)
    u, v = pixel_grid(size, device, dtype)
    pw = tiling / size
    a = _square_wave(u * tiling, pw)
    b = _square_wave(v * tiling, pw)
    return a * b + (1.0 - a) * (1.0 - b)


def parquet_pattern(*, tiling: int = 4, planks: int = 3, gap=0.02, bevel=0.05, luminance_random=0.3,
                    size: int = 512, seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """Parquet 1: a basket-weave parquet, ``tiling`` × ``tiling`` square blocks of ``planks``
    planks each, horizontal and vertical blocks alternating like a checkerboard. ``gap`` (fraction
    of a block) separates planks, ``bevel`` (fraction of a plank's width) rounds their edges;
    luminance varies per plank."""
    tiling = check_int(tiling, "parquet_1.tiling", 1, 128)
    planks = check_int(planks, "parquet_1.planks", 1, 32)
    ref = ref_tensor(device, dtype)
    gap = param4d(gap, ref)
    bevel = param4d(bevel, ref)
    lum_r = param4d(luminance_random, ref)
    u, v = pixel_grid(size, device, dtype)
    X, Y = u * tiling, v * tiling
    bx, by = torch.floor(X), torch.floor(Y)
    fx, fy = X - bx, Y - by
    vertical = torch.remainder(bx + by, 2.0) == 1
    along = torch.where(vertical, fy, fx)
    across = torch.where(vertical, fx, fy) * planks
    k = torch.floor(across)
    a = across - k
    # distances to the plank's edges, in texture units
    d_along = torch.minimum(along, 1.0 - along) / tiling
    d_across = torch.minimum(a, 1.0 - a) / (tiling * planks)
    d = torch.minimum(d_along, d_across)
    half_gap = 0.5 * gap / tiling
    pix = 1.0 / size
    body = aa_coverage(half_gap - d, pix)
    ramp = ((d - half_gap) / (bevel / (tiling * planks)).clamp_min(1e-6)).clamp(0.0, 1.0)
    rnd = lattice_random(seed, 1, tiling * tiling * planks, device, dtype)[0]
    idx = ((by * tiling + bx) * planks + k).long()
    lum = 1.0 - lum_r * rnd[idx]
    return (body * torch.maximum(ramp, torch.zeros_like(ramp)) * lum).clamp(0.0, 1.0)


def _weave(size, cells, width, lum_random, seed, device, dtype):
    """Threads over and under: ``cells`` horizontal and ``cells`` vertical threads (cells even),
    each ``width`` (x, y: fraction of a cell) wide, rounded across, rising where on top and sinking
    where underneath, the crossing above alternating like a checkerboard."""
    ref = ref_tensor(device, dtype)
    t = param4d(width, ref)
    wx, wy = (t, t) if t.shape[1] == 1 else (t[:, 0:1], t[:, 1:2])
    lum_random = param4d(lum_random, ref)
    u, v = pixel_grid(size, device, dtype)
    X, Y = u * cells, v * cells
    col, row = torch.floor(X), torch.floor(Y)
    rnd = lattice_random(seed, 2, cells, device, dtype)
    pix = cells / size  # one pixel in cell units
    # horizontal thread of this row: across coordinate (Y - row - 0.5), height up where (col+row) even
    dy = (Y - row - 0.5).abs()
    hw_h = (0.5 * wy).clamp_min(1e-6)
    prof_h = safe_sqrt(1.0 - (dy / hw_h) ** 2) * aa_coverage(dy - hw_h, pix)
    elev_h = 0.5 + 0.5 * torch.cos(math.pi * (X - 0.5 + row))
    h = prof_h * (0.35 + 0.65 * elev_h) * (1.0 - lum_random * rnd[0][row.long()])
    dx = (X - col - 0.5).abs()
    hw_v = (0.5 * wx).clamp_min(1e-6)
    prof_v = safe_sqrt(1.0 - (dx / hw_v) ** 2) * aa_coverage(dx - hw_v, pix)
    elev_v = 0.5 - 0.5 * torch.cos(math.pi * (Y - 0.5 + col))
    vv = prof_v * (0.35 + 0.65 * elev_v) * (1.0 - lum_random * rnd[1][col.long()])
    return torch.maximum(h, vv).clamp(0.0, 1.0)


def weave_pattern(*, tiling: int = 4, width=(0.8, 0.8), luminance_random=0.2, size: int = 512, seed: int = 0,
                  device=None, dtype=torch.float32) -> torch.Tensor:
    """Weave Generator: a plain weave of 2·``tiling`` threads each way, thread ``width`` (x, y)
    as a fraction of the spacing, random luminance per thread."""
    tiling = check_int(tiling, "weave_generator.tiling", 1, 128)
    return _weave(size, 2 * tiling, width, luminance_random, seed, device, dtype)


def plain_weave(*, tiling: int = 4, size: int = 512, seed: int = 0, device=None,
                dtype=torch.float32) -> torch.Tensor:
    """Weave 1: "a simple weave pattern" (Substance's documentation), ``tiling`` repeats each way of
    the over-under unit of two threads; the Weave Generator's threads, without their random shade."""
    tiling = check_int(tiling, "weave_1.tiling", 1, 128)
    return _weave(size, 2 * tiling, (0.8, 0.8), 0.0, seed, device, dtype)


def mesh_pattern(*, tiling: int = 4, width=0.3, size: int = 512, seed: int = 0, device=None,
                 dtype=torch.float32) -> torch.Tensor:
    """Mesh 1: a wire mesh, 2·``tiling`` thin interlaced wires each way, ``width`` of the spacing."""
    tiling = check_int(tiling, "mesh_1.tiling", 1, 128)
    return _weave(size, 2 * tiling, width, 0.0, seed, device, dtype)


def circular_splatter(*, pattern: int = 2, pattern_amount: int = 8, radius=0.3, pattern_size=0.15,
                      pattern_specific=0.5, ring_rotation=0.0, pattern_rotation=0.0, scale_random=0.0,
                      luminance_random=0.0, size: int = 512, seed: int = 0, device=None,
                      dtype=torch.float32) -> torch.Tensor:
    """Splatter Circular: ``pattern_amount`` copies of a shape (Tile Generator's list, no image)
    evenly spaced on a circle of ``radius`` around the image centre, each ``pattern_size`` wide,
    turned to follow the circle (plus ``pattern_rotation``), the ring turned by ``ring_rotation``;
    per-copy random scale and luminance. Copies reaching past the border wrap around."""
    n = check_int(pattern_amount, "splatter_circular.pattern_amount", 1, 256)
    name = TILE_PATTERNS[check_enum(pattern, "splatter_circular.pattern", range(1, len(TILE_PATTERNS)))]
    ref = ref_tensor(device, dtype)
    radius = param4d(radius, ref)
    half = (0.5 * param4d(pattern_size, ref)).clamp_min(1e-6)
    spec = param4d(pattern_specific, ref)
    ring_rot = param4d(ring_rotation, ref) * TAU
    pat_rot = param4d(pattern_rotation, ref) * TAU
    scale_random = param4d(scale_random, ref)
    luminance_random = param4d(luminance_random, ref)
    rnd = lattice_random(seed, 2, n, device, dtype)
    u, v = pixel_grid(size, device, dtype)
    with torch.no_grad():
        reach = float((radius.abs() + half * math.sqrt(2.0)).max()) + 1.0 / size
    shifts = (0,) if reach <= 0.5 else (-1, 0, 1)
    sector = TAU / n
    out = None
    for sy in shifts:
        for sx in shifts:
            px = u - 0.5 + sx
            py = v - 0.5 + sy
            theta = torch.atan2(py, px) - ring_rot
            k0 = torch.round(theta / sector)
            for dk in (-1, 0, 1):
                k = k0 + dk
                phi = ring_rot + k * sector
                cx, cy = radius * torch.cos(phi), radius * torch.sin(phi)
                idx = torch.remainder(k, n).long()
                idx = idx.expand(max(idx.shape[0], phi.shape[0]), -1, -1, -1)
                s = (1.0 - scale_random * rnd[0][idx]) * half
                a = phi + pat_rot
                ca, sa = torch.cos(a), torch.sin(a)
                dx, dy = px - cx, py - cy
                lx = (ca * dx + sa * dy) / s
                ly = (-sa * dx + ca * dy) / s
                h = shape_profile(name, lx, ly, (1.0 / size) / s, spec)
                h = h * (1.0 - luminance_random * rnd[1][idx])
                out = h if out is None else torch.maximum(out, h)
    assert out is not None  # the loops above always run
    return out.clamp(0.0, 1.0)
