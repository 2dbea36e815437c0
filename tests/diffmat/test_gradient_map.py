"""Known-value tests of Gradient Map and Gradient Dynamic (functional/gradient_map.py)."""
from __future__ import annotations

import pytest
import torch

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F

X = torch.tensor([0.0, 0.1, 0.25, 0.4, 0.5, 0.6, 0.75, 1.0]).reshape(1, 1, 1, 8)
BLACK, WHITE = (0.0, 0.0, 0.0, 1.0), (1.0, 1.0, 1.0, 1.0)
RED, GREEN, BLUE = (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0)


def test_black_to_white_is_identity():
    out = F.gradient_map(X, positions=(0.0, 1.0), colors=BLACK + WHITE)
    assert out.shape == (1, 4, 1, 8)
    for c in range(3):
        torch.testing.assert_close(out[:, c:c + 1], X)
    torch.testing.assert_close(out[:, 3:], torch.ones_like(X))
    gray = F.gradient_map(X, positions=(0.0, 1.0), colors=BLACK + WHITE, colorswitch=False)
    assert gray.shape == (1, 1, 1, 8)
    torch.testing.assert_close(gray, X)


def test_three_keys_linear_unsorted_and_held_ends():
    # keys given out of order: blue at 0.75, red at 0.25, green at 0.5
    out = F.gradient_map(X, positions=(0.75, 0.25, 0.5), colors=BLUE + RED + GREEN)
    x = X.flatten()
    red = torch.where(x <= 0.25, 1.0, torch.where(x < 0.5, (0.5 - x) / 0.25, 0.0))
    green = torch.where((x > 0.25) & (x < 0.75), 1 - (x - 0.5).abs() / 0.25, 0.0)
    blue = torch.where(x >= 0.75, 1.0, torch.where(x > 0.5, (x - 0.5) / 0.25, 0.0))
    torch.testing.assert_close(out[0, 0, 0], red)
    torch.testing.assert_close(out[0, 1, 0], green)
    torch.testing.assert_close(out[0, 2, 0], blue)


def test_smooth_and_flat_tangents_ease_between_keys():
    for mode in (1, 2):
        out = F.gradient_map(X, positions=(0.0, 1.0), colors=BLACK + WHITE, interpmode=mode, colorswitch=False)
        x = X.flatten()
        torch.testing.assert_close(out.flatten(), x * x * (3 - 2 * x))
    assert out.flatten()[2].item() < 0.25 and out.flatten()[6].item() > 0.75


def test_no_interpolation_holds_each_key():
    out = F.gradient_map(X, positions=(0.0, 0.5, 0.75), colors=(0.1, 0, 0, 1) + (0.6, 0, 0, 1) + (0.9, 0, 0, 1),
                         interpmode=3)
    torch.testing.assert_close(out[0, 0, 0], torch.tensor([0.1, 0.1, 0.1, 0.1, 0.6, 0.6, 0.9, 0.9]))


def test_repeat_addressing_wraps_from_last_key_to_first():
    keys = dict(positions=(0.25, 0.75), colors=(0.0, 0, 0, 1) + (1.0, 0, 0, 1))
    clamped = F.gradient_map(X, **keys)[0, 0, 0]
    torch.testing.assert_close(clamped[[0, 1, 7]], torch.tensor([0.0, 0.0, 1.0]))
    wrapped = F.gradient_map(X, addressingrepeat=True, **keys)[0, 0, 0]
    # from 1.0 at 0.75 down to 0.0 at 1.25: x = 1.0 -> 0.5, x = 0.0 (= 1.0 - 1) -> 0.5, 0.1 -> 0.3
    torch.testing.assert_close(wrapped[[0, 1, 7]], torch.tensor([0.5, 0.3, 0.5]))
    torch.testing.assert_close(wrapped[2:7], clamped[2:7])


