"""Known-value tests of the pattern generators (functional/pattern_tiles.py, pattern_shapes.py,
pattern_cells.py): layouts, symmetry, areas, ramps, seeds, normal colours."""
from __future__ import annotations

import math

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F
from blender_match.diffmat.functional.pattern_shapes import jitter_cells, tile_supersampling

S = 64


def _render(name, size=S, seed=0, **params):
    with torch.no_grad():
        return Node(name, params)(ctx=EvalContext(size=size, seed=seed))


# --- tile generator ------------------------------------------------------------------------------
def test_tile_generator_4x4_squares_are_16_equal_tiles():
    out = _render("tile_generator", x_amount=4, y_amount=4, pattern=1, scale=0.7)
    q = S // 4
    torch.testing.assert_close(out, torch.roll(out, q, dims=-1))
    torch.testing.assert_close(out, torch.roll(out, q, dims=-2))
    assert not torch.allclose(out, torch.roll(out, q // 2, dims=-1))  # not trivially uniform
    # each tile: a 0.7-wide square -> coverage 0.49
    assert abs(out.mean().item() - 0.49) < 0.02


def test_tile_generator_interstice_widens_the_gaps():
    narrow = _render("tile_generator", x_amount=4, y_amount=4, pattern=1, interstice=(0.1, 0.1))
    wide = _render("tile_generator", x_amount=4, y_amount=4, pattern=1, interstice=(0.4, 0.4))
    assert abs(narrow.mean().item() - 0.81) < 0.02
    assert abs(wide.mean().item() - 0.36) < 0.02
    x_only = _render("tile_generator", x_amount=4, y_amount=4, pattern=1, interstice=(0.5, 0.0))
    cols, rows = x_only[0, 0].mean(dim=0), x_only[0, 0].mean(dim=1)
    assert cols.min() < 0.01 and rows.min() > 0.4  # vertical gaps only


def test_tile_generator_offset_shifts_every_row_by_its_number():
    """Substance's Tile Generator "offsets the entire pattern incrementally over every consecutive
    row": row k by k × offset cells (at 0.5, every other row by half a cell, as bricks)."""
    kw = dict(x_amount=4, y_amount=4, pattern=1, interstice=(0.2, 0.2))
    base = _render("tile_generator", **kw)[0, 0]
    cell = S // 4
    for offset in (0.5, 0.25):
        off = _render("tile_generator", offset=offset, **kw)[0, 0]
        for row in range(4):
            band = slice(row * cell, (row + 1) * cell)
            shift = round(row * offset * cell) % S
            torch.testing.assert_close(off[band], torch.roll(base[band], shift, dims=-1))
    brick = _render("brick_generator", x_amount=4, y_amount=4, offset=0.25)[0, 0]   # Brick Generator:
    torch.testing.assert_close(brick[2 * cell:3 * cell], _render("brick_generator", x_amount=4, y_amount=4,
                                                                  offset=0.0)[0, 0][2 * cell:3 * cell])  # alternate


def test_tile_generator_random_row_offsets():
    """Offset Random shifts each row by its own random amount (the reference's: up to
    offset_random x (k + 1) / rows of the image for row k), seeded."""
    kw = dict(x_amount=4, y_amount=4, pattern=1, interstice=(0.2, 0.2))
    base = _render("tile_generator", **kw)[0, 0]
    cell = S // 4
    jittered = _render("tile_generator", offset_random=0.5, **kw)[0, 0]
    assert torch.equal(jittered, _render("tile_generator", offset_random=0.5, **kw)[0, 0])
    shifts = []
    for row in range(4):
        band = slice(row * cell, (row + 1) * cell)
        errors = torch.stack([(jittered[band] - torch.roll(base[band], d, dims=-1)).abs().mean() for d in range(cell)])
        assert errors.min() < 0.06, row   # each row is the plain row moved sideways (within a pixel)
        shifts.append(int(errors.argmin()))
    assert len(set(shifts)) > 1   # by different amounts


def test_tile_generator_older_seeds_draw_their_own_row_shifts_and_scales():
    """The older Tile Generator's Offset Random Seed and Scale Variation Seed: 0 keeps the layout's
    own random values; another seed changes only the random row shifts or the random scales."""
    kw = dict(x_amount=4, y_amount=4, pattern=1, interstice=(0.2, 0.2))
    shifted = _render("tile_generator", offset_random=0.5, **kw)
    assert torch.equal(shifted, _render("tile_generator", offset_random=0.5, offset_random_seed=0, **kw))
    assert not torch.equal(shifted, _render("tile_generator", offset_random=0.5, offset_random_seed=377, **kw))
    assert torch.equal(_render("tile_generator", **kw), _render("tile_generator", offset_random_seed=377, **kw))
    scaled = _render("tile_generator", scale_random=0.6, **kw)
    reseeded = _render("tile_generator", scale_random=0.6, scale_random_seed=5, **kw)
    assert not torch.equal(scaled, reseeded)
    assert abs(float(scaled.mean() - reseeded.mean())) < 0.15   # the same spread of scales, drawn anew
    assert torch.equal(_render("tile_generator", luminance_random=0.6, **kw),
                       _render("tile_generator", luminance_random=0.6, scale_random_seed=5, **kw))


def test_tile_generator_luminance_by_number_fades_the_tiles_in_order():
    """Luminance By Number: tile k of N (counted down each column, then across) at (k + 1) / N."""
    out = _render("tile_generator", x_amount=4, y_amount=4, pattern=1, scale=0.5, luminance_by_number=True)[0, 0]
    centres = out[S // 8::S // 4, S // 8::S // 4]   # [row, column]
    expected = (torch.arange(4)[None, :] * 4 + torch.arange(4)[:, None] + 1) / 16
    torch.testing.assert_close(centres, expected.float())


def test_tile_generator_reverse_rendering_order_reverses_the_random_values():
    """Reverse Rendering Order: the tiles take their random values (and their number) in the
    reverse order; a layout without randomness is unchanged."""
    kw = dict(x_amount=4, y_amount=4, pattern=1, scale=0.5)
    plain = _render("tile_generator", **kw)[0, 0]
    torch.testing.assert_close(_render("tile_generator", reverse_rendering_order=True, **kw)[0, 0], plain)
    fwd = _render("tile_generator", luminance_random=1.0, **kw)[0, 0][S // 8::S // 4, S // 8::S // 4]
    rev = _render("tile_generator", luminance_random=1.0, reverse_rendering_order=True, **kw)[0, 0]
    rev = rev[S // 8::S // 4, S // 8::S // 4]
    # cell (row, column) k = column x 4 + row takes tile 15 - k's values: the grid turned half round
    torch.testing.assert_close(rev, fwd.flip(0).flip(1))
    numbered = _render("tile_generator", luminance_by_number=True, reverse_rendering_order=True, **kw)[0, 0]
    expected = (16 - (torch.arange(4)[None, :] * 4 + torch.arange(4)[:, None])) / 16
    torch.testing.assert_close(numbered[S // 8::S // 4, S // 8::S // 4], expected.float())


def test_tile_generator_vertical_offset_shifts_columns_down():
    """Vertical Offset: column k moves down by k × offset cells (the MATch reference) where
    otherwise row k moves across; with no offset the layout is the same either way, whatever the
    pattern's asymmetry or rotation, Luminance By Number's order included."""
    kw = dict(x_amount=8, y_amount=4, pattern=9, rotation=0.1, size_xy=(0.9, 0.6), interstice=(0.1, 0.0),
              luminance_by_number=True)
    torch.testing.assert_close(_render("tile_generator", vertical_offset=True, **kw), _render("tile_generator", **kw))
    kw = dict(x_amount=4, y_amount=4, pattern=1, interstice=(0.2, 0.2))
    base = _render("tile_generator", **kw)[0, 0]
    off = _render("tile_generator", offset=0.25, vertical_offset=True, **kw)[0, 0]
    cell = S // 4
    for column in range(4):
        band = slice(column * cell, (column + 1) * cell)
        shift = round(column * 0.25 * cell)
        torch.testing.assert_close(off[:, band], torch.roll(base[:, band], shift, dims=-2))


def test_tile_generator_global_offset_moves_the_layout():
    kw = dict(x_amount=4, y_amount=2, pattern=8, offset=0.5)
    moved = _render("tile_generator", global_offset=(0.25, 0.125), **kw)
    torch.testing.assert_close(moved, torch.roll(_render("tile_generator", **kw), (S // 8, S // 4), dims=(-2, -1)))


def test_tile_generator_position_and_rotation_random_spread_as_the_reference():
    """Position Random: ± that many cells, per axis; Rotation Random: ± that many turns (the MATch
    reference's `(2r - 1) x amount`). A jitter along x only keeps every row on its line; a
    spread past one cell folds into ± 1 cell and still scatters the tiles."""
    kw = dict(x_amount=4, y_amount=4, pattern=2, scale=0.4)
    along_x = _render("tile_generator", position_random=(1.0, 0.0), **kw)[0, 0]
    plain = _render("tile_generator", **kw)[0, 0]
    assert torch.equal(along_x.amax(dim=1) > 0.5, plain.amax(dim=1) > 0.5)   # the same rows hold discs
    assert not torch.allclose(along_x, plain)
    with torch.no_grad():   # a production file's 10 (a translated graph widens the node's range)
        wide = F.tile_pattern(position_random=(10.0, 10.0), size=S, **kw)[0, 0]
    assert abs(wide.mean().item() - plain.mean().item()) < 0.03   # scattered, none lost
    r = torch.tensor([0.0, 0.25, 0.5, 1.0])
    torch.testing.assert_close(jitter_cells(torch.tensor(0.8), r), torch.tensor([-0.8, -0.4, 0.0, 0.8]))
    assert (jitter_cells(torch.tensor(10.0), torch.rand(1000)).abs() <= 1.0).all()
    # Brick bars turned by up to ± 1/8 turn: some tiles lean each way by more than 1/16 turn
    bars = dict(x_amount=4, y_amount=4, pattern=1, size_xy=(1.0, 0.15), scale=0.8, seed=3)
    half = _render("tile_generator", rotation_random=0.125, **bars)
    quarter = _render("tile_generator", rotation_random=0.0625, **bars)
    straight = _render("tile_generator", **bars)
    assert (half - straight).abs().mean() > (quarter - straight).abs().mean() > 0.0


def test_tile_generator_luminance_by_scale_dims_the_smaller_tiles():
    kw = dict(x_amount=4, y_amount=4, pattern=1, scale=0.8, scale_random=0.8)
    plain = _render("tile_generator", **kw)[0, 0][S // 8::S // 4, S // 8::S // 4]
    dimmed = _render("tile_generator", luminance_by_scale=True, **kw)[0, 0][S // 8::S // 4, S // 8::S // 4]
    assert torch.equal(plain, torch.ones_like(plain)) and dimmed.min() < 0.6 and dimmed.max() <= 1.0


def test_tile_generator_add_adds_each_tile_above_the_background():
    """Under Add, a tile adds its luminance less the background (at least 0); Max keeps the higher."""
    kw = dict(x_amount=4, y_amount=4, pattern=1, scale=0.5, luminance_random=1.0, background_level=0.4)
    add = _render("tile_generator", **kw)[0, 0]
    high = _render("tile_generator", blending_mode=2, **kw)[0, 0]
    torch.testing.assert_close(add, high)   # tiles apart: the same either way
    assert add.min() >= 0.4 - 1e-6 and add.max() > 0.9


@pytest.mark.parametrize("pattern", [2, 7, 8, 10])  # disc, pyramid, brick, waves
def test_tile_generator_small_tiles_are_the_large_render_box_filtered(pattern):
    # 64 tiles at 256 px are 4 px wide: sampled at pixel centres, a Brick's bevel was missed and
    # the whole image came out a constant 1.0; drawn supersampled it is the 1024-px render averaged
    kw = dict(x_amount=64, y_amount=64, pattern=pattern, pattern_specific=0.34)
    small = _render("tile_generator", size=256, **kw)
    large = torch.nn.functional.avg_pool2d(_render("tile_generator", size=1024, **kw), 4)
    assert small.std().item() > 0.05
    assert (small - large).abs().mean().item() < 0.03
    assert tile_supersampling(256, 64, 64) == 2 and tile_supersampling(512, 64, 64) == 1


def test_tile_generator_randomness_is_seeded_and_per_tile():
    kw = dict(x_amount=8, y_amount=8, luminance_random=1.0, pattern=1, scale=0.8)
    a, b, c = _render("tile_generator", seed=1, **kw), _render("tile_generator", seed=1, **kw), \
        _render("tile_generator", seed=2, **kw)
    assert torch.equal(a, b) and not torch.allclose(a, c)
    centres = a[0, 0, 4::8, 4::8]  # one sample per tile
    assert centres.std() > 0.1
    # luminance is constant inside a tile
    tile = a[0, 0, 8 + 2:8 + 6, 8 + 2:8 + 6]
    assert tile.max() - tile.min() < 1e-6


def test_tile_generator_mask_random_hides_tiles_and_is_differentiable():
    full = _render("tile_generator", x_amount=8, y_amount=8, pattern=1, scale=0.8)
    half = _render("tile_generator", x_amount=8, y_amount=8, pattern=1, scale=0.8, mask_random=0.5)
    none = _render("tile_generator", x_amount=8, y_amount=8, pattern=1, scale=0.8, mask_random=1.0)
    assert none.max() == 0
    assert 0.2 < half.mean().item() / full.mean().item() < 0.8
    m = torch.tensor([0.5], requires_grad=True)
    F.tile_pattern(x_amount=8, y_amount=8, pattern=1, mask_random=m, size=32).sum().backward()
    assert m.grad is not None and m.grad.item() < 0


def test_tile_generator_mask_switches_hide_every_other_tile_column_or_row():
    """Substance's Checker Mask hides every other tile, Horizontal Mask every other column,
    Vertical Mask every other row, and Invert Mask shows only what they hide."""
    def tiles(**switches):   # the 4 x 4 tiles' centre values
        out = _render("tile_generator", x_amount=4, y_amount=4, pattern=1, scale=0.5, **switches)[0, 0]
        return out[S // 8::S // 4, S // 8::S // 4]
    j, i = torch.meshgrid(torch.arange(4), torch.arange(4), indexing="ij")
    assert torch.equal(tiles(), torch.ones(4, 4))
    assert torch.equal(tiles(checker_mask=True), ((i + j) % 2 == 0).float())
    assert torch.equal(tiles(horizontal_mask=True), (i % 2 == 0).float())
    assert torch.equal(tiles(vertical_mask=True), (j % 2 == 0).float())
    assert torch.equal(tiles(checker_mask=True, invert_mask=True), ((i + j) % 2 == 1).float())
    assert torch.equal(tiles(invert_mask=True), torch.ones(4, 4))   # nothing masked, nothing to invert


def test_tile_generator_pattern_input_is_stamped_in_each_tile():
    img = torch.zeros(1, 1, 16, 16)
    img[..., :, :8] = 1.0  # left half white
    out = F.tile_pattern(img, x_amount=2, y_amount=2, pattern=0, size=S)
    tile = out[0, 0, :32, :32]
    assert tile[:, :14].mean() > 0.95 and tile[:, 18:].mean() < 0.05
    torch.testing.assert_close(out, torch.roll(out, 32, dims=-1))


def test_tile_generator_color_has_a_colour_per_tile():
    out = _render("tile_generator_color", x_amount=4, y_amount=4, pattern=1, scale=0.8)
    assert out.shape == (1, 4, S, S)
    centres = out[0, :3, 8::16, 8::16].reshape(3, -1)
    assert (centres.std(dim=1) > 0.05).all()
    assert torch.all(out[0, 3] == 1)
    assert out[0, :3, 0, 0].max() == 0  # background between tiles


def test_tile_generator_blending_modes_add_by_default_max_and_add_sub():
    """Substance's Tile Generator adds overlapping tiles by default; Max keeps the higher; Add Sub
    adds each tile's luminance less the background, so darker tiles darken (the MATch reference
    implementation's facts). Two squares 1.5 cells wide overlap by half a cell."""
    common = dict(x_amount=2, y_amount=2, pattern=1, scale=1.5, global_opacity=0.4)
    add = _render("tile_generator", **common)
    high = _render("tile_generator", blending_mode=2, **common)
    assert _render("tile_generator", blending_mode=1, **common).equal(add)   # the list's empty entry
    assert (high - 0.4).abs().max() < 1e-6   # every pixel under some tile; Max keeps one tile's 0.4
    levels = torch.tensor([0.4, 0.8, 1.0])   # one tile, two, and four (1.6 clamped)
    counts = [int(((add - v).abs() < 1e-4).sum()) for v in levels]
    assert all(c > 0 for c in counts) and sum(counts) > 0.95 * add.numel(), counts
    lum = dict(x_amount=4, y_amount=4, pattern=1, scale=0.6, luminance_random=1.0, background_level=0.5)
    over_grey = _render("tile_generator", **lum)
    signed = _render("tile_generator", blending_mode=3, **lum)
    assert over_grey.min() >= 0.5 - 1e-6 and signed.min() < 0.3 and signed.max() > 0.7
    assert (signed[0, 0, 0, 0] - 0.5).abs() < 1e-6   # between the tiles: the background


def test_tile_generator_global_opacity_scales_the_tiles():
    full = _render("tile_generator", x_amount=4, y_amount=4, pattern=1, scale=0.7)
    faint = _render("tile_generator", x_amount=4, y_amount=4, pattern=1, scale=0.7, global_opacity=0.25)
    torch.testing.assert_close(faint, 0.25 * full)


def test_tile_generator_batched_and_bad_values():
    out = F.tile_pattern(x_amount=4, y_amount=4, pattern=1, scale=torch.tensor([[0.5], [1.0]]), size=32)
    assert out.shape[0] == 2 and out[0].mean() < out[1].mean()
    with pytest.raises(DiffMatError):
        F.tile_pattern(pattern=99, size=32)
    with pytest.raises(DiffMatError):
        Node("tile_generator", {"x_amount": 0})


# --- shapes ---------------------------------------------------------------------------------------
def test_shape_disc_is_symmetric_and_its_area_matches_its_size():
    for scale in (0.4, 0.8):
        out = _render("shape", size=128, pattern=1, scale=scale)[0, 0]
        torch.testing.assert_close(out, out.flip(-1))
        torch.testing.assert_close(out, out.flip(-2))
        torch.testing.assert_close(out, out.transpose(0, 1))
        assert abs(out.mean().item() - math.pi * (scale / 2) ** 2) < 0.005


def test_shape_tiling_and_square():
    sq = _render("shape", pattern=0, scale=0.5)
    assert abs(sq.mean().item() - 0.25) < 0.01
    tiled = _render("shape", pattern=1, scale=0.5, tiling=4)
    torch.testing.assert_close(tiled, torch.roll(tiled, S // 4, dims=-1))


def test_shape_profiles_are_bounded_and_peak_in_the_centre():
    for pattern in range(16):
        out = _render("shape", size=32, pattern=pattern, scale=0.8)
        assert out.min() >= 0 and out.max() <= 1
        if pattern not in (8, 9, 10, 12):  # gradation, waves, half bell, crescent are off-centre
            assert out[0, 0, 16, 16] >= out.max() - 0.15, pattern
        assert out[0, 0, 0, 0] < 0.05, pattern


def test_shape_angle_rotates():
    a = _render("shape", pattern=8, scale=0.6)[0, 0]  # gradation: ramp along x
    b = _render("shape", pattern=8, scale=0.6, angle=0.25)[0, 0]
    torch.testing.assert_close(b, a.rot90(-1, dims=(0, 1)), atol=2e-3, rtol=0)


def test_polygon_sides_change_the_area():
    areas = [_render("polygon_1", size=128, sides=n, scale=0.8).mean().item() for n in (3, 4, 8)]
    r = 0.4
    for n, area in zip((3, 4, 8), areas):
        assert abs(area - 0.5 * n * r * r * math.sin(2 * math.pi / n)) < 0.01


# --- gradients, normal colour, stripes -----------------------------------------------------------------
def test_gradient_linear_1_is_a_ramp():
    """Substance's default rises upwards (white at the top, black at the bottom, the MATch reference
    implementation's facts); each quarter turn turns it clockwise: 1/4 rises to the right."""
    out = _render("gradient_linear_1", rotation=0.25)[0, 0]
    row = out[0]
    assert torch.all(out == row)  # constant down the columns
    assert torch.all(row[1:-1] - row[:-2] > 0)  # increasing (the last pixel is the anti-aliased drop)
    torch.testing.assert_close(row[1:-1] - row[:-2], torch.full((S - 2,), 1 / (S - 1)), atol=1e-5, rtol=0)
    assert row[0] < 0.02 and row[-2] > 0.97
    up = _render("gradient_linear_1")[0, 0]
    torch.testing.assert_close(up, out.T.flip(0))   # default: the same ramp rising from the bottom
    assert up[-1, 0] < 0.02 and up[1, 0] > 0.97
    down = _render("gradient_linear_1", rotation=0.5)[0, 0]
    torch.testing.assert_close(down, out.T)
    two = _render("gradient_linear_1", rotation=0.25, tiling=2)[0, 0, 0]
    torch.testing.assert_close(two[:S // 2], two[S // 2:])


def test_gradient_linear_2_and_3_are_symmetric_peaks():
    for name in ("gradient_linear_2", "gradient_linear_3"):
        row = _render(name)[0, 0, 0]
        torch.testing.assert_close(row, row.flip(0))
        assert row.max() > 0.98 and row.min() < 0.05
        assert row[S // 2 - 1] > 0.95


def test_normal_color_of_a_flat_direction():
    out = _render("normal_color", size=8)
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor([0.5, 0.5, 1.0, 1.0]))
    tilt = _render("normal_color", size=8, direction=0.0, slope_angle=0.125)[0, :, 0, 0]
    s = math.sin(math.pi / 4) * 0.5
    torch.testing.assert_close(tilt, torch.tensor([0.5 + s, 0.5, 0.5 + s, 1.0]))
    up = _render("normal_color", size=8, direction=0.25, slope_angle=0.125, invert_y=True)[0, :, 0, 0]
    assert up[1] < 0.5


def test_stripes_count_and_width():
    out = _render("stripes", number=4, width=0.25)[0, 0]
    assert abs(out.mean().item() - 0.25) < 0.01
    torch.testing.assert_close(out, torch.roll(out, S // 4, dims=-1))
    assert torch.all(out == out[0])


def test_checker():
    out = _render("checker_1", tiling=2)[0, 0]
    assert out[0, 0] == 1 and out[0, S // 4] == 0 and out[S // 4, S // 4] == 1
    assert abs(out.mean().item() - 0.5) < 1e-6


# --- cells ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["cells_1", "cells_2", "cells_3", "cells_4", "alveolus"])
def test_cells_differ_across_seeds_and_follow_scale(name):
    a, b = _render(name, seed=1), _render(name, seed=2)
    assert (a - b).abs().mean() > 0.02
    torch.testing.assert_close(a, _render(name, seed=1))
    # more cells -> more structure per pixel (larger mean neighbour difference)
    fine, coarse = _render(name, seed=1, scale=16), _render(name, seed=1, scale=4)

    def grad(x):
        return (x - torch.roll(x, 1, -1)).abs().mean()

    assert grad(fine) > grad(coarse)


def test_cells_2_is_zero_at_the_feature_points():
    out = _render("cells_2", size=128, scale=4)
    assert out.min() < 0.02 and out.max() > 0.5


def test_cells_4_is_flat_inside_cells():
    out = _render("cells_4", size=128, scale=4)[0, 0]
    flat = ((out - torch.roll(out, 1, -1)).abs() < 1e-6).float().mean()
    assert flat > 0.75


# --- other tile layouts ---------------------------------------------------------------------------
def test_brick_generator_rows_are_offset():
    out = _render("brick_generator", size=128, luminance_random=0.0)[0, 0]
    row_h = 128 // 8
    r0, r1 = out[row_h // 2], out[row_h + row_h // 2]
    torch.testing.assert_close(r1, torch.roll(r0, 128 // 8, dims=0))
    assert r0.min() < 0.05 and r0.max() > 0.95


def test_brick_generator_height_puts_each_brick_at_min_or_max():
    """Height (min, max, balance, variance): the bricks stand at min or max, the share at max
    (1 + balance) / 2; variance lowers each by a random factor; the default changes nothing."""
    kw = dict(size=128, luminance_random=0.0)
    flat = _render("brick_generator", **kw)[0, 0]
    assert torch.equal(flat, _render("brick_generator", height=(1.0, 1.0, 0.0, 0.0), **kw)[0, 0])
    centres = lambda img: img[8::16, 8::16]          # noqa: E731 (the 4 x 8 bricks' centres at offset 0)
    kw_grid = dict(kw, offset=0.0)
    base = centres(_render("brick_generator", **kw_grid)[0, 0])
    for balance, level in ((1.0, 0.7), (-1.0, 0.2)):
        lifted = centres(_render("brick_generator", height=(0.2, 0.7, balance, 0.0), **kw_grid)[0, 0])
        assert torch.allclose(lifted, level * base)
    mixed = centres(_render("brick_generator", height=(0.2, 0.7, 0.0, 0.0), **kw_grid)[0, 0]) / base
    levels = set(round(v, 4) for v in mixed.flatten().tolist())
    assert levels == {0.2, 0.7}
    spread = centres(_render("brick_generator", height=(1.0, 1.0, 0.0, 0.8), **kw_grid)[0, 0]) / base
    assert spread.min() > 0.2 - 1e-4 and spread.max() <= 1.0 + 1e-5 and spread.std() > 0.1


def test_brick_generator_slope_ramps_across_each_brick():
    """Slope (x, y, balance, variance): balance 1 ramps every brick along x (rising rightwards for
    x > 0, down to 1 - |x| at its low end), -1 along y (rising upwards); variance turns some round."""
    kw = dict(size=128, luminance_random=0.0, offset=0.0, interstice=(0.0, 0.0), bevel=0.0)
    flat = _render("brick_generator", **kw)[0, 0]
    along_x = _render("brick_generator", slope=(0.5, 0.0, 1.0, 0.0), **kw)[0, 0] / flat.clamp_min(1e-6)
    row = along_x[8, :32]                              # one brick of 32 px across
    assert row[0] < 0.55 and row[-1] > 0.98 and bool((row[1:] >= row[:-1] - 1e-6).all())
    along_y = _render("brick_generator", slope=(0.0, 0.5, -1.0, 0.0), **kw)[0, 0] / flat.clamp_min(1e-6)
    col = along_y[:16, 4]                              # one brick of 16 px down: rises upwards
    assert col[0] > 0.95 and col[-1] < 0.55
    turned = _render("brick_generator", slope=(0.5, 0.0, 1.0, 1.0), **kw)[0, 0] / flat.clamp_min(1e-6)
    rising = (turned[8::16, 31::32] > turned[8::16, 0::32]).float().mean()
    assert 0.2 < rising < 0.8                          # about half of them turned round


def test_parquet_weave_mesh_splatter_scratches_creased_basic_looks():
    parquet = _render("parquet_1", size=128)[0, 0]
    assert parquet.mean() > 0.4 and (parquet < 0.05).float().mean() > 0.02  # planks and gaps
    weave = _render("weave_generator", luminance_random=0.0)
    torch.testing.assert_close(weave, torch.roll(weave, S // 4, dims=-1))  # period 2 threads
    mesh = _render("mesh_1")
    assert (mesh < 0.01).float().mean() > 0.3  # holes between wires
    spl = _render("splatter_circular", size=128, pattern=2, pattern_amount=6)[0, 0]
    assert spl[64, 64] == 0 and spl.max() > 0.9
    rot = torch.rot90(spl, 2, dims=(0, 1))  # 6 copies: symmetric under a half turn about the centre
    assert (rot - spl).abs().max() < 1e-4
    s1, s2 = _render("scratches_generator", seed=1), _render("scratches_generator", seed=2)
    assert s1.max() > 0.5 and not torch.allclose(s1, s2) and s1.mean() < 0.3
    cr = _render("creased")
    assert cr.std() > 0.1



def test_weave_1_is_a_plain_weave_of_one_shade_repeated_tiling_times():
    weave = _render("weave_1", tiling=4)
    torch.testing.assert_close(weave, torch.roll(weave, S // 4, dims=-1))   # 4 repeats across
    torch.testing.assert_close(weave, torch.roll(weave, S // 4, dims=-2))
    assert not torch.allclose(weave, torch.roll(weave, S // 8, dims=-1))    # one thread is not a repeat
    shaded = _render("weave_generator", tiling=4)   # the Weave Generator shades each thread at random
    assert not torch.allclose(shaded, torch.roll(shaded, S // 4, dims=-1))


def test_scratches_generator_normal_is_the_scratches_as_grooves():
    params = dict(amount=4, angle=0.25, angle_random=0.0, width=0.1)
    grooves = Node("scratches_generator_normal", {**params, "normal_intensity": 1.0})
    normal, mask = grooves(ctx=EvalContext(size=S, seed=3))
    torch.testing.assert_close(mask, _render("scratches_generator", seed=3, **params))
    assert normal.shape == (1, 4, S, S) and mask.max() > 0.5
    flat = (mask == 0) & (torch.roll(mask, 1, -1) == 0) & (torch.roll(mask, -1, -1) == 0) \
        & (torch.roll(mask, 1, -2) == 0) & (torch.roll(mask, -1, -2) == 0)
    torch.testing.assert_close(normal[:, :3][flat.expand(-1, 3, -1, -1)].view(3, -1).T,
                               torch.tensor([0.5, 0.5, 1.0]).expand(int(flat.sum()), 3))
    assert (normal[:, :2] - 0.5).abs().max() > 0.1   # the grooves' walls tilt the normal
    gl, _ = Node("scratches_generator_normal", {**params, "normal_intensity": 1.0, "normal_format": 1})(
        ctx=EvalContext(size=S, seed=3))
    torch.testing.assert_close(gl[:, 1] - 0.5, -(normal[:, 1] - 0.5), atol=1e-5, rtol=0)   # green flipped


def test_scratches_bands_match_full_evaluation_and_wrap():
    """Scratches are rasterised per line band; the result equals the tile-layout evaluation of the
    same lines (tile_field, every cell in reach) and tiles."""
    from blender_match.diffmat.functional.pattern_shapes import aa_coverage, safe_sqrt, tile_field

    def line(x, y, w, s, ex, ey):
        ratio = torch.sqrt(ex / ey)
        return aa_coverage(y.abs() - safe_sqrt(1.0 - x * x), w * ratio) * aa_coverage(x.abs() - 1.0, w / ratio)

    size, n = 128, 4
    out = F.scratches(amount=n, size=size, seed=5)
    size_xy = torch.tensor([1.4, 0.02])
    ref = None
    for layer in range(2):
        h, _ = tile_field(size, n, n, seed=5 * 2 + layer + 1, profile=line, size_xy=size_xy, position_random=0.25,
                          scale_random=0.5, rotation=0.0, rotation_random=0.25, luminance_random=0.5,
                          offset=0.5 * layer)
        ref = h if ref is None else torch.maximum(ref, h)
    assert (out - ref).abs().max() < 1e-4
    assert out.max() > 0.5
