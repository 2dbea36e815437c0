"""Tests of the input nodes: Bitmap (file round trip, wrap-around resizing, errors) and the SVG and
Text placeholders (functional/inputs.py)."""
from __future__ import annotations

import numpy as np
import pytest
import torch
from PIL import Image

from blender_match.diffmat import DiffMatError, EvalContext, Node
from blender_match.diffmat import functional as F


def _write_png(path, array: np.ndarray):
    Image.fromarray(array).save(path)
    return str(path)


def _rgba_array(size=8, seed=0):
    rng = np.random.default_rng(seed)
    return rng.integers(0, 256, size=(size, size, 4), dtype=np.uint8)


def test_bitmap_round_trip(tmp_path):
    arr = _rgba_array()
    path = _write_png(tmp_path / "img.png", arr)
    out = F.bitmap(bitmapresourcepath=path, size=8)
    assert out.shape == (1, 4, 8, 8) and out.dtype == torch.float32
    expected = torch.from_numpy(arr.astype(np.float32) / 255).permute(2, 0, 1)[None]
    torch.testing.assert_close(out, expected)
    gray = F.bitmap(bitmapresourcepath=path, size=8, colorswitch=False)
    torch.testing.assert_close(gray, expected[:, :3].mean(1, keepdim=True))


def test_bitmap_through_the_node(tmp_path):
    arr = np.zeros((4, 4, 3), dtype=np.uint8)
    arr[1, 2] = (255, 128, 0)
    path = _write_png(tmp_path / "rgb.png", arr)
    out = Node("bitmap", {"bitmapresourcepath": path})(ctx=EvalContext(size=4, dtype=torch.float64))
    assert out.dtype == torch.float64
    torch.testing.assert_close(out[0, :, 1, 2], torch.tensor([1.0, 128 / 255, 0.0, 1.0], dtype=torch.float64))
    assert out[0, :3].sum().item() == pytest.approx(1 + 128 / 255, abs=1e-6)


def test_bitmap_sixteen_bit_gray(tmp_path):
    arr = np.array([[0, 65535], [32768, 1000]], dtype=np.uint16)
    path = tmp_path / "g16.png"
    Image.fromarray(arr).save(path)
    out = F.bitmap(bitmapresourcepath=str(path), size=2, colorswitch=False)
    torch.testing.assert_close(out[0, 0], torch.from_numpy(arr.astype(np.float32) / 65535), atol=1e-6, rtol=0)


def test_bitmap_resize_wraps_around(tmp_path):
    # a single bright column at the left edge: shrinking spreads it across the seam to the right edge
    arr = np.zeros((8, 8), dtype=np.uint8)
    arr[:, 0] = 255
    path = _write_png(tmp_path / "col.png", arr)
    out = F.bitmap(bitmapresourcepath=path, size=4, colorswitch=False)[0, 0]
    assert out.shape == (4, 4)
    assert out[0, 0].item() > 0 and out[0, 3].item() > 0          # both sides of the seam
    # tent of half-width 2 input pixels: texel 0 weighs 3/8 in output 0 and 1/8 across the seam
    assert out[0, 0].item() == pytest.approx(0.375) and out[0, 3].item() == pytest.approx(0.125)
    assert out[0, 1].item() == pytest.approx(0.0) and out[0, 2].item() == pytest.approx(0.0)
    # mean is preserved when shrinking
    assert out.mean().item() == pytest.approx(1 / 8, abs=1e-6)
    # enlarging a tiling image keeps it tiling: a constant stays constant, a column wraps bilinearly
    up = F.bitmap(bitmapresourcepath=path, size=16, colorswitch=False)[0, 0]
    assert up[0, 0].item() == pytest.approx(up[0, 1].item())       # 0.75 each side of texel 0's centre
    assert up[0, 15].item() == pytest.approx(0.25) and up[0, 0].item() == pytest.approx(0.75)


def test_bitmap_missing_and_unreadable_files(tmp_path):
    missing = tmp_path / "nope.png"
    with pytest.raises(DiffMatError, match="nope.png"):
        F.bitmap(bitmapresourcepath=str(missing), size=8)
    bad = tmp_path / "bad.png"
    bad.write_bytes(b"this is not an image")
    with pytest.raises(DiffMatError, match="bad.png"):
        F.bitmap(bitmapresourcepath=str(bad), size=8)
    with pytest.raises(DiffMatError, match="Resources"):
        Node("bitmap", {"bitmapresourcepath": "pkg:///Resources/foo?dependency=1"})(ctx=EvalContext(size=8))


def test_bitmap_unset_path_is_opaque_black():
    out = F.bitmap(size=4)
    torch.testing.assert_close(out[0, :, 0, 0], torch.tensor([0.0, 0.0, 0.0, 1.0]))


def test_svg_and_text_render_background():
    for fn in (F.svg, F.text):
        out = fn(background=(0.2, 0.4, 0.6, 1.0), size=4)
        assert out.shape == (1, 4, 4, 4)
        torch.testing.assert_close(out[0, :, 2, 3], torch.tensor([0.2, 0.4, 0.6, 1.0]))
        gray = fn(background=(0.2, 0.4, 0.6, 1.0), colorswitch=False, size=4)
        assert gray.shape == (1, 1, 4, 4) and gray[0, 0, 0, 0].item() == pytest.approx(0.2)
        img = torch.rand(1, 4, 8, 8)
        torch.testing.assert_close(fn(img, size=4), img)
        batched = fn(background=torch.tensor([[0.0, 0, 0, 1], [1.0, 1, 1, 1]]), size=4)
        assert batched.shape == (2, 4, 4, 4) and batched[1].min().item() == 1.0


def test_text_node_accepts_its_parameters():
    node = Node("text", {"text": "hello", "fontdata": "Avenir Next|Regular", "alignment": 2,
                         "background": [0.5, 0.5, 0.5, 1.0]})
    out = node(ctx=EvalContext(size=8))
    torch.testing.assert_close(out, torch.tensor([0.5, 0.5, 0.5, 1.0]).reshape(1, 4, 1, 1).expand(1, 4, 8, 8))