def test_batched_keys_and_gradients():
    pos = torch.tensor([[0.0, 1.0], [0.0, 0.5]], requires_grad=True)
    out = F.gradient_map(X, positions=pos, colors=BLACK + WHITE, colorswitch=False)
    assert out.shape == (2, 1, 1, 8)
    torch.testing.assert_close(out[1, 0, 0], (X.flatten() / 0.5).clamp(0, 1))
    out.sum().backward()
    assert pos.grad.abs().sum() > 0


def test_gradient_errors():
    with pytest.raises(DiffMatError, match="colors"):
        F.gradient_map(X, positions=(0.0, 1.0), colors=BLACK)
    with pytest.raises(DiffMatError, match="interpmode"):
        F.gradient_map(X, interpmode=7)
    with pytest.raises(DiffMatError):
        F.gradient_map(torch.rand(1, 4, 4, 4))
    node = Node("gradient", {"positions": [0.0, 0.5, 1.0], "colors": list(RED + GREEN + BLUE)})
    out = node(torch.full((1, 1, 4, 4), 0.5), ctx=EvalContext(size=4))
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor(GREEN))


# ------------------------------------------------------------------ dynamic gradient

def _gradient_image():
    """8x8 colour image: R = column / 7 (a horizontal ramp), G = row / 7, B = 0.5, A = 1."""
    c = torch.arange(8, dtype=torch.float32) / 7
    img = torch.zeros(1, 4, 8, 8)
    img[0, 0] = c[None, :].expand(8, 8)
    img[0, 1] = c[:, None].expand(8, 8)
    img[0, 2] = 0.5
    img[0, 3] = 1.0
    return img


def test_dynamic_gradient_horizontal_reads_a_row():
    grad = _gradient_image()
    x = torch.tensor([0.0, 0.5, 1.0, 9 / 16]).reshape(1, 1, 1, 4)
    out = F.dynamic_gradient(x, grad, uvselector=0, coordinate=5.5 / 8)
    # along the row: clamped to the first/last pixel centres; 9/16 is pixel 4's centre -> 4/7
    torch.testing.assert_close(out[0, 0, 0], torch.tensor([0.0, 0.5, 1.0, 4 / 7]), atol=1e-5, rtol=0)
    torch.testing.assert_close(out[0, 1, 0], torch.full((4,), 5 / 7), atol=1e-5, rtol=0)
    torch.testing.assert_close(out[0, 2, 0], torch.full((4,), 0.5), atol=1e-5, rtol=0)


def test_dynamic_gradient_vertical_reads_a_column_and_repeat_wraps():
    grad = _gradient_image()
    x = torch.tensor([0.5 / 8, 3.5 / 8, 1.0]).reshape(1, 1, 1, 3)
    out = F.dynamic_gradient(x, grad, uvselector=1, coordinate=2.5 / 8)
    torch.testing.assert_close(out[0, 1, 0], torch.tensor([0.0, 3 / 7, 1.0]), atol=1e-5, rtol=0)
    torch.testing.assert_close(out[0, 0, 0], torch.full((3,), 2 / 7), atol=1e-5, rtol=0)
    wrapped = F.dynamic_gradient(x, grad, uvselector=1, coordinate=2.5 / 8, addressingrepeat=True)
    # x = 1.0 wraps to v = 0: halfway between the last row (1.0) and the first (0.0)
    assert wrapped[0, 1, 0, 2].item() == pytest.approx(0.5, abs=1e-5)


def test_dynamic_gradient_gray_gradient_and_batched_coordinate():
    grad = _gradient_image()[:, 1:2]                 # gray: row / 7
    x = torch.full((1, 1, 2, 2), 0.5)
    out = F.dynamic_gradient(x, grad, coordinate=torch.tensor([[0.5 / 8], [7.5 / 8]]))
    assert out.shape == (2, 1, 2, 2)
    torch.testing.assert_close(out[:, 0, 0, 0], torch.tensor([0.0, 1.0]), atol=1e-5, rtol=0)
    with pytest.raises(DiffMatError, match="uvselector"):
        F.dynamic_gradient(x, grad, uvselector=2)
