"""Known-value tests of the Distance node (functional/distance.py)."""
from __future__ import annotations

import math

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, F, Node
from blender_match.diffmat.functional.distance import nearest_mask_pixel


def dots(n, *points):
    m = torch.zeros(1, 1, n, n)
    for y, x in points:
        m[..., y, x] = 1.0
    return m


def brute_force(mask: torch.Tensor) -> torch.Tensor:
    n = mask.shape[-1]
    ys, xs = torch.meshgrid(torch.arange(n), torch.arange(n), indexing="ij")
    py, px = torch.nonzero(mask[0, 0] > 0.5, as_tuple=True)
    dy = (ys[..., None] - py).abs()
    dx = (xs[..., None] - px).abs()
    dy, dx = torch.minimum(dy, n - dy), torch.minimum(dx, n - dx)
    return (dy.square() + dx.square()).double().sqrt().amin(-1)


def test_single_dot_fades_linearly_and_wraps():
    n = 32
    out = F.distance(dots(n, (0, 0)), distance=32.0)        # 1 px at 32 = 8 reference pixels
    assert out.shape == (1, 1, n, n)
    assert out[0, 0, 0, 0] == 1.0
    torch.testing.assert_close(out[0, 0, 0, 1], torch.tensor(0.75))
    torch.testing.assert_close(out[0, 0, 0, n - 1], torch.tensor(0.75))      # across the edge
    torch.testing.assert_close(out[0, 0, n - 1, n - 1], torch.tensor(1 - 8 * math.sqrt(2) / 32))
    row = out[0, 0, 0, : n // 2]
    assert (row[1:5] < row[:4]).all() and (row[4:] == 0).all()
    torch.testing.assert_close(out[0, 0, 0, 1:5], out[0, 0, 0, -4:].flip(-1))


def test_distance_transform_is_exact_on_random_masks():
    torch.manual_seed(3)
    for n in (16, 64):
        mask = (torch.rand(1, 1, n, n) > 0.95).float()
        mask[..., 0, 0] = 1.0
        _, d = nearest_mask_pixel(mask > 0.5, float(n))
        torch.testing.assert_close(d[0, 0], brute_force(mask), atol=1e-6, rtol=0)
        out = F.distance(mask, distance=256.0 * 6 / n)                        # 6 px
        expected = (1 - brute_force(mask) / 6).clamp(0, 1).float()
        torch.testing.assert_close(out[0, 0], expected, atol=1e-5, rtol=0)


def test_threshold_and_resolution_scaling():
    m = dots(16, (4, 4)) * 0.5                              # 0.5 is not above the threshold
    assert F.distance(m, distance=50.0).max() == 0
    small = F.distance(dots(32, (0, 0)), distance=64.0)     # 8 px at 32
    big = F.distance(dots(64, (0, 0)), distance=64.0)       # 16 px at 64
    torch.testing.assert_close(small[0, 0, 0, 4], big[0, 0, 0, 8])
    torch.testing.assert_close(small[0, 0, 0, 4], torch.tensor(0.5))


def test_source_fills_cells_with_the_nearest_colour():
    n = 16
    mask = dots(n, (2, 2), (10, 10))
    source = torch.zeros(1, 4, n, n)
    source[..., 2, 2] = torch.tensor([1.0, 0.0, 0.0, 1.0])
    source[..., 10, 10] = torch.tensor([0.0, 0.0, 1.0, 1.0])
    out = F.distance(mask, source, distance=256.0, colorswitch=True, combinedistance=False)
    assert out.shape == (1, 4, n, n)
    torch.testing.assert_close(out[0, :, 3, 3], torch.tensor([1.0, 0.0, 0.0, 1.0]))
    torch.testing.assert_close(out[0, :, 9, 11], torch.tensor([0.0, 0.0, 1.0, 1.0]))
    torch.testing.assert_close(out[0, :, 15, 15], torch.tensor([1.0, 0.0, 0.0, 1.0]))   # wraps to (2, 2)
    faded = F.distance(mask, source, distance=16.0 * 4, colorswitch=True, combinedistance=True)  # 4 px
    torch.testing.assert_close(faded[0, :, 2, 4], torch.tensor([0.5, 0.0, 0.0, 0.5]))
    cut = F.distance(mask, source, distance=16.0 * 4, colorswitch=True, combinedistance=False)
    torch.testing.assert_close(cut[0, :, 2, 5], torch.tensor([1.0, 0.0, 0.0, 1.0]))
    assert cut[0, :, 2, 7].abs().max() == 0                  # 5 px away: beyond the distance
    gray = F.distance(mask, source, distance=256.0, colorswitch=False, combinedistance=False)
    assert gray.shape == (1, 1, n, n)
    torch.testing.assert_close(gray[0, 0, 9, 11], torch.tensor(1 / 3))


def test_color_mode_without_source_is_gray_in_rgb():
    out = F.distance(dots(16, (5, 5)), distance=64.0, colorswitch=True)
    assert out.shape == (1, 4, 16, 16)
    torch.testing.assert_close(out[:, 0], out[:, 2])
    assert (out[:, 3] == 1).all()


def test_gradient_with_respect_to_distance_is_analytic():
    n = 32
    d = torch.tensor([40.0], requires_grad=True)            # 5 px at 32
    out = F.distance(dots(n, (0, 0)), distance=d)
    out[0, 0, 0, 3].backward()                              # 3 px = 24 reference px: 1 - 24 / D
    torch.testing.assert_close(d.grad, torch.tensor([24.0 / 40.0 ** 2]))
    batch = F.distance(dots(n, (0, 0)), distance=torch.tensor([[20.0], [40.0]]))
    assert batch.shape == (2, 1, n, n)
    torch.testing.assert_close(batch[1:], F.distance(dots(n, (0, 0)), distance=40.0))


def test_distance_rejects_bad_input():
    with pytest.raises(DiffMatError):
        F.distance(torch.rand(1, 4, 16, 16))
    with pytest.raises(DiffMatError):
        F.distance(torch.rand(1, 1, 16, 16), torch.rand(1, 4, 32, 32))
    node = Node("distance")
    with pytest.raises(DiffMatError):
        node(torch.rand(1, 3, 16, 16), ctx=EvalContext(size=16))
    with pytest.raises(DiffMatError):
        Node("distance", {"colorswitch": 3})
